//! The one triangle mesh type of the crate, its quantities (volume, area,
//! normals) and its invariant checker [`Mesh::sanity_check`].
//!
//! # Layout
//! Positions are `f32` (what every export format stores), in the mesh's
//! [`Units`] (cd by default; 1 unit of length = 1 unit of intensity), in the
//! luminaire frame: z up, nadir −z, C0 = +x, C90 = +y. Triangles index the
//! positions and are wound counter-clockwise seen from outside (outward
//! normals, right-hand rule). Quantities are accumulated in `f64`.

use std::borrow::Cow;
use std::fmt;

use glam::{DVec3, Vec3};

use super::topology::{count_pinched, remove_fins, split_vertices, SHEET_SEPARATION};
use super::{Units, UNIT_FRAME};
use crate::error::ModelError;

/// What a mesh is and in which units its coordinates are. Written into the
/// metadata of every export (OBJ/PLY comments, STL header, glTF `extras`).
#[derive(Debug, Clone, PartialEq)]
pub struct SolidInfo {
    /// How the mesh was made, e.g. `measured (Delaunay of 72 x 37 directions)`.
    pub kind: String,
    /// Where the data came from (file name, synthetic kind); may be empty.
    pub source: String,
    /// Units of the coordinates.
    pub units: Units,
    /// Coordinate units per candela (1 for [`Units::Candela`]).
    pub units_per_cd: f64,
}

impl Default for SolidInfo {
    fn default() -> Self {
        Self {
            kind: "mesh".into(),
            source: String::new(),
            units: Units::Candela,
            units_per_cd: 1.0,
        }
    }
}

impl SolidInfo {
    /// One line per fact, for file comments and glTF extras, without comment markers.
    pub fn lines(&self) -> Vec<String> {
        let mut v = vec![
            "photosolid photometric solid".to_string(),
            format!("kind: {}", self.kind),
        ];
        if !self.source.is_empty() {
            v.push(format!("source: {}", self.source));
        }
        v.push(format!("units: {}", self.units.describe()));
        v.push(format!("scale: {} unit per cd", self.units_per_cd));
        v.push(format!("frame: {UNIT_FRAME}"));
        v
    }
}

/// A triangle mesh: the photometric solid or anything else closed.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    colors: Option<Vec<[u8; 3]>>,
    origin: Option<u32>,
    info: SolidInfo,
}

impl Mesh {
    /// A mesh from raw parts; indices are checked to be in range.
    /// `origin` names the vertex at (0, 0, 0) where zero-intensity regions
    /// were merged, if any (see the module docs of [`crate::solid`]).
    pub fn from_parts(
        positions: Vec<[f32; 3]>,
        triangles: Vec<[u32; 3]>,
        origin: Option<u32>,
        info: SolidInfo,
    ) -> Result<Self, ModelError> {
        let n = positions.len();
        if n > u32::MAX as usize {
            return Err(ModelError::Mesh(format!("{n} vertices do not fit 32-bit indices")));
        }
        if let Some(t) = triangles.iter().position(|t| t.iter().any(|&i| i as usize >= n)) {
            return Err(ModelError::Mesh(format!(
                "triangle #{t} {:?} indexes past the {n} vertices",
                triangles[t]
            )));
        }
        if let Some(o) = origin {
            if o as usize >= n || positions[o as usize] != [0.0; 3] {
                return Err(ModelError::Mesh(format!("origin vertex #{o} is not at (0, 0, 0)")));
            }
        }
        Ok(Self {
            positions,
            triangles,
            normals: None,
            colors: None,
            origin,
            info,
        })
    }

