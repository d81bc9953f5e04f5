//! Luminous openings as files declare them, and their directional area
//! source (equal-share patches; see `photosolid::scene::near_field` for the models).

use std::f64::consts::PI;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::ModelError;
use crate::model::{Format, Luminaire};

/// A luminous opening, in metres, in the luminaire frame (centred on the
/// photometric centre; a flat opening lies in the plane z = 0 and emits
/// downwards, as the far-field distribution says).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Opening {
    /// No luminous dimensions: a point source.
    Point,
    /// A horizontal rectangle, `length_m` along C0 (x), `width_m` along C90 (y).
    Rectangle {
        /// Along x, m.
        length_m: f64,
        /// Along y, m.
        width_m: f64,
    },
    /// A horizontal ellipse (a disk when both diameters are equal).
    Ellipse {
        /// Diameter along x, m.
        length_m: f64,
        /// Diameter along y, m.
        width_m: f64,
    },
    /// A vertical ellipse in the y–z plane (facing ±x).
    VerticalEllipse {
        /// Diameter along y, m.
        width_m: f64,
        /// Diameter along z, m.
        height_m: f64,
    },
    /// A box with luminous sides, centred on the photometric centre.
    Box(Extent3),
    /// A cylinder along one axis (0 = x, 1 = y, 2 = z), centred.
    Cylinder(CylinderShape),
    /// An ellipsoid (a sphere when all three diameters are equal), centred.
    Ellipsoid(Extent3),
    /// An EULUMDAT luminous area: a horizontal rectangle (or a disk when
    /// `width_m` is 0) at z = 0 with luminous sides rising to the heights
    /// declared for the C0, C90, C180 and C270 planes.
    LdtArea {
        /// Length (or diameter), m.
        length_m: f64,
        /// Width, m; 0 for a circular area.
        width_m: f64,
        /// Luminous heights on the C0, C90, C180, C270 sides, m.
        heights_m: [f64; 4],
    },
}

/// The three extents of a solid opening (a box's sides or an ellipsoid's
/// diameters), m, along the luminaire frame's axes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Extent3 {
    /// Along x (C0), m.
    pub length_m: f64,
    /// Along y (C90), m.
    pub width_m: f64,
    /// Along z (up), m.
    pub height_m: f64,
}

/// A centred cylinder's size and axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderShape {
    /// The axis: 0 = x, 1 = y, 2 = z.
    pub axis: u8,
    /// Length along the axis, m.
    pub length_m: f64,
    /// Cross-section diameter along the first other axis (x for a z cylinder, else y), m.
    pub diameter_a_m: f64,
    /// Cross-section diameter along the second other axis (y for a z cylinder, else z), m.
    pub diameter_b_m: f64,
}

impl Opening {
    /// The opening `lum` declares: IES LM-63 signs (docs/domain.md §1.3; the
    /// 1986/1991 and 1995 encodings by the file's version) or the EULUMDAT
    /// luminous area and heights.
    ///
    /// # Errors
    /// A sign combination no LM-63 version defines, as a sentence naming the values.
    pub fn of_luminaire(lum: &Luminaire) -> Result<Opening, ModelError> {
        let o = lum.luminous_opening();
        // EULUMDAT dimensions, read from the file or kept in a TM-33 document
        // we wrote (which then carries the four heights too).
        if lum.format() == Format::Ldt || (lum.format() == Format::Tm33 && lum.luminous_heights_m().is_some()) {
            let heights = lum.luminous_heights_m().unwrap_or([o.height_m; 4]);
            return Self::ldt(o.length_m, o.width_m, heights);
        }
        let old = matches!(lum.version(), "LM-63-1986" | "LM-63-1991");
        Self::ies(o.width_m, o.length_m, o.height_m, old, lum.version() == "LM-63-1995")
    }

