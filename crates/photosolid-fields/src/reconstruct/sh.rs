//! Spherical harmonics of an intensity distribution (`sh:L`, `sh:L+f16`).
//!
//! A band-limited approximation of any [`IntensityField`] (in the trade
//! table: the Catmull–Rom reconstruction of the measured grid), the
//! representation Apple's ModelIO uses for IES profiles and real-time
//! renderers use for environment light (Ramamoorthi and Hanrahan 2001;
//! Sloan 2008).
//!
//! # Basis
//! Real orthonormal spherical harmonics `Y_lm`, l ≤ L, −l ≤ m ≤ l, in the
//! luminaire frame ([`crate::model::frame`]): polar angle γ (from the nadir,
//! `z = cos γ`) and azimuth C. `Y_l0 = P̄_l^0(z)`, `Y_lm = √2 P̄_l^m(z) cos mC`,
//! `Y_l,−m = √2 P̄_l^m(z) sin mC` (no Condon–Shortley phase), with the fully
//! normalised associated Legendre functions computed by the stable
//! three-term recurrence (Holmes and Featherstone 2002). Evaluation needs no
//! trigonometry: `sin^m γ · e^{imC} = (d_x + i d_y)^m` for a unit direction
//! (Sloan 2013). Coefficient `(l, m)` is stored at `l² + l + m`.
//!
//! # Projection
//! `c_lm = ∫ f Y_lm dΩ` by Gauss–Legendre quadrature in `z`, separately on
//! each hemisphere (z in [−1, 0] and [0, 1]: a cut-off at the horizon, the
//! commonest kink of a luminaire, lies on the rule's ends), times the
//! trapezoidal rule in C. With `n ≥ L + 1` nodes per hemisphere and
//! `n_C ≥ 2L + 1` azimuths the rule is exact for every band-limited field of
//! degree ≤ L (and for `max(0, cos γ)^p` with integer p ≤ 2n − 1 − L), so an
//! isotropic source is exact at any L. [`QUAD_RINGS`] × [`QUAD_AZIMUTHS`]
//! samples (about 1° apart) are used at least.
//!
//! # Ringing
//! A truncated series rings near a cut-off and can go negative. Each band is
//! multiplied by a window ([`ShWindow`]); the default, Lanczos' σ factors
//! `σ_l = sinc(π l / (L + 1))` (Lanczos 1956; Sloan 2008 "Stupid Spherical
//! Harmonics Tricks", §"Windowing"), damps the ringing at the cost of some
//! blur. What is left below zero is clamped to 0 at evaluation
//! ([`ShField::unclamped_cd`] shows it).
//!
//! # Storage
//! `(L + 1)²` coefficients (only the `L + 1` zonal ones, m = 0, when every
//! other one is zero to rounding: a rotationally symmetric field,
//! [`ShField::is_zonal`]) relative to a scale (the largest sampled
//! intensity, f64, not counted: the same convention as a stored texture's
//! I_max), in f32 (4 bytes each) or f16 (2 bytes: rounded to the nearest half
//! float, 11 significant bits). The scale makes the isotropic `Y_00`
//! coefficient exactly 1.

use std::f64::consts::PI;

use glam::DVec3;

use crate::error::ModelError;
use crate::model::frame::{direction, sin_cos_deg};
use crate::model::IntensityField;

use super::lookup::Precision;

/// Largest degree L of a series with non-zonal terms (`(L + 1)² = 1089`
/// coefficients, as many terms a lookup).
pub const MAX_SH_DEGREE: usize = 32;
/// Largest degree L of a zonal series (a rotationally symmetric field:
/// `L + 1 = 129` coefficients and terms a lookup, the cost of an
/// asymmetric `sh:10`). A profile's sharp edge needs such degrees: the
/// Lanczos-windowed series blurs an edge over about 180° / (L + 1).
pub const MAX_ZONAL_SH_DEGREE: usize = 128;
/// Gauss–Legendre nodes per hemisphere at least (`n = max(L + 1, QUAD_RINGS / 2)`).
pub const QUAD_RINGS: usize = 180;
/// Azimuths of the quadrature at least (`max(2L + 2, QUAD_AZIMUTHS)`), 1° apart.
pub const QUAD_AZIMUTHS: usize = 360;

/// The window applied to the bands of a truncated series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShWindow {
    /// No window: the plain truncation (least-squares optimal, rings most).
    None,
    /// Lanczos' σ factors `sinc(π l / (L + 1))` (Lanczos 1956).
    Lanczos,
}

