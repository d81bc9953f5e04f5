//! Lookups into a stored (rendered) texture, as a renderer's sampler does them.
//!
//! Wallner's pipeline renders the texture once with a good filter at a
//! factor k, then looks it up in the shader with the hardware's filter. The
//! lookup's error depends on k; these are those lookups, on the texel grid
//! of [`TexelMapping`](super::TexelMapping): row i centred at
//! γ = (i + ½)·180/H, column j at C = (j + ½)·360/W. C is periodic; rows are
//! clamped at the first and last texel (held towards the poles, as
//! `CLAMP_TO_EDGE` does). Values are clamped at 0 (Catmull–Rom overshoot).

use std::fmt;
use std::str::FromStr;

use serde::Serialize;

use super::filter::{Filter, Real};
use super::texture::Rendered;
use crate::error::ModelError;
use crate::model::{frame, wrap360, IntensityField, Symmetry};

/// How a stored texture is read back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Lookup {
    /// The texel the direction falls in (`GL_NEAREST`).
    Nearest,
    /// Bilinear between the four nearest texel centres (`GL_LINEAR`).
    Bilinear,
    /// Separable Catmull–Rom on the 4 x 4 nearest texel centres (a bicubic shader lookup).
    CatmullRom,
}

impl Lookup {
    /// Every lookup, cheapest first.
    pub const ALL: [Lookup; 3] = [Lookup::Nearest, Lookup::Bilinear, Lookup::CatmullRom];
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Lookup::Nearest => "nearest",
            Lookup::Bilinear => "bilinear",
            Lookup::CatmullRom => "catmull-rom",
        }
    }
}

impl fmt::Display for Lookup {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Lookup {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Lookup::ALL
            .into_iter()
            .find(|l| l.name() == s.trim())
            .ok_or_else(|| ModelError::Parameter {
                name: "lookup",
                value: s.to_string(),
                reason: "expected nearest, bilinear or catmull-rom".into(),
            })
    }
}

/// How a rendered texture is stored for the renderer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Precision {
    /// 32-bit floats (`R32F`).
    F32,
    /// 16-bit floats (`R16F`): values rounded to the nearest f16 (10-bit
    /// mantissa; I/I_max under 6.1e-5 become subnormal, under 3e-8 zero).
    F16,
    /// 16-bit unsigned normalised integers (`R16_UNORM`): each texel is
    /// rounded to the nearest of 65,535 steps of the texture's largest texel
    /// (one scale per texture; a step is at most 1.5e-5 of it).
    U16,
    /// 8-bit unsigned normalised integers (`R8_UNORM`): 255 steps of the
    /// largest texel (a step is 0.39 % of it; values under half a step become 0).
    U8,
    /// BC6H block compression (`BC6H_UF16`, feature `bc6h`): 16 bytes per
    /// 4 × 4 texels (1 byte per texel; edges padded to whole blocks), each
    /// block two half-float endpoints and 3- or 4-bit indices between them.
    /// Encoded by Intel's ISPC compressor, read back by an independent
    /// decoder (bcdec). As 1-D values ([`Precision::store`]) it rounds like
    /// f16 (its endpoints' precision); textures go through the blocks.
    Bc6h,
}

impl Precision {
    /// Bytes per stored value: 4 (f32), 2 (f16, u16) or 1 (u8).
    pub fn bytes(self) -> usize {
        match self {
            Precision::F32 => 4,
            Precision::F16 | Precision::U16 => 2,
            Precision::U8 | Precision::Bc6h => 1,
        }
    }

    /// The steps of a normalised-integer format (65,535 or 255); None for floats.
    pub fn unorm_steps(self) -> Option<f32> {
        match self {
            Precision::F32 | Precision::F16 | Precision::Bc6h => None,
            Precision::U16 => Some(65_535.0),
            Precision::U8 => Some(255.0),
        }
    }

