//! Photometric-solid meshes: closed forms, convergence rates, invariants over
//! many synthetic distributions, and exports read back.

use std::f64::consts::PI;

use photosolid::model::{Distribution, Symmetry};
use photosolid::solid::export::{self, MeshFormat};
use photosolid::solid::{
    check_measured, grid_solid, measured_solid, CheckError, ColorMap, Mesh, SanityReport, SolidGrid, Units,
};
use photosolid::synth::{GridSpec, Synth};
use photosolid::ModelError;

fn all_kinds() -> Vec<Synth> {
    vec![
        Synth::Isotropic,
        Synth::Lambertian,
        Synth::CosinePower { p: 5.0 },
        Synth::Spot {
            p: 4.0,
            cutoff_deg: 40.0,
        },
        Synth::Batwing,
        Synth::Roadway,
    ]
}

fn check(m: &Mesh, what: &str) -> SanityReport {
    m.sanity_check().unwrap_or_else(|e| panic!("{what}: {e}"))
}

/// Volume error of the grid solid at n x n/2 and 2n x n: the ratio of the
/// errors shows the order (4 = second order).
fn grid_volume_errors(f: &(dyn Fn(f64, f64) -> f64 + Sync), exact: f64, n: usize) -> (f64, f64) {
    let e = |n: usize| {
        let m = grid_solid(&f, &SolidGrid::uniform(n, n / 2).unwrap(), Units::Candela).unwrap();
        check(&m, "convergence");
        (m.volume() - exact).abs()
    };
    (e(n), e(2 * n))
}

#[test]
fn isotropic_grid_solid_is_a_sphere_of_radius_i_second_order() {
    let i0 = 3.0;
    let exact = 4.0 / 3.0 * PI * i0 * i0 * i0;
    let (e1, e2) = grid_volume_errors(&|_, _| i0, exact, 36);
    let ratio = e1 / e2;
    assert!(e2 / exact < 5e-3, "fine error {}", e2 / exact);
    assert!((3.6..4.4).contains(&ratio), "ratio {ratio} ({e1} -> {e2})");
    // Area of the sphere 4π I², also second order.
    let m = grid_solid(
        &|_: f64, _: f64| i0,
        &SolidGrid::uniform(144, 72).unwrap(),
        Units::Candela,
    )
    .unwrap();
    assert_close!(m.area(), 4.0 * PI * i0 * i0, rel = 1e-3);
}

#[test]
fn lambertian_grid_solid_is_a_sphere_touching_the_origin_second_order() {
    let i0 = 2.0;
    let exact = PI * i0 * i0 * i0 / 6.0;
    let f = move |c: f64, g: f64| i0 * Synth::Lambertian.relative(c, g);
    let (e1, e2) = grid_volume_errors(&f, exact, 36);
    let ratio = e1 / e2;
    assert!(e2 / exact < 1e-2, "fine error {}", e2 / exact);
    assert!((3.6..4.4).contains(&ratio), "ratio {ratio} ({e1} -> {e2})");
    let m = grid_solid(&f, &SolidGrid::uniform(72, 36).unwrap(), Units::Candela).unwrap();
    let r = check(&m, "lambertian");
    // The whole upper hemisphere is one merged origin vertex: one sheet, one sphere.
    assert_eq!((r.origin_sheets, r.components, r.euler_characteristic), (1, 1, 2));
    assert_eq!(m.origin_vertex(), Some(0));
    // Vertices: the origin, the nadir, and the 17 rings 5..85 degrees of 72.
    assert_eq!(m.n_vertices(), 1 + 1 + 72 * 17);
}

#[test]
fn measured_lambertian_volume_converges_second_order() {
    let exact = PI / 6.0;
    let err = |step: f64| {
        let lum = Synth::Lambertian
            .build(&GridSpec::uniform(step, step).unwrap(), 1.0)
            .unwrap();
        let m = measured_solid(lum.distribution(), Units::Candela).unwrap();
        check(&m, "measured lambertian");
        (m.volume() - exact).abs()
    };
    let (e1, e2) = (err(10.0), err(5.0));
    assert!((3.5..4.5).contains(&(e1 / e2)), "ratio {} ({e1} -> {e2})", e1 / e2);
}

