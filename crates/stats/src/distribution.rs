//! Discrete distributions sampled by inversion (pbrt-v4 `PiecewiseConstant1D`'s
//! discrete half): which light a photon leaves, which triangle of a target a
//! connection aims at, which area light a shadow ray samples.

/// A distribution over 0..n proportional to non-negative weights, kept as its
/// cumulative sums so that a draw is a binary search: O(log n) for the thousands of
/// emitting triangles of a real scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Distribution1D {
    /// Σ of the weights up to and including each entry.
    cdf: Vec<f64>,
}

impl Distribution1D {
    /// The distribution of `weights` (each ≥ 0; negative or NaN weights count as 0).
    pub fn new(weights: impl IntoIterator<Item = f64>) -> Distribution1D {
        let mut acc = 0.0f64;
        let cdf = weights
            .into_iter()
            .map(|w| {
                if w > 0.0 {
                    acc += w;
                }
                acc
            })
            .collect();
        Distribution1D { cdf }
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.cdf.len()
    }

    /// Whether there are no entries.
    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty()
    }

    /// Σ of the weights.
    pub fn total(&self) -> f64 {
        self.cdf.last().copied().unwrap_or(0.0)
    }

    /// The weight of entry `i`.
    pub fn weight(&self, i: usize) -> f64 {
        let below = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        self.cdf[i] - below
    }

    /// The probability of entry `i`.
    pub fn pmf(&self, i: usize) -> f64 {
        self.weight(i) / self.total()
    }

    /// The entry whose cumulative interval holds `u·total` for a uniform u in [0, 1):
    /// entries of zero weight are never drawn. Must not be called when the total is 0.
    #[inline]
    pub fn sample(&self, u: f32) -> usize {
        self.sample_continuous(u as f64).0
    }

    /// The entry [`Distribution1D::sample`] draws for `u`, with where `u·total` falls
    /// inside that entry's interval, rescaled to [0, 1): a uniform number independent
    /// of the entry, so one uniform chooses an entry and a position in it (pbrt-v4
    /// `PiecewiseConstant1D::Sample`'s offset `du`). Must not be called when the total
    /// is 0.
    #[inline]
    pub fn sample_continuous(&self, u: f64) -> (usize, f64) {
        let target = u * self.total();
        let i = self
            .cdf
            .partition_point(|&c| c <= target)
            .min(self.cdf.len() - 1);
        let below = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let w = self.cdf[i] - below;
        let r = if w > 0.0 { (target - below) / w } else { 0.0 };
        (i, r.clamp(0.0, 1.0 - f64::EPSILON / 2.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_follow_the_weights() {
        let d = Distribution1D::new([1.0, 0.0, 3.0]);
        assert_eq!(d.sample(0.0), 0);
        assert_eq!(d.sample(0.2), 0);
        assert_eq!(d.sample(0.25), 2);
        assert_eq!(d.sample(0.999), 2);
        assert_eq!(
            (d.total(), d.pmf(0), d.pmf(1), d.pmf(2)),
            (4.0, 0.25, 0.0, 0.75)
        );
    }

    #[test]
    fn continuous_draws_remap_the_uniform() {
        let d = Distribution1D::new([1.0, 0.0, 3.0]);
        assert_eq!(d.sample_continuous(0.125), (0, 0.5));
        assert_eq!(d.sample_continuous(0.625), (2, 0.5));
    }

    /// Σ over draws of 1/(p·N) estimates the number of entries with weight (pbrt-v4's
    /// sampling tests): each drawn entry's probability is what `pmf` says.
    #[test]
    fn pmf_is_the_probability_of_a_draw() {
        let d = Distribution1D::new([0.5, 2.0, 0.0, 1.5, 6.0]);
        let n = 100_000;
        let mut counts = [0u32; 5];
        for k in 0..n {
            counts[d.sample((k as f32 + 0.5) / n as f32)] += 1;
        }
        for (i, &c) in counts.iter().enumerate() {
            assert!((c as f64 / n as f64 - d.pmf(i)).abs() < 1e-4, "{i}: {c}");
        }
    }
}
