//! The light distribution texture (Wallner 2008, §4) and its render.
//!
//! # Storage
//! A [`LightTexture`] holds the intensities of a [`Distribution`] divided by
//! I_max (f32, what a GPU samples) and in candela (f64, the reference), with
//! I_max kept beside them. It stores only what the data needs:
//! - C: the distribution's stored planes (one for rotational symmetry, a
//!   quadrant for Isym 4, a half for Isym 2/3). Lookups go through the
//!   full-circle plane list ([`Distribution::full_planes`]), whose entries name
//!   the stored column, so they give the same values as the expanded grid.
//! - γ: the rows from two before the first to two after the last row holding a
//!   non-zero value (so a hemisphere when the other one is empty). Two rows of
//!   margin keep every 4-tap support that touches data inside the stored band,
//!   so cropping changes no value.
//!
//! Each column is padded with one ghost row at each end (a "padded column"
//! of `gamma.len() + 2` rows; row 0 and the last row are the ghosts):
//! - at a measured pole (γ = 0 or 180): the value across the pole,
//!   `I(C, −γ₁) = I(C + 180, γ₁)` and `I(C, 180 + δ) = I(C + 180, 180 − δ)`, so
//!   cubics are continuous through nadir and zenith. When C + 180 is not
//!   itself a full-circle plane (non-uniform grids), the ghost value is
//!   interpolated **linearly in C** between the two neighbouring planes:
//!   bounded, never overshooting, and it only shapes the first interval.
//! - at a band edge that is not a pole (e.g. 0–90 data ending at 90): the
//!   linear extrapolation `2p₀ − p₁` at knot `2t₀ − t₁`. Catmull–Rom then
//!   uses the one-sided secant slope at the edge, the B-spline passes through
//!   the end value, and 2-knot axes degrade to exactly linear. PCHIP's end
//!   slope is the secant of the first interval (SciPy uses a three-point end
//!   formula there; the interior is identical). Beyond the band the result
//!   is 0: no tap reaches past the ghost, so there is no ringing outside.
//! - at a cropped edge: the next measured (zero) row, value 0.
//!
//! Pole values are first averaged over the circle
//! ([`Distribution::with_averaged_poles`]), so the value at a pole does not
//! depend on C; files whose pole values agree across planes are unchanged.
//! This makes every interpolating filter single-valued at the poles.
//! Approximating filters (mitchell, bspline) blend the pole row with the
//! first row and its ghost there, `k(0)·p₀ + k(1)·(I(C, γ₁) + I(C+180, γ₁))`:
//! continuous along every meridian through the pole on grids closed under
//! C + 180 (every uniform grid), but the pole value itself may vary with C by
//! up to k(1) = 1/18 (Mitchell) or 1/6 (B-spline) of the spread of row γ₁.
//!
//! # Texel centres of a render
//! A render of height H and width W covers γ 0–180 and C 0–360 with texel
//! (row i, column j) centred at `γ = (i + ½)·180/H`, `C = (j + ½)·360/W`
//! (degrees). In Wallner's texture coordinates, `s = γ/180 = arccos(n·d)/π`
//! and `t = C/360 = atan2(d·v, d·u)/2π mod 1` with n = −z (γ = 0), u = +x
//! (C0), v = +y (C90): texel row `floor(s·H)`, column `floor(t·W)`.

use rayon::prelude::*;

use crate::error::ModelError;
use crate::model::{Distribution, Symmetry, ANGLE_EPS};

use super::axis::{Axis, AxisKind, AxisTaps, Tap};
use super::filter::{combine, Filter};

/// What one end of the stored γ band continues with (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GhostKind {
    /// A measured pole: the ghost is the value across the pole (plane C + 180).
    Pole,
    /// The end of the measured band: linear extrapolation of the last two rows.
    Edge,
    /// Rows of zeros were cropped: the ghost is the next (zero) row.
    Cropped,
    /// A single γ row: no neighbours at all.
    Single,
}

