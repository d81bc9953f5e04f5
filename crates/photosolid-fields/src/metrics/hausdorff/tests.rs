use super::screened::*;
use super::*;

/// The borrowed mesh of `positions` and `triangles`.
fn mesh_ref<'a>(positions: &'a [DVec3], triangles: &'a [[u32; 3]]) -> MeshRef<'a> {
    MeshRef { positions, triangles }
}

/// A UV sphere of radius r centred at c.
pub(crate) fn sphere(r: f64, c: [f64; 3], n_lat: usize, n_lon: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut pos = vec![DVec3::new(c[0], c[1], c[2] - r)];
    for i in 1..n_lat {
        let th = std::f64::consts::PI * i as f64 / n_lat as f64;
        for j in 0..n_lon {
            let ph = 2.0 * std::f64::consts::PI * j as f64 / n_lon as f64;
            pos.push(DVec3::new(
                c[0] + r * th.sin() * ph.cos(),
                c[1] + r * th.sin() * ph.sin(),
                c[2] - r * th.cos(),
            ));
        }
    }
    pos.push(DVec3::new(c[0], c[1], c[2] + r));
    let top = (pos.len() - 1) as u32;
    let idx = |i: usize, j: usize| (1 + (i - 1) * n_lon + (j % n_lon)) as u32;
    let mut t = Vec::new();
    for j in 0..n_lon {
        t.push([0, idx(1, j + 1), idx(1, j)]);
        t.push([top, idx(n_lat - 1, j), idx(n_lat - 1, j + 1)]);
    }
    for i in 1..n_lat - 1 {
        for j in 0..n_lon {
            t.push([idx(i, j), idx(i, j + 1), idx(i + 1, j)]);
            t.push([idx(i, j + 1), idx(i + 1, j + 1), idx(i + 1, j)]);
        }
    }
    (pos, t)
}

#[test]
fn queued_triangles_stay_small() {
    // Issue 15: a mesh's own triangles wait as 16-byte seeds, not 120-byte cells.
    assert_eq!(std::mem::size_of::<ByUpper<u32>>(), 16);
    assert_eq!(std::mem::size_of::<ByUpper<Cell>>(), 120);
}

type Solid = (Vec<DVec3>, Vec<[u32; 3]>);

/// A sphere of radius 10 and the two solids it is searched against: the
/// same sphere with a bump (a few vertices pushed out along their rays),
/// and a larger, shifted sphere (different everywhere).
fn sphere_bumped_and_shifted() -> (Solid, [Solid; 2]) {
    let a = sphere(10.0, [0.0; 3], 40, 80);
    let (mut p2, t2) = sphere(10.0, [0.0; 3], 40, 80);
    for p in p2.iter_mut().filter(|p| p.z > 9.5) {
        *p *= 1.3;
    }
    (a, [(p2, t2), sphere(11.0, [0.4, -0.2, 0.1], 30, 60)])
}

