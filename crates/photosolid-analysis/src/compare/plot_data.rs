//! What the comparison report draws: polar curves and error maps of intensity fields.

use serde::Serialize;

use super::view::{SampledSolids, SolidSet};
use crate::model::{Distribution, IntensityField};
use crate::reconstruct::eval_all;

/// Curves of one pair of half-planes for a polar diagram: points are (signed γ, value).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PolarPlane {
    /// C of the half-plane drawn with negative γ.
    pub left_c: f64,
    /// C of the half-plane drawn with positive γ.
    pub right_c: f64,
    /// `(name, points)` of each reconstruction, then the reference field.
    pub curves: Vec<(String, Vec<(f64, f64)>)>,
    /// `(label, points)` of measured data (the reference's; with `vs`, FILE's too).
    pub measured: Vec<(String, Vec<(f64, f64)>)>,
}

/// Signed error of one reconstruction over C x γ, % of I_max: `values[iy * xs.len() + ix]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorMap {
    /// The reconstruction.
    pub name: String,
    /// C angles, degrees.
    pub xs: Vec<f64>,
    /// γ angles, degrees.
    pub ys: Vec<f64>,
    /// (recon − reference) / I_max · 100.
    pub values: Vec<f64>,
}

/// What the report draws.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct PlotData {
    /// C0-C180, C90-C270, and the plane of maximum intensity.
    pub planes: Vec<PolarPlane>,
    /// One per reconstruction.
    pub error_maps: Vec<ErrorMap>,
    /// The interactive 3D view's sampled solids (with a field reference), not in the JSON.
    #[serde(skip)]
    pub viewer: Option<SampledSolids>,
}

/// The plot data of a comparison: polar curves of every field in three
/// plane pairs of the reference data `ref_dist` (C0-C180, C90-C270, the
/// plane of maximum intensity), the measured points of the reference data
/// (and of FILE's, `file_dist`, when it is another file), and each
/// reconstruction's signed error map against `reference` (% of `i_max`).
pub(crate) fn plot_data(
    recons: &[(String, &dyn IntensityField)],
    reference: Option<(&str, &dyn IntensityField)>,
    ref_dist: &Distribution,
    file_dist: Option<&Distribution>,
    i_max: f64,
) -> PlotData {
    let c_max = c_of_max(ref_dist);
    let pairs = [
        (0.0, 180.0),
        (90.0, 270.0),
        (c_max, crate::model::wrap360(c_max + 180.0)),
    ];
    let planes = pairs
        .iter()
        .map(|&(right, left)| polar_plane(recons, reference, ref_dist, file_dist, right, left))
        .collect();
    let Some((reference_name, reference)) = reference else {
        return PlotData {
            planes,
            error_maps: Vec::new(),
            viewer: None,
        };
    };
    let error_maps = error_maps(recons, reference, i_max);
    let viewer = Some(SampledSolids::new(&SolidSet {
        reference_label: reference_name,
        reference,
        recons,
        i_max,
        note: None,
        error_domain: None,
    }));
    PlotData {
        planes,
        error_maps,
        viewer,
    }
}

/// The C angle (degrees, of the full circle of planes) of `d`'s largest
/// intensity: the first plane that holds it.
fn c_of_max(d: &Distribution) -> f64 {
    let ng = d.n_gamma();
    let (mut best, mut c_max) = (f64::NEG_INFINITY, 0.0);
    for (c, ic) in d.full_planes() {
        for ig in 0..ng {
            if d.value_cd(ic, ig) > best {
                best = d.value_cd(ic, ig);
                c_max = c;
            }
        }
    }
    c_max
}

/// The polar plot of the plane pair `right` (+γ) and `left` (−γ), C in degrees: the
/// curve of every field, then the reference's, and the measured points of the
/// reference data and (when it is another file) of FILE's.
fn polar_plane(
    recons: &[(String, &dyn IntensityField)],
    reference: Option<(&str, &dyn IntensityField)>,
    ref_dist: &Distribution,
    file_dist: Option<&Distribution>,
    right: f64,
    left: f64,
) -> PolarPlane {
    let mut curves: Vec<(String, Vec<(f64, f64)>)> = recons
        .iter()
        .map(|(name, f)| (name.clone(), polar_curve(*f, right, left)))
        .collect();
    if let Some((name, f)) = reference {
        curves.push((format!("{name} (reference)"), polar_curve(f, right, left)));
    }
    let vs = file_dist.is_some();
    let mut measured = vec![(
        if vs { "measured (OTHER)" } else { "measured" }.to_string(),
        measured_points(ref_dist, right, left),
    )];
    if let Some(fd) = file_dist {
        measured.push(("measured (FILE)".into(), measured_points(fd, right, left)));
    }
    PolarPlane {
        left_c: left,
        right_c: right,
        curves,
        measured,
    }
}

/// `f` along the plane pair as (signed γ, cd) every 0.5°: the plane `left`
/// at −γ (from −180° up), then the plane `right` at +γ.
fn polar_curve(f: &dyn IntensityField, right: f64, left: f64) -> Vec<(f64, f64)> {
    let gammas: Vec<f64> = (0..=360).map(|k| k as f64 * 0.5).collect();
    let mut pts: Vec<(f64, f64)> = gammas.iter().rev().map(|&g| (-g, f.intensity_cd(left, g))).collect();
    pts.extend(gammas.iter().skip(1).map(|&g| (g, f.intensity_cd(right, g))));
    pts
}

/// The measured points of `dist` along the plane pair as (signed γ, cd), at
/// its own γ angles: the plane `left` at −γ, then the plane `right` at +γ > 0.
fn measured_points(dist: &Distribution, right: f64, left: f64) -> Vec<(f64, f64)> {
    let g = dist.gamma_angles_deg();
    let (r, l) = (
        crate::photometry::plane_profile(dist, right),
        crate::photometry::plane_profile(dist, left),
    );
    let mut pts: Vec<(f64, f64)> = g.iter().zip(&l).rev().map(|(&g, &v)| (-g, v)).collect();
    pts.extend(g.iter().zip(&r).filter(|(&g, _)| g > 0.0).map(|(&g, &v)| (g, v)));
    pts
}

/// Each reconstruction's signed error against `reference`, % of `i_max` (cd),
/// on the cell centres of a 2° x 1° (C, γ) grid.
fn error_maps(recons: &[(String, &dyn IntensityField)], reference: &dyn IntensityField, i_max: f64) -> Vec<ErrorMap> {
    // Cell centres of a 2° x 1° grid: between the knots of the usual
    // measurement grids, where reconstructions differ (at a knot every
    // interpolating filter equals the measurement).
    let xs: Vec<f64> = (0..180).map(|k| 1.0 + k as f64 * 2.0).collect();
    let ys: Vec<f64> = (0..180).map(|k| 0.5 + k as f64).collect();
    let dirs: Vec<(f64, f64)> = ys.iter().flat_map(|&g| xs.iter().map(move |&c| (c, g))).collect();
    let m = eval_all(reference, &dirs);
    recons
        .iter()
        .map(|(name, f)| {
            let v = eval_all(*f, &dirs);
            ErrorMap {
                name: name.clone(),
                xs: xs.clone(),
                ys: ys.clone(),
                values: v.iter().zip(&m).map(|(a, b)| 100.0 * (a - b) / i_max).collect(),
            }
        })
        .collect()
}