impl ShWindow {
    /// Name in reports: `none` or `lanczos`.
    pub fn name(self) -> &'static str {
        match self {
            ShWindow::None => "none",
            ShWindow::Lanczos => "lanczos",
        }
    }

    /// The factor of band `l` of a series of degree `degree` (1 at l = 0).
    pub fn factor(self, l: usize, degree: usize) -> f64 {
        match self {
            ShWindow::None => 1.0,
            ShWindow::Lanczos if l == 0 => 1.0,
            ShWindow::Lanczos => {
                let x = PI * l as f64 / (degree + 1) as f64;
                x.sin() / x
            }
        }
    }
}

/// Index of coefficient `(l, m)`, −l ≤ m ≤ l.
#[inline]
pub fn sh_index(l: usize, m: isize) -> usize {
    ((l * l + l) as isize + m) as usize
}

/// Gauss–Legendre nodes and weights of `n` points on [−1, 1] (Newton on P_n;
/// Golub and Welsch 1969 give the same rule).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = if n == 1 {
                    1.0
                } else {
                    n as f64 * (x * p1 - p0) / (x * x - 1.0)
                };
                let dx = if n == 1 { x } else { p1 / dp };
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The recurrence constants of degree `degree`: per (l, m ≥ 0) at
/// `l(l+1)/2 + m`, `(a_lm, b_lm)` of `P̄_l^m = a (z P̄_{l−1}^m − b P̄_{l−2}^m)`.
fn recurrence(degree: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity((degree + 1) * (degree + 2) / 2);
    for l in 0..=degree {
        for m in 0..=l {
            let (lf, mf) = (l as f64, m as f64);
            if l <= m {
                out.push((0.0, 0.0));
                continue;
            }
            let a = ((4.0 * lf * lf - 1.0) / (lf * lf - mf * mf)).sqrt();
            let b = if l >= m + 2 {
                (((lf - 1.0) * (lf - 1.0) - mf * mf) / (4.0 * (lf - 1.0) * (lf - 1.0) - 1.0)).sqrt()
            } else {
                0.0
            };
            out.push((a, b));
        }
    }
    out
}

/// `√(4π) P̄_l^m(z) / sin^m γ` for every (l, m ≥ 0) at `l(l+1)/2 + m`,
/// times √2 for m > 0: the zonal factor of `√(4π) Y_lm`.
fn legendre_scaled(degree: usize, z: f64, rec: &[(f64, f64)], out: &mut [f64]) {
    let tri = |l: usize, m: usize| l * (l + 1) / 2 + m;
    let mut pmm = 1.0;
    for m in 0..=degree {
        if m > 0 {
            pmm *= ((2 * m + 1) as f64 / (2 * m) as f64).sqrt();
        }
        let k = if m == 0 { 1.0 } else { std::f64::consts::SQRT_2 };
        let (mut p2, mut p1) = (0.0, pmm);
        out[tri(m, m)] = k * pmm;
        for l in m + 1..=degree {
            let (a, b) = rec[tri(l, m)];
            let p = a * (z * p1 - b * p2);
            out[tri(l, m)] = k * p;
            p2 = p1;
            p1 = p;
        }
    }
}