    /// The suffix of its name (`+f16`, `+u16`, `+u8`; none for f32).
    pub fn suffix(self) -> &'static str {
        match self {
            Precision::F32 => "",
            Precision::F16 => "+f16",
            Precision::U16 => "+u16",
            Precision::U8 => "+u8",
            Precision::Bc6h => "+bc6h",
        }
    }

    /// Values `v` as stored in this precision and read back. A float format
    /// rounds each value; a normalised-integer format rounds `v / scale` to
    /// its steps, `scale` being the largest |value| (UNORM: 255 or 65,535
    /// steps; when some value is negative, SNORM: 127 or 32,767 steps each
    /// side, as for spherical-harmonic coefficients). Non-finite values become 0.
    pub fn store(self, v: &[f64]) -> Vec<f64> {
        let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
        match self.unorm_steps() {
            None => v
                .iter()
                .map(|&x| match self {
                    Precision::F16 | Precision::Bc6h => half::f16::from_f64(finite(x)).to_f64(),
                    _ => finite(x) as f32 as f64,
                })
                .collect(),
            Some(steps) => {
                let signed = v.iter().any(|&x| finite(x) < 0.0);
                let steps = if signed {
                    (f64::from(steps) - 1.0) / 2.0
                } else {
                    f64::from(steps)
                };
                let scale = v.iter().map(|&x| finite(x).abs()).fold(0.0, f64::max);
                if scale == 0.0 {
                    return vec![0.0; v.len()];
                }
                v.iter()
                    .map(|&x| (finite(x) / scale * steps).round() / steps * scale)
                    .collect()
            }
        }
    }
}

/// A rendered texture as a renderer stores it: all of it or only the C
/// sector its symmetry needs, in f32 or f16, with the lookup it is read with.
///
/// A symmetry-reduced texture keeps the columns of the full render whose
/// centres lie in [`Symmetry::stored_range`]; a query's C is folded into
/// that range ([`Symmetry::fold`]) and the taps beyond the sector's edges
/// are mirrored back into it (exact when the edges lie on texel boundaries,
/// as they do for renders of symmetric data). Rotational data keeps one column.
#[derive(Debug, Clone, PartialEq)]
pub struct StoredTexture {
    /// The stored texels (already rounded to `precision`), row-major, `columns` wide.
    data: Vec<f32>,
    height: usize,
    /// Columns of the full render (the C step is 360 / `full_width`).
    full_width: usize,
    /// First stored column of the full render, and how many are stored.
    first_column: usize,
    columns: usize,
    /// `Some` when only the symmetry's sector is stored.
    reduced: Option<Symmetry>,
    precision: Precision,
    /// What a normalised-integer texel of 1 stands for (the largest texel; 1 for floats).
    unorm_scale: f32,
    /// [`Precision::Bc6h`]: the BC6H_UF16 blocks the texels were decoded
    /// from (what a renderer uploads); `None` for other precisions.
    blocks: Option<Vec<u8>>,
    lookup: Lookup,
    i_max_cd: f64,
    /// What the texture was rendered with, for its name.
    filter: Filter,
    factor: u32,
}

/// The texels `kept` (`columns` × `h`, I / I_max) as `precision` stores
/// them, and the BC6H blocks they were decoded from for [`Precision::Bc6h`].
#[cfg_attr(not(feature = "bc6h"), allow(unused_variables))] // the sizes are the encoder's
fn stored_texels(kept: &[f64], columns: usize, h: usize, precision: Precision) -> (Vec<f32>, Option<Vec<u8>>) {
    match precision {
        #[cfg(feature = "bc6h")]
        Precision::Bc6h if columns > 0 && h > 0 => {
            let blocks = super::bc6h::encode(kept, columns, h);
            (super::bc6h::decode(&blocks, columns, h), Some(blocks))
        }
        p => (p.store(kept).into_iter().map(|v| v as f32).collect(), None),
    }
}

