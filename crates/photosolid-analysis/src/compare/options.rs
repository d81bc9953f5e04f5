//! What a comparison is asked to do: the scaling ([`Normalize`]), the
//! directions sampled ([`Directions`]), the reference ([`Against`]), and
//! [`CompareOptions`] with a Type A/B file's own readings ([`SourceMeasurements`]).

use std::str::FromStr;

use serde::Serialize;

use super::*;
/// How the distributions are scaled before comparing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Normalize {
    /// Absolute candela.
    #[default]
    Cd,
    /// I_max = 1 (each distribution by its own peak).
    Peak,
    /// cd/klm as in EULUMDAT and lighting practice: candela per 1000 lm of
    /// *lamp* flux (each distribution by its file's declared lamp flux, or
    /// [`CompareOptions::lamp_flux_lm`] in the library). Does not apply to
    /// absolute photometry.
    #[cfg_attr(
        feature = "cli",
        value(
            help = "cd/klm as in EULUMDAT: candela per 1000 lm of the lamp flux each file declares (not for absolute photometry)"
        )
    )]
    Klm,
    /// Equal flux: each distribution divided by its own computed luminaire
    /// flux (x 1000: cd per 1000 lm of luminaire flux).
    Flux,
}

impl Normalize {
    /// The scale factor of `d`, whose file declares the lamp flux
    /// `lamp_flux_lm` (lm; `None` for absolute photometry).
    pub fn factor(self, d: &Distribution, lamp_flux_lm: Option<f64>) -> Result<f64, ModelError> {
        let k = match self {
            Normalize::Cd => 1.0,
            Normalize::Peak => 1.0 / d.max_cd(),
            Normalize::Klm => match lamp_flux_lm {
                Some(lm) => 1000.0 / lm,
                None => {
                    return Err(ModelError::Parameter {
                        name: "normalize",
                        value: "klm".into(),
                        reason: "cd/klm is per 1000 lm of lamp flux, and this file has absolute photometry (no \
                                 lamp flux); use --normalize flux (equal luminaire flux) or peak"
                            .into(),
                    })
                }
            },
            Normalize::Flux => 1000.0 / crate::photometry::flux(d).total_lm,
        };
        if k.is_finite() && k > 0.0 {
            Ok(k)
        } else {
            Err(ModelError::AllZero("normalisation needs a positive peak and flux"))
        }
    }
    /// The unit of lengths after scaling.
    pub fn unit(self) -> &'static str {
        match self {
            Normalize::Cd => "cd",
            Normalize::Peak => "I/I_max",
            Normalize::Klm => "cd/klm",
            Normalize::Flux => "cd/klm of luminaire flux",
        }
    }
}

impl FromStr for Normalize {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "cd" => Ok(Normalize::Cd),
            "peak" => Ok(Normalize::Peak),
            "klm" => Ok(Normalize::Klm),
            "flux" => Ok(Normalize::Flux),
            _ => Err(ModelError::Parameter {
                name: "normalize",
                value: s.into(),
                reason: "expected cd, peak, klm (lamp flux) or flux (equal luminaire flux)".into(),
            }),
        }
    }
}

/// The direction set of the radial metrics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Directions {
    /// The measured directions of the reference distribution.
    Measured,
    /// A spherical Fibonacci lattice of N directions.
    Dense(usize),
}

impl Default for Directions {
    fn default() -> Self {
        Directions::Dense(20_000)
    }
}

impl std::fmt::Display for Directions {
    /// As `--directions` writes it: `measured` or `dense:N`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Directions::Measured => f.write_str("measured"),
            Directions::Dense(n) => write!(f, "dense:{n}"),
        }
    }
}

impl FromStr for Directions {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || ModelError::Parameter {
            name: "directions",
            value: s.into(),
            reason: "expected measured, dense or dense:N (N ≥ 100)".into(),
        };
        match s {
            "measured" => Ok(Directions::Measured),
            "dense" => Ok(Directions::default()),
            _ => match s.strip_prefix("dense:").map(str::parse::<usize>) {
                Some(Ok(n)) if n >= 100 => Ok(Directions::Dense(n)),
                _ => Err(bad()),
            },
        }
    }
}

/// What the reconstructions are measured against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Against {
    /// The closed-form distribution the file was sampled from ([`Truth`]).
    Truth,
    /// The measurements themselves, by k-fold hold-out: each reconstruction
    /// is rebuilt without the withheld planes (rows) and measured at them.
    Withheld,
    /// A reconstruction: of OTHER with `vs` (a denser measurement: `dense`),
    /// or of FILE itself (one reconstruction against another, not the truth).
    Recon(Recon),
}

impl std::fmt::Display for Against {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Against::Truth => f.write_str("truth"),
            Against::Withheld => f.write_str("withheld"),
            Against::Recon(r) => write!(f, "{r}"),
        }
    }
}

impl FromStr for Against {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "truth" => Ok(Against::Truth),
            "withheld" => Ok(Against::Withheld),
            x => x.parse().map(Against::Recon).map_err(|_| ModelError::Parameter {
                name: "against",
                value: x.to_string(),
                reason: format!(
                    "expected truth, withheld, measured, {} or a filter ({})",
                    crate::fit::RECONSTRUCTION_NAME,
                    crate::reconstruct::FILTER_NAMES
                ),
            }),
        }
    }
}

