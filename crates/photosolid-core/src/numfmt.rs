//! Numbers as text, in one place: [`significant()`] for tables and reports
//! (one precision per column, trailing zeros kept), [`trimmed()`] for
//! messages about computed values (trailing zeros dropped: `3153`,
//! `0.316992`, `1.5e-7`), [`write_shortest()`] for a value as it was read
//! (`crate::error::Num` in error and warning messages), and
//! [`push_fixed_trimmed()`], the allocation-free core the writers append
//! with (fixed notation only, as the file formats require); [`PctOfPeak`],
//! a quantity relative to I_max as every flag and Python argument spells it
//! (`0.1%`), parsed in one place.
//!
//! The lowest layer: it depends on nothing, so the errors (`crate::error`),
//! the readers' warnings, the writers and the reports all share it.

use std::fmt::Write as _;

/// `x` with `digits` significant digits: fixed notation for 1e-3 <= |x| < 1e6
/// (trailing zeros kept, so a column of numbers has one precision), scientific
/// otherwise; "0" for zero and "n/a" for NaN or infinity (never printed as such).
/// For tables and messages about computed values (a difference of two
/// measured values carries arithmetic noise in its last digits).
pub fn significant(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return "n/a".into();
    }
    // Round first: 9.99995 at 4 digits is 10.00, one more integer digit.
    let rounded: f64 = format!("{x:.*e}", digits - 1).parse().unwrap_or(x);
    let mag = rounded.abs().log10().floor() as i32;
    if (-3..6).contains(&mag) {
        let decimals = (digits as i32 - 1 - mag).max(0) as usize;
        format!("{rounded:.decimals$}")
    } else {
        format!("{x:.*e}", digits - 1)
    }
}

/// `x` with `n` significant digits as a reader expects it: plain decimals
/// without trailing zeros from 1e-4 to below 1e9 (`3153`, `0.316992`,
/// `-12.5`), scientific outside (`1.5e-7`); `NaN` and `inf` as such.
pub fn trimmed(x: f64, n: usize) -> String {
    let n = n.max(1);
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return x.to_string();
    }
    let a = x.abs();
    if !(1e-4..1e9).contains(&a) {
        let s = format!("{:.*e}", n - 1, x);
        // 1.500e-7 -> 1.5e-7
        return match s.split_once('e') {
            Some((m, e)) if m.contains('.') => format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.')),
            _ => s,
        };
    }
    let decimals = (n as i32 - 1 - a.log10().floor() as i32).max(0) as usize;
    let mut s = String::new();
    push_fixed_trimmed(&mut s, x, decimals);
    s
}

/// Write `x` as the shortest text that reads back to the same `f64`, in
/// scientific notation below 1e-4 and from 1e16 on in magnitude (`1e-200`,
/// not two hundred digits); `0`, `NaN` and `inf` as such.
pub fn write_shortest(out: &mut dyn std::fmt::Write, x: f64) -> std::fmt::Result {
    if x == 0.0 || !x.is_finite() || (1e-4..1e16).contains(&x.abs()) {
        write!(out, "{x}")
    } else {
        write!(out, "{x:e}")
    }
}

/// Append `v` in fixed notation with at most `decimals` decimals, trailing
/// zeros (and a bare point) trimmed, never `-0`. No allocation beyond `out`
/// (the LDT writer appends every value of a file with it).
pub fn push_fixed_trimmed(out: &mut String, v: f64, decimals: usize) {
    let start = out.len();
    let _ = write!(out, "{v:.decimals$}");
    if out[start..].contains('.') {
        let trimmed = out.trim_end_matches('0').trim_end_matches('.').len();
        out.truncate(trimmed);
    }
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
    }
}

/// A quantity relative to I_max (a tolerance, a guard), as every flag
/// spells it: a percent with its sign, `0.1%`. Holds the percent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PctOfPeak(pub f64);

impl PctOfPeak {
    /// The value in percent of I_max (`0.1%` is 0.1).
    pub fn pct(self) -> f64 {
        self.0
    }
    /// The value as a fraction of I_max (`0.1%` is 0.001), as the library takes it.
    pub fn fraction(self) -> f64 {
        self.0 / 100.0
    }
}

impl std::fmt::Display for PctOfPeak {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}%", short(self.0))
    }
}

/// `x` with at most 10 decimals and no trailing zeros (`0.1`, not
/// `0.10000000000000002`; `5`, not `5.0`); scientific below 1e-10.
pub fn short(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-10 {
        return format!("{x:e}");
    }
    let mut s = String::new();
    push_fixed_trimmed(&mut s, x, 10);
    s
}

/// A percent that does not parse ([`PctOfPeak::parse`],
/// [`parse_percentage_points`]): the message says what was written and what
/// is expected, with the hint for a bare number. Its own type because this
/// layer is below `crate::error`; the CLI prints it as a usage error, the
/// Python binding raises it as a `ValueError` naming the argument.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PercentError(pub String);

impl std::fmt::Display for PercentError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for PercentError {}

