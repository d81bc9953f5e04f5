//! Near field: light from an area instead of a point.
//!
//! Two area models, both in the luminaire frame of [`crate::model::frame`]
//! (metres from the photometric centre):
//! - [`lambert_polygon_lux`]: the exact unoccluded illuminance from a uniform
//!   Lambertian polygon (Lambert's vector-irradiance formula, docs/domain.md §8),
//!   clipped to the receiver's horizon, switching to the point form when the
//!   polygon is small against its distance ([`POINT_FORM_RATIO`], measured:
//!   see its docs);
//! - [`Opening::patches`](super::opening::Opening::patches): the directional area source, the opening cut into
//!   equal-share patches, each carrying the far-field distribution times its
//!   share; a flat opening is cut into surface patches, a solid one (box,
//!   cylinder, ellipsoid) into equal-volume cells.

use std::f64::consts::PI;

use glam::DVec3;

/// Below this size/distance ratio (largest polygon extent over the distance
/// from the receiver to the polygon's centroid) [`lambert_polygon_lux`] uses
/// the point form `L·A·cosθs·cosθr/d²` instead of Lambert's formula.
///
/// Measured, not guessed (test `point_form_switch_is_where_the_errors_cross`
/// recomputes it against 8 × 8 Gauss–Legendre quadrature of a small square
/// at distance 1): the point form is off by about 0.2–0.6 s² relatively
/// (s = side / distance), Lambert's formula loses about 1e-16–2e-15 / s to
/// cancellation when the square is seen off axis (its terms are O(s), their
/// sum O(s²)); the two cross near s = 1e-5 (45° and 80° off axis), where
/// both are about 1e-10 relative. On axis Lambert's formula stays exact.
pub const POINT_FORM_RATIO: f64 = 1e-5;

/// Illuminance (lx) at `point` (receiver normal `normal`, unit) from a
/// uniform Lambertian polygon of luminance `luminance` (cd/m²), exact and
/// unoccluded (Lambert's formula, docs/domain.md §8).
///
/// The polygon is planar and emits on the side its vertex order makes
/// counter-clockwise (the right-hand normal); a receiver behind or in its
/// plane gets 0. The polygon is first clipped to the receiver's horizon.
/// Below [`POINT_FORM_RATIO`] the point form is used. Never NaN for finite
/// input; fewer than 3 vertices or a degenerate polygon give 0.
pub fn lambert_polygon_lux(vertices: &[DVec3], luminance: f64, point: DVec3, normal: DVec3) -> f64 {
    if vertices.len() < 3 || !luminance.is_finite() {
        return 0.0;
    }
    // Newell normal (twice the area vector), relative to the first vertex
    // (no cancellation for a small polygon far from the origin).
    let mut area2 = DVec3::ZERO;
    for (i, &a) in vertices.iter().enumerate() {
        area2 += (a - vertices[0]).cross(vertices[(i + 1) % vertices.len()] - vertices[0]);
    }
    let area = area2.length() / 2.0;
    let Some(front) = area2.try_normalize() else { return 0.0 };
    let Some(n) = normal.try_normalize() else { return 0.0 };
    let centroid = vertices.iter().copied().sum::<DVec3>() / vertices.len() as f64;
    let size = vertices
        .iter()
        .flat_map(|a| vertices.iter().map(move |b| (*a - *b).length()))
        .fold(0.0, f64::max);
    let to_point = point - centroid;
    let d = to_point.length();
    // One-sided: behind or in the emitter's plane sees nothing.
    if front.dot(to_point) <= 1e-12 * size.max(d) {
        return 0.0;
    }
    if size < POINT_FORM_RATIO * d {
        let w = to_point / d;
        return (luminance * area * front.dot(w) * n.dot(-w)).max(0.0) / (d * d);
    }
    lambert_formula_lux(&clip_to_horizon(vertices, point, n), luminance, point, n)
}

