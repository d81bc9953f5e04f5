//! The solid of the measured directions alone: no interpolation, a Delaunay
//! triangulation (crate `spade`) of the measured directions on the sphere.
//!
//! # Parametrisation and stitching
//! Real grids are non-uniform and partial (γ 0-130.5 then 180; C steps of
//! 4/5/6°), so a grid quad split is not what the measurements say; the
//! Delaunay triangulation on the sphere is (it is the convex hull of the
//! unit directions: no direction inside any triangle's circumcircle).
//!
//! The sphere is cut along one measured γ ring, the one nearest the
//! horizontal (γ_s), into a lower part (γ ≤ γ_s) and an upper part
//! (γ ≥ γ_s). Each part is mapped to the plane by the **stereographic
//! projection** from the opposite pole (lower: r = tan(γ/2), upper:
//! r = tan((180° − γ)/2), angle C). Stereographic projection maps circles on
//! the sphere to circles in the plane, so the planar Delaunay triangulation
//! of each part *is* the spherical one; it is exactly computed by spade's
//! robust predicates. The ring at γ_s is shared: its directions lie on one
//! circle in both projections and every other direction of the part lies
//! inside (on a ring direction's ray, nearer the centre, since every
//! [`crate::model::Distribution`] is a C x γ tensor grid), so both parts
//! have that ring polygon as convex hull and share its edges exactly:
//! stitched with no gap and no overlap, no extra vertex.
//!
//! # What becomes a vertex
//! Every measured direction is one vertex (each pole once, with the
//! C-weighted mean of its plane values, [`crate::model::Distribution::with_averaged_poles`]).
//! A rotational or single-plane distribution is constant in C; it is
//! expanded to [`MeasuredOptions::rotational_planes`] planes. Planes that
//! leave a gap of 180° or more (e.g. only C0 and C180) cannot enclose the
//! axis: the gap is filled with planes every 90° or less, their values
//! linear in C between the gap's ends (the bilinear reconstruction), and
//! only those inserted directions are not measured. Outside the
//! measured γ range the intensity is zero: an unmeasured pole is added as a
//! zero direction, so the last measured ring is joined to the origin. Every
//! zero direction is the merged origin vertex (see [`crate::solid`]).

use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

use super::mesh::{Mesh, SolidInfo};
use super::{stored_radius, Units};
use crate::error::ModelError;
use crate::model::{Distribution, ANGLE_EPS};

/// Options of [`measured_solid_with`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeasuredOptions {
    /// Planes a rotational (or single-plane) distribution is expanded to,
    /// evenly spaced from C = 0. Default: 72 (5°). At least 3.
    pub rotational_planes: usize,
}

impl Default for MeasuredOptions {
    fn default() -> Self {
        Self { rotational_planes: 72 }
    }
}

/// `d` unchanged when its full-circle planes leave no gap of 180° or more;
/// otherwise a copy (no symmetry) with planes inserted in each such gap, at
/// most 90° apart, their values linear in C between the gap's ends.
fn close_c_gaps(d: &Distribution) -> Result<Distribution, ModelError> {
    let planes = d.full_planes();
    let np = planes.len();
    if np < 2 {
        return Ok(d.clone());
    }
    let gap = |i: usize| {
        let next = if i + 1 == np {
            planes[0].0 + 360.0
        } else {
            planes[i + 1].0
        };
        next - planes[i].0
    };
    if (0..np).all(|i| gap(i) < 180.0 - ANGLE_EPS) {
        return Ok(d.clone());
    }
    let mut c = Vec::new();
    for (i, p) in planes.iter().enumerate() {
        c.push(p.0);
        let g = gap(i);
        if g >= 180.0 - ANGLE_EPS {
            let pieces = (g / 90.0).ceil() as usize;
            for k in 1..pieces {
                c.push(crate::model::wrap360(p.0 + g * k as f64 / pieces as f64));
            }
        }
    }
    c.sort_by(f64::total_cmp);
    c.dedup_by(|a, b| (*a - *b).abs() <= ANGLE_EPS);
    let cd: Vec<f64> = c.iter().flat_map(|&a| crate::photometry::plane_profile(d, a)).collect();
    Distribution::new(c, d.gamma_angles_deg().to_vec(), cd, crate::model::Symmetry::None)
}

/// A direction inserted into a planar triangulation, with its direction index.
#[derive(Debug, Clone, Copy)]
struct Site {
    x: f64,
    y: f64,
    id: u32,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        Point2::new(self.x, self.y)
    }
}

/// [`measured_solid_with`] with default options.
pub fn measured_solid(d: &Distribution, units: Units) -> Result<Mesh, ModelError> {
    measured_solid_with(d, units, &MeasuredOptions::default())
}

