//! Per-axis knot lists and tap tables: the one seam the CPU render and the
//! GPU shader share.
//!
//! An [`Axis`] is either the periodic C axis (the full-circle plane list,
//! period 360°) or the γ band (the stored rows plus one ghost knot at each
//! end). For a query position it yields a [`Tap`]: four storage indices and
//! four weights. [`AxisTaps`] is a table of them for a list of positions,
//! built once on the CPU with f32 weights (what a shader reads).

use crate::model::ANGLE_EPS;

use super::filter::Filter;

/// One tap row in f64: four storage indices and their weights (or PCHIP's
/// `[s, h_prev, h, h_next]`; see [`super::filter::combine`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tap {
    pub index: [u32; 4],
    pub weight: [f64; 4],
}

impl Tap {
    /// A query outside the band: every weight (and PCHIP's `h`) is 0, so the result is 0.
    fn zero(index: u32) -> Self {
        Tap {
            index: [index; 4],
            weight: [0.0; 4],
        }
    }
    /// The knot `index` itself, exactly.
    fn exact(index: u32, filter: Filter, spacing: f64) -> Self {
        Tap {
            index: [index; 4],
            weight: if filter.is_data_dependent() {
                [0.0, spacing, spacing, spacing]
            } else {
                [0.0, 1.0, 0.0, 0.0]
            },
        }
    }
}

/// The largest k with `knots[k] <= x` (−1 when `x` lies before the first
/// knot), for ascending `knots`: the same answer as a binary search, found
/// from the index a uniform axis would have (exact on uniform axes, a step
/// or two away on nearly uniform ones) and a short walk; a binary search
/// when the walk would be long. A lookup's taps are most of its cost.
#[inline]
fn last_at_or_below(knots: &[f64], x: f64) -> isize {
    let n = knots.len();
    let (first, last) = (knots[0], knots[n - 1]);
    if x.is_nan() || x < first {
        return -1; // before the first knot, or NaN (as the binary search answers)
    }
    if x >= last {
        return n as isize - 1;
    }
    // first <= x < last, so n >= 2 and the guess lies in 0..n-1.
    let guess = ((x - first) / (last - first) * (n - 1) as f64) as usize;
    let mut k = guess.min(n - 2);
    for _ in 0..4 {
        if knots[k] > x {
            k -= 1; // knots[0] <= x, so k > 0 here
        } else if knots[k + 1] <= x {
            k += 1; // knots[n - 1] > x, so k + 1 < n - 1 here
        } else {
            return k as isize;
        }
    }
    knots.partition_point(|&t| t <= x) as isize - 1
}

/// How an axis continues beyond its knots.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum AxisKind {
    /// C: knot k + n is knot k shifted by 360°.
    Periodic,
    /// γ: queries outside `[knots[0], knots[n-1]]` (± [`ANGLE_EPS`]) give 0;
    /// inside, taps beyond the ends read one ghost knot each side:
    /// `(position in degrees, storage index)`.
    Band { lo: (f64, u32), hi: (f64, u32) },
}

/// Knots of one axis and where each one's values are stored.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    /// Knot positions (degrees), strictly ascending; for [`AxisKind::Periodic`] in [0, 360).
    pub knots: Vec<f64>,
    /// Storage index of each knot (C: stored column; γ: padded row).
    pub store: Vec<u32>,
    pub kind: AxisKind,
}

impl Axis {
    /// Bytes held by the knot and storage tables.
    pub fn bytes(&self) -> usize {
        self.knots.len() * 8 + self.store.len() * 4
    }

    /// Knot `k` (any integer for a periodic axis, −1..=n for a band) as (position, storage index).
    #[inline]
    fn knot(&self, k: isize) -> (f64, u32) {
        let n = self.knots.len() as isize;
        match self.kind {
            AxisKind::Periodic => {
                // A tap reaches at most two knots past either end: one turn
                // without an integer division (the general form otherwise).
                let (kk, turns) = if (0..n).contains(&k) {
                    (k, 0.0)
                } else if (-n..0).contains(&k) {
                    (k + n, -1.0)
                } else if (n..2 * n).contains(&k) {
                    (k - n, 1.0)
                } else {
                    (k.rem_euclid(n), k.div_euclid(n) as f64)
                };
                let kk = kk as usize;
                (self.knots[kk] + 360.0 * turns, self.store[kk])
            }
            AxisKind::Band { lo, hi } => {
                if k < 0 {
                    lo
                } else if k >= n {
                    hi
                } else {
                    (self.knots[k as usize], self.store[k as usize])
                }
            }
        }
    }

