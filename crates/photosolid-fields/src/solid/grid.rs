//! The solid of any reconstruction, sampled on a C x γ grid.
//!
//! Vertices sit at I(C, γ) d(C, γ) for every C of the grid (the circle is
//! closed: the last C connects to the first) and every γ strictly between
//! the poles; each pole is one vertex whose intensity is the mean of the
//! field over the C angles there (weighted by each angle's share of the
//! circle), joined to the first (last) ring by a triangle fan. Each grid
//! quad is split along the same diagonal, (C_i, γ_j)–(C_i+1, γ_j+1), unless
//! that split has a zero-area triangle and the other does not. Zero samples
//! become the merged origin vertex (see [`crate::solid`] for the topology).
//!
//! The volume of a smooth solid converges as h² in the grid step (the
//! polyhedron inscribed in the surface).

use super::mesh::{p64, Mesh, SolidInfo};
use super::{stored_radius, Units};
use crate::error::ModelError;
use crate::model::{periodic_widths, Distribution, IntensityField, ANGLE_EPS};

/// Largest number of grid points (C-planes × γ angles) a solid grid may
/// hold: about 2^24, i.e. 33 M triangles, several GB of mesh. A larger
/// `--factor` is refused before anything is allocated.
pub const MAX_GRID_POINTS: usize = 1 << 24;

/// The C x γ angles (degrees) a reconstruction is sampled at.
///
/// Invariants: C ascending in [0, 360), at least 3 angles, every gap on the
/// circle below 180° (so the rings enclose the axis); γ ascending from
/// exactly 0 to exactly 180 with at least one angle in between.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidGrid {
    c: Vec<f64>,
    gamma: Vec<f64>,
}

impl SolidGrid {
    /// A grid from explicit angles (degrees). γ = 0 and γ = 180 are added
    /// when missing: the solid always covers the whole sphere (the field
    /// decides where it is zero).
    pub fn new(c: Vec<f64>, mut gamma: Vec<f64>) -> Result<Self, ModelError> {
        let bad = |axis: &'static str, reason: String| ModelError::Angles { axis, reason };
        if c.len() < 3 {
            return Err(bad("C", format!("a solid needs at least 3 C angles, got {}", c.len())));
        }
        for (i, &a) in c.iter().enumerate() {
            if !a.is_finite() || !(0.0..360.0).contains(&a) || (i > 0 && a <= c[i - 1]) {
                return Err(bad("C", format!("angle #{} = {a} is not ascending in [0, 360)", i + 1)));
            }
        }
        let widest = (0..c.len())
            .map(|i| {
                if i + 1 == c.len() {
                    c[0] + 360.0 - c[i]
                } else {
                    c[i + 1] - c[i]
                }
            })
            .fold(0.0, f64::max);
        if widest >= 180.0 - ANGLE_EPS {
            return Err(bad(
                "C",
                format!("a gap of {widest}° between C angles: the rings would not enclose the axis"),
            ));
        }
        if gamma.first().is_none_or(|&g| g > ANGLE_EPS) {
            gamma.insert(0, 0.0);
        }
        if gamma.last().is_none_or(|&g| g < 180.0 - ANGLE_EPS) {
            gamma.push(180.0);
        }
        let n = gamma.len();
        gamma[0] = 0.0;
        gamma[n - 1] = 180.0;
        for i in 1..n {
            if !gamma[i].is_finite() || gamma[i] <= gamma[i - 1] {
                return Err(bad(
                    "gamma",
                    format!("angle #{} = {} is not ascending in [0, 180]", i + 1, gamma[i]),
                ));
            }
        }
        if n < 3 {
            return Err(bad("gamma", "a solid needs at least one γ between the poles".into()));
        }
        Ok(Self { c, gamma })
    }

    /// A uniform grid: `n_c` C angles 360/n_c apart from C = 0, and
    /// `gamma_steps` equal γ steps from 0 to 180 (`gamma_steps + 1` angles).
    pub fn uniform(n_c: usize, gamma_steps: usize) -> Result<Self, ModelError> {
        let c = (0..n_c).map(|k| k as f64 * 360.0 / n_c as f64).collect();
        let gamma = (0..=gamma_steps)
            .map(|k| k as f64 * 180.0 / gamma_steps.max(1) as f64)
            .collect();
        Self::new(c, gamma)
    }