    /// Vertex positions, in [`SolidInfo::units`].
    pub fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }
    /// Vertex positions widened to `f64` (same units as [`Mesh::positions`]),
    /// for distance queries ([`crate::metrics::MeshRef`]).
    pub fn positions_f64(&self) -> Vec<DVec3> {
        self.positions.iter().map(p64).collect()
    }
    /// Triangles (vertex indices), counter-clockwise seen from outside.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }
    /// Unit per-vertex normals, when computed ([`Mesh::compute_normals`]).
    pub fn normals(&self) -> Option<&[[f32; 3]]> {
        self.normals.as_deref()
    }
    /// Per-vertex sRGB colours, when set ([`Mesh::colorize`]).
    pub fn colors(&self) -> Option<&[[u8; 3]]> {
        self.colors.as_deref()
    }
    /// The merged vertex at (0, 0, 0) standing for every zero-intensity direction, if any.
    pub fn origin_vertex(&self) -> Option<u32> {
        self.origin
    }
    /// What the mesh is and its units.
    pub fn info(&self) -> &SolidInfo {
        &self.info
    }
    /// Mutable metadata (e.g. to set [`SolidInfo::source`] to the file name).
    pub fn info_mut(&mut self) -> &mut SolidInfo {
        &mut self.info
    }
    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.positions.len()
    }
    /// Number of triangles.
    pub fn n_triangles(&self) -> usize {
        self.triangles.len()
    }

    /// Largest distance of a vertex from the origin: the peak intensity in
    /// the mesh's units (the solid's vertices sit at I(d) d with |d| = 1).
    pub fn max_radius(&self) -> f64 {
        self.positions.iter().map(|p| p64(p).length()).fold(0.0, f64::max)
    }

    /// Enclosed volume (units³) by the divergence theorem: Σ det(p0, p1, p2) / 6
    /// over the triangles. Positive for outward winding; exact for the polyhedron.
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = self.tri(t);
                a.dot(b.cross(c))
            })
            .sum::<f64>()
            / 6.0
    }

    /// Surface area (units²): Σ |(p1 − p0) × (p2 − p0)| / 2.
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = self.tri(t);
                (b - a).cross(c - a).length()
            })
            .sum::<f64>()
            / 2.0
    }

    #[inline]
    fn tri(&self, t: &[u32; 3]) -> [DVec3; 3] {
        [
            p64(&self.positions[t[0] as usize]),
            p64(&self.positions[t[1] as usize]),
            p64(&self.positions[t[2] as usize]),
        ]
    }

    /// Per-vertex normals: the area-weighted mean of the adjacent face
    /// normals, normalised. A vertex whose weighted sum vanishes (a cusp, e.g.
    /// the merged origin vertex between opposite sheets) gets the normalised
    /// sum of the adjacent unit face normals, and failing that its own
    /// direction from the origin, and failing that +z: never NaN, always unit.
    pub fn compute_normals(&mut self) {
        let n = self.positions.len();
        let mut acc = vec![DVec3::ZERO; n];
        for t in &self.triangles {
            let [a, b, c] = self.tri(t);
            let fnorm = (b - a).cross(c - a);
            for &i in t {
                acc[i as usize] += fnorm;
            }
        }
        let mut out = Vec::with_capacity(n);
        let mut fallback = Vec::new();
        for (i, s) in acc.iter().enumerate() {
            match s.try_normalize() {
                Some(u) => out.push(u.as_vec3().to_array()),
                None => {
                    fallback.push(i);
                    out.push([0.0, 0.0, 1.0]);
                }
            }
        }
        if !fallback.is_empty() {
            // Rare: recompute only for the few vertices that need it.
            let mut unit_acc = vec![DVec3::ZERO; fallback.len()];
            for t in &self.triangles {
                for &i in t {
                    if let Ok(k) = fallback.binary_search(&(i as usize)) {
                        let [a, b, c] = self.tri(t);
                        if let Some(u) = (b - a).cross(c - a).try_normalize() {
                            unit_acc[k] += u;
                        }
                    }
                }
            }
            for (k, &i) in fallback.iter().enumerate() {
                let u = unit_acc[k]
                    .try_normalize()
                    .or_else(|| p64(&self.positions[i]).try_normalize())
                    .unwrap_or(DVec3::Z);
                out[i] = u.as_vec3().to_array();
            }
        }
        self.normals = Some(out);
    }

    /// Colour every vertex by its distance from the origin (the intensity)
    /// relative to the largest one, through `map`: 0 at the origin, 1 at the peak.
    pub fn colorize(&mut self, map: super::ColorMap) {
        let peak = self.max_radius();
        let inv = if peak > 0.0 { 1.0 / peak } else { 0.0 };
        self.colors = Some(self.positions.iter().map(|p| map.rgb8(p64(p).length() * inv)).collect());
    }

    /// Drop the normals.
    pub fn clear_normals(&mut self) {
        self.normals = None;
    }
    /// Drop the colours.
    pub fn clear_colors(&mut self) {
        self.colors = None;
    }

    /// The last step of every solid builder: drop zero-thickness fins at the
    /// origin (and vertices left unused), refuse a solid that encloses
    /// nothing, build the mesh and its normals.
    pub(crate) fn finish(
        mut positions: Vec<[f32; 3]>,
        mut triangles: Vec<[u32; 3]>,
        mut origin: Option<u32>,
        info: SolidInfo,
    ) -> Result<Mesh, ModelError> {
        remove_fins(&mut positions, &mut triangles, &mut origin);
        if triangles.is_empty() {
            // Nothing but zero-thickness fins: non-zero only on a set of no solid angle.
            return Err(ModelError::AllZero("photometric solid (it encloses no volume)"));
        }
        let mut mesh = Mesh::from_parts(positions, triangles, origin, info)?;
        mesh.compute_normals();
        Ok(mesh)
    }

    /// Check every invariant a photometric solid must hold; see [`SanityError`]
    /// for the list. On success, returns the mesh's topology and quantities.
    ///
    /// # Topology
    /// A solid with zero-intensity regions has one merged vertex at the
    /// origin where several sheets of the surface may meet (e.g. two lobes of
    /// a batwing-like distribution that is zero between them). The check
    /// splits that vertex into one copy per cycle of its link (one per sheet,
    /// [`SanityReport::origin_sheets`]), does the same for any other vertex
    /// where two sheets touch at a point ([`SanityReport::pinch_vertices`]:
    /// a small lit sample between dark ones can make one), and then requires an orientable
    /// closed 2-manifold whose every connected component is a sphere:
    /// every edge shared by exactly two triangles with opposite directions,
    /// and Euler characteristic V − E + F = 2 per component.
    ///
    /// # Cost
    /// O(F log F) time (sorts the 3F directed edges), O(V + F) memory.
    pub fn sanity_check(&self) -> Result<SanityReport, SanityError> {
        let nv = self.positions.len();
        let nf = self.triangles.len();
        self.check_attributes()?;
        self.check_triangles()?;
        self.check_directed_edges()?;
        // Split the origin vertex into one copy per simple cycle of its link.
        let (tris, sheets, pinch_vertices, nv_split) = self.split_pinches();
        let n_edges = count_manifold_edges(&tris)?;
        let components = count_components(&tris, nv_split);
        let euler = nv_split as i64 - n_edges as i64 + nf as i64;
        // χ ≤ 2 for every connected closed surface, so the sum equals 2 per
        // component only when each component is a sphere.
        if euler != 2 * components as i64 {
            return Err(SanityError::Topology { euler, components });
        }
        let volume = self.volume();
        if volume.is_nan() || volume < 0.0 {
            return Err(SanityError::InwardFacing { volume });
        }
        Ok(SanityReport {
            vertices: nv,
            triangles: nf,
            edges: n_edges,
            euler_characteristic: euler,
            components,
            origin_sheets: sheets,
            pinch_vertices,
            volume,
            area: self.area(),
        })
    }

    /// The first checks of [`Mesh::sanity_check`]: triangles present, finite
    /// positions, one unit normal and one colour per vertex where present.
    fn check_attributes(&self) -> Result<(), SanityError> {
        let nv = self.positions.len();
        if self.triangles.is_empty() {
            return Err(SanityError::Empty);
        }
        if let Some(v) = self.positions.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
            return Err(SanityError::NonFinite { vertex: v });
        }
        if let Some(normals) = &self.normals {
            if normals.len() != nv {
                return Err(SanityError::Attribute(format!(
                    "{} normals for {nv} vertices",
                    normals.len()
                )));
            }
            if let Some(v) = normals
                .iter()
                .position(|n| n.iter().any(|x| !x.is_finite()) || (p64(n).length() - 1.0).abs() > 1e-3)
            {
                return Err(SanityError::Attribute(format!(
                    "normal of vertex {v} is not a unit vector"
                )));
            }
        }
        if let Some(c) = &self.colors {
            if c.len() != nv {
                return Err(SanityError::Attribute(format!("{} colours for {nv} vertices", c.len())));
            }
        }
        Ok(())
    }

    /// Every triangle indexes existing vertices and has area; every vertex is used.
    fn check_triangles(&self) -> Result<(), SanityError> {
        let nv = self.positions.len();
        let mut used = vec![false; nv];
        for (i, t) in self.triangles.iter().enumerate() {
            if t.iter().any(|&v| v as usize >= nv) {
                return Err(SanityError::IndexOutOfRange { triangle: i });
            }
            let [a, b, c] = self.tri(t);
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || (b - a).cross(c - a) == DVec3::ZERO {
                return Err(SanityError::Degenerate {
                    triangle: i,
                    vertices: *t,
                });
            }
            for &v in t {
                used[v as usize] = true;
            }
        }
        if let Some(v) = used.iter().position(|u| !u) {
            return Err(SanityError::UnusedVertex { vertex: v });
        }
        Ok(())
    }

    /// Directed edges, sorted: each (a, b) must be matched by as many (b, a)
    /// (no hole, consistent winding), and used once unless it touches the
    /// origin vertex (where several sheets may meet).
    fn check_directed_edges(&self) -> Result<(), SanityError> {
        let mut directed: Vec<u64> = Vec::with_capacity(3 * self.triangles.len());
        for t in &self.triangles {
            directed.push(edge_key(t[0], t[1]));
            directed.push(edge_key(t[1], t[2]));
            directed.push(edge_key(t[2], t[0]));
        }
        directed.sort_unstable();
        let count = |k: u64| -> usize {
            let lo = directed.partition_point(|&x| x < k);
            let hi = directed.partition_point(|&x| x <= k);
            hi - lo
        };
        let origin = self.origin;
        let mut i = 0;
        while i < directed.len() {
            let k = directed[i];
            let mut j = i + 1;
            while j < directed.len() && directed[j] == k {
                j += 1;
            }
            let n_ab = j - i;
            let (a, b) = ((k >> 32) as u32, k as u32);
            let n_ba = count(edge_key(b, a));
            let at_origin = origin.is_some_and(|o| a == o || b == o);
            if n_ab != n_ba {
                // One triangle on one side only is a hole; anything else
                // unbalanced is a triangle wound the wrong way round.
                return Err(if n_ab == 1 && n_ba == 0 {
                    SanityError::OpenEdge { a, b }
                } else {
                    SanityError::InconsistentOrientation { a, b }
                });
            }
            if n_ab > 1 && !at_origin {
                return Err(SanityError::NonManifoldEdge {
                    a,
                    b,
                    triangles: n_ab + n_ba,
                });
            }
            i = j;
        }
        Ok(())
    }

    /// This mesh as it is written to files: every pinch vertex (the merged
    /// origin where several sheets meet, or any other point where two sheets
    /// touch) split into one vertex per sheet, so that the file is a
    /// 2-manifold for readers that merge vertices by position (STL readers,
    /// trimesh, Blender, slicers). Each sheet's copy is moved by
    /// up to [`SHEET_SEPARATION`] x [`Mesh::max_radius`] along the mean unit
    /// direction to its sheet's neighbours (into the cone the sheet forms
    /// there; for a flat sheet, a little along its normal away from the
    /// other sheets): copies at one position would be merged again on reading.
    /// Normals are recomputed, colours copied. Borrowed when nothing is pinched.
    pub fn separate_sheets(&self) -> Cow<'_, Mesh> {
        let nv = self.positions.len();
        let (tris, _, _, nv_split) = self.split_pinches();
        if nv_split == nv {
            return Cow::Borrowed(self);
        }
        let (source, moved) = self.copy_sources(&tris, nv_split);
        let mut positions: Vec<[f32; 3]> = source.iter().map(|&s| self.positions[s as usize]).collect();
        let fans = Fans::of(&tris, &positions, &moved);
        self.move_copies_apart(&mut positions, &source, &moved, &fans);
        let mut out = Mesh {
            positions,
            triangles: tris,
            normals: None,
            colors: self
                .colors
                .as_ref()
                .map(|c| source.iter().map(|&s| c[s as usize]).collect()),
            origin: self.origin.filter(|&o| !moved[o as usize]),
            info: self.info.clone(),
        };
        if self.normals.is_some() {
            out.compute_normals();
        }
        Cow::Owned(out)
    }

    /// For each vertex of the split triangles `tris` (`nv_split` vertices):
    /// the vertex of this mesh it copies, and whether it is one of a pinch
    /// vertex's copies (or the pinch vertex itself), which move apart.
    fn copy_sources(&self, tris: &[[u32; 3]], nv_split: usize) -> (Vec<u32>, Vec<bool>) {
        let nv = self.positions.len();
        let mut source: Vec<u32> = (0..nv_split as u32).collect();
        let mut moved = vec![false; nv_split];
        for (t0, t1) in self.triangles.iter().zip(tris) {
            for k in 0..3 {
                if t1[k] as usize >= nv {
                    source[t1[k] as usize] = t0[k];
                    moved[t1[k] as usize] = true;
                    moved[t0[k] as usize] = true;
                }
            }
        }
        (source, moved)
    }

    /// Moves each copy of a pinch vertex by up to [`SHEET_SEPARATION`] x
    /// [`Mesh::max_radius`] into its sheet (see [`Mesh::separate_sheets`]).
    ///
    /// The mean direction lies inside the cone the sheet's link spans, and
    /// its length (the cosine of a circular cone's half-angle) orders
    /// nested coaxial cones: apexes moved by it keep the sheets apart. A
    /// flat sheet (link on a great circle, mean ~ 0) moves a little along
    /// its normal, away from the other sheets at the point.
    fn move_copies_apart(&self, positions: &mut [[f32; 3]], source: &[u32], moved: &[bool], fans: &Fans) {
        let mut others = vec![DVec3::ZERO; self.positions.len()];
        for v in (0..moved.len()).filter(|&v| moved[v]) {
            others[source[v] as usize] += fans.mean_dir[v];
        }
        let step = SHEET_SEPARATION * self.max_radius();
        for v in (0..moved.len()).filter(|&v| moved[v] && fans.count[v] > 0) {
            let m = fans.mean_dir[v];
            let offset = if m.length() > 1e-3 {
                Some(m)
            } else {
                fans.normal[v].try_normalize().map(|n| {
                    let o = others[source[v] as usize] - m;
                    let sign = if n.dot(o) > 0.0 { -1e-3 } else { 1e-3 };
                    sign * n
                })
            };
            if let Some(d) = offset {
                let p = p64(&positions[v]);
                positions[v] = (p + step * d).as_vec3().to_array();
            }
        }
    }

    /// Triangles with every pinch vertex (a vertex whose link has several
    /// cycles: the merged origin between sheets, or an isolated point where
    /// two sheets of the surface touch, e.g. a tiny lit sample between dark
    /// ones) replaced by one copy per simple cycle of its link. Returns
    /// (triangles, sheets at the origin, other vertices split, vertex count).
    fn split_pinches(&self) -> (Vec<[u32; 3]>, usize, usize, usize) {
        let nv = self.positions.len() as u32;
        let mut tris = self.triangles.clone();
        // The origin first: other vertices' links must see its sheets apart,
        // or a vertex joined to the origin through two sheets would look pinched there.
        let (origin_sheets, next_id) = match self.origin {
            Some(o) => split_vertices(&mut tris, nv, |v| v == o),
            None => (0, nv),
        };
        let origin_copies = self.origin.map(|o| (o, nv..next_id));
        let is_origin = |v: u32| origin_copies.as_ref().is_some_and(|(o, r)| v == *o || r.contains(&v));
        let before = next_id;
        let (_, next_id) = split_vertices(&mut tris, next_id, |v| !is_origin(v));
        // Each pinched vertex adds at least one copy; count vertices, not copies.
        let pinched = if next_id > before {
            count_pinched(&self.triangles, &tris, before)
        } else {
            0
        };
        (tris, origin_sheets, pinched, next_id as usize)
    }
}

