//! Stratified random numbers for photons: consecutive photons form groups of [`GROUP`],
//! and within a group every dimension of the path (which light, where on it, which way,
//! each bounce's roulette and direction) is stratified: each photon of the group takes a
//! different stratum, jittered inside it. This is pbrt-v4's `StratifiedSampler` with the
//! group in the place of the pixel: a fresh pseudo-random permutation of the strata per
//! group and dimension (Kensler 2013, "Correlated Multi-Jittered Sampling", Pixar
//! Technical Memo 13-01, `permute`; pbrt-v4 `PermutationElement`) keeps the dimensions
//! independent of one another, so every number a photon draws is still uniform on its
//! own and every estimate stays unbiased.
//!
//! Why: the light a target receives directly, usually most of it, is an integral over the
//! first few dimensions (a point on the lamp and a direction). Stratifying them spreads
//! each group's photons evenly over the lamp and its beam instead of letting them clump,
//! which takes away much of the variance of "did this photon reach the target". The
//! photons of one group are not independent of one another, but groups are: the
//! group, not the photon, is the independent sample whose variance the standard error is
//! computed from (`Estimate::from_groups`), so reported intervals stay honest.
//!
//! Numbers are keyed by (seed, photon index): photon i draws the same numbers
//! whatever thread traces it, and two configurations traced with the same seed share
//! them (common random numbers).

use crate::estimator::GROUP;
use invlight_stats::{Pcg32, mix};

/// Strata per side of a group's two-dimensional grid.
const SIDE: u32 = 8;
const _: () = assert!(SIDE as u64 * SIDE as u64 == GROUP);

/// Dimensions stratified per photon: emission and the first bounces, where the paths of
/// a group's photons are still alike enough for stratification to pay. Later dimensions
/// are plain independent numbers.
const STRATIFIED_DIMENSIONS: u32 = 16;
/// The largest f32 below 1 (pbrt-v4 `OneMinusEpsilon`): a jittered stratum must stay in
/// [0, 1).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// The permutation keys of one group, one per stratified dimension, hashed from
/// (seed, group): the same for the group's photons, so computed once per group.
#[derive(Debug, Clone)]
pub struct GroupKeys([u32; STRATIFIED_DIMENSIONS as usize]);

impl GroupKeys {
    /// The keys of group `group` (photons `group·GROUP ..`) under `seed`.
    pub fn new(seed: u64, group: u64) -> GroupKeys {
        let group_key = mix(mix(seed ^ 0x5851_f42d_4c95_7f2d) ^ group);
        GroupKeys(std::array::from_fn(|d| mix(group_key ^ d as u64) as u32))
    }
}

/// The random numbers of one photon.
#[derive(Debug, Clone)]
pub struct Sampler<'k> {
    rng: Pcg32,
    /// The keys of the photon's group.
    keys: &'k GroupKeys,
    /// The photon's place in its group, 0..GROUP.
    index: u32,
    /// Dimensions drawn so far.
    dimension: u32,
}

impl<'k> Sampler<'k> {
    /// The numbers of photon `photon` under `seed`; `keys` are those of its group,
    /// `GroupKeys::new(seed, photon / GROUP)`.
    #[inline]
    pub fn new(keys: &'k GroupKeys, seed: u64, photon: u64) -> Sampler<'k> {
        Sampler {
            rng: Pcg32::new(seed, photon),
            keys,
            index: (photon % GROUP) as u32,
            dimension: 0,
        }
    }

    /// The stratum of this photon in the next dimension, or `None` past the stratified
    /// dimensions.
    #[inline]
    fn stratum(&mut self) -> Option<u32> {
        let key = *self.keys.0.get(self.dimension as usize)?;
        self.dimension += 1;
        Some(permute(self.index, GROUP as u32, key))
    }

    /// A uniform number in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f32 {
        match self.stratum() {
            Some(s) => {
                ((s as f32 + self.rng.uniform()) * (1.0 / GROUP as f32)).min(ONE_MINUS_EPSILON)
            }
            None => self.rng.uniform(),
        }
    }

