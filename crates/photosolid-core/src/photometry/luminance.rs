//! Average luminance of the luminous opening, L = I / A_p (cd/m²), and the
//! projected area A_p (m²) it rests on.
//!
//! # Projected area
//! The opening is the one the file declares ([`Opening::of_luminaire`]: IES
//! LM-63 width/length/height signs, EULUMDAT luminous area and the four side
//! heights). Seen from the emission direction d = (sinγ cosC, sinγ sinC,
//! −cosγ), a horizontal face of area A shows A·|cos γ|, a vertical face with
//! normal n shows its area times max(0, d·n) (only the faces turned toward
//! the observer count), an ellipsoid with semi-axes a, b, c shows
//! π·sqrt((b c dx)² + (a c dy)² + (a b dz)²). This is the "projected luminous
//! area" of CIE 117 / CIE 190 that UGR and luminance tables divide by.
//!
//! # Luminance table
//! L at γ = 45°, 50°, … 85° in the C0 and C90 planes (the angles a glare
//! assessment looks at; CIE 117 luminance limit curves), intensities from the
//! bilinear interpolant of the grid. A point source (no luminous area) has no
//! luminance: the table is then absent, with the reason.

use glam::DVec3;
use serde::Serialize;

use crate::error::{ModelError, Undefined};
use crate::model::frame::direction;
use crate::model::opening::Opening;
use crate::model::{Distribution, Luminaire};

/// Projected area (m²) of `opening` seen from emission direction `d` (unit vector, luminaire frame).
pub fn projected_area_m2(opening: &Opening, d: DVec3) -> f64 {
    let (ax, ay, az) = (d.x.abs(), d.y.abs(), d.z.abs());
    let ellipse = |a: f64, b: f64| std::f64::consts::PI * a * b / 4.0;
    match *opening {
        Opening::Point => 0.0,
        Opening::Rectangle { length_m, width_m } => length_m * width_m * az,
        Opening::Ellipse { length_m, width_m } => ellipse(length_m, width_m) * az,
        Opening::VerticalEllipse { width_m, height_m } => ellipse(width_m, height_m) * ax,
        Opening::Box(e) => e.length_m * e.width_m * az + e.width_m * e.height_m * ax + e.length_m * e.height_m * ay,
        Opening::Cylinder(cyl) => {
            // Along the axis: the elliptic end; across it: the side's shadow (length × the
            // ellipse's width across the view), for a circular section d·L·sin(angle to axis).
            let (along, across) = match cyl.axis {
                0 => (ax, (d.y * cyl.diameter_b_m).hypot(d.z * cyl.diameter_a_m)),
                1 => (ay, (d.x * cyl.diameter_b_m).hypot(d.z * cyl.diameter_a_m)),
                _ => (az, (d.x * cyl.diameter_b_m).hypot(d.y * cyl.diameter_a_m)),
            };
            ellipse(cyl.diameter_a_m, cyl.diameter_b_m) * along + cyl.length_m * across
        }
        Opening::Ellipsoid(e) => {
            let (a, b, c) = (e.length_m / 2.0, e.width_m / 2.0, e.height_m / 2.0);
            std::f64::consts::PI * ((b * c * d.x).powi(2) + (a * c * d.y).powi(2) + (a * b * d.z).powi(2)).sqrt()
        }
        Opening::LdtArea {
            length_m,
            width_m,
            heights_m,
        } => {
            let circular = width_m == 0.0;
            let base = if circular {
                ellipse(length_m, length_m)
            } else {
                length_m * width_m
            };
            // Sides in the C0, C90, C180, C270 directions: widths across them.
            let (w_x, w_y) = if circular {
                (length_m, length_m)
            } else {
                (width_m, length_m)
            };
            let side = |h: f64, w: f64, dn: f64| h * w * dn.max(0.0);
            // A cylinder's side shows d·h·sinγ in total; split by cos²/sin² of C so
            // that equal heights give exactly that.
            let (kx, ky) = if circular {
                let s = (d.x * d.x + d.y * d.y).sqrt();
                if s > 0.0 {
                    (d.x.abs() / s, d.y.abs() / s)
                } else {
                    (0.0, 0.0)
                }
            } else {
                (1.0, 1.0)
            };
            base * az
                + kx * (side(heights_m[0], w_x, d.x) + side(heights_m[2], w_x, -d.x))
                + ky * (side(heights_m[1], w_y, d.y) + side(heights_m[3], w_y, -d.y))
        }
    }
}

/// γ angles (degrees) of the luminance table.
pub const TABLE_GAMMA_DEG: [f64; 9] = [45.0, 50.0, 55.0, 60.0, 65.0, 70.0, 75.0, 80.0, 85.0];