/// Per vertex to be moved apart by [`Mesh::separate_sheets`], its sheet's
/// fan of triangles around it (other vertices: zero).
struct Fans {
    /// Mean unit direction from the vertex to its fan's other vertices.
    mean_dir: Vec<DVec3>,
    /// How many directions the mean is over (0: none has a length).
    count: Vec<u32>,
    /// Sum of the fan's area-weighted normals.
    normal: Vec<DVec3>,
}

impl Fans {
    /// The fans of the `moved` vertices in `tris` over `positions`.
    fn of(tris: &[[u32; 3]], positions: &[[f32; 3]], moved: &[bool]) -> Self {
        let n_vertices = moved.len();
        let mut mean_dir = vec![DVec3::ZERO; n_vertices];
        let mut count = vec![0u32; n_vertices];
        let mut normal = vec![DVec3::ZERO; n_vertices];
        for t in tris {
            let [a, b, c] = t.map(|i| p64(&positions[i as usize]));
            let n = (b - a).cross(c - a);
            for k in 0..3 {
                let v = t[k] as usize;
                if !moved[v] {
                    continue;
                }
                let p = p64(&positions[v]);
                for q in [t[(k + 1) % 3], t[(k + 2) % 3]].map(|i| p64(&positions[i as usize])) {
                    if let Some(u) = (q - p).try_normalize() {
                        mean_dir[v] += u;
                        count[v] += 1;
                    }
                }
                normal[v] += n;
            }
        }
        for v in 0..n_vertices {
            let n = f64::from(count[v].max(1));
            mean_dir[v] /= n;
        }
        Self {
            mean_dir,
            count,
            normal,
        }
    }
}

