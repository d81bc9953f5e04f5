//! Analytic distributions with closed-form answers: the project's own test data.
//!
//! Every kind is defined in the luminaire frame of [`crate::model`] (γ from
//! nadir, C counter-clockwise from +x). `intensity_cd` sets the peak I0.
//!
//! | kind | I(C, γ) | flux (closed form) |
//! |---|---|---|
//! | `isotropic` | I0 | 4π I0 |
//! | `lambertian` | I0 cos γ (γ ≤ 90°) | π I0 |
//! | `cosine-power` | I0 cos^p γ (γ ≤ 90°) | 2π I0 / (p + 1) |
//! | `spot` | I0 cos^p γ inside the cut-off, 0 outside (an OpenGL spotlight) | 2π I0 (1 − cos^{p+1} c) / (p + 1) |
//! | `batwing` | I0 (3.3 u − 3 u³)/k, u = cos γ, k = max (peak at γ ≈ 52.7°) | 2π I0 · 0.9 / k |
//! | `roadway` | asymmetric: two cos^8 lobes at (C 60°, γ 65°) and (C 120°, γ 65°), house side 0.15 I0 cos γ | numeric |
//!
//! The roadway's street side is C90 in this table's frame. [`Synth::build_for`]
//! turns it onto the front of the format it is written in ([`crate::model::front`]:
//! C90 for EULUMDAT, C0 for IES and TM-33), so every reader finds its front
//! where its light goes; the recorded [`Truth`] carries the turn, so the
//! closed form stays the truth of the file.

use std::f64::consts::PI;

use crate::error::ModelError;
use crate::model::frame::direction;
use crate::model::{Distribution, Format, Front, IntensityField, LampSet, Luminaire, Symmetry};

/// An analytic distribution kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Synth {
    /// Equal intensity in every direction.
    Isotropic,
    /// A Lambertian emitter facing down: I0 cos γ.
    Lambertian,
    /// I0 cos^p γ on the lower hemisphere.
    CosinePower {
        /// Exponent p ≥ 0.
        p: f64,
    },
    /// OpenGL spotlight pointing down: I0 cos^p γ inside `cutoff_deg`, 0 outside.
    Spot {
        /// Exponent p in [0, 128].
        p: f64,
        /// Cut-off angle, degrees in (0, 90].
        cutoff_deg: f64,
    },
    /// Rotationally symmetric batwing with its peak at γ ≈ 52.7°.
    Batwing,
    /// Asymmetric road luminaire (mirror symmetric about the C90-C270 plane only).
    Roadway,
}

/// Peak of 3.3u − 3u³ on [0, 1], at u = sqrt(3.3/9).
fn batwing_peak() -> f64 {
    let u = (3.3f64 / 9.0).sqrt();
    3.3 * u - 3.0 * u.powi(3)
}

impl Synth {
    /// Relative intensity (peak 1) at (C, γ) in degrees.
    pub fn relative(&self, c_deg: f64, g_deg: f64) -> f64 {
        let g = g_deg.to_radians();
        let lower = g_deg <= 90.0;
        match *self {
            Synth::Isotropic => 1.0,
            Synth::Lambertian => {
                if lower {
                    g.cos().max(0.0)
                } else {
                    0.0
                }
            }
            Synth::CosinePower { p } => {
                if lower {
                    g.cos().max(0.0).powf(p)
                } else {
                    0.0
                }
            }
            Synth::Spot { p, cutoff_deg } => {
                if g_deg <= cutoff_deg {
                    g.cos().max(0.0).powf(p)
                } else {
                    0.0
                }
            }
            Synth::Batwing => {
                if lower {
                    let u = g.cos().max(0.0);
                    ((3.3 * u - 3.0 * u.powi(3)) / batwing_peak()).max(0.0)
                } else {
                    0.0
                }
            }
            Synth::Roadway => {
                // Evaluate on the folded angle so the mirror symmetry holds bit for bit.
                let d = direction(Symmetry::C90C270.fold(c_deg), g_deg);
                let lobe = |ca: f64| d.dot(direction(ca, 65.0)).max(0.0).powi(8);
                let house = if lower { 0.15 * g.cos() } else { 0.0 };
                lobe(60.0).max(lobe(120.0)).max(house)
            }
        }
    }

