//! The CLI where a new user hit wrong outputs and rough edges (issue 12):
//! the real binary, run in a temporary directory per test.

mod common;

use common::cli::{bin, fails, ok, run, write_ies};
use photosolid::solid::{export, topology};

/// A downlight dark at nadir and above the horizontal: two sheets meet at the
/// origin (a dimple under a flat top). Every written format must read back
/// watertight and manifold, and `--json` must say so from a real check.
#[test]
fn mesh_json_reports_the_written_files_topology() {
    let t = tempfile::tempdir().unwrap();
    let gamma: Vec<f64> = (0..=18).map(|k| 10.0 * k as f64).collect();
    let cd: Vec<f64> = gamma
        .iter()
        .map(|&g| if g > 0.0 && g <= 90.0 { 100.0 } else { 0.0 })
        .collect();
    write_ies(t.path(), "dimple.ies", 1000.0, &gamma, &cd);
    for ext in ["ply", "obj", "stl", "glb"] {
        let out = format!("s.{ext}");
        let v: serde_json::Value = serde_json::from_str(&ok(&run(
            &["mesh", "dimple.ies", "--measured", "-o", &out, "--json"],
            t.path(),
        )))
        .unwrap();
        assert_eq!(v["origin_sheets"], 2, "{ext}: {v}");
        assert_eq!(
            (&v["watertight"], &v["manifold"], &v["components"]),
            (&true.into(), &true.into(), &1.into()),
            "{ext}: {v}"
        );
        let back = export::read(&t.path().join(&out)).unwrap();
        let topo = topology(back.positions(), back.triangles());
        assert!(
            topo.watertight && topo.manifold && topo.components == 1,
            "{ext}: {topo:?}"
        );
        assert_eq!(v["vertices"], back.positions().len(), "{ext}");
    }
}
