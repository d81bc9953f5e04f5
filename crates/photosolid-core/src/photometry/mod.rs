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
pub mod floodlight;
pub mod flux;
pub mod luminance;
pub mod throw;
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
pub use floodlight::{floodlight, Floodlight};
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

/// Largest light output ratio a luminaire can have (fraction): 100 % plus
/// half a percentage point for rounding in the files.
pub const LOR_PHYSICAL_MAX: f64 = 1.005;

/// Codes of the warnings [`summary`] gives for declarations no luminaire can
/// have (the batch catalogue lists such files among its first outliers).
pub const IMPOSSIBLE_DECLARATIONS: [&str; 4] = [
    "lor-above-100",
    "flux-above-lamp",
    "luminous-area-larger-than-luminaire",
    "efficacy-above-limit",
];

/// The luminous efficacy of radiation at 555 nm, lm/W: no luminaire's
/// flux per input watt can exceed it (CIE S 017, the definition of K_m).
pub const MAX_EFFICACY_LM_PER_W: f64 = 683.0;

/// The input power a file declares, and where it says so.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputWatts {
    /// Input power, W (finite, positive).
    pub watts: f64,
    /// Where it came from, for messages.
    pub source: &'static str,
}

/// The input power of `lum`, W: IES the input watts field, EULUMDAT the sum
/// of the lamp sets' wattage, TM-33 `InputWattage`; `None` when the file
/// gives none (or 0, or a value that is not a positive number).
pub fn input_watts(lum: &Luminaire) -> Option<InputWatts> {
    let watts = lum.declared().input_watts?;
    let source = match lum.format() {
        crate::model::Format::Ldt => "the sum of the EULUMDAT lamp sets' wattage (line 26f)",
        crate::model::Format::Ies => "the IES input watts field",
        crate::model::Format::Tm33 => "TM-33 InputWattage",
    };
    (watts.is_finite() && watts > 0.0).then_some(InputWatts { watts, source })
}

/// Declarations no luminaire can have: a light output ratio above 100 %
/// (declared or computed, relative photometry only: a luminaire cannot emit
/// more than its lamps), a luminaire flux declared above the lamp flux where
/// the file declares both separately (no LOR links them; with a LOR the
/// first check says it), and a luminous area larger than the luminaire
/// (EULUMDAT, which declares both).
fn impossible_declarations(lum: &Luminaire, computed_lm: f64) -> Vec<Warning> {
    let mut out = Vec::new();
    if let Some(w) = input_watts(lum) {
        let efficacy = computed_lm / w.watts;
        if efficacy > MAX_EFFICACY_LM_PER_W {
            out.push(Warning::new(
                WarningCode::EfficacyAboveLimit,
                format!(
                    "luminous efficacy {efficacy:.2} lm/W ({computed_lm:.1} lm / {} W, the watts from {}) is above \
                     {MAX_EFFICACY_LM_PER_W} lm/W, the most any light source can give: the input watts are wrong",
                    crate::error::Num(w.watts),
                    w.source
                ),
            ));
        }
    }
    let dcl = lum.declared();
    let pct = |x: f64| format!("{:.1} %", 100.0 * x);
    if !dcl.absolute {
        let lamp = dcl.lamp_flux_lm.filter(|&l| l > 0.0 && l.is_finite());
        let computed = lamp.map(|l| computed_lm / l).filter(|r| r.is_finite());
        let declared = dcl.lor.filter(|r| r.is_finite());
        let over: Vec<String> = [("declared", declared), ("computed", computed)]
            .into_iter()
            .filter_map(|(what, lor)| {
                lor.filter(|&r| r > LOR_PHYSICAL_MAX)
                    .map(|r| format!("{what} {}", pct(r)))
            })
            .collect();
        if !over.is_empty() {
            out.push(Warning::new(
                WarningCode::LorAbove100,
                format!(
                    "light output ratio above 100 % ({}): a luminaire cannot emit more than its lamps",
                    over.join(", ")
                ),
            ));
        }
        if let (Some(l), Some(f), None) = (lamp, dcl.luminaire_flux_lm, dcl.lor) {
            if f > LOR_PHYSICAL_MAX * l {
                out.push(Warning::new(
                    WarningCode::FluxAboveLamp,
                    format!(
                        "declared luminaire flux {f:.1} lm is above the lamp flux {l:.1} lm ({})",
                        pct(f / l)
                    ),
                ));
            }
        }
    }
    if lum.format() == crate::model::Format::Ldt {
        let (body, area) = (lum.dimensions(), lum.luminous_opening());
        // Width 0 is a circle of diameter `length` (EULUMDAT), for the body and the area alike.
        let width = |d: crate::model::Dimensions| if d.width_m == 0.0 { d.length_m } else { d.width_m };
        // Half a millimetre for files that round to whole millimetres.
        let larger = |a: f64, b: f64| b > 0.0 && a > b + 5e-4;
        let size = |d: crate::model::Dimensions| {
            if d.width_m == 0.0 {
                format!("a circle of {:.0} mm", 1000.0 * d.length_m)
            } else {
                format!("{:.0} x {:.0} mm", 1000.0 * d.length_m, 1000.0 * d.width_m)
            }
        };
        if larger(area.length_m, body.length_m) || larger(width(area), width(body)) {
            out.push(Warning::new(
                WarningCode::LuminousAreaLargerThanLuminaire,
                format!(
                    "the luminous area ({}) is larger than the luminaire ({})",
                    size(area),
                    size(body)
                ),
            ));
        }
    }
    out
}