    /// Closed-form flux (lm) for a peak of `intensity_cd`, when one exists.
    pub fn exact_flux(&self, intensity_cd: f64) -> Option<f64> {
        Some(
            intensity_cd
                * match *self {
                    Synth::Isotropic => 4.0 * PI,
                    Synth::Lambertian => PI,
                    Synth::CosinePower { p } => 2.0 * PI / (p + 1.0),
                    Synth::Spot { p, cutoff_deg } => {
                        2.0 * PI * (1.0 - cutoff_deg.to_radians().cos().powf(p + 1.0)) / (p + 1.0)
                    }
                    Synth::Batwing => 2.0 * PI * 0.9 / batwing_peak(),
                    Synth::Roadway => return None,
                },
        )
    }

    /// The CLI name of the kind.
    pub fn name(&self) -> &'static str {
        match self {
            Synth::Isotropic => "isotropic",
            Synth::Lambertian => "lambertian",
            Synth::CosinePower { .. } => "cosine-power",
            Synth::Spot { .. } => "spot",
            Synth::Batwing => "batwing",
            Synth::Roadway => "roadway",
        }
    }

    /// The kind [`Synth::name`] names, with the exponent `p` (cosine-power,
    /// spot) and the cut-off angle `cutoff_deg` (spot), degrees, where the kind
    /// has them; None for another name.
    pub fn named(name: &str, p: f64, cutoff_deg: f64) -> Option<Synth> {
        Some(match name {
            "isotropic" => Synth::Isotropic,
            "lambertian" => Synth::Lambertian,
            "cosine-power" => Synth::CosinePower { p },
            "spot" => Synth::Spot { p, cutoff_deg },
            "batwing" => Synth::Batwing,
            "roadway" => Synth::Roadway,
            _ => return None,
        })
    }

    /// Every kind's name, in [`Synth::name`]'s spelling.
    pub const NAMES: [&'static str; 6] = ["isotropic", "lambertian", "cosine-power", "spot", "batwing", "roadway"];

    fn check(&self) -> Result<(), ModelError> {
        let bad = |name, value: f64, reason: &str| {
            Err(ModelError::Parameter {
                name,
                value: value.to_string(),
                reason: reason.into(),
            })
        };
        match *self {
            Synth::CosinePower { p } if !(0.0..=1e4).contains(&p) => bad("p", p, "must be in [0, 10000]"),
            Synth::Spot { p, .. } if !(0.0..=128.0).contains(&p) => bad("p", p, "must be in [0, 128] (OpenGL)"),
            Synth::Spot { cutoff_deg, .. } if !(cutoff_deg > 0.0 && cutoff_deg <= 90.0) => {
                bad("cutoff", cutoff_deg, "must be in (0, 90] degrees (OpenGL)")
            }
            _ => Ok(()),
        }
    }

    /// The natural symmetry of the kind.
    pub fn symmetry(&self) -> Symmetry {
        match self {
            Synth::Roadway => Symmetry::None,
            _ => Symmetry::Rotational,
        }
    }

    /// The C angle of the roadway kind's street side in the table's frame, degrees.
    pub const ROADWAY_STREET_SIDE_C_DEG: f64 = 90.0;

    /// Sample the kind on `grid` with peak `intensity_cd` (cd). Rotational
    /// kinds store one plane (C = 0); `roadway` stores all of `grid.c`.
    pub fn build(&self, grid: &GridSpec, intensity_cd: f64) -> Result<Luminaire, ModelError> {
        self.build_turned(grid, intensity_cd, 0.0)
    }

    /// [`Synth::build`] for a file of `format`: the roadway turned so that its
    /// street side lies at that format's front (module docs); other kinds as built.
    pub fn build_for(&self, format: Format, grid: &GridSpec, intensity_cd: f64) -> Result<Luminaire, ModelError> {
        let turn = match self {
            Synth::Roadway => Front::convention_c_deg(format) - Self::ROADWAY_STREET_SIDE_C_DEG,
            _ => 0.0,
        };
        let mut lum = self.build_turned(grid, intensity_cd, turn)?;
        lum.set_front(Front::convention(format));
        Ok(lum)
    }

    /// [`Synth::build`] with the closed form turned by `turn_c_deg` about the
    /// vertical axis: I(C, γ) = I_kind(C − turn, γ).
    fn build_turned(&self, grid: &GridSpec, intensity_cd: f64, turn_c_deg: f64) -> Result<Luminaire, ModelError> {
        self.check()?;
        if !(intensity_cd.is_finite() && intensity_cd > 0.0) {
            return Err(ModelError::Parameter {
                name: "intensity",
                value: intensity_cd.to_string(),
                reason: "must be a positive number of cd".into(),
            });
        }
        let sym = self.symmetry();
        let c = if sym == Symmetry::Rotational {
            vec![0.0]
        } else {
            grid.c.clone()
        };
        let mut cd = Vec::with_capacity(c.len() * grid.gamma.len());
        for &cc in &c {
            for &g in &grid.gamma {
                cd.push(intensity_cd * self.relative(crate::model::wrap360(cc - turn_c_deg), g));
            }
        }
        let d = Distribution::new(c, grid.gamma.clone(), cd, sym)?;
        let mut lum = Luminaire::from_distribution(d);
        let flux_lm = self.exact_flux(intensity_cd);
        let md = lum.metadata_mut();
        md.manufacturer = "photosolid".into();
        let truth = Truth {
            turn_c_deg,
            ..self.truth(intensity_cd)
        };
        md.luminaire = format!("{}{}", Truth::PREFIX, truth);
        md.catalogue = format!("SYNTH-{}", self.name().to_uppercase());
        md.lamp = "analytic".into();
        lum.declared_mut().luminaire_flux_lm = flux_lm;
        lum.set_lamp_sets(vec![LampSet {
            count: 1.0,
            lamp_type: "analytic".into(),
            flux_lm: flux_lm.unwrap_or(0.0),
            ..LampSet::default()
        }])?;
        lum.set_version("synthetic");
        Ok(lum)
    }

    /// Kind with its parameters, for metadata.
    pub fn describe(&self) -> String {
        match *self {
            Synth::CosinePower { p } => format!("cosine-power p={p}"),
            Synth::Spot { p, cutoff_deg } => format!("spot p={p} cutoff={cutoff_deg}deg"),
            _ => self.name().to_string(),
        }
    }
}

