//! Binary little-endian PLY: `x y z` floats, optional `nx ny nz` floats and
//! `red green blue` uchars, faces as `list uchar int vertex_indices`.

use super::ascii_lines;
use crate::error::ModelError;
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
pub fn read(bytes: &[u8]) -> Result<Mesh, ModelError> {
    let err = |m: String| ModelError::Intensities(format!("PLY: {m}"));
    let end = find(bytes, b"end_header\n").ok_or_else(|| err("no end_header".into()))?;
    let header = std::str::from_utf8(&bytes[..end]).map_err(|_| err("header is not UTF-8".into()))?;
    let body = &bytes[end + b"end_header\n".len()..];
    let mut binary = true;
    // (element name, count, properties (name, type, list count type))
    let mut elements: Vec<Element> = Vec::new();
    for line in header.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["format", "ascii", ..] => binary = false,
            ["format", "binary_little_endian", ..] => binary = true,
            ["format", f, ..] => return Err(err(format!("unsupported format {f}"))),
            ["element", name, n] => elements.push((name.to_string(), n.parse().map_err(|_| err(line.into()))?, vec![])),
            ["property", "list", ct, t, name] => elements.last_mut().ok_or_else(|| err(line.into()))?.2.push((
                name.to_string(),
                t.to_string(),
                Some(ct.to_string()),
            )),
            ["property", t, name] => {
                elements
                    .last_mut()
                    .ok_or_else(|| err(line.into()))?
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
    let mut tokens = if binary {
        None
    } else {
        Some(
            std::str::from_utf8(body)
                .map_err(|_| err("body is not UTF-8".into()))?
                .split_ascii_whitespace(),
        )
    };
    let mut scalar = |t: &str| -> Result<f64, ModelError> {
        if let Some(tok) = tokens.as_mut() {
            return tok
                .next()
                .and_then(|s| s.parse::<f64>().ok())
                .ok_or_else(|| err("bad or missing ASCII value".into()));
        }
        let n = size(t).ok_or_else(|| err(format!("unknown type {t}")))?;
        let b = body.get(pos..pos + n).ok_or_else(|| err("truncated".into()))?;
        pos += n;
        Ok(match t {
            "char" | "int8" => b[0] as i8 as f64,
            "uchar" | "uint8" => b[0] as f64,
            "short" | "int16" => i16::from_le_bytes([b[0], b[1]]) as f64,
            "ushort" | "uint16" => u16::from_le_bytes([b[0], b[1]]) as f64,
            "int" | "int32" => i32::from_le_bytes(b.try_into().unwrap()) as f64,
            "uint" | "uint32" => u32::from_le_bytes(b.try_into().unwrap()) as f64,
            "float" | "float32" => f32::from_le_bytes(b.try_into().unwrap()) as f64,
            _ => f64::from_le_bytes(b.try_into().unwrap()),
        })
    };
    // Every instance of an element takes at least one byte (binary) or one
    // token (ASCII) of the body: a count past that is a damaged header, refused
    // before any loop or allocation runs on it.
    for (name, count, props) in &elements {
        if props.is_empty() {
            return Err(err(format!("element {name} has no properties")));
        }
        if *count > body.len() {
            return Err(err(format!(
                "element {name} declares {count} entries but the body has {} bytes",
                body.len()
            )));
        }
        let has = |axis: &str| props.iter().any(|(p, _, list)| p == axis && list.is_none());
        if name == "vertex" && !(has("x") && has("y") && has("z")) {
            return Err(err("vertex element without x, y and z properties".into()));
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
                        return Err(err(format!("list {pname} of {n} entries")));
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
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}
