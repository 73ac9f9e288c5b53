//! What the search is told of a configuration and what it decides of it: the goal's
//! sense, an evaluation's estimates, the verdict, the search's settings, and the
//! evaluation function it is generic over (tested without photons).

use super::Strategy;
use crate::intention::Bound;
use crate::space::Configuration;
use invlight_stats::{Confidence, Estimate};

/// What the search decided about an evaluation (the CSV's `verdict` column).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The initial configuration, valid.
    Initial,
    /// Joined the ISOC and beat at least one member (or was the first valid one).
    Better,
    /// Joined the ISOC, indistinguishable from every member.
    Probable,
    /// Case A: its interval lies below the SIISOC.
    Bad,
    /// Reaches the SIISOC but a member is better by eq. 3.7.
    Beaten,
    /// Its interval lies entirely above the objective's cap.
    Invalid,
    /// A constraint is violated at the confidence.
    Infeasible,
    /// Its constraints cannot be decided even with N samples.
    Undecided,
    /// A fast estimate that reached the SIISOC: the next row re-evaluates it with N.
    Refine,
    /// `REFINE_ISOC_ON_END` and `RACE_ISOC_ON_END`: an ISOC member re-evaluated with
    /// N; the final ISOC is rebuilt from these rows.
    Final,
    /// The global screening of [`Strategy::Paired`](crate::Strategy::Paired) and [`Strategy::RaceOnEnd`](crate::Strategy::RaceOnEnd): a cell
    /// of a space-filling set looked at once with the fewest samples, not offered to the
    /// ISOC (the search may evaluate it again as a candidate).
    Screened,
}

impl Verdict {
    const ALL: [Verdict; 11] = [
        Verdict::Initial,
        Verdict::Better,
        Verdict::Probable,
        Verdict::Bad,
        Verdict::Beaten,
        Verdict::Invalid,
        Verdict::Infeasible,
        Verdict::Undecided,
        Verdict::Refine,
        Verdict::Final,
        Verdict::Screened,
    ];

    /// The CSV spelling.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Initial => "initial",
            Verdict::Better => "better",
            Verdict::Probable => "probable",
            Verdict::Bad => "bad",
            Verdict::Beaten => "beaten",
            Verdict::Invalid => "invalid",
            Verdict::Infeasible => "infeasible",
            Verdict::Undecided => "undecided",
            Verdict::Refine => "refine",
            Verdict::Final => "final",
            Verdict::Screened => "screened",
        }
    }

    /// Parses the CSV spelling.
    pub fn parse(s: &str) -> Option<Verdict> {
        Verdict::ALL.into_iter().find(|v| v.name() == s)
    }
}

/// Which way the goal is better.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sense {
    /// The larger the better (`maximizeRadiance`, `maximizeUniformity`).
    Maximize,
    /// The smaller the better (`minimizeRadiance`, `minimizePower`).
    Minimize,
    /// The closer to this value the better (`targetRadiance`).
    Target(f64),
}

impl Sense {
    /// The score the search maximises for a goal estimate: the goal, minus it, or
    /// minus its distance |E − T| to the target, each with the goal's standard error
    /// (for a target, |E − T|'s first-order error; its interval is folded at T).
    pub fn score(self, goal: &Estimate) -> Estimate {
        let mean = match self {
            Sense::Maximize => goal.mean,
            Sense::Minimize => -goal.mean,
            Sense::Target(t) => -(goal.mean - t).abs(),
        };
        Estimate { mean, ..*goal }
    }

    /// The groups' scores ([`Evaluation::groups`](crate::Evaluation::groups)) where the score is linear in the
    /// goal — the goal or minus it — so that the mean of the groups' scores is the
    /// score; none for a target, whose |E − T| of a group's E is not a group of |Ē − T|.
    pub fn score_groups(self, groups: &[f64]) -> Vec<f64> {
        match self {
            Sense::Maximize => groups.to_vec(),
            Sense::Minimize => groups.iter().map(|g| -g).collect(),
            Sense::Target(_) => Vec::new(),
        }
    }
}

/// What one evaluation estimated: the goal, and each constraint's quantity in the
/// order of [`Settings::constraints`](crate::Settings::constraints).
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// The goal's quantity (lx, U0, lm), not its score.
    pub goal: Estimate,
    /// The constrained quantities.
    pub constraints: Vec<Estimate>,
    /// The goal as each independent group of samples estimates it, in group order
    /// (their mean is `goal.mean`); group g of every configuration uses the same random
    /// numbers, so two configurations are compared by their groups' paired differences
    /// ([`Strategy::Paired`](crate::Strategy::Paired)). Empty when the goal is no mean of groups (a uniformity
    /// ratio, a power) or the evaluator does not keep them: eq. 3.7 decides then.
    pub groups: Vec<f64>,
    /// The configuration evaluated, when the evaluator chose the values of the space's
    /// solved variables itself ([`Space::with_solved`](crate::Space::with_solved): the least-power levels of the
    /// candidate's arrangement): the search records and keeps this one in place of
    /// the candidate it asked for.
    pub solved: Option<Configuration>,
}