/// A light distribution texture: intensities over (γ, C) normalised by I_max.
#[derive(Debug, Clone, PartialEq)]
pub struct LightTexture {
    i_max_cd: f64,
    symmetry: Symmetry,
    measured_gamma: (f64, f64),
    n_measured_gamma: usize,
    /// Stored C-plane angles (degrees), one per column.
    columns: Vec<f64>,
    /// Stored γ rows (degrees), without ghosts.
    gamma: Vec<f64>,
    ghosts: (GhostKind, GhostKind),
    /// Padded rows per column: `gamma.len() + 2`.
    rows: usize,
    cd: Vec<f64>,
    norm: Vec<f32>,
    gamma_axis: Axis,
    c_axis: Axis,
}

/// Largest render the library will allocate, in texels (1 GiB of f32).
pub const MAX_RENDER_TEXELS: usize = 1 << 28;

/// The default oversampling factor of a render (Wallner renders a five times larger texture).
pub const DEFAULT_FACTOR: u32 = 5;

/// The γ rows (indices into the distribution's angles) a texture keeps: the
/// non-zero rows and two more on each side (within the measured band), so
/// the widest kernel sees the zeros beyond a cut-off.
fn kept_rows(d: &Distribution) -> (usize, usize) {
    let ng = d.gamma_angles_deg().len();
    let nonzero = |ig: usize| (0..d.n_c()).any(|ic| d.value_cd(ic, ig) != 0.0);
    // I_max > 0, so some row is non-zero (the defaults are never taken).
    let first = (0..ng).find(|&ig| nonzero(ig)).unwrap_or(0);
    let last = (0..ng).rev().find(|&ig| nonzero(ig)).unwrap_or(ng - 1);
    (first.saturating_sub(2), (last + 2).min(ng - 1))
}

/// What continues the kept rows `lo..=hi` of the measured angles `g`
/// (degrees) below and above: each ghost row's kind and its knot (γ, degrees).
fn ghosts(g: &[f64], lo: usize, hi: usize) -> ((GhostKind, f64), (GhostKind, f64)) {
    let ng = g.len();
    let lo_kind = if lo > 0 {
        GhostKind::Cropped
    } else if ng == 1 {
        GhostKind::Single
    } else if g[0] <= ANGLE_EPS {
        GhostKind::Pole
    } else {
        GhostKind::Edge
    };
    let hi_kind = if hi < ng - 1 {
        GhostKind::Cropped
    } else if ng == 1 {
        GhostKind::Single
    } else if g[ng - 1] >= 180.0 - ANGLE_EPS {
        GhostKind::Pole
    } else {
        GhostKind::Edge
    };
    let lo_knot = match lo_kind {
        GhostKind::Cropped => g[lo - 1],
        GhostKind::Single => g[0] - 1.0,
        GhostKind::Pole => -g[1],
        GhostKind::Edge => 2.0 * g[0] - g[1],
    };
    let hi_knot = match hi_kind {
        GhostKind::Cropped => g[hi + 1],
        GhostKind::Single => g[0] + 1.0,
        GhostKind::Pole => 360.0 - g[ng - 2],
        GhostKind::Edge => 2.0 * g[ng - 1] - g[ng - 2],
    };
    ((lo_kind, lo_knot), (hi_kind, hi_knot))
}

/// Linear interpolation in C (degrees) of row `ig` between the full-circle planes around `c`.
fn linear_in_c(d: &Distribution, full: &[(f64, usize)], c: f64, ig: usize) -> f64 {
    let n = full.len();
    if n == 1 {
        return d.value_cd(full[0].1, ig);
    }
    let c = crate::model::wrap360(c);
    let i = full.partition_point(|p| p.0 <= c + ANGLE_EPS) as isize - 1;
    let (a, ia) = if i < 0 {
        (full[n - 1].0 - 360.0, full[n - 1].1)
    } else {
        (full[i as usize].0, full[i as usize].1)
    };
    if (c - a).abs() <= ANGLE_EPS {
        return d.value_cd(ia, ig);
    }
    let (b, ib) = if (i + 1) as usize >= n {
        (full[0].0 + 360.0, full[0].1)
    } else {
        (full[(i + 1) as usize].0, full[(i + 1) as usize].1)
    };
    let f = (c - a) / (b - a);
    (1.0 - f) * d.value_cd(ia, ig) + f * d.value_cd(ib, ig)
}