/// The result of a successful [`Mesh::sanity_check`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SanityReport {
    /// Number of vertices (the origin counted once).
    pub vertices: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Number of edges after splitting the origin per sheet.
    pub edges: usize,
    /// V − E + F after splitting the origin per sheet: 2 per component.
    pub euler_characteristic: i64,
    /// Connected components after splitting the origin (1 for a solid with no
    /// zero region or a single one; more when sheets meet only at the origin).
    pub components: usize,
    /// Vertices other than the origin where two sheets of the surface touch
    /// at a single point (split like the origin before the topology check).
    pub pinch_vertices: usize,
    /// Number of surface sheets meeting at the merged origin vertex (0 when
    /// the intensity is nowhere zero).
    pub origin_sheets: usize,
    /// Enclosed volume, units³.
    pub volume: f64,
    /// Surface area, units².
    pub area: f64,
}

/// A broken invariant found by [`Mesh::sanity_check`].
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SanityError {
    /// The mesh has no triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// Vertex index.
        vertex: usize,
    },
    /// A normal or colour array does not match the vertices, or a normal is not unit.
    #[error("attribute: {0}")]
    Attribute(String),
    /// A triangle indexes past the vertices.
    #[error("triangle {triangle} indexes past the vertices")]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
    },
    /// A triangle repeats a vertex or has zero area.
    #[error("triangle {triangle} {vertices:?} is degenerate (repeated vertex or zero area)")]
    Degenerate {
        /// Triangle index.
        triangle: usize,
        /// Its vertex indices.
        vertices: [u32; 3],
    },
    /// A vertex is used by no triangle.
    #[error("vertex {vertex} is used by no triangle")]
    UnusedVertex {
        /// Vertex index.
        vertex: usize,
    },
    /// An edge has triangles on one side only: the surface has a hole.
    #[error("edge {a} -> {b} has no opposite edge: the surface is open")]
    OpenEdge {
        /// From vertex.
        a: u32,
        /// To vertex.
        b: u32,
    },
    /// Two triangles run along an edge in the same direction: winding flips.
    #[error("edge {a} -> {b} is used more often in one direction than the other: inconsistent winding")]
    InconsistentOrientation {
        /// From vertex.
        a: u32,
        /// To vertex.
        b: u32,
    },
    /// An edge (away from the origin vertex) is shared by more than two triangles.
    #[error("edge {a} - {b} is shared by {triangles} triangles")]
    NonManifoldEdge {
        /// One end.
        a: u32,
        /// Other end.
        b: u32,
        /// How many triangles share it.
        triangles: usize,
    },
    /// The surface is not a union of spheres.
    #[error("Euler characteristic {euler} for {components} component(s): expected 2 per component (a sphere)")]
    Topology {
        /// V − E + F after splitting the origin.
        euler: i64,
        /// Connected components.
        components: usize,
    },
    /// The enclosed volume is negative: the triangles face inwards.
    #[error("enclosed volume {volume} is negative: triangles face inwards")]
    InwardFacing {
        /// The signed volume.
        volume: f64,
    },
}