/// `beam-angle-undefined` when a lit distribution has no IES beam or field
/// angle in the C0-C180 plane, with the reason ([`beam::undefined_reason`]).
fn beam_angle_undefined(d: &crate::model::Distribution, beams: &BeamAngles, max_cd: f64) -> Option<Warning> {
    if max_cd <= 0.0 {
        return None;
    }
    let undefined = [
        ("beam", 0.5, beams.ies_beam_deg[0]),
        ("field", 0.1, beams.ies_field_deg[0]),
    ]
    .into_iter()
    .filter(|(_, _, v)| v.is_none())
    .filter_map(|(what, f, _)| beam::undefined_reason(d, 0.0, f).map(|why| format!("{what} angle: {why}")))
    .collect::<Vec<_>>();
    (!undefined.is_empty()).then(|| {
        Warning::new(
            WarningCode::BeamAngleUndefined,
            format!(
                "no IES beam/field angle in the C0-C180 plane ({}); beam_angle_deg / field_angle_deg are null",
                undefined.join("; ")
            ),
        )
    })
}

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
    warnings.extend(impossible_declarations(lum, flux.total_lm));
    let beams = beam_angles(d);
    warnings.extend(beam_angle_undefined(d, &beams, max_cd));
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
        beams,
        warnings,
    }
}

#[cfg(test)]
mod impossible_tests {
    use super::*;
    use crate::model::{Declared, Dimensions, Format};

    /// An isotropic 1000 cd luminaire (4π klm) with `declared` and an EULUMDAT body/area.
    fn luminaire(declared: Declared, body: Dimensions, area: Dimensions) -> Luminaire {
        let d = test_support::rot(vec![0.0, 90.0, 180.0], |_| 1000.0);
        let mut parts = Luminaire::from_distribution(d).into_parts();
        parts.format = Format::Ldt;
        parts.declared = declared;
        parts.dimensions = body;
        parts.luminous_opening = area;
        Luminaire::from_parts(parts).unwrap()
    }

