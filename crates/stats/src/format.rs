//! Numbers as people read them in tables and messages: four significant digits, in
//! plain notation from a thousandth to ten million (lux values from a dim corridor to
//! the sun on snow) and in scientific notation outside.

/// `x` with four significant digits: `165.2`, `0.5022`, `78952`, `3.000e-4`, `0`.
pub fn significant(x: f64) -> String {
    let a = x.abs();
    if !x.is_finite() {
        format!("{x}")
    } else if a != 0.0 && !(1e-3..1e7).contains(&a) {
        format!("{x:.3e}")
    } else {
        let decimals = if a == 0.0 {
            0
        } else {
            (3 - a.log10().floor() as i32).max(0) as usize
        };
        format!("{x:.decimals$}")
    }
}

/// A long duration in words: "3.2 hours" below two days, "12 days" above.
pub fn hours_or_days(d: std::time::Duration) -> String {
    let h = d.as_secs_f64() / 3600.0;
    if h < 48.0 {
        format!("{h:.1} hours")
    } else {
        format!("{:.0} days", h / 24.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_durations_in_words() {
        use std::time::Duration;
        assert_eq!(hours_or_days(Duration::from_secs(11_520)), "3.2 hours");
        assert_eq!(hours_or_days(Duration::from_secs(12 * 86_400)), "12 days");
    }

    #[test]
    fn four_significant_digits() {
        assert_eq!(significant(165.23), "165.2");
        assert_eq!(significant(0.5022), "0.5022");
        assert_eq!(significant(0.0003), "3.000e-4");
        assert_eq!(significant(0.0), "0");
        assert_eq!(significant(78952.4), "78952");
        assert_eq!(significant(-2.5), "-2.500");
        assert_eq!(significant(3.2e7), "3.200e7");
    }
}
