//! Paired comparisons of two estimates traced with common random numbers (DESIGN.md
//! §2).
//!
//! Eq. 3.7 of the thesis compares x and y as if independent: var(x̄ − ȳ) = σx² + σy².
//! Every configuration is traced with the same photon seeds, group by group, so group g
//! of x and group g of y share their random numbers and their errors are positively
//! correlated. The groups are the independent samples (stratified inside, DESIGN.md
//! §1), so the differences d_g = X_g − Y_g over the common groups are i.i.d. with mean
//! μx − μy, and their sample mean and standard error give the difference's estimate
//! directly (the paired t statistic; with common random numbers this is the method of
//! Law & Kelton, *Simulation Modeling and Analysis*, §11.2 on CRN). The covariance
//! narrows the test instead of being ignored.

use crate::estimate::Estimate;
use crate::interval::Comparison;

/// The estimate of μx − μy from the per-group means of x and y (each group's total over
/// its sample count, so their mean is the estimate's mean) over the groups both have —
/// the first `min(len)`: a fast estimate's groups are the first of the full one's, and
/// group g of every configuration uses the same seeds. `None` with fewer than two
/// common groups (no spread to measure). `samples` of the result counts groups.
pub fn paired_difference(x: &[f64], y: &[f64]) -> Option<Estimate> {
    let g = x.len().min(y.len());
    if g < 2 {
        return None;
    }
    let (mut sum, mut sum_sq) = (0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        let d = a - b;
        sum += d;
        sum_sq += d * d;
    }
    let gf = g as f64;
    let e = Estimate::from_sums(sum, sum_sq, g as u64);
    Some(Estimate {
        std_error: e.std_error * (gf / (gf - 1.0)).sqrt(),
        ..e
    })
}

/// x against y by their paired differences at the level of the normal quantile `z`: x
/// is better when the mean difference exceeds t times its standard error, worse when
/// below −t times it, t the Student quantile of G − 1 degrees of freedom at z's level
/// ([`student_quantile`]: the standard error is estimated from the G groups, and with
/// few of them z alone would decide too often). `None` when they share fewer than two
/// groups (the caller falls back to eq. 3.7).
pub fn compare_paired(x: &[f64], y: &[f64], z: f64) -> Option<Comparison> {
    let d = paired_difference(x, y)?;
    let t = student_quantile(z, d.samples - 1);
    Some(if d.mean > t * d.std_error {
        Comparison::Better
    } else if d.mean < -t * d.std_error {
        Comparison::Worse
    } else {
        Comparison::Indistinguishable
    })
}

/// The quantile of Student's t with `df` degrees of freedom at the level of the
/// standard normal quantile `z`, by the Cornish–Fisher expansion of Abramowitz &
/// Stegun 26.7.5 (four terms in 1/df). Against tables its error at the levels used here
/// (z ≤ 3.1) is below 0.5 % from df = 10 (2.2281 against 2.2281 for z = 1.96), and
/// photon estimates have at least 32 groups.
pub fn student_quantile(z: f64, df: u64) -> f64 {
    let v = df.max(1) as f64;
    let z2 = z * z;
    let g1 = (z2 + 1.0) * z / 4.0;
    let g2 = ((5.0 * z2 + 16.0) * z2 + 3.0) * z / 96.0;
    let g3 = (((3.0 * z2 + 19.0) * z2 + 17.0) * z2 - 15.0) * z / 384.0;
    let g4 = ((((79.0 * z2 + 776.0) * z2 + 1482.0) * z2 - 1920.0) * z2 - 945.0) * z / 92160.0;
    z + g1 / v + g2 / (v * v) + g3 / (v * v * v) + g4 / (v * v * v * v)
}

