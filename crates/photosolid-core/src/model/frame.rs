//! The luminaire frame: the one conversion between (C, γ) and directions.
//!
//! C0 = +x (the luminaire's length), C90 = +y, counter-clockwise seen from
//! above; γ = 0 is the nadir (−z), γ = 180 the zenith (+z):
//!
//! `d = (sin γ cos C, sin γ sin C, −cos γ)`, and back
//! `γ = acos(−d_z)`, `C = atan2(d_y, d_x) mod 360` (degrees).
//!
//! Sines and cosines of angles in degrees are exact at every multiple of 90°
//! (the poles, the horizon, C0/C90/C180/C270), so a direction on an axis has
//! exact zero components: a 90° cut-off, a plane through the axis or a
//! horizon ring then behaves the same in every quadrant. Everything in the
//! crate that turns angles into vectors or back goes through this module.

use glam::{DVec3, Vec3};

/// `(sin a, cos a)` of an angle in degrees, exact at multiples of 90°.
///
/// The angle is reduced to the nearest multiple of 90° plus a remainder in
/// [−45°, 45°] before the trigonometry, so the quadrant swap is exact and the
/// remainder's sine and cosine are as accurate as `f64::sin_cos` allows.
/// Non-finite input gives NaN components (callers check finiteness first).
#[inline]
pub fn sin_cos_deg(a_deg: f64) -> (f64, f64) {
    if !a_deg.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let quarter = (a_deg / 90.0).round();
    let rest = a_deg - 90.0 * quarter;
    let (s, c) = if rest == 0.0 {
        (0.0, 1.0)
    } else {
        rest.to_radians().sin_cos()
    };
    // rem_euclid of an integral f64 is exact; quadrant in 0..4.
    match quarter.rem_euclid(4.0) as u8 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// sin of an angle in degrees, exact at multiples of 90°.
#[inline]
pub fn sin_deg(a_deg: f64) -> f64 {
    sin_cos_deg(a_deg).0
}

/// cos of an angle in degrees, exact at multiples of 90°.
#[inline]
pub fn cos_deg(a_deg: f64) -> f64 {
    sin_cos_deg(a_deg).1
}

/// The unit direction (luminaire frame) of (C, γ) in degrees.
#[inline]
pub fn direction(c_deg: f64, gamma_deg: f64) -> DVec3 {
    let (sg, cg) = sin_cos_deg(gamma_deg);
    let (sc, cc) = sin_cos_deg(c_deg);
    DVec3::new(sg * cc, sg * sc, -cg)
}

/// [`direction`] of every (C, γ) of a grid (degrees), plane-major (all γ of the first
/// plane, then the next): the same bits as calling [`direction`] per pair, with one
/// sine and cosine per angle instead of two per pair.
pub fn grid_directions(c_deg: &[f64], gamma_deg: &[f64]) -> Vec<DVec3> {
    let g: Vec<(f64, f64)> = gamma_deg.iter().map(|&a| sin_cos_deg(a)).collect();
    let mut out = Vec::with_capacity(c_deg.len() * g.len());
    for &c in c_deg {
        let (sc, cc) = sin_cos_deg(c);
        out.extend(g.iter().map(|&(sg, cg)| DVec3::new(sg * cc, sg * sc, -cg)));
    }
    out
}

/// [`direction`] in single precision (the shader's input).
#[inline]
pub fn direction_f32(c_deg: f64, gamma_deg: f64) -> Vec3 {
    direction(c_deg, gamma_deg).as_vec3()
}

/// (C, γ) in degrees of a direction of any length, C in [0, 360), γ in
/// [0, 180]. At a pole C is 0. `None` for a zero or non-finite vector.
#[inline]
pub fn angles(d: DVec3) -> Option<(f64, f64)> {
    let u = d.try_normalize()?;
    Some(unit_angles(u))
}

/// (C, γ) in degrees of a unit direction (no normalisation: the caller
/// guarantees |u| = 1 and finite components).
#[inline]
pub fn unit_angles(u: DVec3) -> (f64, f64) {
    let gamma = (-u.z).clamp(-1.0, 1.0).acos().to_degrees();
    let c = if u.x == 0.0 && u.y == 0.0 {
        0.0
    } else {
        super::wrap360(u.y.atan2(u.x).to_degrees())
    };
    (c, gamma)
}

/// [`unit_angles`] with every step in f32, as a shader computes it:
/// (C in [0, 360), γ in [0, 180]) degrees of the unit vector `u`.
pub fn unit_angles_f32(u: glam::Vec3) -> (f32, f32) {
    let gamma = (-u.z).clamp(-1.0, 1.0).acos().to_degrees();
    let c = if u.x == 0.0 && u.y == 0.0 {
        0.0
    } else {
        let c = u.y.atan2(u.x).to_degrees();
        // c + 360 may round up to 360 itself for a tiny negative c.
        let c = if c < 0.0 { c + 360.0 } else { c };
        if c >= 360.0 {
            0.0
        } else {
            c
        }
    };
    (c, gamma)
}

/// A luminaire-frame vector (z up) in the y-up OpenGL frame of Zotti et al. 2005: `(x, z, −y)`.
#[inline]
pub fn to_gl(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.z, -v.y)
}

