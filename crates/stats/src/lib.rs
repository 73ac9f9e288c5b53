//! invlight-stats: the Monte Carlo numbers every layer of invlight shares, and nothing
//! else — no geometry, no photons — so that the search (`invlight-ilp`) is built and
//! tested on them without linking the tracer (DESIGN.md §7).
//!
//! - [`Estimate`]: a noisy mean with its standard error and sample count, from sums of
//!   independent samples or of stratified groups (thesis §3.3.2, appendix C).
//! - [`Confidence`], [`Interval`], [`compare`]: two-sided intervals `mean ± z·σ` and the
//!   statistical order of thesis eq. 3.7; [`normal_quantile`] gives z.
//! - [`paired_difference`], [`compare_paired`], [`variance_ratio`]: the same order from
//!   the paired differences of per-group means traced with common random numbers.
//! - [`SplitMix64`], [`Pcg32`], [`mix`]: reproducible random streams keyed by a seed
//!   and an index, so results never depend on thread count or scheduling.
//! - [`significant`]: numbers as tables and messages show them.
//! - [`ChannelSums`]: group sums of a vector of channels with their cross products, so
//!   that any weighted sum of them (a dimming, a side) has its own standard error.
//! - [`Distribution1D`]: a discrete distribution from weights, sampled by inversion
//!   with the probability of what it returns; [`PiecewiseConstant2D`]: a density
//!   constant on the cells of a grid, sampled with its exact density.
//!
//! ```
//! use invlight_stats::{Confidence, Estimate, compare, Comparison};
//! let c = Confidence::new(0.95).unwrap();
//! let a = Estimate::from_sums(10.0, 30.0, 4); // samples 1, 2, 3, 4
//! assert_eq!(a.mean, 2.5);
//! let i = a.interval(c.z());
//! assert!(i.low < 2.5 && 2.5 < i.high);
//! let b = Estimate { mean: 9.0, std_error: 0.1, samples: 100 };
//! assert_eq!(compare(&b, &a, c.z()), Comparison::Better);
//! ```
#![deny(missing_docs)]

mod channels;
mod distribution;
mod distribution2d;
mod estimate;
mod format;
mod interval;
mod pace;
mod paired;
mod rng;

pub use channels::ChannelSums;
pub use distribution::Distribution1D;
pub use distribution2d::{Distribution2DError, PiecewiseConstant2D, Sample2D};
pub use estimate::{Estimate, normal_quantile};
pub use format::{hours_or_days, significant, significant_beside};
pub use interval::{
    Comparison, Confidence, ConfidenceError, ConfidenceParseError, Interval, compare,
};
pub use pace::{LONG_WORK, LongWork, PACE_SAMPLE, Pace};
pub use paired::{compare_paired, paired_difference, student_quantile, variance_ratio};
pub use rng::{Pcg32, SplitMix64, mix};