/// The projection coefficients `c_lm = ∫ f Y_lm dΩ` (orthonormal basis, cd)
/// of `field` up to `degree`, by the quadrature of the module docs, and the
/// largest |sample| (cd).
///
/// # Errors
/// [`ModelError::Parameter`] (`sh`) for a degree above [`MAX_ZONAL_SH_DEGREE`].
pub fn project(field: &dyn IntensityField, degree: usize) -> Result<(Vec<f64>, f64), ModelError> {
    check_degree(degree)?;
    let n = (degree + 1).max(QUAD_RINGS / 2);
    let nc = (2 * degree + 2).max(QUAD_AZIMUTHS);
    // Rings: z = cos γ in (0, 1] (lower hemisphere, γ < 90) and [−1, 0).
    let half = gauss_legendre(n);
    let rings: Vec<(f64, f64)> = half
        .iter()
        .flat_map(|&(x, w)| [(0.5 * (x + 1.0), 0.5 * w), (-0.5 * (x + 1.0), 0.5 * w)])
        .collect();
    let gammas: Vec<f64> = rings
        .iter()
        .map(|&(z, _)| z.clamp(-1.0, 1.0).acos().to_degrees())
        .collect();
    let cs: Vec<f64> = (0..nc).map(|j| 360.0 * j as f64 / nc as f64).collect();
    let mut v = vec![0.0; cs.len() * gammas.len()];
    field.sample_grid(&cs, &gammas, &mut v);
    let ng = gammas.len();
    let scale = v
        .iter()
        .map(|x| if x.is_finite() { x.abs() } else { 0.0 })
        .fold(0.0, f64::max);
    let trig: Vec<(f64, f64)> = (0..nc).map(|j| sin_cos_deg(cs[j])).collect();
    let rec = recurrence(degree);
    let mut leg = vec![0.0; (degree + 1) * (degree + 2) / 2];
    let mut c = vec![0.0; (degree + 1) * (degree + 1)];
    let dphi = 2.0 * PI / nc as f64;
    let mut fm = vec![(0.0, 0.0); degree + 1];
    for (ig, &(z, w)) in rings.iter().enumerate() {
        // Azimuthal Fourier sums of the ring: Σ_j f cos(mC_j), Σ_j f sin(mC_j).
        fm.iter_mut().for_each(|x| *x = (0.0, 0.0));
        for j in 0..nc {
            let f = v[j * ng + ig];
            if f == 0.0 || !f.is_finite() {
                continue;
            }
            let (s1, c1) = trig[j];
            let (mut cm, mut sm) = (1.0, 0.0);
            for x in fm.iter_mut() {
                x.0 += f * cm;
                x.1 += f * sm;
                (cm, sm) = (cm * c1 - sm * s1, sm * c1 + cm * s1);
            }
        }
        let sin_g = (1.0 - z * z).max(0.0).sqrt();
        legendre_scaled(degree, z, &rec, &mut leg);
        let mut sinm = 1.0;
        for m in 0..=degree {
            for l in m..=degree {
                // √(4π) Y_lm = leg · sin^m γ · (cos, sin)(mC); divide by √(4π) for Y_lm.
                let k = w * dphi * leg[l * (l + 1) / 2 + m] * sinm / (4.0 * PI).sqrt();
                c[l * l + l + m] += k * fm[m].0;
                if m > 0 {
                    c[l * l + l - m] += k * fm[m].1;
                }
            }
            sinm *= sin_g;
        }
    }
    Ok((c, scale))
}

/// The largest |coefficient| with m ≠ 0, relative to the largest one, below
/// which a series is stored zonal (m = 0 only). The projection of a field
/// that does not depend on C leaves its non-zonal coefficients at rounding
/// level (about 1e-17 of the largest); a real asymmetry is many orders above.
pub const ZONAL_TOLERANCE: f64 = 1e-12;

/// Whether the non-zonal coefficients of `coeffs` (degree `degree`, at
/// `l² + l + m`) are all within [`ZONAL_TOLERANCE`] of zero; they are then
/// set to exactly zero (what is stored is what is evaluated).
fn zonal_only(coeffs: &mut [f64], degree: usize) -> bool {
    let largest = coeffs.iter().fold(0.0f64, |a, c| a.max(c.abs()));
    let non_zonal = |l: usize| (0..2 * l + 1).filter(move |&k| k != l).map(move |k| l * l + k);
    let zonal = (0..=degree)
        .flat_map(non_zonal)
        .all(|i| coeffs.get(i).is_none_or(|c| c.abs() <= ZONAL_TOLERANCE * largest));
    if zonal {
        for i in (0..=degree).flat_map(non_zonal) {
            if let Some(c) = coeffs.get_mut(i) {
                *c = 0.0;
            }
        }
    }
    zonal
}

fn check_degree(degree: usize) -> Result<(), ModelError> {
    if degree > MAX_ZONAL_SH_DEGREE {
        return Err(ModelError::Parameter {
            name: "sh",
            value: degree.to_string(),
            reason: format!(
                "the degree L must be 0 to {MAX_SH_DEGREE} ({MAX_ZONAL_SH_DEGREE} for rotationally symmetric data)"
            ),
        });
    }
    Ok(())
}

/// A truncated, windowed spherical-harmonic series as a renderer stores it
/// (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ShField {
    degree: usize,
    window: ShWindow,
    precision: Precision,
    /// Intensity (cd) the coefficients are relative to.
    scale_cd: f64,
    /// `σ_l c_lm / (√(4π) scale)`, rounded to the storage precision.
    coeffs: Vec<f64>,
    /// Every stored coefficient with m ≠ 0 is zero (a rotationally symmetric
    /// field): only the L + 1 zonal ones are stored and evaluated.
    zonal: bool,
    rec: Vec<(f64, f64)>,
    diag: Vec<f64>,
}

