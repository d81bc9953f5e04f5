//! The supremum-only search of [`super::one_sided_bounded`]: screening the
//! triangles of A from the largest Lipschitz bound down, in batches, and
//! refining only those that can set h(A, B).

use super::*;
/// Triangles of A screened in the first round of [`one_sided_bounded`];
/// each round screens twice the last (most files need one or two rounds,
/// a smooth difference everywhere needs many), at most [`SCREEN_BATCH_MAX`].
pub(super) const SCREEN_BATCH: usize = 256;
pub(super) const SCREEN_BATCH_MAX: usize = 16_384;

/// h(A, B) alone, to within `tolerance`, searching only the triangles of A
/// that can set it: `upper[i]` must be an upper bound of vertex i's
/// distance to B (e.g. its distance to some triangles of B near it; the
/// certificate is only as good as these bounds). Mean and RMS are not
/// computed (`None`): they need every vertex.
///
/// Each triangle's Lipschitz bound from `upper` is an upper bound of
/// `d(·, B)` over it. Triangles are screened from the largest such bound
/// down, in batches: their vertices' and centroids' distances raise
/// the lower bound, and screening stops at the first bound within the
/// tolerance of it. Every triangle not screened is pruned with its bound
/// (so the certified upper bound covers all of A); the screened ones are
/// refined as [`one_sided`] refines every triangle.
pub fn one_sided_bounded(a: MeshRef<'_>, b: &Bvh, tolerance: f64, upper: &[f64]) -> OneSided {
    one_sided_bounded_within(a, b, tolerance, upper, &[])
}

/// [`one_sided_bounded`] with an upper bound of `d(·, B)` over each whole triangle
/// of A as well (`within[k]` for triangle k; empty: none), taken where it is lower
/// than the Lipschitz bound, in the screening order and for the screened triangles.
/// Two meshes with the same triangles give one ([`corresponding_bounds`]).
pub fn one_sided_bounded_within(a: MeshRef<'_>, b: &Bvh, tolerance: f64, upper: &[f64], within: &[f64]) -> OneSided {
    let upper_of = |i: u32| upper.get(i as usize).copied().unwrap_or(f64::INFINITY);
    let within_of = |k: u32| within.get(k as usize).copied().unwrap_or(f64::INFINITY);
    let mut order: Vec<(f64, u32)> = a
        .triangles
        .par_iter()
        .enumerate()
        .map(|(k, t)| {
            let v = t.map(|i| a.positions[i as usize]);
            (lipschitz_bound(&v, &t.map(upper_of)).min(within_of(k as u32)), k as u32)
        })
        .collect();
    let s = screen(a, b, tolerance.max(0.0), &mut order, upper_of, within_of);
    let cells = MeshCells {
        a,
        near: &s.near,
        b,
        supremum_only: true,
    };
    let mut refinement = Refinement::new(s.lb, tolerance);
    let kept: Vec<(Option<ByUpper<u32>>, f64)> = order[..s.screened]
        .par_iter()
        .zip(s.centroid_nearest.par_iter())
        .map(|(&(_, k), &kc)| {
            let t = &a.triangles[k as usize];
            let cand = [
                s.near[t[0] as usize].1,
                s.near[t[1] as usize].1,
                s.near[t[2] as usize].1,
                kc,
            ];
            let ub = upper_bound(&cells.vertices(t), &cells.distances(t), &cand, b);
            let whole = within_of(k);
            if whole < ub && !refinement.needs_refining(whole) {
                // The whole triangle's bound clears it: no piece needs refining.
                (None, whole)
            } else if refinement.needs_refining(ub) {
                (Some(ByUpper { ub, item: k }), 0.0)
            } else {
                (None, ub)
            }
        })
        .collect();
    let unscreened = order.get(s.screened).map_or(0.0, |x| x.0);
    let pruned = kept.iter().map(|x| x.1).fold(unscreened, f64::max);
    refinement.add_seeds(kept.into_iter().filter_map(|x| x.0).collect(), pruned);
    let refined = refinement.run(&cells, MAX_REFINEMENT_QUERIES);
    OneSided {
        value: refined.lb,
        bound: (refined.ub - refined.lb).max(0.0),
        mean: None,
        rms: None,
        queries: s.queries + refined.queries,
        converged: refined.converged,
    }
}

/// What the screening of [`one_sided_bounded`] found.
pub(super) struct Screened {
    /// Each vertex's distance and nearest B triangle for the screened
    /// triangles' vertices, or an upper bound attained by the triangle given
    /// where the search stopped early ([`measure_batch`]); the upper bound and
    /// none (`u32::MAX`) for the rest and where the bound needed no search.
    pub(super) near: Vec<(f64, u32)>,
    /// Largest distance evaluated.
    pub(super) lb: f64,
    /// Distance queries made.
    pub(super) queries: usize,
    /// How many triangles of the order were screened (a prefix).
    pub(super) screened: usize,
    /// The nearest B triangle of each screened triangle's centroid, in order.
    pub(super) centroid_nearest: Vec<u32>,
}