impl LightTexture {
    /// Build the texture of `dist` (see the module docs for what is stored).
    ///
    /// # Errors
    /// [`ModelError::AllZero`] when no intensity is positive (I_max would be 0).
    pub fn new(dist: &Distribution) -> Result<Self, ModelError> {
        let d = dist.with_averaged_poles();
        let i_max_cd = d.max_cd();
        // Values are finite (a Distribution invariant), so I_max is never NaN.
        if i_max_cd <= 0.0 {
            return Err(ModelError::AllZero(
                "a light distribution texture is normalised by I_max, which must be positive",
            ));
        }
        let g = d.gamma_angles_deg();
        let ng = g.len();
        let (lo, hi) = kept_rows(&d);
        let gamma = g[lo..=hi].to_vec();
        let rows = gamma.len() + 2;
        let full = d.full_planes();
        let columns = d.c_angles_deg().to_vec();
        let ((lo_kind, lo_knot), (hi_kind, hi_knot)) = ghosts(g, lo, hi);

        let mut cd = Vec::with_capacity(columns.len() * rows);
        for (ic, &c) in columns.iter().enumerate() {
            let plane = d.plane_cd(ic);
            cd.push(match lo_kind {
                GhostKind::Cropped => 0.0,
                GhostKind::Single => plane[0],
                GhostKind::Pole => linear_in_c(&d, &full, c + 180.0, 1),
                GhostKind::Edge => 2.0 * plane[0] - plane[1],
            });
            cd.extend_from_slice(&plane[lo..=hi]);
            cd.push(match hi_kind {
                GhostKind::Cropped => 0.0,
                GhostKind::Single => plane[0],
                GhostKind::Pole => linear_in_c(&d, &full, c + 180.0, ng - 2),
                GhostKind::Edge => 2.0 * plane[ng - 1] - plane[ng - 2],
            });
        }
        let norm = cd.iter().map(|&v| (v / i_max_cd) as f32).collect();
        let gamma_axis = Axis {
            store: (1..=gamma.len() as u32).collect(),
            knots: gamma.clone(),
            kind: AxisKind::Band {
                lo: (lo_knot, 0),
                hi: (hi_knot, rows as u32 - 1),
            },
        };
        let c_axis = Axis {
            knots: full.iter().map(|p| p.0).collect(),
            store: full.iter().map(|p| p.1 as u32).collect(),
            kind: AxisKind::Periodic,
        };
        Ok(LightTexture {
            i_max_cd,
            symmetry: d.symmetry(),
            measured_gamma: (g[0], g[ng - 1]),
            n_measured_gamma: ng,
            columns,
            gamma,
            ghosts: (lo_kind, hi_kind),
            rows,
            cd,
            norm,
            gamma_axis,
            c_axis,
        })
    }