    /// An EULUMDAT luminous area (metres; width 0 = circular).
    pub fn ldt(length_m: f64, width_m: f64, heights_m: [f64; 4]) -> Result<Opening, ModelError> {
        let all = [
            length_m,
            width_m,
            heights_m[0],
            heights_m[1],
            heights_m[2],
            heights_m[3],
        ];
        if all.iter().any(|v| !v.is_finite() || *v < 0.0) {
            return Err(ModelError::Opening(format!(
                "luminous area {length_m} x {width_m} m, heights {heights_m:?} m: expected finite values >= 0"
            )));
        }
        Ok(match (length_m > 0.0, heights_m.iter().any(|&h| h > 0.0)) {
            (false, _) => Opening::Point,
            (true, false) if width_m == 0.0 => Opening::Ellipse {
                length_m,
                width_m: length_m,
            },
            (true, false) => Opening::Rectangle { length_m, width_m },
            (true, true) => Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            },
        })
    }

    /// An IES opening from the signed width, length and height (metres).
    /// `old`: LM-63-1986/1991 rules (width first); `v1995`: the 1995 sphere.
    pub fn ies(w: f64, l: f64, h: f64, old: bool, v1995: bool) -> Result<Opening, ModelError> {
        if ![w, l, h].iter().all(|v| v.is_finite()) {
            return Err(ModelError::Opening(format!(
                "luminous opening W {}, L {}, H {} m: expected finite numbers",
                crate::numfmt::trimmed(w, 6),
                crate::numfmt::trimmed(l, 6),
                crate::numfmt::trimmed(h, 6)
            )));
        }
        Self::ies_shape(w, l, h, old, v1995).ok_or_else(|| {
            ModelError::Opening(format!(
                "luminous opening signs W {}, L {}, H {} m match no LM-63 shape (point, rectangle, box, disk or \
                 ellipse, cylinder, sphere or ellipsoid, vertical disk)",
                crate::numfmt::trimmed(w, 6),
                crate::numfmt::trimmed(l, 6),
                crate::numfmt::trimmed(h, 6)
            ))
        })
    }

    /// LM-63's table of shapes by the signs of the (finite) width, length and
    /// height (metres); None for a combination the table does not list.
    fn ies_shape(w: f64, l: f64, h: f64, old: bool, v1995: bool) -> Option<Opening> {
        let s = |v: f64| {
            if v > 0.0 {
                1
            } else if v < 0.0 {
                -1
            } else {
                0
            }
        };
        let (aw, al, ah) = (w.abs(), l.abs(), h.abs());
        Some(match (s(w), s(l), s(h)) {
            (0, 0, 0) => Opening::Point,
            (1, 1, 0) => Opening::Rectangle {
                length_m: al,
                width_m: aw,
            },
            (1, 1, 1) => Opening::Box(Extent3 {
                length_m: al,
                width_m: aw,
                height_m: ah,
            }),
            (-1, -1, 0) => Opening::Ellipse {
                length_m: al,
                width_m: aw,
            },
            (-1, 0, 0) if old => Opening::Ellipse {
                length_m: aw,
                width_m: aw,
            },
            (-1, -1, 1) => Opening::Cylinder(CylinderShape {
                axis: 2,
                length_m: ah,
                diameter_a_m: al,
                diameter_b_m: aw,
            }),
            (-1, 0, 1) if old => Opening::Cylinder(CylinderShape {
                axis: 2,
                length_m: ah,
                diameter_a_m: aw,
                diameter_b_m: aw,
            }),
            (-1, -1, -1) => Opening::Ellipsoid(Extent3 {
                length_m: al,
                width_m: aw,
                height_m: ah,
            }),
            (-1, 0, -1) if v1995 => Opening::Ellipsoid(Extent3 {
                length_m: aw,
                width_m: aw,
                height_m: aw,
            }),
            (-1, 1, -1) => Opening::Cylinder(CylinderShape {
                axis: 0,
                length_m: al,
                diameter_a_m: aw,
                diameter_b_m: ah,
            }),
            (1, -1, -1) => Opening::Cylinder(CylinderShape {
                axis: 1,
                length_m: aw,
                diameter_a_m: al,
                diameter_b_m: ah,
            }),
            (-1, 0, -1) => Opening::VerticalEllipse {
                width_m: aw,
                height_m: ah,
            },
            (0, -1, -1) => Opening::VerticalEllipse {
                width_m: al,
                height_m: ah,
            },
            _ => return None,
        })
    }

    /// The opening in EULUMDAT's terms: luminous length and width (width 0 for
    /// a disk) and the luminous heights on the C0, C90, C180 and C270 sides,
    /// metres; with a note naming what EULUMDAT cannot hold (an ellipse, a
    /// cylinder lying down, an ellipsoid, a vertical disk), written then as
    /// its footprint: a disk of the same area for an upright ellipse or
    /// elliptic cylinder, else the bounding rectangle with the height as
    /// luminous sides.
    pub fn to_ldt(&self) -> (f64, f64, [f64; 4], Option<String>) {
        let footprint = |what: &str, l: f64, w: f64, h: f64| {
            (
                l,
                w,
                [h; 4],
                Some(format!(
                    "EULUMDAT holds rectangles and disks with luminous sides: the {what} is written as its \
                     bounding {} x {} mm rectangle{}",
                    crate::numfmt::trimmed(1000.0 * l, 1),
                    crate::numfmt::trimmed(1000.0 * w, 1),
                    if h > 0.0 {
                        format!(" with {} mm luminous sides", crate::numfmt::trimmed(1000.0 * h, 1))
                    } else {
                        String::new()
                    }
                )),
            )
        };
        let disk_of_area = |what: &str, a: f64, b: f64, h: f64| {
            let d = (a * b).sqrt();
            (
                d,
                0.0,
                [h; 4],
                Some(format!(
                    "EULUMDAT holds disks, not ellipses: the {what} ({} x {} mm) is written as a disk of the same \
                     area ({} mm)",
                    crate::numfmt::trimmed(1000.0 * a, 1),
                    crate::numfmt::trimmed(1000.0 * b, 1),
                    crate::numfmt::trimmed(1000.0 * d, 1)
                )),
            )
        };
        match *self {
            Opening::Point => (0.0, 0.0, [0.0; 4], None),
            Opening::Rectangle { length_m, width_m } => (length_m, width_m, [0.0; 4], None),
            Opening::Ellipse { length_m, width_m } if length_m == width_m => (length_m, 0.0, [0.0; 4], None),
            Opening::Ellipse { length_m, width_m } => disk_of_area("ellipse", length_m, width_m, 0.0),
            Opening::Box(e) => (e.length_m, e.width_m, [e.height_m; 4], None),
            Opening::Cylinder(c) if c.axis == 2 && c.diameter_a_m == c.diameter_b_m => {
                (c.diameter_a_m, 0.0, [c.length_m; 4], None)
            }
            Opening::Cylinder(c) if c.axis == 2 => {
                disk_of_area("elliptic cylinder", c.diameter_a_m, c.diameter_b_m, c.length_m)
            }
            Opening::Cylinder(c) if c.axis == 0 => {
                footprint("horizontal cylinder", c.length_m, c.diameter_a_m, c.diameter_b_m)
            }
            Opening::Cylinder(c) => footprint("horizontal cylinder", c.diameter_a_m, c.length_m, c.diameter_b_m),
            Opening::Ellipsoid(e) => footprint("ellipsoid", e.length_m, e.width_m, e.height_m),
            Opening::VerticalEllipse { width_m, height_m } => footprint("vertical disk", 0.0, width_m, height_m),
            Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            } => (length_m, width_m, heights_m, None),
        }
    }

    /// The opening in LM-63-2002/2019's signed width, length and height
    /// (metres), with a note naming what LM-63 cannot hold (an EULUMDAT area
    /// whose luminous sides differ in height: written with the tallest).
    pub fn to_ies(&self) -> (f64, f64, f64, Option<String>) {
        match *self {
            Opening::Point => (0.0, 0.0, 0.0, None),
            Opening::Rectangle { length_m, width_m } => (width_m, length_m, 0.0, None),
            Opening::Ellipse { length_m, width_m } => (-width_m, -length_m, 0.0, None),
            Opening::Box(e) => (e.width_m, e.length_m, e.height_m, None),
            Opening::Ellipsoid(e) => (-e.width_m, -e.length_m, -e.height_m, None),
            Opening::VerticalEllipse { width_m, height_m } => (-width_m, 0.0, -height_m, None),
            Opening::Cylinder(c) => match c.axis {
                2 => (-c.diameter_b_m, -c.diameter_a_m, c.length_m, None),
                0 => (-c.diameter_a_m, c.length_m, -c.diameter_b_m, None),
                _ => (c.length_m, -c.diameter_a_m, -c.diameter_b_m, None),
            },
            Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            } => {
                let h = heights_m.iter().fold(0.0f64, |a, &b| a.max(b));
                let note = heights_m.iter().any(|&x| x != h).then(|| {
                    format!(
                        "LM-63 holds one luminous height: the EULUMDAT heights {:?} mm (C0, C90, C180, C270) are \
                         written as {} mm",
                        heights_m.map(|x| 1000.0 * x),
                        crate::numfmt::trimmed(1000.0 * h, 1)
                    )
                });
                if width_m == 0.0 {
                    (-length_m, -length_m, h, note)
                } else {
                    (width_m, length_m, h, note)
                }
            }
        }
    }

    /// Check an opening given in a scene: every size finite and ≥ 0, a cylinder axis 0, 1 or 2.
    pub fn check(&self) -> Result<(), ModelError> {
        let sizes: Vec<f64> = match *self {
            Opening::Point => vec![],
            Opening::Rectangle { length_m, width_m } | Opening::Ellipse { length_m, width_m } => {
                vec![length_m, width_m]
            }
            Opening::VerticalEllipse { width_m, height_m } => vec![width_m, height_m],
            Opening::Box(e) | Opening::Ellipsoid(e) => vec![e.length_m, e.width_m, e.height_m],
            Opening::Cylinder(cyl) => {
                if cyl.axis > 2 {
                    return Err(ModelError::Opening(format!(
                        "cylinder axis {}: expected 0 (x), 1 (y) or 2 (z)",
                        cyl.axis
                    )));
                }
                vec![cyl.length_m, cyl.diameter_a_m, cyl.diameter_b_m]
            }
            Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            } => [length_m, width_m].into_iter().chain(heights_m).collect(),
        };
        match sizes.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
            Some(v) => Err(ModelError::Opening(format!("size {v}: expected finite metres >= 0"))),
            None => Ok(()),
        }
    }

    /// Whether the opening has no extent (a point source).
    pub fn is_point(&self) -> bool {
        self.largest_dimension_m() == 0.0
    }

    /// The largest extent of the opening, m (what the five-times rule scales).
    pub fn largest_dimension_m(&self) -> f64 {
        match *self {
            Opening::Point => 0.0,
            Opening::Rectangle { length_m, width_m } => length_m.hypot(width_m),
            Opening::Ellipse { length_m, width_m } => length_m.max(width_m),
            Opening::VerticalEllipse { width_m, height_m } => width_m.max(height_m),
            Opening::Box(e) => DVec3::new(e.length_m, e.width_m, e.height_m).length(),
            Opening::Cylinder(CylinderShape {
                length_m,
                diameter_a_m,
                diameter_b_m,
                ..
            }) => length_m.hypot(diameter_a_m.max(diameter_b_m)),
            Opening::Ellipsoid(e) => e.length_m.max(e.width_m).max(e.height_m),
            Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            } => {
                let foot = if width_m == 0.0 {
                    length_m
                } else {
                    length_m.hypot(width_m)
                };
                foot.hypot(heights_m.iter().copied().fold(0.0, f64::max))
            }
        }
    }

    /// Whether `p` (luminaire frame, m) lies on or inside the opening: a
    /// receiver there has no defined illuminance. A flat opening counts
    /// points within 1e-9 of its size from its plane.
    pub fn contains(&self, p: DVec3) -> bool {
        let tol = 1e-9 * self.largest_dimension_m().max(1e-3);
        let in_ellipse = |a: f64, b: f64, da: f64, db: f64| {
            da > 0.0 && db > 0.0 && (2.0 * a / da).powi(2) + (2.0 * b / db).powi(2) <= 1.0 + 1e-12
        };
        let within = |v: f64, size: f64| v.abs() <= size / 2.0 + tol;
        match *self {
            Opening::Point => p.length() <= tol,
            Opening::Rectangle { length_m, width_m } => {
                p.z.abs() <= tol && within(p.x, length_m) && within(p.y, width_m)
            }
            Opening::Ellipse { length_m, width_m } => p.z.abs() <= tol && in_ellipse(p.x, p.y, length_m, width_m),
            Opening::VerticalEllipse { width_m, height_m } => {
                p.x.abs() <= tol && in_ellipse(p.y, p.z, width_m, height_m)
            }
            Opening::Box(e) => within(p.x, e.length_m) && within(p.y, e.width_m) && within(p.z, e.height_m),
            Opening::Cylinder(cyl) => {
                let (along, a, b) = cylinder_coords(cyl.axis, p);
                within(along, cyl.length_m) && in_ellipse(a, b, cyl.diameter_a_m, cyl.diameter_b_m)
            }
            Opening::Ellipsoid(e) => {
                e.length_m > 0.0
                    && e.width_m > 0.0
                    && e.height_m > 0.0
                    && (2.0 * p.x / e.length_m).powi(2)
                        + (2.0 * p.y / e.width_m).powi(2)
                        + (2.0 * p.z / e.height_m).powi(2)
                        <= 1.0 + 1e-12
            }
            Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            } => {
                let top = heights_m.iter().copied().fold(0.0, f64::max);
                let foot = if width_m == 0.0 {
                    in_ellipse(p.x, p.y, length_m, length_m)
                } else {
                    within(p.x, length_m) && within(p.y, width_m)
                };
                foot && p.z >= -tol && p.z <= top + tol
            }
        }
    }

    /// The directional area source at subdivision `n` (≥ 1): patch centres
    /// (luminaire frame, m) and their shares (summing to 1). A point opening
    /// is one patch at the centre whatever `n`. Patch counts: n² for a
    /// rectangle, 4n² for an ellipse (n equal-area rings × 4n sectors), n³
    /// for a box, 4n³ for a cylinder or an ellipsoid, up to 5n² (4n² + n² per
    /// lit side) for an EULUMDAT area.
    pub fn patches(&self, n: usize) -> Vec<(DVec3, f64)> {
        let n = n.max(1);
        let mut out = Vec::new();
        match *self {
            Opening::Point => out.push((DVec3::ZERO, 1.0)),
            Opening::Rectangle { length_m, width_m } => {
                for i in 0..n {
                    for j in 0..n {
                        let p = DVec3::new((mid(i, n) - 0.5) * length_m, (mid(j, n) - 0.5) * width_m, 0.0);
                        out.push((p, 1.0));
                    }
                }
            }
            Opening::Ellipse { length_m, width_m } => {
                for (a, b, w) in disk_points(n) {
                    out.push((DVec3::new(a * length_m / 2.0, b * width_m / 2.0, 0.0), w));
                }
            }
            Opening::VerticalEllipse { width_m, height_m } => {
                for (a, b, w) in disk_points(n) {
                    out.push((DVec3::new(0.0, a * width_m / 2.0, b * height_m / 2.0), w));
                }
            }
            Opening::Box(e) => box_patches(e, n, &mut out),
            Opening::Cylinder(cyl) => cylinder_patches(cyl, n, &mut out),
            Opening::Ellipsoid(e) => ellipsoid_patches(e, n, &mut out),
            Opening::LdtArea {
                length_m,
                width_m,
                heights_m,
            } => ldt_patches(length_m, width_m, heights_m, n, &mut out),
        }
        let total: f64 = out.iter().map(|p| p.1).sum();
        if total > 0.0 {
            for p in &mut out {
                p.1 /= total;
            }
        }
        out
    }
}