/// Luminance at the standard angles.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LuminanceTable {
    /// The γ angles, degrees.
    pub gamma_deg: Vec<f64>,
    /// Luminance in the C0 plane at each γ, cd/m² (None where A_p = 0).
    pub c0_cd_m2: Vec<Option<f64>>,
    /// Luminance in the C90 plane at each γ, cd/m².
    pub c90_cd_m2: Vec<Option<f64>>,
    /// Largest value in the table, cd/m².
    pub max_cd_m2: Option<f64>,
}

/// The bilinear interpolant of a distribution's measured grid (linear in γ
/// between rows, linear in C between neighbouring full-circle planes, as
/// [`plane_profile`](super::beam::plane_profile)), prepared for many lookups.
/// Zero outside the measured γ range.
pub struct GridLookup<'a> {
    d: &'a Distribution,
    planes: Vec<(f64, usize)>,
}

impl<'a> GridLookup<'a> {
    /// Prepare lookups into `d`.
    pub fn new(d: &'a Distribution) -> Self {
        GridLookup {
            d,
            planes: d.full_planes(),
        }
    }

    /// Intensity (cd) at (C, γ) in degrees.
    pub fn at(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        let g = self.d.gamma_angles_deg();
        let (i, t) = if g.len() == 1 {
            if (g[0] - gamma_deg).abs() > 1e-9 {
                return 0.0;
            }
            (0, 0.0)
        } else {
            if !(g[0]..=g[g.len() - 1]).contains(&gamma_deg) {
                return 0.0;
            }
            let i = g.partition_point(|&x| x <= gamma_deg).clamp(1, g.len() - 1) - 1;
            (i, (gamma_deg - g[i]) / (g[i + 1] - g[i]))
        };
        let row = |ic: usize| {
            let p = self.d.plane_cd(ic);
            if t == 0.0 {
                p[i]
            } else {
                p[i] + t * (p[i + 1] - p[i])
            }
        };
        let n = self.planes.len();
        if n == 1 {
            return row(self.planes[0].1);
        }
        let c = crate::model::wrap360(c_deg);
        let k = self.planes.partition_point(|p| p.0 <= c);
        let (lo, hi) = if k == 0 || k == n {
            (self.planes[n - 1], self.planes[0])
        } else {
            (self.planes[k - 1], self.planes[k])
        };
        let span = (hi.0 - lo.0).rem_euclid(360.0);
        let u = if span > 0.0 {
            (c - lo.0).rem_euclid(360.0) / span
        } else {
            0.0
        };
        let a = row(lo.1);
        if u == 0.0 {
            a
        } else {
            a + u * (row(hi.1) - a)
        }
    }
}

/// Intensity (cd) at (C, γ) on the bilinear interpolant of `d` (one lookup; see [`GridLookup`]).
pub fn intensity_at(d: &Distribution, c_deg: f64, gamma_deg: f64) -> f64 {
    GridLookup::new(d).at(c_deg, gamma_deg)
}

