//! Confidence intervals and the statistical order of noisy estimates (thesis §3.3.3,
//! eq. 3.7).

use crate::estimate::{Estimate, normal_quantile};
use std::fmt;

/// A confidence level 1 − α in (0, 1), checked once where it enters (a flag, a problem
/// file), so that every interval and comparison downstream can trust it.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct Confidence(f64);

/// A confidence level outside (0, 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConfidenceError(pub f64);

impl fmt::Display for ConfidenceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the confidence {} must lie strictly between 0 and 1 (e.g. 0.95)",
            self.0
        )
    }
}

impl std::error::Error for ConfidenceError {}

impl Confidence {
    /// 95 %, the thesis' level.
    pub const DEFAULT: Confidence = Confidence(0.95);

    /// The level `c`, or an error unless 0 < c < 1.
    pub fn new(c: f64) -> Result<Confidence, ConfidenceError> {
        if c > 0.0 && c < 1.0 {
            Ok(Confidence(c))
        } else {
            Err(ConfidenceError(c))
        }
    }

    /// The level as a fraction.
    pub fn level(self) -> f64 {
        self.0
    }

    /// The z of two-sided intervals: a standard normal lies in [−z, z] with this
    /// probability.
    pub fn z(self) -> f64 {
        normal_quantile(0.5 + 0.5 * self.0)
    }

    /// The z of one-sided bounds: a standard normal lies below z with this probability
    /// (a constraint "at least 500 lx" holds at 95 % when mean − z·σ ≥ 500).
    pub fn z_one_sided(self) -> f64 {
        normal_quantile(self.0)
    }
}

/// A `--confidence` value that is not a level: not a number, or one outside (0, 1).
#[derive(Debug, Clone, PartialEq)]
pub enum ConfidenceParseError {
    /// The text, which does not read as a number.
    NotANumber(String),
    /// A number, but not a level.
    OutOfRange(ConfidenceError),
}

impl fmt::Display for ConfidenceParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConfidenceParseError::NotANumber(text) => write!(f, "'{text}' is not a number"),
            ConfidenceParseError::OutOfRange(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for ConfidenceParseError {}

/// A level as a flag gives it, `0.95`: the value of `--confidence`.
impl std::str::FromStr for Confidence {
    type Err = ConfidenceParseError;

    fn from_str(s: &str) -> Result<Confidence, ConfidenceParseError> {
        let c: f64 = s
            .parse()
            .map_err(|_| ConfidenceParseError::NotANumber(s.to_string()))?;
        Confidence::new(c).map_err(ConfidenceParseError::OutOfRange)
    }
}

impl Default for Confidence {
    fn default() -> Self {
        Confidence::DEFAULT
    }
}

/// A closed interval [low, high] with low ≤ high.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Lower end.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

impl Interval {
    /// The common part of two intervals, or `None` when they are disjoint: never an
    /// inverted interval standing for an empty one.
    pub fn intersect(&self, other: &Interval) -> Option<Interval> {
        let low = self.low.max(other.low);
        let high = self.high.min(other.high);
        (low <= high).then_some(Interval { low, high })
    }

    /// Whether this interval lies entirely below `other`.
    pub fn below(&self, other: &Interval) -> bool {
        self.high < other.low
    }

    /// Whether `x` lies in the interval.
    pub fn contains(&self, x: f64) -> bool {
        self.low <= x && x <= self.high
    }
}

/// The outcome of comparing x with y at confidence 1 − α.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    /// x >₁₋α y.
    Better,
    /// x <₁₋α y.
    Worse,
    /// x =₁₋α y: the samples cannot tell them apart.
    Indistinguishable,
}

/// Eq. 3.7: x and y differ when |μx − μy| > z·sqrt(σx² + σy²), and then the larger mean
/// is the better (we maximise).
///
/// The thesis derives the variance of the difference assuming independent estimates.
/// invlight traces every configuration with the same photon seed (common random
/// numbers, DESIGN.md §2), which correlates them positively, so the true variance of
/// the difference is smaller than σx² + σy² and the test errs on the side of
/// "indistinguishable": it keeps more members in the ISOC, never drops a good one.
pub fn compare(x: &Estimate, y: &Estimate, z: f64) -> Comparison {
    let d = x.mean - y.mean;
    if d.abs() > z * (x.std_error.powi(2) + y.std_error.powi(2)).sqrt() {
        if d > 0.0 {
            Comparison::Better
        } else {
            Comparison::Worse
        }
    } else {
        Comparison::Indistinguishable
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn est(mean: f64, std_error: f64) -> Estimate {
        Estimate {
            mean,
            std_error,
            samples: 100,
        }
    }

    #[test]
    fn eq_3_7_threshold() {
        // sqrt(3² + 4²) = 5: with z = 2 the threshold is 10.
        assert_eq!(
            compare(&est(10.1, 3.0), &est(0.0, 4.0), 2.0),
            Comparison::Better
        );
        assert_eq!(
            compare(&est(0.0, 3.0), &est(10.1, 4.0), 2.0),
            Comparison::Worse
        );
        assert_eq!(
            compare(&est(9.9, 3.0), &est(0.0, 4.0), 2.0),
            Comparison::Indistinguishable
        );
    }

    #[test]
    fn intervals_intersect_or_not() {
        let a = Interval {
            low: 0.0,
            high: 2.0,
        };
        let b = Interval {
            low: 1.0,
            high: 3.0,
        };
        assert_eq!(
            a.intersect(&b),
            Some(Interval {
                low: 1.0,
                high: 2.0
            })
        );
        let c = Interval {
            low: 2.5,
            high: 3.0,
        };
        assert_eq!(a.intersect(&c), None);
        assert!(a.below(&c) && !c.below(&a));
        assert_eq!(
            est(1.0, 0.5).interval(2.0),
            Interval {
                low: 0.0,
                high: 2.0
            }
        );
    }

    #[test]
    fn confidence_is_checked_once() {
        assert!(Confidence::new(0.0).is_err());
        assert!(Confidence::new(1.0).is_err());
        assert!(Confidence::new(f64::NAN).is_err());
        let c = Confidence::new(0.95).unwrap();
        assert!((c.z() - 1.959_963_984_540_053_6).abs() < 1e-8);
        assert!((c.z_one_sided() - 1.644_853_626_951_471_5).abs() < 1e-8);
        assert_eq!(Confidence::default(), c);
    }

    #[test]
    fn confidence_flags_are_read_with_their_messages() {
        assert_eq!(
            "0.9".parse::<Confidence>().unwrap(),
            Confidence::new(0.9).unwrap()
        );
        assert_eq!(
            "high".parse::<Confidence>().unwrap_err().to_string(),
            "'high' is not a number"
        );
        assert_eq!(
            "1.5".parse::<Confidence>().unwrap_err().to_string(),
            "the confidence 1.5 must lie strictly between 0 and 1 (e.g. 0.95)"
        );
    }
}