    /// The tap row for a query at `x` (degrees; a periodic axis wraps any real `x`).
    pub fn tap(&self, filter: Filter, x: f64) -> Tap {
        let n = self.knots.len();
        let (x, i) = match self.kind {
            AxisKind::Periodic => {
                if n == 1 {
                    return Tap::exact(self.store[0], filter, 360.0);
                }
                let x = crate::model::wrap360(x);
                // Largest k with t_k <= x; −1 when x lies before the first knot (wraps to the last).
                (x, last_at_or_below(&self.knots, x))
            }
            AxisKind::Band { .. } => {
                let (a, b) = (self.knots[0], self.knots[n - 1]);
                if !(x >= a - ANGLE_EPS && x <= b + ANGLE_EPS) {
                    return Tap::zero(self.store[0]);
                }
                if n == 1 {
                    return Tap::exact(self.store[0], filter, 1.0);
                }
                let x = x.clamp(a, b);
                let i = last_at_or_below(&self.knots, x).clamp(0, n as isize - 2);
                (x, i)
            }
        };
        let (t0, i0) = self.knot(i - 1);
        let (t1, i1) = self.knot(i);
        let (t2, i2) = self.knot(i + 1);
        let (t3, i3) = self.knot(i + 2);
        let s = ((x - t1) / (t2 - t1)).clamp(0.0, 1.0);
        let weight = filter
            .linear_weights([t0, t1, t2, t3], s)
            .unwrap_or([s, t1 - t0, t2 - t1, t3 - t2]);
        Tap {
            index: [i0, i1, i2, i3],
            weight,
        }
    }

    /// The tap table for `positions` (degrees).
    pub fn table(&self, filter: Filter, positions: Vec<f64>) -> AxisTaps {
        let (index, weight) = positions
            .iter()
            .map(|&x| {
                let t = self.tap(filter, x);
                (t.index, t.weight.map(|w| w as f32))
            })
            .unzip();
        AxisTaps {
            filter,
            positions,
            index,
            weight,
        }
    }
}

/// A per-axis tap table, built once on the CPU and consumed unchanged by the
/// CPU render and (later) the GPU shader.
///
/// Entry `k` reconstructs the value at `positions[k]` (degrees) from four
/// stored values: `v[m] = src(index[k][m])`, then
/// - every filter but PCHIP: `Σ_m weight[k][m] · v[m]`;
/// - PCHIP: `weight[k] = [s, h_prev, h, h_next]`, the fraction `s` in the
///   interval `[t_i, t_{i+1}]` and the spacings `t_i − t_{i−1}`,
///   `t_{i+1} − t_i`, `t_{i+2} − t_{i+1}` (degrees); the two Fritsch–Butland
///   slopes at `t_i` and `t_{i+1}` are computed from the four values and
///   these spacings, then the cubic Hermite is evaluated
///   ([`super::filter::combine`]). `h = 0` marks a position outside the band.
///
/// Indices always point at valid storage, also where every weight is 0.
/// For the γ axis of a [`super::LightTexture`] the index is a padded row of a
/// column; for the C axis it is the stored column.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisTaps {
    /// The filter whose weights these are.
    pub filter: Filter,
    /// Query positions (degrees), one per entry.
    pub positions: Vec<f64>,
    /// Four storage indices per entry, for taps `i−1, i, i+1, i+2`.
    pub index: Vec<[u32; 4]>,
    /// Four weights per entry (or PCHIP's spacings, see the type docs).
    pub weight: Vec<[f32; 4]>,
}

