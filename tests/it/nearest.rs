//! The distance from a point to a field's solid searched on the surface
//! (`metrics::nearest`, the withheld reference's H since issue 26) against
//! the exact distance to a fine adaptive mesh of the same solid, measured
//! independently: the two differ by at most the mesh's distance from the
//! solid, |d(p, S) − d(p, M)| ≤ H(S, M).

use glam::DVec3;
use photosolid::metrics::hausdorff::distances;
use photosolid::metrics::{distances_to_solid, Bvh, NearestSearch};
use photosolid::model::frame::direction;
use photosolid::model::{ConstantCells, Distribution, IntensityField};
use photosolid::numfmt::PctOfPeak;
use photosolid::reconstruct::{Filter, LightTexture};
use photosolid::solid::{adaptive_grid, grid_solid, surface_distance, AdaptiveOptions, SolidGrid, Tolerance, Units};
use photosolid::synth::{GridSpec, Synth};

use crate::common::corpus;

/// Points around the solid: each measured direction at 0.7, 0.95, 1.05 and
/// 1.4 times its value, and the origin.
fn points(d: &Distribution) -> Vec<DVec3> {
    let mut p = vec![DVec3::ZERO];
    for (ic, &c) in d.c_angles_deg().iter().enumerate() {
        for (ig, &g) in d.gamma_angles_deg().iter().enumerate() {
            let v = d.value_cd(ic, ig);
            for s in [0.7, 0.95, 1.05, 1.4] {
                p.push(s * v * direction(c, g));
            }
        }
    }
    p
}

fn agrees(name: &str, d: &Distribution, field: &dyn IntensityField) {
    assert!(field.is_continuous(), "{name}");
    let i_max = d.max_cd();
    let a = adaptive_grid(
        field,
        &SolidGrid::knots(d).unwrap(),
        &AdaptiveOptions::new(Tolerance::PercentOfPeak(PctOfPeak(0.01))),
    )
    .unwrap();
    let mesh = grid_solid(field, &a.grid, Units::Candela).unwrap();
    let pos = mesh.positions_f64();
    let h_sm = surface_distance(field, &mesh, 100_000, 3).max(a.tolerance_cd.max(a.tested_deviation_cd));
    let pts = points(d);
    let on_mesh = distances(&pts, &Bvh::build(&pos, mesh.triangles()));
    let polar: Vec<(DVec3, f64)> = pts.iter().map(|p| (p.normalize_or(DVec3::NEG_Z), p.length())).collect();
    let on_surface = distances_to_solid(field, &polar, &NearestSearch::default());
    let bound = 2.0 * h_sm + 1e-9 * i_max;
    let mut worst: f64 = 0.0;
    for (k, (&m, &s)) in on_mesh.iter().zip(&on_surface).enumerate() {
        assert!(s.is_finite(), "{name}: point {k}");
        // Never more than the distance along the point's own direction.
        let own = field.intensity_dir_cd(pts[k]);
        let u = (pts[k].length() - own).abs();
        assert!(
            s <= u + 1e-9 * i_max || pts[k] == DVec3::ZERO,
            "{name}: point {k}: {s} > {u}"
        );
        worst = worst.max((s - m).abs());
        assert!(
            (s - m).abs() <= bound,
            "{name}: point {k} {}: surface {s}, mesh {m}, bound {bound}",
            pts[k]
        );
    }
    eprintln!(
        "{name}: {} points, largest |surface - mesh| {:.3e} % of I_max (bound {:.3e} %)",
        pts.len(),
        100.0 * worst / i_max,
        100.0 * bound / i_max
    );
}

#[test]
fn surface_search_agrees_with_a_fine_mesh_on_synthetic_luminaires() {
    for s in [Synth::Roadway, Synth::CosinePower { p: 5.0 }] {
        let d = s
            .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 5000.0)
            .unwrap()
            .into_distribution();
        let tex = LightTexture::new(&d).unwrap();
        for f in [Filter::CatmullRom, Filter::Bilinear] {
            agrees(&format!("{s:?} {f}"), &d, &tex.sampler(f));
        }
    }
}

#[test]
fn surface_search_agrees_with_a_fine_mesh_on_real_files() {
    let Some(root) = corpus() else { return };
    for (name, filter) in [
        ("lithonia-iesparser/PMO_2_32_9LS_ASY.ies", Filter::CatmullRom),
        ("ils20/NDNN74022.ies", Filter::CatmullRom),
        ("photompy/LLIA001477-003.ies", Filter::Bilinear),
    ] {
        let path = root.join(name);
        let lum = photosolid::formats::load(&path).unwrap();
        let d = lum.distribution();
        let tex = LightTexture::new(d).unwrap();
        agrees(&format!("{name} {filter}"), d, &tex.sampler(filter));
    }
}

