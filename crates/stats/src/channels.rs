//! Sums over independent groups of samples of a vector of channels — a target's light
//! split by the lamp it came from and the side it arrived on — kept with their cross
//! products, so that the estimate of any weighted sum of the channels (a dimming of
//! the lamps, one side or both) has its own standard error from the same trace.
//!
//! With X_g ∈ ℝᶜ the g-th group's channel totals and w the weights, the weighted total
//! Y_g = w·X_g has Σ Y_g = w·ΣX_g and Σ Y_g² = wᵀ(Σ X_g X_gᵀ)w: the C(C+1)/2 sums of
//! products are all a quadratic form needs. Covariances of two weightings come the same
//! way, for ratios such as a uniformity Emin/Eavg (the delta method).

use crate::estimate::Estimate;

/// Σ X_g and Σ X_g X_gᵀ (upper triangle, row by row) over groups of a C-vector.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelSums {
    sum: Vec<f64>,
    cross: Vec<f64>,
}

/// The index of (i, j), i ≤ j, in the upper triangle of a C × C matrix stored by rows.
#[inline]
fn upper(c: usize, i: usize, j: usize) -> usize {
    debug_assert!(i <= j && j < c);
    i * c - i * (i + 1) / 2 + j
}

impl ChannelSums {
    /// The bytes its sums take on the heap.
    pub fn heap_bytes(&self) -> usize {
        (self.sum.len() + self.cross.len()) * size_of::<f64>()
    }

    /// Empty sums of `channels` channels.
    pub fn new(channels: usize) -> ChannelSums {
        ChannelSums {
            sum: vec![0.0; channels],
            cross: vec![0.0; channels * (channels + 1) / 2],
        }
    }

    /// The number of channels.
    pub fn channels(&self) -> usize {
        self.sum.len()
    }

    /// Adds one group's channel totals.
    #[inline]
    pub fn add_group(&mut self, x: &[f64]) {
        let c = self.sum.len();
        debug_assert_eq!(x.len(), c);
        for i in 0..c {
            if x[i] == 0.0 {
                continue;
            }
            self.sum[i] += x[i];
            let row = upper(c, i, i);
            for j in i..c {
                self.cross[row + j - i] += x[i] * x[j];
            }
        }
    }

    /// Adds `other`'s sums (groups of another chunk).
    pub fn merge(&mut self, other: &ChannelSums) {
        for (a, b) in self.sum.iter_mut().zip(&other.sum) {
            *a += b;
        }
        for (a, b) in self.cross.iter_mut().zip(&other.cross) {
            *a += b;
        }
    }

    /// Appends the sums to `out` as the bits of their values (Σ X_g, then the products),
    /// so that a process traces a chunk and another folds its sums with the same bits
    /// (a trace shared by the processes of a cluster job).
    pub fn pack(&self, out: &mut Vec<u64>) {
        out.extend(self.sum.iter().chain(&self.cross).map(|x| x.to_bits()));
    }

    /// Reads back what [`ChannelSums::pack`] wrote, into sums of the same channel count.
    ///
    /// # Panics
    /// If `words` ends first: the packing process held sums of more channels.
    pub fn unpack(&mut self, words: &mut impl Iterator<Item = u64>) {
        for x in self.sum.iter_mut().chain(&mut self.cross) {
            *x = f64::from_bits(words.next().expect("packed sums of as many channels"));
        }
    }

    /// Σ_g w·X_g.
    pub fn total(&self, w: &[f64]) -> f64 {
        self.sum.iter().zip(w).map(|(s, w)| s * w).sum()
    }

    /// Σ_g (a·X_g)(b·X_g).
    pub fn product(&self, a: &[f64], b: &[f64]) -> f64 {
        let c = self.sum.len();
        let mut out = 0.0;
        for (i, &ai) in a.iter().enumerate().take(c) {
            for (j, &bj) in b.iter().enumerate().take(c) {
                let (lo, hi) = if i <= j { (i, j) } else { (j, i) };
                out += ai * bj * self.cross[upper(c, lo, hi)];
            }
        }
        out
    }

