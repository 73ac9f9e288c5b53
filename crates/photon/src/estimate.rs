//! Estimates with their uncertainty (thesis §3.3.2, appendix C; DESIGN.md §1).
//!
//! A surface's mean illuminance F_N is the mean of N per-photon contributions X_i (the
//! illuminance one photon brings, all its hits on the surface summed). For independent
//! photons its standard error is `sqrt((mean(X²) − mean(X)²)/N)`; with equal photon
//! powers this is the thesis' binomial formula (eq. 3.4), and unlike it stays right after
//! Russian roulette and coloured surfaces. Photons are traced in stratified groups
//! ([`crate::Sampler`]); the groups are the independent samples, and
//! [`Estimate::from_groups`] takes the same formula over them.

use crate::sampler::GROUP;

/// A noisy estimate of a mean: its value, standard error and sample count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The estimated mean (lux for illuminance).
    pub mean: f64,
    /// Standard error of `mean`.
    pub std_error: f64,
    /// Photons behind it (for the photon tracer's estimates; a sample count for others).
    pub photons: u64,
}

impl Estimate {
    /// The estimate from the sums of N samples: Σx and Σx².
    pub fn from_sums(sum: f64, sum_sq: f64, n: u64) -> Estimate {
        if n == 0 {
            return Estimate {
                mean: 0.0,
                std_error: f64::INFINITY,
                photons: 0,
            };
        }
        let nf = n as f64;
        let mean = sum / nf;
        let var = (sum_sq / nf - mean * mean).max(0.0);
        Estimate {
            mean,
            std_error: (var / nf).sqrt(),
            photons: n,
        }
    }

    /// The estimate of a per-photon mean from N photons traced in stratified groups of
    /// [`GROUP`] ([`crate::Sampler`]; N a whole number of groups, see
    /// [`crate::whole_groups`]): `sum` and `sum_sq` are Σ X_g and Σ X_g² over the G = N/GROUP
    /// group totals X_g. The mean is Σ X_g / N; the standard error is that of the mean of
    /// G independent totals, with the unbiased sample variance (G − 1 in the
    /// denominator), scaled to photons: sqrt(s²_g / G) · G / N. A single group has no
    /// spread to measure: its standard error is infinite.
    pub fn from_groups(sum: f64, sum_sq: f64, photons: u64) -> Estimate {
        let groups = photons.div_ceil(GROUP);
        if groups < 2 {
            return Estimate {
                mean: if photons > 0 {
                    sum / photons as f64
                } else {
                    0.0
                },
                std_error: f64::INFINITY,
                photons,
            };
        }
        let g = groups as f64;
        let per_group = Estimate::from_sums(sum, sum_sq, groups);
        let scale = g / photons as f64;
        Estimate {
            mean: per_group.mean * scale,
            std_error: per_group.std_error * (g / (g - 1.0)).sqrt() * scale,
            photons,
        }
    }

    /// The two-sided interval `mean ± z·σ` at `confidence` (e.g. 0.95).
    pub fn interval(&self, confidence: f64) -> (f64, f64) {
        let h = z_two_sided(confidence) * self.std_error;
        (self.mean - h, self.mean + h)
    }
}

/// The z such that a standard normal lies in [−z, z] with probability `confidence`.
pub fn z_two_sided(confidence: f64) -> f64 {
    normal_quantile(0.5 + 0.5 * confidence)
}

/// Inverse of the standard normal CDF (P. J. Acklam's rational approximation, relative
/// error below 1.2e-9 after one Halley step, which is far below any Monte Carlo noise).
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
    let x = if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    };
    // One Halley refinement against the CDF written with erfc.
    let e = 0.5 * erfc(-x / std::f64::consts::SQRT_2) - p;
    let u = e * (2.0 * std::f64::consts::PI).sqrt() * (x * x / 2.0).exp();
    x - u / (1.0 + x * u / 2.0)
}

/// Complementary error function (W. J. Cody's rational Chebyshev approximation as given
/// in Numerical Recipes 3rd ed. §6.2.2, `erfccheb`-free form; relative error < 1.2e-7),
/// used only to polish the quantile above.
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let r = t
        * (-z * z - 1.26551223
            + t * (1.00002368
                + t * (0.37409196
                    + t * (0.09678418
                        + t * (-0.18628806
                            + t * (0.27886807
                                + t * (-1.13520398
                                    + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))))
            .exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_quantiles() {
        assert!((z_two_sided(0.95) - 1.959964).abs() < 1e-5);
        assert!((z_two_sided(0.99) - 2.575829).abs() < 1e-5);
        assert!((normal_quantile(0.5)).abs() < 1e-7);
        assert!((normal_quantile(0.001) + 3.090232).abs() < 1e-5);
    }

    #[test]
    fn groups_give_the_per_photon_mean_and_an_unbiased_spread() {
        // Two groups of 64 photons with totals 1 and 3: per-photon mean 4/128; sample
        // variance of the totals (G − 1 = 1 in the denominator) 2, so the error of the
        // mean total is sqrt(2/2) = 1, and per photon 1/64.
        let e = Estimate::from_groups(4.0, 10.0, 2 * GROUP);
        assert_eq!(e.mean, 4.0 / 128.0);
        assert!((e.std_error - 1.0 / 64.0).abs() < 1e-12, "{}", e.std_error);
        assert_eq!(e.photons, 128);
        // One group has no spread to measure.
        assert!(
            Estimate::from_groups(4.0, 16.0, GROUP)
                .std_error
                .is_infinite()
        );
        // Measurements trace whole groups, at least MIN_GROUPS of them.
        assert_eq!(crate::whole_groups(1), crate::MIN_GROUPS * GROUP);
        assert_eq!(crate::whole_groups(100_001), 100_032);
        assert_eq!(crate::whole_groups(2_000_000), 2_000_000);
    }

    #[test]
    fn sums_give_sample_mean_and_error() {
        // Samples 1, 2, 3, 4: mean 2.5, population variance 1.25, σ = sqrt(1.25/4).
        let e = Estimate::from_sums(10.0, 30.0, 4);
        assert_eq!(e.mean, 2.5);
        assert!((e.std_error - (1.25f64 / 4.0).sqrt()).abs() < 1e-12);
    }
}