/// (along, a, b) coordinates of `p` for a cylinder along `axis`.
fn cylinder_coords(axis: u8, p: DVec3) -> (f64, f64, f64) {
    match axis {
        0 => (p.x, p.y, p.z),
        1 => (p.y, p.x, p.z),
        _ => (p.z, p.x, p.y),
    }
}

/// The middle of cell `i` of `k` equal cells of (0, 1).
fn mid(i: usize, k: usize) -> f64 {
    (i as f64 + 0.5) / k as f64
}

/// n³ equal cells of a box (centres, weight 1 each).
fn box_patches(e: Extent3, n: usize, out: &mut Vec<(DVec3, f64)>) {
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let p = DVec3::new(
                    (mid(i, n) - 0.5) * e.length_m,
                    (mid(j, n) - 0.5) * e.width_m,
                    (mid(k, n) - 0.5) * e.height_m,
                );
                out.push((p, 1.0));
            }
        }
    }
}

/// A cylinder's cells: the disk's points (with their weights) times n steps along the axis.
fn cylinder_patches(cyl: CylinderShape, n: usize, out: &mut Vec<(DVec3, f64)>) {
    for (a, b, w) in disk_points(n) {
        for k in 0..n {
            let along = (mid(k, n) - 0.5) * cyl.length_m;
            let (a, b) = (a * cyl.diameter_a_m / 2.0, b * cyl.diameter_b_m / 2.0);
            let p = match cyl.axis {
                0 => DVec3::new(along, a, b),
                1 => DVec3::new(a, along, b),
                _ => DVec3::new(a, b, along),
            };
            out.push((p, w));
        }
    }
}