/// The closed-form distribution of a [`Synth`] kind with its peak: the
/// truth that errors of reconstructions of its sampled files are measured
/// against.
///
/// Files written by `photosolid synth` record it in the luminaire name
/// (`synthetic cosine-power p=5 peak=1000cd`, IES `[LUMINAIRE]`, EULUMDAT
/// line 9), which both readers keep and both writers round-trip, so
/// [`Truth::of_luminaire`] finds it again.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truth {
    /// The analytic kind.
    pub kind: Synth,
    /// The peak intensity I0 (cd) the relative distribution is scaled by.
    pub peak_cd: f64,
    /// The angle the closed form is turned by about the vertical axis,
    /// degrees: I(C, γ) = I_kind(C − turn, γ) (0 but for a roadway written
    /// as IES or TM-33, [`Synth::build_for`]).
    pub turn_c_deg: f64,
}

impl Synth {
    /// The closed-form distribution of this kind with peak `peak_cd` (cd).
    pub fn truth(&self, peak_cd: f64) -> Truth {
        Truth {
            kind: *self,
            peak_cd,
            turn_c_deg: 0.0,
        }
    }

    /// The kind from its [`Synth::describe`] text (`cosine-power p=5`,
    /// `spot p=8 cutoff=40deg`, `roadway`).
    pub fn from_description(text: &str) -> Option<Synth> {
        let mut words = text.split_whitespace();
        let name = words.next()?;
        let mut p = None;
        let mut cutoff = None;
        for w in words {
            let (k, v) = w.split_once('=')?;
            let v: f64 = v.trim_end_matches("deg").parse().ok()?;
            match k {
                "p" => p = Some(v),
                "cutoff" => cutoff = Some(v),
                _ => return None,
            }
        }
        let kind = match name {
            "isotropic" => Synth::Isotropic,
            "lambertian" => Synth::Lambertian,
            "cosine-power" => Synth::CosinePower { p: p? },
            "spot" => Synth::Spot {
                p: p?,
                cutoff_deg: cutoff?,
            },
            "batwing" => Synth::Batwing,
            "roadway" => Synth::Roadway,
            _ => return None,
        };
        kind.check().ok().map(|()| kind)
    }
}

