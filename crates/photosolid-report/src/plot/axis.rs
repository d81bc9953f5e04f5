//! Axis ticks for the plots: steps on the 1–2–5 × 10^k sequence, degree
//! steps, tick labels, and the linear-or-log value axis of [`super::scatter()`].

/// A step on the 1–2–5 × 10^k sequence giving about `target` intervals over `range`.
pub(super) fn nice_step(range: f64, target: usize) -> f64 {
    let raw = range / target.max(1) as f64;
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    // Tolerance: 1.2 / 6 must give 0.2, not 0.5.
    let m = if f <= 1.0 + 1e-9 {
        1.0
    } else if f <= 2.0 + 1e-9 {
        2.0
    } else if f <= 5.0 + 1e-9 {
        5.0
    } else {
        10.0
    };
    m * mag
}

/// Multiples of `step` in [lo, hi] (with a little tolerance).
pub(super) fn ticks_in(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let eps = step * 1e-6;
    let first = (lo / step - 1e-6).ceil() as i64;
    let last = (hi / step + 1e-6).floor() as i64;
    if last < first || last - first > 1000 {
        return Vec::new();
    }
    (first..=last)
        .map(|k| k as f64 * step)
        .filter(|v| *v >= lo - eps && *v <= hi + eps)
        .collect()
}

/// A tick value, with as many decimals as `step` needs; exponent notation for
/// very large or very small steps ("2e6", "5e-7").
pub(super) fn fmt_tick(v: f64, step: f64) -> String {
    if v.abs() < step.abs() * 1e-6 || v == 0.0 {
        return "0".into();
    }
    let sl = step.abs().log10().floor();
    if step.abs() >= 1e5 || step.abs() < 1e-3 {
        let e = v.abs().log10().floor();
        let m = v / 10f64.powf(e);
        let d = ((e - sl).max(0.0) as usize).min(3);
        let mut ms = format!("{m:.d$}");
        if ms.contains('.') {
            ms = ms.trim_end_matches('0').trim_end_matches('.').to_string();
        }
        return format!("{ms}e{}", e as i64);
    }
    let d = (-sl).max(0.0) as usize;
    format!("{v:.d$}")
}

/// A value axis from `lo` to `hi`; when `log`, both are log10 of the values.
pub(super) struct Axis {
    /// Low end (value, or its log10).
    pub lo: f64,
    /// High end (value, or its log10).
    pub hi: f64,
    /// Logarithmic axis.
    pub log: bool,
}

impl Axis {
    /// Position of `v` along the axis, 0 at `lo`, 1 at `hi`.
    pub fn t(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.lo) / (self.hi - self.lo)
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }
    /// (value, label or "" for a minor tick).
    pub fn ticks(&self) -> Vec<(f64, String)> {
        if !self.log {
            let s = nice_step(self.hi - self.lo, 6);
            return ticks_in(self.lo, self.hi, s)
                .into_iter()
                .map(|t| (t, fmt_tick(t, s)))
                .collect();
        }
        let (a, b) = (self.lo.floor() as i32, self.hi.ceil() as i32);
        let decades = b - a;
        let mut out = Vec::new();
        for e in a..=b {
            for m in 1..10 {
                let v = f64::from(m) * 10f64.powi(e);
                let lv = v.log10();
                if lv < self.lo - 1e-9 || lv > self.hi + 1e-9 {
                    continue;
                }
                // Enough labels on a short log axis: every mantissa within
                // about a decade, 1-2-5 over two, powers of ten beyond.
                let span = self.hi - self.lo;
                let labelled = m == 1 || (span <= 1.2 && m != 7 && m != 9) || (decades <= 2 && (m == 2 || m == 5));
                let text = if !labelled {
                    String::new()
                } else if (-3..5).contains(&e) {
                    fmt_tick(v, 10f64.powi(e.min(0)))
                } else {
                    format!("{m}e{e}")
                };
                out.push((v, text));
            }
        }
        out
    }
}

/// Degree-friendly tick step for an axis span.
pub(super) fn degree_step(span: f64, max_ticks: usize) -> f64 {
    for s in [1.0, 2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0, 180.0] {
        if span / s <= max_ticks as f64 {
            return s;
        }
    }
    nice_step(span, max_ticks)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_and_labels() {
        assert_eq!(nice_step(10.0, 5), 2.0);
        assert_eq!(nice_step(1e6, 4), 5e5);
        assert_eq!(nice_step(1.2, 6), 0.2);
        assert_eq!(fmt_tick(2e6, 5e5), "2e6");
        assert_eq!(fmt_tick(1.5e6, 5e5), "1.5e6");
        assert_eq!(fmt_tick(0.25, 0.05), "0.25");
        assert_eq!(fmt_tick(400.0, 100.0), "400");
        assert_eq!(fmt_tick(4e-7, 2e-7), "4e-7");
        assert_eq!(fmt_tick(0.0, 2e-7), "0");
        assert_eq!(ticks_in(0.0, 1.0, 0.25), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    }
}
