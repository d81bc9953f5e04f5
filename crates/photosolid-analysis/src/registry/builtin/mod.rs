//! The built-in representations, registered in one place (the list
//! `BUILTINS` here): each family's names and which of its instances each job lists.
//!
//! Every job that offers a choice of representations reads its candidates
//! from a [`Registry`](super::Registry) ([`Registry::candidates`](super::Registry::candidates)),
//! which lists these families in this order and then the representations a
//! caller added; `--recon`, a scene's `representation` and
//! [`Recon::from_str`](std::str::FromStr) parse through the same list. A job
//! describes itself with a [`Job`], holding what its lists depend on (the
//! file's symmetry, the texture factors, the directions a scene sees).
//!
//! The built-in families keep typed parameters in [`Recon`]'s variants
//! (a filter, a texture's storage, a crop's angles) and share what they
//! prepare in [`Reconstructions`](super::Reconstructions) (one light texture
//! for every filter, one lobe search for every count). A representation
//! named by one integer parameter needs neither: it implements
//! [`Representation`] in a file of its own and is one line of this
//! module's `open` list.

mod c_mean;
mod fitted;
mod lobes;
mod measured;
mod regridded;
mod sh;
mod texture;

use std::sync::Arc;

use super::{Recon, Representation};
use crate::error::ModelError;
use crate::model::{Distribution, Symmetry};

pub use lobes::{FRONT_LOBE_COUNTS, LOBE_COUNTS};
pub use sh::{FRONT_SH_DEGREE, SH_DEGREES, ZONAL_FRONT_SH_DEGREES};
pub use texture::PLAN_TEXTURE_FACTORS;

/// The directions a scene sees of a luminaire: γ from, γ to and, when not
/// every plane, the C sector from, to (degrees; [`Recon::Cropped`]).
pub type Visible = (f64, f64, Option<(f64, f64)>);

/// The job asking a registry for its candidate representations, with what
/// its lists depend on. Non-exhaustive: a representation outside this crate
/// matches the jobs it knows and lists nothing (or its defaults) for others.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Job<'a> {
    /// `compare`'s default reconstructions.
    Compare,
    /// `tradeoff`'s table for `file` (its declared symmetry, and whether every
    /// C-plane holds the same values), stored textures at `factors`, and the
    /// GPU's evaluations beside their CPU twins when `gpu`.
    Tradeoff {
        /// The file.
        file: &'a Distribution,
        /// The texture factors.
        factors: &'a [u32],
        /// Add the `+gpu` rows.
        gpu: bool,
    },
    /// The trade table's CPU rows for data of `symmetry` whose C-planes
    /// differ (what [`Job::Tradeoff`] lists without its file).
    TradeRows {
        /// The declared symmetry.
        symmetry: Symmetry,
        /// The texture factors.
        factors: &'a [u32],
    },
    /// `plan`'s candidates for a luminaire of `dist` that a scene sees in `visible`.
    Plan {
        /// The luminaire's distribution.
        dist: &'a Distribution,
        /// The directions the scene sees, when not all.
        visible: Option<Visible>,
    },
    /// `batch --compact`'s candidates for a file of `dist`, besides the
    /// filters (which its hold-out pass measures).
    Compact {
        /// The file's distribution (the hold-out's kept samples are a part of it).
        dist: &'a Distribution,
    },
}

impl Job<'_> {
    /// The declared symmetry and whether every C-plane holds the same values
    /// (a trade table's view of its file).
    fn trade_view(&self) -> Option<(Symmetry, bool, &[u32])> {
        match *self {
            Job::Tradeoff { file, factors, .. } => Some((
                file.symmetry(),
                file.detect_symmetry(0.0) == Symmetry::Rotational,
                factors,
            )),
            Job::TradeRows { symmetry, factors } => Some((symmetry, false, factors)),
            _ => None,
        }
    }

    /// The symmetry the job's file declares, when it has one.
    pub fn declared_symmetry(&self) -> Option<Symmetry> {
        match *self {
            Job::Tradeoff { file: dist, .. } | Job::Plan { dist, .. } | Job::Compact { dist } => Some(dist.symmetry()),
            Job::TradeRows { symmetry, .. } => Some(symmetry),
            Job::Compare => None,
        }
    }

    /// Whether the job adds the GPU's evaluations.
    fn gpu(&self) -> bool {
        matches!(self, Job::Tradeoff { gpu: true, .. })
    }
}

