//! How a search ended: why it stopped early, or what it found.

use std::fmt;

/// Why a search stopped early.
#[derive(Debug)]
pub enum SearchError<E> {
    /// The evaluation function failed.
    Evaluate(E),
    /// The observer could not write.
    Output(std::io::Error),
}

impl<E: fmt::Display> fmt::Display for SearchError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SearchError::Evaluate(e) => write!(f, "evaluation failed: {e}"),
            SearchError::Output(e) => write!(f, "cannot write the results: {e}"),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> std::error::Error for SearchError<E> {}

/// How a search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// `max_iterations` reached.
    Finished,
    /// Every cell was evaluated.
    Exhausted,
    /// The observer asked to stop; the ISOC is as it was (not refined).
    Interrupted,
    /// [`Strategy::Paired`](crate::Strategy::Paired), [`Strategy::RaceOnEnd`](crate::Strategy::RaceOnEnd): a whole sweep of the radii
    /// 0.05 … 0.95 around the ISOC, I candidates each, admitted no configuration, nor
    /// did the cells adjacent to its members (see [`Search::run`](crate::Search::run)).
    Settled,
    /// [`Strategy::Paired`](crate::Strategy::Paired), [`Strategy::RaceOnEnd`](crate::Strategy::RaceOnEnd): the global screening found every
    /// configuration it tried (and the initial one) indistinguishable from no light at
    /// all, until the budget or the cells ran out.
    Unlit,
}

impl Outcome {
    /// Why the search stopped, for `stopped: …` in the table and `result.json`;
    /// `surface` names the goal's surface.
    pub fn stopped(self, surface: Option<&str>) -> String {
        match self {
            Outcome::Finished => "maxIterations candidates drawn".into(),
            Outcome::Exhausted => "every cell was evaluated".into(),
            Outcome::Interrupted => "interrupted".into(),
            Outcome::Settled => {
                "decided: a whole sweep of the radii 0.05 to 0.95 around the ISOC, and every cell next to a member, admitted no configuration".into()
            }
            Outcome::Unlit => format!(
                "no configuration tried lights '{}': every estimate of its light was indistinguishable from 0 (check that a light can reach it, or widen the variables' ranges)",
                surface.unwrap_or("the goal's surface")
            ),
        }
    }

    /// What a user should know about it, if anything (the table already ends with
    /// [`Outcome::stopped`](crate::Outcome::stopped)).
    pub fn note(self) -> Option<&'static str> {
        match self {
            Outcome::Finished | Outcome::Settled | Outcome::Unlit => None,
            Outcome::Exhausted => Some("every cell was evaluated"),
            Outcome::Interrupted => Some(
                "interrupted: the files are complete up to the last evaluation; continue with --resume",
            ),
        }
    }
}