impl StoredTexture {
    /// Store `rendered` (reduced to `symmetry`'s sector when given) in
    /// `precision`, to be read with `lookup`.
    pub fn new(rendered: &Rendered, reduced: Option<Symmetry>, precision: Precision, lookup: Lookup) -> Self {
        let (h, w) = (rendered.mapping.height, rendered.mapping.width);
        let (first_column, columns) = match reduced {
            Some(Symmetry::Rotational) => (0, 1.min(w)),
            Some(sym) if sym != Symmetry::None && w > 0 => {
                let (lo, hi) = sym.stored_range();
                let cols: Vec<usize> = (0..w)
                    .filter(|&j| {
                        let c = rendered.mapping.c_of_column(j);
                        c >= lo && c <= hi
                    })
                    .collect();
                match (cols.first(), cols.last()) {
                    (Some(&a), Some(&b)) => (a, b - a + 1),
                    _ => (0, w),
                }
            }
            _ => (0, w),
        };
        let reduced = reduced.filter(|&s| s != Symmetry::None && columns < w);
        // Without the encoder the blocks cannot be made: f16, named so (never `+bc6h` unencoded).
        let precision = match precision {
            Precision::Bc6h if !super::bc6h::available() => Precision::F16,
            p => p,
        };
        let mut kept = Vec::with_capacity(h * columns);
        for i in 0..h {
            let row = &rendered.data[i * w..][..w];
            kept.extend(row[first_column..first_column + columns].iter().map(|&v| f64::from(v)));
        }
        let (data, blocks) = stored_texels(&kept, columns, h, precision);
        let unorm_scale = match precision.unorm_steps() {
            Some(_) => data.iter().copied().fold(0.0, f32::max),
            None => 1.0,
        };
        Self {
            data,
            unorm_scale,
            blocks,
            height: h,
            full_width: w,
            first_column,
            columns,
            reduced,
            precision,
            lookup,
            i_max_cd: rendered.i_max_cd,
            filter: rendered.filter,
            factor: rendered.factor,
        }
    }

    /// The BC6H_UF16 blocks of a [`Precision::Bc6h`] texture (16 bytes per
    /// 4 × 4 block, row-major, the stored columns padded to whole blocks with
    /// their edge texels): what a renderer uploads; `None` for other precisions.
    pub fn bc6h_blocks(&self) -> Option<&[u8]> {
        self.blocks.as_deref()
    }

    /// Bytes of the stored texels (4 per texel in f32, 2 in f16 and u16, 1
    /// in u8); the scale of a normalised-integer texture is not counted (it
    /// takes the place of I_max, which a float texture needs as well).
    pub fn texel_bytes(&self) -> usize {
        match self.precision {
            // Whole 4 x 4 blocks of 16 bytes.
            Precision::Bc6h => super::bc6h::block_bytes(self.columns, self.height).unwrap_or(usize::MAX),
            p => self.data.len() * p.bytes(),
        }
    }

    /// What a normalised-integer texel of 1 stands for, I / I_max (the
    /// largest stored texel); 1 for float precisions.
    pub fn unorm_scale(&self) -> f32 {
        self.unorm_scale
    }

    /// The stored texels (I / I_max, already rounded to the precision),
    /// row-major, `columns` wide: what a renderer uploads.
    pub fn texels(&self) -> &[f32] {
        &self.data
    }
    /// Rows (γ direction; row i centred at γ = (i + ½)·180/height degrees).
    pub fn height(&self) -> usize {
        self.height
    }
    /// Columns of the full render (column j centred at C = (j + ½)·360/full_width degrees).
    pub fn full_width(&self) -> usize {
        self.full_width
    }
    /// The first stored column of the full render and how many are stored.
    pub fn stored_columns(&self) -> (usize, usize) {
        (self.first_column, self.columns)
    }
    /// The symmetry whose C sector is stored (`None`: the whole circle).
    pub fn reduced(&self) -> Option<Symmetry> {
        self.reduced
    }
    /// The storage precision.
    pub fn precision(&self) -> Precision {
        self.precision
    }
    /// The lookup it is read with.
    pub fn lookup(&self) -> Lookup {
        self.lookup
    }
    /// I_max (cd) the texels are normalised by.
    pub fn i_max_cd(&self) -> f64 {
        self.i_max_cd
    }