impl Truth {
    /// What a luminaire name starts with when it records its truth.
    pub const PREFIX: &'static str = "synthetic ";

    /// The truth a luminaire written by `photosolid synth` records, if any.
    pub fn of_luminaire(lum: &Luminaire) -> Option<Truth> {
        lum.metadata().luminaire.trim().strip_prefix(Self::PREFIX)?.parse().ok()
    }
}

impl std::fmt::Display for Truth {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} peak={}cd", self.kind.describe(), self.peak_cd)?;
        if self.turn_c_deg != 0.0 {
            write!(f, " turn={}deg", self.turn_c_deg)?;
        }
        Ok(())
    }
}

impl std::str::FromStr for Truth {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || ModelError::Parameter {
            name: "truth",
            value: s.to_string(),
            reason: "expected a synth description such as `cosine-power p=5 peak=1000cd`".into(),
        };
        let (rest, turn_c_deg) = match s.trim().rsplit_once(" turn=") {
            Some((rest, turn)) => {
                let turn: f64 = turn.trim_end_matches("deg").parse().map_err(|_| bad())?;
                if !turn.is_finite() {
                    return Err(bad());
                }
                (rest, turn)
            }
            None => (s.trim(), 0.0),
        };
        let (kind, peak) = rest.rsplit_once(" peak=").ok_or_else(bad)?;
        let peak_cd: f64 = peak.trim_end_matches("cd").parse().map_err(|_| bad())?;
        let kind = Synth::from_description(kind).ok_or_else(bad)?;
        if !(peak_cd.is_finite() && peak_cd > 0.0) {
            return Err(bad());
        }
        Ok(Truth {
            kind,
            peak_cd,
            turn_c_deg,
        })
    }
}

/// The closed form, evaluated exactly (no grid) in any direction.
impl IntensityField for Truth {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let c = if self.turn_c_deg == 0.0 {
            c_deg
        } else {
            crate::model::wrap360(c_deg - self.turn_c_deg)
        };
        self.peak_cd * self.kind.relative(c, gamma_deg.clamp(0.0, 180.0))
    }
    fn name(&self) -> String {
        format!("truth {}", self.kind.describe())
    }
    fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
    }
}

/// The angles a synthetic distribution is sampled at, degrees.
#[derive(Debug, Clone, PartialEq)]
pub struct GridSpec {
    /// C angles in [0, 360), ascending.
    pub c: Vec<f64>,
    /// γ angles in [0, 180], ascending.
    pub gamma: Vec<f64>,
}

impl GridSpec {
    /// A uniform grid: C = 0, c_step, ... < 360 and γ = 0, gamma_step, ..., 180
    /// (180 always included). Steps must divide nothing in particular but be in (0, 180].
    pub fn uniform(c_step: f64, gamma_step: f64) -> Result<Self, ModelError> {
        for (name, s, max) in [("c-step", c_step, 360.0), ("gamma-step", gamma_step, 180.0)] {
            if !(s.is_finite() && s >= 0.01 && s <= max) {
                return Err(ModelError::Parameter {
                    name,
                    value: s.to_string(),
                    reason: format!("must be in [0.01, {max}] degrees"),
                });
            }
        }
        let c: Vec<f64> = (0..)
            .map(|k| k as f64 * c_step)
            .take_while(|&x| x < 360.0 - 1e-9)
            .collect();
        let mut gamma: Vec<f64> = (0..)
            .map(|k| k as f64 * gamma_step)
            .take_while(|&x| x < 180.0 - 1e-9)
            .collect();
        gamma.push(180.0);
        Ok(Self { c, gamma })
    }