impl ShField {
    /// The series of degree `degree` of `field`, windowed and stored in `precision`.
    ///
    /// # Errors
    /// [`ModelError::Parameter`] (`sh`) for a degree above [`MAX_SH_DEGREE`]
    /// unless the series is zonal (then up to [`MAX_ZONAL_SH_DEGREE`]),
    /// (`precision`) for [`Precision::Bc6h`].
    pub fn new(
        field: &dyn IntensityField,
        degree: usize,
        window: ShWindow,
        precision: Precision,
    ) -> Result<Self, ModelError> {
        if precision == Precision::Bc6h {
            return Err(ModelError::Parameter {
                name: "precision",
                value: "bc6h".into(),
                reason:
                    "BC6H is a texture block format: spherical-harmonic coefficients are stored as f32, f16, u16 or u8"
                        .into(),
            });
        }
        let (c, scale_cd) = project(field, degree)?;
        let sh = Self::from_coefficients(&c, scale_cd, degree, window, precision);
        if sh.degree < degree {
            return Err(ModelError::Parameter {
                name: "sh",
                value: degree.to_string(),
                reason: format!(
                    "a degree above {MAX_SH_DEGREE} needs a rotationally symmetric distribution \
                     (a zonal series, L + 1 coefficients); this one depends on C"
                ),
            });
        }
        Ok(sh)
    }

    /// The series of orthonormal coefficients `c` (cd, at `l² + l + m`) of
    /// degree `degree`, relative to `scale_cd` (> 0; else the field is 0).
    /// A degree above [`MAX_SH_DEGREE`] is kept only for a zonal series (up
    /// to [`MAX_ZONAL_SH_DEGREE`]); a series with non-zonal terms is cut
    /// there ([`ShField::degree`] says which was kept).
    pub fn from_coefficients(c: &[f64], scale_cd: f64, degree: usize, window: ShWindow, precision: Precision) -> Self {
        let degree = degree.min(MAX_ZONAL_SH_DEGREE);
        let sh = Self::from_coefficients_at(c, scale_cd, degree, window, precision);
        if sh.zonal || degree <= MAX_SH_DEGREE {
            sh
        } else {
            Self::from_coefficients_at(c, scale_cd, MAX_SH_DEGREE, window, precision)
        }
    }

    fn from_coefficients_at(c: &[f64], scale_cd: f64, degree: usize, window: ShWindow, precision: Precision) -> Self {
        let ok = scale_cd.is_finite() && scale_cd > 0.0;
        let norm = if ok { 1.0 / ((4.0 * PI).sqrt() * scale_cd) } else { 0.0 };
        let windowed: Vec<f64> = (0..=degree)
            .flat_map(|l| (0..2 * l + 1).map(move |k| (l, l * l + k)))
            .map(|(l, i)| c.get(i).copied().unwrap_or(0.0) * window.factor(l, degree) * norm)
            .collect();
        // As stored: rounded to the float format, or to the integer steps of the largest |coefficient|.
        let mut coeffs = precision.store(&windowed);
        let zonal = zonal_only(&mut coeffs, degree);
        let diag = (0..=degree)
            .map(|m| {
                if m == 0 {
                    1.0
                } else {
                    ((2 * m + 1) as f64 / (2 * m) as f64).sqrt()
                }
            })
            .collect();
        Self {
            degree,
            window,
            precision,
            scale_cd: if ok { scale_cd } else { 0.0 },
            coeffs,
            zonal,
            rec: recurrence(degree),
            diag,
        }
    }

