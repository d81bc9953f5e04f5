//! glTF 2.0 binary (.glb): one scene, one node, one mesh, one triangle
//! primitive with `POSITION` (with the min/max glTF requires), optional
//! `NORMAL` and `COLOR_0` (RGBA unsigned byte, normalized: every attribute
//! element stays 4-byte aligned), and `u32` indices. The node rotates the
//! luminaire frame (z up) into glTF's +Y up (−90° about x), so the data in
//! the buffer are the mesh's coordinates unchanged. Metadata (units, kind,
//! frame) go into `asset.extras` and `meshes[0].extras`.

use serde_json::json;

use crate::error::MeshFileError;
use crate::solid::{Mesh, SolidInfo};

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_BYTE: u32 = 5121;
const UNSIGNED_INT: u32 = 5125;

/// The .glb file's bytes.
pub fn encode(mesh: &Mesh) -> Vec<u8> {
    let (doc, bin) = document(mesh);
    pack(&doc, bin)
}

/// The glTF JSON document and the binary buffer of `mesh`, before packing:
/// callers that add to the scene (lights, more buffer views) extend both and
/// then [`pack`] them. Node 0 is the solid (luminaire frame → glTF +Y up);
/// `buffers[0].byteLength` must be updated when `bin` grows (see [`pack`]).
pub fn document(mesh: &Mesh) -> (serde_json::Value, Vec<u8>) {
    let nv = mesh.n_vertices();
    let nf = mesh.n_triangles();
    let normals = mesh.normals();
    let colors = mesh.colors();
    let bin_len = 12 * nv + normals.map_or(0, |_| 12 * nv) + colors.map_or(0, |_| 4 * nv) + 12 * nf;
    let mut bin: Vec<u8> = Vec::with_capacity(bin_len);
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut attributes = serde_json::Map::new();

    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in mesh.positions() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
            bin.extend_from_slice(&p[k].to_le_bytes());
        }
    }
    views.push(json!({"buffer": 0, "byteOffset": 0, "byteLength": 12 * nv, "target": ARRAY_BUFFER}));
    accessors.push(json!({"bufferView": 0, "componentType": FLOAT, "count": nv, "type": "VEC3", "min": lo, "max": hi}));
    attributes.insert("POSITION".into(), json!(0));
    if let Some(n) = normals {
        let offset = bin.len();
        for v in n {
            for x in v {
                bin.extend_from_slice(&x.to_le_bytes());
            }
        }
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": 12 * nv, "target": ARRAY_BUFFER}));
        accessors.push(json!({"bufferView": views.len() - 1, "componentType": FLOAT, "count": nv, "type": "VEC3"}));
        attributes.insert("NORMAL".into(), json!(accessors.len() - 1));
    }
    if let Some(c) = colors {
        let offset = bin.len();
        for v in c {
            bin.extend_from_slice(&[v[0], v[1], v[2], 255]);
        }
        views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": 4 * nv, "target": ARRAY_BUFFER}));
        accessors.push(json!({"bufferView": views.len() - 1, "componentType": UNSIGNED_BYTE, "normalized": true, "count": nv, "type": "VEC4"}));
        attributes.insert("COLOR_0".into(), json!(accessors.len() - 1));
    }
    let offset = bin.len();
    for t in mesh.triangles() {
        for v in t {
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    views.push(json!({"buffer": 0, "byteOffset": offset, "byteLength": 12 * nf, "target": ELEMENT_ARRAY_BUFFER}));
    accessors
        .push(json!({"bufferView": views.len() - 1, "componentType": UNSIGNED_INT, "count": 3 * nf, "type": "SCALAR"}));
    let indices = accessors.len() - 1;

    let info = mesh.info();
    let extras = json!({
        "photosolid": {
            "kind": info.kind,
            "source": info.source,
            "units": info.units.name(),
            "units_description": info.units.describe(),
            "units_per_cd": info.units_per_cd,
            "frame": crate::solid::UNIT_FRAME,
            "node_rotation": "-90 deg about x: luminaire z up -> glTF +Y up",
            "origin_vertex": mesh.origin_vertex(),
        }
    });
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let doc = json!({
        "asset": {"version": "2.0", "generator": concat!("photosolid ", env!("CARGO_PKG_VERSION")), "extras": extras},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "photometric solid", "rotation": [-s, 0.0, 0.0, s]}],
        "meshes": [{"name": "photometric solid", "primitives": [{"attributes": attributes, "indices": indices, "mode": 4, "material": 0}], "extras": extras}],
        "materials": [{"name": "solid", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": views,
        "accessors": accessors,
    });
    (doc, bin)
}

/// Pack a glTF document and its binary buffer into .glb bytes; the buffer is
/// padded to 4 bytes and `buffers[0].byteLength` set to its unpadded length.
pub fn pack(doc: &serde_json::Value, mut bin: Vec<u8>) -> Vec<u8> {
    let mut doc = doc.clone();
    doc["buffers"] = json!([{"byteLength": bin.len()}]);
    let mut json_bytes = doc.to_string().into_bytes();
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_bytes);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// Read the first triangle primitive of a .glb file of the kind [`encode`]
/// writes: `POSITION` as float VEC3 (tightly packed), indices as unsigned
/// byte, short or int (or none: consecutive triples). The node transform is
/// not applied: the coordinates are the buffer's, the luminaire frame.
/// The vertex at exactly (0, 0, 0), if any, is taken as the origin vertex.
pub fn read(bytes: &[u8]) -> Result<Mesh, MeshFileError> {
    let (doc, bin) = chunks(bytes)?;
    let prim = &doc["meshes"][0]["primitives"][0];
    let mode = prim.get("mode").and_then(|m| m.as_u64()).unwrap_or(4);
    if mode != 4 {
        return Err(doc_error(
            "a triangle list (mode 4) as the first primitive",
            format!("mode {mode}"),
        ));
    }
    let (pdata, nv, ptype) = accessor(&doc, bin, &prim["attributes"]["POSITION"])?;
    let position_bytes = nv.checked_mul(12).filter(|&b| b <= pdata.len());
    let (Some(position_bytes), true) = (position_bytes, ptype == u64::from(FLOAT)) else {
        return Err(doc_error(
            "POSITION as float VEC3 within its bufferView",
            format!(
                "POSITION is not float VEC3 within its bufferView (component type {ptype}, {nv} vertices, {} bytes)",
                pdata.len()
            ),
        ));
    };
    let positions: Vec<[f32; 3]> = pdata[..position_bytes]
        .chunks_exact(12)
        .map(|c| [0, 1, 2].map(|k| super::le_f32(c, 4 * k)))
        .collect();
    let indices: Vec<u32> = match prim.get("indices") {
        None => (0..nv as u32).collect(),
        Some(a) => indices(&doc, bin, a)?,
    };
    if !indices.len().is_multiple_of(3) {
        return Err(doc_error(
            "a multiple of 3 indices (triangles)",
            format!("{} indices", indices.len()),
        ));
    }
    let triangles = indices.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let origin = positions.iter().position(|p| *p == [0.0; 3]).map(|i| i as u32);
    Mesh::from_parts(positions, triangles, origin, SolidInfo::default())
        .map_err(|source| MeshFileError::Mesh { format: "glTF", source })
}

/// An error at byte `offset` of a .glb file.
fn at(offset: usize, expected: &str, found: String) -> MeshFileError {
    MeshFileError::at_byte("glTF", Some(offset), expected, found)
}

/// An error in the glTF document (no byte offset to point at).
fn doc_error(expected: &str, found: String) -> MeshFileError {
    MeshFileError::at_byte("glTF", None, expected, found)
}

/// The JSON document and the BIN chunk of a .glb file (header checked).
fn chunks(bytes: &[u8]) -> Result<(serde_json::Value, &[u8]), MeshFileError> {
    let u32_at = |o: usize| -> Result<usize, MeshFileError> {
        let b = bytes
            .get(o..o + 4)
            .ok_or_else(|| at(o, "a 4-byte integer", "end of file".into()))?;
        Ok(super::le_u32(b, 0) as usize)
    };
    if bytes.get(..4) != Some(b"glTF".as_slice()) || u32_at(4)? != 2 {
        return Err(at(
            0,
            "a glTF 2.0 binary (.glb) header (`glTF`, version 2)",
            "other bytes".into(),
        ));
    }
    let json_len = u32_at(12)?;
    let json_bytes = bytes
        .get(20..20 + json_len)
        .ok_or_else(|| at(20, &format!("a JSON chunk of {json_len} bytes"), "end of file".into()))?;
    let doc: serde_json::Value = serde_json::from_slice(json_bytes)
        .map_err(|e| at(20, "a JSON chunk", format!("JSON that does not parse: {e}")))?;
    let bin_at = 20 + json_len;
    let bin_len = u32_at(bin_at)?;
    let bin = bytes.get(bin_at + 8..bin_at + 8 + bin_len).ok_or_else(|| {
        at(
            bin_at + 8,
            &format!("a BIN chunk of {bin_len} bytes"),
            "end of file".into(),
        )
    })?;
    Ok((doc, bin))
}

/// The data in `bin` of the accessor `a` indexes in `doc`, its count and
/// its component type (0 when absent).
fn accessor<'b>(
    doc: &serde_json::Value,
    bin: &'b [u8],
    a: &serde_json::Value,
) -> Result<(&'b [u8], usize, u64), MeshFileError> {
    let i = a
        .as_u64()
        .ok_or_else(|| doc_error("an accessor index", "none".into()))? as usize;
    let acc = &doc["accessors"][i];
    let view = &doc["bufferViews"][acc["bufferView"]
        .as_u64()
        .ok_or_else(|| doc_error("a bufferView in the accessor", "an accessor without bufferView".into()))?
        as usize];
    if view.get("byteStride").is_some() {
        return Err(doc_error(
            "tightly packed buffer views",
            "an interleaved one (byteStride), which is not read".into(),
        ));
    }
    // Offsets and lengths come from the file: added with overflow checks,
    // so a damaged document is refused rather than wrapping or panicking.
    let offset = |v: &serde_json::Value| v["byteOffset"].as_u64().unwrap_or(0);
    let len = view["byteLength"].as_u64().ok_or_else(|| {
        doc_error(
            "a byteLength in the bufferView",
            "a bufferView without byteLength".into(),
        )
    })?;
    let range = offset(view).checked_add(offset(acc)).and_then(|start| {
        Some((
            usize::try_from(start).ok()?,
            usize::try_from(start.checked_add(len)?).ok()?,
        ))
    });
    let data = range.and_then(|(start, end)| bin.get(start..end)).ok_or_else(|| {
        doc_error(
            "a bufferView within the BIN chunk",
            "a bufferView past the BIN chunk".into(),
        )
    })?;
    let count = acc["count"]
        .as_u64()
        .ok_or_else(|| doc_error("a count in the accessor", "an accessor without count".into()))?
        as usize;
    Ok((data, count, acc["componentType"].as_u64().unwrap_or(0)))
}

/// The vertex indices of the index accessor `a` (unsigned byte, short or int).
fn indices(doc: &serde_json::Value, bin: &[u8], a: &serde_json::Value) -> Result<Vec<u32>, MeshFileError> {
    let (data, n, t) = accessor(doc, bin, a)?;
    let size = match t {
        5121 => 1,
        5123 => 2,
        5125 => 4,
        _ => {
            return Err(doc_error(
                "indices as unsigned byte, short or int",
                format!("component type {t}"),
            ))
        }
    };
    let data = n.checked_mul(size).and_then(|bytes| data.get(..bytes)).ok_or_else(|| {
        doc_error(
            "an index accessor within its bufferView",
            format!("{n} indices of {size} bytes in {} bytes", data.len()),
        )
    })?;
    Ok(data
        .chunks_exact(size)
        .map(|c| match size {
            1 => u32::from(c[0]),
            2 => u32::from(u16::from_le_bytes([c[0], c[1]])),
            _ => super::le_u32(c, 0),
        })
        .collect())
}