impl AxisTaps {
    /// Number of entries.
    pub fn len(&self) -> usize {
        self.index.len()
    }
    /// True when there are no entries.
    pub fn is_empty(&self) -> bool {
        self.index.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn band(knots: Vec<f64>, lo: f64, hi: f64) -> Axis {
        let n = knots.len() as u32;
        Axis {
            store: (1..=n).collect(),
            knots,
            kind: AxisKind::Band {
                lo: (lo, 0),
                hi: (hi, n + 1),
            },
        }
    }

    #[test]
    fn band_taps_hit_knots_and_reject_outside() {
        let a = band(vec![0.0, 10.0, 25.0, 90.0], -10.0, 155.0);
        for f in [Filter::Nearest, Filter::Bilinear, Filter::CatmullRom] {
            for (k, &t) in a.knots.iter().enumerate() {
                let tap = a.tap(f, t);
                let hit = (0..4).find(|&m| tap.weight[m] == 1.0).unwrap();
                assert_eq!(tap.index[hit], k as u32 + 1);
                assert_eq!(tap.weight.iter().filter(|&&w| w != 0.0).count(), 1, "{f} at {t}");
            }
            assert_eq!(a.tap(f, 90.5).weight, [0.0; 4]);
            assert_eq!(a.tap(f, -0.5).weight, [0.0; 4]);
        }
        // Ghost knots are used at the ends.
        assert_eq!(a.tap(Filter::CatmullRom, 5.0).index, [0, 1, 2, 3]);
        assert_eq!(a.tap(Filter::CatmullRom, 50.0).index, [2, 3, 4, 5]);
    }

    /// The guessed-and-walked knot search answers what the binary search
    /// answers, on uniform, nearly uniform, clustered and two-knot axes, at
    /// knots, between them, outside and at NaN.
    #[test]
    fn knot_search_equals_the_binary_search() {
        let uniform: Vec<f64> = (0..73).map(|k| 5.0 * k as f64).collect();
        let nearly: Vec<f64> = (0..37).map(|k| 5.0 * k as f64 + 0.3 * ((k * 7) % 3) as f64).collect();
        let clustered: Vec<f64> = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 5.0, 10.0, 20.0, 45.0, 90.0, 179.0, 180.0].to_vec();
        let geometric: Vec<f64> = (0..30).map(|k| 1.3f64.powi(k) - 1.0).collect();
        for knots in [uniform, nearly, clustered, geometric, vec![0.0, 180.0], vec![42.0]] {
            let (lo, hi) = (knots[0] - 10.0, knots[knots.len() - 1] + 10.0);
            let mut xs: Vec<f64> = (0..=4000).map(|k| lo + (hi - lo) * k as f64 / 4000.0).collect();
            xs.extend(knots.iter().copied());
            xs.extend(knots.iter().map(|&t| t - 1e-12));
            xs.push(f64::NAN);
            for x in xs {
                let want = knots.partition_point(|&t| t <= x) as isize - 1;
                assert_eq!(last_at_or_below(&knots, x), want, "{x} in {knots:?}");
            }
        }
    }

    /// Knots reached past either end of a periodic axis carry whole turns,
    /// the same with or without the division.
    #[test]
    fn periodic_knots_past_the_ends() {
        for n in 2isize..6 {
            let a = Axis {
                knots: (0..n).map(|k| 360.0 * k as f64 / n as f64 + 1.0).collect(),
                store: (0..n as u32).collect(),
                kind: AxisKind::Periodic,
            };
            for k in -3 * n..4 * n {
                let kk = k.rem_euclid(n) as usize;
                let want = (a.knots[kk] + 360.0 * k.div_euclid(n) as f64, a.store[kk]);
                assert_eq!(a.knot(k), want, "n {n}, k {k}");
            }
        }
    }

    #[test]
    fn periodic_taps_wrap() {
        let a = Axis {
            knots: vec![10.0, 100.0, 200.0, 300.0],
            store: vec![0, 1, 2, 3],
            kind: AxisKind::Periodic,
        };
        let t = a.tap(Filter::CatmullRom, 5.0); // between 300 − 360 and 10
        assert_eq!(t.index, [2, 3, 0, 1]);
        let t = a.tap(Filter::Bilinear, 695.0); // 335
        assert_eq!(t.index, [2, 3, 0, 1]);
        assert!((t.weight[1] - 0.5).abs() < 1e-12);
        let t = a.tap(Filter::Bilinear, 330.0);
        assert!((t.weight[1] - 40.0 / 70.0).abs() < 1e-12);
        assert_eq!(a.tap(Filter::Bilinear, 360.0), a.tap(Filter::Bilinear, 0.0));
    }
}
