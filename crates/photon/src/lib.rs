//! Photon tracing (thesis §2.6.1, §3.3; DESIGN.md §2): emission from every light kind in
//! proportion to its flux (photometric luminaires from their candela tables), Russian roulette over diffuse, mirror, refraction and
//! absorption, per-surface tallies, and estimates with confidence intervals.
//!
//! - [`trace`] measures surfaces: it returns one [`Tally`] per target, from which
//!   [`TraceResult::estimate`] gives the mean illuminance in lux with its standard error.
//!   Besides the photons' arrivals it counts [`Targets::connect`]ions: each photon
//!   departure joined to a point on each target by a ray, the two weighted by
//!   multiple importance sampling.
//! - [`trace_photon`] follows one photon and reports its arrivals to a [`PathVisitor`];
//!   rendering stores photons through it.
//! - [`trace_chunks`] is the parallel driver of every trace: chunks of photons, each with
//!   its own visitor, folded in index order.
//! - [`Rng`] streams are keyed by (seed, photon index): results are bit-identical for any
//!   thread count. [`Sampler`] stratifies them over groups of [`GROUP`] photons.
#![deny(missing_docs)]

mod chunks;
mod connect;
mod emit;
mod estimate;
mod measure;
mod path;
mod rng;
mod sampler;
mod sampling;

pub use chunks::{BLOCK, CHUNK, trace_chunks};
pub use connect::{Departure, Lobe, Targets};
pub use emit::{EmissiveTriangle, EmitSample, Emitters, emissive_triangles};
pub use estimate::{Estimate, normal_quantile, z_two_sided};
pub use measure::{DEFAULT_MAX_BOUNCES, PhotonTallies, Tally, TraceResult, TraceSettings, trace};
pub use path::{PathVisitor, fresnel_dielectric, reflect, refract, trace_photon};
pub use rng::Rng;
pub use sampler::{GROUP, GroupKeys, MIN_GROUPS, Sampler, whole_groups};
pub use sampling::{basis, cosine_hemisphere};