/// A mesh built from the definition of a constant-cell solid: every cell's
/// patch on its sphere and every wall between cells of different value,
/// each cut into `n` × `n` flat pieces with their corners on the solid.
fn cell_mesh(cells: &ConstantCells, n: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (rows, cols) = cells.shape();
    let (mut pos, mut tri) = (Vec::new(), Vec::new());
    let mut quad = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| {
        let k = pos.len() as u32;
        pos.extend([a, b, c, d]);
        tri.extend([[k, k + 1, k + 2], [k, k + 2, k + 3]]);
    };
    let lerp = |e: &[f64], i: usize, t: usize| e[i] + (e[i + 1] - e[i]) * t as f64 / n as f64;
    for i in 0..rows {
        for j in 0..cols {
            let r = cells.value(i, j);
            let east = cells.value(i, (j + 1) % cols);
            let south = if i + 1 < rows { cells.value(i + 1, j) } else { r };
            let (g1, c1) = (cells.gamma_edges_deg[i + 1], cells.c_edges_deg[j + 1]);
            for a in 0..n {
                let (ga, gb) = (
                    lerp(&cells.gamma_edges_deg, i, a),
                    lerp(&cells.gamma_edges_deg, i, a + 1),
                );
                for b in 0..n {
                    let (ca, cb) = (lerp(&cells.c_edges_deg, j, b), lerp(&cells.c_edges_deg, j, b + 1));
                    let p = |c, g| r * direction(c, g);
                    quad(p(ca, ga), p(cb, ga), p(cb, gb), p(ca, gb));
                }
                // The east wall along this γ piece, from r to the neighbour's value.
                let w = |v: f64, g| v * direction(c1, g);
                quad(w(r, ga), w(east, ga), w(east, gb), w(r, gb));
                // The south wall along the matching C piece.
                let (ca, cb) = (lerp(&cells.c_edges_deg, j, a), lerp(&cells.c_edges_deg, j, a + 1));
                let s = |v: f64, c| v * direction(c, g1);
                quad(s(r, ca), s(south, ca), s(south, cb), s(r, cb));
            }
        }
    }
    (pos, tri)
}

/// The exact distances to a nearest texture lookup's solid
/// (`metrics::cells`, the withheld reference's `cells` method) against a
/// mesh built from the solid's definition (patches and walls cut into
/// 24 × 24 flat pieces per cell, corners on the solid): within the pieces'
/// sag, r_max (1 − cos(δ / 2)) with δ the diagonal of the largest piece,
/// on the synthetic roadway and two real files, points at 0.3 to 1.5 I_max.
#[test]
fn cell_distances_agree_with_a_mesh_of_patches_and_walls() {
    use photosolid::metrics::cells::distances_to_cells;
    use photosolid::reconstruct::{render, Lookup, Precision, StoredTexture};
    let mut files: Vec<(String, Distribution)> = vec![(
        "roadway".into(),
        Synth::Roadway
            .build(&GridSpec::uniform(15.0, 10.0).unwrap(), 1000.0)
            .unwrap()
            .into_distribution(),
    )];
    if let Some(root) = corpus() {
        for name in ["lithonia-iesparser/PMO_2_32_9LS_ASY.ies", "ils20/NDNN74022.ies"] {
            let lum = photosolid::formats::load(root.join(name)).unwrap();
            files.push((name.into(), lum.distribution().clone()));
        }
    }
    let n = 24;
    for (name, d) in files {
        let rendered = render(&LightTexture::new(&d).unwrap(), Filter::CatmullRom, 2).unwrap();
        let tex = StoredTexture::new(&rendered, None, Precision::F32, Lookup::Nearest);
        let cells = tex.constant_cells().expect("a nearest lookup is constant cells");
        let (pos, tri) = cell_mesh(&cells, n);
        let i_max = cells.values_cd.iter().copied().fold(0.0, f64::max);
        let dirs = photosolid::metrics::random_directions(400, 99);
        let polar: Vec<(DVec3, f64)> = dirs
            .iter()
            .enumerate()
            .map(|(k, &u)| (u, i_max * (0.3 + 1.2 * ((k * 37) % 101) as f64 / 100.0)))
            .collect();
        let points: Vec<DVec3> = polar.iter().map(|&(u, m)| m * u).collect();
        let exact = distances_to_cells(&cells, &polar);
        let on_mesh = distances(&points, &Bvh::build(&pos, &tri));
        let (rows, cols) = cells.shape();
        let step = (180.0 / rows as f64).max(360.0 / cols as f64) / n as f64;
        let sag = i_max * (1.0 - (std::f64::consts::SQRT_2 * step.to_radians() / 2.0).cos()) + 1e-9 * i_max;
        let worst = exact
            .iter()
            .zip(&on_mesh)
            .map(|(e, m)| (e - m).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{name}: {rows} x {cols} cells, largest |exact - mesh| {:.2e} % of I_max (sag bound {:.2e} %)",
            100.0 * worst / i_max,
            100.0 * sag / i_max
        );
        assert!(worst <= sag, "{name}: {worst} cd over the sag bound {sag} cd");
    }
}

