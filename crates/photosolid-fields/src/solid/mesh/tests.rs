use super::*;

fn tetra() -> Mesh {
    let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    Mesh::from_parts(p, t, None, SolidInfo::default()).unwrap()
}

#[test]
fn tetrahedron_volume_area_and_check() {
    let mut m = tetra();
    assert!((m.volume() - 1.0 / 6.0).abs() < 1e-12);
    let area = 1.5 + 3f64.sqrt() / 2.0;
    assert!((m.area() - area).abs() < 1e-6);
    m.compute_normals();
    let r = m.sanity_check().unwrap();
    assert_eq!((r.euler_characteristic, r.components, r.edges), (2, 1, 6));
}

#[test]
fn check_finds_flipped_open_and_degenerate() {
    let m = tetra();
    let mut flipped = m.triangles.clone();
    flipped[3] = [1, 3, 2];
    let f = Mesh::from_parts(m.positions.clone(), flipped, None, SolidInfo::default()).unwrap();
    assert!(matches!(
        f.sanity_check(),
        Err(SanityError::InconsistentOrientation { .. })
    ));
    let open = Mesh::from_parts(
        m.positions.clone(),
        m.triangles[..3].to_vec(),
        None,
        SolidInfo::default(),
    )
    .unwrap();
    assert!(matches!(open.sanity_check(), Err(SanityError::OpenEdge { .. })));
    let inward: Vec<[u32; 3]> = m.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let i = Mesh::from_parts(m.positions.clone(), inward, None, SolidInfo::default()).unwrap();
    assert!(matches!(i.sanity_check(), Err(SanityError::InwardFacing { .. })));
    let mut p = m.positions.clone();
    p[3] = [0.5, 0.5, 0.0]; // on the hypotenuse of the face 0-1-2 plane: face 1-2-3 collinear
    let d = Mesh::from_parts(p, m.triangles.clone(), None, SolidInfo::default()).unwrap();
    assert!(matches!(d.sanity_check(), Err(SanityError::Degenerate { .. })));
}
