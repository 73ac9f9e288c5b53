//! Random streams that a seed and an index determine, so that a number never depends on
//! the thread or rank that draws it (DESIGN.md §2; pbrt-v4
//! `IndependentSampler::StartPixelSample` seeds by pixel index the same way), and two
//! configurations traced with the same seed share their numbers (common random
//! numbers make their difference far less noisy than either value).

/// SplitMix64's finaliser (G. Steele, D. Lea, C. Flood, "Fast splittable pseudorandom
/// number generators", OOPSLA 2014): a bijective 64-bit mix, used to derive seeds and
/// keys.
#[inline]
pub fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A SplitMix64 stream: 64-bit numbers in f64 precision for the search, which draws a
/// few per candidate, so reproducibility from the seed matters and speed does not.
#[derive(Debug, Clone)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A stream starting from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix(self.state)
    }

    /// A uniform number in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform number in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// A uniform index in 0..n (n > 0), by Lemire's multiply-shift (the bias, below
    /// n/2⁶⁴, is irrelevant here).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_u64() as u128 * n as u128) >> 64) as usize
    }
}

/// PCG32 (M. E. O'Neill, "PCG: A family of simple fast space-efficient statistically
/// good algorithms for random number generation", 2014, XSH-RR output): the photons'
/// stream, 32-bit and fast, started from a SplitMix64 hash of (seed, index) so that
/// neighbouring photon indices get unrelated streams.
#[derive(Debug, Clone)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

const MULT: u64 = 6364136223846793005;

impl Pcg32 {
    /// The stream of `index` (a photon, a pixel) under `seed`.
    pub fn new(seed: u64, index: u64) -> Pcg32 {
        let a = mix(seed.wrapping_add(0x9e3779b97f4a7c15));
        let state = mix(a ^ index.wrapping_mul(0xd1342543de82ef95));
        Pcg32::seeded(state, mix(a.rotate_left(17) ^ index))
    }

    /// O'Neill's `pcg32_srandom_r(initstate, initseq)`: the stream `initseq` from the
    /// state `initstate`, as the reference implementation (pcg-random.org, pcg-c-basic)
    /// seeds it.
    pub fn seeded(initstate: u64, initseq: u64) -> Pcg32 {
        let mut rng = Pcg32 {
            state: 0,
            inc: (initseq << 1) | 1,
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(initstate);
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
    fn splitmix_reference_values() {
        // First outputs of SplitMix64 seeded with 1234567 (reference implementation).
        let mut r = SplitMix64::new(1234567);
        assert_eq!(r.next_u64(), 6457827717110365317);
        assert_eq!(r.next_u64(), 3203168211198807973);
    }

    #[test]
    fn splitmix_uniform_mean_is_one_half() {
        let mut r = SplitMix64::new(7);
        let n = 100_000;
        let mean = (0..n).map(|_| r.next_f64()).sum::<f64>() / n as f64;
        // σ of the mean of U(0,1) samples: sqrt(1/12/n); 5σ.
        assert!((mean - 0.5).abs() < 5.0 * (1.0 / 12.0 / n as f64).sqrt());
    }

    #[test]
    fn pcg_matches_the_reference_implementation() {
        // pcg-c-basic's pcg32-demo: pcg32_srandom_r(&rng, 42u, 54u), then six draws.
        let mut r = Pcg32::seeded(42, 54);
        let first: Vec<u32> = (0..6).map(|_| r.next_u32()).collect();
        assert_eq!(
            first,
            [
                0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e
            ]
        );
    }

    #[test]
    fn pcg_streams_are_distinct() {
        let mut x = Pcg32::new(1, 7);
        let mut y = Pcg32::new(1, 8);
        let same = (0..64).filter(|_| x.next_u32() == y.next_u32()).count();
        assert!(same < 2);
    }

    #[test]
    fn pcg_uniform_mean_and_variance() {
        // Mean 1/2 and variance 1/12 of U[0,1); the tolerance is 5 standard errors.
        let n = 200_000;
        let mut rng = Pcg32::new(3, 0);
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