/// An edge (a, b) as one sortable key: a in the high 32 bits.
fn edge_key(a: u32, b: u32) -> u64 {
    ((a as u64) << 32) | b as u64
}

/// The undirected edges of `tris` (pinches already split), each of which
/// must be shared by exactly two triangles: their count, or the first that is not.
fn count_manifold_edges(tris: &[[u32; 3]]) -> Result<usize, SanityError> {
    let mut undirected: Vec<u64> = Vec::with_capacity(3 * tris.len());
    for t in tris {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            undirected.push(edge_key(a.min(b), a.max(b)));
        }
    }
    undirected.sort_unstable();
    let mut n_edges = 0usize;
    let mut i = 0;
    while i < undirected.len() {
        let mut j = i + 1;
        while j < undirected.len() && undirected[j] == undirected[i] {
            j += 1;
        }
        if j - i != 2 {
            let k = undirected[i];
            return Err(SanityError::NonManifoldEdge {
                a: (k >> 32) as u32,
                b: k as u32,
                triangles: j - i,
            });
        }
        n_edges += 1;
        i = j;
    }
    Ok(n_edges)
}

/// Connected components of `tris` over `n_vertices` vertices, by union-find
/// (an unused vertex is a component of its own).
fn count_components(tris: &[[u32; 3]], n_vertices: usize) -> usize {
    let mut parent: Vec<u32> = (0..n_vertices as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for t in tris {
        let r0 = find(&mut parent, t[0]);
        for &v in &t[1..] {
            let r = find(&mut parent, v);
            if r != r0 {
                parent[r as usize] = r0;
            }
        }
    }
    (0..n_vertices as u32).filter(|&x| find(&mut parent, x) == x).count()
}

impl fmt::Display for SanityReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} vertices, {} triangles, {} edges, χ = {} over {} component(s), {} sheet(s) at the origin, volume {:.6e}, area {:.6e}",
            self.vertices,
            self.triangles,
            self.edges,
            self.euler_characteristic,
            self.components,
            self.origin_sheets,
            self.volume,
            self.area
        )
    }
}

/// A stored `f32` position or normal as `f64` for accumulating quantities.
#[inline]
pub(crate) fn p64(p: &[f32; 3]) -> DVec3 {
    Vec3::from_array(*p).as_dvec3()
}

#[cfg(test)]
mod tests;