/// Lambert's formula itself on an already clipped polygon (no switch).
fn lambert_formula_lux(clipped: &[DVec3], luminance: f64, point: DVec3, n: DVec3) -> f64 {
    if clipped.len() < 3 {
        return 0.0;
    }
    let mut sum = 0.0;
    for (i, &a) in clipped.iter().enumerate() {
        let b = clipped[(i + 1) % clipped.len()];
        let (Some(ra), Some(rb)) = ((a - point).try_normalize(), (b - point).try_normalize()) else {
            continue;
        };
        let cross = ra.cross(rb);
        let s = cross.length();
        if s <= 1e-300 {
            continue;
        }
        let theta = s.atan2(ra.dot(rb));
        sum += theta * n.dot(cross) / s;
    }
    // Counter-clockwise seen from the front gives a negative sum (the cross
    // products point away from the polygon); E = π L F, F = −Σ/(2π).
    (-luminance * sum / 2.0).max(0.0)
}

/// The polygon clipped to the half-space n·(v − x) ≥ 0 (Sutherland–Hodgman).
fn clip_to_horizon(vertices: &[DVec3], x: DVec3, n: DVec3) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(vertices.len() + 2);
    let side = |v: DVec3| n.dot(v - x);
    for (i, &a) in vertices.iter().enumerate() {
        let b = vertices[(i + 1) % vertices.len()];
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            let t = sa / (sa - sb);
            out.push(a + (b - a) * t);
        }
    }
    out
}