#[test]
fn measured_isotropic_on_nonuniform_partial_grid() {
    // C steps of 4, 5, 6 degrees; gamma 0-130.5 then 180 (a real-file shape).
    let mut c = Vec::new();
    let mut a = 0.0;
    let steps = [4.0, 5.0, 6.0];
    let mut k = 0;
    while a < 360.0 - 1e-9 {
        c.push(a);
        a += steps[k % 3];
        k += 1;
    }
    let mut gamma: Vec<f64> = (0..=29).map(|k| k as f64 * 4.5).collect();
    gamma.push(180.0);
    let n = c.len() * gamma.len();
    let d = Distribution::new(c.clone(), gamma.clone(), vec![100.0; n], Symmetry::None).unwrap();
    let m = measured_solid(&d, Units::Candela).unwrap();
    let r = check(&m, "non-uniform");
    // Every measured direction is a vertex, poles once, no origin (nothing is zero).
    assert_eq!(m.n_vertices(), c.len() * (gamma.len() - 2) + 2);
    assert_eq!(r.origin_sheets, 0);
    // The 130.5-180 gap is one chord facet: the polyhedron loses about 3 %.
    let exact = 4.0 / 3.0 * PI * 1e6;
    assert!(r.volume < exact, "{}", r.volume);
    assert_close!(r.volume, exact, rel = 0.05, "{}", r.volume);
    // Every vertex lies on the sphere of radius 100.
    for p in m.positions() {
        let rr = (p[0] as f64).hypot(p[1] as f64).hypot(p[2] as f64);
        assert_close!(rr, 100.0, abs = 1e-3);
    }
    // Stop at 130.5 (nothing above): the last ring joins the origin.
    let g2: Vec<f64> = gamma[..gamma.len() - 1].to_vec();
    let d2 = Distribution::new(c.clone(), g2.clone(), vec![100.0; c.len() * g2.len()], Symmetry::None).unwrap();
    let m2 = measured_solid(&d2, Units::Candela).unwrap();
    let r2 = check(&m2, "partial 0-130.5");
    assert_eq!((r2.origin_sheets, r2.components), (1, 1));
    assert_eq!(m2.n_vertices(), 1 + c.len() * (g2.len() - 1) + 1);
}

