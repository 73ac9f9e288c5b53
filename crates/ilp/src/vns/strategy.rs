//! When a search traces a candidate with the full photon count N: ILPSolver's
//! strategies (thesis §4.7) and invlight's paired and racing ones.

/// When candidates are evaluated with the full sample count N (ILPSolver's strategies).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Strategy {
    /// Thesis §4.7: every candidate first with n = q·N; when that interval reaches the
    /// SIISOC, again with N before deciding. The initial configuration uses N.
    RefineOnIntersection,
    /// Everything with n; at the end the ISOC members are re-evaluated with N and the
    /// ISOC rebuilt from those estimates.
    RefineOnEnd,
    /// Everything with n, never refined.
    NoRefine,
    /// As `RefineOnIntersection`, but a candidate is compared with each ISOC member by
    /// the paired differences of their groups (common random numbers) instead
    /// of eq. 3.7's independent variances, wherever both kept their groups; a candidate
    /// is looked at with n/16, n/4, n, 4n, … samples ([`looks`](crate::looks)) and is out as soon as
    /// a member beats it by pairs or it falls below the SIISOC or its constraints at
    /// an early look's level ([`early_look_z`](crate::early_look_z)); [`Search::run`](crate::Search::run)'s stopping rule
    /// ends the search when it is decided. `solutions.csv` keeps no groups, so the
    /// members a resumed run rebuilds from it are compared by eq. 3.7.
    Paired,
    /// The walk of `REFINE_ISOC_ON_END` (every candidate with n, compared by eq. 3.7)
    /// with `PAIRED_ISOC`'s global screening, early looks below n (n/16, n/4) and
    /// stopping rule; at the end the ISOC is raced to N rather than re-evaluated whole
    /// (`race`): its members are looked at together with 4n, 16n, … samples, and a
    /// member that another beats by the paired differences of their groups at an early
    /// look's level ([`early_look_z`](crate::early_look_z)) goes no further. The walk's decisions at n do
    /// not pair (only its early looks screen by pairs, at their stricter level): with
    /// n's few groups pairs decide many more comparisons than eq. 3.7, each at its
    /// nominal error, and over a walk's hundreds of them they drop the optimum more
    /// often than the thesis' search does (`crates/ilp/tests/paired.rs`).
    RaceOnEnd,
}

impl Strategy {
    /// The strategy of a problem file naming none: the one that traced the fewest
    /// photons for an answer in its region on every bundled example (BENCHMARKS.md,
    /// "The default strategy"), so no user has to pick the faster search by hand.
    pub const DEFAULT: Strategy = Strategy::RaceOnEnd;

    /// The problem-file spelling.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::RefineOnIntersection => "REFINE_ISOC_ON_INTERSECTION",
            Strategy::RefineOnEnd => "REFINE_ISOC_ON_END",
            Strategy::NoRefine => "NO_REFINE_ISOC",
            Strategy::Paired => "PAIRED_ISOC",
            Strategy::RaceOnEnd => "RACE_ISOC_ON_END",
        }
    }

    /// Whether evaluations keep their groups for paired comparisons, the search
    /// screens the space first, looks at a candidate with n/16, n/4, … before
    /// deciding, and stops when decided.
    pub fn paired(self) -> bool {
        matches!(self, Strategy::Paired | Strategy::RaceOnEnd)
    }

    /// Whether candidates are evaluated in two stages, n then N (§4.7).
    pub fn two_stage(self) -> bool {
        matches!(self, Strategy::RefineOnIntersection | Strategy::Paired)
    }

    /// Every strategy, in the order the documentation gives them.
    pub const ALL: [Strategy; 5] = [
        Strategy::RefineOnIntersection,
        Strategy::RefineOnEnd,
        Strategy::NoRefine,
        Strategy::Paired,
        Strategy::RaceOnEnd,
    ];

    /// Parses the problem-file spelling.
    pub fn parse(s: &str) -> Option<Strategy> {
        Strategy::ALL.into_iter().find(|k| k.name() == s)
    }

    /// The spellings, for messages that list them.
    pub fn names() -> String {
        let names: Vec<&str> = Strategy::ALL.iter().map(|k| k.name()).collect();
        format!(
            "{} or {}",
            names[..names.len() - 1].join(", "),
            names[names.len() - 1]
        )
    }
}

/// `--strategy NAME`: the problem-file spelling, refused with the list.
impl std::str::FromStr for Strategy {
    type Err = UnknownStrategy;

    fn from_str(s: &str) -> Result<Strategy, UnknownStrategy> {
        Strategy::parse(s).ok_or_else(|| UnknownStrategy(s.to_string()))
    }
}

/// A name that is not one of [`Strategy::names`](crate::Strategy::names).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownStrategy(pub String);

impl std::fmt::Display for UnknownStrategy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "'{}' is not a strategy: {}", self.0, Strategy::names())
    }
}

impl std::error::Error for UnknownStrategy {}