/// Upper bounds of each vertex's distance to `b` (`exact`, the distances
/// themselves): tight, loose and none.
fn vertex_bounds(exact: &[f64]) -> [(&'static str, Vec<f64>); 3] {
    [
        ("tight", exact.iter().map(|d| d * (1.0 + 1e-9) + 1e-9).collect()),
        ("loose", exact.iter().map(|d| 2.0 * d + 1.0).collect()),
        ("none", vec![f64::INFINITY; exact.len()]),
    ]
}

/// The pruned search certifies the same H as the full one: on meshes
/// that differ in one place (a bump), everywhere (offset spheres), and
/// with A deep inside B (a small sphere within a large one, each point
/// about as near to much of B: the searches that stop within the largest
/// distance), with tight vertex bounds, loose ones and none (every
/// triangle screened), both intervals [value, value + bound] overlap, the
/// bound is within the tolerance, and on the bump a tight bound queries far less.
#[test]
fn bounded_search_certifies_the_full_searchs_h() {
    let (sphere_a, [bumped, shifted]) = sphere_bumped_and_shifted();
    let deep = (sphere(1.0, [0.2, -0.1, 0.3], 20, 40), sphere(12.0, [0.0; 3], 50, 100));
    let tol = 1e-3;
    for (case, ((pa, ta), (pb, tb))) in [
        ("bump", (&sphere_a, &bumped)),
        ("shifted", (&sphere_a, &shifted)),
        ("deep inside", (&deep.0, &deep.1)),
    ] {
        let ma = mesh_ref(pa, ta);
        let bvh_b = Bvh::build(pb, tb);
        let full = one_sided(ma, &bvh_b, tol);
        for (name, upper) in vertex_bounds(&distances(pa, &bvh_b)) {
            let b = one_sided_bounded(ma, &bvh_b, tol, &upper);
            assert!(b.converged && b.bound <= tol + 1e-12, "{case}, {name}: {b:?}");
            assert!(
                b.value <= full.value + full.bound + 1e-12 && full.value <= b.value + b.bound + 1e-12,
                "{case}, {name}: bounded {b:?} vs full {full:?}"
            );
            assert!(b.mean.is_none() && b.rms.is_none());
            if case == "bump" && name == "tight" {
                assert!(
                    b.queries * 4 < full.queries,
                    "{name}: {} vs {} queries",
                    b.queries,
                    full.queries
                );
            }
        }
    }
}

/// The screening as it was: every triangle bounded again and the whole
/// rest sorted after each batch. [`screen`] must screen the same
/// triangles in the same order, find the same distances and return the
/// same largest bound of the rest.
fn screen_by_full_sorts(
    a: MeshRef<'_>,
    b: &Bvh,
    tol: f64,
    order: &mut [(f64, u32)],
    upper: &[f64],
    within: &[f64],
) -> Screened {
    let n = a.positions.len();
    let mut s = Screened {
        near: (0..n).map(|i| (upper[i], u32::MAX)).collect(),
        lb: 0.0,
        queries: 0,
        screened: 0,
        centroid_nearest: Vec::new(),
    };
    order.sort_by(by_bound);
    let mut measured = vec![false; n];
    let mut batch_len = SCREEN_BATCH;
    while s.screened < order.len() && order[s.screened].0 > s.lb + tol {
        let end = (s.screened + batch_len).min(order.len());
        batch_len = (2 * batch_len).min(SCREEN_BATCH_MAX);
        let lb = s.lb;
        let mut fresh: Vec<u32> = order[s.screened..end]
            .iter()
            .flat_map(|&(_, k)| a.triangles[k as usize])
            .filter(|&i| !measured[i as usize])
            .collect();
        fresh.sort_unstable();
        fresh.dedup();
        for i in fresh {
            // The accept radius from the vertex's longest triangle in the batch.
            let slack = order[s.screened..end]
                .iter()
                .map(|&(_, k)| a.triangles[k as usize])
                .filter(|t| t.contains(&i))
                .map(|t| longest_edge(&t.map(|j| a.positions[j as usize])) / 3f64.sqrt())
                .fold(f64::NEG_INFINITY, f64::max);
            let accept = lb.min(lb + tol - slack);
            measured[i as usize] = true;
            if upper[i as usize] <= accept {
                continue;
            }
            s.near[i as usize] = nearest_within(b, a.positions[i as usize], upper[i as usize], accept);
            s.lb = s.lb.max(s.near[i as usize].0);
            s.queries += 1;
        }
        for &(_, k) in &order[s.screened..end] {
            let t = &a.triangles[k as usize];
            let v = t.map(|i| a.positions[i as usize]);
            let c = (v[0] + v[1] + v[2]) / 3.0;
            let hint = (0..3)
                .map(|i| s.near[t[i] as usize].0 + c.distance(v[i]))
                .fold(f64::INFINITY, f64::min);
            if hint <= lb {
                s.centroid_nearest.push(u32::MAX);
                continue;
            }
            let d = nearest_within(b, c, hint, lb);
            s.centroid_nearest.push(d.1);
            s.lb = s.lb.max(d.0);
            s.queries += 1;
        }
        s.screened = end;
        for (ub, k) in order[s.screened..].iter_mut() {
            let t = &a.triangles[*k as usize];
            let v = t.map(|i| a.positions[i as usize]);
            *ub = lipschitz_bound(&v, &t.map(|i| s.near[i as usize].0)).min(within[*k as usize]);
        }
        order[s.screened..].sort_by(by_bound);
    }
    s
}

/// [`screen`] bounds and sorts only the triangles that can still be
/// screened, and gives what the full bound and sort after every batch
/// gave: the same screened triangles in the same order, the same
/// distances and nearest triangles, queries and largest distance, and
/// the same bounds of the rest, the largest next. Bumped and shifted spheres, with
/// tight, loose and no vertex bounds and with and without whole-triangle
/// bounds, at tolerances that stop at once, early and late.
#[test]
fn screening_is_the_full_sorts_screening() {
    let ((p1, t1), others) = sphere_bumped_and_shifted();
    let ma = mesh_ref(&p1, &t1);
    let mut screened_any = false;
    for (pb, tb) in &others {
        let bvh_b = Bvh::build(pb, tb);
        let sampled: Vec<f64> = (0..t1.len()).map(|k| 0.5 + (k % 7) as f64).collect();
        let no_within = vec![f64::INFINITY; t1.len()];
        for (_, upper) in vertex_bounds(&distances(&p1, &bvh_b)) {
            for within in [&no_within, &sampled] {
                for tol in [1e-3, 0.05, 0.5, 100.0] {
                    let start: Vec<(f64, u32)> = t1
                        .iter()
                        .enumerate()
                        .map(|(k, t)| {
                            let v = t.map(|i| p1[i as usize]);
                            (
                                lipschitz_bound(&v, &t.map(|i| upper[i as usize])).min(within[k]),
                                k as u32,
                            )
                        })
                        .collect();
                    let (mut got_order, mut want_order) = (start.clone(), start);
                    let got = screen(
                        ma,
                        &bvh_b,
                        tol,
                        &mut got_order,
                        |i| upper[i as usize],
                        |k| within[k as usize],
                    );
                    let want = screen_by_full_sorts(ma, &bvh_b, tol, &mut want_order, &upper, within);
                    assert_eq!(got.screened, want.screened, "tol {tol}");
                    assert_eq!(got_order[..got.screened], want_order[..want.screened], "tol {tol}");
                    assert_eq!(got_order.get(got.screened), want_order.get(want.screened), "tol {tol}");
                    // Every bound of the rest, with the final distances, as the full sort left them.
                    let mut rest = got_order[got.screened..].to_vec();
                    rest.sort_by(by_bound);
                    assert_eq!(rest, want_order[want.screened..], "tol {tol}");
                    assert_eq!(got.near, want.near, "tol {tol}");
                    assert_eq!(got.centroid_nearest, want.centroid_nearest, "tol {tol}");
                    assert_eq!((got.lb, got.queries), (want.lb, want.queries), "tol {tol}");
                    screened_any |= got.screened > SCREEN_BATCH && got.screened < t1.len();
                }
            }
        }
    }
    assert!(
        screened_any,
        "no case screened past the first batch and stopped before the end"
    );
}

/// Two meshes with the same triangles, the second bumped and twisted: the
/// corresponding-vertex bound of each triangle holds over it (sampled at
/// barycentric points), and the search that takes it certifies the full search's
/// h with fewer queries than the search without it.
#[test]
fn corresponding_bounds_certify_the_full_searchs_h() {
    let ((p1, t1), [(mut p2, t2), _]) = sphere_bumped_and_shifted();
    assert_eq!(t1, t2);
    // A twist too: every vertex moved sideways a little, so no vertex keeps its ray.
    for p in p2.iter_mut() {
        *p += DVec3::new(0.02 * p.y, -0.02 * p.x, 0.01);
    }
    let within = corresponding_bounds(&p1, &p2, &t1, 13.0);
    let (ma, mb) = (mesh_ref(&p1, &t1), mesh_ref(&p2, &t2));
    let bvh_b = Bvh::build(mb.positions, mb.triangles);
    for (k, t) in t1.iter().enumerate().step_by(97) {
        for (l1, l2) in [(0.2, 0.3), (0.6, 0.1), (1.0 / 3.0, 1.0 / 3.0), (0.05, 0.9)] {
            let q = p1[t[0] as usize] * l1 + p1[t[1] as usize] * l2 + p1[t[2] as usize] * (1.0 - l1 - l2);
            let d = distances(&[q], &bvh_b)[0];
            assert!(d <= within[k], "triangle {k}: {d} > {}", within[k]);
        }
    }
    let tol = 1e-3;
    let full = one_sided(ma, &bvh_b, tol);
    let exact = distances(&p1, &bvh_b);
    let upper: Vec<f64> = exact.iter().map(|d| 2.0 * d + 1.0).collect();
    let plain = one_sided_bounded(ma, &bvh_b, tol, &upper);
    let with = one_sided_bounded_within(ma, &bvh_b, tol, &upper, &within);
    assert!(with.converged && with.bound <= tol + 1e-12, "{with:?}");
    assert!(
        with.value <= full.value + full.bound + 1e-12 && full.value <= with.value + with.bound + 1e-12,
        "with the triangle bounds {with:?} vs full {full:?}"
    );
    // Both prune: the searches stopped within the largest distance already
    // make the plain one cheap here, so the two are not ordered.
    for (name, q) in [("with", with.queries), ("plain", plain.queries)] {
        assert!(q * 4 < full.queries, "{name}: {q} vs {} queries", full.queries);
    }
}

#[test]
fn concentric_spheres_give_the_radius_difference() {
    let (p1, t1) = sphere(10.0, [0.0; 3], 40, 80);
    let (p2, t2) = sphere(12.0, [0.0; 3], 50, 100);
    let h = hausdorff(mesh_ref(&p1, &t1), mesh_ref(&p2, &t2), 1e-3);
    // Polygonal spheres: the inscribed facets sit inside the true spheres by at most
    // r (1 − cos(half the angular step)), so H lies within that of |r1 − r2| = 2.
    let sag = 12.0 * (1.0 - (std::f64::consts::PI / 50.0).cos());
    assert!((h.value - 2.0).abs() <= sag + 1e-3, "{h:?}");
    assert!(h.bound <= 1e-3 + 1e-12);
    // h(big -> small) is the larger side (the big sphere's vertices are 2 away; the
    // small sphere's facet centres are farther from the big sphere than its vertices).
    assert!(h.a_to_b.value >= 2.0 - 1e-9);
}

#[test]
fn identical_meshes_give_zero_without_refinement() {
    // Each triangle's centroid has the triangle itself as its nearest: the convexity
    // bound over it is 0, so nothing waits for refinement (issue 12: 8 s on 323 k triangles).
    let (p, t) = sphere(10.0, [0.0; 3], 60, 120);
    let m = mesh_ref(&p, &t);
    let h = hausdorff(m, m, 1e-9);
    // Centroids differ from the triangle by round-off only (1e-15 of the radius).
    assert!(h.value <= 1e-12 && h.bound == 0.0, "{h:?}");
    assert_eq!(h.a_to_b.queries, p.len() + t.len());
    assert!(h.a_to_b.converged && h.b_to_a.converged);
}

#[test]
fn bound_is_certified_against_dense_sampling() {
    // Offset spheres: the sup lies inside faces, not only at vertices.
    let (p1, t1) = sphere(10.0, [0.0; 3], 12, 24);
    let (p2, t2) = sphere(10.0, [1.5, 0.0, 0.0], 12, 24);
    let a = mesh_ref(&p1, &t1);
    let bvh = Bvh::build(&p2, &t2);
    let h = one_sided(a, &bvh, 1e-4);
    // Dense barycentric sampling never exceeds the certified upper bound.
    let mut dense: f64 = 0.0;
    for t in &t1 {
        let v = [p1[t[0] as usize], p1[t[1] as usize], p1[t[2] as usize]];
        for i in 0..=20 {
            for j in 0..=(20 - i) {
                let (u, w) = (i as f64 / 20.0, j as f64 / 20.0);
                let x = v[0] + u * (v[1] - v[0]) + w * (v[2] - v[0]);
                dense = dense.max(bvh.distance(x));
            }
        }
    }
    assert!(
        dense <= h.value + h.bound + 1e-9,
        "dense {dense} > {} + {}",
        h.value,
        h.bound
    );
    assert!(
        h.value >= dense - 0.05,
        "refinement found {} but sampling {dense}",
        h.value
    );
}
