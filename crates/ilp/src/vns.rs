//! The adapted Variable Neighbourhood Search of thesis Algorithms 3.1 and 3.2, made aware
//! of noisy estimates by the ISOC (§3.3.4, §4.6), discretised into cells with a tabu
//! cache (§4.8, §4.9.1), and evaluating in two stages (§4.7).
//!
//! The search knows nothing of photons: it calls an [`Evaluate`] for an estimate of the
//! objective at a configuration with a given sample count, and reports every evaluation
//! to an [`Observer`] (the CSV writer, a progress bar).
//!
//! Steps (Algorithm 3.1 with Algorithm 3.2 inlined):
//! 1. evaluate the initial configuration (the scene as authored, snapped to its cell);
//!    under [`Strategy::Paired`] and [`Strategy::RaceOnEnd`], then screen a
//!    space-filling set of cells (`screen`);
//! 2. r = 0.05; while r < 1: up to I times pick a centre x (a random ISOC member — they
//!    are indistinguishable, so any is "the current solution"), draw x′ ∈ N(x, r), snap
//!    it to its cell; a cell already in the cache costs an iteration but no tracing;
//!    otherwise evaluate it; if it joined the ISOC and beat a member, it is an
//!    improvement: r = 0.05 again; after I tries without one, r += 0.05 (the first
//!    looks of the candidates the walk will draw next are readied side by side when one
//!    leaves cores idle, `walk`, without changing a thing);
//! 3. repeat step 2 until `max_iterations` candidates were drawn (cache hits included,
//!    as in ILPSolver), every cell was evaluated, or the caller asked to stop;
//! 4. with `REFINE_ISOC_ON_END`, re-evaluate the ISOC with N samples and rebuild it;
//!    with `RACE_ISOC_ON_END`, race it to N first (`race`) and rebuild it from the
//!    members that stay.
//!
//! Beyond the thesis, the goal may be minimised or brought to a target ([`Sense`]: the
//! search maximises a score, the goal or minus it or minus its distance to the target),
//! and constraints decide which configurations may join the ISOC at all
//! ([`Feasibility`], one-sided at the run's confidence): an infeasible candidate is
//! out; one whose constraints cannot be decided with n samples but that could join is
//! evaluated with N before it is admitted, and stays out if N does not decide either.
//! The configurations that violate the constraints least are kept, so that a problem
//! with no feasible configuration still says which came closest; until a feasible one
//! is found the search draws around the closest, and coming closer counts as an
//! improvement (a first phase toward feasibility, as in two-phase methods).
//!
//! When some variables are cheap to change ([`Space::with_cheap`]: dimming levels, which
//! the photon evaluator reads from the trace of the same arrangement), every other
//! candidate moves those alone: a second neighbourhood structure, as VNS allows
//! (Mladenović & Hansen 1997), that searches the levels of each arrangement for free.

use crate::cache::{Cache, Entry};
use crate::intention::Feasibility;
use crate::isoc::{Admission, Isoc, Member};
use crate::space::{Cell, Configuration, Space};
use invlight_stats::{Confidence, student_quantile};
use invlight_stats::{SplitMix64, mix, variance_ratio};
use std::collections::HashSet;
use std::time::Instant;

mod evaluation;
mod outcome;
mod race;
mod record;
mod screen;
mod strategy;
mod walk;

pub use evaluation::{Evaluate, Evaluation, Sense, Settings, Verdict};
pub use outcome::{Outcome, SearchError};
pub use record::{Observer, Record, Standing};
pub use strategy::{Strategy, UnknownStrategy};

/// How far below the thesis' fast evaluation n = q·N the first look of
/// [`Strategy::Paired`] and [`Strategy::RaceOnEnd`] is: n/16, two steps of the ladder
/// of [`looks`]. Each look continues the trace of the one before, so a candidate that
/// goes on costs what it would have from n (only the early looks' z grows,
/// [`early_look_z`]), while one far below the ISOC or far from its constraints — most
/// of a walk's — is told so with a sixteenth of n. With the thesis' q = 0.25 (the
/// examples' too) each of those would otherwise cost a quarter of N.
const BELOW_FAST: u64 = 16;

/// The fewest groups at which a sequential search's early look decides: where
/// [`student_quantile`]'s expansion is accurate to 0.5 %. The photon layer's
/// evaluations hold at least 32.
const MIN_LOOK_GROUPS: usize = 10;