/// Every builder over every synthetic kind, grid shape and magnitude passes
/// the sanity check.
#[test]
fn sanity_over_many_synthetic_distributions() {
    let grids: Vec<(&str, GridSpec)> = vec![
        ("uniform 15x5", GridSpec::uniform(15.0, 5.0).unwrap()),
        ("uniform 5x2.5", GridSpec::uniform(5.0, 2.5).unwrap()),
        (
            "lower hemisphere 0-90",
            GridSpec::explicit(
                (0..24).map(|k| k as f64 * 15.0).collect(),
                (0..=18).map(|k| k as f64 * 5.0).collect(),
            ),
        ),
        (
            "upper hemisphere 90-180",
            GridSpec::explicit(
                (0..24).map(|k| k as f64 * 15.0).collect(),
                (18..=36).map(|k| k as f64 * 5.0).collect(),
            ),
        ),
        (
            "0-130.5 then 180",
            GridSpec::explicit((0..36).map(|k| k as f64 * 10.0).collect(), {
                let mut g: Vec<f64> = (0..=29).map(|k| k as f64 * 4.5).collect();
                g.push(180.0);
                g
            }),
        ),
        (
            "two gamma angles",
            GridSpec::explicit((0..12).map(|k| k as f64 * 30.0).collect(), vec![0.0, 60.0]),
        ),
    ];
    let mut n = 0;
    for (gname, grid) in &grids {
        for kind in all_kinds() {
            for i0 in [1e-6, 1.0, 1e6] {
                let what = format!("{} on {gname} at {i0} cd", kind.describe());
                let d = kind.build(grid, i0).unwrap().into_distribution();
                match check_measured(&d) {
                    Ok(r) => assert!(r.volume > 0.0, "{what}"),
                    // The upper-hemisphere grid of a downward kind is all zero.
                    // No solid: only round-off is lit (a downward kind on the upper
                    // grid), or only a pole (a spot seen at 0 and 60 degrees).
                    Err(CheckError::Build(ModelError::AllZero(_))) => {
                        let g = d.gamma_angles_deg();
                        let lit_inner = (0..d.n_c()).any(|ic| {
                            (0..g.len()).any(|ig| g[ig] > 0.0 && g[ig] < 180.0 && d.value_cd(ic, ig) > 1e-15 * i0)
                        });
                        assert!(!lit_inner, "{what}: AllZero with peak {}", d.max_cd())
                    }
                    Err(e) => panic!("{what}: {e}"),
                }
                // The same kind as an analytic field on a refined grid of the distribution.
                let f = move |c: f64, g: f64| i0 * kind.relative(c, g);
                for factor in [1, 3] {
                    let g = SolidGrid::refined(&d, factor).unwrap();
                    let m = match grid_solid(&f, &g, Units::Peak) {
                        Ok(m) => m,
                        // A grid too coarse to see anything but a pole spans no solid.
                        Err(ModelError::AllZero(_)) => {
                            let ga = g.gamma_angles_deg();
                            let lit = g
                                .c_angles_deg()
                                .iter()
                                .any(|&c| ga[1..ga.len() - 1].iter().any(|&gg| f(c, gg) > 1e-15 * i0));
                            assert!(!lit, "grid x{factor} of {what}: AllZero but lit");
                            continue;
                        }
                        Err(e) => panic!("grid x{factor} of {what}: {e}"),
                    };
                    let r = check(&m, &format!("grid x{factor} of {what}"));
                    assert_close!(m.max_radius(), 1.0, abs = 1e-6, "{what}: peak-relative");
                    assert!(r.volume > 0.0);
                    n += 1;
                }
            }
        }
    }
    assert!(n >= 100);
}

#[test]
fn single_plane_and_roadway_and_symmetries() {
    // A single C-plane with no symmetry: constant in C, expanded to 72 planes.
    let d = Distribution::new(
        vec![0.0],
        (0..=36).map(|k| k as f64 * 5.0).collect(),
        vec![7.0; 37],
        Symmetry::None,
    )
    .unwrap();
    let m = measured_solid(&d, Units::Candela).unwrap();
    check(&m, "single plane");
    assert_eq!(m.n_vertices(), 72 * 35 + 2);
    // Roadway: asymmetric, zero regions above the horizontal between the lobes.
    let road = Synth::Roadway
        .build(&GridSpec::uniform(5.0, 2.5).unwrap(), 1000.0)
        .unwrap()
        .into_distribution();
    for sym in [Symmetry::None, Symmetry::C90C270] {
        let r = check_measured(&road.with_symmetry(sym).unwrap()).unwrap();
        assert!(r.origin_sheets >= 1);
    }
    // Quadrant non-uniform planes.
    let q = Distribution::new(
        vec![0.0, 30.0, 90.0],
        (0..=18).map(|k| k as f64 * 10.0).collect(),
        (0..3 * 19).map(|i| 10.0 + (i % 19) as f64).collect(),
        Symmetry::Quadrant,
    )
    .unwrap();
    let m = measured_solid(&q, Units::Candela).unwrap();
    check(&m, "quadrant");
    assert_eq!(m.n_vertices(), 8 * 17 + 2);
}