    /// Explicit angle lists (checked by the model when the distribution is built).
    pub fn explicit(c: Vec<f64>, gamma: Vec<f64>) -> Self {
        Self { c, gamma }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::flux;

    /// `named` reads back every `name`, and nothing else.
    #[test]
    fn names_read_back() {
        for name in Synth::NAMES {
            assert_eq!(Synth::named(name, 3.0, 40.0).map(|s| s.name()), Some(name));
        }
        assert_eq!(Synth::named("cosine", 1.0, 90.0), None);
        assert_eq!(
            Synth::named("spot", 3.0, 40.0),
            Some(Synth::Spot {
                p: 3.0,
                cutoff_deg: 40.0
            })
        );
    }

    #[test]
    fn sampled_flux_approaches_closed_forms() {
        let grid = GridSpec::uniform(5.0, 0.25).unwrap();
        for kind in [
            Synth::Isotropic,
            Synth::Lambertian,
            Synth::CosinePower { p: 3.0 },
            Synth::Batwing,
        ] {
            let lum = kind.build(&grid, 1000.0).unwrap();
            let exact = kind.exact_flux(1000.0).unwrap();
            let got = flux(lum.distribution()).total_lm;
            // 0.25° steps: the h²-error of the smooth kinds is below 1e-4.
            assert!((got - exact).abs() / exact < 1e-4, "{kind:?}: {got} vs {exact}");
        }
    }

    /// A cut-off is a jump: the linear interpolant turns it into a ramp one
    /// step wide, adding about half a step's zone: 2π I(c) sin(c) h/2 (O(h)).
    #[test]
    fn spot_cutoff_adds_half_a_zone() {
        let h = 0.25f64;
        let kind = Synth::Spot {
            p: 4.0,
            cutoff_deg: 40.0,
        };
        let lum = kind.build(&GridSpec::uniform(5.0, h).unwrap(), 1000.0).unwrap();
        let err = flux(lum.distribution()).total_lm - kind.exact_flux(1000.0).unwrap();
        let c = 40f64.to_radians();
        let ramp = 2.0 * PI * 1000.0 * c.cos().powi(4) * c.sin() * h.to_radians() / 2.0;
        assert!((err - ramp).abs() < 0.02 * ramp, "{err} vs {ramp}");
    }

    #[test]
    fn roadway_is_asymmetric_with_c90_mirror() {
        let lum = Synth::Roadway
            .build(&GridSpec::uniform(5.0, 5.0).unwrap(), 1000.0)
            .unwrap();
        let d = lum.distribution();
        assert_eq!(d.detect_symmetry(1e-9), Symmetry::C90C270);
        assert!((d.max_cd() - 1000.0).abs() < 1e-9);
    }

    #[test]
    fn files_record_their_truth() {
        let g = GridSpec::uniform(15.0, 5.0).unwrap();
        for kind in [
            Synth::Isotropic,
            Synth::Lambertian,
            Synth::CosinePower { p: 5.0 },
            Synth::Spot {
                p: 8.0,
                cutoff_deg: 40.0,
            },
            Synth::Batwing,
            Synth::Roadway,
        ] {
            let lum = kind.build(&g, 1234.5).unwrap();
            let t = Truth::of_luminaire(&lum).unwrap();
            assert_eq!(t, kind.truth(1234.5));
            // The truth agrees with the samples at every measured direction.
            let d = lum.distribution();
            for (ic, &c) in d.c_angles_deg().iter().enumerate() {
                for (ig, &gm) in d.gamma_angles_deg().iter().enumerate() {
                    assert_eq!(t.intensity_cd(c, gm), d.value_cd(ic, ig), "{kind:?} ({c}, {gm})");
                }
            }
        }
        assert!("spot p=8 peak=1cd".parse::<Truth>().is_err());
        assert!("cosine-power p=5 peak=-1cd".parse::<Truth>().is_err());
        assert!("unknown peak=1cd".parse::<Truth>().is_err());
    }

    #[test]
    fn parameters_are_checked() {
        let g = GridSpec::uniform(15.0, 5.0).unwrap();
        assert!(Synth::Spot {
            p: 200.0,
            cutoff_deg: 30.0
        }
        .build(&g, 1.0)
        .is_err());
        assert!(Synth::Spot {
            p: 2.0,
            cutoff_deg: 0.0
        }
        .build(&g, 1.0)
        .is_err());
        assert!(Synth::Isotropic.build(&g, f64::NAN).is_err());
        assert!(GridSpec::uniform(0.0, 5.0).is_err());
    }
}
