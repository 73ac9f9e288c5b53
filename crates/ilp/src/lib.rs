//! invlight-ilp: inverse lighting problems (thesis chapters 3–4, DESIGN.md §3–4).
//!
//! The core types:
//! - [`Problem`]: an ILPSolver XML problem file, read with located errors and warnings
//!   (`docs/problem-file.md`).
//! - [`Binding`]: a problem bound to a [`Scene`](invlight_scene::Scene): the [`Space`]
//!   of its variables ([`Variable`], [`Domain`]: placement [`Rectangle`]s, sun
//!   [`Hemisphere`]s, colour segments) with their neighbourhoods N(x, r) and cells, the
//!   initial [`Configuration`], and [`Binding::apply`], which changes only what moved.
//! - [`Search`]: the adapted VNS, generic over an [`Evaluate`] function returning an
//!   [`Estimate`] with its standard error; it keeps the [`Isoc`] (the indistinguishable
//!   set of optimum configurations) and a tabu cache of evaluated cells, and reports
//!   every evaluation to an [`Observer`].
//! - [`PhotonEvaluator`]: the objective by photon tracing; [`Output`]: `solutions.csv`
//!   and `result.json`, and [`read_solutions`] to resume.
//!
//! ```
//! use invlight_ilp::{Configuration, Domain, Evaluate, Search, Settings, Space, Strategy,
//!     Variable, Observer, Record, Isoc, Estimate};
//! use std::sync::atomic::AtomicBool;
//!
//! // Maximise 1 − (V − 0.3)² over a colour value V ∈ [0, 1] (exact, σ = 0).
//! struct Parabola;
//! impl Evaluate for Parabola {
//!     type Error = ();
//!     fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Estimate, ()> {
//!         let v = c.coords[0];
//!         Ok(Estimate { mean: 1.0 - (v - 0.3).powi(2), std_error: 0.0, photons })
//!     }
//! }
//! struct Quiet;
//! impl Observer for Quiet {
//!     fn evaluated(&mut self, _: &Record, _: &Isoc, _: bool) -> std::io::Result<()> { Ok(()) }
//! }
//! let space = Space::new(
//!     vec![Variable { id: "Walls".into(), domain: Domain::Segment { min: 0.0, max: 1.0 } }],
//!     &[10],
//! );
//! let settings = Settings {
//!     max_iterations: 200, photons: 1000, fast_quality: 0.25,
//!     strategy: Strategy::RefineOnIntersection, confidence: 0.95, cap: None, seed: 1,
//!     tries_per_radius: None,
//! };
//! let mut search = Search::new(&space, settings, &Configuration { coords: vec![0.9] });
//! search.run(&mut Parabola, &mut Quiet, &AtomicBool::new(false)).unwrap();
//! // The best cell is [0.3, 0.4), evaluated at its centre 0.35.
//! assert_eq!(search.isoc().members()[0].config.coords, vec![0.35]);
//! ```
#![deny(missing_docs)]

mod apply;
mod cache;
mod compare;
mod isoc;
mod output;
mod photons;
mod problem;
mod rng;
mod space;
mod vns;

pub use apply::{Binding, Value, hsv_to_rgb};
pub use cache::{Cache, Entry};
pub use compare::{Comparison, Interval, compare};
pub use invlight_photon::Estimate;
pub use isoc::{Admission, Isoc, Member};
pub use output::{ObjectiveInfo, Output, RunSettings, csv_header, read_solutions};
pub use photons::PhotonEvaluator;
pub use problem::{Objective, Problem, ProblemError, VariableKind, VariableSpec};
pub use rng::{SplitMix64, mix};
pub use space::{
    Cell, Configuration, Domain, Hemisphere, Rectangle, RectangleError, Space, Variable,
};
pub use vns::{
    Evaluate, Observer, Outcome, Record, Search, SearchError, Settings, Strategy, Verdict,
};