    /// The degree L.
    pub fn degree(&self) -> usize {
        self.degree
    }
    /// Whether only the zonal coefficients (m = 0) are stored: the field is
    /// rotationally symmetric about the vertical axis (see [`ZONAL_TOLERANCE`]).
    pub fn is_zonal(&self) -> bool {
        self.zonal
    }
    /// The window.
    pub fn window(&self) -> ShWindow {
        self.window
    }
    /// The storage precision of the coefficients.
    pub fn precision(&self) -> Precision {
        self.precision
    }
    /// The intensity (cd) the stored coefficients are relative to.
    pub fn scale_cd(&self) -> f64 {
        self.scale_cd
    }
    /// The coefficients as stored: windowed, divided by `√(4π)` and the
    /// scale, rounded to the storage precision (at `l² + l + m`).
    pub fn stored_coefficients(&self) -> &[f64] {
        &self.coeffs
    }
    /// The recurrence constants `(a_lm, b_lm)` of the evaluation, per (l, m ≥ 0)
    /// at `l(l+1)/2 + m` (see [`ShField::unclamped_cd`]).
    /// Public for the GPU's compact shader (`photosolid-gpu`), which evaluates the same recurrence.
    pub fn recurrence_constants(&self) -> &[(f64, f64)] {
        &self.rec
    }
    /// The diagonal factors `√((2m+1)/2m)` per m (1 at m = 0).
    /// Public for the GPU's compact shader (`photosolid-gpu`).
    pub fn diagonal_factors(&self) -> &[f64] {
        &self.diag
    }
    /// The stored coefficients as orthonormal ones, windowed (cd, at `l² + l + m`).
    pub fn coefficients_cd(&self) -> Vec<f64> {
        let k = (4.0 * PI).sqrt() * self.scale_cd;
        self.coeffs.iter().map(|b| b * k).collect()
    }

    /// The series' value (cd) at unit direction `u`, before clamping
    /// (negative where the series rings below zero). Summed degree by degree
    /// from L = 12 on, order by order below (the same bits).
    pub fn unclamped_cd(&self, u: DVec3) -> f64 {
        let orders = if self.zonal { 0 } else { self.degree };
        let sum = if self.degree >= BY_DEGREE_FROM {
            self.sum_by_degree(u, orders)
        } else {
            self.sum_by_order(u, orders)
        };
        let v = sum * self.scale_cd;
        if v.is_finite() {
            v
        } else {
            0.0
        }
    }

    /// The series' sum (relative to the scale) at unit direction `u`, order
    /// by order: for each m ≤ `orders`, the recurrence of P̄_l^m over l = m..=L
    /// (constants of [`recurrence`]), then the order's azimuthal factor.
    /// Each order's recurrence is a chain of dependent multiply-adds:
    /// fastest for low degrees, where the chains are short.
    pub(crate) fn sum_by_order(&self, u: DVec3, orders: usize) -> f64 {
        let (x, y, z) = (u.x, u.y, -u.z);
        let c = &self.coeffs;
        let base = |l: usize| l * l + l;
        let mut sum = 0.0;
        let mut pmm = 1.0;
        let (mut cr, mut ci) = (1.0, 0.0);
        for m in 0..=orders {
            if m > 0 {
                pmm *= self.diag[m];
                (cr, ci) = (cr * x - ci * y, cr * y + ci * x);
            }
            let (mut p2, mut p1) = (0.0, pmm);
            let (mut sc, mut ss) = (c[base(m) + m] * p1, c[base(m) - m] * p1);
            for l in m + 1..=self.degree {
                let (a, b) = self.rec[l * (l + 1) / 2 + m];
                let p = a * (z * p1 - b * p2);
                sc += c[base(l) + m] * p;
                ss += c[base(l) - m] * p;
                (p2, p1) = (p1, p);
            }
            sum += if m == 0 {
                sc
            } else {
                std::f64::consts::SQRT_2 * (sc * cr + ss * ci)
            };
        }
        sum
    }