    fn view(&self) -> TexelView<'_> {
        TexelView {
            data: &self.data,
            height: self.height,
            full_width: self.full_width,
            first_column: self.first_column,
            columns: self.columns,
            reduced: self.reduced,
        }
    }

    /// Intensity (cd, ≥ 0) at (C, γ) degrees; 0 for an empty texture or non-finite angles.
    pub fn cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        (self.view().sample(self.lookup, c_deg, gamma_deg) * self.i_max_cd).max(0.0)
    }

    /// Intensity (cd, ≥ 0) from a unit direction with every step in f32, as a
    /// shader computes it: the angles ([`frame::unit_angles_f32`]), the texel
    /// coordinates, the weights and the sums. 0 for an empty texture or a
    /// non-finite direction. Differs from [`StoredTexture::cd`] by the f32
    /// rounding of those steps (measured in the trade table,
    /// `f32_vs_f64_max_pct`).
    pub fn cd_dir_f32(&self, d: glam::Vec3) -> f32 {
        if !d.is_finite() {
            return 0.0;
        }
        let (c, g) = frame::unit_angles_f32(d);
        let c = match self.reduced {
            // The fold only reflects C about the sector's edges.
            Some(sym) => sym.fold(c as f64) as f32,
            None => c,
        };
        (self.view().sample_real(self.lookup, c, g) * self.i_max_cd as f32).max(0.0)
    }
}

/// The float type a lookup computes in: f64 (the reference) or f32 (as a
/// shader does). One lookup code for both, so they differ only by rounding.
trait LookupReal: Real {
    fn floor(self) -> Self;
    fn to_isize(self) -> isize;
    fn from_texel(v: f32) -> Self;
    fn from_usize(v: usize) -> Self;
    fn clamp_to(self, lo: Self, hi: Self) -> Self;
    /// Catmull–Rom weights of the four texels around fraction `s`.
    fn catmull_rom(s: Self) -> [Self; 4];
}

impl LookupReal for f64 {
    #[inline]
    fn floor(self) -> Self {
        f64::floor(self)
    }
    #[inline]
    fn to_isize(self) -> isize {
        self as isize
    }
    #[inline]
    fn from_texel(v: f32) -> Self {
        v as f64
    }
    #[inline]
    fn from_usize(v: usize) -> Self {
        v as f64
    }
    #[inline]
    fn clamp_to(self, lo: Self, hi: Self) -> Self {
        self.clamp(lo, hi)
    }
    #[inline]
    fn catmull_rom(s: Self) -> [Self; 4] {
        uniform_catmull_rom(s)
    }
}

impl LookupReal for f32 {
    #[inline]
    fn floor(self) -> Self {
        f32::floor(self)
    }
    #[inline]
    fn to_isize(self) -> isize {
        self as isize
    }
    #[inline]
    fn from_texel(v: f32) -> Self {
        v
    }
    #[inline]
    fn from_usize(v: usize) -> Self {
        v as f32
    }
    #[inline]
    fn clamp_to(self, lo: Self, hi: Self) -> Self {
        self.clamp(lo, hi)
    }
    /// The uniform Catmull–Rom cubic in f32 (a shader's closed form; the
    /// f64 weights come from [`Filter::linear_weights`], the same polynomial).
    #[inline]
    fn catmull_rom(s: Self) -> [Self; 4] {
        let (s2, s3) = (s * s, s * s * s);
        [
            0.5 * (-s3 + 2.0 * s2 - s),
            0.5 * (3.0 * s3 - 5.0 * s2 + 2.0),
            0.5 * (-3.0 * s3 + 4.0 * s2 + s),
            0.5 * (s3 - s2),
        ]
    }
}

/// Texels of a render, whole or a sector, borrowed for a lookup.
#[derive(Debug, Clone, Copy)]
struct TexelView<'a> {
    data: &'a [f32],
    height: usize,
    full_width: usize,
    first_column: usize,
    columns: usize,
    reduced: Option<Symmetry>,
}