/// A dark band at the horizontal: a downward and an upward lobe that meet
/// only at the origin. Two spheres sharing one vertex.
#[test]
fn dark_band_gives_two_sheets_at_the_origin() {
    let f = |_: f64, g: f64| (g.to_radians().cos().abs() - 0.2).max(0.0);
    let m = grid_solid(&f, &SolidGrid::uniform(48, 36).unwrap(), Units::Candela).unwrap();
    let r = check(&m, "dark band");
    assert_eq!((r.origin_sheets, r.components), (2, 2));
    let mut c = Vec::new();
    let g: Vec<f64> = (0..=36).map(|k| k as f64 * 5.0).collect();
    for _ in 0..24 {
        c.extend(g.iter().map(|&g| f(0.0, g)));
    }
    let d = Distribution::new((0..24).map(|k| k as f64 * 15.0).collect(), g, c, Symmetry::None).unwrap();
    let r = check_measured(&d).unwrap();
    assert_eq!((r.origin_sheets, r.components), (2, 2));
}

#[test]
fn all_zero_and_degenerate_inputs_are_errors() {
    let d = Distribution::new(vec![0.0], vec![0.0, 90.0, 180.0], vec![0.0; 3], Symmetry::Rotational).unwrap();
    assert!(matches!(
        measured_solid(&d, Units::Candela),
        Err(ModelError::AllZero(_))
    ));
    assert!(matches!(
        grid_solid(
            &|_: f64, _: f64| 0.0,
            &SolidGrid::uniform(8, 4).unwrap(),
            Units::Candela
        ),
        Err(ModelError::AllZero(_))
    ));
    assert!(matches!(
        grid_solid(
            &|_: f64, _: f64| f64::NAN,
            &SolidGrid::uniform(8, 4).unwrap(),
            Units::Candela
        ),
        Err(ModelError::Intensities(_))
    ));
    // One gamma angle spans no solid angle.
    let one = Distribution::new(vec![0.0], vec![45.0], vec![1.0], Symmetry::Rotational).unwrap();
    assert!(measured_solid(&one, Units::Candela).is_err());
    // Two planes 180 degrees apart cannot enclose the axis alone: planes are
    // inserted linearly in C, and the hemisphere of radius 1 closes.
    let two = Distribution::new(
        vec![0.0, 180.0],
        vec![0.0, 90.0],
        vec![1.0, 1.0, 1.0, 3.0],
        Symmetry::None,
    )
    .unwrap();
    let m = measured_solid(&two, Units::Candela).unwrap();
    check(&m, "two planes");
    // C0 and C180 stay vertices; the inserted C90 plane holds the mean at gamma 90.
    assert!(m
        .positions()
        .iter()
        .any(|p| (p[1] - 2.0).abs() < 1e-6 && p[2].abs() < 1e-6));
    // Negative values are clamped to zero, not mirrored through the origin.
    let neg = |_: f64, g: f64| if g < 90.0 { 1.0 } else { -1.0 };
    let m = grid_solid(&neg, &SolidGrid::uniform(12, 12).unwrap(), Units::Candela).unwrap();
    assert!(m.positions().iter().all(|p| p[2] <= 0.0));
    check(&m, "negative clamped");
}

#[test]
fn units_scale_and_metadata() {
    let lum = Synth::Isotropic
        .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 50.0)
        .unwrap();
    let d = lum.distribution();
    let cd = measured_solid(d, Units::Candela).unwrap();
    assert_close!(cd.max_radius(), 50.0, abs = 1e-4);
    let peak = measured_solid(d, Units::Peak).unwrap();
    assert_close!(peak.max_radius(), 1.0, abs = 1e-6);
    let klm = measured_solid(d, Units::per_kilolumen(d).unwrap()).unwrap();
    // Isotropic: Φ = 4π I, so 1000 I / Φ = 1000 / 4π cd/klm.
    assert_close!(klm.max_radius(), 1000.0 / (4.0 * PI), abs = 1e-3);
    for (m, word) in [(&cd, "units: cd"), (&peak, "units: relative"), (&klm, "units: cd/klm")] {
        for f in [MeshFormat::Obj, MeshFormat::Ply] {
            let bytes = export::encode(m, f);
            let text = String::from_utf8_lossy(&bytes[..bytes.len().min(2000)]).into_owned();
            assert!(text.contains(word), "{f:?} lacks {word}");
        }
        let stl = export::encode(m, MeshFormat::Stl);
        assert!(String::from_utf8_lossy(&stl[..80]).contains(word));
        assert!(!stl.starts_with(b"solid"));
        let json = glb_json(&export::encode(m, MeshFormat::Glb));
        assert_eq!(json["asset"]["extras"]["photosolid"]["units"], m.info().units.name());
    }
}

