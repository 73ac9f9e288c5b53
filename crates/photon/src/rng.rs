//! Random streams keyed by (seed, photon index), so a photon draws the same numbers
//! whatever thread traces it (DESIGN.md §2; pbrt-v4 `IndependentSampler::StartPixelSample`
//! seeds by pixel index the same way). Two configurations traced with the same seed then
//! share random numbers: common random numbers make their difference far less noisy.

/// PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
/// algorithms for random number generation", XSH-RR output), started from a SplitMix64
/// hash of the key so neighbouring photon indices get unrelated streams.
#[derive(Debug, Clone)]
pub struct Rng {
    state: u64,
    inc: u64,
}

const MULT: u64 = 6364136223846793005;

/// SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mixer.
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
    z ^ (z >> 31)
}

impl Rng {
    /// The stream of photon `index` under `seed`.
    pub fn new(seed: u64, index: u64) -> Rng {
        let a = mix64(seed.wrapping_add(0x9e3779b97f4a7c15));
        let state = mix64(a ^ index.wrapping_mul(0xd1342543de82ef95));
        let inc = (mix64(a.rotate_left(17) ^ index) << 1) | 1;
        let mut rng = Rng { state: 0, inc };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(state);
        rng.next_u32();
        rng
    }

    /// The next 32 random bits.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULT).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// A uniform float in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f32 {
        // 24 high bits: every value exactly representable, never 1.0.
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let a: Vec<u32> = (0..4).map(|_| Rng::new(1, 7).next_u32()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        let mut x = Rng::new(1, 7);
        let mut y = Rng::new(1, 8);
        let same = (0..64).filter(|_| x.next_u32() == y.next_u32()).count();
        assert!(same < 2);
    }

    #[test]
    fn uniform_mean_and_variance() {
        // Mean 1/2 and variance 1/12 of U[0,1); the tolerance is 5 standard errors.
        let n = 200_000;
        let mut rng = Rng::new(3, 0);
        let (mut s, mut s2) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let u = rng.uniform() as f64;
            assert!((0.0..1.0).contains(&u));
            s += u;
            s2 += u * u;
        }
        let mean = s / n as f64;
        let var = s2 / n as f64 - mean * mean;
        assert!((mean - 0.5).abs() < 5.0 * (1.0f64 / 12.0 / n as f64).sqrt());
        assert!((var - 1.0 / 12.0).abs() < 5.0 * (1.0f64 / 180.0 / n as f64).sqrt());
    }
}
