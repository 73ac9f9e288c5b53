//! Numbers as a command line gives them, checked where they enter so that nothing
//! downstream meets a zero scale or an infinite radius.

/// A positive finite number, as a flag's value parser (`--scale`, `--em`, …).
pub fn positive<T: std::str::FromStr + PartialOrd + Default + Copy + Into<f64>>(
    s: &str,
) -> Result<T, String> {
    match s.parse::<T>() {
        Ok(x) if x > T::default() && x.into().is_finite() => Ok(x),
        _ => Err(format!("'{s}' is not a positive number")),
    }
}

/// A finite number, as a flag's value parser.
pub fn finite(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{s}' is not a finite number")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_outside_their_range_are_refused_by_name() {
        assert_eq!(positive::<f32>("0.5"), Ok(0.5));
        for bad in ["0", "-1", "inf", "NaN", "x"] {
            assert_eq!(
                positive::<f64>(bad),
                Err(format!("'{bad}' is not a positive number"))
            );
        }
        assert_eq!(finite("-2"), Ok(-2.0));
        assert!(finite("inf").is_err());
    }
}
