//! Derivative-free minimisers shared by the fits (`photosolid::fit`: spots,
//! lobes) and the metrics (`photosolid::metrics::walls`): Nelder–Mead in n
//! dimensions, golden-section search on an interval, and the local minima of
//! a sampled function to start them from. Deterministic: no randomness, the
//! first of equal values wins.

/// Nelder–Mead minimisation of `f` from `x0` with initial steps `step`.
/// Stops after `max_evals`, or when the simplex values agree within `ftol`
/// (absolute) or its extent is below `xtol`. Returns (best point, value, evals).
pub fn nelder_mead<F: FnMut(&[f64]) -> f64>(
    f: &mut F,
    x0: &[f64],
    step: &[f64],
    max_evals: usize,
    ftol: f64,
    xtol: f64,
) -> (Vec<f64>, f64, usize) {
    let n = x0.len();
    let mut pts: Vec<Vec<f64>> = vec![x0.to_vec()];
    for i in 0..n {
        let mut p = x0.to_vec();
        p[i] += step[i];
        pts.push(p);
    }
    let mut vals: Vec<f64> = pts.iter().map(|p| f(p)).collect();
    let mut evals = n + 1;
    while evals < max_evals {
        let mut order: Vec<usize> = (0..=n).collect();
        order.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
        pts = order.iter().map(|&i| pts[i].clone()).collect();
        vals = order.iter().map(|&i| vals[i]).collect();
        if vals[n] - vals[0] <= ftol || extent(&pts) <= xtol {
            break;
        }
        let centroid = centroid(&pts[..n]);
        let xr = combine(&centroid, &pts[n], -1.0);
        let fr = f(&xr);
        evals += 1;
        if fr < vals[0] {
            let xe = combine(&centroid, &pts[n], -2.0);
            let fe = f(&xe);
            evals += 1;
            if fe < fr {
                pts[n] = xe;
                vals[n] = fe;
            } else {
                pts[n] = xr;
                vals[n] = fr;
            }
        } else if fr < vals[n - 1] {
            pts[n] = xr;
            vals[n] = fr;
        } else {
            // Contract towards the better of the worst point and its reflection.
            let (xc, fc) = if fr < vals[n] {
                let xc = combine(&centroid, &xr, 0.5);
                let fc = f(&xc);
                (xc, fc)
            } else {
                let xc = combine(&centroid, &pts[n], 0.5);
                let fc = f(&xc);
                (xc, fc)
            };
            evals += 1;
            if fc < vals[n].min(fr) {
                pts[n] = xc;
                vals[n] = fc;
            } else {
                for i in 1..=n {
                    pts[i] = combine(&pts[0], &pts[i], 0.5);
                    vals[i] = f(&pts[i]);
                }
                evals += n;
            }
        }
    }
    let b = (1..=n).fold(0, |b, a| if vals[a].total_cmp(&vals[b]).is_lt() { a } else { b });
    (pts[b].clone(), vals[b], evals)
}

/// The point a + t (b − a), coordinate by coordinate (t = −1: `b` reflected
/// through `a`; 0.5: half-way).
fn combine(a: &[f64], b: &[f64], t: f64) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x + t * (y - x)).collect()
}

/// The extent of a simplex sorted best first: the largest coordinate difference
/// (in the units of the coordinates) between the best point and any other.
fn extent(pts: &[Vec<f64>]) -> f64 {
    pts[1..]
        .iter()
        .map(|p| p.iter().zip(&pts[0]).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max)
}

/// The centroid of the points `pts`: the simplex without its worst point, so n
/// points in n dimensions.
fn centroid(pts: &[Vec<f64>]) -> Vec<f64> {
    let n = pts.len();
    let mut centroid = vec![0.0; n];
    for p in pts {
        for (c, v) in centroid.iter_mut().zip(p) {
            *c += v / n as f64;
        }
    }
    centroid
}

/// Golden-section search for a minimum of `f` on `[a, b]`, until the
/// bracket is narrower than `tol`: of the last two interior points and the
/// two ends, the one whose `value` is least (the first of equals). `f` is
/// called twice plus once per step, and at both ends.
pub fn golden_section<T>(
    mut f: impl FnMut(f64) -> T,
    value: impl Fn(&T) -> f64,
    mut a: f64,
    mut b: f64,
    tol: f64,
) -> T {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let mut fc = f(c);
    let mut fd = f(d);
    let ea = f(a);
    let eb = f(b);
    while b - a > tol {
        if value(&fc) <= value(&fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    [fd, ea, eb].into_iter().fold(fc, |best, next| {
        if value(&next).total_cmp(&value(&best)).is_lt() {
            next
        } else {
            best
        }
    })
}

/// The indices of the local minima of `values` (no larger than their
/// neighbours; the ends count), the `keep` least first.
pub fn best_local_minima(values: &[f64], keep: usize) -> Vec<usize> {
    let n = values.len();
    let mut minima: Vec<usize> = (0..n)
        .filter(|&i| (i == 0 || values[i] <= values[i - 1]) && (i + 1 == n || values[i] <= values[i + 1]))
        .collect();
    minima.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    minima.truncate(keep);
    minima
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nelder–Mead finds the minimum of a shifted, scaled quadratic bowl in 3
    /// dimensions to within its stopping extent.
    #[test]
    fn nelder_mead_finds_a_bowl_minimum() {
        let mut f = |x: &[f64]| (x[0] - 1.0).powi(2) + 4.0 * (x[1] + 2.0).powi(2) + 0.5 * (x[2] - 0.25).powi(2);
        let (x, v, evals) = nelder_mead(&mut f, &[0.0, 0.0, 0.0], &[0.5, 0.5, 0.5], 5000, 0.0, 1e-9);
        assert!(v < 1e-12, "{v} at {x:?}");
        for (got, want) in x.iter().zip([1.0, -2.0, 0.25]) {
            assert!((got - want).abs() < 1e-5, "{x:?}");
        }
        assert!(evals < 5000);
    }

    /// Golden-section search brackets the minimum of a parabola to `tol`, and
    /// an end wins when the minimum lies outside the interval.
    #[test]
    fn golden_section_brackets_the_minimum() {
        let x = golden_section(|x| x, |&x| (x - 0.3) * (x - 0.3), -1.0, 2.0, 1e-9);
        assert!((x - 0.3).abs() < 1e-8, "{x}");
        let end = golden_section(|x| x, |&x| x, 0.0, 1.0, 1e-6);
        assert_eq!(end, 0.0);
    }

    /// Local minima count the ends, ties included, least first, `keep` at most.
    #[test]
    fn local_minima_least_first() {
        let v = [3.0, 1.0, 2.0, 0.5, 0.5, 4.0, 2.5];
        assert_eq!(best_local_minima(&v, 10), vec![3, 4, 1, 6]);
        assert_eq!(best_local_minima(&v, 2), vec![3, 4]);
        assert!(best_local_minima(&[], 3).is_empty());
    }
}