/// Validate a .glb container and return its JSON; checks the header, chunk
/// layout, buffer lengths, accessor ranges and POSITION min/max.
fn glb_json(b: &[u8]) -> serde_json::Value {
    let u32_at = |o: usize| u32::from_le_bytes(b[o..o + 4].try_into().unwrap()) as usize;
    assert_eq!(&b[0..4], b"glTF");
    assert_eq!(u32_at(4), 2);
    assert_eq!(u32_at(8), b.len());
    let jlen = u32_at(12);
    assert_eq!(&b[16..20], b"JSON");
    assert_eq!(jlen % 4, 0);
    let json: serde_json::Value = serde_json::from_slice(&b[20..20 + jlen]).unwrap();
    let bo = 20 + jlen;
    let blen = u32_at(bo);
    assert_eq!(&b[bo + 4..bo + 8], b"BIN\0");
    assert_eq!(bo + 8 + blen, b.len());
    assert_eq!(json["asset"]["version"], "2.0");
    let buf_len = json["buffers"][0]["byteLength"].as_u64().unwrap() as usize;
    assert!(buf_len <= blen && blen - buf_len < 4);
    let views = json["bufferViews"].as_array().unwrap();
    for v in views {
        let end = v["byteOffset"].as_u64().unwrap() + v["byteLength"].as_u64().unwrap();
        assert!(end as usize <= buf_len);
        assert_eq!(v["byteOffset"].as_u64().unwrap() % 4, 0);
    }
    let prim = &json["meshes"][0]["primitives"][0];
    for (name, acc) in prim["attributes"].as_object().unwrap() {
        let a = &json["accessors"][acc.as_u64().unwrap() as usize];
        let view = &views[a["bufferView"].as_u64().unwrap() as usize];
        let comp = match a["componentType"].as_u64().unwrap() {
            5126 => 4,
            5121 => 1,
            other => panic!("{name}: component type {other}"),
        };
        let ncomp = match a["type"].as_str().unwrap() {
            "VEC3" => 3,
            "VEC4" => 4,
            t => panic!("{t}"),
        };
        assert_eq!(
            a["count"].as_u64().unwrap() as usize * comp * ncomp,
            view["byteLength"].as_u64().unwrap() as usize,
            "{name}"
        );
        if name == "POSITION" {
            assert_eq!(a["min"].as_array().unwrap().len(), 3);
            assert_eq!(a["max"].as_array().unwrap().len(), 3);
        }
        if name == "COLOR_0" {
            assert_eq!(a["normalized"], true);
        }
    }
    let idx = &json["accessors"][prim["indices"].as_u64().unwrap() as usize];
    assert_eq!(idx["componentType"], 5125);
    assert_eq!(idx["count"].as_u64().unwrap() % 3, 0);
    json
}

fn glb_positions_and_indices(b: &[u8]) -> (Vec<[f32; 3]>, Vec<u32>) {
    let json = glb_json(b);
    let jlen = u32::from_le_bytes(b[12..16].try_into().unwrap()) as usize;
    let bin = &b[20 + jlen + 8..];
    let view = |acc: usize| {
        let a = &json["accessors"][acc];
        let v = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let o = v["byteOffset"].as_u64().unwrap() as usize;
        &bin[o..o + v["byteLength"].as_u64().unwrap() as usize]
    };
    let prim = &json["meshes"][0]["primitives"][0];
    let pos = view(prim["attributes"]["POSITION"].as_u64().unwrap() as usize)
        .chunks(12)
        .map(|c| [0, 1, 2].map(|k| f32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap())))
        .collect();
    let idx = view(prim["indices"].as_u64().unwrap() as usize)
        .chunks(4)
        .map(|c| u32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    (pos, idx)
}