impl TexelView<'_> {
    /// The stored value (I / I_max) at row `i` and full-render column `j`:
    /// rows clamped, columns periodic (whole) or clamped to the sector (reduced).
    #[inline]
    fn texel<T: LookupReal>(&self, i: isize, j: isize) -> T {
        let i = i.clamp(0, self.height as isize - 1) as usize;
        let j = match self.reduced {
            None => j.rem_euclid(self.full_width as isize) as usize,
            Some(_) => {
                // Mirror about the sector's edges (they lie on texel boundaries), then clamp.
                let n = self.columns as isize;
                let mut k = j - self.first_column as isize;
                if k < 0 {
                    k = -1 - k;
                } else if k >= n {
                    k = 2 * n - 1 - k;
                }
                k.clamp(0, n - 1) as usize
            }
        };
        T::from_texel(self.data[i * self.columns + j])
    }

    /// The value (I / I_max, unclamped) at (C, γ) degrees read with `lookup`.
    fn sample(&self, lookup: Lookup, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        let c = match self.reduced {
            Some(sym) => sym.fold(c_deg),
            None => wrap360(c_deg),
        };
        self.sample_real(lookup, c, gamma_deg)
    }

    /// [`TexelView::sample`] in `T` for C already in the stored range, degrees.
    fn sample_real<T: LookupReal>(&self, lookup: Lookup, c: T, gamma_deg: T) -> T {
        let (h, w) = (self.height, self.full_width);
        if h == 0 || w == 0 || self.columns == 0 {
            return T::ZERO;
        }
        let half = T::from_f64(0.5);
        let y = gamma_deg.clamp_to(T::ZERO, T::from_f64(180.0)) / T::from_f64(180.0) * T::from_usize(h) - half;
        let x = c / T::from_f64(360.0) * T::from_usize(w) - half;
        match lookup {
            Lookup::Nearest => self.texel((y + half).floor().to_isize(), (x + half).floor().to_isize()),
            Lookup::Bilinear => {
                let (i0, j0) = (y.floor(), x.floor());
                let (ty, tx) = (y - i0, x - j0);
                let (i0, j0) = (i0.to_isize(), j0.to_isize());
                let row = |i| self.texel::<T>(i, j0) * (T::ONE - tx) + self.texel::<T>(i, j0 + 1) * tx;
                row(i0) * (T::ONE - ty) + row(i0 + 1) * ty
            }
            Lookup::CatmullRom => {
                let (i0, j0) = (y.floor(), x.floor());
                let wy = T::catmull_rom(y - i0);
                let wx = T::catmull_rom(x - j0);
                let (i0, j0) = (i0.to_isize(), j0.to_isize());
                let mut acc = T::ZERO;
                for (a, &wa) in wy.iter().enumerate() {
                    let mut row = T::ZERO;
                    for (b, &wb) in wx.iter().enumerate() {
                        row = row + wb * self.texel::<T>(i0 - 1 + a as isize, j0 - 1 + b as isize);
                    }
                    acc = acc + wa * row;
                }
                acc
            }
        }
    }
}

/// Catmull–Rom weights of the four texels around fraction `s` on a uniform grid.
#[inline]
fn uniform_catmull_rom(s: f64) -> [f64; 4] {
    Filter::CatmullRom
        .linear_weights([-1.0, 0.0, 1.0, 2.0], s)
        .unwrap_or([0.0, 1.0 - s, s, 0.0])
}

impl IntensityField for StoredTexture {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.cd(c_deg, gamma_deg)
    }
    fn name(&self) -> String {
        let mut n = format!(
            "{}@x{}/{}{}",
            self.filter,
            self.factor,
            self.lookup,
            self.precision.suffix()
        );
        if self.reduced.is_some() {
            n.push_str("+reduced");
        }
        n
    }
    fn bytes(&self) -> usize {
        self.texel_bytes()
    }
    fn is_continuous(&self) -> bool {
        !matches!(self.lookup, Lookup::Nearest) && !matches!(self.filter, Filter::Nearest)
    }
    /// A nearest lookup of the whole texture is its texels as cells: row i
    /// covers γ from i·180/height to (i + 1)·180/height, column j C from
    /// j·360/full_width to (j + 1)·360/full_width, each texel × I_max,
    /// clamped at 0 (as [`StoredTexture::cd`]). A symmetry-reduced texture
    /// mirrors its columns and is not described here (`None`).
    fn constant_cells(&self) -> Option<crate::model::ConstantCells> {
        if self.lookup != Lookup::Nearest || self.reduced.is_some() || self.height == 0 || self.full_width == 0 {
            return None;
        }
        let edges = |n: usize, span: f64| (0..=n).map(|k| span * k as f64 / n as f64).collect();
        Some(crate::model::ConstantCells {
            gamma_edges_deg: edges(self.height, 180.0),
            c_edges_deg: edges(self.full_width, 360.0),
            values_cd: self
                .data
                .iter()
                .map(|&v| (f64::from(v) * self.i_max_cd).max(0.0))
                .collect(),
        })
    }
}