    /// Bytes held: the candela and normalised grids and both axis tables.
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.cd.len() * 8
            + self.norm.len() * 4
            + (self.columns.len() + self.gamma.len()) * 8
            + self.gamma_axis.bytes()
            + self.c_axis.bytes()
    }

    /// The largest intensity (cd) the normalised values are divided by.
    pub fn i_max_cd(&self) -> f64 {
        self.i_max_cd
    }
    /// The symmetry of the stored columns.
    pub fn symmetry(&self) -> Symmetry {
        self.symmetry
    }
    /// The measured γ band (degrees): outside it every lookup is 0.
    pub fn measured_gamma(&self) -> (f64, f64) {
        self.measured_gamma
    }
    /// Stored C-plane angles (degrees), one per column.
    pub fn columns(&self) -> &[f64] {
        &self.columns
    }
    /// Stored γ rows (degrees), without the ghost rows.
    pub fn gamma_rows(&self) -> &[f64] {
        &self.gamma
    }
    /// The smallest spacing (degrees) between two stored γ rows or two
    /// full-circle C-planes; `None` with a single row and a single plane.
    pub fn knot_spacing_deg(&self) -> Option<f64> {
        let c = &self.c_axis.knots;
        let seam = (c.len() > 1).then(|| c[0] + 360.0 - c[c.len() - 1]);
        self.gamma
            .windows(2)
            .chain(c.windows(2))
            .map(|w| w[1] - w[0])
            .chain(seam)
            .filter(|&s| s > 0.0)
            .min_by(f64::total_cmp)
    }
    /// What the stored band continues with below and above.
    pub fn ghosts(&self) -> (GhostKind, GhostKind) {
        self.ghosts
    }
    /// Padded rows per column (stored rows + 2 ghosts).
    pub fn rows_per_column(&self) -> usize {
        self.rows
    }
    /// Stored texture as (rows, columns) without ghosts: 1 column for rotational symmetry.
    pub fn stored_size(&self) -> (usize, usize) {
        (self.gamma.len(), self.columns.len())
    }
    /// The padded normalised texture (I / I_max, f32), column-major:
    /// `normalized()[col * rows_per_column() + padded_row]`.
    pub fn normalized(&self) -> &[f32] {
        &self.norm
    }
    /// The padded texture in cd (f64), same layout as [`LightTexture::normalized`].
    pub fn candela(&self) -> &[f64] {
        &self.cd
    }
    /// Full-circle C-planes (degrees, ascending in [0, 360)) and the stored column of each.
    pub fn full_circle(&self) -> impl Iterator<Item = (f64, u32)> + '_ {
        self.c_axis.knots.iter().copied().zip(self.c_axis.store.iter().copied())
    }

    /// Tap rows for one query (C, γ in degrees).
    pub(crate) fn taps(&self, filter: Filter, c: f64, gamma: f64) -> Option<(Tap, Tap)> {
        let gt = self.gamma_axis.tap(filter, gamma);
        if gt.weight == [0.0; 4] {
            return None;
        }
        Some((gt, self.c_axis.tap(filter, c)))
    }

    /// Unclamped reconstruction in cd at (C, γ) degrees, f64 throughout
    /// (tensor order: γ within each of the four C-tap columns, then C).
    pub(crate) fn eval_cd(&self, filter: Filter, c: f64, gamma: f64) -> f64 {
        let Some((gt, ct)) = self.taps(filter, c, gamma) else {
            return 0.0;
        };
        self.eval_taps_cd(filter, &gt, &ct)
    }

    /// Unclamped reconstruction in cd at every (C, γ) of `c_deg` × `gamma_deg`
    /// (degrees), C-major (`out[i * gamma_deg.len() + j]` at `c_deg[i]`, `gamma_deg[j]`):
    /// the same numbers as [`LightTexture::eval_cd`] at each pair, with each axis's
    /// taps found once per position instead of once per pair.
    pub(crate) fn eval_grid_cd(&self, filter: Filter, c_deg: &[f64], gamma_deg: &[f64]) -> Vec<f64> {
        let gamma_taps: Vec<Tap> = gamma_deg.iter().map(|&g| self.gamma_axis.tap(filter, g)).collect();
        let mut out = Vec::with_capacity(c_deg.len() * gamma_deg.len());
        for &c in c_deg {
            let ct = self.c_axis.tap(filter, c);
            out.extend(gamma_taps.iter().map(|gt| {
                if gt.weight == [0.0; 4] {
                    0.0
                } else {
                    self.eval_taps_cd(filter, gt, &ct)
                }
            }));
        }
        out
    }

    /// Unclamped reconstruction in cd from a γ tap row and a C tap row.
    #[inline]
    fn eval_taps_cd(&self, filter: Filter, gt: &Tap, ct: &Tap) -> f64 {
        let pchip = filter.is_data_dependent();
        let mut v = [0.0; 4];
        for (k, vk) in v.iter_mut().enumerate() {
            let col = &self.cd[ct.index[k] as usize * self.rows..][..self.rows];
            *vk = combine(pchip, gt.index.map(|r| col[r as usize]), gt.weight);
        }
        combine(pchip, v, ct.weight)
    }

    /// Default render size (rows, columns) before the factor: rows = the
    /// number of mean measured γ steps in 180° (at least 1), columns = the
    /// number of full-circle planes.
    pub fn base_size(&self) -> (usize, usize) {
        let (a, b) = self.measured_gamma;
        let rows = if self.n_measured_gamma >= 2 && b > a {
            ((180.0 * (self.n_measured_gamma - 1) as f64 / (b - a)).round() as usize).max(1)
        } else {
            1
        };
        (rows, self.c_axis.knots.len())
    }

    /// The tap tables of a render: what the CPU render below and the GPU shader both consume.
    ///
    /// # Errors
    /// [`ModelError::Parameter`] when `factor` is outside 1–32 or the render
    /// would exceed [`MAX_RENDER_TEXELS`].
    pub fn render_plan(&self, filter: Filter, factor: u32) -> Result<RenderPlan, ModelError> {
        if !(1..=32).contains(&factor) {
            return Err(ModelError::Parameter {
                name: "factor",
                value: factor.to_string(),
                reason: "must be an integer from 1 to 32".into(),
            });
        }
        let (r, c) = self.base_size();
        let (height, width) = (r * factor as usize, c * factor as usize);
        if height.saturating_mul(width) > MAX_RENDER_TEXELS {
            return Err(ModelError::Parameter {
                name: "factor",
                value: factor.to_string(),
                reason: format!("a {height} x {width} render exceeds {MAX_RENDER_TEXELS} texels"),
            });
        }
        let mapping = TexelMapping { height, width };
        Ok(RenderPlan {
            filter,
            factor,
            mapping,
            rows_per_column: self.rows,
            columns: self.columns.len(),
            gamma: self
                .gamma_axis
                .table(filter, (0..height).map(|i| mapping.gamma_of_row(i)).collect()),
            c: self
                .c_axis
                .table(filter, (0..width).map(|j| mapping.c_of_column(j)).collect()),
        })
    }
}

