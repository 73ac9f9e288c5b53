//! Estimates with their uncertainty (thesis §3.3.2, appendix C; DESIGN.md §1).
//!
//! A mean of N independent samples X_i has the standard error
//! `sqrt((mean(X²) − mean(X)²)/N)`; with equal photon powers this is the thesis'
//! binomial formula (eq. 3.4), and unlike it stays right after Russian roulette and
//! coloured surfaces. Photons are traced in stratified groups whose members are not
//! independent of one another; the groups are, and [`Estimate::from_groups`] takes the
//! same formula over them.

use crate::interval::Interval;

/// A noisy estimate of a mean: its value, standard error and sample count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The estimated mean (lux for illuminance).
    pub mean: f64,
    /// Standard error of `mean`; infinite when the samples cannot measure their spread.
    pub std_error: f64,
    /// Samples behind it: photons for the tracer's estimates.
    pub samples: u64,
}

impl Estimate {
    /// The estimate from the sums of `n` independent samples: Σx and Σx².
    pub fn from_sums(sum: f64, sum_sq: f64, n: u64) -> Estimate {
        if n == 0 {
            return Estimate {
                mean: 0.0,
                std_error: f64::INFINITY,
                samples: 0,
            };
        }
        let nf = n as f64;
        let mean = sum / nf;
        let var = (sum_sq / nf - mean * mean).max(0.0);
        Estimate {
            mean,
            std_error: (var / nf).sqrt(),
            samples: n,
        }
    }

    /// The estimate of a per-sample mean from `samples` samples taken in `groups`
    /// independent groups (stratified inside: photons in groups of 64): `sum` and
    /// `sum_sq` are Σ X_g and Σ X_g² over the group totals X_g. The mean is
    /// Σ X_g / samples; the standard error is that of the mean of G independent
    /// totals with the unbiased sample variance (G − 1 in the denominator), scaled to
    /// samples: sqrt(s²_g / G) · G / samples. A single group has no spread to measure:
    /// its standard error is infinite.
    pub fn from_groups(sum: f64, sum_sq: f64, groups: u64, samples: u64) -> Estimate {
        if groups < 2 || samples == 0 {
            return Estimate {
                mean: if samples > 0 {
                    sum / samples as f64
                } else {
                    0.0
                },
                std_error: f64::INFINITY,
                samples,
            };
        }
        let g = groups as f64;
        let per_group = Estimate::from_sums(sum, sum_sq, groups);
        let scale = g / samples as f64;
        Estimate {
            mean: per_group.mean * scale,
            std_error: per_group.std_error * (g / (g - 1.0)).sqrt() * scale,
            samples,
        }
    }

    /// The interval `mean ± z·σ` (see [`crate::Confidence::z`]).
    pub fn interval(&self, z: f64) -> Interval {
        let h = z * self.std_error;
        Interval {
            low: self.mean - h,
            high: self.mean + h,
        }
    }

    /// The estimate of `k` times the quantity (a unit change, a dimming level).
    pub fn scaled(&self, k: f64) -> Estimate {
        Estimate {
            mean: self.mean * k,
            std_error: self.std_error * k.abs(),
            samples: self.samples,
        }
    }
}

/// The standard normal quantile Φ⁻¹(p) for p in (0, 1), by P. J. Acklam's rational
/// approximation ("An algorithm for computing the inverse normal cumulative
/// distribution function", 2003: a central rational function for
/// 0.02425 ≤ p ≤ 0.97575 and one in sqrt(−2 ln p) for the tails), whose relative error
/// is below 1.15e-9 everywhere — far below any Monte Carlo noise. Acklam suggests one
/// Halley step against an exact Φ to reach machine precision; with the approximate
/// erfc at hand it made the result worse (8.6e-9 at p = 0.95, 2.8e-6 at 0.51), so there
/// is none.
pub fn normal_quantile(p: f64) -> f64 {
    assert!(p > 0.0 && p < 1.0, "probability {p} outside (0, 1)");
    const A: [f64; 6] = [
        -3.969683028665376e+01,
        2.209460984245205e+02,
        -2.759285104469687e+02,
        1.383_577_518_672_69e2,
        -3.066479806614716e+01,
        2.506628277459239e+00,
    ];
    const B: [f64; 5] = [
        -5.447609879822406e+01,
        1.615858368580409e+02,
        -1.556989798598866e+02,
        6.680131188771972e+01,
        -1.328068155288572e+01,
    ];
    const C: [f64; 6] = [
        -7.784894002430293e-03,
        -3.223964580411365e-01,
        -2.400758277161838e+00,
        -2.549732539343734e+00,
        4.374664141464968e+00,
        2.938163982698783e+00,
    ];
    const D: [f64; 4] = [
        7.784695709041462e-03,
        3.224671290700398e-01,
        2.445134137142996e+00,
        3.754408661907416e+00,
    ];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Φ⁻¹ against values tabulated to 16 digits (Python's `statistics.NormalDist
    /// ().inv_cdf`, Wichura's algorithm AS 241, accurate to about 1e-16), to 1e-8
    /// relative, in the central region and both tails.
    #[test]
    fn quantiles_match_tabulated_values() {
        let table = [
            (0.5, 0.0),
            (0.51, 0.025_068_908_258_711_057),
            (0.9, 1.281_551_565_544_600_8),
            (0.95, 1.644_853_626_951_471_5),
            (0.975, 1.959_963_984_540_053_6),
            (0.995, 2.575_829_303_548_9),
            (0.02, -2.053_748_910_631_822_5),
            (0.001, -3.090_232_306_167_813),
            (1e-6, -4.753_424_308_822_899),
            (0.999_999, 4.753_424_308_817_089),
        ];
        for (p, z) in table {
            let q = normal_quantile(p);
            let err = if z == 0.0 {
                q.abs()
            } else {
                (q / z - 1.0).abs()
            };
            assert!(err < 1e-8, "Φ⁻¹({p}) = {q}, tabulated {z}: {err:e}");
        }
    }

    #[test]
    fn groups_give_the_per_sample_mean_and_an_unbiased_spread() {
        // Two groups of 64 photons with totals 1 and 3: per-photon mean 4/128; sample
        // variance of the totals (G − 1 = 1 in the denominator) 2, so the error of the
        // mean total is sqrt(2/2) = 1, and per photon 1/64.
        let e = Estimate::from_groups(4.0, 10.0, 2, 128);
        assert_eq!(e.mean, 4.0 / 128.0);
        assert!((e.std_error - 1.0 / 64.0).abs() < 1e-12, "{}", e.std_error);
        assert_eq!(e.samples, 128);
        // One group has no spread to measure.
        assert!(
            Estimate::from_groups(4.0, 16.0, 1, 64)
                .std_error
                .is_infinite()
        );
    }

    #[test]
    fn sums_give_sample_mean_and_error() {
        // Samples 1, 2, 3, 4: mean 2.5, population variance 1.25, σ = sqrt(1.25/4).
        let e = Estimate::from_sums(10.0, 30.0, 4);
        assert_eq!(e.mean, 2.5);
        assert!((e.std_error - (1.25f64 / 4.0).sqrt()).abs() < 1e-12);
        assert!(Estimate::from_sums(0.0, 0.0, 0).std_error.is_infinite());
    }
}