/// Options of [`compare`].
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// Reconstructions of FILE to compare. Default: the built-in registry's
    /// candidates for [`Job::Compare`](crate::registry::Job::Compare) (`measured`,
    /// the filters but nearest, `fitted-gl`).
    pub recons: Vec<Recon>,
    /// The reference. Default (`None`): with `vs`, Catmull–Rom of OTHER
    /// (`dense`); else `truth` when [`CompareOptions::truth`] is known, else `withheld`.
    pub against: Option<Against>,
    /// FILE's closed-form truth, when it has one ([`Truth::of_luminaire`]), in cd.
    pub truth: Option<Truth>,
    /// Folds of the `withheld` reference (k ≥ 2). Default: 2.
    pub folds: usize,
    /// Scaling. Default: cd.
    pub normalize: Normalize,
    /// Declared lamp flux (lm) of FILE and of OTHER, `None` for absolute
    /// photometry: what [`Normalize::Klm`] divides by. Default: none.
    pub lamp_flux_lm: [Option<f64>; 2],
    /// Direction set of the radial metrics. Default: dense 20000.
    pub directions: Directions,
    /// Hausdorff tolerance as a fraction of the reference I_max. Default: 0.001 (0.1 %).
    pub tolerance: f64,
    /// Refinement factor of the grid solids when `solid_tolerance` is `None`. Default: 3.
    pub factor: usize,
    /// Grid solids (and profiles) adaptive to within this fraction of the
    /// reference I_max ([`crate::solid::adaptive`]); `None`: refined
    /// `factor` times. Default: 0.0005 (0.05 %, half the Hausdorff tolerance).
    pub solid_tolerance: Option<f64>,
    /// Search the best C rotation and mirror of FILE onto OTHER (only with `vs`).
    pub align: bool,
    /// Zotti's constant C, fraction of I_max. Default: [`ZOTTI_C`].
    pub zotti_c: f64,
    /// Unit directions timed per reconstruction. Default: 20000.
    pub timing_samples: usize,
    /// Timing repeats (median). Default: 5.
    pub timing_repeats: usize,
    /// Compute the data of the report's plots. Default: false.
    pub plots: bool,
    /// A Type A/B file's own readings: the `withheld` reference then
    /// withholds them instead of the converted grid's points. Default: none.
    pub source: Option<SourceMeasurements>,
    /// Measure only the Hausdorff distance of the `withheld` reference:
    /// a rebuilt solid searched on its surface (at any point count, never
    /// meshed) or made of constant cells is measured only from the withheld
    /// points whose distance can be the largest ([`crate::metrics::largest`]),
    /// so the rows' mean and RMS distances and their `ref_to_recon` are not
    /// measured (`None`). `tradeoff` sets it: its
    /// table shows H alone. Other references ignore it. Default: false.
    pub hausdorff_only: bool,
}

impl CompareOptions {
    /// The directions every timing column samples: `timing_samples` uniform
    /// random unit vectors from one fixed seed, so every row (CPU, f32,
    /// GPU) is timed on the same set.
    pub fn timing_directions(&self) -> Vec<glam::DVec3> {
        crate::metrics::random_directions(self.timing_samples.max(1), 0x5eed)
    }

    /// The reference these options compare against: `against`, or by default
    /// catmull-rom of the other file with one (`with_vs`), the truth when the
    /// file records it, else the file's withheld measurements.
    pub fn reference(&self, with_vs: bool) -> Against {
        self.against.unwrap_or(match (with_vs, self.truth) {
            (true, _) => Against::Recon(Recon::Filter(crate::reconstruct::Filter::CatmullRom)),
            (false, Some(_)) => Against::Truth,
            (false, None) => Against::Withheld,
        })
    }
}

impl Default for CompareOptions {
    fn default() -> Self {
        Self {
            recons: crate::registry::Registry::builtin().candidates(&crate::registry::Job::Compare),
            against: None,
            truth: None,
            folds: 2,
            normalize: Normalize::Cd,
            lamp_flux_lm: [None, None],
            directions: Directions::default(),
            tolerance: 1e-3,
            factor: 3,
            solid_tolerance: Some(5e-4),
            align: false,
            zotti_c: ZOTTI_C,
            timing_samples: 20_000,
            timing_repeats: 5,
            plots: false,
            source: None,
            hausdorff_only: false,
        }
    }
}

/// A Type A/B file's goniometer readings and the handedness it was read
/// with ([`crate::model::Luminaire::source_grid`]): given in
/// [`CompareOptions::source`], the `withheld` reference withholds these
/// readings and rebuilds the Type C grid from the rest, as the reader
/// converted it (`withheld_source`).
#[derive(Debug, Clone, PartialEq)]
pub struct SourceMeasurements {
    /// The readings as the file holds them.
    pub grid: crate::model::SourceGrid,
    /// The rotation sense the file was read with.
    pub handedness: crate::formats::Handedness,
}