/// The sample counts at which a sequential search looks at a candidate before its full
/// evaluation: `first`, 4·first, 16·first, … while below N (`samples` rounds each as
/// the evaluator will). Most candidates are told worse than a member after a few
/// groups; those close to the ISOC go on. A fixed schedule, so the error of the looks
/// is bounded in advance ([`early_look_z`]).
pub fn looks(first: u64, full: u64, samples: impl Fn(u64) -> u64) -> Vec<u64> {
    let mut out = Vec::new();
    let mut m = first;
    while m < full {
        out.push(m);
        m = samples(m.saturating_mul(4));
    }
    out
}

/// The z of each of `early` looks before the full evaluation: the one-sided level
/// α/(4·early), α = 1 − confidence. A candidate as good as a member is wrongly found
/// worse at some early look with probability ≤ α/4 and at the full one (the ISOC's
/// two-sided z, one-sided α/2) with ≤ α/2, so over all looks with ≤ 3α/4 ≤ α by
/// Bonferroni's inequality, whatever the correlation between looks (a fixed schedule
/// of looks with the error spent in parts: Jennison & Turnbull, *Group Sequential
/// Methods with Applications to Clinical Trials*, 2000, §1.3).
pub fn early_look_z(confidence: Confidence, early: usize) -> f64 {
    let alpha = 1.0 - confidence.level();
    invlight_stats::normal_quantile(1.0 - alpha / (4.0 * early.max(1) as f64))
}

/// A search in progress.
pub struct Search<'s> {
    space: &'s Space,
    settings: Settings,
    isoc: Isoc,
    cache: Cache,
    rng: SplitMix64,
    /// Centre of the neighbourhoods while the ISOC is empty.
    start: Configuration,
    /// Next candidate's number.
    iteration: u64,
    evaluations: u64,
    started: bool,
    /// The configurations that violate the constraints least, least first.
    closest: Vec<(f64, Member)>,
    /// Whether `closest` changed since the last report.
    closest_changed: bool,
    /// var(X−Y)/(var X + var Y) of each decided candidate X against the best member Y
    /// then, over their common groups ([`Search::variance_ratio`]).
    ratios: Vec<f64>,
    /// Candidates admitted to the ISOC so far, for the stopping rule.
    admissions: u64,
    /// Points of the global screening drawn so far ([`Search::screen`]).
    screens: u64,
    /// The cells screened, each looked at once.
    screened: HashSet<Cell>,
    /// The best screened configuration that could be feasible, with its score.
    best_screen: Option<(f64, Configuration)>,
    /// Whether some evaluation's goal was distinguishable from 0 (the target is lit).
    lit: bool,
    /// The screening's current round and its permutations, one per coordinate.
    round: Option<(u64, Vec<Vec<u32>>)>,
    /// Structured starts evaluated as candidates right after the initial
    /// configuration, iterations 1, 2, … ([`Space::regular_arrays`]).
    starts: Vec<Configuration>,
    /// The best of them decided feasible ([`Standing::best_start`]).
    best_start: Option<Member>,
}

/// How many of the least-violating configurations a search keeps.
const CLOSEST: usize = 5;

impl<'s> Search<'s> {
    /// A search of `space` from `initial` (snapped to its cell).
    pub fn new(space: &'s Space, settings: Settings, initial: &Configuration) -> Search<'s> {
        let z = settings.confidence.z();
        let rng = SplitMix64::new(mix(settings.seed ^ 0x5EA5_C4F0_0D15_EA5E));
        Search {
            space,
            isoc: if settings.strategy == Strategy::Paired {
                Isoc::paired(z)
            } else {
                Isoc::new(z)
            },
            cache: Cache::default(),
            rng,
            start: space.snap(initial),
            iteration: 0,
            evaluations: 0,
            started: false,
            closest: Vec::new(),
            closest_changed: false,
            ratios: Vec::new(),
            admissions: 0,
            screens: 0,
            screened: HashSet::new(),
            best_screen: None,
            lit: false,
            round: None,
            starts: if settings.strategy.paired() {
                space.regular_arrays(&space.snap(initial))
            } else {
                Vec::new()
            },
            best_start: None,
            settings,
        }
    }

    /// Where the search stands: the ISOC and the configurations closest to feasible
    /// (what a problem without a feasible configuration came closest to).
    pub fn standing(&self) -> Standing<'_> {
        Standing {
            isoc: &self.isoc,
            closest: &self.closest,
            best_start: self.best_start.as_ref(),
        }
    }