    /// A uniform point in [0, 1)².
    #[inline]
    pub fn uniform2(&mut self) -> (f32, f32) {
        match self.stratum() {
            Some(s) => {
                let (x, y) = ((s % SIDE) as f32, (s / SIDE) as f32);
                let scale = 1.0 / SIDE as f32;
                (
                    ((x + self.rng.uniform()) * scale).min(ONE_MINUS_EPSILON),
                    ((y + self.rng.uniform()) * scale).min(ONE_MINUS_EPSILON),
                )
            }
            None => (self.rng.uniform(), self.rng.uniform()),
        }
    }
}

/// Element `i` of a pseudo-random permutation of 0..`len` chosen by `key` (Kensler 2013,
/// `permute`: a hash that is a bijection on the next power of two, cycle-walked down
/// to `len`).
#[inline]
fn permute(mut i: u32, len: u32, key: u32) -> u32 {
    let mut w = len - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= key;
        i = i.wrapping_mul(0xe170893d);
        i ^= key >> 16;
        i ^= (i & w) >> 4;
        i ^= key >> 8;
        i = i.wrapping_mul(0x0929eb3f);
        i ^= key >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | key >> 27);
        i = i.wrapping_mul(0x6935fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dcb303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e501cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860a3df);
        i &= w;
        i ^= i >> 5;
        if i < len {
            break;
        }
    }
    (i.wrapping_add(key)) % len
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutations_are_bijections() {
        for key in [0u32, 1, 0xdead_beef, 12345] {
            for len in [1u32, 5, 64, 100] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let p = permute(i, len, key) as usize;
                    assert!(!seen[p], "{p} twice for len {len}, key {key}");
                    seen[p] = true;
                }
            }
        }
    }

    #[test]
    fn a_group_fills_every_stratum_in_every_dimension() {
        // Each dimension of a group takes each of its GROUP strata exactly once; in two
        // dimensions each cell of the 8 × 8 grid once.
        let keys = GroupKeys::new(7, 3);
        let mut all: Vec<Sampler> = (0..GROUP)
            .map(|i| Sampler::new(&keys, 7, 3 * GROUP + i))
            .collect();
        for _ in 0..STRATIFIED_DIMENSIONS / 2 {
            let mut cells = [0u32; GROUP as usize];
            let mut strata = [0u32; GROUP as usize];
            for s in &mut all {
                let u = s.uniform();
                strata[(u * GROUP as f32) as usize] += 1;
                let (x, y) = s.uniform2();
                let cell = (y * SIDE as f32) as usize * SIDE as usize + (x * SIDE as f32) as usize;
                cells[cell] += 1;
            }
            assert!(strata.iter().all(|&c| c == 1), "{strata:?}");
            assert!(cells.iter().all(|&c| c == 1), "{cells:?}");
        }
        // Past the stratified dimensions the numbers are plain and still in [0, 1).
        for s in &mut all {
            let u = s.uniform();
            assert!((0.0..1.0).contains(&u));
        }
    }

    #[test]
    fn groups_and_dimensions_use_different_permutations() {
        // The strata of photon 0 of many groups in dimension 0 and 1 are not all equal:
        // groups and dimensions are permuted independently.
        let first: Vec<(u32, u32)> = (0..32)
            .map(|g| {
                let keys = GroupKeys::new(1, g);
                let mut s = Sampler::new(&keys, 1, g * GROUP);
                let a = (s.uniform() * GROUP as f32) as u32;
                let b = (s.uniform() * GROUP as f32) as u32;
                (a, b)
            })
            .collect();
        assert!(first.iter().any(|&(a, _)| a != first[0].0));
        assert!(first.iter().filter(|&&(a, b)| a == b).count() < 8);
    }
}
