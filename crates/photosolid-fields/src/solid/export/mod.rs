//! Mesh export: OBJ, binary PLY, binary STL and binary glTF (.glb), all
//! from one [`Mesh`], each file written atomically through
//! [`crate::formats::write_atomic`] (one buffer, sized up front, one write).
//!
//! | format | normals | per-vertex colour | metadata (units, kind, frame) |
//! |---|---|---|---|
//! | OBJ | `vn`, `f a//a` | `v x y z r g b` (floats in [0, 1]; read by trimesh, Blender, MeshLab) | `#` comments |
//! | PLY (binary little endian) | `nx ny nz` | `red green blue` (uchar) | `comment` lines |
//! | STL (binary) | one per facet, recomputed | **none: STL has no per-vertex colour** | the 80-byte header (truncated) |
//! | glTF 2.0 binary (.glb) | `NORMAL` | `COLOR_0` (RGBA unsigned byte, normalized) | `asset.extras` and `meshes[0].extras` |
//!
//! Coordinates are written in the luminaire frame (z up) unchanged, except
//! that the glTF node carries a −90° rotation about x, because glTF is +Y
//! up: viewers (and Blender's importer) then show nadir down. When importing
//! OBJ into Blender, choose "Up: Z" (its OBJ default is Y up).
//! Pinch points (the origin where several sheets meet) are split per sheet
//! in every file ([`Mesh::separate_sheets`]).
//! The readers here ([`read`]: [`ply::read`], [`obj::read`], [`stl::read`], [`glb::read`]) read back what the
//! writers write (and simple files like it); they are for tests and for
//! loading reference solids, not general-purpose importers.

pub mod glb;
pub mod obj;
pub mod ply;
pub mod stl;

use std::path::Path;

use super::Mesh;
use crate::error::{Error, Result};

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (text).
    Obj,
    /// Stanford PLY, binary little endian.
    Ply,
    /// STL, binary.
    Stl,
    /// glTF 2.0 binary container (.glb).
    Glb,
}

impl MeshFormat {
    /// From a file extension (any case): `obj`, `ply`, `stl`, `glb`.
    pub fn from_path(path: &Path) -> Option<Self> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "obj" => Some(Self::Obj),
            "ply" => Some(Self::Ply),
            "stl" => Some(Self::Stl),
            "glb" => Some(Self::Glb),
            _ => None,
        }
    }

    /// The error for a path whose extension names no mesh format.
    pub fn unknown_extension(path: &Path) -> Error {
        Error::UnknownExtension {
            path: path.to_path_buf(),
            what: "mesh format",
            accepted: &[".obj", ".ply", ".stl", ".glb"],
        }
    }

    /// The usual extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Ply => "ply",
            Self::Stl => "stl",
            Self::Glb => "glb",
        }
    }
}

/// The file's bytes for `mesh` in `format`: the mesh with its sheets
/// separated at pinch points ([`Mesh::separate_sheets`]), so that every
/// format (STL included, which has no shared vertices) reads back as a
/// closed 2-manifold.
pub fn encode(mesh: &Mesh, format: MeshFormat) -> Vec<u8> {
    let mesh = &*mesh.separate_sheets();
    match format {
        MeshFormat::Obj => obj::encode(mesh),
        MeshFormat::Ply => ply::encode(mesh),
        MeshFormat::Stl => stl::encode(mesh),
        MeshFormat::Glb => glb::encode(mesh),
    }
}

/// Write `mesh` to `path` in the format of its extension, atomically.
pub fn write(mesh: &Mesh, path: &Path) -> Result<()> {
    let format = MeshFormat::from_path(path).ok_or_else(|| MeshFormat::unknown_extension(path))?;
    write_as(mesh, path, format)
}

/// Write `mesh` to `path` in `format`, atomically. An empty mesh is refused
/// (glTF cannot hold one, and no solid is empty).
pub fn write_as(mesh: &Mesh, path: &Path, format: MeshFormat) -> Result<()> {
    if mesh.n_triangles() == 0 {
        return Err(crate::error::MeshError::Empty { path: path.into() }.into());
    }
    crate::formats::write_atomic(path, &encode(mesh, format))
}

/// Read a mesh file in any format this module writes (format from the
/// extension), with [`ply::read`], [`obj::read`], [`stl::read`] or [`glb::read`].
pub fn read(path: &Path) -> Result<Mesh> {
    let format = MeshFormat::from_path(path).ok_or_else(|| MeshFormat::unknown_extension(path))?;
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let mesh = match format {
        MeshFormat::Obj => obj::read(&bytes),
        MeshFormat::Ply => ply::read(&bytes),
        MeshFormat::Stl => stl::read(&bytes),
        MeshFormat::Glb => glb::read(&bytes),
    };
    mesh.map_err(|source| {
        crate::error::MeshError::File {
            path: path.into(),
            source: Box::new(source),
        }
        .into()
    })
}

/// The little-endian `u32` at byte `at` of `b` (the caller has checked the length).
pub(crate) fn le_u32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// The little-endian `f32` at byte `at` of `b` (the caller has checked the length).
pub(crate) fn le_f32(b: &[u8], at: usize) -> f32 {
    f32::from_bits(le_u32(b, at))
}

/// The units a mesh file records in its header (photosolid writes them in
/// every format: PLY `comment`, OBJ `#` lines, the STL header, the glTF
/// extras); `name` is `None` for a file without them (another tool's).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RecordedUnits {
    /// `cd`, `peak` or `cd/klm`.
    pub name: Option<&'static str>,
    /// Units per cd (the `scale:` line, glTF `units_per_cd`), when recorded:
    /// dividing coordinates by it gives cd.
    pub units_per_cd: Option<f64>,
}

/// The units recorded in the first 64 KiB of a mesh file's bytes (see
/// [`RecordedUnits`]).
pub fn recorded_units(bytes: &[u8]) -> RecordedUnits {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(64 * 1024)]);
    let mut r = RecordedUnits::default();
    let after = |key: &str| {
        head.find(key)
            .map(|i| head[i + key.len()..].trim_start_matches([' ', '"', ':']))
    };
    if let Some(text) = after("units: ") {
        r.name = if text.starts_with("cd/klm") {
            Some("cd/klm")
        } else if text.starts_with("cd") {
            Some("cd")
        } else if text.starts_with("relative to the peak") {
            Some("peak")
        } else {
            None
        };
    } else if let Some(text) = after("\"units\"") {
        r.name = ["cd/klm", "cd", "peak"]
            .into_iter()
            .find(|n| text.starts_with(&format!("{n}\"")));
    }
    let number = |text: &str| {
        let end = text
            .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+')))
            .unwrap_or(text.len());
        text[..end].parse::<f64>().ok().filter(|x| x.is_finite() && *x > 0.0)
    };
    r.units_per_cd = after("scale: ")
        .and_then(number)
        .or_else(|| after("\"units_per_cd\"").and_then(number));
    r
}

/// Mesh metadata lines, ASCII only (STL headers and some PLY readers need
/// it): non-ASCII characters become `?`, line breaks spaces.
pub(crate) fn ascii_lines(mesh: &Mesh) -> Vec<String> {
    mesh.info()
        .lines()
        .into_iter()
        .map(|l| {
            l.chars()
                .map(|c| match c {
                    '\n' | '\r' => ' ',
                    c if c.is_ascii() => c,
                    _ => '?',
                })
                .collect()
        })
        .collect()
}
