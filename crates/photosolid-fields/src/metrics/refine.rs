//! The certified branch-and-bound shared by [`super::hausdorff()`] (triangles
//! of a mesh) and [`super::profile::hausdorff`] (segments of a profile).
//!
//! A one-sided distance `h(A, B) = sup_{a ∈ A} d(a, B)` is certified by
//! covering A with cells, each with an upper bound of `d(·, B)` over it, and
//! a lower bound `lb`: the largest distance actually evaluated. The cell with
//! the largest upper bound is split (which evaluates new points, raising
//! `lb`) until that bound is within the tolerance of `lb`, or the query cap
//! is hit. Every cell dropped without refinement (its bound already within
//! the tolerance) is remembered by its bound, so the final upper bound covers
//! all of A, not only the cells still queued.
//!
//! The two metrics differ only in their cells, which [`Refine`] describes.
//! A mesh's own triangles wait as small *seeds* (an index: 16 bytes where a
//! split triangle holds 120; issue 15, peak memory of `compare` on 200 k
//! triangles) and become cells only when they are refined first; a profile
//! has no seeds ([`std::convert::Infallible`]).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// An item of a refinement queue with its upper bound (same unit as the
/// distances), ordered by that bound alone: the queue is a max-heap of bounds.
#[derive(Debug, Clone, Copy)]
pub(super) struct ByUpper<T> {
    /// Upper bound of the distance over the item.
    pub ub: f64,
    /// The cell or seed.
    pub item: T,
}

impl<T> PartialEq for ByUpper<T> {
    fn eq(&self, o: &Self) -> bool {
        self.ub == o.ub
    }
}
impl<T> Eq for ByUpper<T> {}
impl<T> PartialOrd for ByUpper<T> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl<T> Ord for ByUpper<T> {
    fn cmp(&self, o: &Self) -> Ordering {
        self.ub.total_cmp(&o.ub)
    }
}

/// The cells of one metric: how a seed becomes a cell, and how a cell splits.
pub(super) trait Refine {
    /// A region of A with the data its split needs (vertices and their distances).
    type Cell;
    /// A region of A queued before any refinement, in a smaller form than a
    /// cell (turned into one by [`Refine::expand`] when it is refined).
    type Seed;
    /// The children of a split with their bounds (an array: no allocation).
    type Children: IntoIterator<Item = ByUpper<Self::Cell>>;
    /// Distance queries one split makes (counted against the cap).
    const QUERIES_PER_SPLIT: usize;
    /// The cell a seed stands for.
    fn expand(&self, seed: Self::Seed) -> Self::Cell;
    /// The children of `cell`, each with its upper bound; raises `lb` to the
    /// largest distance the split evaluated.
    fn split(&self, cell: &Self::Cell, lb: &mut f64) -> Self::Children;
}

/// What a refinement certified.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Refined {
    /// Largest distance evaluated (attained: `h ≥ lb`).
    pub lb: f64,
    /// Certified upper bound of `h`, never below `lb`.
    pub ub: f64,
    /// Distance queries made by the splits.
    pub queries: usize,
    /// Whether the tolerance was reached before the query cap.
    pub converged: bool,
}

/// The state of one refinement: the queues of cells and seeds, the lower
/// bound, and the largest bound of every item dropped without refinement.
#[derive(Debug)]
pub(super) struct Refinement<C, S> {
    lb: f64,
    tol: f64,
    pruned_ub: f64,
    cells: BinaryHeap<ByUpper<C>>,
    seeds: BinaryHeap<ByUpper<S>>,
}

impl<C, S> Refinement<C, S> {
    /// An empty refinement from the lower bound `lb` already attained, to
    /// within `tolerance` (a negative tolerance is 0).
    pub fn new(lb: f64, tolerance: f64) -> Self {
        Self {
            lb,
            tol: tolerance.max(0.0),
            pruned_ub: 0.0,
            cells: BinaryHeap::new(),
            seeds: BinaryHeap::new(),
        }
    }

    /// The tolerance test: whether an item with upper bound `ub` must be
    /// refined (it is more than the tolerance above the lower bound).
    pub fn needs_refining(&self, ub: f64) -> bool {
        ub > self.lb + self.tol
    }

    /// Queues `cell` if its bound `ub` needs refining, else records the bound as pruned.
    pub fn offer(&mut self, ub: f64, cell: C) {
        if self.needs_refining(ub) {
            self.cells.push(ByUpper { ub, item: cell });
        } else {
            self.pruned_ub = self.pruned_ub.max(ub);
        }
    }

    /// Queues seeds already tested with [`Refinement::needs_refining`] (by a
    /// parallel pass), and the largest bound of those it dropped.
    pub fn add_seeds(&mut self, kept: Vec<ByUpper<S>>, pruned_ub: f64) {
        self.seeds.extend(kept);
        self.pruned_ub = self.pruned_ub.max(pruned_ub);
    }

    /// Room for `n` more seeds (one allocation for a whole mesh's triangles).
    pub fn reserve_seeds(&mut self, n: usize) {
        self.seeds.reserve(n);
    }