    /// The grid of a measured distribution refined `factor` times (the CLI's
    /// `--factor`): every interval between the file's own C-planes (all
    /// full-circle images, so non-uniform grids keep their knots) and γ
    /// angles is cut into `factor` equal steps, and the poles are added when
    /// the γ range is partial. A distribution with fewer than 4 full-circle
    /// planes (rotational, single plane) gets 72 planes (5°) before refining.
    ///
    /// # Errors
    /// [`ModelError::Parameter`] when `factor` is 0 or the grid would exceed
    /// [`MAX_GRID_POINTS`] (checked before anything is allocated).
    pub fn refined(d: &Distribution, factor: usize) -> Result<Self, ModelError> {
        if factor == 0 {
            return Err(ModelError::Parameter {
                name: "factor",
                value: "0".into(),
                reason: "must be at least 1".into(),
            });
        }
        let mut knots: Vec<f64> = d.full_planes().iter().map(|p| p.0).collect();
        if knots.len() < 4 {
            knots = (0..72).map(|k| k as f64 * 5.0).collect();
        }
        let mut g_count = d.gamma_angles_deg().len() + 1;
        g_count += usize::from(d.gamma_angles_deg()[0] > ANGLE_EPS)
            + usize::from(d.gamma_angles_deg().last().is_some_and(|&l| l < 180.0 - ANGLE_EPS));
        let points = (knots.len() as u128) * (factor as u128) * (g_count as u128) * (factor as u128);
        if points > MAX_GRID_POINTS as u128 {
            return Err(ModelError::Parameter {
                name: "factor",
                value: factor.to_string(),
                reason: format!(
                    "the refined grid would hold about {points} points ({} C-planes x {} gamma angles, each x {factor}); \
                     at most {MAX_GRID_POINTS} are allowed",
                    knots.len(),
                    g_count
                ),
            });
        }
        let mut c = Vec::with_capacity(knots.len() * factor);
        for (i, &a) in knots.iter().enumerate() {
            let b = if i + 1 == knots.len() {
                knots[0] + 360.0
            } else {
                knots[i + 1]
            };
            for k in 0..factor {
                c.push(a + (b - a) * k as f64 / factor as f64);
            }
        }
        let mut g_knots = d.gamma_angles_deg().to_vec();
        if g_knots[0] > ANGLE_EPS {
            g_knots.insert(0, 0.0);
        }
        if g_knots[g_knots.len() - 1] < 180.0 - ANGLE_EPS {
            g_knots.push(180.0);
        }
        let mut gamma = Vec::with_capacity(g_knots.len() * factor);
        for w in g_knots.windows(2) {
            for k in 0..factor {
                gamma.push(w[0] + (w[1] - w[0]) * k as f64 / factor as f64);
            }
        }
        gamma.push(180.0);
        Self::new(c, gamma)
    }

    /// C angles (degrees), ascending in [0, 360).
    pub fn c_angles_deg(&self) -> &[f64] {
        &self.c
    }
    /// γ angles (degrees), from 0 to 180.
    pub fn gamma_angles_deg(&self) -> &[f64] {
        &self.gamma
    }
    /// Vertices of the solid when nothing is zero: C x inner γ + 2 poles.
    pub fn max_vertices(&self) -> usize {
        self.c.len() * (self.gamma.len() - 2) + 2
    }
}

/// The solid of `d`'s texture rendered with `filter` at `factor` (texel
/// centres as vertices, as the GPU path produces it), in `units`.
///
/// # Errors
/// The texture's and the render's errors (an empty distribution, a factor
/// outside 1..=32), then [`grid_solid`]'s.
pub fn texture_solid(
    d: &Distribution,
    filter: crate::reconstruct::Filter,
    factor: u32,
    units: Units,
) -> Result<Mesh, ModelError> {
    let tex = crate::reconstruct::LightTexture::new(d)?;
    let rendered = crate::reconstruct::render(&tex, filter, factor)?;
    grid_solid(&rendered, &SolidGrid::of_texture(&rendered)?, units)
}