/// An ellipsoid's cells, of equal volume: uniform in r³, cos θ and φ (weight 1 each).
fn ellipsoid_patches(e: Extent3, n: usize, out: &mut Vec<(DVec3, f64)>) {
    for i in 0..n {
        let r = mid(i, n).cbrt();
        for j in 0..n {
            let ct = 2.0 * mid(j, n) - 1.0;
            let st = (1.0 - ct * ct).max(0.0).sqrt();
            for k in 0..4 * n {
                let (sp, cp) = crate::model::frame::sin_cos_deg(360.0 * mid(k, 4 * n));
                let u = DVec3::new(st * cp, st * sp, ct) * r;
                out.push((u * DVec3::new(e.length_m, e.width_m, e.height_m) / 2.0, 1.0));
            }
        }
    }
}

/// Equal-area points of the unit disk: n rings (uniform in ρ²) × 4n sectors,
/// each with weight 1 (midpoint rule in ρ² and angle).
fn disk_points(n: usize) -> Vec<(f64, f64, f64)> {
    let mut out = Vec::with_capacity(4 * n * n);
    for i in 0..n {
        let rho = ((i as f64 + 0.5) / n as f64).sqrt();
        for k in 0..4 * n {
            let (s, c) = crate::model::frame::sin_cos_deg(360.0 * (k as f64 + 0.5) / (4 * n) as f64);
            out.push((rho * c, rho * s, 1.0));
        }
    }
    out
}