/// The measured solid of `d` in `units` ([`Units::Peak`] normalises by the
/// largest measured value after pole averaging), with per-vertex normals.
/// See the module docs for the triangulation.
///
/// # Errors
/// [`ModelError::AllZero`] for all-zero data; [`ModelError::Angles`] when the
/// directions span no solid angle (a single γ angle, or only the poles) or
/// the C-planes leave a gap of 180° or more (the rings cannot enclose the axis).
pub fn measured_solid_with(d: &Distribution, units: Units, opts: &MeasuredOptions) -> Result<Mesh, ModelError> {
    let d = close_c_gaps(&d.with_averaged_poles())?;
    let planes = full_circle_planes(&d, opts)?;
    if d.n_gamma() < 2 {
        return Err(angles_error(
            "gamma",
            "a single γ angle spans no solid angle: there is no solid".into(),
        ));
    }
    let peak = d.max_cd();
    if peak.is_nan() || peak <= 0.0 {
        return Err(ModelError::AllZero("photometric solid"));
    }
    let scale = units.units_per_cd(peak)?;
    let rows = gamma_rows(d.gamma_angles_deg());
    let split = cut_ring(&rows)?;
    let dirs = Directions::new(planes, rows);
    let (radius, unit_dir) = dirs.radii(&d, scale, peak)?;
    let (positions, origin, vertex_of) = vertices(&radius, &unit_dir);
    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(2 * dirs.n_dirs);
    for lower in [true, false] {
        dirs.triangulate_part(lower, split, &vertex_of, &mut triangles)?;
    }
    let info = SolidInfo {
        kind: format!(
            "measured solid: Delaunay triangulation of {} measured directions ({} C-planes x {} gamma rows, poles once), stereographic per part, stitched at gamma = {}",
            dirs.n_dirs,
            dirs.planes.len(),
            dirs.rows.len(),
            dirs.rows[split].0
        ),
        source: String::new(),
        units,
        units_per_cd: scale,
    };
    Mesh::finish(positions, triangles, origin, info)
}

/// A [`ModelError::Angles`] on `axis`.
fn angles_error(axis: &'static str, reason: String) -> ModelError {
    ModelError::Angles { axis, reason }
}

/// Whether γ `a` (degrees) is a pole.
fn is_pole(a: f64) -> bool {
    a <= ANGLE_EPS || a >= 180.0 - ANGLE_EPS
}

/// `d`'s full-circle planes (angle in degrees, stored plane index); a single
/// plane expanded to [`MeasuredOptions::rotational_planes`]. Refused when two
/// neighbours are 180° or more apart (they cannot enclose the axis).
fn full_circle_planes(d: &Distribution, opts: &MeasuredOptions) -> Result<Vec<(f64, usize)>, ModelError> {
    let mut planes = d.full_planes();
    if planes.len() == 1 {
        let n = opts.rotational_planes.max(3);
        let ic = planes[0].1;
        planes = (0..n).map(|k| (k as f64 * 360.0 / n as f64, ic)).collect();
    }
    let np = planes.len();
    let widest = (0..np)
        .map(|i| {
            if i + 1 == np {
                planes[0].0 + 360.0 - planes[i].0
            } else {
                planes[i + 1].0 - planes[i].0
            }
        })
        .fold(0.0, f64::max);
    if widest >= 180.0 - ANGLE_EPS {
        return Err(angles_error(
            "C",
            format!("the C-planes leave a gap of {widest}°: the measured directions cannot enclose the axis"),
        ));
    }
    Ok(planes)
}

/// γ rows from the measured angles `g` (degrees, ascending): (angle,
/// Some(measured index) | None for an unmeasured, zero pole).
fn gamma_rows(g: &[f64]) -> Vec<(f64, Option<usize>)> {
    let mut rows: Vec<(f64, Option<usize>)> = g.iter().copied().zip((0..g.len()).map(Some)).collect();
    if g[0] > ANGLE_EPS {
        rows.insert(0, (0.0, None));
    }
    if g[g.len() - 1] < 180.0 - ANGLE_EPS {
        rows.push((180.0, None));
    }
    rows
}

/// The cut ring: the index of the inner row nearest the horizontal.
fn cut_ring(rows: &[(f64, Option<usize>)]) -> Result<usize, ModelError> {
    (0..rows.len())
        .filter(|&j| !is_pole(rows[j].0))
        .min_by(|&a, &b| (rows[a].0 - 90.0).abs().total_cmp(&(rows[b].0 - 90.0).abs()))
        .ok_or_else(|| {
            angles_error(
                "gamma",
                "only the poles are measured: the directions span no solid angle".into(),
            )
        })
}

/// The directions of the solid: row-major (all planes of a ring together),
/// poles once.
struct Directions {
    /// Full-circle planes (angle in degrees, stored plane index).
    planes: Vec<(f64, usize)>,
    /// γ rows (see [`gamma_rows`]).
    rows: Vec<(f64, Option<usize>)>,
    /// First direction index of each row.
    dir_row: Vec<usize>,
    /// Number of directions.
    n_dirs: usize,
    /// sin C of each plane.
    sin_c: Vec<f64>,
    /// cos C of each plane.
    cos_c: Vec<f64>,
}