/// A y-up OpenGL-frame vector back in the luminaire frame (inverse of [`to_gl`]).
#[inline]
pub fn from_gl(v: DVec3) -> DVec3 {
    DVec3::new(v.x, -v.z, v.y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_on_the_axes() {
        assert_eq!(direction(0.0, 0.0), DVec3::new(0.0, 0.0, -1.0));
        assert_eq!(direction(123.0, 180.0).z, 1.0);
        assert_eq!(direction(0.0, 90.0), DVec3::new(1.0, 0.0, 0.0));
        assert_eq!(direction(90.0, 90.0), DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(direction(180.0, 90.0), DVec3::new(-1.0, 0.0, 0.0));
        assert_eq!(direction(270.0, 90.0), DVec3::new(0.0, -1.0, 0.0));
        assert_eq!(direction(-90.0, 90.0), DVec3::new(0.0, -1.0, 0.0));
        assert_eq!(direction(450.0, 90.0), DVec3::new(0.0, 1.0, 0.0));
        for a in [0.0, 90.0, 180.0, 270.0, 360.0, -180.0] {
            let (s, c) = sin_cos_deg(a);
            assert!(s.abs() == 0.0 || s.abs() == 1.0);
            assert!(c.abs() == 0.0 || c.abs() == 1.0);
        }
    }

    #[test]
    fn grid_directions_are_direction_bit_for_bit() {
        let c: Vec<f64> = (0..37).map(|k| k as f64 * 9.7).collect();
        let g: Vec<f64> = (0..=60).map(|k| k as f64 * 3.0 + 0.25).collect();
        let all = grid_directions(&c, &g);
        assert_eq!(all.len(), c.len() * g.len());
        for (i, &cc) in c.iter().enumerate() {
            for (j, &gg) in g.iter().enumerate() {
                assert_eq!(all[i * g.len() + j], direction(cc, gg));
            }
        }
    }

    #[test]
    fn agrees_with_std_elsewhere() {
        for i in -720..=720 {
            let a = i as f64 * 0.37;
            let (s, c) = sin_cos_deg(a);
            let (s0, c0) = a.to_radians().sin_cos();
            assert!(
                (s - s0).abs() < 1e-15 && (c - c0).abs() < 1e-15,
                "{a}: {s} {s0} {c} {c0}"
            );
        }
    }

    #[test]
    fn round_trip() {
        for ic in 0..72 {
            for ig in 1..36 {
                let (c, g) = (ic as f64 * 5.0, ig as f64 * 5.0);
                let (c2, g2) = angles(direction(c, g) * 3.0).unwrap();
                assert!((c - c2).abs() < 1e-9 && (g - g2).abs() < 1e-9, "{c} {g} -> {c2} {g2}");
            }
        }
        assert_eq!(angles(DVec3::new(0.0, 0.0, -2.0)), Some((0.0, 0.0)));
        assert_eq!(angles(DVec3::new(0.0, 0.0, 1.0)), Some((0.0, 180.0)));
        assert_eq!(angles(DVec3::ZERO), None);
        assert_eq!(angles(DVec3::new(f64::NAN, 0.0, 1.0)), None);
        let v = DVec3::new(0.3, -0.2, 0.9);
        assert_eq!(from_gl(to_gl(v)), v);
    }
}
