//! invlight-ilp: inverse lighting problems (thesis chapters 3–4, DESIGN.md §3–4).
//!
//! The core types:
//! - [`Problem`]: an ILPSolver XML problem file, read with located errors and warnings
//!   ([`Diagnostic`], `docs/problem-file.md`).
//! - [`Binding`]: a problem bound to a [`Scene`](invlight_scene::Scene): the [`Space`]
//!   of its variables ([`Variable`], [`Domain`]: placement [`Parallelogram`]s, sun
//!   [`Hemisphere`]s, colour segments) with their neighbourhoods N(x, r) and cells, the
//!   initial [`Configuration`], [`Binding::apply`], which changes only what moved, and
//!   [`Binding::configuration`], the way back from world values to a configuration.
//! - Intentions ([`Goal`], [`Constraint`]): the most or least light on a surface, a
//!   target illuminance, the most uniform light, the least lamp power, under bounds on
//!   the mean, the uniformity U0 or the least point value of other surfaces, each on
//!   the front, back or both sides; [`Reading`] says what they measure.
//! - [`Search`]: the adapted VNS, generic over an [`Evaluate`] function returning an
//!   [`Evaluation`] (the goal's and the constraints' [`Estimate`]s with their standard
//!   errors); it keeps the [`Isoc`] (the indistinguishable set of optimum feasible
//!   configurations), the configurations closest to feasible and a tabu cache of
//!   evaluated cells, and reports every evaluation to an [`Observer`]. It uses
//!   `invlight-stats` alone, so it is tested on synthetic functions without the tracer.
//! - [`PhotonEvaluator`]: the goal and constraints by photon tracing, every dimming of
//!   an arrangement from one trace.
//! - The files of a run, one typed schema each, read and written by the same struct:
//!   [`SolutionRow`] (`solutions.csv`), [`ResultFile`] (`result.json`), [`RunFile`]
//!   (`run.json`), kept by [`Output`] as the search goes; [`Recorder`], the observer a
//!   command gives the search (the files, the records, what to show).
//! - [`visits`]: what the search visited, for its plots.
//!
//! ```
//! use invlight_ilp::{Configuration, Domain, Evaluate, Evaluation, Search, Sense, Settings,
//!     Space, Standing, Strategy, Variable, Observer, Record};
//! use invlight_stats::{Confidence, Estimate};
//!
//! // Maximise 1 − (V − 0.3)² over a colour value V ∈ [0, 1] (exact, σ = 0).
//! struct Parabola;
//! impl Evaluate for Parabola {
//!     type Error = ();
//!     fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Evaluation, ()> {
//!         let v = c.coords[0];
//!         let e = Estimate { mean: 1.0 - (v - 0.3).powi(2), std_error: 0.0, samples: photons };
//!         Ok(Evaluation::of(e))
//!     }
//! }
//! struct Quiet;
//! impl Observer for Quiet {
//!     fn evaluated(&mut self, _: &Record, _: Standing, _: bool) -> std::io::Result<()> { Ok(()) }
//! }
//! let space = Space::new(
//!     vec![Variable { id: "Walls".into(), domain: Domain::Segment { min: 0.0, max: 1.0 } }],
//!     &[10],
//! );
//! let settings = Settings {
//!     max_iterations: 200, photons: 1000, fast_quality: 0.25,
//!     strategy: Strategy::RefineOnIntersection, confidence: Confidence::DEFAULT, cap: None,
//!     sense: Sense::Maximize, constraints: Vec::new(), seed: 1, tries_per_radius: None,
//! };
//! let mut search = Search::new(&space, settings, &Configuration { coords: vec![0.9] });
//! search.run(&mut Parabola, &mut Quiet).unwrap();
//! // The best cell is [0.3, 0.4), evaluated at its centre 0.35.
//! assert_eq!(search.isoc().members()[0].config.coords, vec![0.35]);
//! ```
#![deny(missing_docs)]

mod binding;
mod cache;
mod dimming;
mod history;
mod intention;
mod isoc;
mod member;
mod output;
mod photons;
mod problem;
mod reading;
mod space;
mod vns;

pub use binding::{
    ArrayLayout, Binding, Bounds, ConfigurationError, Layout, LuminaireUse, PowerUnit,
    VariableValue, hsv_to_rgb, regular_array,
};
pub use cache::{Cache, Entry};
pub use history::{Axes, Role, Visit, visits};
pub use intention::{
    Bound, Constraint, Feasibility, FromTask, Goal, Grid, GridValues, Side, Spacing, SurfaceRef,
    en12464_spacing,
};
pub use invlight_scene::Diagnostic;
pub use invlight_stats::{Comparison, Confidence, Estimate, Interval, compare};
pub use isoc::{Admission, Isoc, Member};
pub use member::{MemberNumberError, MemberRef, configured_scene};
pub use output::{
    ConstraintInfo, FolderLock, MemberError, ObjectiveInfo, Output, OutputError, Progress,
    RESULT_SCHEMA, RUN_FILES, RUN_SCHEMA, Recorder, ResultConstraint, ResultEstimate, ResultFile,
    ResultMember, ResultValue, Run, RunFile, SolutionRow, Solutions, Start, csv_header, csv_line,
    is_run_picture,
};
pub use photons::{EvaluationError, PhotonEvaluator, SideSplit};
pub use problem::{
    Anchor, FittingSize, LightGroup, PlacementSpec, Problem, SceneRef, TaskSpec, VariableKind,
    VariableSpec,
};
pub use reading::{GridSpec, Quantity, Reading};
pub use space::{
    ArrayDomain, ArrayShape, Cell, Configuration, Domain, Hemisphere, Parallelogram,
    ParallelogramError, Space, Variable,
};
pub use vns::{
    Evaluate, Evaluation, Observer, Outcome, Record, Search, SearchError, Sense, Settings,
    Standing, Strategy, UnknownStrategy, Verdict, early_look_z, looks,
};
