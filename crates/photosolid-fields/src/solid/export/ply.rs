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
    let end = find(bytes, b"end_header\n")
        .ok_or_else(|| at_line(0, "a header ending in an `end_header` line", "none".into()))?;
    let header = std::str::from_utf8(&bytes[..end]).map_err(|e| {
        let line = bytes[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + 1;
        at_line(line, "a UTF-8 text header", "bytes that are not UTF-8".into())
    })?;
    let body_start = end + b"end_header\n".len();
    let body = &bytes[body_start..];
    // The body's first line (ASCII): the header's lines and `end_header`.
    let body_line = header.lines().count() + 2;
    let (binary, elements, element_lines) = parse_header(header)?;
    // ASCII: the body as text (checked before the elements, as ever).
    let text = if binary {
        None
    } else {
        Some(std::str::from_utf8(body).map_err(|e| {
            let line = body[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + body_line;
            at_line(
                line,
                "a UTF-8 text body (format ascii)",
                "bytes that are not UTF-8".into(),
            )
        })?)
    };
    check_elements(&elements, &element_lines, body.len())?;
    let (positions, triangles) = match text {
        None => read_elements(
            &elements,
            body.len(),
            &mut BinaryBody {
                body,
                body_start,
                pos: 0,
            },
        )?,
        Some(text) => {
            let mut scalars = AsciiBody {
                tokens: text
                    .lines()
                    .enumerate()
                    .flat_map(|(i, l)| l.split_ascii_whitespace().map(move |t| (i, t))),
                first_line: body_line,
                n_lines: body.iter().filter(|&&b| b == b'\n').count(),
            };
            read_elements(&elements, body.len(), &mut scalars)?
        }
    };
    let origin = positions.iter().position(|p| *p == [0.0; 3]).map(|i| i as u32);
    Mesh::from_parts(positions, triangles, origin, SolidInfo::default())
        .map_err(|source| MeshFileError::Mesh { format: "PLY", source })
}

/// An error at `line` (1-based) of a PLY file.
fn at_line(line: usize, expected: &str, found: String) -> MeshFileError {
    MeshFileError::at_line("PLY", line, expected, found)
}

/// The header's format (true: binary little endian, false: ASCII), its
/// elements, and the line of each element's `element` line.
fn parse_header(header: &str) -> Result<(bool, Vec<Element>, Vec<usize>), MeshFileError> {
    let mut binary = true;
    // (element name, count, properties (name, type, list count type)), and each element's header line.
    let mut elements: Vec<Element> = Vec::new();
    let mut element_lines: Vec<usize> = Vec::new();
    for (i, line) in header.lines().enumerate() {
        let ln = i + 1;
        let w: Vec<&str> = line.split_whitespace().collect();
        let no_element = || at_line(ln, "an `element` line before the first `property`", format!("`{line}`"));
        match w.as_slice() {
            ["format", "ascii", ..] => binary = false,
            ["format", "binary_little_endian", ..] => binary = true,
            ["format", f, ..] => {
                return Err(at_line(
                    ln,
                    "format ascii or binary_little_endian",
                    format!("format {f}, which is not read"),
                ))
            }
            ["element", name, n] => {
                let count = n
                    .parse()
                    .map_err(|_| at_line(ln, "`element NAME COUNT` with a whole count", format!("`{line}`")))?;
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
    Ok((binary, elements, element_lines))
}

/// Refuses a damaged header before any loop or allocation runs on it: every
/// instance of an element takes at least one byte (binary) or one token
/// (ASCII) of the body (`body_len` bytes), so a count past that is refused;
/// so is an element without properties, or vertices without x, y and z.
fn check_elements(elements: &[Element], element_lines: &[usize], body_len: usize) -> Result<(), MeshFileError> {
    for ((name, count, props), &ln) in elements.iter().zip(element_lines) {
        if props.is_empty() {
            return Err(at_line(
                ln,
                "at least one `property` per element",
                format!("element {name} has no properties"),
            ));
        }
        if *count > body_len {
            return Err(at_line(
                ln,
                "at most one entry per byte of the body",
                format!("element {name} declares {count} entries but the body has {body_len} bytes"),
            ));
        }
        let has = |axis: &str| props.iter().any(|(p, _, list)| p == axis && list.is_none());
        if name == "vertex" && !(has("x") && has("y") && has("z")) {
            return Err(at_line(
                ln,
                "vertex properties x, y and z",
                "vertex element without x, y and z properties".into(),
            ));
        }
    }
    Ok(())
}

/// Vertex positions and triangles (vertex indices) read from a body.
type Geometry = (Vec<[f32; 3]>, Vec<[u32; 3]>);

/// The body's values one at a time, each read as the property type it is
/// declared with.
trait Scalars {
    /// The next value, of PLY type `t`.
    fn scalar(&mut self, t: &str) -> Result<f64, MeshFileError>;
}

/// A binary little-endian body from byte `pos` on (`body_start`: its offset in the file).
struct BinaryBody<'a> {
    body: &'a [u8],
    body_start: usize,
    pos: usize,
}

impl Scalars for BinaryBody<'_> {
    fn scalar(&mut self, t: &str) -> Result<f64, MeshFileError> {
        let at = Some(self.body_start + self.pos);
        let n = type_size(t).ok_or_else(|| {
            MeshFileError::at_byte(
                "PLY",
                at,
                "a property type char, uchar, short, ushort, int, uint, float or double",
                format!("`{t}`"),
            )
        })?;
        let b = self.body.get(self.pos..self.pos + n).ok_or_else(|| {
            MeshFileError::at_byte("PLY", at, format!("a {t} ({n} bytes)"), "end of file (truncated)")
        })?;
        self.pos += n;
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
    }
}

/// Bytes of a binary PLY scalar type; `None` for a type that is not one.
fn type_size(t: &str) -> Option<usize> {
    match t {
        "char" | "uchar" | "int8" | "uint8" => Some(1),
        "short" | "ushort" | "int16" | "uint16" => Some(2),
        "int" | "uint" | "float" | "int32" | "uint32" | "float32" => Some(4),
        "double" | "float64" => Some(8),
        _ => None,
    }
}

/// An ASCII body: its tokens with their 0-based line in the body, which
/// starts at line `first_line` of the file and has `n_lines` lines.
struct AsciiBody<I> {
    tokens: I,
    first_line: usize,
    n_lines: usize,
}

impl<'a, I: Iterator<Item = (usize, &'a str)>> Scalars for AsciiBody<I> {
    fn scalar(&mut self, t: &str) -> Result<f64, MeshFileError> {
        match self.tokens.next() {
            Some((i, s)) => s
                .parse::<f64>()
                .map_err(|_| at_line(self.first_line + i, &format!("a number ({t})"), format!("`{s}`"))),
            None => Err(at_line(
                self.first_line + self.n_lines,
                &format!("a number ({t})"),
                "end of file".into(),
            )),
        }
    }
}

/// The vertex positions and the faces (fanned into triangles) of the body
/// (`body_len` bytes), element by element; other elements and properties
/// are read past.
fn read_elements(elements: &[Element], body_len: usize, scalars: &mut impl Scalars) -> Result<Geometry, MeshFileError> {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (name, count, props) in elements {
        for _ in 0..*count {
            let mut xyz = [0.0f32; 3];
            for (pname, t, list) in props {
                if let Some(ct) = list {
                    let n = scalars.scalar(ct)?;
                    if !(n >= 0.0 && n <= body_len as f64 && n.fract() == 0.0) {
                        return Err(MeshFileError::at_byte(
                            "PLY",
                            None,
                            format!("a length of list {pname} within the body ({body_len} bytes)"),
                            format!("list {pname} of {n} entries"),
                        ));
                    }
                    let n = n as usize;
                    let mut idx = Vec::with_capacity(n);
                    for _ in 0..n {
                        idx.push(scalars.scalar(t)? as u32);
                    }
                    if name == "face" && (pname == "vertex_indices" || pname == "vertex_index") {
                        for k in 1..n.saturating_sub(1) {
                            triangles.push([idx[0], idx[k], idx[k + 1]]);
                        }
                    }
                } else {
                    let v = scalars.scalar(t)?;
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
    Ok((positions, triangles))
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}
