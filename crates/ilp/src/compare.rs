//! Comparing noisy estimates (thesis §3.3.3): confidence intervals and the statistical
//! order of eq. 3.7.

use invlight_photon::Estimate;

/// A closed interval [low, high] with low ≤ high.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Lower end.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

impl Interval {
    /// The confidence interval `mean ± z·σ` of an estimate.
    pub fn of(e: &Estimate, z: f64) -> Interval {
        let h = z * e.std_error;
        Interval {
            low: e.mean - h,
            high: e.mean + h,
        }
    }

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
}

/// The outcome of comparing x with y at confidence 1 − α.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    /// x >₁₋α y.
    Better,
    /// x <₁₋α y.
    Worse,
    /// x =₁₋α y: the sample cannot tell them apart.
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
            photons: 100,
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
            Interval::of(&est(1.0, 0.5), 2.0),
            Interval {
                low: 0.0,
                high: 2.0
            }
        );
    }
}
