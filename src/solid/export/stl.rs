//! Binary STL: 80-byte header holding the metadata (ASCII, truncated; never
//! starting with `solid`, which would make readers take it for ASCII STL),
//! the triangle count, and per triangle its unit normal (recomputed from the
//! vertices; zero for a degenerate one), three vertices and a zero
//! attribute word. STL has no per-vertex colour or normal: those are dropped.

use super::ascii_lines;
use crate::solid::mesh::{cross, p64, sub, unit};
use crate::solid::Mesh;

/// The STL file's bytes.
pub fn encode(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * mesh.n_triangles());
    let lines = ascii_lines(mesh);
    // "photosolid photometric solid; units: ...; scale: ...": the units matter most.
    let wanted: Vec<&str> = lines
        .iter()
        .filter(|l| l.starts_with("photosolid") || l.starts_with("units:") || l.starts_with("frame:"))
        .map(|s| s.as_str())
        .collect();
    let mut header = wanted.join("; ").into_bytes();
    header.resize(80, b' ');
    out.extend_from_slice(&header);
    out.extend_from_slice(&(mesh.n_triangles() as u32).to_le_bytes());
    let p = mesh.positions();
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|i| p[i as usize]);
        let n = unit(cross(sub(p64(&b), p64(&a)), sub(p64(&c), p64(&a)))).unwrap_or([0.0; 3]);
        for x in n {
            out.extend_from_slice(&(x as f32).to_le_bytes());
        }
        for v in [a, b, c] {
            for x in v {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}