/// Screens the triangles of A in `order` (each with an upper bound of its
/// distance to B, in any order) from the largest bound down, in doubling
/// batches, until the next one's bound is within `tol` of the largest
/// distance found. On return `order` starts with the screened triangles in
/// the order they were screened, then the largest bound of the rest (with
/// the vertices' final distances), then the others.
///
/// Every batch tightens the bounds of the triangles around the vertices it
/// measured, so the rest are bounded again and ordered again: largest
/// bound first, ties by index, so the order is the same on every run. Only
/// the triangles still above the stop (bound > largest distance + `tol`)
/// can be screened, and a bound only falls while the largest distance only
/// rises: those are bounded and sorted after each batch, the others when a
/// batch reaches past them (the last) and at the end. The screened triangles and
/// the bound returned are those of a full sort after every batch (a full
/// sort and bound of every triangle after each batch was most of the
/// screening's time on a 434,000-triangle truth solid: BENCHMARKS.md).
pub(super) fn screen(
    a: MeshRef<'_>,
    b: &Bvh,
    tol: f64,
    order: &mut [(f64, u32)],
    upper_of: impl Fn(u32) -> f64 + Sync,
    within_of: impl Fn(u32) -> f64 + Sync,
) -> Screened {
    let n = a.positions.len();
    let mut s = Screened {
        near: (0..n).map(|i| (upper_of(i as u32), u32::MAX)).collect(),
        lb: 0.0,
        queries: 0,
        screened: 0,
        centroid_nearest: Vec::new(),
    };
    let bound = |near: &[(f64, u32)], k: u32| {
        let t = &a.triangles[k as usize];
        let v = t.map(|i| a.positions[i as usize]);
        lipschitz_bound(&v, &t.map(|i| near[i as usize].0)).min(within_of(k))
    };
    let mut measured = vec![false; n];
    let mut batch_len = SCREEN_BATCH;
    // order = [screened | above the stop, sorted | the rest]
    let mut above = sort_above(order, s.lb + tol);
    let mut rebounded = false;
    while s.screened < order.len() && order[s.screened].0 > s.lb + tol {
        let end = (s.screened + batch_len).min(order.len());
        if end > above {
            // The batch reaches past the triangles above the stop: it takes
            // the largest of the rest, bounded now. The others stay below the
            // stop (their bounds only fall, the stop only rises), so this is
            // the last batch.
            let near = &s.near;
            order[above..].par_iter_mut().for_each(|(ub, k)| *ub = bound(near, *k));
            top_sorted(&mut order[above..], end - above);
            above = end;
        }
        let batch = &order[s.screened..end];
        batch_len = (2 * batch_len).min(SCREEN_BATCH_MAX);
        measure_batch(a, b, (batch, tol), &mut s, &mut measured, &upper_of);
        s.screened += batch.len();
        // The vertices just measured tighten the bounds of the triangles above the stop.
        let near = &s.near;
        order[s.screened..above]
            .par_iter_mut()
            .for_each(|(ub, k)| *ub = bound(near, *k));
        above = s.screened + sort_above(&mut order[s.screened..above], s.lb + tol);
        rebounded = true;
    }
    // The rest's largest bound, with the final distances, next in the order.
    if rebounded {
        let near = &s.near;
        order[above..].par_iter_mut().for_each(|(ub, k)| *ub = bound(near, *k));
    }
    top_sorted(&mut order[s.screened..], 1);
    s
}

