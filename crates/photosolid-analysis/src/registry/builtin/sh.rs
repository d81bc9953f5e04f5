//! `sh:L[+f16][+gpu]`: spherical-harmonic series ([`Recon::Sh`]).

use super::{Builtin, Job};
use crate::error::ModelError;
use crate::reconstruct::{MAX_SH_DEGREE, MAX_ZONAL_SH_DEGREE};
use crate::registry::recon::{strip_gpu, SH_PREFIX};
use crate::registry::Recon;

/// The degrees L of the default `sh:L` rows.
pub const SH_DEGREES: [usize; 4] = [2, 4, 8, 16];

/// The degree of the trade table's extra `sh:L` row, beside [`SH_DEGREES`]:
/// it fills the bytes front between the default compact rows and the
/// textures. On asymmetric data `sh:32` is 4,356 bytes (1,089 terms a
/// lookup) where `sh:16` is 1,156; on rotationally symmetric data the series
/// are zonal, L + 1 coefficients, so every default compact row is under 128
/// bytes and `sh:32` is 132 bytes (33 terms), below the one-column texture
/// (144-720 bytes). Over the corpus it puts a compact row on the bytes front
/// between 128 bytes and 10 kB on 12 more files than the default rows alone
/// (docs/compact.md). Not among `batch --compact`'s or `plan`'s candidates.
pub const FRONT_SH_DEGREE: usize = MAX_SH_DEGREE;

/// The degrees of the trade table's extra `sh:L` rows on data the same in
/// every C-plane (whatever symmetry the file declares), where a series is
/// zonal: 260 and 516 bytes (L + 1
/// coefficients, as many terms a lookup). There every default compact row
/// is under 128 bytes and the one-column texture (144-1,100 bytes) was the
/// front above them; a profile with a sharp edge needs these degrees to
/// come within a few % of it (the Lanczos window blurs an edge over about
/// 180° / (L + 1)). Over the corpus's rotational files they put an `sh:L`
/// row on the bytes front between 128 bytes and 10 kB where none was
/// (docs/compact.md, "Rotational data: zonal series to L = 128").
pub const ZONAL_FRONT_SH_DEGREES: [usize; 2] = [64, 128];

/// Series of degree L, 0 to [`MAX_SH_DEGREE`] (to [`MAX_ZONAL_SH_DEGREE`]
/// for rotationally symmetric data, whose series is zonal).
pub(crate) struct Sh;

/// The CPU's f32 series of `degree`.
fn sh(degree: usize) -> Recon {
    Recon::Sh {
        degree,
        f16: false,
        gpu: false,
    }
}

impl Builtin for Sh {
    fn spelling(&self) -> String {
        "sh:L[+f16]".into()
    }

    /// `sh:L[+f16][+gpu]`, L in 0..=[`MAX_ZONAL_SH_DEGREE`] (above
    /// [`MAX_SH_DEGREE`] only rotationally symmetric data builds).
    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        let (body, gpu) = strip_gpu(name.strip_prefix(SH_PREFIX)?);
        let (digits, f16) = match body.strip_suffix("+f16") {
            Some(d) => (d, true),
            None => (body, false),
        };
        Some(match digits.parse::<usize>() {
            Ok(degree) if degree <= MAX_ZONAL_SH_DEGREE => Ok(Recon::Sh { degree, f16, gpu }),
            _ => Err(ModelError::Parameter {
                name: "recon",
                value: name.to_string(),
                reason: format!(
                    "expected sh:L[+f16][+gpu] with the degree L from 0 to {MAX_SH_DEGREE} \
                     ({MAX_ZONAL_SH_DEGREE} for rotationally symmetric data)"
                ),
            }),
        })
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        let Some((_, zonal, _)) = job.trade_view() else {
            return match job {
                Job::Plan { .. } | Job::Compact { .. } => SH_DEGREES.map(sh).to_vec(),
                _ => Vec::new(),
            };
        };
        let mut out: Vec<Recon> = SH_DEGREES.into_iter().chain([FRONT_SH_DEGREE]).map(sh).collect();
        if zonal {
            out.extend(ZONAL_FRONT_SH_DEGREES.map(sh));
        }
        if job.gpu() {
            // The largest default series evaluated by the compute shader.
            out.push(Recon::Sh {
                degree: SH_DEGREES[SH_DEGREES.len() - 1],
                f16: false,
                gpu: true,
            });
        }
        out
    }
}
