//! Binary little-endian PLY: `x y z` floats, optional `nx ny nz` floats and
//! `red green blue` uchars, faces as `list uchar int vertex_indices`.

use super::ascii_lines;
use crate::error::MeshFileError;
use crate::solid::{Mesh, SolidInfo};

/// A header element: name, count, properties (name, type, list count type).
type Element = (String, usize, Vec<(String, String, Option<String>)>);

/// The PLY file's bytes.
pub fn encode(mesh: &Mesh) -> Vec<u8> {
    let normals = mesh.normals();
    let colors = mesh.colors();
    let mut header = String::from("ply\nformat binary_little_endian 1.0\n");
    for l in ascii_lines(mesh) {
        header.push_str("comment ");
        header.push_str(&l);
        header.push('\n');
    }
    header.push_str(&format!(
        "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
        mesh.n_vertices()
    ));
    if normals.is_some() {
        header.push_str("property float nx\nproperty float ny\nproperty float nz\n");
    }
    if colors.is_some() {
        header.push_str("property uchar red\nproperty uchar green\nproperty uchar blue\n");
    }
    header.push_str(&format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.n_triangles()
    ));
    let stride = 12 + if normals.is_some() { 12 } else { 0 } + if colors.is_some() { 3 } else { 0 };
    let mut out = Vec::with_capacity(header.len() + stride * mesh.n_vertices() + 13 * mesh.n_triangles());
    out.extend_from_slice(header.as_bytes());
    for (i, p) in mesh.positions().iter().enumerate() {
        for x in p {
            out.extend_from_slice(&x.to_le_bytes());
        }
        if let Some(n) = normals {
            for x in &n[i] {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        if let Some(c) = colors {
            out.extend_from_slice(&c[i]);
        }
    }
    for t in mesh.triangles() {
        out.push(3);
        for &v in t {
            out.extend_from_slice(&(v as i32).to_le_bytes());
        }
    }
    out
}

/// Read a PLY file of the kind [`encode`] writes (binary little endian or
/// ASCII; float or double coordinates; other vertex properties skipped;
/// polygon faces fanned into triangles). The vertex at exactly (0, 0, 0),
/// if any, is taken as the origin vertex. Metadata is not restored.
pub fn read(bytes: &[u8]) -> Result<Mesh, MeshFileError> {
    let err = |line: usize, expected: &str, found: String| MeshFileError::at_line("PLY", line, expected, found);
    let end =
        find(bytes, b"end_header\n").ok_or_else(|| err(0, "a header ending in an `end_header` line", "none".into()))?;
    let header = std::str::from_utf8(&bytes[..end]).map_err(|e| {
        let line = bytes[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + 1;
        err(line, "a UTF-8 text header", "bytes that are not UTF-8".into())
    })?;
    let body_start = end + b"end_header\n".len();
    let body = &bytes[body_start..];
    // The body's first line (ASCII): the header's lines and `end_header`.
    let body_line = header.lines().count() + 2;
    let mut binary = true;
    // (element name, count, properties (name, type, list count type)), and each element's header line.
    let mut elements: Vec<Element> = Vec::new();
    let mut element_lines: Vec<usize> = Vec::new();
    for (i, line) in header.lines().enumerate() {
        let ln = i + 1;
        let w: Vec<&str> = line.split_whitespace().collect();
        let no_element = || err(ln, "an `element` line before the first `property`", format!("`{line}`"));
        match w.as_slice() {
            ["format", "ascii", ..] => binary = false,
            ["format", "binary_little_endian", ..] => binary = true,
            ["format", f, ..] => {
                return Err(err(
                    ln,
                    "format ascii or binary_little_endian",
                    format!("format {f}, which is not read"),
                ))
            }
            ["element", name, n] => {
                let count = n
                    .parse()
                    .map_err(|_| err(ln, "`element NAME COUNT` with a whole count", format!("`{line}`")))?;
                elements.push((name.to_string(), count, vec![]));
                element_lines.push(ln);
            }
            ["property", "list", ct, t, name] => elements.last_mut().ok_or_else(no_element)?.2.push((
                name.to_string(),
                t.to_string(),
                Some(ct.to_string()),
            )),
            ["property", t, name] => {
                elements
                    .last_mut()
                    .ok_or_else(no_element)?
                    .2
                    .push((name.to_string(), t.to_string(), None))
            }
            _ => {}
        }
    }
    let size = |t: &str| match t {
        "char" | "uchar" | "int8" | "uint8" => Some(1),
        "short" | "ushort" | "int16" | "uint16" => Some(2),
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => Some(4),
        "double" | "float64" => Some(8),
        _ => None,
    };
    let mut pos = 0usize;
    // ASCII: the tokens with their 0-based line in the body.
    let mut tokens = if binary {
        None
    } else {
        let text = std::str::from_utf8(body).map_err(|e| {
            let line = body[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + body_line;
            err(
                line,
                "a UTF-8 text body (format ascii)",
                "bytes that are not UTF-8".into(),
            )
        })?;
        Some(
            text.lines()
                .enumerate()
                .flat_map(|(i, l)| l.split_ascii_whitespace().map(move |t| (i, t))),
        )
    };
    let body_lines = body.iter().filter(|&&b| b == b'\n').count();
    let mut scalar = |t: &str| -> Result<f64, MeshFileError> {
        if let Some(tok) = tokens.as_mut() {
            return match tok.next() {
                Some((i, s)) => s
                    .parse::<f64>()
                    .map_err(|_| err(body_line + i, &format!("a number ({t})"), format!("`{s}`"))),
                None => Err(err(
                    body_line + body_lines,
                    &format!("a number ({t})"),
                    "end of file".into(),
                )),
            };
        }
        let n = size(t).ok_or_else(|| {
            MeshFileError::at_byte(
                "PLY",
                Some(body_start + pos),
                "a property type char, uchar, short, ushort, int, uint, float or double",
                format!("`{t}`"),
            )
        })?;
        let b = body.get(pos..pos + n).ok_or_else(|| {
            MeshFileError::at_byte(
                "PLY",
                Some(body_start + pos),
                format!("a {t} ({n} bytes)"),
                "end of file (truncated)",
            )
        })?;
        pos += n;
        Ok(match t {
            "char" | "int8" => b[0] as i8 as f64,
            "uchar" | "uint8" => b[0] as f64,
            "short" | "int16" => i16::from_le_bytes([b[0], b[1]]) as f64,
            "ushort" | "uint16" => u16::from_le_bytes([b[0], b[1]]) as f64,
            "int" | "int32" => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            "uint" | "uint32" => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            "float" | "float32" => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            _ => f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]),
        })
    };
    // Every instance of an element takes at least one byte (binary) or one
    // token (ASCII) of the body: a count past that is a damaged header, refused
    // before any loop or allocation runs on it.
    for ((name, count, props), &ln) in elements.iter().zip(&element_lines) {
        if props.is_empty() {
            return Err(err(
                ln,
                "at least one `property` per element",
                format!("element {name} has no properties"),
            ));
        }
        if *count > body.len() {
            return Err(err(
                ln,
                "at most one entry per byte of the body",
                format!(
                    "element {name} declares {count} entries but the body has {} bytes",
                    body.len()
                ),
            ));
        }
        let has = |axis: &str| props.iter().any(|(p, _, list)| p == axis && list.is_none());
        if name == "vertex" && !(has("x") && has("y") && has("z")) {
            return Err(err(
                ln,
                "vertex properties x, y and z",
                "vertex element without x, y and z properties".into(),
            ));
        }
    }
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (name, count, props) in &elements {
        for _ in 0..*count {
            let mut xyz = [0.0f32; 3];
            for (pname, t, list) in props {
                if let Some(ct) = list {
                    let n = scalar(ct)?;
                    if !(n >= 0.0 && n <= body.len() as f64 && n.fract() == 0.0) {
                        return Err(MeshFileError::at_byte(
                            "PLY",
                            None,
                            format!("a length of list {pname} within the body ({} bytes)", body.len()),
                            format!("list {pname} of {n} entries"),
                        ));
                    }
                    let n = n as usize;
                    let mut idx = Vec::with_capacity(n);
                    for _ in 0..n {
                        idx.push(scalar(t)? as u32);
                    }
                    if name == "face" && (pname == "vertex_indices" || pname == "vertex_index") {
                        for k in 1..n.saturating_sub(1) {
                            triangles.push([idx[0], idx[k], idx[k + 1]]);
                        }
                    }
                } else {
                    let v = scalar(t)?;
                    if name == "vertex" {
                        match pname.as_str() {
                            "x" => xyz[0] = v as f32,
                            "y" => xyz[1] = v as f32,
                            "z" => xyz[2] = v as f32,
                            _ => {}
                        }
                    }
                }
            }
            if name == "vertex" {
                positions.push(xyz);
            }
        }
    }
    let origin = positions.iter().position(|p| *p == [0.0; 3]).map(|i| i as u32);
    Mesh::from_parts(positions, triangles, origin, SolidInfo::default())
        .map_err(|source| MeshFileError::Mesh { format: "PLY", source })
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}
