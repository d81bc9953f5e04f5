//! Binary STL: 80-byte header holding the metadata (ASCII, truncated; never
//! starting with `solid`, which would make readers take it for ASCII STL),
//! the triangle count, and per triangle its unit normal (recomputed from the
//! vertices; zero for a degenerate one), three vertices and a zero
//! attribute word. STL has no per-vertex colour or normal: those are dropped.

use super::ascii_lines;
use crate::solid::mesh::p64;
use std::collections::HashMap;

use crate::error::MeshFileError;
use crate::solid::{Mesh, SolidInfo};

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
        let n = (p64(&b) - p64(&a))
            .cross(p64(&c) - p64(&a))
            .try_normalize()
            .unwrap_or_default();
        for x in n.to_array() {
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

/// Read a binary STL file: vertices at the same position merged (−0.0 and
/// 0.0 being one position), so the mesh has the topology the triangles
/// describe; the facet normals are ignored. The vertex at exactly (0, 0, 0),
/// if any, is taken as the origin vertex. Metadata is not restored.
pub fn read(bytes: &[u8]) -> Result<Mesh, MeshFileError> {
    if bytes.len() < 84 {
        return Err(MeshFileError::at_byte(
            "STL",
            Some(bytes.len()),
            "an 84-byte header (80 bytes, then the triangle count)",
            format!("end of file after {} bytes", bytes.len()),
        ));
    }
    let n = super::le_u32(bytes, 80) as usize;
    let want = 84 + 50 * n;
    if bytes.len() != want {
        return Err(MeshFileError::at_byte(
            "STL",
            None,
            format!("{want} bytes for the {n} triangles the header declares (binary STL; ASCII STL is not read)"),
            format!("{} bytes", bytes.len()),
        ));
    }
    let mut index: HashMap<[u32; 3], u32> = HashMap::with_capacity(n / 2 + 3);
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut triangles = Vec::with_capacity(n);
    for rec in bytes[84..].chunks_exact(50) {
        let mut t = [0u32; 3];
        for (k, v) in t.iter_mut().enumerate() {
            let o = 12 + 12 * k;
            let p: [f32; 3] = [0, 1, 2].map(|j| super::le_f32(rec, o + 4 * j) + 0.0);
            *v = *index.entry(p.map(f32::to_bits)).or_insert_with(|| {
                positions.push(p);
                positions.len() as u32 - 1
            });
        }
        triangles.push(t);
    }
    let origin = positions.iter().position(|p| *p == [0.0; 3]).map(|i| i as u32);
    Mesh::from_parts(positions, triangles, origin, SolidInfo::default())
        .map_err(|source| MeshFileError::Mesh { format: "STL", source })
}
