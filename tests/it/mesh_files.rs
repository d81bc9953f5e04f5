//! Written mesh files as a reader sees them: every format read back with the
//! crate's own readers, vertices merged by position (as STL readers, trimesh
//! and Blender do), must be a closed 2-manifold with the solid's components,
//! also where several sheets of the solid meet at the origin.

use crate::common;

use photosolid::solid::export::{self, MeshFormat};
use photosolid::solid::{grid_solid, measured_solid, topology, Mesh, SolidGrid, Units, SHEET_SEPARATION};

const FORMATS: [MeshFormat; 4] = [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Stl, MeshFormat::Glb];

/// Write `m` in every format, read each file back, check its topology and volume.
fn check_files(m: &Mesh, what: &str) {
    let r = m.sanity_check().unwrap_or_else(|e| panic!("{what}: {e}"));
    let dir = tempfile::tempdir().unwrap();
    for f in FORMATS {
        let path = dir.path().join(format!("solid.{}", f.extension()));
        export::write(m, &path).unwrap();
        let back = export::read(&path).unwrap_or_else(|e| panic!("{what} {f:?}: {e}"));
        let t = topology(back.positions(), back.triangles());
        assert!(t.watertight && t.manifold, "{what} {f:?}: {t:?}");
        assert_eq!(t.components, r.components, "{what} {f:?}");
        assert_eq!(t.euler_characteristic, 2 * r.components as i64, "{what} {f:?}");
        // The separated copies move by at most SHEET_SEPARATION x the largest radius.
        assert_close!(back.volume(), m.volume(), rel = 1e-4, "{what} {f:?}: volume");
        let r_back = back
            .sanity_check()
            .unwrap_or_else(|e| panic!("{what} {f:?} read back: {e}"));
        assert_eq!(
            (r_back.pinch_vertices, r_back.components),
            (0, r.components),
            "{what} {f:?}"
        );
    }
}

/// Several sheets meeting at the origin: two lobes; a dark nadir dimple under
/// a flat top (zero above 90°); a thin lit band between dark bands (three
/// coaxial sheets). Before the split the mesh is pinched (watertight, not
/// manifold); every written file is manifold.
#[test]
fn pinched_solids_are_written_as_manifolds() {
    type Case = (&'static str, fn(f64, f64) -> f64, usize);
    let cases: [Case; 3] = [
        ("two lobes", |_, g| (g.to_radians().cos().abs() - 0.2).max(0.0), 2),
        (
            "dimple under a flat top",
            |_, g| if g > 0.0 && g <= 90.0 { 100.0 } else { 0.0 },
            1,
        ),
        (
            "thin band",
            |_, g| if g < 74.0 || (g > 82.0 && g < 89.0) { 100.0 } else { 0.0 },
            2,
        ),
    ];
    for (what, f, components) in cases {
        let m = grid_solid(&f, &SolidGrid::uniform(48, 72).unwrap(), Units::Candela).unwrap();
        let r = m.sanity_check().unwrap();
        assert!(r.origin_sheets >= 2, "{what}: {r:?}");
        assert_eq!(r.components, components, "{what}");
        let pinched = topology(m.positions(), m.triangles());
        assert!(pinched.watertight && !pinched.manifold, "{what}: {pinched:?}");
        let sep = m.separate_sheets();
        let moved = m.max_radius() * SHEET_SEPARATION * 1.0001;
        assert!(sep
            .positions()
            .iter()
            .all(|p| p.iter().map(|x| x * x).sum::<f32>().sqrt() <= moved as f32 || m.positions().contains(p)));
        check_files(&m, what);
    }
}

/// Every corpus file that loads: its measured solid, written in every format, reads back as a manifold.
#[test]
fn corpus_measured_solids_are_written_as_manifolds() {
    let Some(root) = common::corpus() else { return };
    let mut pinched = 0;
    for e in common::manifest(&root)
        .into_iter()
        .filter(|e| e.photometric() && !e.malformed())
    {
        let Ok(lum) = photosolid::load(&e.path) else { continue };
        let Ok(m) = measured_solid(lum.distribution(), Units::Candela) else {
            continue;
        };
        if m.sanity_check().unwrap().origin_sheets > 1 {
            pinched += 1;
        }
        check_files(&m, &e.rel);
    }
    assert!(pinched > 0, "the corpus has solids with several sheets at the origin");
}

/// Damaged mesh files give an error naming the file: counts and offsets past
/// the data are refused before any loop or allocation runs on them, and
/// arithmetic on them cannot overflow (these hung, allocated or panicked).
#[test]
fn damaged_mesh_files_are_refused() {
    let t = tempfile::tempdir().unwrap();
    let ply = |body: &str| format!("ply\nformat ascii 1.0\n{body}");
    let glb = |json: &str, bin: &[u8]| {
        let mut j = json.as_bytes().to_vec();
        while !j.len().is_multiple_of(4) {
            j.push(b' ');
        }
        let total = 12 + 8 + j.len() + 8 + bin.len();
        let mut out = b"glTF".to_vec();
        for v in [2u32, total as u32, j.len() as u32, 0x4E4F_534A] {
            out.extend(v.to_le_bytes());
        }
        out.extend(&j);
        out.extend((bin.len() as u32).to_le_bytes());
        out.extend(0x004E_4942u32.to_le_bytes());
        out.extend(bin);
        out
    };
    let view = |offset: &str, count: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":36}}],
            "bufferViews":[{{"buffer":0,"byteOffset":{offset},"byteLength":36}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":{count},"type":"VEC3"}}],
            "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}]}}"#
        )
    };
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "huge.ply",
            ply("element vertex 1000000000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n").into(),
            "declares 1000000000000000000 entries",
        ),
        (
            "nolist.ply",
            ply("element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n").into(),
            "list vertex_indices of 4000000000 entries",
        ),
        (
            "empty-element.ply",
            ply("element vertex 1000000000\nend_header\n").into(),
            "element vertex has no properties",
        ),
        (
            "noxyz.ply",
            ply("element vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n").into(),
            "without x, y and z",
        ),
        ("offset.glb", glb(&view("18446744073709551615", "3"), &[0; 36]), "past the BIN chunk"),
        ("count.glb", glb(&view("0", "4611686018427387904"), &[0; 36]), "POSITION is not float VEC3"),
    ];
    for (name, bytes, expected) in cases {
        let path = t.path().join(name);
        std::fs::write(&path, &bytes).unwrap();
        let e = export::read(&path).expect_err(name).to_string();
        assert!(
            e.starts_with(&path.display().to_string()) && e.contains(expected),
            "{name}: {e}"
        );
    }
}