    fn codes(l: &Luminaire) -> Vec<&'static str> {
        summary(l).warnings.iter().map(|w| w.code.as_str()).collect()
    }

    fn dims(l: f64, w: f64) -> Dimensions {
        Dimensions {
            length_m: l,
            width_m: w,
            height_m: 0.05,
        }
    }

    fn declared(lamp: f64, luminaire: Option<f64>, lor: Option<f64>, absolute: bool) -> Declared {
        Declared {
            lamp_flux_lm: (!absolute).then_some(lamp),
            luminaire_flux_lm: luminaire,
            lor,
            dff: None,
            absolute,
            input_watts: None,
        }
    }

    /// 1 W of input for 4π klm (12,566 lm/W) is past 683 lm/W: flagged with the watts
    /// and where they came from; 20 W (628 lm/W) is not.
    #[test]
    fn efficacy_above_the_theoretical_limit_is_flagged() {
        let with_watts = |w: f64| {
            let mut parts = luminaire(declared(1.0, None, None, true), dims(0.6, 0.3), dims(0.6, 0.3)).into_parts();
            parts.format = Format::Ies;
            parts.declared.input_watts = Some(w);
            Luminaire::from_parts(parts).unwrap()
        };
        let w = summary(&with_watts(1.0))
            .warnings
            .into_iter()
            .find(|w| w.code == WarningCode::EfficacyAboveLimit)
            .unwrap();
        assert!(
            w.message.contains("1 W") && w.message.contains("IES input watts"),
            "{}",
            w.message
        );
        assert!(!codes(&with_watts(20.0)).contains(&"efficacy-above-limit"));
    }

    /// Each impossible declaration is flagged by its code, and only it:
    /// a declared LOR of 112 %, a computed one of 4π klm / 10 klm = 126 %, a
    /// luminaire flux above the lamp flux with no LOR between them, a
    /// luminous area longer (or, for a circle, wider) than the body.
    #[test]
    fn impossible_declarations_are_flagged() {
        let flux = 4.0 * std::f64::consts::PI * 1000.0;
        let ok = luminaire(
            declared(flux, Some(flux), Some(1.0), false),
            dims(0.6, 0.3),
            dims(0.6, 0.3),
        );
        assert!(impossible_declarations(&ok, flux).is_empty(), "{:?}", codes(&ok));
        // 100.4 % is rounding, not physics.
        let rounding = luminaire(
            declared(flux / 1.004, None, Some(1.004), false),
            dims(0.6, 0.3),
            dims(0.6, 0.3),
        );
        assert!(impossible_declarations(&rounding, flux).is_empty());
        // The JSON spelling is the code's (serde's kebab-case alone would write `lor-above100`).
        for code in [
            WarningCode::LorAbove100,
            WarningCode::FluxAboveLamp,
            WarningCode::LuminousAreaLargerThanLuminaire,
        ] {
            assert_eq!(serde_json::to_value(code).unwrap(), code.as_str());
        }
        let declared_lor = luminaire(
            declared(2.0 * flux, None, Some(1.12), false),
            dims(0.6, 0.3),
            dims(0.6, 0.3),
        );
        let w = impossible_declarations(&declared_lor, flux);
        assert_eq!(w.len(), 1);
        assert_eq!(w[0].code, WarningCode::LorAbove100);
        assert!(w[0].message.contains("declared 112.0 %"), "{}", w[0].message);
        let computed_lor = luminaire(
            declared(10_000.0, None, Some(0.9), false),
            dims(0.6, 0.3),
            dims(0.6, 0.3),
        );
        let w = impossible_declarations(&computed_lor, flux);
        assert!(w[0].message.contains("computed 125.7 %"), "{}", w[0].message);
        // Absolute photometry has no lamp flux to exceed.
        let absolute = luminaire(declared(0.0, Some(flux), None, true), dims(0.6, 0.3), dims(0.6, 0.3));
        assert!(impossible_declarations(&absolute, flux).is_empty());
        let separate = luminaire(
            declared(1000.0, Some(1200.0), None, false),
            dims(0.6, 0.3),
            dims(0.6, 0.3),
        );
        assert!(codes(&separate).contains(&"flux-above-lamp"), "{:?}", codes(&separate));
        let long = luminaire(declared(flux, None, Some(1.0), false), dims(0.6, 0.3), dims(0.7, 0.3));
        assert!(codes(&long).contains(&"luminous-area-larger-than-luminaire"));
        // A 105 mm circle in a 96 x 96 mm body (corpus gldf-rs/SLV_Tria2_narrow.ldt).
        let circle = luminaire(
            declared(flux, None, Some(1.0), false),
            dims(0.096, 0.096),
            dims(0.105, 0.0),
        );
        assert!(codes(&circle).contains(&"luminous-area-larger-than-luminaire"));
    }
}
