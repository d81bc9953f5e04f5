//! Wavefront OBJ: `v x y z [r g b]`, `vn`, triangles `f a//a b//b c//c` (1-based).

use std::io::Write;

use super::ascii_lines;
use crate::error::MeshFileError;
use crate::solid::{Mesh, SolidInfo};

/// The OBJ file's bytes. Floats are written in their shortest round-trip form.
pub fn encode(mesh: &Mesh) -> Vec<u8> {
    let mut out =
        Vec::with_capacity(40 * mesh.n_vertices() * (1 + mesh.normals().is_some() as usize) + 30 * mesh.n_triangles());
    for l in ascii_lines(mesh) {
        let _ = writeln!(out, "# {l}");
    }
    let colors = mesh.colors();
    for (i, p) in mesh.positions().iter().enumerate() {
        let _ = write!(out, "v {} {} {}", p[0], p[1], p[2]);
        if let Some(c) = colors {
            let f = |x: u8| x as f32 / 255.0;
            let _ = write!(out, " {} {} {}", f(c[i][0]), f(c[i][1]), f(c[i][2]));
        }
        out.push(b'\n');
    }
    if let Some(n) = mesh.normals() {
        for v in n {
            let _ = writeln!(out, "vn {} {} {}", v[0], v[1], v[2]);
        }
    }
    let with_n = mesh.normals().is_some();
    for t in mesh.triangles() {
        let [a, b, c] = t.map(|v| v as u64 + 1);
        let _ = if with_n {
            writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}")
        } else {
            writeln!(out, "f {a} {b} {c}")
        };
    }
    out
}

/// Read the vertices and faces of an OBJ file (`v` and `f` lines; `f`
/// entries may carry `/vt/vn`, negative indices count from the end;
/// polygons are fanned). The vertex at exactly (0, 0, 0), if any, is taken
/// as the origin vertex. Metadata is not restored.
pub fn read(bytes: &[u8]) -> Result<Mesh, MeshFileError> {
    let err = |line: usize, expected: &str, found: String| MeshFileError::at_line("OBJ", line, expected, found);
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + 1;
        err(line, "UTF-8 text", "bytes that are not UTF-8".into())
    })?;
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut triangles = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        let mut w = line.split_whitespace();
        let shown = || format!("`{}`", line.trim());
        match w.next() {
            Some("v") => {
                let mut p = [0.0f32; 3];
                for x in &mut p {
                    *x = w
                        .next()
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(|| err(ln + 1, "3 numbers after `v`", shown()))?;
                }
                positions.push(p);
            }
            Some("f") => {
                let idx: Vec<u32> = w
                    .map(|s| {
                        let i: i64 = s.split('/').next().unwrap_or("").parse().map_err(|_| {
                            err(
                                ln + 1,
                                "vertex indices after `f` (integers, 1-based or negative from the end)",
                                format!("`{s}` in {}", shown()),
                            )
                        })?;
                        let at = if i < 0 { positions.len() as i64 + i } else { i - 1 };
                        u32::try_from(at).map_err(|_| {
                            err(
                                ln + 1,
                                "a face index within the vertices read so far",
                                format!("index {i} with {} vertices", positions.len()),
                            )
                        })
                    })
                    .collect::<Result<_, _>>()?;
                for k in 1..idx.len().saturating_sub(1) {
                    triangles.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    let origin = positions.iter().position(|p| *p == [0.0; 3]).map(|i| i as u32);
    Mesh::from_parts(positions, triangles, origin, SolidInfo::default())
        .map_err(|source| MeshFileError::Mesh { format: "OBJ", source })
}