/// Form factor (dimensionless) from a differential area to a parallel
/// rectangle `a × b` whose corner lies on the area's normal at distance `c`
/// (closed form; Howell's catalogue, configuration B-3). Stable for small
/// rectangles (no cancellation).
pub fn corner_rectangle_form_factor(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

/// Illuminance (lx) on axis at distance `z` (m) from a Lambertian disk of
/// radius `r` (m) and luminance `luminance` (cd/m²): `π L r²/(r² + z²)`.
pub fn lambert_disk_on_axis_lux(luminance: f64, r: f64, z: f64) -> f64 {
    PI * luminance * r * r / (r * r + z * z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(side: f64) -> Vec<DVec3> {
        let h = side / 2.0;
        // Counter-clockwise seen from below (−z): emits downwards.
        vec![
            DVec3::new(-h, -h, 0.0),
            DVec3::new(-h, h, 0.0),
            DVec3::new(h, h, 0.0),
            DVec3::new(h, -h, 0.0),
        ]
    }

    #[test]
    fn lambert_polygon_matches_closed_forms() {
        let l = 1000.0;
        for (side, z) in [(1.0, 0.5), (0.2, 3.0), (2.0, 2.0)] {
            let e = lambert_polygon_lux(&square(side), l, DVec3::new(0.0, 0.0, -z), DVec3::Z);
            let f = 4.0 * corner_rectangle_form_factor(side / 2.0, side / 2.0, z);
            assert!((e - PI * l * f).abs() < 1e-12 * e, "{side} {z}: {e} vs {}", PI * l * f);
        }
        // Off axis: split the rectangle at the foot point into four corner rectangles.
        let verts = vec![
            DVec3::new(-0.3, -0.5, 0.0),
            DVec3::new(-0.3, 1.0, 0.0),
            DVec3::new(0.9, 1.0, 0.0),
            DVec3::new(0.9, -0.5, 0.0),
        ];
        let e = lambert_polygon_lux(&verts, l, DVec3::new(0.0, 0.0, -0.7), DVec3::Z);
        let f: f64 = [(0.3, 0.5), (0.3, 1.0), (0.9, 1.0), (0.9, 0.5)]
            .iter()
            .map(|&(a, b)| corner_rectangle_form_factor(a, b, 0.7))
            .sum();
        assert!((e - PI * l * f).abs() < 1e-12 * e);
        // Behind, in the plane, or wrong winding: nothing.
        assert_eq!(
            lambert_polygon_lux(&square(1.0), l, DVec3::new(0.0, 0.0, 1.0), -DVec3::Z),
            0.0
        );
        assert_eq!(
            lambert_polygon_lux(&square(1.0), l, DVec3::new(3.0, 0.0, 0.0), DVec3::Z),
            0.0
        );
        // A receiver facing away gets nothing; one beside the source, facing it, gets a horizon-clipped part.
        assert_eq!(
            lambert_polygon_lux(&square(1.0), l, DVec3::new(0.0, 0.0, -1.0), -DVec3::Z),
            0.0
        );
        let side = lambert_polygon_lux(&square(1.0), l, DVec3::new(0.0, 0.0, -1.0), DVec3::X);
        assert!(side > 0.0 && side.is_finite());
    }

    /// A square of side `s` at distance 1, seen `angle` degrees off the
    /// receiver's normal (+z, at the receiver): its vertices, the receiver
    /// point, and the exact illuminance for L = 1 by 8 x 8 Gauss–Legendre
    /// quadrature of the point kernel (error ~ s^16, exact in f64 here).
    fn square_case(s: f64, angle: f64) -> (Vec<DVec3>, DVec3, f64) {
        let (sa, ca) = crate::model::frame::sin_cos_deg(angle);
        let centre = DVec3::new(sa, 0.0, 0.0);
        let x = DVec3::new(0.0, 0.0, -ca);
        let kernel = |p: DVec3| {
            let v = x - p;
            let r = v.length();
            (-DVec3::Z).dot(v) / r * DVec3::Z.dot(-v) / r / (r * r)
        };
        // The polygon as stored: its corners are rounded to f64 around the
        // centre, so integrate over the rectangle they actually span.
        let verts: Vec<DVec3> = square(s).into_iter().map(|v| v + centre).collect();
        let (lo, hi) = (verts[0], verts[2]);
        let (a, b) = (hi.x - lo.x, hi.y - lo.y);
        let mid = (lo + hi) / 2.0;
        let gl = crate::reconstruct::sh::gauss_legendre(8);
        let mut exact = 0.0;
        for &(u, wu) in &gl {
            for &(v, wv) in &gl {
                exact += wu * wv * kernel(mid + DVec3::new(u * a / 2.0, v * b / 2.0, 0.0));
            }
        }
        (verts, x, exact * a * b / 4.0)
    }

    #[test]
    fn point_form_switch_is_where_the_errors_cross() {
        let sizes: Vec<f64> = (8..=30).map(|k| 10f64.powf(-k as f64 / 4.0)).collect();
        for angle in [0.0, 45.0, 80.0] {
            let rel = |e: f64, exact: f64| (e - exact).abs() / exact;
            // Where the point form becomes better than Lambert's formula (side s; extent s·√2).
            let cross = sizes.iter().copied().find(|&s| {
                let (verts, x, exact) = square_case(s, angle);
                let c = verts.iter().copied().sum::<DVec3>() / 4.0;
                let v = x - c;
                let point = s * s * (-DVec3::Z).dot(v) * DVec3::Z.dot(-v) / v.length().powi(4);
                rel(point, exact) < rel(lambert_formula_lux(&verts, 1.0, x, DVec3::Z), exact)
            });
            if angle > 0.0 {
                let ratio = cross.expect("the errors cross") * 2f64.sqrt();
                assert!(
                    ratio > POINT_FORM_RATIO / 10.0 && ratio < POINT_FORM_RATIO * 10.0,
                    "{angle} deg: crossover at {ratio:e}, switch at {POINT_FORM_RATIO:e}"
                );
            }
            // With the switch, both regimes stay within 5e-10 at every size.
            for &s in &sizes {
                let (verts, x, exact) = square_case(s, angle);
                let err = rel(lambert_polygon_lux(&verts, 1.0, x, DVec3::Z), exact);
                assert!(err < 5e-10, "{angle} deg, side {s:e}: {err:e}");
            }
        }
    }
}
