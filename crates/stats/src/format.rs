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

/// `x` as [`significant`] prints it, with as many more decimals (up to six) as it takes
/// to read different from `limit` when it is: a one-sided bound of 500.03 lx beside a
/// limit of 500 lx reads `500.03`, not `500.0`, so the reader sees which side it is on.
pub fn significant_beside(x: f64, limit: f64) -> String {
    let plain = significant(x);
    if x == limit || !x.is_finite() || plain.contains('e') || plain != significant(limit) {
        return plain;
    }
    let decimals = plain.split_once('.').map_or(0, |(_, d)| d.len());
    (decimals + 1..=decimals + 6)
        .map(|d| (format!("{x:.d$}"), format!("{limit:.d$}")))
        .find(|(a, b)| a != b)
        .map_or(plain, |(a, _)| a)
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
    fn a_bound_beside_its_limit_shows_the_side_it_is_on() {
        assert_eq!(significant_beside(500.03, 500.0), "500.03");
        assert_eq!(significant_beside(499.996, 500.0), "499.996");
        assert_eq!(significant_beside(0.60004, 0.6), "0.60004");
        assert_eq!(significant_beside(0.60049, 0.6), "0.6005");
        assert_eq!(significant_beside(512.3, 500.0), "512.3");
        assert_eq!(significant_beside(500.0, 500.0), "500.0");
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