impl Rendered {
    /// Intensity (cd) at (C, γ) degrees read from the whole f32 texture with
    /// `lookup`; 0 for an empty texture or non-finite angles.
    pub fn lookup_cd(&self, lookup: Lookup, c_deg: f64, gamma_deg: f64) -> f64 {
        let view = TexelView {
            data: &self.data,
            height: self.mapping.height,
            full_width: self.mapping.width,
            first_column: 0,
            columns: self.mapping.width,
            reduced: None,
        };
        (view.sample(lookup, c_deg, gamma_deg) * self.i_max_cd).max(0.0)
    }
}

/// A rendered texture is an intensity field read bilinearly from all of its
/// f32 texels (the default hardware lookup); [`StoredTexture`] stores and
/// reads it otherwise.
impl IntensityField for Rendered {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.lookup_cd(Lookup::Bilinear, c_deg, gamma_deg)
    }
    fn name(&self) -> String {
        format!("{}@x{}/bilinear", self.filter, self.factor)
    }
    fn bytes(&self) -> usize {
        self.data.len() * std::mem::size_of::<f32>()
    }
    fn is_continuous(&self) -> bool {
        !matches!(self.filter, Filter::Nearest)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Symmetry;
    use crate::reconstruct::{render, LightTexture};
    use crate::synth::{GridSpec, Synth};

    #[test]
    fn lookups_return_texel_values_at_texel_centres() {
        let lum = Synth::CosinePower { p: 5.0 }
            .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 100.0)
            .unwrap();
        let tex = LightTexture::new(lum.distribution()).unwrap();
        let r = render(&tex, Filter::CatmullRom, 2).unwrap();
        let (h, w) = (r.mapping.height, r.mapping.width);
        for i in [0, h / 3, h - 1] {
            for j in [0, w / 2, w - 1] {
                let (c, g) = (r.mapping.c_of_column(j), r.mapping.gamma_of_row(i));
                let want = (r.data[i * w + j] as f64 * r.i_max_cd).max(0.0);
                for l in Lookup::ALL {
                    let got = r.lookup_cd(l, c, g);
                    assert!(
                        (got - want).abs() <= 1e-9 * r.i_max_cd,
                        "{l} at ({c}, {g}): {got} vs {want}"
                    );
                }
            }
        }
        assert_eq!(r.lookup_cd(Lookup::Bilinear, f64::NAN, 3.0), 0.0);
        let s = StoredTexture::new(&r, None, Precision::F32, Lookup::CatmullRom);
        assert_eq!(s.bytes(), 4 * h * w);
        assert_eq!(s.name(), "catmull-rom@x2/catmull-rom");
        assert_eq!("catmull-rom".parse::<Lookup>().unwrap(), Lookup::CatmullRom);
        assert!("cubic".parse::<Lookup>().is_err());
    }

    /// Storing only the symmetry's sector changes no value (beyond f32
    /// rounding), only the bytes;
    /// f16 storage changes values by at most half an f16 ulp of I_max.
    #[test]
    fn reduced_and_half_storage() {
        let g = GridSpec::uniform(15.0, 5.0).unwrap();
        let lum = Synth::Roadway.build(&g, 1000.0).unwrap();
        let d = lum.distribution().with_symmetry(Symmetry::C90C270).unwrap();
        let tex = LightTexture::new(&d).unwrap();
        let r = render(&tex, Filter::CatmullRom, 2).unwrap();
        for l in Lookup::ALL {
            let full = StoredTexture::new(&r, None, Precision::F32, l);
            let part = StoredTexture::new(&r, Some(Symmetry::C90C270), Precision::F32, l);
            let half = StoredTexture::new(&r, None, Precision::F16, l);
            assert!(
                2 * part.bytes() <= full.bytes() + 4 * r.mapping.height,
                "{} vs {}",
                part.bytes(),
                full.bytes()
            );
            assert_eq!(2 * half.bytes(), full.bytes());
            for ic in 0..72 {
                for ig in 0..=36 {
                    let (c, gm) = (ic as f64 * 5.0 + 0.3, ig as f64 * 5.0);
                    let (a, b) = (full.cd(c, gm), part.cd(c, gm));
                    // The render's mirrored columns agree to f32 rounding, not bit for bit.
                    assert!(
                        (a - b).abs() <= 4.0 * f64::from(f32::EPSILON) * 1000.0,
                        "{l} ({c}, {gm}): {a} vs {b}"
                    );
                    assert!((a - half.cd(c, gm)).abs() <= 1000.0 * 2f64.powi(-11), "{l} f16");
                }
            }
        }
    }

    /// The f32 lookup (angles, coordinates, weights and sums in f32, from an
    /// f32 unit vector) differs from the f64 one only by rounding. Bound for
    /// the continuous lookups: the f32 direction and angles carry errors of a
    /// few 1e-5 degrees (an ulp of 360 is 3e-5), which move the lookup by that
    /// times the texture's slope (the roadway render changes by at most ~1e-3
    /// of I_max per 2.5-degree texel: ~1e-8), and the f32 weights and sums
    /// add a few ulps of I_max (1.2e-7 each): measured 7.6e-7 of I_max here;
    /// 1e-5 leaves a margin of 13. Nearest is discontinuous: the f32 angles
    /// pick the neighbouring texel when a direction lies within their error
    /// of a texel edge, a full texel step (3.4e-3 of I_max here) on about
    /// 1e-5 of the directions; at most 1 in 1,000 may differ.
    #[test]
    fn f32_lookup_differs_from_f64_by_rounding_only() {
        let g = GridSpec::uniform(15.0, 5.0).unwrap();
        let lum = Synth::Roadway.build(&g, 1000.0).unwrap();
        let d = lum.distribution().with_symmetry(Symmetry::C90C270).unwrap();
        let r = render(&LightTexture::new(&d).unwrap(), Filter::CatmullRom, 2).unwrap();
        let dirs = crate::metrics::random_directions(20_000, 7);
        let mut worst_continuous: f64 = 0.0;
        for l in Lookup::ALL {
            for reduced in [None, Some(Symmetry::C90C270)] {
                let s = StoredTexture::new(&r, reduced, Precision::F32, l);
                let mut flips = 0;
                // Random directions, then the poles and the seam, where the
                // angles are least well conditioned.
                let special = [
                    glam::DVec3::Z,
                    -glam::DVec3::Z,
                    glam::DVec3::new(1.0, -1e-7, 0.0).normalize(),
                ];
                for dir in dirs.iter().chain(&special) {
                    let (a, b) = (s.cd_dir_f32(dir.as_vec3()) as f64, s.intensity_dir_cd(*dir));
                    assert!(a.is_finite() && a >= 0.0);
                    let diff = (a - b).abs() / 1000.0;
                    if l == Lookup::Nearest {
                        flips += usize::from(diff > 1e-6);
                    } else {
                        worst_continuous = worst_continuous.max(diff);
                    }
                }
                assert!(flips <= dirs.len() / 1000, "{l} {reduced:?}: {flips} texel flips");
                assert_eq!(s.cd_dir_f32(glam::Vec3::NAN), 0.0);
            }
        }
        let worst = worst_continuous;
        assert!(worst <= 1e-5, "f32 vs f64: {worst:e} of I_max");
        assert!(worst > 0.0, "the f32 path computes in f32");
    }
}