/// A built-in family of representations.
pub(crate) trait Builtin: Sync {
    /// How its names are spelled, for the message of a name nothing reads.
    fn spelling(&self) -> String;

    /// `name` read as one of its instances: `None` when the name is not of
    /// this family's shape, an error when it is but is malformed.
    fn parse(&self, name: &str) -> Option<Result<Recon, ModelError>>;

    /// The instances `job` lists, in order.
    fn candidates(&self, job: &Job<'_>) -> Vec<Recon>;
}

/// The built-in families, in the order the jobs list them. Their names do
/// not overlap (a filter's name is one of its words, a texture's holds `@`,
/// a re-gridded one `+gamma:` or `+isym:`), so the order names are tried in
/// does not matter.
pub(crate) const BUILTINS: [&dyn Builtin; 7] = [
    &measured::Measured,
    &texture::Filters,
    &texture::Textures,
    &fitted::FittedGl,
    &sh::Sh,
    &lobes::LobeMixtures,
    &regridded::Regridded,
];

/// The built-in representations named by one integer parameter, implemented
/// on the open trait ([`Representation`]): in every registry, listed after
/// the typed families, one line each.
pub(crate) fn open() -> Vec<Arc<dyn Representation>> {
    vec![Arc::new(c_mean::CMean)]
}

/// `name` read as a built-in typed representation.
pub(crate) fn parse(name: &str) -> Result<Recon, ModelError> {
    let name = name.trim();
    BUILTINS
        .iter()
        .find_map(|family| family.parse(name))
        .unwrap_or_else(|| {
            // Every built-in spelling: the typed families', then the open built-ins' names.
            let open = open();
            let names = open
                .iter()
                .flat_map(|rep| rep.defaults().into_iter().map(|p| rep.name(p)));
            let spellings: Vec<String> = BUILTINS.iter().map(|f| f.spelling()).chain(names).collect();
            Err(ModelError::Parameter {
                name: "recon",
                value: name.to_string(),
                reason: format!("expected one of: {}", spellings.join(", ")),
            })
        })
}

/// The typed built-in instances `job` lists, family by family.
pub(crate) fn candidates(job: &Job<'_>) -> Vec<Recon> {
    BUILTINS.iter().flat_map(|family| family.candidates(job)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reconstruct::Filter;
    use crate::registry::Registry;
    use crate::synth::{GridSpec, Synth};

    /// A cosine-power luminaire (p = 5, peak 1000 cd) on a 15° x 5° grid, stored rotational.
    pub(super) fn cosine_p5() -> Distribution {
        let grid = GridSpec::uniform(15.0, 5.0).unwrap();
        let lum = Synth::CosinePower { p: 5.0 }.build(&grid, 1000.0).unwrap();
        lum.distribution().clone()
    }

    /// Every candidate of every job prints a name that parses back to it.
    #[test]
    fn every_candidate_round_trips_through_its_name() {
        let dist = cosine_p5();
        let jobs = [
            Job::Compare,
            Job::Tradeoff {
                file: &dist,
                factors: &[1, 5],
                gpu: true,
            },
            Job::TradeRows {
                symmetry: Symmetry::C0C180,
                factors: &[2],
            },
            Job::Plan {
                dist: &dist,
                visible: Some((0.0, 80.0, Some((350.0, 10.0)))),
            },
            Job::Compact { dist: &dist },
        ];
        for job in jobs {
            let listed = Registry::builtin().candidates(&job);
            assert!(!listed.is_empty(), "{job:?}");
            for r in listed {
                assert_eq!(r.to_string().parse::<Recon>().unwrap(), r, "{job:?}");
            }
        }
    }

    /// `compare`'s defaults: the measured solid, the filters but nearest, the fit.
    #[test]
    fn compare_lists_the_measured_solid_the_filters_and_the_fit() {
        let names: Vec<String> = candidates(&Job::Compare).iter().map(Recon::to_string).collect();
        assert_eq!(
            names,
            [
                "measured",
                "bilinear",
                "catmull-rom",
                &Filter::MITCHELL.to_string(),
                "bspline",
                "pchip",
                "fitted-gl"
            ]
        );
    }

    /// A name no family reads names every family's spelling and the open built-ins' names.
    #[test]
    fn an_unknown_name_lists_every_spelling() {
        let Err(ModelError::Parameter { reason, .. }) = parse("octahedral:8") else {
            panic!("parsed");
        };
        for family in BUILTINS {
            assert!(reason.contains(&family.spelling()), "{reason}");
        }
        assert!(reason.contains("c-mean"), "{reason}");
    }
}