/// var(x̄ − ȳ) / (var x̄ + var ȳ) over the common groups: 1 for independent estimates,
/// near 0 when common random numbers make their errors move together. What the paired
/// test gains over eq. 3.7: its threshold is the square root of this times eq. 3.7's.
/// `None` with fewer than two common groups or no spread in either.
pub fn variance_ratio(x: &[f64], y: &[f64]) -> Option<f64> {
    let g = x.len().min(y.len());
    let d = paired_difference(x, y)?;
    let var = |s: &[f64]| {
        let e = Estimate::from_sums(s.iter().sum(), s.iter().map(|v| v * v).sum(), g as u64);
        e.std_error * e.std_error
    };
    let (vx, vy) = (var(&x[..g]), var(&y[..g]));
    let gf = g as f64;
    let vd = d.std_error * d.std_error * (gf - 1.0) / gf;
    (vx + vy > 0.0).then(|| vd / (vx + vy))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interval::compare;
    use crate::rng::SplitMix64;

    /// A standard normal by Box–Muller from the stream.
    fn normal(rng: &mut SplitMix64) -> f64 {
        let u = rng.next_f64().max(f64::MIN_POSITIVE);
        let v = rng.next_f64();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }

    /// Per-group means of two configurations whose true means differ by `delta`, with
    /// a shared per-group noise of σ `shared` (the common photon streams) and an
    /// independent one of σ `own`.
    fn pair(seed: u64, groups: usize, delta: f64, shared: f64, own: f64) -> (Vec<f64>, Vec<f64>) {
        let mut rng = SplitMix64::new(seed);
        let mut x = Vec::with_capacity(groups);
        let mut y = Vec::with_capacity(groups);
        for _ in 0..groups {
            let s = shared * normal(&mut rng);
            x.push(10.0 + delta + s + own * normal(&mut rng));
            y.push(10.0 + s + own * normal(&mut rng));
        }
        (x, y)
    }

    fn estimate(x: &[f64]) -> Estimate {
        let g = x.len() as u64;
        Estimate::from_groups(x.iter().sum(), x.iter().map(|v| v * v).sum(), g, g)
    }

    /// With shared noise σ_s = 1 and own noise σ_o = 0.1 over G = 100 groups, a true
    /// difference δ = 0.1 is 0.1/(0.1·√2/√100) ≈ 7.1 paired standard errors away from 0
    /// but only 0.1/(√(2·1.01)/√100) ≈ 0.70 independent ones: at z = 1.96 the paired test
    /// must decide (it fails only when the noise of d̄ exceeds 5.1 σ, p < 1e-6) and eq.
    /// 3.7 must not (it errs when |N(0.70, 1)| > 1.96, p ≈ 0.10) — over 200 seeds the
    /// paired test decides in all, eq. 3.7 in at most 40 (the binomial count's mean 20
    /// plus 4.5 of its σ ≈ 4.3).
    #[test]
    fn correlated_noise_is_decided_by_pairs_not_by_eq_3_7() {
        let (mut paired, mut independent) = (0, 0);
        for seed in 0..200 {
            let (x, y) = pair(seed, 100, 0.1, 1.0, 0.1);
            if compare_paired(&x, &y, 1.96) == Some(Comparison::Better) {
                paired += 1;
            }
            if compare(&estimate(&x), &estimate(&y), 1.96) == Comparison::Better {
                independent += 1;
            }
        }
        assert_eq!(paired, 200);
        assert!(independent <= 40, "eq. 3.7 decided {independent} of 200");
    }

    /// With equal means the paired test's false decisions stay at α: over 2 000 seeds
    /// at z = 1.96 (α = 5 %, the t quantile of 99 degrees of freedom used) the count of
    /// "better or worse" has mean 100 and σ ≈ 9.7: it lies within 4.5 σ.
    #[test]
    fn equal_means_are_told_apart_at_rate_alpha() {
        let wrong = (0..2000)
            .filter(|&seed| {
                let (x, y) = pair(seed + 10_000, 100, 0.0, 1.0, 0.1);
                compare_paired(&x, &y, 1.96) != Some(Comparison::Indistinguishable)
            })
            .count() as f64;
        assert!((wrong - 100.0).abs() < 4.5 * 9.7, "{wrong} of 2000");
    }

    /// The ratio var(x̄ − ȳ)/(var x̄ + var ȳ) of the model above is 2σ_o²/(2(σ_s² + σ_o²))
    /// = 0.01/1.01 ≈ 0.0099; from 10 000 groups it is within 10 % of that (the sample
    /// variances' relative error is √(2/G) ≈ 1.4 %).
    #[test]
    fn the_variance_ratio_is_that_of_the_model() {
        let (x, y) = pair(7, 10_000, 0.3, 1.0, 0.1);
        let r = variance_ratio(&x, &y).unwrap();
        assert!((r / (0.01 / 1.01) - 1.0).abs() < 0.1, "{r}");
        let (x, y) = pair(8, 10_000, 0.3, 0.0, 1.0);
        let r = variance_ratio(&x, &y).unwrap();
        assert!((r - 1.0).abs() < 0.1, "independent: {r}");
    }

    /// Student quantiles against tables (two-sided 95 %, z = 1.959964): 2.2281 at 10
    /// degrees of freedom, 2.0639 at 24, 1.9842 at 99; and 99.5 % one-sided (z =
    /// 2.575829) 2.7969 at 24.
    #[test]
    fn student_quantiles_match_tables() {
        for (z, df, t) in [
            (1.959964, 10, 2.2281),
            (1.959964, 24, 2.0639),
            (1.959964, 99, 1.9842),
            (2.575829, 24, 2.7969),
        ] {
            let q = student_quantile(z, df);
            assert!((q / t - 1.0).abs() < 0.005, "t({z}, {df}) = {q}, table {t}");
        }
    }

    /// Only the common groups pair; fewer than two say nothing.
    #[test]
    fn pairs_are_the_common_prefix() {
        let d = paired_difference(&[1.0, 2.0, 3.0], &[0.0, 1.0]).unwrap();
        assert_eq!(d.mean, 1.0);
        assert_eq!(d.std_error, 0.0);
        assert_eq!(d.samples, 2);
        assert!(paired_difference(&[1.0], &[0.0, 1.0]).is_none());
        assert!(compare_paired(&[], &[], 2.0).is_none());
    }
}
