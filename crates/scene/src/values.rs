//! Numbers as a command line gives them, checked where they enter so that nothing
//! downstream meets a zero scale or an infinite radius.

use std::fmt;

/// A flag's value that is not the number the flag takes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NumberError {
    /// The text, which is not a positive finite number.
    NotPositive(String),
    /// The text, which is not a finite number.
    NotFinite(String),
}

impl fmt::Display for NumberError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumberError::NotPositive(text) => write!(f, "'{text}' is not a positive number"),
            NumberError::NotFinite(text) => write!(f, "'{text}' is not a finite number"),
        }
    }
}

impl std::error::Error for NumberError {}

/// A positive finite number, as a flag's value parser (`--scale`, `--em`, …).
pub fn positive<T: std::str::FromStr + PartialOrd + Default + Copy + Into<f64>>(
    s: &str,
) -> Result<T, NumberError> {
    match s.parse::<T>() {
        Ok(x) if x > T::default() && x.into().is_finite() => Ok(x),
        _ => Err(NumberError::NotPositive(s.to_string())),
    }
}

/// A finite number, as a flag's value parser.
pub fn finite(s: &str) -> Result<f32, NumberError> {
    match s.parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(NumberError::NotFinite(s.to_string())),
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
                positive::<f64>(bad).unwrap_err().to_string(),
                format!("'{bad}' is not a positive number")
            );
        }
        assert_eq!(finite("-2"), Ok(-2.0));
        assert_eq!(
            finite("inf").unwrap_err().to_string(),
            "'inf' is not a finite number"
        );
    }
}