    /// The settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The ISOC so far.
    pub fn isoc(&self) -> &Isoc {
        &self.isoc
    }

    /// The median over the candidates decided so far of var(X−Y)/(var X + var Y), X the
    /// candidate and Y the best ISOC member then, from their common groups, with the
    /// number of such pairs; `None` when no evaluation kept its groups (only
    /// [`Strategy::Paired`] and [`Strategy::RaceOnEnd`] keep them). It is what pairing
    /// gains over eq. 3.7: the paired threshold is its square root times eq. 3.7's.
    pub fn variance_ratio(&self) -> Option<(f64, usize)> {
        let mut r = self.ratios.clone();
        r.sort_by(f64::total_cmp);
        let n = r.len();
        (n > 0).then(|| {
            let m = if n % 2 == 1 {
                r[n / 2]
            } else {
                0.5 * (r[n / 2 - 1] + r[n / 2])
            };
            (m, n)
        })
    }

    /// [`Search::variance_ratio`] in words, for the end of a run.
    pub fn paired_note(&self) -> Option<String> {
        self.variance_ratio().map(|(ratio, pairs)| {
            format!(
                "paired comparisons: var(X−Y)/(var X + var Y) = {} (median of {pairs} candidates against the best member)",
                invlight_stats::significant(ratio)
            )
        })
    }

    /// Candidates drawn so far.
    pub fn iteration(&self) -> u64 {
        self.iteration
    }

    /// Evaluations made so far (replayed ones included).
    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// Continues a stopped run from its records (`solutions.csv`): every evaluated cell
    /// goes back into the cache and the ISOC is rebuilt by offering it the rows that
    /// joined it, in order — the same decisions on the same estimates. The search then
    /// goes on from the next iteration with random numbers derived from it.
    pub fn replay(&mut self, records: &[Record]) {
        let mut rebuilt: Option<Isoc> = None;
        for rec in records {
            let cell = self.space.cell(&rec.config);
            let config = self.space.snap(&rec.config);
            let member = self.member(config.clone(), cell.clone(), &rec.evaluation);
            if rec.verdict == Verdict::Final {
                let fresh = rebuilt.get_or_insert_with(|| self.isoc.emptied());
                if !self.invalid(&rec.evaluation)
                    && self.feasibility(&rec.evaluation) == Feasibility::Feasible
                {
                    fresh.admit(member);
                }
            } else {
                if let Some(done) = rebuilt.take() {
                    self.isoc = done;
                }
                match rec.verdict {
                    Verdict::Initial | Verdict::Better | Verdict::Probable => {
                        self.isoc.admit(member);
                    }
                    Verdict::Infeasible | Verdict::Undecided => self.keep_closest(member),
                    Verdict::Screened => self.screened_as(&cell, config.clone(), &rec.evaluation),
                    _ => {}
                }
            }
            self.note_last_look(rec, &config, &cell);
            if rec.iteration == 0 {
                self.start = config;
            }
            self.evaluations += 1;
            self.iteration = self.iteration.max(rec.iteration + 1);
            self.started = true;
            self.lit |= self.lights(&rec.evaluation);
            // A fast estimate is decided by the full one on the next row; without it
            // (a hard stop in between) the cell stays open to be drawn again. A
            // screened cell stays open to the search too.
            if matches!(rec.verdict, Verdict::Refine | Verdict::Screened) {
                continue;
            }
            self.cache.insert(
                cell,
                Entry::Evaluated {
                    estimate: rec.evaluation.goal,
                    verdict: rec.verdict,
                },
            );
        }
        if let Some(done) = rebuilt {
            self.isoc = done;
        }
        self.rng = SplitMix64::new(mix(self.settings.seed ^ mix(self.iteration)));
    }

