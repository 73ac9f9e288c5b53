//! Photon tracing (thesis §2.6.1, §3.3; DESIGN.md §2): emission from every light kind in
//! proportion to its flux, Russian roulette over diffuse, mirror, refraction and
//! absorption, per-surface tallies, and estimates with confidence intervals.
//!
//! - [`trace`] measures surfaces: it returns one [`Tally`] per target, from which
//!   [`TraceResult::estimate`] gives the mean illuminance in lux with its standard error.
//! - [`trace_photon`] follows one photon and reports its arrivals to a [`PathVisitor`];
//!   rendering stores photons through it.
//! - [`Rng`] streams are keyed by (seed, photon index): results are bit-identical for any
//!   thread count.
#![deny(missing_docs)]

mod emit;
mod estimate;
mod measure;
mod path;
mod rng;
mod sampling;

pub use emit::{EmitSample, Emitters};
pub use estimate::{Estimate, normal_quantile, z_two_sided};
pub use measure::{BLOCK, CHUNK, DEFAULT_MAX_BOUNCES, Tally, TraceResult, TraceSettings, trace};
pub use path::{PathVisitor, fresnel_dielectric, reflect, refract, trace_photon};
pub use rng::Rng;
pub use sampling::{basis, cosine_hemisphere};
