//! Photon tracing (thesis §2.6.1, §3.3; DESIGN.md §2): emission from every light kind,
//! Russian roulette, per-surface tallies, and estimates with confidence intervals.
#![deny(missing_docs)]

mod estimate;

pub use estimate::{Estimate, normal_quantile, z_two_sided};