#[test]
fn exports_round_trip_through_files() {
    let d = Synth::Batwing
        .build(&GridSpec::uniform(10.0, 5.0).unwrap(), 800.0)
        .unwrap()
        .into_distribution();
    let mut m = measured_solid(&d, Units::Candela).unwrap();
    m.info_mut().source = "synthetic batwing".into();
    m.colorize(ColorMap::Viridis);
    let dir = tempfile::tempdir().unwrap();
    for f in [MeshFormat::Obj, MeshFormat::Ply, MeshFormat::Stl, MeshFormat::Glb] {
        let path = dir.path().join(format!("solid.{}", f.extension()));
        export::write(&m, &path).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        match f {
            MeshFormat::Ply | MeshFormat::Obj => {
                let back = if f == MeshFormat::Ply {
                    export::ply::read(&bytes).unwrap()
                } else {
                    export::obj::read(&bytes).unwrap()
                };
                // Files hold the mesh with its sheets separated at pinch points.
                let written = m.separate_sheets();
                assert_eq!(back.positions(), written.positions(), "{f:?}");
                assert_eq!(back.triangles(), written.triangles(), "{f:?}");
                assert_eq!(back.origin_vertex(), written.origin_vertex());
                let r = check(&back, "read back");
                assert_close!(r.volume, m.volume(), rel = 1e-12);
            }
            MeshFormat::Stl => {
                assert_eq!(bytes.len(), 84 + 50 * m.n_triangles());
                assert_eq!(
                    u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize,
                    m.n_triangles()
                );
            }
            MeshFormat::Glb => {
                let (pos, idx) = glb_positions_and_indices(&bytes);
                let written = m.separate_sheets();
                assert_eq!(pos, written.positions());
                assert_eq!(idx, written.triangles().iter().flatten().copied().collect::<Vec<_>>());
                let json = glb_json(&bytes);
                assert!(json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"].is_u64());
                assert!(json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].is_u64());
            }
        }
    }
    // PLY header carries normals and colours.
    let ply = std::fs::read(dir.path().join("solid.ply")).unwrap();
    let head = String::from_utf8_lossy(&ply[..1500]).into_owned();
    assert!(head.contains("property float nx") && head.contains("property uchar red"));
    assert!(head.contains("comment source: synthetic batwing"));
    // No stray temporary files.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 4);
    // Unknown extension is refused.
    assert!(export::write(&m, &dir.path().join("solid.xyz")).is_err());
}

#[test]
fn normals_are_unit_and_outward() {
    let f = |c: f64, g: f64| {
        100.0
            * Synth::Spot {
                p: 2.0,
                cutoff_deg: 60.0,
            }
            .relative(c, g)
    };
    let m = grid_solid(&f, &SolidGrid::uniform(36, 36).unwrap(), Units::Candela).unwrap();
    let n = m.normals().unwrap();
    for (p, n) in m.positions().iter().zip(n) {
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert_close!(len, 1.0, abs = 1e-5);
        // Away from the origin the solid is star-shaped: normals face away from it.
        if p != &[0.0; 3] {
            assert!(p[0] * n[0] + p[1] * n[1] + p[2] * n[2] > -1e-3);
        }
    }
}

