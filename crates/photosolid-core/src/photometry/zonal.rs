//! Zonal lumens and the CIE flux code.
//!
//! # Zonal lumens
//! Flux in γ zones over the whole circle of C, by [`zone_flux`](super::zone_flux) (the rule of
//! [`flux`](super::flux())): the eighteen 10° zones 0-10 … 170-180 and the
//! cumulative IES zones 0-30, 0-40, 0-60, 0-90, 90-180 (IES LM-63 /
//! Photometric Toolbox "zonal lumen summary"), each in lm, in % of the lamp
//! flux (relative photometry only) and in % of the luminaire flux.
//!
//! # CIE flux code (CIE 52:1982; docs/domain.md §5)
//! The cumulative downward cones of π/2, π, 3π/2 and 2π sr have half-angles
//! arccos(3/4) = 41.41°, arccos(1/2) = 60°, arccos(1/4) = 75.52° and 90°:
//! N1 = Φ(0-41.4)/Φ(0-90), N2 = Φ(0-60)/Φ(0-90), N3 = Φ(0-75.5)/Φ(0-90),
//! N4 = Φ(0-90)/Φ(0-180) (= DLOR/LOR), N5 = LOR, each in %, written as five
//! rounded integers ("45 72 95 100 100"). For absolute photometry the file's
//! flux is the luminaire flux (EULUMDAT writes LORL = 100 then), so N5 = 100.
//! Closed forms: an isotropic downlight gives N1..N3 = 25, 50, 75 (Φ(θ) ∝ 1 − cos θ);
//! a Lambertian one gives 43.75, 75, 93.75 (Φ(θ) ∝ sin²θ).

use serde::Serialize;

use super::flux::Rings;
use crate::model::Luminaire;

/// One γ zone over the whole circle of C.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Zone {
    /// Lower γ bound, degrees.
    pub from_deg: f64,
    /// Upper γ bound, degrees.
    pub to_deg: f64,
    /// Flux in the zone, lm.
    pub lm: f64,
    /// Percent of the declared lamp flux (None for absolute photometry).
    pub percent_lamp: Option<f64>,
    /// Percent of the luminaire (integrated) flux (None when it is 0).
    pub percent_luminaire: Option<f64>,
}

/// Zonal lumen summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZonalLumens {
    /// The 10° zones 0-10 … 170-180.
    pub ten_degree: Vec<Zone>,
    /// The IES summary zones 0-30, 0-40, 0-60, 0-90, 90-180 and 0-180.
    pub summary: Vec<Zone>,
}

/// γ bounds (degrees) of the IES summary zones.
pub const IES_ZONES: [(f64, f64); 6] = [
    (0.0, 30.0),
    (0.0, 40.0),
    (0.0, 60.0),
    (0.0, 90.0),
    (90.0, 180.0),
    (0.0, 180.0),
];

/// Flux (lm) in γ ∈ [a, b] (degrees) over the whole circle: `zone_flux(d, (a, b), (0.0, 360.0))`.
fn ring(rings: &Rings<'_>, a: f64, b: f64) -> f64 {
    rings.flux((a, b))
}

/// Percent `x / of`, or None when it is not a finite number.
fn percent(x: f64, of: Option<f64>) -> Option<f64> {
    of.filter(|&v| v > 0.0).map(|v| 100.0 * x / v).filter(|p| p.is_finite())
}

/// The lamp flux ratios refer to: the declared lamp flux of relative photometry.
pub(crate) fn lamp_flux(lum: &Luminaire) -> Option<f64> {
    if lum.declared().absolute {
        None
    } else {
        lum.declared().lamp_flux_lm.filter(|&v| v > 0.0 && v.is_finite())
    }
}

/// Zonal lumens of `lum`.
pub fn zonal_lumens(lum: &Luminaire) -> ZonalLumens {
    let d = &Rings::new(lum.distribution());
    let lamp = lamp_flux(lum);
    let total = ring(d, 0.0, 180.0);
    let zone = |a: f64, b: f64| {
        let lm = ring(d, a, b);
        Zone {
            from_deg: a,
            to_deg: b,
            lm,
            percent_lamp: percent(lm, lamp),
            percent_luminaire: percent(lm, Some(total)),
        }
    };
    ZonalLumens {
        ten_degree: (0..18).map(|k| zone(10.0 * k as f64, 10.0 * (k + 1) as f64)).collect(),
        summary: IES_ZONES.iter().map(|&(a, b)| zone(a, b)).collect(),
    }
}

/// The CIE flux code (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CieFluxCode {
    /// N1..N5 in percent.
    pub n: [f64; 5],
    /// The five values rounded to integers, space separated, e.g. "45 72 95 100 100".
    pub code: String,
    /// True when N5 is 100 by the absolute-photometry convention rather than a computed LOR.
    pub n5_absolute: bool,
}

/// Half-angle (degrees) of the downward cone of `k`·π/2 sr, k = 1, 2, 3: arccos(1 − k/4).
pub fn cone_half_angle_deg(k: u8) -> f64 {
    (1.0 - f64::from(k) / 4.0).acos().to_degrees()
}

