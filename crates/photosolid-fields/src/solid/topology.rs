//! Surface topology of triangle meshes: pinch vertices (several sheets
//! meeting at one point) and their splitting, zero-thickness fins, and the
//! [`MeshTopology`] check of a mesh as a file reader sees it (vertices merged
//! by position), which is what `photosolid mesh --json` reports.

/// Remove zero-thickness fins at the origin, then drop unused vertices.
///
/// Merging zero samples into the origin can leave a triangle and its mirror
/// image (same three vertices, opposite winding): a flat fin of no volume,
/// e.g. a single non-zero ring between zero rings. Such a pair cancels as a
/// surface (its edges are matched within the pair), so both are removed; any
/// vertex then unused is dropped (indices renumbered, order kept). Fins always
/// contain the origin (no other merge makes two triangles share all three
/// vertices), so only triangles at the origin are examined.
pub(crate) fn remove_fins(positions: &mut Vec<[f32; 3]>, triangles: &mut Vec<[u32; 3]>, origin: &mut Option<u32>) {
    let Some(o) = *origin else { return };
    let dead = fin_triangles(triangles, o);
    // Even without fins, triangles dropped for touching the origin twice can
    // leave a vertex unused: the compaction below runs in every case.
    let mut k = 0;
    let mut idx = 0;
    triangles.retain(|_| {
        let keep = !(k < dead.len() && dead[k] == idx);
        if !keep {
            k += 1;
        }
        idx += 1;
        keep
    });
    drop_unused_vertices(positions, triangles, origin);
}

/// Indices (ascending) of the triangles at the origin `o` that pair off with
/// a mirror image: same vertex set, opposite winding.
fn fin_triangles(triangles: &[[u32; 3]], o: u32) -> Vec<usize> {
    // (canonical vertex set, +1/-1 parity of the winding, triangle index)
    let mut at_o: Vec<([u32; 3], bool, usize)> = triangles
        .iter()
        .enumerate()
        .filter(|(_, t)| t.contains(&o))
        .map(|(i, t)| {
            let mut s = *t;
            s.sort_unstable();
            // Even permutation of the sorted order = same winding as sorted.
            let k = t.iter().position(|&v| v == s[0]).unwrap_or(0); // s is a permutation of t
            let even = t[(k + 1) % 3] == s[1];
            (s, even, i)
        })
        .collect();
    at_o.sort_unstable();
    let mut dead = Vec::new();
    let mut i = 0;
    while i < at_o.len() {
        let mut j = i;
        while j < at_o.len() && at_o[j].0 == at_o[i].0 {
            j += 1;
        }
        // Pair off opposite windings within the group.
        let (mut ev, mut od): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
        for e in &at_o[i..j] {
            if e.1 {
                ev.push(e.2)
            } else {
                od.push(e.2)
            }
        }
        let n = ev.len().min(od.len());
        dead.extend_from_slice(&ev[..n]);
        dead.extend_from_slice(&od[..n]);
        i = j;
    }
    dead.sort_unstable();
    dead
}

/// Drops the vertices no triangle uses (indices renumbered, order kept);
/// `origin` follows its vertex, or is `None` once unused.
fn drop_unused_vertices(positions: &mut Vec<[f32; 3]>, triangles: &mut [[u32; 3]], origin: &mut Option<u32>) {
    let mut used = vec![false; positions.len()];
    for t in triangles.iter() {
        for &v in t {
            used[v as usize] = true;
        }
    }
    if used.iter().all(|&u| u) {
        return;
    }
    let mut remap = vec![u32::MAX; positions.len()];
    let mut next = 0u32;
    let mut kept = Vec::with_capacity(positions.len());
    for (v, p) in positions.iter().enumerate() {
        if used[v] {
            remap[v] = next;
            next += 1;
            kept.push(*p);
        }
    }
    *positions = kept;
    for t in triangles.iter_mut() {
        for v in t.iter_mut() {
            *v = remap[*v as usize];
        }
    }
    *origin = origin.filter(|&o| used[o as usize]).map(|o| remap[o as usize]);
}