/// Build the solid of `field` on `grid`, in `units` ([`Units::Peak`]
/// normalises by the largest sample), with per-vertex normals.
///
/// # Errors
/// [`ModelError::AllZero`] when every sample is ≤ 0; [`ModelError::Intensities`]
/// for a NaN sample or coordinates too large for f32.
///
/// # Allocations
/// One sample buffer (8 bytes per grid point), one index map (4 bytes per
/// grid point), and the mesh's vectors, each allocated once at its final size bound.
pub fn grid_solid(field: &dyn IntensityField, grid: &SolidGrid, units: Units) -> Result<Mesh, ModelError> {
    let (nc, ng) = (grid.c.len(), grid.gamma.len());
    let GridRadii {
        radii: s,
        r_nadir,
        r_zenith,
        scale,
        any_zero,
    } = grid_radii(field, grid, units)?;
    let (sin_c, cos_c): (Vec<f64>, Vec<f64>) = grid.c.iter().map(|c| c.to_radians().sin_cos()).unzip();
    let (sin_g, cos_g): (Vec<f64>, Vec<f64>) = grid.gamma.iter().map(|g| g.to_radians().sin_cos()).unzip();

    let mut positions: Vec<[f32; 3]> = Vec::with_capacity(grid.max_vertices() + 1);
    let origin = any_zero.then(|| {
        positions.push([0.0; 3]);
        0u32
    });
    let o = origin.unwrap_or(u32::MAX);
    let mut push = |r: f64, sg: f64, cg: f64, sc: f64, cc: f64| -> u32 {
        if r == 0.0 {
            return o;
        }
        positions.push(vertex(r, sg, cg, sc, cc));
        (positions.len() - 1) as u32
    };
    let nadir_id = push(r_nadir, 0.0, 1.0, 0.0, 1.0);
    // Index map for the inner rings, C-major like the samples.
    let mut idx = vec![0u32; nc * ng];
    for ic in 0..nc {
        for ig in 1..ng - 1 {
            idx[ic * ng + ig] = push(s[ic * ng + ig], sin_g[ig], cos_g[ig], sin_c[ic], cos_c[ic]);
        }
    }
    let zenith_id = push(r_zenith, 0.0, -1.0, 0.0, 1.0);
    for ic in 0..nc {
        idx[ic * ng] = nadir_id;
        idx[ic * ng + ng - 1] = zenith_id;
    }

    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(2 * nc * (ng - 1));
    for ic in 0..nc {
        let ic1 = if ic + 1 == nc { 0 } else { ic + 1 };
        for ig in 0..ng - 1 {
            let ids = [
                idx[ic * ng + ig],
                idx[ic1 * ng + ig],
                idx[ic1 * ng + ig + 1],
                idx[ic * ng + ig + 1],
            ];
            let corners = ids.map(|i| positions[i as usize]);
            for t in quad_split(&corners, &ids).into_iter().flatten() {
                triangles.push(t.map(|k| ids[k]));
            }
        }
    }
    let info = SolidInfo {
        kind: format!(
            "grid solid of {} ({} C x {} gamma angles, poles single vertices)",
            field.name(),
            nc,
            ng
        ),
        source: String::new(),
        units,
        units_per_cd: scale,
    };
    Mesh::finish(positions, triangles, origin, info)
}

/// The vertex radii of a grid solid, in output units, as [`grid_solid`] places them.
pub(crate) struct GridRadii {
    /// C-major (`ic * n_gamma + ig`) radii of the inner rows; the pole rows are unused.
    pub radii: Vec<f64>,
    /// The nadir vertex's radius: the C-weighted mean of the field at γ = 0.
    pub r_nadir: f64,
    /// The zenith vertex's radius: the same at γ = 180.
    pub r_zenith: f64,
    /// Output units per cd.
    pub scale: f64,
    /// Whether any radius is zero (the merged origin vertex exists).
    pub any_zero: bool,
}

/// Sample `field` on `grid` and turn the samples into stored radii (poles
/// averaged over C, zero below [`super::ZERO_FRACTION`] of the peak).
///
/// # Errors
/// As [`grid_solid`].
pub(crate) fn grid_radii(field: &dyn IntensityField, grid: &SolidGrid, units: Units) -> Result<GridRadii, ModelError> {
    let (nc, ng) = (grid.c.len(), grid.gamma.len());
    let mut s = vec![0.0f64; nc * ng];
    field.sample_grid(&grid.c, &grid.gamma, &mut s);
    // Poles: one value each, the C-weighted mean of the samples there.
    let widths = periodic_widths(&grid.c);
    let pole = |ig: usize| -> f64 { (0..nc).map(|ic| s[ic * ng + ig] * widths[ic]).sum::<f64>() / 360.0 };
    let (nadir, zenith) = (pole(0), pole(ng - 1));
    let mut peak = nadir.max(zenith);
    for ic in 0..nc {
        for &v in &s[ic * ng + 1..ic * ng + ng - 1] {
            if v.is_nan() {
                return Err(ModelError::Intensities("the field returned NaN".into()));
            }
            peak = peak.max(v);
        }
    }
    if peak.is_nan() {
        return Err(ModelError::Intensities("the field returned NaN at a pole".into()));
    }
    if peak <= 0.0 {
        return Err(ModelError::AllZero("photometric solid"));
    }
    let scale = units.units_per_cd(peak)?;
    // Radii in output units; zero means "at the origin".
    let r_nadir = stored_radius(nadir * scale, peak * scale)?;
    let r_zenith = stored_radius(zenith * scale, peak * scale)?;
    let mut any_zero = r_nadir == 0.0 || r_zenith == 0.0;
    for ic in 0..nc {
        for ig in 1..ng - 1 {
            let r = stored_radius(s[ic * ng + ig] * scale, peak * scale)?;
            s[ic * ng + ig] = r;
            any_zero |= r == 0.0;
        }
    }
    Ok(GridRadii {
        radii: s,
        r_nadir,
        r_zenith,
        scale,
        any_zero,
    })
}

