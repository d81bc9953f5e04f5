//! The filters on the measured grid ([`Recon::Filter`]) and the textures
//! rendered from them, stored and read back on the CPU ([`Recon::Texture`])
//! or by the GPU's texture hardware ([`Recon::Gpu`]).

use super::{regridded, Builtin, Job};
use crate::error::ModelError;
use crate::model::Symmetry;
use crate::reconstruct::{bc6h, Filter, Lookup, Precision, TextureSpec, FILTER_NAMES};
use crate::registry::recon::GPU_SUFFIX;
use crate::registry::Recon;

/// The render factors of `plan`'s texture candidates.
pub const PLAN_TEXTURE_FACTORS: [u32; 3] = [1, 2, 5];

/// A filter on the measured grid.
pub(crate) struct Filters;

impl Builtin for Filters {
    fn spelling(&self) -> String {
        format!("a filter ({FILTER_NAMES})")
    }

    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        name.parse::<Filter>().ok().map(|f| Ok(Recon::Filter(f)))
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        match job {
            // Nearest is a lookup's baseline, not a reconstruction anyone would ship.
            Job::Compare => Filter::ALL
                .into_iter()
                .filter(|f| *f != Filter::Nearest)
                .map(Recon::Filter)
                .collect(),
            Job::Tradeoff { .. } | Job::TradeRows { .. } | Job::Plan { .. } => {
                Filter::ALL.into_iter().map(Recon::Filter).collect()
            }
            // `batch`'s hold-out pass measures the filters itself.
            Job::Compact { .. } => Vec::new(),
        }
    }
}

/// A texture rendered once and read back: `FILTER@xK/LOOKUP[+PRECISION][+reduced][+gpu]`.
pub(crate) struct Textures;

/// The f32 texture of `filter` at `factor`, read with `lookup`.
fn texture(filter: Filter, factor: u32, lookup: Lookup, precision: Precision, reduced: bool) -> TextureSpec {
    TextureSpec {
        filter,
        factor,
        lookup,
        precision,
        reduced,
    }
}

impl Builtin for Textures {
    fn spelling(&self) -> String {
        "a texture FILTER@xK/LOOKUP".into()
    }

    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>> {
        if !name.contains('@') || regridded::claims(name) {
            return None;
        }
        Some(match name.strip_suffix(GPU_SUFFIX) {
            Some(t) => t.parse().map(Recon::Gpu),
            None => name.parse().map(Recon::Texture),
        })
    }

    fn candidates(&self, job: &Job<'_>) -> Vec<Recon> {
        if let Some((symmetry, _, factors)) = job.trade_view() {
            return trade_rows(symmetry, factors, job.gpu());
        }
        match job {
            Job::Plan { dist, .. } => plan_rows(dist.symmetry()),
            _ => Vec::new(),
        }
    }
}

/// The trade table's textures: the Catmull-Rom render at each of `factors`
/// read with every lookup, the x5 one in every smaller storage and, for
/// data with a symmetry, reduced to its sector; with `gpu`, the x5 one read
/// by the GPU's bilinear hardware and its Catmull-Rom from linear fetches.
fn trade_rows(symmetry: Symmetry, factors: &[u32], gpu: bool) -> Vec<Recon> {
    let tex = |factor, lookup, precision, reduced| {
        Recon::Texture(texture(Filter::CatmullRom, factor, lookup, precision, reduced))
    };
    let mut out = Vec::new();
    for &k in factors {
        for l in Lookup::ALL {
            out.push(tex(k, l, Precision::F32, false));
        }
    }
    // The same texture in half floats and in 16- and 8-bit normalised integers.
    for precision in [Precision::F16, Precision::U16, Precision::U8] {
        out.push(tex(5, Lookup::Bilinear, precision, false));
    }
    if bc6h::available() {
        out.push(tex(5, Lookup::Bilinear, Precision::Bc6h, false));
    }
    if symmetry != Symmetry::None {
        out.push(tex(5, Lookup::Bilinear, Precision::F32, true));
        out.push(tex(5, Lookup::Bilinear, Precision::F16, true));
    }
    if gpu {
        for lookup in [Lookup::Bilinear, Lookup::CatmullRom] {
            out.push(Recon::Gpu(texture(
                Filter::CatmullRom,
                5,
                lookup,
                Precision::F32,
                false,
            )));
        }
    }
    out
}

/// `plan`'s textures: every filter rendered at each of
/// [`PLAN_TEXTURE_FACTORS`] read with the hardware's bilinear lookup, the
/// Catmull-Rom render also with the others; the x5 Catmull-Rom render in
/// half floats and, for data with a symmetry, reduced to its sector.
fn plan_rows(symmetry: Symmetry) -> Vec<Recon> {
    let mut out = Vec::new();
    for factor in PLAN_TEXTURE_FACTORS {
        for filter in Filter::ALL {
            for lookup in Lookup::ALL {
                if lookup == Lookup::Bilinear || filter == Filter::CatmullRom {
                    out.push(Recon::Texture(texture(filter, factor, lookup, Precision::F32, false)));
                }
            }
        }
    }
    for (precision, reduced) in [(Precision::F16, false), (Precision::F32, true), (Precision::F16, true)] {
        if reduced && symmetry == Symmetry::None {
            continue;
        }
        out.push(Recon::Texture(texture(
            Filter::CatmullRom,
            5,
            Lookup::Bilinear,
            precision,
            reduced,
        )));
    }
    out
}