impl PctOfPeak {
    /// A percent of I_max as the CLI's flags and the Python functions take
    /// it, with its sign (`0.1%`); `zero_allowed`: whether 0% is accepted.
    /// A bare number is refused with a hint naming both readings (`0.1` →
    /// "did you mean 0.1%? ... write 10%"); the message is the user's.
    ///
    /// # Errors
    /// The message, for a bare number, text that is not a number, or a
    /// percent below (or at, without `zero_allowed`) 0 or not finite.
    pub fn parse(s: &str, zero_allowed: bool) -> Result<PctOfPeak, PercentError> {
        let t = s.trim();
        let Some(body) = t.strip_suffix('%') else {
            return Err(PercentError(match t.parse::<f64>() {
                Ok(x) if x.is_finite() => format!(
                    "`{s}` has no unit: values relative to I_max are percents written with their sign; \
                     did you mean {}%? (If {} was meant as a fraction of I_max, write {}%.)",
                    short(x),
                    short(x),
                    short(100.0 * x)
                ),
                _ => format!("`{s}` is not a percent of I_max such as 0.1%"),
            }));
        };
        let x: f64 = body
            .trim()
            .parse()
            .map_err(|_| PercentError(format!("`{s}` is not a percent of I_max such as 0.1%")))?;
        if !x.is_finite() || x < 0.0 || (x == 0.0 && !zero_allowed) {
            return Err(PercentError(format!(
                "{s} must be a finite percent {} 0%",
                if zero_allowed { ">=" } else { ">" }
            )));
        }
        Ok(PctOfPeak(x))
    }
}

/// A percent >= 0 of a quantity other than I_max (`fit --tolerance 1%`: percentage
/// points of the fit's error), as the percent; a bare number is refused with a hint.
///
/// # Errors
/// The message, as [`PctOfPeak::parse`].
pub fn parse_percentage_points(s: &str) -> Result<f64, PercentError> {
    let t = s.trim();
    let Some(body) = t.strip_suffix('%') else {
        return Err(PercentError(match t.parse::<f64>() {
            Ok(x) if x.is_finite() => format!(
                "`{s}` has no unit: write a percent with its sign, such as {}% (or {}% if {} was meant as \
                 a fraction)",
                short(x),
                short(100.0 * x),
                short(x)
            ),
            _ => format!("`{s}` is not a percent such as 1%"),
        }));
    };
    match body.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(PercentError(format!("`{s}` is not a finite percent >= 0%"))),
    }
}

#[cfg(test)]
mod tests {
    use super::{push_fixed_trimmed, significant, trimmed, write_shortest};

    #[test]
    fn one_precision_for_every_magnitude() {
        let cases = [
            (0.75821, "0.7582"),
            (6.427, "6.427"),
            (5000.0, "5000"),
            (12345.6, "12350"),
            (9.99995, "10.00"),
            (-0.0012346, "-0.001235"),
            (0.00012346, "1.235e-4"),
            (1.5e7, "1.500e7"),
            (0.0, "0"),
            (f64::NAN, "n/a"),
        ];
        for (x, want) in cases {
            assert_eq!(significant(x, 4), want, "{x}");
        }
        assert_eq!(significant(0.5672226957349551, 6), "0.567223");
    }

    #[test]
    fn messages_drop_trailing_zeros() {
        assert_eq!(trimmed(3153.04, 4), "3153");
        assert_eq!(trimmed(-0.31699200000000005, 6), "-0.316992");
        assert_eq!(trimmed(1.5e-7, 4), "1.5e-7");
        assert_eq!(trimmed(2.0e9, 3), "2e9");
        assert_eq!(trimmed(-1e-9, 3), "-1e-9");
        assert_eq!(trimmed(12.5, 6), "12.5");
        assert_eq!(trimmed(-0.00001, 1), "-1e-5");
        assert_eq!(trimmed(f64::NAN, 3), "NaN");
        assert_eq!(trimmed(f64::NEG_INFINITY, 3), "-inf");
    }

    #[test]
    fn shortest_reads_back_the_same_value() {
        let f = |x: f64| {
            let mut s = String::new();
            write_shortest(&mut s, x).unwrap();
            s
        };
        assert_eq!(f(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(f(1e-200), "1e-200");
        assert_eq!(f(2.5e16), "2.5e16");
        assert_eq!(f(-12.5), "-12.5");
        assert_eq!(f(f64::NAN), "NaN");
        for x in [0.1 + 0.2, 1e-200, 2.5e16, 123456.789, -3e-5] {
            assert_eq!(f(x).parse::<f64>().unwrap(), x);
        }
    }

    #[test]
    fn fixed_values_append_without_negative_zero() {
        let f = |v: f64, d: usize| {
            let mut s = String::from("x=");
            push_fixed_trimmed(&mut s, v, d);
            s
        };
        assert_eq!(f(123.4000, 3), "x=123.4");
        assert_eq!(f(-0.0001, 2), "x=0");
        assert_eq!(f(5.0, 4), "x=5");
        assert_eq!(f(1200.0, 0), "x=1200");
    }
}