/// The luminance table of `lum`, or the reason there is none.
///
/// # Errors
/// [`ModelError::Undefined`] for a point source; [`ModelError::Opening`]
/// when the declared opening is not one this crate models.
pub fn luminance_table(lum: &Luminaire) -> Result<LuminanceTable, ModelError> {
    let opening = Opening::of_luminaire(lum)?;
    if opening.is_point() {
        return Err(ModelError::Undefined {
            quantity: "luminance",
            why: Undefined::NoLuminousArea,
        });
    }
    let d = lum.distribution();
    let at = |c: f64, g: f64| {
        let a = projected_area_m2(&opening, direction(c, g));
        (a > 0.0).then(|| intensity_at(d, c, g) / a).filter(|l| l.is_finite())
    };
    let c0: Vec<Option<f64>> = TABLE_GAMMA_DEG.iter().map(|&g| at(0.0, g)).collect();
    let c90: Vec<Option<f64>> = TABLE_GAMMA_DEG.iter().map(|&g| at(90.0, g)).collect();
    let max_cd_m2 = c0.iter().chain(&c90).flatten().copied().reduce(f64::max);
    Ok(LuminanceTable {
        gamma_deg: TABLE_GAMMA_DEG.to_vec(),
        c0_cd_m2: c0,
        c90_cd_m2: c90,
        max_cd_m2,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::opening::{CylinderShape, Extent3};
    use crate::model::Symmetry;

    /// A Lambertian emitter of uniform luminance L over a flat area A has
    /// I(γ) = L·A·cos γ, so the table must read L at every angle (the
    /// definition of luminance, CIE S 017 17-21-050).
    #[test]
    fn lambertian_panel_has_constant_luminance() {
        let (l, w, lum_cd_m2) = (0.6, 0.6, 5000.0);
        let g: Vec<f64> = (0..=90).map(f64::from).collect();
        let cd = g.iter().map(|x| lum_cd_m2 * l * w * x.to_radians().cos()).collect();
        let d = Distribution::new(vec![0.0], g, cd, Symmetry::Rotational).unwrap();
        let mut lum = Luminaire::from_distribution(d);
        lum.set_luminous_opening(crate::model::Dimensions {
            length_m: l,
            width_m: w,
            height_m: 0.0,
        });
        let t = luminance_table(&lum).unwrap();
        for v in t.c0_cd_m2.iter().chain(&t.c90_cd_m2) {
            let v = v.unwrap();
            assert!((v - lum_cd_m2).abs() < 1e-9 * lum_cd_m2, "{v}");
        }
        // No luminous area: no table, a reason instead.
        lum.set_luminous_opening(crate::model::Dimensions::default());
        let e = luminance_table(&lum).unwrap_err();
        assert!(matches!(e, ModelError::Undefined { .. }), "{e:?}");
        assert_eq!(
            e.to_string(),
            "the file declares no luminous area (point source): luminance undefined"
        );
    }

    /// Projected areas of closed shapes: a sphere of diameter D shows π D²/4
    /// from everywhere; a box shows the three faces' cosines; a cylinder's
    /// side d·L·sinθ.
    #[test]
    fn projected_areas() {
        let sphere = Opening::Ellipsoid(Extent3 {
            length_m: 2.0,
            width_m: 2.0,
            height_m: 2.0,
        });
        for (c, g) in [(0.0, 0.0), (30.0, 70.0), (200.0, 135.0)] {
            let a = projected_area_m2(&sphere, direction(c, g));
            assert!((a - std::f64::consts::PI).abs() < 1e-12);
        }
        let b = Opening::Box(Extent3 {
            length_m: 2.0,
            width_m: 1.0,
            height_m: 0.5,
        });
        let d = direction(90.0, 60.0);
        let want = 2.0 * 60f64.to_radians().cos() + 2.0 * 0.5 * 60f64.to_radians().sin();
        assert!((projected_area_m2(&b, d) - want).abs() < 1e-12);
        let cyl = Opening::Cylinder(CylinderShape {
            axis: 2,
            length_m: 1.0,
            diameter_a_m: 0.2,
            diameter_b_m: 0.2,
        });
        let d = direction(33.0, 90.0);
        assert!((projected_area_m2(&cyl, d) - 0.2).abs() < 1e-12);
        // EULUMDAT disk with equal side heights: base·|cosγ| + D·h·sinγ, at any C.
        let disk = Opening::LdtArea {
            length_m: 0.3,
            width_m: 0.0,
            heights_m: [0.05; 4],
        };
        for c in [0.0, 27.0, 90.0, 222.0] {
            let d = direction(c, 70.0);
            let want = std::f64::consts::PI * 0.0225 * 70f64.to_radians().cos() + 0.3 * 0.05 * 70f64.to_radians().sin();
            assert!((projected_area_m2(&disk, d) - want).abs() < 1e-12, "C {c}");
        }
    }

    /// The lookup is the interpolant `plane_profile` defines: equal at grid
    /// rows for any C, linear in γ between rows; zero outside the range.
    #[test]
    fn lookup_matches_plane_profile() {
        let c: Vec<f64> = (0..8).map(|k| 45.0 * f64::from(k)).collect();
        let g = vec![0.0, 10.0, 35.0, 90.0];
        let cd: Vec<f64> = c
            .iter()
            .flat_map(|&cc| g.iter().map(move |&gg| 1.0 + cc + 0.1 * gg))
            .collect();
        let d = Distribution::new(c, g.clone(), cd, Symmetry::None).unwrap();
        let look = GridLookup::new(&d);
        for cq in [0.0, 12.5, 44.9, 200.0, 337.5, 359.9, -30.0] {
            let p = super::super::beam::plane_profile(&d, cq);
            for (k, &gg) in g.iter().enumerate() {
                assert!((look.at(cq, gg) - p[k]).abs() < 1e-9, "C {cq} g {gg}");
            }
            assert!((look.at(cq, 22.5) - 0.5 * (p[1] + p[2])).abs() < 1e-9);
        }
        assert_eq!(look.at(0.0, 95.0), 0.0);
    }
}