/// Split every vertex selected by `select` whose link has several cycles
/// into one copy per cycle (new ids from `next_id` on). Returns (cycles of
/// the last selected vertex with any triangle, the next free id).
pub(crate) fn split_vertices(tris: &mut [[u32; 3]], mut next_id: u32, select: impl Fn(u32) -> bool) -> (usize, u32) {
    let mut link: Vec<(u32, u32, u32, usize)> = Vec::with_capacity(3 * tris.len());
    for (i, t) in tris.iter().enumerate() {
        for k in 0..3 {
            if select(t[k]) {
                link.push((t[k], t[(k + 1) % 3], t[(k + 2) % 3], i));
            }
        }
    }
    link.sort_unstable();
    let mut last_sheets = 0;
    let mut g = 0;
    while g < link.len() {
        let v = link[g].0;
        let mut h = g;
        while h < link.len() && link[h].0 == v {
            h += 1;
        }
        let group = &link[g..h];
        let sheet_of = link_cycles(group);
        let sheets = sheet_of.iter().copied().max().map_or(0, |m| m + 1);
        last_sheets = sheets;
        for (k, e) in group.iter().enumerate() {
            if sheet_of[k] > 0 {
                let new_id = next_id + sheet_of[k] as u32 - 1;
                for x in &mut tris[e.3] {
                    if *x == v {
                        *x = new_id;
                    }
                }
            }
        }
        next_id += sheets.saturating_sub(1) as u32;
        g = h;
    }
    (last_sheets, next_id)
}

/// Number of distinct original vertices that received copies with ids >= `first_new`.
pub(crate) fn count_pinched(original: &[[u32; 3]], split: &[[u32; 3]], first_new: u32) -> usize {
    let mut v: Vec<u32> = original
        .iter()
        .zip(split)
        .flat_map(|(a, b)| (0..3).filter(move |&k| b[k] >= first_new).map(move |k| a[k]))
        .collect();
    v.sort_unstable();
    v.dedup();
    v.len()
}

/// Decompose a vertex's link edges (sorted by their start) into simple
/// cycles; returns the cycle index of each edge. Whenever the walk revisits
/// a vertex, the loop since that vertex is one cycle (one sheet).
fn link_cycles(group: &[(u32, u32, u32, usize)]) -> Vec<usize> {
    let n = group.len();
    let mut used = vec![false; n];
    let mut sheet_of = vec![0usize; n];
    let mut sheets = 0usize;
    for start in 0..n {
        if used[start] {
            continue;
        }
        let mut path_v: Vec<u32> = vec![group[start].1];
        let mut path_e: Vec<usize> = Vec::new();
        let mut e = start;
        loop {
            used[e] = true;
            path_e.push(e);
            let y = group[e].2;
            if let Some(pos) = path_v.iter().rposition(|&x| x == y) {
                for &pe in &path_e[pos..] {
                    sheet_of[pe] = sheets;
                }
                sheets += 1;
                path_e.truncate(pos);
                path_v.truncate(pos + 1);
            } else {
                path_v.push(y);
            }
            // The walk started with one vertex and truncation keeps `pos + 1 >= 1`.
            let Some(&from) = path_v.last() else { break };
            let lo = group.partition_point(|l| l.1 < from);
            match (lo..n).take_while(|&k| group[k].1 == from).find(|&k| !used[k]) {
                Some(next) => e = next,
                None => {
                    // An open link (unbalanced edges, reported by the edge check): one sheet.
                    if !path_e.is_empty() {
                        for &pe in &path_e {
                            sheet_of[pe] = sheets;
                        }
                        sheets += 1;
                    }
                    break;
                }
            }
        }
    }
    sheet_of
}

/// How far [`Mesh::separate_sheets`](crate::solid::Mesh::separate_sheets) moves each sheet's copy of a pinch
/// vertex, relative to the largest radius: far above `f32` resolution and
/// the merge tolerances of mesh readers (trimesh: 1e-8 absolute), far below
/// any measurement's precision.
pub const SHEET_SEPARATION: f64 = 1e-5;

/// The topology of a mesh as a file reader sees it: vertices at the same
/// position merged (STL has no shared vertices at all; trimesh, Blender and
/// slicers merge by position), then every edge and vertex examined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct MeshTopology {
    /// Distinct vertex positions used by a triangle.
    pub vertices: usize,
    /// Distinct undirected edges.
    pub edges: usize,
    /// Triangles.
    pub triangles: usize,
    /// Closed and consistently oriented: every edge is shared by exactly two
    /// triangles that run along it in opposite directions (trimesh's
    /// `is_watertight` and `is_winding_consistent` together).
    pub watertight: bool,
    /// Watertight, no triangle with a repeated vertex, and every vertex's
    /// neighbourhood a single disc (its link one cycle): no pinch point.
    pub manifold: bool,
    /// Connected components, triangles joined through shared edges.
    pub components: usize,
    /// V − E + F of the merged mesh: 2 per component for a union of spheres.
    pub euler_characteristic: i64,
}