    /// Runs (or continues) the search until `max_iterations`, exhaustion or the
    /// observer asks to stop; under [`Strategy::Paired`] and [`Strategy::RaceOnEnd`]
    /// also when it is decided.
    ///
    /// The stopping rule (stop when the answer is decided): a sweep is one
    /// pass of Algorithm 3.1's radii from 0.05 to 0.95 without an improvement, I
    /// candidates at each around the ISOC; when a whole sweep admits no candidate to
    /// the ISOC (neither better nor indistinguishable), every neighbourhood size up to
    /// r = 1 was tried around the answer and none changed it, and further candidates are
    /// drawn from the same neighbourhoods. The cells adjacent to the members are then
    /// evaluated (random draws miss them often on fine grids); if none joins either, the
    /// ISOC is a local optimum over its adjacent cells and the search stops. On a lamp-on-a-ceiling problem the thesis'
    /// search found its optimum early and traced on until `maxIterations`.
    pub fn run<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<Outcome, SearchError<E::Error>> {
        if !self.started {
            self.initial(eval, observer)?;
        }
        if !self.structured_starts(eval, observer)? {
            return Ok(Outcome::Interrupted);
        }
        if self.settings.strategy.paired() {
            if !self.screen(eval, observer)? {
                return Ok(Outcome::Interrupted);
            }
            if self.plateau() {
                return Ok(Outcome::Unlit);
            }
        }
        let max = self.settings.max_iterations;
        let tries = self.settings.tries(self.space.dimensions());
        let mut settled = false;
        'vns: while self.iteration < max {
            let admitted = self.admissions;
            // Radius r = k·0.05 for k = 1…19 (Algorithm 3.1), counted in integers.
            let mut k = 1u32;
            while k < 20 {
                if observer.should_stop() {
                    return Ok(Outcome::Interrupted);
                }
                if self.exhausted() {
                    break 'vns;
                }
                if self.iteration >= max {
                    break 'vns;
                }
                match self.first_improvement(k as f64 * 0.05, tries, eval, observer)? {
                    Some(true) => k = 1,
                    Some(false) => k += 1,
                    None => return Ok(Outcome::Interrupted),
                }
            }
            if self.settings.strategy.paired()
                && k == 20
                && self.admissions == admitted
                && !self.isoc.members().is_empty()
            {
                match self.adjacent(eval, observer)? {
                    None => return Ok(Outcome::Interrupted),
                    Some(true) => {}
                    Some(false) => {
                        settled = true;
                        break;
                    }
                }
            }
        }
        let outcome = if self.exhausted() && self.iteration < max {
            Outcome::Exhausted
        } else if settled {
            Outcome::Settled
        } else {
            Outcome::Finished
        };
        let complete = match self.settings.strategy {
            Strategy::RefineOnEnd => {
                self.refine_on_end(eval, observer)?;
                true
            }
            Strategy::RaceOnEnd => self.race(eval, observer)?,
            _ => true,
        };
        Ok(if complete {
            outcome
        } else {
            Outcome::Interrupted
        })
    }

    /// Whether a drawn cell is worth an evaluation: not one already looked at, and
    /// not one the evaluation refuses (cached as refused and reported, so it is never
    /// drawn into an evaluation again). Every way of proposing a cell (regular
    /// arrays, screening, the walks) asks this before it evaluates.
    fn fresh<E: Evaluate, O: Observer>(
        &mut self,
        (iteration, config, cell): (u64, &Configuration, &Cell),
        eval: &E,
        observer: &mut O,
    ) -> bool {
        if self.cache.get(cell).is_some() {
            return false;
        }
        if let Some(why) = eval.refuses(config) {
            self.cache.insert(cell.clone(), Entry::Refused);
            observer.refused(iteration, &why);
            return false;
        }
        true
    }

    fn exhausted(&self) -> bool {
        self.cache.len() as f64 >= self.space.cell_count()
    }

    /// Whether the goal's whole interval lies above the cap (thesis §5.3.4).
    fn invalid(&self, e: &Evaluation) -> bool {
        self.invalid_at(e, self.isoc.z())
    }

    /// Whether the goal's interval at `z` lies above the cap.
    fn invalid_at(&self, e: &Evaluation, z: f64) -> bool {
        self.settings
            .cap
            .is_some_and(|cap| e.goal.interval(z).low > cap)
    }

    /// Whether the constraints hold at the confidence, one-sided.
    fn feasibility(&self, e: &Evaluation) -> Feasibility {
        self.feasibility_at(e, self.settings.confidence.z_one_sided())
    }

    /// Whether the constraints hold at the one-sided `z`.
    fn feasibility_at(&self, e: &Evaluation, z: f64) -> Feasibility {
        Feasibility::all(
            self.settings
                .constraints
                .iter()
                .zip(&e.constraints)
                .map(|(bound, c)| Feasibility::of(c.mean, c.std_error, z, bound)),
        )
    }

    /// How far the means are from meeting the constraints: the largest relative
    /// shortfall (0 when every mean meets its bound).
    fn violation(&self, e: &Evaluation) -> f64 {
        self.settings
            .constraints
            .iter()
            .zip(&e.constraints)
            .map(|(bound, c)| {
                let short = -bound.inside(c.mean);
                (short / bound.limit().abs().max(f64::MIN_POSITIVE)).max(0.0)
            })
            .fold(0.0, f64::max)
    }

    /// A member of the ISOC (or of the closest) for an evaluation.
    fn member(&self, config: Configuration, cell: Cell, e: &Evaluation) -> Member {
        Member {
            config: e.solved.clone().unwrap_or(config),
            cell,
            estimate: self.settings.sense.score(&e.goal),
            groups: self.settings.sense.score_groups(&e.groups),
            evaluation: Evaluation {
                groups: Vec::new(),
                solved: None,
                ..e.clone()
            },
        }
    }

    /// Keeps a structured start's last look (the row that decided it, whether after
    /// its decisive evaluation or an earlier look) as [`Standing::best_start`] when it
    /// is feasible and scores above the one kept. The search and a replay of its rows
    /// see the same rows, so they keep the same start.
    fn note_last_look(&mut self, record: &Record, config: &Configuration, cell: &Cell) {
        let e = &record.evaluation;
        if matches!(
            record.verdict,
            Verdict::Refine | Verdict::Screened | Verdict::Final
        ) || record.iteration == 0
            || record.iteration > self.starts.len() as u64
            || self.invalid(e)
            || self.feasibility(e) != Feasibility::Feasible
        {
            return;
        }
        let member = self.member(config.clone(), cell.clone(), e);
        if self
            .best_start
            .as_ref()
            .is_none_or(|b| member.estimate.mean > b.estimate.mean)
        {
            self.best_start = Some(member);
        }
    }

    /// Remembers a configuration that misses a constraint among the closest.
    fn keep_closest(&mut self, member: Member) {
        let v = self.violation(&member.evaluation);
        if self.closest.iter().any(|(_, m)| m.cell == member.cell) {
            self.closest.retain(|(_, m)| m.cell != member.cell);
        }
        let at = self.closest.partition_point(|(w, _)| *w <= v);
        if at < CLOSEST {
            self.closest.insert(at, (v, member));
            self.closest.truncate(CLOSEST);
            self.closest_changed = true;
        }
    }

    /// The verdict of a full evaluation: invalid, infeasible, undecided, or what the
    /// ISOC made of it (`initial` for the first configuration).
    fn decide(
        &mut self,
        config: &Configuration,
        cell: &Cell,
        e: &Evaluation,
        initial: bool,
    ) -> Verdict {
        if self.invalid(e) {
            return Verdict::Invalid;
        }
        let member = self.member(config.clone(), cell.clone(), e);
        if let Some(r) = self
            .isoc
            .best()
            .and_then(|b| variance_ratio(&member.groups, &b.groups))
        {
            self.ratios.push(r);
        }
        match self.feasibility(e) {
            Feasibility::Infeasible => {
                self.keep_closest(member);
                return Verdict::Infeasible;
            }
            Feasibility::Undecided => {
                self.keep_closest(member);
                return Verdict::Undecided;
            }
            Feasibility::Feasible => {}
        }
        match self.isoc.admit(member) {
            _ if initial => Verdict::Initial,
            Admission::Below => Verdict::Bad,
            Admission::Beaten => Verdict::Beaten,
            Admission::Joined { removed, was_empty } => {
                self.admissions += 1;
                if removed > 0 || was_empty {
                    Verdict::Better
                } else {
                    Verdict::Probable
                }
            }
        }
    }

    /// Whether an estimate made with fewer than N samples must be made again with N
    /// before deciding: its constraints are undecided while it could join the ISOC.
    fn undecided_but_promising(&self, e: &Evaluation) -> bool {
        !self.invalid(e)
            && self.feasibility(e) == Feasibility::Undecided
            && self.isoc.reaches(&self.settings.sense.score(&e.goal))
    }

    /// Evaluates `config` with `photons` samples, and again with `full` when the first
    /// leaves its constraints undecided but it could join (the first then is reported
    /// as `refine`); `lead` is added to the first's time (see [`Search::candidate`]).
    /// Returns the last evaluation and its time.
    fn evaluate_deciding<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
        (iteration, config, cell): (u64, &Configuration, &Cell),
        (photons, full, lead): (u64, u64, f64),
    ) -> Result<(Evaluation, f64), SearchError<E::Error>> {
        let (e, seconds) = self.evaluate(eval, config, photons)?;
        let seconds = seconds + lead;
        if photons >= full || !self.undecided_but_promising(&e) {
            return Ok((e, seconds));
        }
        let record = Record {
            iteration,
            config: config.clone(),
            evaluation: e,
            seconds,
            verdict: Verdict::Refine,
        };
        self.report(observer, cell.clone(), record)?;
        self.evaluate(eval, config, full)
    }

    /// Step 1: the initial configuration, with N samples under
    /// `REFINE_ISOC_ON_INTERSECTION` (so the first SIISOC is precise), n otherwise.
    fn initial<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<(), SearchError<E::Error>> {
        let (fast, full) = self.settings.sample_counts(eval);
        let photons = if self.settings.strategy.two_stage() {
            full
        } else {
            fast
        };
        let config = self.start.clone();
        let cell = self.space.cell(&config);
        let (evaluation, seconds) =
            self.evaluate_deciding(eval, observer, (0, &config, &cell), (photons, full, 0.0))?;
        let verdict = self.decide(&config, &cell, &evaluation, true);
        self.started = true;
        self.iteration = 1;
        let record = Record {
            iteration: 0,
            config,
            evaluation,
            seconds,
            verdict,
        };
        self.report(observer, cell, record)
    }

    /// The structured starts not evaluated yet, each as a candidate of its own
    /// iteration (a regular array of the interchangeable lamps, [`Space::regular_arrays`]):
    /// a designer's first layout is among the configurations the walk compares, and it
    /// starts from the best of them. Each is evaluated at once with the decisive
    /// count, without the looks before it: a look of few photons reads a uniformity
    /// low (the least of noisy cells is biased down), its least-power levels then ask
    /// for more light than the array needs, and the start would lose to the incumbent
    /// on a power it would not draw. The starts are few, so this costs little.
    /// `false` when the observer asked to stop.
    fn structured_starts<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<bool, SearchError<E::Error>> {
        let (_, decisive) = self.schedule(eval);
        while let Some(config) = self.starts.get(self.iteration as usize - 1).cloned() {
            if observer.should_stop() {
                return Ok(false);
            }
            if self.iteration >= self.settings.max_iterations {
                break;
            }
            let cell = self.space.cell(&config);
            let iteration = self.iteration;
            self.iteration += 1;
            observer.iteration(self.iteration);
            if !self.fresh((iteration, &config, &cell), eval, observer) {
                continue;
            }
            self.candidate_after(
                &[],
                decisive,
                (iteration, config, cell),
                0.0,
                eval,
                observer,
            )?;
        }
        Ok(true)
    }

    /// The sample counts of a candidate's looks before its decisive evaluation, and
    /// that evaluation's count (before any re-evaluation with N to decide its
    /// constraints): n under `REFINE_ISOC_ON_INTERSECTION` then N; n/16, n/4, n, …
    /// then N under [`Strategy::Paired`]; n/16, n/4 then n under
    /// [`Strategy::RaceOnEnd`] (whose ISOC is raced to N at the end); n or N alone
    /// otherwise.
    fn schedule<E: Evaluate>(&self, eval: &E) -> (Vec<u64>, u64) {
        let (n, full) = self.settings.sample_counts(eval);
        let looks = match self.settings.strategy {
            Strategy::Paired => looks(eval.samples(n / BELOW_FAST), full, |m| eval.samples(m)),
            Strategy::RaceOnEnd => looks(eval.samples(n / BELOW_FAST), n, |m| eval.samples(m)),
            Strategy::RefineOnIntersection if n < full => vec![n],
            _ => Vec::new(),
        };
        let decisive = if self.settings.strategy.two_stage() {
            full
        } else {
            n
        };
        (looks, decisive)
    }

    /// The samples of a candidate's first evaluation, the one the walk readies ahead.
    fn first_look<E: Evaluate>(&self, eval: &E) -> u64 {
        let (looks, decisive) = self.schedule(eval);
        looks.first().copied().unwrap_or(decisive)
    }

    /// Evaluates a new cell, in two stages under `REFINE_ISOC_ON_INTERSECTION` (§4.7);
    /// `lead` is the time spent readying its first evaluation ahead (side by side with
    /// others, [`Evaluate::prepare`]), counted in that evaluation's seconds.
    fn candidate<E: Evaluate, O: Observer>(
        &mut self,
        at: (u64, Configuration, Cell),
        lead: f64,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<Verdict, SearchError<E::Error>> {
        let (looks, photons) = self.schedule(eval);
        self.candidate_after(&looks, photons, at, lead, eval, observer)
    }

    /// A candidate judged at each of `looks` in turn, then, when none decided it, with
    /// `photons` ([`Search::candidate`]).
    fn candidate_after<E: Evaluate, O: Observer>(
        &mut self,
        looks: &[u64],
        photons: u64,
        (iteration, config, cell): (u64, Configuration, Cell),
        mut lead: f64,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<Verdict, SearchError<E::Error>> {
        let (fast_n, full) = self.settings.sample_counts(eval);
        let z_early = early_look_z(self.settings.confidence, looks.len());
        let sequential = self.settings.strategy.paired();
        for &look in looks {
            let (fast, seconds) = self.evaluate(eval, &config, look)?;
            let seconds = seconds + std::mem::take(&mut lead);
            // The thesis' one fast look decides at the ISOC's own levels; a sequential
            // search's several looks each at the early-look level, so that together
            // they wrongly reject a candidate no more often than the bound promises,
            // and by Student's t, whose quantile is accurate from ten groups on
            // (`student_quantile`): a look of fewer decides nothing.
            let groups = fast.groups.len();
            let (z_two, z_one) = if sequential {
                let t = match groups {
                    0 => z_early,
                    g => student_quantile(z_early, g as u64 - 1),
                };
                (t, t)
            } else {
                (self.isoc.z(), self.settings.confidence.z_one_sided())
            };
            let verdict = if sequential && (1..MIN_LOOK_GROUPS).contains(&groups) {
                None
            } else if self.invalid_at(&fast, z_two) {
                Some(Verdict::Invalid)
            } else if self.feasibility_at(&fast, z_one) == Feasibility::Infeasible {
                self.keep_closest(self.member(config.clone(), cell.clone(), &fast));
                Some(Verdict::Infeasible)
            } else if !self
                .isoc
                .reaches_at(&self.settings.sense.score(&fast.goal), z_two)
            {
                Some(Verdict::Bad)
            } else if sequential
                && self
                    .isoc
                    .screens_out(&self.member(config.clone(), cell.clone(), &fast), z_early)
            {
                Some(Verdict::Beaten)
            } else {
                None
            };
            // A score without groups (a uniformity, a power, a target) cannot be
            // screened by pairs, but its looks below n may still find it below the
            // SIISOC or infeasible; from n on, only N decides.
            let pairs = !self.settings.sense.score_groups(&fast.groups).is_empty();
            let record = Record {
                iteration,
                config: config.clone(),
                evaluation: fast,
                seconds,
                verdict: verdict.unwrap_or(Verdict::Refine),
            };
            self.report(observer, cell.clone(), record)?;
            if let Some(v) = verdict {
                return Ok(v);
            }
            if !pairs && look >= fast_n {
                break;
            }
        }
        let (evaluation, seconds) = self.evaluate_deciding(
            eval,
            observer,
            (iteration, &config, &cell),
            (photons, full, lead),
        )?;
        let verdict = self.decide(&config, &cell, &evaluation, false);
        let record = Record {
            iteration,
            config,
            evaluation,
            seconds,
            verdict,
        };
        self.report(observer, cell, record)?;
        Ok(verdict)
    }

    /// Step 4 (`REFINE_ISOC_ON_END`): re-evaluates every member with N and rebuilds the
    /// ISOC from the new estimates ([`Search::finish`]).
    fn refine_on_end<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<(), SearchError<E::Error>> {
        let (fast, full) = self.settings.sample_counts(eval);
        if fast >= full {
            return Ok(());
        }
        let members = self.isoc.members().to_vec();
        self.finish(members, eval, observer)
    }

    /// Re-evaluates `members` (ISOC members, oldest first) with N and rebuilds the ISOC
    /// from the new estimates alone, in that order; a member whose constraints N no
    /// longer finds met leaves.
    fn finish<E: Evaluate, O: Observer>(
        &mut self,
        members: Vec<Member>,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<(), SearchError<E::Error>> {
        let full = self.settings.sample_counts(eval).1;
        self.isoc = self.isoc.emptied();
        for m in members {
            let (evaluation, seconds) = self.evaluate(eval, &m.config, full)?;
            if !self.invalid(&evaluation) && self.feasibility(&evaluation) == Feasibility::Feasible
            {
                self.isoc
                    .admit(self.member(m.config.clone(), m.cell.clone(), &evaluation));
            }
            let record = Record {
                iteration: self.iteration,
                config: m.config,
                evaluation,
                seconds,
                verdict: Verdict::Final,
            };
            self.report(observer, m.cell, record)?;
        }
        Ok(())
    }

    fn evaluate<E: Evaluate>(
        &mut self,
        eval: &mut E,
        config: &Configuration,
        photons: u64,
    ) -> Result<(Evaluation, f64), SearchError<E::Error>> {
        let t = Instant::now();
        let mut e = eval
            .evaluate(config, photons)
            .map_err(SearchError::Evaluate)?;
        if !self.settings.strategy.paired() {
            e.groups = Vec::new();
        }
        self.evaluations += 1;
        Ok((e, t.elapsed().as_secs_f64()))
    }

    /// Remembers the cell's estimate and verdict and tells the observer. The record
    /// goes without its groups: only ISOC members need them, and they keep their own.
    fn report<O: Observer, X>(
        &mut self,
        observer: &mut O,
        cell: Cell,
        mut record: Record,
    ) -> Result<(), SearchError<X>> {
        record.evaluation.groups = Vec::new();
        if let Some(config) = record.evaluation.solved.take() {
            record.config = config;
        }
        let (estimate, verdict) = (record.evaluation.goal, record.verdict);
        self.lit |= self.lights(&record.evaluation);
        self.note_last_look(&record, &record.config, &cell);
        if verdict != Verdict::Screened {
            self.cache
                .insert(cell, Entry::Evaluated { estimate, verdict });
        }
        let changed = matches!(
            verdict,
            Verdict::Initial | Verdict::Better | Verdict::Probable | Verdict::Final
        ) || (std::mem::take(&mut self.closest_changed)
            && self.isoc.members().is_empty());
        observer
            .evaluated(&record, self.standing(), changed)
            .map_err(SearchError::Output)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::{Domain, Variable};
    use invlight_stats::Estimate;

    struct Slope;
    impl Evaluate for Slope {
        type Error = ();
        fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Evaluation, ()> {
            Ok(Evaluation::of(Estimate {
                mean: c.coords[0],
                std_error: 0.5 / (photons as f64).sqrt(),
                samples: photons,
            }))
        }
    }

    struct Log(Vec<Record>);
    impl Observer for Log {
        fn evaluated(&mut self, r: &Record, _: Standing<'_>, _: bool) -> std::io::Result<()> {
            self.0.push(r.clone());
            Ok(())
        }
    }

    #[test]
    fn a_refine_row_without_its_full_row_leaves_the_cell_open() {
        let space = Space::new(
            vec![Variable {
                id: "v".into(),
                domain: Domain::Segment { min: 0.0, max: 1.0 },
            }],
            &[50],
        );
        let settings = Settings {
            max_iterations: 100,
            photons: 4096,
            fast_quality: 0.25,
            strategy: Strategy::RefineOnIntersection,
            confidence: Confidence::DEFAULT,
            cap: None,
            sense: Sense::Maximize,
            constraints: Vec::new(),
            seed: 3,
            tries_per_radius: None,
        };
        let start = Configuration { coords: vec![0.0] };
        let mut search = Search::new(&space, settings.clone(), &start);
        let mut log = Log(Vec::new());
        search.run(&mut Slope, &mut log).unwrap();
        let i = log
            .0
            .iter()
            .position(|r| r.verdict == Verdict::Refine)
            .expect("an increasing slope refines its improvements");
        let cell = space.cell(&log.0[i].config);
        let mut cut = Search::new(&space, settings.clone(), &start);
        cut.replay(&log.0[..=i]);
        assert!(cut.cache.get(&cell).is_none());
        assert_eq!(cut.evaluations(), i as u64 + 1);
        let mut whole = Search::new(&space, settings, &start);
        whole.replay(&log.0[..=i + 1]);
        assert!(whole.cache.get(&cell).is_some());
    }
}