/// Measures the vertices of `batch` not measured before (`measured`) and its
/// triangles' centroids against `b`, into `s` (distances, largest distance,
/// queries, the centroids' nearest triangles); `upper_of` bounds a vertex's
/// distance, `tol` is the screening's tolerance.
///
/// A point's search stops at the first triangle of B within its *accept*
/// radius, which is at most the largest distance found before the batch, so
/// a point stopped there could not have raised it: the largest distance is
/// the one the full searches give. A vertex's radius is also at most
/// `lb + tol − L/√3`, L the longest edge of its triangles in the batch, so
/// every triangle of the batch whose vertices all stop there has a
/// Lipschitz bound within the stop and needs no refining. Where B is nearly
/// equidistant from the point (deep inside a solid far from the other), the
/// full search opens every box about as near as the nearest triangle; the
/// stopped one opens one path. Such a vertex keeps an upper bound of its
/// distance and a triangle of B within it, which is all the bounds use.
fn measure_batch(
    a: MeshRef<'_>,
    b: &Bvh,
    (batch, tol): (&[(f64, u32)], f64),
    s: &mut Screened,
    measured: &mut [bool],
    upper_of: &(impl Fn(u32) -> f64 + Sync),
) {
    let lb = s.lb;
    // (vertex, L/√3 of its longest triangle in the batch), one entry a vertex.
    let mut fresh: Vec<(u32, f64)> = batch
        .iter()
        .flat_map(|&(_, k)| {
            let t = a.triangles[k as usize];
            let slack = longest_edge(&t.map(|i| a.positions[i as usize])) / 3f64.sqrt();
            t.map(|i| (i, slack))
        })
        .filter(|&(i, _)| !measured[i as usize])
        .collect();
    fresh.sort_unstable_by(|x, y| x.0.cmp(&y.0).then(y.1.total_cmp(&x.1)));
    fresh.dedup_by_key(|x| x.0);
    let found: Vec<(f64, u32)> = fresh
        .par_iter()
        .map(|&(i, slack)| {
            let accept = lb.min(lb + tol - slack);
            let upper = upper_of(i);
            if upper <= accept {
                // Its bound is already as good as any answer: no search.
                return (upper, u32::MAX);
            }
            nearest_within(b, a.positions[i as usize], upper, accept)
        })
        .collect();
    for (&(i, _), &d) in fresh.iter().zip(&found) {
        s.near[i as usize] = d;
        measured[i as usize] = true;
        s.lb = s.lb.max(d.0);
    }
    let near = &s.near;
    let centroids: Vec<(f64, u32)> = batch
        .par_iter()
        .map(|&(_, k)| {
            let t = &a.triangles[k as usize];
            let v = t.map(|i| a.positions[i as usize]);
            let c = (v[0] + v[1] + v[2]) / 3.0;
            let hint = (0..3)
                .map(|i| near[t[i] as usize].0 + c.distance(v[i]))
                .fold(f64::INFINITY, f64::min);
            // A centroid's distance only raises the largest one: anything within it will do.
            if hint <= lb {
                return (hint, u32::MAX);
            }
            nearest_within(b, c, hint, lb)
        })
        .collect();
    s.queries += found.iter().chain(&centroids).filter(|d| d.1 != u32::MAX).count();
    s.lb = centroids.iter().fold(s.lb, |m, c| m.max(c.0));
    s.centroid_nearest.extend(centroids.iter().map(|c| c.1));
}

/// The longest edge of a triangle.
pub(super) fn longest_edge(v: &[DVec3; 3]) -> f64 {
    v[0].distance(v[1]).max(v[1].distance(v[2])).max(v[2].distance(v[0]))
}

/// Largest bound first; ties by index, so the screening order is the same on every run.
pub(super) fn by_bound(x: &(f64, u32), y: &(f64, u32)) -> std::cmp::Ordering {
    y.0.total_cmp(&x.0).then(x.1.cmp(&y.1))
}

/// Moves the entries of `order` whose bound is above `stop` to its front,
/// sorted [`by_bound`], and returns how many there are.
fn sort_above(order: &mut [(f64, u32)], stop: f64) -> usize {
    let mut n = 0;
    for i in 0..order.len() {
        if order[i].0 > stop {
            order.swap(i, n);
            n += 1;
        }
    }
    order[..n].par_sort_unstable_by(by_bound);
    n
}

/// Puts the first `m` entries of `order` [`by_bound`] at its front, sorted.
fn top_sorted(order: &mut [(f64, u32)], m: usize) {
    let m = m.min(order.len());
    if m == 0 {
        return;
    }
    if m < order.len() {
        order.select_nth_unstable_by(m - 1, by_bound);
    }
    order[..m].par_sort_unstable_by(by_bound);
}

/// Distance and nearest triangle of `b` from `p`, whose distance is at most
/// `hint`: the search skips everything farther. Should nothing lie within
/// the hint (a bound that was not one), the search is repeated unbounded, so
/// the distance returned is always attained. The search stops at the first
/// triangle within `accept` (cd; 0 or less: never), whose distance is then
/// returned: an upper bound of the distance, attained by that triangle.
pub(super) fn nearest_within(b: &Bvh, p: DVec3, hint: f64, accept: f64) -> (f64, u32) {
    let accept2 = if accept > 0.0 {
        accept * accept
    } else {
        f64::NEG_INFINITY
    };
    let (d2, t) = if hint.is_finite() {
        let (d2, t, _) = b.nearest_below_or_within(p, search_limit2(hint), accept2);
        (d2, t)
    } else {
        (f64::INFINITY, u32::MAX)
    };
    if t == u32::MAX {
        let (d2, t, _) = b.nearest_below_or_within(p, f64::INFINITY, accept2);
        return (d2.sqrt(), t);
    }
    (d2.sqrt(), t)
}