/// Where the texels of a render lie (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct TexelMapping {
    /// Rows (γ direction).
    pub height: usize,
    /// Columns (C direction).
    pub width: usize,
}

impl TexelMapping {
    /// The mapping in words, as stored in file metadata.
    pub const DESCRIPTION: &'static str = "row i centre gamma = (i + 0.5) * 180 / height deg, column j centre C = \
         (j + 0.5) * 360 / width deg; s = gamma / 180 = acos(n.d) / pi, t = C / 360 = atan2(d.v, d.u) / 2pi mod 1; \
         n = -z (gamma 0), u = +x (C0), v = +y (C90); d = (sin g cos C, sin g sin C, -cos g)";
    /// Handedness of the C angle, as stored in file metadata.
    pub const HANDEDNESS: &'static str = "right-handed, z up, C counter-clockwise seen from above (C0 = +x, C90 = +y)";

    /// γ (degrees) at the centre of row `i`.
    pub fn gamma_of_row(&self, i: usize) -> f64 {
        (i as f64 + 0.5) * 180.0 / self.height as f64
    }
    /// C (degrees) at the centre of column `j`.
    pub fn c_of_column(&self, j: usize) -> f64 {
        (j as f64 + 0.5) * 360.0 / self.width as f64
    }
}

/// Everything a render needs besides the texture: sizes and the two tap tables.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderPlan {
    /// The filter of both tables.
    pub filter: Filter,
    /// Oversampling factor (1–32).
    pub factor: u32,
    /// Output size and texel centres.
    pub mapping: TexelMapping,
    /// Padded rows per texture column (the γ table's indices are padded rows).
    pub rows_per_column: usize,
    /// Texture columns (the C table's indices are columns).
    pub columns: usize,
    /// One entry per output row.
    pub gamma: AxisTaps,
    /// One entry per output column.
    pub c: AxisTaps,
}

/// A rendered texture: f32 intensities normalised by I_max, row-major (rows = γ).
#[derive(Debug, Clone, PartialEq)]
pub struct Rendered {
    /// `data[i * width + j]` is texel (row i, column j), dimensionless (I / I_max).
    pub data: Vec<f32>,
    /// Size and texel centres.
    pub mapping: TexelMapping,
    /// I_max (cd): multiply a texel by it to get candela.
    pub i_max_cd: f64,
    /// The filter used.
    pub filter: Filter,
    /// The oversampling factor used.
    pub factor: u32,
    /// The measured γ band (degrees); texels outside it are 0.
    pub measured_gamma: (f64, f64),
    /// Texels whose cubic overshoot below 0 was clamped to 0 (0 when unclamped).
    pub clamped: usize,
}

/// How to render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Reconstruction filter. Default: Catmull–Rom.
    pub filter: Filter,
    /// Oversampling factor in both axes, 1–32. Default: [`DEFAULT_FACTOR`] (5).
    pub factor: u32,
    /// Clamp negative results to 0 (and count them). Default: true.
    pub clamp: bool,
    /// Render rows in parallel with rayon. Default: true.
    pub parallel: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            filter: Filter::CatmullRom,
            factor: DEFAULT_FACTOR,
            clamp: true,
            parallel: true,
        }
    }
}