/// Patches of an EULUMDAT area: the base (rectangle or disk) and the lit
/// sides, each weighted by its area.
fn ldt_patches(length: f64, width: f64, heights: [f64; 4], n: usize, out: &mut Vec<(DVec3, f64)>) {
    if width == 0.0 {
        let r = length / 2.0;
        let base_w = PI * r * r / (4 * n * n) as f64;
        for (a, b, _) in disk_points(n) {
            out.push((DVec3::new(a * r, b * r, 0.0), base_w));
        }
        // The wall: 4n sectors, each as high as the nearest of the four C planes.
        for k in 0..4 * n {
            let deg = 360.0 * mid(k, 4 * n);
            let h = heights[((deg + 45.0) / 90.0) as usize % 4];
            let (s, c) = crate::model::frame::sin_cos_deg(deg);
            let w = 2.0 * PI * r / (4 * n) as f64 * h / n as f64;
            for j in 0..n {
                if h > 0.0 {
                    out.push((DVec3::new(r * c, r * s, mid(j, n) * h), w));
                }
            }
        }
        return;
    }
    let base_w = length * width / (n * n) as f64;
    for i in 0..n {
        for j in 0..n {
            out.push((
                DVec3::new((mid(i, n) - 0.5) * length, (mid(j, n) - 0.5) * width, 0.0),
                base_w,
            ));
        }
    }
    // Sides: C0 at x = +L/2, C90 at y = +W/2, C180 at x = −L/2, C270 at y = −W/2.
    for (side, &h) in heights.iter().enumerate() {
        if h <= 0.0 {
            continue;
        }
        let span = if side % 2 == 0 { width } else { length };
        let w = span * h / (n * n) as f64;
        for i in 0..n {
            for j in 0..n {
                let t = (mid(i, n) - 0.5) * span;
                let z = mid(j, n) * h;
                let p = match side {
                    0 => DVec3::new(length / 2.0, t, z),
                    1 => DVec3::new(t, width / 2.0, z),
                    2 => DVec3::new(-length / 2.0, t, z),
                    _ => DVec3::new(t, -width / 2.0, z),
                };
                out.push((p, w));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ies_signs() {
        assert_eq!(Opening::ies(0.0, 0.0, 0.0, false, false).unwrap(), Opening::Point);
        assert!(matches!(
            Opening::ies(-0.2, -0.2, 0.0, false, false).unwrap(),
            Opening::Ellipse { .. }
        ));
        assert!(matches!(
            Opening::ies(-0.2, 0.5, -0.2, false, false).unwrap(),
            Opening::Cylinder(CylinderShape { axis: 0, .. })
        ));
        assert!(matches!(
            Opening::ies(-0.2, 0.0, -0.2, false, true).unwrap(),
            Opening::Ellipsoid(Extent3 { .. })
        ));
        assert!(matches!(
            Opening::ies(-0.2, 0.0, -0.2, false, false).unwrap(),
            Opening::VerticalEllipse { .. }
        ));
        assert!(Opening::ies(0.3, 0.0, 0.0, false, false).is_err());
        assert!(Opening::ies(f64::NAN, 0.0, 0.0, false, false).is_err());
    }

    #[test]
    fn patches_share_one_and_stay_inside() {
        let shapes = [
            Opening::Rectangle {
                length_m: 0.6,
                width_m: 0.3,
            },
            Opening::Ellipse {
                length_m: 0.4,
                width_m: 0.4,
            },
            Opening::VerticalEllipse {
                width_m: 0.3,
                height_m: 0.2,
            },
            Opening::Box(Extent3 {
                length_m: 0.3,
                width_m: 0.2,
                height_m: 0.1,
            }),
            Opening::Cylinder(CylinderShape {
                axis: 1,
                length_m: 1.2,
                diameter_a_m: 0.1,
                diameter_b_m: 0.1,
            }),
            Opening::Ellipsoid(Extent3 {
                length_m: 0.3,
                width_m: 0.3,
                height_m: 0.3,
            }),
            Opening::ldt(0.5, 0.2, [0.05, 0.0, 0.05, 0.0]).unwrap(),
            Opening::ldt(0.5, 0.0, [0.05, 0.05, 0.05, 0.05]).unwrap(),
        ];
        for s in shapes {
            for n in [1, 3, 8] {
                let p = s.patches(n);
                let sum: f64 = p.iter().map(|x| x.1).sum();
                assert!((sum - 1.0).abs() < 1e-12, "{s:?}");
                assert!(p.iter().all(|(x, _)| s.contains(*x)), "{s:?} n {n}");
                let centre = p.iter().map(|(x, w)| *x * *w).sum::<DVec3>();
                assert!(centre.x.abs() < 1e-12 && centre.y.abs() < 1e-12, "{s:?} {centre}");
            }
        }
    }

    /// Scene files spell a solid opening flat (`shape = "cylinder"` beside its
    /// sizes): the newtype variants keep that layout and still refuse unknown keys.
    #[test]
    fn scene_toml_layout_of_solid_openings() {
        #[derive(Deserialize)]
        struct Holder {
            opening: Opening,
        }
        let cyl: Holder = toml::from_str(
            "[opening]\nshape = \"cylinder\"\naxis = 1\nlength_m = 1.2\ndiameter_a_m = 0.1\ndiameter_b_m = 0.2\n",
        )
        .unwrap();
        assert_eq!(
            cyl.opening,
            Opening::Cylinder(CylinderShape {
                axis: 1,
                length_m: 1.2,
                diameter_a_m: 0.1,
                diameter_b_m: 0.2
            })
        );
        let json = serde_json::to_value(cyl.opening).unwrap();
        assert_eq!(json["shape"], "cylinder");
        assert_eq!(json["diameter_b_m"], 0.2);
        let b: Holder =
            toml::from_str("[opening]\nshape = \"box\"\nlength_m = 1\nwidth_m = 2\nheight_m = 3\n").unwrap();
        assert_eq!(
            b.opening,
            Opening::Box(Extent3 {
                length_m: 1.0,
                width_m: 2.0,
                height_m: 3.0
            })
        );
        let bad = toml::from_str::<Holder>(
            "[opening]\nshape = \"ellipsoid\"\nlength_m = 1\nwidth_m = 2\nheight_m = 3\ndepth_m = 4\n",
        );
        assert!(bad.is_err(), "an unknown key must be refused");
    }
}
