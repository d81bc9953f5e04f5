//! Numbers as text for tables and messages: [`significant()`], used by the
//! readers' warnings (`formats`) and every report. (Readers' error messages
//! use [`crate::error::sig`], which drops trailing zeros.)

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

#[cfg(test)]
mod tests {
    use super::significant;

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
}