/// The cells describe the lookup they come from: at 20,000 random
/// directions a nearest texture (f32 and 8-bit, on the roadway and a real
/// file) answers exactly the value of the cell holding the direction (its
/// row floor(γ h / 180), column floor(C w / 360)); a bilinear lookup and a
/// symmetry-reduced texture are not constant cells.
#[test]
fn constant_cells_are_the_nearest_lookup() {
    use photosolid::reconstruct::{render, Lookup, Precision, StoredTexture};
    let mut files: Vec<Distribution> = vec![Synth::Roadway
        .build(&GridSpec::uniform(15.0, 10.0).unwrap(), 1000.0)
        .unwrap()
        .into_distribution()];
    if let Some(root) = corpus() {
        let lum = photosolid::formats::load(root.join("lithonia-iesparser/PMO_2_32_9LS_ASY.ies")).unwrap();
        files.push(lum.distribution().clone());
    }
    let dirs = photosolid::metrics::random_directions(20_000, 5);
    for d in files {
        let rendered = render(&LightTexture::new(&d).unwrap(), Filter::CatmullRom, 2).unwrap();
        for precision in [Precision::F32, Precision::U8] {
            let tex = StoredTexture::new(&rendered, None, precision, Lookup::Nearest);
            let cells = tex.constant_cells().unwrap();
            let (rows, cols) = cells.shape();
            assert_eq!((rows, cols), (tex.height(), tex.full_width()));
            let mut near_edge = 0;
            for &u in &dirs {
                let (c, g) = photosolid::model::frame::unit_angles(u);
                let (y, x) = (g / 180.0 * rows as f64, c / 360.0 * cols as f64);
                // A direction within rounding of a cell edge may fall either side.
                if (y - y.round()).abs() < 1e-9 || (x - x.round()).abs() < 1e-9 {
                    near_edge += 1;
                    continue;
                }
                let (i, j) = ((y.floor() as usize).min(rows - 1), (x.floor() as usize) % cols);
                assert_eq!(
                    tex.intensity_dir_cd(u),
                    cells.value(i, j),
                    "{precision:?} at ({c}, {g})"
                );
            }
            assert!(near_edge < 10, "{near_edge} directions on an edge");
        }
        assert!(StoredTexture::new(&rendered, None, Precision::F32, Lookup::Bilinear)
            .constant_cells()
            .is_none());
        if d.symmetry() != photosolid::model::Symmetry::None {
            let reduced = StoredTexture::new(&rendered, Some(d.symmetry()), Precision::F32, Lookup::Nearest);
            assert!(reduced.reduced().is_none() || reduced.constant_cells().is_none());
        }
    }
}

/// The largest distance searched only where it can be set equals, bit for
/// bit, the largest of every point's search, on a real file's bilinear
/// solid and a synthetic Catmull-Rom one, and searches fewer points; a
/// floor above every distance searches none of those below it, and
/// extreme points (the origin, negative and infinite |p|) stay finite.
#[test]
fn largest_distance_searches_only_points_that_can_set_it() {
    use photosolid::metrics::largest_distance_to_solid;
    let roadway = Synth::Roadway
        .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 5000.0)
        .unwrap()
        .into_distribution();
    let mut cases = vec![("Roadway".to_string(), roadway, Filter::CatmullRom)];
    if let Some(root) = corpus() {
        let lum = photosolid::formats::load(root.join("photompy/LLIA001477-003.ies")).unwrap();
        cases.push(("LLIA001477-003".into(), lum.distribution().clone(), Filter::Bilinear));
    }
    for (name, d, filter) in cases {
        let tex = LightTexture::new(&d).unwrap();
        let field = tex.sampler(filter);
        // Points near the solid (a good reconstruction's withheld points) and a few far off.
        let mut polar: Vec<(DVec3, f64)> = points(&d)
            .iter()
            .enumerate()
            .map(|(k, p)| {
                (
                    p.normalize_or(DVec3::NEG_Z),
                    p.length() * if k % 97 == 0 { 1.0 } else { 0.98 },
                )
            })
            .collect();
        polar.truncate(3000);
        let search = NearestSearch::default();
        let all = distances_to_solid(&field, &polar, &search);
        let want = all.iter().copied().fold(0.0, f64::max);
        let got = largest_distance_to_solid(&field, &polar, &search, 0.0);
        assert_eq!(got.value_cd.to_bits(), want.to_bits(), "{name}");
        assert!(
            got.searched < polar.len(),
            "{name}: searched {} of {}",
            got.searched,
            polar.len()
        );
        eprintln!(
            "{name}: H {want:.4} cd, searched {} of {} points",
            got.searched,
            polar.len()
        );
        // A floor: only points whose own distance exceeds it are searched.
        let floor = 2.0 * want;
        let above = largest_distance_to_solid(&field, &polar, &search, floor);
        assert!(above.value_cd <= floor, "{name}");
        let own_above = polar
            .iter()
            .filter(|&&(w, m)| (field.intensity_dir_cd(w) - m).abs() > floor)
            .count();
        assert!(above.searched <= own_above, "{name}: {} > {own_above}", above.searched);
    }
    let field = |_: f64, g: f64| if g < 90.0 { 100.0 } else { 0.0 };
    let odd = [
        (DVec3::ZERO, 0.0),
        (DVec3::X, -50.0),
        (DVec3::Z, f64::INFINITY),
        (DVec3::new(f64::NAN, 0.0, 0.0), 10.0),
    ];
    let got = largest_distance_to_solid(&field, &odd, &NearestSearch::default(), 0.0);
    let want = distances_to_solid(&field, &odd, &NearestSearch::default())
        .into_iter()
        .fold(0.0, f64::max);
    assert!(
        got.value_cd.is_finite() && got.value_cd.to_bits() == want.to_bits(),
        "{got:?} vs {want}"
    );
}