/// The H-only search between two solids certifies the full search's H, and
/// the per-vertex bound it starts from is a bound: on pairs of synthetic
/// solids (near each other, far apart, one with a dark band), every vertex's
/// `RadialMesh::distance_bound` is at least its exact distance to the other
/// solid (BVH) and at most the radial difference along its ray, and the
/// intervals [H, H + bound] of both searches overlap.
#[test]
fn bounded_solid_hausdorff_certifies_the_full_one() {
    use photosolid::compare::{solid_hausdorff, solid_hausdorff_bounded};
    use photosolid::metrics::{hausdorff::distances, Bvh};
    use photosolid::solid::RadialMesh;
    let grid = SolidGrid::uniform(72, 36).unwrap();
    let solid = |s: Synth| {
        let f = move |c: f64, g: f64| 1000.0 * s.relative(c, g);
        grid_solid(&f, &grid, Units::Candela).unwrap()
    };
    let pairs = [
        (Synth::CosinePower { p: 5.0 }, Synth::CosinePower { p: 6.0 }),
        (Synth::Lambertian, Synth::Batwing),
        (
            Synth::Spot {
                p: 4.0,
                cutoff_deg: 40.0,
            },
            Synth::Roadway,
        ),
    ];
    for (sa, sb) in pairs {
        let (a, b) = (solid(sa), solid(sb));
        let (ra, rb) = (RadialMesh::new(&a), RadialMesh::new(&b));
        let exact = distances(&a.positions_f64(), &Bvh::build_owned(b.positions_f64(), b.triangles()));
        let mut bounded = 0;
        for (p, d) in a.positions_f64().iter().zip(&exact) {
            let Some(u) = rb.distance_bound(*p) else { continue };
            bounded += 1;
            assert!(
                u >= d - 1e-9 * (1.0 + d),
                "{sa:?} vs {sb:?}: bound {u} below the distance {d} at {p}"
            );
            let n = p.length();
            let r = rb.radius(*p / n);
            if r > 0.0 {
                assert!(
                    u <= (n - r).abs() + 1e-9 * n,
                    "{sa:?}: bound {u} above the radial difference {}",
                    (n - r).abs()
                );
            }
        }
        assert!(
            bounded > a.n_vertices() / 2,
            "{sa:?}: {bounded} of {} vertices bounded",
            a.n_vertices()
        );
        let tol = 1e-3 * a.max_radius().max(b.max_radius());
        let full = solid_hausdorff(&a, &b, tol);
        let fast = solid_hausdorff_bounded((&a, &ra), (&b, &rb), tol);
        assert!(
            fast.value <= full.value + full.bound + 1e-9 && full.value <= fast.value + fast.bound + 1e-9,
            "{sa:?} vs {sb:?}: bounded {:?} vs full {:?}",
            (fast.value, fast.bound),
            (full.value, full.bound)
        );
        assert!(fast.a_to_b.mean.is_none() && full.a_to_b.mean.is_some());
        assert!(fast.a_to_b.queries + fast.b_to_a.queries <= full.a_to_b.queries + full.b_to_a.queries);
    }
}

/// A solid of over 32,400 triangles gets a finer bucket grid in its
/// `RadialMesh` (fewer triangles per `distance_bound`): the bound stays a
/// bound on such a pair, and the full search started below the bounds
/// (`solid_hausdorff_radial`, `SurfaceSearch::Full`) gives the numbers of
/// the plain one (`solid_hausdorff`) to the bit, on a fine and a coarse pair.
#[test]
fn full_search_below_the_radial_bounds_gives_the_same_numbers() {
    use photosolid::compare::{solid_hausdorff, solid_hausdorff_radial, SurfaceSearch};
    use photosolid::metrics::{hausdorff::distances, Bvh};
    use photosolid::solid::RadialMesh;
    for (nc, ng) in [(240, 120), (72, 36)] {
        let grid = SolidGrid::uniform(nc, ng).unwrap();
        let solid = |s: Synth| {
            let f = move |c: f64, g: f64| 1000.0 * s.relative(c, g);
            grid_solid(&f, &grid, Units::Candela).unwrap()
        };
        let (a, b) = (
            solid(Synth::CosinePower { p: 5.0 }),
            solid(Synth::Spot {
                p: 4.0,
                cutoff_deg: 60.0,
            }),
        );
        let (ra, rb) = (RadialMesh::new(&a), RadialMesh::new(&b));
        let exact = distances(&a.positions_f64(), &Bvh::build_owned(b.positions_f64(), b.triangles()));
        for (p, d) in a.positions_f64().iter().zip(&exact) {
            if let Some(u) = rb.distance_bound(*p) {
                assert!(
                    u >= d - 1e-9 * (1.0 + d),
                    "{nc}x{ng}: bound {u} below the distance {d} at {p}"
                );
            }
        }
        let tol = 1e-3 * a.max_radius().max(b.max_radius());
        let plain = solid_hausdorff(&a, &b, tol);
        let hinted = solid_hausdorff_radial((&a, &ra), (&b, &rb), tol, SurfaceSearch::Full);
        for (x, y) in [(&plain.a_to_b, &hinted.a_to_b), (&plain.b_to_a, &hinted.b_to_a)] {
            assert_eq!(x.value.to_bits(), y.value.to_bits(), "{nc}x{ng}");
            assert_eq!(x.bound.to_bits(), y.bound.to_bits(), "{nc}x{ng}");
            assert_eq!(x.mean.map(f64::to_bits), y.mean.map(f64::to_bits), "{nc}x{ng}");
            assert_eq!(x.rms.map(f64::to_bits), y.rms.map(f64::to_bits), "{nc}x{ng}");
            assert_eq!(x.queries, y.queries, "{nc}x{ng}");
        }
        assert!(plain.value > 0.01 * a.max_radius(), "{nc}x{ng}: the pair differs");
    }
}