    /// [`ShField::sum_by_order`] with the loops swapped, l outside and m
    /// inside: for one l the orders are independent, so the processor runs
    /// them side by side (about 2x faster at L = 32, slower at L ≤ 8 where the
    /// per-degree set-up dominates). Each order's sums take the same terms
    /// in the same order of l, so both give the same bits
    /// (`sum_orders_agree_bit_for_bit`).
    pub(crate) fn sum_by_degree(&self, u: DVec3, orders: usize) -> f64 {
        const N: usize = MAX_SH_DEGREE + 1;
        let (x, y, z) = (u.x, u.y, -u.z);
        let c = &self.coeffs;
        // Per order m: the last two P_l^m and the sums Σ_l c_{l,±m} P_l^m.
        let (mut p1, mut p2) = ([0.0; N], [0.0; N]);
        let (mut sc, mut ss) = ([0.0; N], [0.0; N]);
        let mut pmm = 1.0;
        for l in 0..=self.degree {
            let row = l * (l + 1) / 2;
            let at = l * l + l;
            // Orders m < l continue their recurrence.
            let k = l.min(orders + 1);
            let recurrence = &self.rec[row..row + k];
            let plus = &c[at..at + k];
            let minus = c[at + 1 - k..=at].iter().rev();
            for (((((p1, p2), (sc, ss)), &(a, b)), &cp), &cm) in p1[..k]
                .iter_mut()
                .zip(&mut p2[..k])
                .zip(sc[..k].iter_mut().zip(&mut ss[..k]))
                .zip(recurrence)
                .zip(plus)
                .zip(minus)
            {
                let p = a * (z * *p1 - b * *p2);
                *sc += cp * p;
                *ss += cm * p;
                (*p2, *p1) = (*p1, p);
            }
            // Order m = l starts at P_l^l.
            if l <= orders {
                if l > 0 {
                    pmm *= self.diag[l];
                }
                sc[l] = c[at + l] * pmm;
                ss[l] = c[at - l] * pmm;
                p1[l] = pmm;
            }
        }
        let mut sum = sc[0];
        let (mut cr, mut ci) = (1.0, 0.0);
        for m in 1..=orders {
            (cr, ci) = (cr * x - ci * y, cr * y + ci * x);
            sum += std::f64::consts::SQRT_2 * (sc[m] * cr + ss[m] * ci);
        }
        sum
    }
}

/// The degree from which [`ShField::unclamped_cd`] sums degree by degree
/// ([`ShField::sum_by_degree`]) instead of order by order: measured
/// crossover between L = 8 (by order 73 ns, by degree 95 ns a lookup) and
/// L = 16 (255 ns against 198 ns), release build.
const BY_DEGREE_FROM: usize = 12;

impl IntensityField for ShField {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(c_deg.is_finite() && gamma_deg.is_finite()) {
            return 0.0;
        }
        self.unclamped_cd(direction(c_deg, gamma_deg)).max(0.0)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        match d.try_normalize() {
            Some(u) => self.unclamped_cd(u).max(0.0),
            None => 0.0,
        }
    }
    fn name(&self) -> String {
        format!(
            "sh:{}{} ({} window{})",
            self.degree,
            self.precision.suffix(),
            self.window.name(),
            if self.zonal { ", zonal" } else { "" }
        )
    }
    /// `zonal` when only the m = 0 coefficients are stored ([`ShField::is_zonal`]).
    fn form(&self) -> Option<String> {
        self.zonal.then(|| "zonal".to_string())
    }
    /// `(L + 1)²` coefficients (`L + 1` when zonal) × 4 bytes (f32), × 2
    /// (f16, u16) or × 1 (u8); the f64 scale is not counted (as a stored
    /// texture's I_max).
    fn bytes(&self) -> usize {
        let n = if self.zonal {
            self.degree + 1
        } else {
            (self.degree + 1) * (self.degree + 1)
        };
        n * self.precision.bytes()
    }
    /// A finite sum of harmonics, clamped at 0: continuous.
    fn is_continuous(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reconstruct::{Filter, LightTexture};
    use crate::synth::{GridSpec, Synth};

    /// Both loop orders of the sum give the same bits at every degree, on an
    /// asymmetric field and on a zonal one, so the switch at
    /// [`BY_DEGREE_FROM`] changes speed and nothing else.
    #[test]
    fn sum_orders_agree_bit_for_bit() {
        let grid = GridSpec::uniform(15.0, 5.0).unwrap();
        for synth in [Synth::Roadway, Synth::Batwing] {
            let lum = synth.build(&grid, 1000.0).unwrap();
            let texture = LightTexture::new(lum.distribution()).unwrap();
            let source = texture.sampler(Filter::CatmullRom);
            for degree in [0, 1, 2, 5, 8, 12, 16, 32] {
                let sh = ShField::new(&source, degree, ShWindow::Lanczos, Precision::F32).unwrap();
                let orders = if sh.is_zonal() { 0 } else { degree };
                for i in 0..200 {
                    // A spiral over the sphere, poles included.
                    let z = 1.0 - 2.0 * i as f64 / 199.0;
                    let phi = i as f64 * 2.399_963;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let u = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                    let (a, b) = (sh.sum_by_order(u, orders), sh.sum_by_degree(u, orders));
                    assert_eq!(a.to_bits(), b.to_bits(), "{synth:?} L = {degree} at {u}: {a} vs {b}");
                }
            }
        }
    }
}