/// A nearest filter on the measured data is constant cells too, with edges
/// at the midpoints between knots: at 20,000 random directions and at
/// points just either side of every edge, the filter answers exactly the
/// value of the cell holding the direction, on the roadway (a cut-off), a
/// quadrant-symmetric and a rotationally symmetric grid, an uneven real
/// grid and a real file with half-degree rows. Other filters are not cells.
#[test]
fn a_nearest_filter_is_constant_cells() {
    let spec = GridSpec::uniform(15.0, 10.0).unwrap();
    let mut files: Vec<(String, Distribution)> = vec![
        (
            "roadway".into(),
            Synth::Roadway.build(&spec, 1000.0).unwrap().into_distribution(),
        ),
        (
            "cosine".into(),
            Synth::CosinePower { p: 5.0 }
                .build(&spec, 1000.0)
                .unwrap()
                .into_distribution(),
        ),
    ];
    if let Some(root) = corpus() {
        for name in [
            "lithonia-iesparser/PMO_2_32_9LS_ASY.ies",
            "photompy/LLIA001477-003.ies",
            "eulumdat-rs/road_luminaire.ldt",
            "ils20/NDNN74022.ies",
        ] {
            let lum = photosolid::formats::load(root.join(name)).unwrap();
            files.push((name.into(), lum.distribution().clone()));
        }
    }
    let dirs = photosolid::metrics::random_directions(20_000, 9);
    for (name, d) in files {
        let tex = LightTexture::new(&d).unwrap();
        let field = tex.sampler(Filter::Nearest);
        let cells = field.constant_cells().unwrap();
        let (rows, cols) = cells.shape();
        let (ge, ce) = (&cells.gamma_edges_deg, &cells.c_edges_deg);
        assert!(
            ge[0] == 0.0 && ge[rows] == 180.0 && ce[0] == 0.0 && ce[cols] == 360.0,
            "{name}"
        );
        assert!(
            ge.windows(2).all(|w| w[0] < w[1]) && ce.windows(2).all(|w| w[0] < w[1]),
            "{name}"
        );
        let cell_of = |c: f64, g: f64| {
            let i = ge[1..rows].partition_point(|&e| e <= g);
            let j = ce[1..cols].partition_point(|&e| e <= c);
            cells.value(i, j)
        };
        // Random directions, and the centre and both sides of every edge.
        let mut at: Vec<(f64, f64)> = dirs.iter().map(|&u| photosolid::model::frame::unit_angles(u)).collect();
        let mids = |e: &[f64]| e.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect::<Vec<f64>>();
        let (gm, cm) = (mids(ge), mids(ce));
        for &g in &gm {
            for &c in &cm {
                at.push((c, g));
            }
        }
        for &e in &ge[1..rows] {
            for &c in cm.iter().step_by(7) {
                at.extend([(c, e - 1e-7), (c, e + 1e-7)]);
            }
        }
        for &e in &ce[1..cols] {
            for &g in gm.iter().step_by(7) {
                at.extend([(e - 1e-7, g), (e + 1e-7, g)]);
            }
        }
        for &(c, g) in &at {
            assert_eq!(field.intensity_cd(c, g), cell_of(c, g), "{name} at ({c}, {g})");
        }
        eprintln!("{name}: {rows} x {cols} cells, {} lookups agree", at.len());
        for f in [Filter::Bilinear, Filter::CatmullRom] {
            assert!(tex.sampler(f).constant_cells().is_none());
        }
    }
}