/// The f32 vertex at radius `r` in the direction given by the sines and cosines of γ and C.
#[inline]
pub(crate) fn vertex(r: f64, sin_g: f64, cos_g: f64, sin_c: f64, cos_c: f64) -> [f32; 3] {
    [
        (r * sin_g * cos_c) as f32,
        (r * sin_g * sin_c) as f32,
        (-r * cos_g) as f32,
    ]
}

/// The two triangles of a grid quad with corners (C, γ), (C+1, γ), (C+1,
/// γ+1), (C, γ+1) (`corners` and their vertex ids `ids`), as corner
/// numbers 0..4; `None` for a triangle that collapses (two corners are one
/// vertex). The quad is split along (C, γ)–(C+1, γ+1) unless that split has
/// a zero-area triangle and the other does not. Outward winding: ∂d/∂C ×
/// ∂d/∂γ points outwards, so (C, γ) → (C+1, γ) → (C+1, γ+1) is
/// counter-clockwise seen from outside.
pub(crate) fn quad_split(corners: &[[f32; 3]; 4], ids: &[u32; 4]) -> [Option<[usize; 3]>; 2] {
    let distinct = |t: &[usize; 3]| ids[t[0]] != ids[t[1]] && ids[t[1]] != ids[t[2]] && ids[t[0]] != ids[t[2]];
    let zero_area = |t: &[usize; 3]| {
        let (a, b, c) = (p64(&corners[t[0]]), p64(&corners[t[1]]), p64(&corners[t[2]]));
        (b - a).cross(c - a) == glam::DVec3::ZERO
    };
    let bad = |p: &[[usize; 3]; 2]| p.iter().any(|t| distinct(t) && zero_area(t));
    let mut pair = [[0, 1, 2], [0, 2, 3]];
    if bad(&pair) {
        let other = [[0, 1, 3], [1, 2, 3]];
        if !bad(&other) {
            pair = other;
        }
    }
    pair.map(|t| distinct(&t).then_some(t))
}

impl SolidGrid {
    /// The texel centres of a rendered texture (plus the poles): a solid on
    /// this grid has one vertex per texel, at exactly the texel's value. A
    /// texture narrower than 72 columns (rotational data stores one plane,
    /// so its render is only `factor` columns wide) gets 72 evenly spaced
    /// columns instead, sampled between its texels.
    pub fn of_texture(t: &crate::reconstruct::Rendered) -> Result<Self, ModelError> {
        let c = if t.mapping.width >= 72 {
            (0..t.mapping.width).map(|j| t.mapping.c_of_column(j)).collect()
        } else {
            (0..72).map(|j| j as f64 * 5.0).collect()
        };
        let g = (0..t.mapping.height).map(|i| t.mapping.gamma_of_row(i)).collect();
        SolidGrid::new(c, g)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn isotropic_sphere_closed_and_close() {
        let grid = SolidGrid::uniform(72, 36).unwrap();
        let m = grid_solid(&|_c: f64, _g: f64| 2.0, &grid, Units::Candela).unwrap();
        let r = m.sanity_check().unwrap();
        assert_eq!(m.n_vertices(), 72 * 35 + 2);
        assert_eq!((r.euler_characteristic, r.components, r.origin_sheets), (2, 1, 0));
        let exact = 4.0 / 3.0 * PI * 8.0;
        assert!((r.volume - exact).abs() / exact < 5e-3, "{}", r.volume);
    }

    #[test]
    fn refined_grid_keeps_knots_and_adds_poles() {
        let d = Distribution::new(
            vec![0.0, 30.0, 90.0],
            vec![0.0, 45.0, 90.0],
            vec![1.0; 9],
            crate::model::Symmetry::Quadrant,
        )
        .unwrap();
        let g = SolidGrid::refined(&d, 2).unwrap();
        assert_eq!(&g.c_angles_deg()[..5], &[0.0, 15.0, 30.0, 60.0, 90.0]);
        assert_eq!(g.gamma_angles_deg(), &[0.0, 22.5, 45.0, 67.5, 90.0, 135.0, 180.0]);
        assert!(SolidGrid::new(vec![0.0, 180.0], vec![90.0]).is_err());
        assert!(SolidGrid::new(vec![0.0, 10.0, 20.0], vec![90.0]).is_err());
    }
}