/// Two solids with the same vertices and triangles are one surface: the radial
/// search (`compare`, `tradeoff`, `engines`) gives H, its bound, the mean and the RMS
/// as 0 exactly, with no distance query, for both searches; the plain search that
/// queries every vertex finds the same up to its point-triangle arithmetic. A solid
/// that differs in one vertex is searched as before.
#[test]
fn one_surface_is_zero_apart_without_a_query() {
    use photosolid::compare::{solid_hausdorff, solid_hausdorff_radial, SurfaceSearch};
    use photosolid::solid::RadialMesh;
    let grid = SolidGrid::uniform(72, 36).unwrap();
    let f = |c: f64, g: f64| {
        1000.0
            * Synth::Spot {
                p: 4.0,
                cutoff_deg: 60.0,
            }
            .relative(c, g)
    };
    let (a, b) = (
        grid_solid(&f, &grid, Units::Candela).unwrap(),
        grid_solid(&f, &grid, Units::Candela).unwrap(),
    );
    let (ra, rb) = (RadialMesh::new(&a), RadialMesh::new(&b));
    let tol = 1e-3 * a.max_radius();
    for search in [SurfaceSearch::Full, SurfaceSearch::SupremumOnly] {
        let h = solid_hausdorff_radial((&a, &ra), (&b, &rb), tol, search);
        assert_eq!((h.value, h.bound), (0.0, 0.0));
        for side in [h.a_to_b, h.b_to_a] {
            assert_eq!(
                (side.value, side.bound, side.queries, side.converged),
                (0.0, 0.0, 0, true)
            );
            let zero = (search == SurfaceSearch::Full).then_some(0.0);
            assert_eq!((side.mean, side.rms), (zero, zero));
        }
    }
    let plain = solid_hausdorff(&a, &b, tol);
    assert!(plain.value <= 1e-9 * a.max_radius(), "{}", plain.value);
    assert!(plain.a_to_b.queries > 0);
    // One vertex moved outward by 1 cd: no longer one surface.
    let bump = |c: f64, gam: f64| c.abs() < 1e-9 && (gam - 30.0).abs() < 1e-9;
    let g = |c: f64, gam: f64| f(c, gam) + if bump(c, gam) { 1.0 } else { 0.0 };
    let c = grid_solid(&g, &grid, Units::Candela).unwrap();
    assert_ne!(c.positions(), a.positions());
    let h = solid_hausdorff_radial((&a, &ra), (&c, &RadialMesh::new(&c)), tol, SurfaceSearch::SupremumOnly);
    assert!(h.value > 0.0 && h.a_to_b.queries + h.b_to_a.queries > 0, "{h:?}");
}
