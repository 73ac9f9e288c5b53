//! What a search reports as it goes: one row per evaluation (`solutions.csv`) and the
//! standing of the best set, to an observer that writes them.

use super::{Evaluation, Verdict};
use crate::isoc::{Isoc, Member};
use crate::space::Configuration;

/// One evaluation, as reported and written to `solutions.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Iteration (candidate number) that made it; the initial configuration is 0.
    pub iteration: u64,
    /// The configuration evaluated (a cell's reference point).
    pub config: Configuration,
    /// What was estimated.
    pub evaluation: Evaluation,
    /// Wall time of the evaluation, s.
    pub seconds: f64,
    /// What the search decided.
    pub verdict: Verdict,
}

/// Receives the search's progress.
pub trait Observer {
    /// After every evaluation, with the ISOC (and the configurations closest to
    /// feasible) as they are now; `changed` when this evaluation changed what a result
    /// file shows: the ISOC, or the closest while the ISOC is empty.
    fn evaluated(
        &mut self,
        record: &Record,
        standing: Standing<'_>,
        changed: bool,
    ) -> std::io::Result<()>;
    /// After every candidate drawn (cache hits included).
    fn iteration(&mut self, _iteration: u64) {}

    /// A candidate the evaluator refused untraced, and why.
    fn refused(&mut self, _iteration: u64, _why: &str) {}

    /// Asked before every candidate: `true` stops the search there (Ctrl-C), leaving
    /// everything reported so far valid.
    fn should_stop(&mut self) -> bool {
        false
    }
}

/// Where a search stands: its ISOC and the configurations that came closest to
/// meeting the constraints.
#[derive(Debug, Clone, Copy)]
pub struct Standing<'a> {
    /// The ISOC: feasible configurations that cannot be told apart from the best.
    pub isoc: &'a Isoc,
    /// The configurations that violate the constraints least (by the largest relative
    /// shortfall of their means), least first, with that shortfall.
    pub closest: &'a [(f64, Member)],
    /// The best of the structured starts ([`Space::regular_arrays`](crate::Space::regular_arrays)) that was decided
    /// feasible: the regular array an answer of free positions is to be weighed
    /// against, even when the search went past it.
    pub best_start: Option<&'a Member>,
}
