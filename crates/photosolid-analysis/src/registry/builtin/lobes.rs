//! `lobes:K[+gpu]`: mixtures of cosine-power lobes ([`Recon::Lobes`]).

use super::{Builtin, Job};
use crate::error::ModelError;
use crate::fit::lobes::MAX_LOBES;
use crate::registry::recon::{strip_gpu, LOBES_PREFIX};
use crate::registry::Recon;

/// The lobe counts K of the default `lobes:K` rows.
pub const LOBE_COUNTS: [usize; 4] = [1, 2, 3, 4];

/// The lobe counts of the trade table's extra `lobes:K` rows, beside
/// [`LOBE_COUNTS`]: the stages of the lobe search that lie between 128 bytes
/// and 10 kB, where the table's other extra rows (`sh:32`, the zonal
/// series) fill the bytes front too: 140 and 160 bytes. They are fitted in
/// the same search as the default counts (the fit of K lobes is a stage of
/// the fit of 8), so they cost their measurement only. A narrow spot is
/// lobes', where 33 zonal bands still ring. The mixture's radial max against
/// withheld samples does not fall with K (the fit minimises a weighted RMS
/// of the kept samples): on eulumdat-plot's sample_02 `lobes:7` reads
/// 4.08 % where `lobes:4` reads 5.29 % and `lobes:8` 6.12 %, and only
/// `lobes:7` is on its bytes front in that band (docs/compact.md, "Seven
/// lobes"). Not among `batch --compact`'s or `plan`'s candidates.
pub const FRONT_LOBE_COUNTS: [usize; 2] = [7, 8];

/// Mixtures of K lobes, K from 1 to [`MAX_LOBES`].
pub(crate) struct LobeMixtures;

/// The CPU's mixture of `count` lobes.
fn lobes(count: usize) -> Recon {
    Recon::Lobes { count, gpu: false }
}

impl Builtin for LobeMixtures {
    fn spelling(&self) -> String {
        "lobes:K".into()
    }

    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        let (body, gpu) = strip_gpu(name.strip_prefix(LOBES_PREFIX)?);
        Some(match body.parse::<usize>() {
            Ok(count) if (1..=MAX_LOBES).contains(&count) => Ok(Recon::Lobes { count, gpu }),
            _ => Err(ModelError::Parameter {
                name: "recon",
                value: name.to_string(),
                reason: format!("expected lobes:K[+gpu] with the lobe count K from 1 to {MAX_LOBES}"),
            }),
        })
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        match job {
            Job::Compare => Vec::new(),
            Job::Tradeoff { .. } | Job::TradeRows { .. } => {
                let mut out: Vec<Recon> = LOBE_COUNTS.into_iter().chain(FRONT_LOBE_COUNTS).map(lobes).collect();
                if job.gpu() {
                    // The largest default mixture evaluated by the compute shader.
                    out.push(Recon::Lobes {
                        count: LOBE_COUNTS[LOBE_COUNTS.len() - 1],
                        gpu: true,
                    });
                }
                out
            }
            Job::Plan { .. } | Job::Compact { .. } => LOBE_COUNTS.map(lobes).to_vec(),
        }
    }
}