impl Evaluation {
    /// An evaluation of a problem without constraints.
    pub fn of(goal: Estimate) -> Evaluation {
        Evaluation {
            goal,
            constraints: Vec::new(),
            groups: Vec::new(),
            solved: None,
        }
    }
}

/// Search parameters (problem file `<objectives>` plus invlight's additions).
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Candidates drawn before stopping (`maxIterations`), the initial one included.
    pub max_iterations: u64,
    /// N, samples (photons) of a full evaluation.
    pub photons: u64,
    /// q of §4.7 (`fastEvaluationQuality`): a fast evaluation uses n = q·N samples.
    pub fast_quality: f64,
    /// When to use N.
    pub strategy: Strategy,
    /// Confidence 1 − α of intervals and comparisons (the thesis fixed 95 %).
    pub confidence: Confidence,
    /// `maxRadiosity`: a configuration whose interval lies entirely above it is invalid.
    pub cap: Option<f64>,
    /// Which way the goal is better.
    pub sense: Sense,
    /// The bounds of the constraints, in the order evaluations give their estimates.
    pub constraints: Vec<Bound>,
    /// Seed of the search's own random numbers.
    pub seed: u64,
    /// I of Algorithm 3.2, tries per radius; `None`: 4 per dimension, at least 8.
    pub tries_per_radius: Option<u32>,
}

impl Settings {
    /// n and N, the samples of a fast and of a full evaluation as `eval` will take
    /// them ([`Evaluate::samples`](crate::Evaluate::samples): the photon tracer traces whole groups, at least
    /// 2 048 photons): n from q·N rounded up, never more than N.
    pub fn sample_counts<E: Evaluate>(&self, eval: &E) -> (u64, u64) {
        let full = eval.samples(self.photons);
        let fast = eval.samples((self.fast_quality * self.photons as f64).ceil() as u64);
        (fast.min(full), full)
    }

    /// I for a space of `dimensions` coordinates.
    pub fn tries(&self, dimensions: usize) -> u32 {
        self.tries_per_radius
            .unwrap_or((4 * dimensions as u32).max(8))
            .max(1)
    }
}

/// Estimates of the goal and the constraints at a configuration with a given number of
/// samples.
pub trait Evaluate {
    /// Why an evaluation failed.
    type Error;
    /// Estimates the goal and constraints at `config` from `photons` samples.
    /// Evaluations with the same sample count should share random numbers (common
    /// random numbers).
    fn evaluate(&mut self, config: &Configuration, photons: u64)
    -> Result<Evaluation, Self::Error>;

    /// Evaluates each of `configs` with `photons` samples, as [`Evaluate::evaluate`](crate::Evaluate::evaluate)
    /// would one after another and with the same numbers, after readying them all at
    /// once ([`Evaluate::prepare`](crate::Evaluate::prepare)).
    fn evaluate_all(
        &mut self,
        configs: &[Configuration],
        photons: u64,
    ) -> Vec<Result<Evaluation, Self::Error>> {
        self.prepare(configs, photons);
        configs.iter().map(|c| self.evaluate(c, photons)).collect()
    }

    /// Readies evaluations of `configs` with `photons` samples that [`Evaluate::evaluate`](crate::Evaluate::evaluate)
    /// may be asked for next: an evaluator that can trace several at once on all cores
    /// does. The search may go on to ask for only some of them, in their order, or for
    /// none (the walk readies the candidates it will draw if none of them changes its
    /// course): readying must change neither what
    /// `evaluate` returns nor the work it reports, so the search's results do not
    /// depend on the thread count or on how far ahead it readied.
    fn prepare(&mut self, _configs: &[Configuration], _photons: u64) {}

    /// How many evaluations of `photons` samples [`Evaluate::prepare`](crate::Evaluate::prepare) would trace side
    /// by side to keep every core busy: the walk readies that many candidates ahead
    /// (1, the default: none ahead).
    fn side_by_side(&self, _photons: u64) -> usize {
        1
    }

    /// The samples an evaluation asked for `requested` really takes (the photon tracer
    /// rounds up to whole groups and a minimum): the search sizes its evaluations by
    /// it, so the two layers never disagree about what a fast evaluation is.
    fn samples(&self, requested: u64) -> u64 {
        requested.max(1)
    }

    /// Why `config` must not be evaluated at all (it puts an object outside the
    /// scene), or `None`. A refused candidate costs an iteration and no samples.
    fn refuses(&self, _config: &Configuration) -> Option<String> {
        None
    }
}