/// Render `texture` with `filter` into a texture `factor` times denser than
/// [`LightTexture::base_size`] in both axes (clamped, in parallel).
///
/// # Errors
/// As [`LightTexture::render_plan`].
pub fn render(texture: &LightTexture, filter: Filter, factor: u32) -> Result<Rendered, ModelError> {
    render_with(
        texture,
        &RenderOptions {
            filter,
            factor,
            ..RenderOptions::default()
        },
    )
}

/// [`render`] with every option.
///
/// Separable: each output row first reconstructs one value per texture
/// column along γ (the γ table), then each texel combines four of them along
/// C (the C table), all in f32. No allocation per texel; one row buffer per
/// worker.
///
/// # Errors
/// As [`LightTexture::render_plan`].
pub fn render_with(texture: &LightTexture, options: &RenderOptions) -> Result<Rendered, ModelError> {
    let plan = texture.render_plan(options.filter, options.factor)?;
    Ok(render_planned(texture, &plan, options.clamp, options.parallel))
}

/// [`render_with`] from a [`RenderPlan`] built beforehand by
/// [`LightTexture::render_plan`] on the same texture: the CPU side of a
/// comparison with the GPU render of the same plan (`photosolid::gpu`).
///
/// # Panics
/// When `plan` was built for a texture of another layout (rows per column or
/// column count differ).
pub fn render_planned(texture: &LightTexture, plan: &RenderPlan, clamp: bool, parallel: bool) -> Rendered {
    assert!(
        plan.rows_per_column == texture.rows && plan.columns == texture.columns.len(),
        "render plan built for another texture layout"
    );
    let (h, w) = (plan.mapping.height, plan.mapping.width);
    let mut data = vec![0f32; h * w];
    let row_job =
        |tmp: &mut Vec<f32>, (i, out): (usize, &mut [f32])| -> usize { render_row(texture, plan, clamp, i, tmp, out) };
    let clamped = if parallel {
        data.par_chunks_mut(w)
            .enumerate()
            .map_init(|| vec![0f32; plan.columns], row_job)
            .sum()
    } else {
        let mut tmp = vec![0f32; plan.columns];
        data.chunks_mut(w).enumerate().map(|r| row_job(&mut tmp, r)).sum()
    };
    Rendered {
        data,
        mapping: plan.mapping,
        i_max_cd: texture.i_max_cd,
        filter: plan.filter,
        factor: plan.factor,
        measured_gamma: texture.measured_gamma,
        clamped,
    }
}

/// One output row; returns how many texels were clamped.
fn render_row(tex: &LightTexture, plan: &RenderPlan, clamp: bool, i: usize, tmp: &mut [f32], out: &mut [f32]) -> usize {
    let gw = plan.gamma.weight[i];
    if gw == [0.0; 4] {
        // Outside the measured band (or outside the stored rows): all zero.
        out.fill(0.0);
        return 0;
    }
    let gi = plan.gamma.index[i].map(|r| r as usize);
    let rows = plan.rows_per_column;
    let mut clamped = 0;
    if plan.filter.is_data_dependent() {
        for (col, t) in tmp.iter_mut().enumerate() {
            let c = &tex.norm[col * rows..][..rows];
            *t = combine(true, gi.map(|r| c[r]), gw);
        }
        for ((o, ci), cw) in out.iter_mut().zip(&plan.c.index).zip(&plan.c.weight) {
            let v = combine(true, ci.map(|k| tmp[k as usize]), *cw);
            *o = if clamp && v < 0.0 {
                clamped += 1;
                0.0
            } else {
                v
            };
        }
    } else {
        for (col, t) in tmp.iter_mut().enumerate() {
            let c = &tex.norm[col * rows..][..rows];
            *t = gw[0] * c[gi[0]] + gw[1] * c[gi[1]] + gw[2] * c[gi[2]] + gw[3] * c[gi[3]];
        }
        for ((o, ci), cw) in out.iter_mut().zip(&plan.c.index).zip(&plan.c.weight) {
            let v = cw[0] * tmp[ci[0] as usize]
                + cw[1] * tmp[ci[1] as usize]
                + cw[2] * tmp[ci[2] as usize]
                + cw[3] * tmp[ci[3] as usize];
            *o = if clamp && v < 0.0 {
                clamped += 1;
                0.0
            } else {
                v
            };
        }
    }
    clamped
}