/// The CIE flux code of `lum`; None when the luminaire emits nothing downward
/// (N1..N3 are fractions of the downward flux) or the total flux is 0.
pub fn cie_flux_code(lum: &Luminaire) -> Option<CieFluxCode> {
    let d = &Rings::new(lum.distribution());
    let down = ring(d, 0.0, 90.0);
    let total = ring(d, 0.0, 180.0);
    if !(down > 0.0 && total > 0.0) {
        return None;
    }
    let cone = |k: u8| 100.0 * ring(d, 0.0, cone_half_angle_deg(k)) / down;
    let lamp = lamp_flux(lum);
    let (n5, n5_absolute) = match lamp {
        Some(l) => (100.0 * total / l, false),
        None => (100.0, true),
    };
    let n = [cone(1), cone(2), cone(3), 100.0 * down / total, n5];
    if n.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let code = n.iter().map(|v| format!("{:.0}", v)).collect::<Vec<_>>().join(" ");
    Some(CieFluxCode { n, code, n5_absolute })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Distribution, Symmetry};
    use std::f64::consts::PI;

    fn lum(gamma: Vec<f64>, f: impl Fn(f64) -> f64, lamp: Option<f64>) -> Luminaire {
        let cd = gamma.iter().map(|&g| f(g.to_radians())).collect();
        let d = Distribution::new(vec![0.0], gamma, cd, Symmetry::Rotational).unwrap();
        let mut l = Luminaire::from_distribution(d);
        if let Some(v) = lamp {
            l.declared_mut().absolute = false;
            l.declared_mut().lamp_flux_lm = Some(v);
        }
        l
    }

    fn grid(n: usize, to: f64) -> Vec<f64> {
        (0..n).map(|i| to * i as f64 / (n - 1) as f64).collect()
    }

    /// Closed forms (module docs): the cone half-angles hold k·π/2 sr, and an
    /// isotropic downlight's code is 25 50 75 100 N5 on any grid (linear data
    /// are integrated exactly), with N5 = flux / lamp flux.
    #[test]
    fn isotropic_downlight_code_is_exact() {
        for k in 1..=3u8 {
            let sr = 2.0 * PI * (1.0 - cone_half_angle_deg(k).to_radians().cos());
            assert!((sr - f64::from(k) * PI / 2.0).abs() < 1e-12);
        }
        assert!((cone_half_angle_deg(1) - 41.4096).abs() < 1e-4);
        assert!((cone_half_angle_deg(3) - 75.5225).abs() < 1e-4);
        let l = lum(grid(7, 90.0), |_| 10.0, Some(20.0 * PI / 0.8));
        let c = cie_flux_code(&l).unwrap();
        for (got, want) in c.n.iter().zip([25.0, 50.0, 75.0, 100.0, 80.0]) {
            assert!((got - want).abs() < 1e-9, "{:?}", c.n);
        }
        assert_eq!(c.code, "25 50 75 100 80");
    }

    /// Lambertian I0 cos γ: Φ(θ)/Φ(90) = sin²θ, so N1 = 7/16, N2 = 3/4, N3 =
    /// 15/16; on a 1° grid the piecewise-linear integral is within 0.01 %.
    #[test]
    fn lambertian_code_converges_to_closed_form() {
        let l = lum(grid(181, 180.0), |g| if g <= PI / 2.0 { g.cos() } else { 0.0 }, None);
        let c = cie_flux_code(&l).unwrap();
        for (got, want) in c.n.iter().zip([43.75, 75.0, 93.75, 100.0, 100.0]) {
            assert!((got - want).abs() < 1e-2, "{:?}", c.n);
        }
        assert!(c.n5_absolute);
        assert_eq!(c.code, "44 75 94 100 100");
    }

    /// Zones of an isotropic 1 cd source: 2π (cos a − cos b) lm each, sums
    /// equal to the total 4π, percentages of a 100 lm lamp.
    #[test]
    fn isotropic_zones_are_closed_form() {
        let l = lum(grid(13, 180.0), |_| 1.0, Some(100.0));
        let z = zonal_lumens(&l);
        let ring = |a: f64, b: f64| 2.0 * PI * (a.to_radians().cos() - b.to_radians().cos());
        for zone in z.ten_degree.iter().chain(&z.summary) {
            let want = ring(zone.from_deg, zone.to_deg);
            assert!((zone.lm - want).abs() < 1e-12, "{zone:?}");
            assert!((zone.percent_lamp.unwrap() - want).abs() < 1e-10);
            assert!((zone.percent_luminaire.unwrap() - 100.0 * want / (4.0 * PI)).abs() < 1e-10);
        }
        let sum: f64 = z.ten_degree.iter().map(|z| z.lm).sum();
        assert!((sum - 4.0 * PI).abs() < 1e-12);
    }

    /// Extremes: all-zero data and upward-only light have no flux code (no
    /// downward flux to divide by) and zones of 0 lm, never NaN.
    #[test]
    fn zero_and_upward_only_have_no_code() {
        let zero = lum(grid(19, 180.0), |_| 0.0, Some(1000.0));
        assert!(cie_flux_code(&zero).is_none());
        let z = zonal_lumens(&zero);
        assert!(z
            .ten_degree
            .iter()
            .all(|z| z.lm == 0.0 && z.percent_luminaire.is_none()));
        let up = lum(grid(19, 180.0), |g| if g > PI / 2.0 { 1e6 } else { 0.0 }, None);
        assert!(cie_flux_code(&up).is_none());
        let tiny = lum(grid(19, 90.0), |_| 1e-6, None);
        assert_eq!(cie_flux_code(&tiny).unwrap().code, "25 50 75 100 100");
    }
}