impl Directions {
    /// The directions of `planes` x `rows`.
    fn new(planes: Vec<(f64, usize)>, rows: Vec<(f64, Option<usize>)>) -> Self {
        let mut dir_row = Vec::with_capacity(rows.len());
        let mut n_dirs = 0usize;
        for &(a, _) in &rows {
            dir_row.push(n_dirs);
            n_dirs += if is_pole(a) { 1 } else { planes.len() };
        }
        let (sin_c, cos_c) = planes.iter().map(|p| p.0.to_radians().sin_cos()).unzip();
        Self {
            planes,
            rows,
            dir_row,
            n_dirs,
            sin_c,
            cos_c,
        }
    }

    /// Each direction's stored radius (`scale` units per cd; `peak` cd) and unit vector.
    fn radii(&self, d: &Distribution, scale: f64, peak: f64) -> Result<(Vec<f64>, Vec<[f64; 3]>), ModelError> {
        let mut radius = vec![0.0f64; self.n_dirs];
        let mut unit_dir = vec![[0.0f64; 3]; self.n_dirs];
        for (j, &(a, ig)) in self.rows.iter().enumerate() {
            let (sg, cg) = a.to_radians().sin_cos();
            let value = |ic: usize| ig.map_or(0.0, |ig| d.value_cd(ic, ig));
            let first = self.dir_row[j];
            if is_pole(a) {
                radius[first] = stored_radius(value(self.planes[0].1) * scale, peak * scale)?;
                unit_dir[first] = [0.0, 0.0, if a < 90.0 { -1.0 } else { 1.0 }];
            } else {
                for (k, &(_, ic)) in self.planes.iter().enumerate() {
                    radius[first + k] = stored_radius(value(ic) * scale, peak * scale)?;
                    unit_dir[first + k] = [sg * self.cos_c[k], sg * self.sin_c[k], -cg];
                }
            }
        }
        Ok((radius, unit_dir))
    }

    /// Appends to `triangles` the Delaunay triangles of the lower part (rows
    /// up to the cut ring `split`) or the upper part (from it on), each
    /// direction as its vertex in `vertex_of`, wound outward.
    fn triangulate_part(
        &self,
        lower: bool,
        split: usize,
        vertex_of: &[u32],
        triangles: &mut Vec<[u32; 3]>,
    ) -> Result<(), ModelError> {
        let sites = self.projected_sites(lower, split);
        let n_sites = sites.len();
        let dt = DelaunayTriangulation::<Site>::bulk_load(sites)
            .map_err(|e| angles_error("direction", format!("Delaunay triangulation failed: {e:?}")))?;
        if dt.num_vertices() != n_sites {
            return Err(angles_error("direction", "two measured directions coincide".into()));
        }
        for f in dt.inner_faces() {
            let [a, b, c] = f.vertices().map(|v| vertex_of[v.data().id as usize]);
            // spade's faces are counter-clockwise in the plane; seen from
            // outside the sphere that is outward for the upper part (viewed
            // from above) and inward for the lower part (viewed from below).
            let t = if lower { [a, c, b] } else { [a, b, c] };
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                triangles.push(t);
            }
        }
        Ok(())
    }

    /// The directions of the lower or upper part in the plane, by the
    /// stereographic projection from the opposite pole.
    fn projected_sites(&self, lower: bool, split: usize) -> Vec<Site> {
        let rows_in: Vec<usize> = if lower {
            (0..=split).collect()
        } else {
            (split..self.rows.len()).collect()
        };
        let np = self.planes.len();
        let mut sites = Vec::with_capacity(rows_in.len() * np);
        for &j in &rows_in {
            let a = self.rows[j].0;
            let r = if lower {
                (a / 2.0).to_radians().tan()
            } else {
                ((180.0 - a) / 2.0).to_radians().tan()
            };
            if is_pole(a) {
                sites.push(Site {
                    x: 0.0,
                    y: 0.0,
                    id: self.dir_row[j] as u32,
                });
            } else {
                for k in 0..np {
                    // Below spade's smallest coordinate (2^-142) a value is refused; it is 0 here.
                    let snap = |v: f64| if v.abs() < 1e-30 { 0.0 } else { v };
                    sites.push(Site {
                        x: snap(r * self.cos_c[k]),
                        y: snap(r * self.sin_c[k]),
                        id: (self.dir_row[j] + k) as u32,
                    });
                }
            }
        }
        sites
    }
}

/// Mesh vertices: the origin first (if any direction has radius 0), then
/// every non-zero direction. Returns (positions, origin, vertex of each direction).
fn vertices(radius: &[f64], unit_dir: &[[f64; 3]]) -> (Vec<[f32; 3]>, Option<u32>, Vec<u32>) {
    let any_zero = radius.contains(&0.0);
    let mut positions: Vec<[f32; 3]> = Vec::with_capacity(radius.len() + 1);
    let origin = any_zero.then(|| {
        positions.push([0.0; 3]);
        0u32
    });
    let vertex_of: Vec<u32> = radius
        .iter()
        .zip(unit_dir)
        .map(|(&r, u)| {
            if r == 0.0 {
                0
            } else {
                positions.push([(r * u[0]) as f32, (r * u[1]) as f32, (r * u[2]) as f32]);
                (positions.len() - 1) as u32
            }
        })
        .collect();
    (positions, origin, vertex_of)
}
