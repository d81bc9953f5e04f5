//! The solids of the reports' interactive 3D view, sampled: a reference field
//! and each reconstruction on one regular (C, γ) grid, decimated to what a
//! screen needs (2–5° steps, coarser when there are many solids, so the page
//! stays small), with each reconstruction's signed radial error against the
//! reference at every vertex, (recon − reference) / I_max · 100 (% of I_max):
//! the error of largest magnitude among nine points around the vertex, a
//! fraction of a step off it in C and γ, so that the error between the
//! measured directions shows (interpolating filters are exact at them).
//!
//! An analysis result like the polar curves and error maps
//! ([`PlotData`](super::PlotData)); the report packs it for the page
//! (`crate::report::viewer::ViewerData::from_samples`).

use crate::model::IntensityField;

/// Candidate grid steps (C, γ) in degrees, finest first: each divides 360 and 180.
pub const STEPS_DEG: [(f64, f64); 7] = [
    (2.0, 2.0),
    (3.0, 2.0),
    (4.0, 2.0),
    (5.0, 2.5),
    (5.0, 3.0),
    (6.0, 3.0),
    (5.0, 5.0),
];

/// Binary bytes of mesh data (before base64, which adds a third) that the
/// grid is decimated to fit when it can: with the PNGs (about 600 kB in
/// base64 for the default seven solids) a typical report stays under 1 MB. At the coarsest step (5° × 5°) the size grows with the number of solids.
pub const MESH_BUDGET_BYTES: usize = 200_000;

/// The finest step of `STEPS_DEG` ((C, γ) steps from 2° × 2° to 5° × 5°) whose mesh data for `n_recons`
/// reconstructions and one reference fits [`MESH_BUDGET_BYTES`] (else the coarsest).
pub fn grid_step(n_recons: usize) -> (f64, f64) {
    let fits = |&&(dc, dg): &&(f64, f64)| {
        let verts = (360.0 / dc) as usize * (180.0 / dg + 1.0) as usize;
        verts * (6 + 2 * (n_recons + 1) + 2 * n_recons) <= MESH_BUDGET_BYTES
    };
    *STEPS_DEG.iter().find(fits).unwrap_or(&STEPS_DEG[STEPS_DEG.len() - 1])
}

/// The solids one viewer shows: a reference and reconstructions, all in the same unit.
pub struct SolidSet<'a> {
    /// What the reference is, in words (e.g. `truth (roadway peak=9000cd)`,
    /// `the measured solid`): printed in the viewer's caption.
    pub reference_label: &'a str,
    /// The reference field (intensity in the report's unit, e.g. cd).
    pub reference: &'a dyn IntensityField,
    /// `(name, field)` of each reconstruction, same unit.
    pub recons: &'a [(String, &'a dyn IntensityField)],
    /// The reference's I_max (same unit), the 100 % of the error scale.
    pub i_max: f64,
    /// A note on what the colours mean when that differs from the report's
    /// reference (e.g. a withheld-measurement report colours by the measured solid).
    pub note: Option<String>,
    /// The directions the errors are measured over, when the reconstructions
    /// hold only some (a cropped representation: elsewhere it is 0 by
    /// construction, not an error of the directions it keeps); `None`: all.
    pub error_domain: Option<ErrorDomain>,
}

/// A set of directions: a γ band, and optionally a C sector (from, to; from >
/// to wraps through C0), degrees, ends included.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorDomain {
    /// First and last γ, degrees.
    pub gamma_deg: (f64, f64),
    /// First and last C, degrees; `None`: every C.
    pub c_deg: Option<(f64, f64)>,
}

impl ErrorDomain {
    /// Whether (C, γ) (degrees) lies in the set (1e-9° tolerance at the ends).
    pub fn contains(&self, c_deg: f64, gamma_deg: f64) -> bool {
        const EPS: f64 = 1e-9;
        let (g0, g1) = self.gamma_deg;
        let in_gamma = gamma_deg >= g0 - EPS && gamma_deg <= g1 + EPS;
        let in_c = self.c_deg.is_none_or(|(c0, c1)| {
            let c = c_deg.rem_euclid(360.0);
            if c0 <= c1 {
                c >= c0 - EPS && c <= c1 + EPS
            } else {
                c >= c0 - EPS || c <= c1 + EPS
            }
        });
        in_gamma && in_c
    }
}

impl std::fmt::Display for ErrorDomain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = crate::error::Num;
        write!(f, "γ {}–{}°", n(self.gamma_deg.0), n(self.gamma_deg.1))?;
        if let Some((c0, c1)) = self.c_deg {
            write!(f, ", C {}–{}°", n(c0), n(c1))?;
        }
        Ok(())
    }
}

/// Where the errors are sampled around each vertex, in grid steps: −φ, 0
/// and +φ in C and in γ. A filter that interpolates the measurements is
/// exact at the measured directions, and the view's grid (2–5° steps from
/// 0°) falls on them for most files; φ = 0.37 keeps the other eight points
/// off every grid of whole or half degrees, so the colours and the legend
/// show the error between the measurements, where it is.
const ERR_OFFSET: f64 = 0.37;