    /// The estimate of the per-sample mean of w·X, `scale`d (1/area for illuminance),
    /// from `samples` samples in `groups` groups ([`Estimate::from_groups`]).
    pub fn estimate(&self, w: &[f64], groups: u64, samples: u64, scale: f64) -> Estimate {
        Estimate::from_groups(
            self.total(w) * scale,
            self.product(w, w) * scale * scale,
            groups,
            samples,
        )
    }

    /// The covariance of the per-sample means of a·X and b·X (each unscaled), from the
    /// groups' spread as [`Estimate::from_groups`] takes a variance: the sample covariance
    /// of the G group totals (G − 1 in the denominator) over G, scaled to samples.
    pub fn covariance(&self, a: &[f64], b: &[f64], groups: u64, samples: u64) -> f64 {
        if groups < 2 || samples == 0 {
            return f64::INFINITY;
        }
        let g = groups as f64;
        let (sa, sb) = (self.total(a), self.total(b));
        let cov_groups = (self.product(a, b) - sa * sb / g) / (g - 1.0);
        cov_groups * g / (samples as f64 * samples as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A weighted sum of channels has the mean and standard error of the same samples
    /// summed by hand.
    #[test]
    fn packed_sums_unpack_to_the_same_bits() {
        let mut s = ChannelSums::new(3);
        s.add_group(&[0.1, 0.0, -2.5]);
        s.add_group(&[1.0 / 3.0, 7.0, 0.0]);
        let mut words = Vec::new();
        s.pack(&mut words);
        assert_eq!(words.len(), 3 + 6);
        let mut back = ChannelSums::new(3);
        back.unpack(&mut words.iter().copied());
        assert_eq!(back, s);
    }

    #[test]
    fn weighted_sums_match_sums_by_hand() {
        let groups = [
            [1.0, 0.0, 2.0],
            [0.5, 3.0, 0.0],
            [2.0, 1.0, 1.0],
            [0.0, 0.0, 4.0],
        ];
        let mut s = ChannelSums::new(3);
        for g in &groups {
            s.add_group(g);
        }
        let w = [2.0, -1.0, 0.5];
        let by_hand: Vec<f64> = groups
            .iter()
            .map(|g| g.iter().zip(&w).map(|(x, w)| x * w).sum())
            .collect();
        let sum: f64 = by_hand.iter().sum();
        let sum_sq: f64 = by_hand.iter().map(|y| y * y).sum();
        let want = Estimate::from_groups(sum, sum_sq, 4, 256);
        let got = s.estimate(&w, 4, 256, 1.0);
        assert!((got.mean - want.mean).abs() < 1e-15);
        assert!((got.std_error - want.std_error).abs() < 1e-15);
        // Covariance of a channel with itself is its variance of the mean.
        let e0 = s.estimate(&[1.0, 0.0, 0.0], 4, 256, 1.0);
        let var = s.covariance(&[1.0, 0.0, 0.0], &[1.0, 0.0, 0.0], 4, 256);
        assert!((var - e0.std_error * e0.std_error).abs() < 1e-15);
        // Two independent-looking channels: the covariance by hand.
        let (a, b): (Vec<f64>, Vec<f64>) = groups.iter().map(|g| (g[0], g[2])).unzip();
        let (ma, mb) = (a.iter().sum::<f64>() / 4.0, b.iter().sum::<f64>() / 4.0);
        let cov_g: f64 = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x - ma) * (y - mb))
            .sum::<f64>()
            / 3.0;
        let want = cov_g * 4.0 / (256.0 * 256.0);
        let got = s.covariance(&[1.0, 0.0, 0.0], &[0.0, 0.0, 1.0], 4, 256);
        assert!((got - want).abs() < 1e-15, "{got} vs {want}");
        let mut t = ChannelSums::new(3);
        t.add_group(&groups[0]);
        let mut u = ChannelSums::new(3);
        for g in &groups[1..] {
            u.add_group(g);
        }
        t.merge(&u);
        assert_eq!(t, s);
    }
}
