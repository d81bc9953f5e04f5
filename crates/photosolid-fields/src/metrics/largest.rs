//! The largest of many distances, computed only where it can be set.
//!
//! A distance search that starts from an upper bound and only improves on
//! it (the surface search of [`crate::metrics::nearest`] starts at U, the
//! distance along the point's own direction; the cells of
//! [`crate::metrics::cells`] at the point's own cell) never returns more
//! than that bound, which costs one lookup. So the largest distance over a
//! set of points needs the search only at the points whose bound exceeds
//! the largest distance found: [`largest_of`] searches them from the largest
//! bound down, a batch at a time, and stops at the first bound no larger
//! than the largest found (or than a floor found elsewhere). A Hausdorff
//! figure that reports no mean (`tradeoff`'s) needs nothing more.

use rayon::prelude::*;

/// The largest distance over a set of points and how many were searched.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LargestDistance {
    /// The largest distance found, cd (0 when no point was searched): the
    /// largest over all the points whenever it exceeds the floor.
    pub value_cd: f64,
    /// Points searched; the others could not exceed the largest distance.
    pub searched: usize,
}

/// Points searched at a time per thread: enough to keep the threads busy,
/// few enough that the bar rises soon.
const BATCH_PER_THREAD: usize = 32;

/// The largest `distance(k)` over `k` in `0..bounds.len()` when it exceeds
/// `floor` (cd), where `distance(k) ≤ bounds[k]` for every `k`: points are
/// searched in order of decreasing bound, in parallel batches, until the
/// next bound is no larger than the largest distance found or than `floor`.
/// The value is then bit for bit the largest of every `distance(k)`.
pub fn largest_of(bounds: &[f64], floor: f64, distance: impl Fn(usize) -> f64 + Sync) -> LargestDistance {
    // A NaN bound bounds nothing: searched first, as if infinite.
    let mut order: Vec<(f64, usize)> = bounds
        .iter()
        .map(|&b| if b.is_nan() { f64::INFINITY } else { b })
        .zip(0..)
        .collect();
    order.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut best = 0.0_f64;
    let mut searched = 0;
    let batch = BATCH_PER_THREAD * rayon::current_num_threads().max(1);
    while searched < order.len() && order[searched].0 > best.max(floor) {
        let bar = best.max(floor);
        let end = searched
            + order[searched..]
                .iter()
                .take(batch)
                .take_while(|&&(u, _)| u > bar)
                .count();
        best = order[searched..end]
            .par_iter()
            .map(|&(_, k)| distance(k))
            .reduce(|| best, f64::max);
        searched = end;
    }
    LargestDistance {
        value_cd: best,
        searched,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pruned largest equals the plain largest, and only points whose
    /// bound exceeds it (or the floor) are searched; NaN bounds sort first
    /// and are searched, so they never hide a point.
    #[test]
    fn largest_of_equals_the_plain_largest() {
        let n = 5000;
        let dist = |k: usize| ((k as f64 * 0.37).sin().abs() * 10.0).floor();
        let bounds: Vec<f64> = (0..n).map(|k| dist(k) + (k % 7) as f64).collect();
        let want = (0..n).map(dist).fold(0.0, f64::max);
        let got = largest_of(&bounds, 0.0, dist);
        assert_eq!(got.value_cd, want);
        let can = bounds.iter().filter(|&&b| b > want).count();
        assert!(
            got.searched >= can && got.searched < n,
            "{} of {n}, {can} could",
            got.searched
        );
        let floored = largest_of(&bounds, 100.0, dist);
        assert_eq!(floored.searched, 0);
        assert_eq!(largest_of(&[], 0.0, dist).searched, 0);
        let with_nan = largest_of(&[1.0, f64::NAN, 3.0], 0.0, |k| [0.5, 2.0, 1.0][k]);
        assert_eq!(with_nan.value_cd, 2.0);
    }
}