/// Per vertex of the grid `cs` × `gs` (steps `(dc, dg)`), the signed error of
/// `recon` against `reference` (% of `i_max`) of largest magnitude among the
/// nine points at offsets {−φ, 0, +φ} × {−φ, 0, +φ} steps around it
/// ([`ERR_OFFSET`]; γ clamped to 0–180°), counting only the points in
/// `domain` when one is given.
fn vertex_errors(
    reference: &dyn IntensityField,
    recon: &dyn IntensityField,
    cs: &[f64],
    gs: &[f64],
    (dc, dg): (f64, f64),
    i_max: f64,
    domain: Option<&ErrorDomain>,
) -> Vec<f64> {
    let mut worst = vec![0.0f64; cs.len() * gs.len()];
    let (mut a, mut b) = (vec![0.0; worst.len()], vec![0.0; worst.len()]);
    for oc in [-ERR_OFFSET, 0.0, ERR_OFFSET] {
        let c: Vec<f64> = cs.iter().map(|&c| (c + oc * dc).rem_euclid(360.0)).collect();
        for og in [-ERR_OFFSET, 0.0, ERR_OFFSET] {
            let g: Vec<f64> = gs.iter().map(|&g| (g + og * dg).clamp(0.0, 180.0)).collect();
            reference.sample_grid(&c, &g, &mut a);
            recon.sample_grid(&c, &g, &mut b);
            for (k, ((w, x), y)) in worst.iter_mut().zip(&b).zip(&a).enumerate() {
                // Vertex k is (C-plane k / ng, γ row k % ng).
                if domain.is_some_and(|d| !d.contains(c[k / gs.len()], g[k % gs.len()])) {
                    continue;
                }
                let e = 100.0 * (x - y) / i_max;
                if e.is_finite() && e.abs() > w.abs() {
                    *w = e;
                }
            }
        }
    }
    worst
}

/// A reference and its reconstructions sampled on one (C, γ) grid: what the
/// 3D view shows, before it is packed for the page.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledSolids {
    /// What the reference is, in words ([`SolidSet::reference_label`]).
    pub reference_label: String,
    /// A note on what the colours mean ([`SolidSet::note`]).
    pub note: Option<String>,
    /// The directions the errors are measured over ([`SolidSet::error_domain`]).
    pub error_domain: Option<ErrorDomain>,
    /// The reference's I_max, the 100 % of the errors (1 when not finite and positive).
    pub i_max: f64,
    /// C step of the grid, degrees.
    pub c_step_deg: f64,
    /// γ step of the grid, degrees.
    pub gamma_step_deg: f64,
    /// C-planes (0 .. 360 − step).
    pub nc: usize,
    /// γ rows (0 ..= 180).
    pub ng: usize,
    /// The reference at every vertex (`ic * ng + ig`), report unit.
    pub reference: Vec<f64>,
    /// Each reconstruction, in the order of [`SolidSet::recons`].
    pub recons: Vec<SampledSolid>,
}

/// One reconstruction of [`SampledSolids`].
#[derive(Debug, Clone, PartialEq)]
pub struct SampledSolid {
    /// Its name.
    pub name: String,
    /// Its value at every vertex, report unit.
    pub values: Vec<f64>,
    /// Its signed error against the reference at every vertex, % of I_max
    /// (the largest in magnitude of nine points around the vertex).
    pub errors_pct: Vec<f64>,
}

impl SampledSolids {
    /// Sample `set` on the grid of [`grid_step`] for its number of reconstructions.
    pub fn new(set: &SolidSet<'_>) -> SampledSolids {
        let (dc, dg) = grid_step(set.recons.len());
        let nc = (360.0 / dc).round() as usize;
        let ng = (180.0 / dg).round() as usize + 1;
        let cs: Vec<f64> = (0..nc).map(|k| k as f64 * dc).collect();
        let gs: Vec<f64> = (0..ng).map(|k| k as f64 * dg).collect();
        let sample = |f: &dyn IntensityField| -> Vec<f64> {
            let mut out = vec![0.0; nc * ng];
            f.sample_grid(&cs, &gs, &mut out);
            out
        };
        let i_max = if set.i_max.is_finite() && set.i_max > 0.0 {
            set.i_max
        } else {
            1.0
        };
        let reference = sample(set.reference);
        let recons: Vec<Vec<f64>> = set.recons.iter().map(|(_, f)| sample(*f)).collect();
        let errors: Vec<Vec<f64>> = set
            .recons
            .iter()
            .map(|(_, f)| vertex_errors(set.reference, *f, &cs, &gs, (dc, dg), i_max, set.error_domain.as_ref()))
            .collect();
        SampledSolids {
            reference_label: set.reference_label.to_string(),
            note: set.note.clone(),
            error_domain: set.error_domain,
            i_max,
            c_step_deg: dc,
            gamma_step_deg: dg,
            nc,
            ng,
            reference,
            recons: set
                .recons
                .iter()
                .zip(recons.into_iter().zip(errors))
                .map(|((name, _), (values, errors_pct))| SampledSolid {
                    name: name.clone(),
                    values,
                    errors_pct,
                })
                .collect(),
        }
    }
}
