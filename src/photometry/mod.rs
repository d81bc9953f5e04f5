//! Photometric quantities of a [`Distribution`](crate::model::Distribution): flux, output ratios,
//! beam and field angles, and the derived tables lighting engineers read
//! off a data sheet: CIE flux code, zonal lumens, UGR table, BUG rating and
//! luminance table.
//!
//! Every quantity here integrates or samples the **bilinear reconstruction**
//! of the measured grid (piecewise linear in γ, trapezoid/linear in C), the
//! same rule as [`flux()`], so flux, zonal lumens, flux codes and BUG zones add
//! up exactly. See [`flux`](mod@flux) for the rule.

pub mod beam;
pub mod bug;
pub mod derived;
pub mod flux;
pub mod luminance;
pub mod ugr;
pub mod zonal;

/// Closed-form distributions shared by the unit tests of these modules.
#[cfg(test)]
mod test_support {
    use crate::model::{Distribution, Symmetry};

    /// A rotationally symmetric distribution: `f(γ in radians)` cd at each `gamma` (degrees).
    pub fn rot(gamma: Vec<f64>, f: impl Fn(f64) -> f64) -> Distribution {
        let cd = gamma.iter().map(|&g| f(g.to_radians())).collect();
        Distribution::new(vec![0.0], gamma, cd, Symmetry::Rotational).unwrap()
    }

    /// `n` evenly spaced angles from 0 to `to` degrees.
    pub fn uniform(n: usize, to: f64) -> Vec<f64> {
        (0..n).map(|i| to * i as f64 / (n - 1) as f64).collect()
    }
}

pub use beam::{beam_angles, plane_profile, spread_angle, BeamAngles};
pub use derived::Derived;
pub use flux::{flux, zone_flux, Flux};

use serde::Serialize;

use crate::error::{Warning, WarningCode};
use crate::model::Luminaire;

/// The photometric summary of a luminaire that `info` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Largest intensity, cd.
    pub max_cd: f64,
    /// Direction of the largest intensity: (C, γ) in degrees.
    pub max_direction_deg: (f64, f64),
    /// Computed flux.
    pub flux: Flux,
    /// Declared luminaire flux, lm (lamp flux × LOR, or the absolute flux).
    pub declared_flux_lm: Option<f64>,
    /// Computed flux / declared flux.
    pub flux_ratio: Option<f64>,
    /// Light output ratio: computed flux / lamp flux (None for absolute photometry).
    pub lor: Option<f64>,
    /// Downward light output ratio.
    pub dlor: Option<f64>,
    /// Upward light output ratio.
    pub ulor: Option<f64>,
    /// Downward flux fraction: downward / total flux.
    pub dff: Option<f64>,
    /// Beam and field angles.
    pub beams: BeamAngles,
    /// Consistency warnings (declared vs computed).
    pub warnings: Vec<Warning>,
}

/// Relative difference past which declared and computed flux disagree.
pub const FLUX_MISMATCH: f64 = 0.05;

/// Difference (fraction, i.e. 0.01 = 1 percentage point) past which computed and declared LOR disagree.
pub const LOR_MISMATCH: f64 = 0.01;

/// Compute the summary of `lum` (untilted).
pub fn summary(lum: &Luminaire) -> Summary {
    let d = lum.distribution();
    let (max_cd, mc, mg) = d.max_cd_at_deg();
    let flux = flux(d);
    let lamp = if lum.declared().absolute {
        None
    } else {
        lum.declared().lamp_flux_lm.filter(|&v| v > 0.0)
    };
    // A ratio to a declared flux is reported only when it is a number: a
    // file may declare a flux so small (1e-320 lm) that the ratio overflows.
    let ratio = |x: f64| lamp.map(|l| x / l).filter(|r| r.is_finite());
    let declared = lum.declared().luminaire_flux_lm.filter(|&v| v > 0.0);
    let flux_ratio = declared.map(|dcl| flux.total_lm / dcl).filter(|r| r.is_finite());
    let mut warnings = Vec::new();
    if let (Some(r), Some(dcl)) = (flux_ratio, declared) {
        if (r - 1.0).abs() > FLUX_MISMATCH {
            warnings.push(Warning::new(
                WarningCode::FluxMismatch,
                format!(
                    "integrated flux {:.1} lm is {} of the declared {:.1} lm (more than {:.0} % off)",
                    flux.total_lm,
                    // A finite ratio near f64::MAX overflows as a percentage (fuzz finding 9).
                    if (100.0 * r).is_finite() {
                        format!("{:.1} %", 100.0 * r)
                    } else {
                        format!("{} times", crate::error::Num(r))
                    },
                    dcl,
                    100.0 * FLUX_MISMATCH
                ),
            ));
        }
    }
    if let (Some(decl), Some(l)) = (lum.declared().lor, lamp) {
        let lor = flux.total_lm / l;
        if (lor - decl).abs() > LOR_MISMATCH {
            warnings.push(Warning::new(
                WarningCode::LorMismatch,
                format!(
                    "integrated LOR {:.2} % differs from the declared {:.2} % by {:+.2} percentage points",
                    100.0 * lor,
                    100.0 * decl,
                    100.0 * (lor - decl)
                ),
            ));
        }
    }
    if let (Some(decl_dff), true) = (lum.declared().dff, flux.total_lm > 0.0) {
        let dff = flux.downward_lm / flux.total_lm;
        if (dff - decl_dff).abs() > 0.05 {
            warnings.push(Warning::new(
                WarningCode::DffMismatch,
                format!(
                    "computed downward flux fraction {:.1} % differs from the declared {:.1} %",
                    100.0 * dff,
                    100.0 * decl_dff
                ),
            ));
        }
    }
    Summary {
        max_cd,
        max_direction_deg: (mc, mg),
        flux,
        declared_flux_lm: declared,
        flux_ratio,
        lor: ratio(flux.total_lm),
        dlor: ratio(flux.downward_lm),
        ulor: ratio(flux.upward_lm),
        dff: (flux.total_lm > 0.0).then(|| flux.downward_lm / flux.total_lm),
        beams: beam_angles(d),
        warnings,
    }
}
