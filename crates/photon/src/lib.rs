//! Photon tracing (thesis §2.6.1, §3.3; DESIGN.md §2): emission from every light kind in
//! proportion to its flux (photometric luminaires from their candela tables), Russian
//! roulette over diffuse, mirror, refraction and absorption, and the mean illuminance
//! of named surfaces with its standard error.
//!
//! - [`measure`] measures surfaces: one trace of photons, group sums per target, from
//!   which [`Measurement::estimate`] gives the mean illuminance in lux with its standard
//!   error. With [`Estimator::Connected`] it also counts [`Targets::connect`]ions: each
//!   photon departure joined to a point on each target by a ray, the two weighted by
//!   multiple importance sampling.
//! - The estimator, in one module: photons come in stratified groups of [`GROUP`],
//!   the groups are the independent samples, [`photons_traced`] says how many photons a
//!   request becomes; each chunk's groups are summed per target and channel.
//! - [`trace_photon`] follows one photon and reports its departures and arrivals to a
//!   [`PathVisitor`]; rendering stores photons and illuminance maps count cells
//!   through it.
//! - [`trace_chunks`] is the parallel driver of every trace: chunks of photons, each with
//!   its own visitor, folded in index order, so results are bit-identical for any thread
//!   count ([`Sampler`] streams are keyed by seed and photon index).
//! - [`trace_shared`] splits a trace's chunks among the processes of a [`Cluster`]
//!   and folds them in the same order on each: [`measure_with`] gives the
//!   same bits on one process or many.
//!
//! ```
//! use invlight_photon::{Estimator, TraceSettings, measure};
//! use invlight_scene::{Light, LightKind, Mat4, Material, Mesh, Scene, Vec3};
//! use invlight_trace::Accel;
//!
//! // A 1 cd point lamp 1 m above a black 2 m × 2 m floor centred below it.
//! let mut scene = Scene::default();
//! let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
//! let quad = scene.add_mesh(Mesh::quad(
//!     [Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0),
//!      Vec3::new(1.0, 1.0, 0.0), Vec3::new(-1.0, 1.0, 0.0)],
//!     black,
//! ));
//! let floor = scene.add_instance("Floor", quad, Mat4::IDENTITY);
//! scene.lights.push(Light {
//!     name: "Lamp".into(),
//!     kind: LightKind::Point { position: Vec3::new(0.0, 0.0, 1.0), intensity: Vec3::ONE },
//!     c0: Vec3::X,
//! });
//! let accel = Accel::new(&scene);
//! let settings = TraceSettings { photons: 20_000, ..TraceSettings::default() };
//! let m = measure(&scene, &accel, &[scene.surface("Floor").unwrap()], &settings,
//!     Estimator::Connected, None);
//! let e = m.estimate(0);
//! // The floor subtends 2π/3 sr of the lamp: Φ = 2π/3 lm over 4 m².
//! let exact = 2.0 * std::f64::consts::PI / 3.0 / 4.0;
//! assert!((e.mean - exact).abs() < 4.0 * e.std_error);
//! # let _ = floor;
//! ```
#![deny(missing_docs)]

/// The version of the numbers a seed gives: raised whenever a change to the tracer or
/// its estimators changes them (a search's `run.json` records it, and `--resume`
/// refuses to mix rows of two versions, whose common random numbers no longer pair).
/// 2: the roulette's share and connections by solid angle; 3: grids read at their
/// points (the point lights' direct light computed there).
pub const ESTIMATOR_VERSION: u32 = 3;

mod cells;
mod channels;
mod chunks;
mod cluster;
mod connect;
mod direct;
mod emit;
mod estimator;
pub mod glare;
mod grid;
mod measure;
mod measure_report;
mod path;
mod roulette;
mod sampler;
mod sampling;
mod tally;

pub use cells::{GridMeasurement, Uniformity};
pub use channels::{Components, Side, SideParseError};
pub use chunks::{
    BLOCK, BLOCK_MEMORY, CHUNK, DEFAULT_MAX_BOUNCES, PhotonTrace, TraceSettings, trace_chunks,
};
pub use cluster::{Alone, Cluster, Pack, cluster, join_cluster, leads, trace_shared};
pub use connect::{Connection, Departure, Lobe, SOLID_ANGLE_TRIANGLES, SolidAngles, Targets};
pub use direct::OPENING_SAMPLES;
pub use emit::{EmissiveTriangle, EmitSample, Emitters, SourceOrigin, emissive_triangles};
pub use estimator::{
    GROUP, MIN_GROUPS, MIN_PHOTONS, PhotonCountError, photon_count, photons_traced,
};
pub use grid::{GridError, MAX_CELLS, SurfaceGrid, en12464_rule, en12464_spacing};
pub use measure::{
    Estimator, GridRequest, GridValues, Measurement, Request, measure, measure_across,
    measure_more, measure_with,
};
pub use measure_report::{
    DaylightFactor, MeasureReport, SurfaceReport, behind_warning, much_from_behind,
};
pub use path::{PathVisitor, fresnel_dielectric, reflect, refract, trace_photon};
pub use roulette::{
    MIN_PILOT_PHOTONS, PILOT_PHOTONS, ROULETTE_SHARES, RouletteChoice, RouletteTrial,
    tune_roulette, tune_roulette_for,
};
pub use sampler::{GroupKeys, Sampler};
pub use sampling::{basis, cosine_hemisphere};