    /// The largest upper bound queued, if any.
    fn top(&self) -> Option<f64> {
        match (self.seeds.peek(), self.cells.peek()) {
            (None, None) => None,
            (Some(s), None) => Some(s.ub),
            (None, Some(c)) => Some(c.ub),
            (Some(s), Some(c)) => Some(s.ub.max(c.ub)),
        }
    }

    /// The queued item whose bound is `top`, as a cell: a split cell first
    /// when both queues hold that bound.
    fn pop<R: Refine<Cell = C, Seed = S>>(&mut self, top: f64, cells: &R) -> Option<C> {
        if self.cells.peek().is_some_and(|c| c.ub >= top) {
            return self.cells.pop().map(|c| c.item);
        }
        self.seeds.pop().map(|s| cells.expand(s.item))
    }

    /// Refines the largest bound first until it is within the tolerance of
    /// the lower bound or `max_queries` split queries were made.
    pub fn run<R: Refine<Cell = C, Seed = S>>(mut self, cells: &R, max_queries: usize) -> Refined {
        let mut queries = 0usize;
        let mut converged = true;
        let top = loop {
            let Some(top) = self.top() else {
                break self.lb;
            };
            // The queue's top can fall below `lb` (which splits raise after
            // cells were queued); the bound returned is then `lb`, never less:
            // the supremum is at least every value attained.
            if top <= self.lb + self.tol {
                break top.max(self.lb);
            }
            if queries >= max_queries {
                converged = false;
                break top.max(self.lb);
            }
            // `top` came from one of the queues, so this pops.
            let Some(cell) = self.pop(top, cells) else {
                break top.max(self.lb);
            };
            let children = cells.split(&cell, &mut self.lb);
            queries += R::QUERIES_PER_SPLIT;
            for child in children {
                self.offer(child.ub, child.item);
            }
        };
        Refined {
            lb: self.lb,
            ub: top.max(self.pruned_ub),
            queries,
            converged,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Intervals of [0, 1] under f(x) = x (Lipschitz bound: the right end);
    /// a split evaluates the midpoint. `stall` makes every bound stay 1
    /// above the lower bound, so only the cap stops it.
    struct Line {
        stall: bool,
    }

    impl Refine for Line {
        type Cell = (f64, f64);
        type Seed = (f64, f64);
        type Children = [ByUpper<(f64, f64)>; 2];
        const QUERIES_PER_SPLIT: usize = 1;
        fn expand(&self, seed: (f64, f64)) -> (f64, f64) {
            seed
        }
        fn split(&self, c: &(f64, f64), lb: &mut f64) -> Self::Children {
            let m = 0.5 * (c.0 + c.1);
            *lb = lb.max(m);
            // Stalled, every child stays 1 above the raised lower bound.
            let above = if self.stall { 1.0 + *lb } else { 0.0 };
            [(c.0, m), (m, c.1)].map(|item| ByUpper {
                ub: item.1 + above,
                item,
            })
        }
    }

    #[test]
    fn refines_to_the_tolerance_and_counts_queries() {
        let mut r = Refinement::new(0.0, 1e-3);
        r.add_seeds(
            vec![ByUpper {
                ub: 1.0,
                item: (0.0, 1.0),
            }],
            0.0,
        );
        let out = r.run(&Line { stall: false }, 1000);
        assert!(out.converged && out.ub >= out.lb && out.ub - out.lb <= 1e-3, "{out:?}");
        assert_eq!(out.queries, 10); // 1 − 2^−10 is within 1e-3 of 1
    }

    #[test]
    fn the_cap_stops_refinement_unconverged() {
        let mut r = Refinement::new(0.0, 0.0);
        r.offer(2.0, (0.0, 1.0));
        let out = r.run(&Line { stall: true }, 7);
        assert!(!out.converged && out.queries == 7 && out.ub > out.lb, "{out:?}");
    }

    #[test]
    fn the_bound_is_never_below_the_lower_bound_and_covers_pruned_cells() {
        // The first split raises lb to 0.5, above the other queued bound 0.3:
        // the result is lb, not 0.3.
        let mut r: Refinement<(f64, f64), (f64, f64)> = Refinement::new(0.0, 0.0);
        r.offer(1.0, (0.0, 1.0));
        r.offer(0.3, (0.0, 0.2));
        struct Raise;
        impl Refine for Raise {
            type Cell = (f64, f64);
            type Seed = (f64, f64);
            type Children = [ByUpper<(f64, f64)>; 0];
            const QUERIES_PER_SPLIT: usize = 1;
            fn expand(&self, seed: (f64, f64)) -> (f64, f64) {
                seed
            }
            fn split(&self, _: &(f64, f64), lb: &mut f64) -> Self::Children {
                *lb = 0.5;
                []
            }
        }
        let out = r.run(&Raise, 100);
        assert_eq!((out.lb, out.ub, out.queries), (0.5, 0.5, 1));
        // A bound dropped at the start still counts.
        let mut r: Refinement<(f64, f64), (f64, f64)> = Refinement::new(1.0, 0.5);
        r.offer(1.4, (0.0, 1.0));
        let out = r.run(&Raise, 100);
        assert_eq!((out.lb, out.ub, out.queries), (1.0, 1.4, 0));
    }
}