/// The topology of `triangles` over `positions` with equal positions merged
/// (−0.0 and 0.0 are one position). O(F log F).
pub fn topology(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> MeshTopology {
    // Merge by position: sort vertex ids by their coordinates' bits.
    let bits = |p: &[f32; 3]| p.map(|x| (x + 0.0).to_bits());
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    order.sort_unstable_by_key(|&i| bits(&positions[i as usize]));
    let mut id = vec![0u32; positions.len()];
    let mut n_vertices = 0u32;
    for (k, &i) in order.iter().enumerate() {
        if k > 0 && bits(&positions[i as usize]) != bits(&positions[order[k - 1] as usize]) {
            n_vertices += 1;
        }
        id[i as usize] = n_vertices;
    }
    if !positions.is_empty() {
        n_vertices += 1;
    }
    let mut tris: Vec<[u32; 3]> = triangles.iter().map(|t| t.map(|v| id[v as usize])).collect();
    // Positions no triangle uses are not part of the surface.
    let mut used = vec![false; n_vertices as usize];
    for t in &tris {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let n_used = used.iter().filter(|&&u| u).count() as i64;
    let degenerate = tris.iter().any(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2]);
    // (undirected edge, triangle, forward?) sorted by edge.
    let mut edges: Vec<(u64, u32, bool)> = Vec::with_capacity(3 * tris.len());
    for (i, t) in tris.iter().enumerate() {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            edges.push(((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), i as u32, a < b));
        }
    }
    edges.sort_unstable();
    let mut parent: Vec<u32> = (0..tris.len() as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    let (mut n_edges, mut watertight) = (0usize, !tris.is_empty());
    let mut i = 0;
    while i < edges.len() {
        let mut j = i + 1;
        while j < edges.len() && edges[j].0 == edges[i].0 {
            j += 1;
        }
        let group = &edges[i..j];
        if group.len() != 2 || group[0].2 == group[1].2 {
            watertight = false;
        }
        for e in &group[1..] {
            let (r0, r) = (find(&mut parent, group[0].1), find(&mut parent, e.1));
            if r0 != r {
                parent[r as usize] = r0;
            }
        }
        n_edges += 1;
        i = j;
    }
    let components = (0..tris.len() as u32).filter(|&x| find(&mut parent, x) == x).count();
    // A vertex whose link has several cycles gets copies: the mesh is pinched there.
    let pinched = watertight && !degenerate && split_vertices(&mut tris, n_vertices, |_| true).1 != n_vertices;
    MeshTopology {
        vertices: n_used as usize,
        edges: n_edges,
        triangles: triangles.len(),
        watertight,
        manifold: watertight && !degenerate && !pinched,
        components,
        euler_characteristic: n_used - n_edges as i64 + triangles.len() as i64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::{Mesh, SolidInfo};

    /// Two tetrahedra sharing only the origin vertex: one component after the
    /// split would be wrong; the check sees two spheres meeting at the origin.
    #[test]
    fn pinched_origin_splits_into_sheets() {
        let mut p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        p.extend([[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]);
        let mut t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        // The mirror image (det −1) with the winding flipped back.
        t.extend([[0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]]);
        let m = Mesh::from_parts(p, t, Some(0), SolidInfo::default()).unwrap();
        let r = m.sanity_check().unwrap();
        assert_eq!((r.origin_sheets, r.components), (2, 2));
        assert!((r.volume - 2.0 / 6.0).abs() < 1e-9);
    }

    /// Two tetrahedra sharing one vertex: watertight, not manifold, 2 components.
    #[test]
    fn shared_apex_is_watertight_but_not_manifold() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, -1.0],
        ];
        let mut t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let one = topology(&p, &t);
        assert!(one.watertight && one.manifold);
        assert_eq!((one.components, one.euler_characteristic), (1, 2));
        t.extend([[0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]]);
        let two = topology(&p, &t);
        assert!(two.watertight && !two.manifold);
        assert_eq!(two.components, 2);
        // A triangle soup (STL) of one tetrahedron is merged back to 4 vertices; -0.0 is 0.0.
        let mut soup = Vec::new();
        for tri in &t[..4] {
            for &v in tri {
                let q: [f32; 3] = p[v as usize];
                soup.push(q.map(|x| if x == 0.0 { -0.0 } else { x }));
            }
        }
        let st: Vec<[u32; 3]> = (0..4).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let s = topology(&soup, &st);
        assert_eq!((s.vertices, s.edges, s.manifold), (4, 6, true));
        // An open surface is not watertight.
        assert!(!topology(&p, &t[..3]).watertight);
    }
}
