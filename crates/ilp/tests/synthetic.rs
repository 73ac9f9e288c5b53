//! The search on synthetic noisy functions with known optima (1-D, 2-D,
//! several variables, plateaus, a cap). The noise is Gaussian with a known standard
//! error σ = σ₁/√N that the estimate reports, drawn from a stream keyed by the
//! configuration, so every test is reproducible.

use glam::DVec3;
use invlight_ilp::{
    ArrayDomain, ArrayShape, Bound, Cell, Confidence, Configuration, Domain, Estimate, Evaluate,
    Evaluation, Hemisphere, Isoc, Observer, Outcome, Parallelogram, Record, Search, Sense,
    Settings, Space, Standing, Strategy, Variable, Verdict,
};
use invlight_stats::{SplitMix64, mix};
use std::collections::HashSet;

/// A constrained quantity: g(x) with its own noise σ₁/√N.
type Quantity = (Box<dyn Fn(&[f64]) -> f64>, f64);

/// f(x) plus N(0, σ₁²/N) noise, and constrained quantities likewise.
struct Noisy<F: Fn(&[f64]) -> f64> {
    f: F,
    sigma1: f64,
    seed: u64,
    constraints: Vec<Quantity>,
    /// (cell coordinates as bits, photons) already evaluated: no cell twice per N.
    seen: HashSet<(Vec<u64>, u64)>,
}

impl<F: Fn(&[f64]) -> f64> Noisy<F> {
    fn new(f: F, sigma1: f64) -> Self {
        Noisy {
            f,
            sigma1,
            seed: 99,
            constraints: Vec::new(),
            seen: HashSet::new(),
        }
    }

    fn with(mut self, g: impl Fn(&[f64]) -> f64 + 'static, sigma1: f64) -> Self {
        self.constraints.push((Box::new(g), sigma1));
        self
    }
}

/// A draw of N(0, 1) from a stream keyed by `h`.
fn gaussian(h: u64) -> f64 {
    let mut rng = SplitMix64::new(h);
    // Box–Muller.
    let (u1, u2) = (1.0 - rng.next_f64(), rng.next_f64());
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

impl<F: Fn(&[f64]) -> f64> Evaluate for Noisy<F> {
    type Error = String;
    fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Evaluation, String> {
        let bits: Vec<u64> = c.coords.iter().map(|x| x.to_bits()).collect();
        if !self.seen.insert((bits, photons)) {
            return Err(format!("{:?} traced twice with {photons}", c.coords));
        }
        Ok(self.estimate(c, photons))
    }
}

impl<F: Fn(&[f64]) -> f64> Noisy<F> {
    /// The evaluation at `c` with `photons`: a function of the two and the seed alone.
    fn estimate(&self, c: &Configuration, photons: u64) -> Evaluation {
        let h = c
            .coords
            .iter()
            .map(|x| x.to_bits())
            .fold(mix(self.seed ^ photons), |h, b| mix(h ^ b));
        // The goal draws from the stream h itself, each constraint from its own.
        let noisy = |value: f64, sigma1: f64, k: u64| {
            let se = sigma1 / (photons as f64).sqrt();
            let g = if k == 0 {
                gaussian(h)
            } else {
                gaussian(mix(h ^ k))
            };
            Estimate {
                mean: value + se * g,
                std_error: se,
                samples: photons,
            }
        };
        Evaluation {
            goal: noisy((self.f)(&c.coords), self.sigma1, 0),
            constraints: self
                .constraints
                .iter()
                .enumerate()
                .map(|(k, (g, s))| noisy(g(&c.coords), *s, k as u64 + 1))
                .collect(),
            groups: Vec::new(),
            solved: None,
        }
    }
}

/// Every record, and a stop asked for (as Ctrl-C does) once `stop_after` are in.
#[derive(Default)]
struct Log {
    records: Vec<Record>,
    stop_after: Option<usize>,
}

impl Observer for Log {
    fn evaluated(&mut self, r: &Record, _: Standing<'_>, _: bool) -> std::io::Result<()> {
        self.records.push(r.clone());
        Ok(())
    }

    fn should_stop(&mut self) -> bool {
        self.stop_after.is_some_and(|n| self.records.len() >= n)
    }
}

fn settings(max_iterations: u64, strategy: Strategy) -> Settings {
    Settings {
        max_iterations,
        photons: 10_000,
        fast_quality: 0.25,
        strategy,
        confidence: Confidence::DEFAULT,
        cap: None,
        sense: Sense::Maximize,
        constraints: Vec::new(),
        seed: 7,
        tries_per_radius: None,
    }
}

fn segment(id: &str) -> Variable {
    Variable {
        id: id.into(),
        domain: Domain::Segment { min: 0.0, max: 1.0 },
    }
}

fn rectangle(id: &str, w: f64, h: f64) -> Variable {
    let rect = Parallelogram::from_corners(
        DVec3::ZERO,
        [
            DVec3::new(w, 0.0, 0.0),
            DVec3::new(w, h, 0.0),
            DVec3::new(0.0, h, 0.0),
        ],
    )
    .unwrap();
    Variable {
        id: id.into(),
        domain: Domain::Parallelogram(rect),
    }
}

fn run<F: Fn(&[f64]) -> f64>(
    space: &Space,
    settings: Settings,
    start: Vec<f64>,
    eval: &mut Noisy<F>,
) -> (Isoc, Vec<Record>, Outcome) {
    let mut search = Search::new(space, settings, &Configuration { coords: start });
    let mut log = Log::default();
    let outcome = search.run(eval, &mut log).unwrap();
    (search.isoc().clone(), log.records, outcome)
}

/// The optimum's cell is a member, and every member is statistically as good as the
/// best member's true value: f(best) − f(m) ≤ 2·z·sqrt(σm² + σbest²) (each estimate
/// within z·σ of its truth and the two indistinguishable).
fn check_optimum<F: Fn(&[f64]) -> f64>(space: &Space, isoc: &Isoc, optimum: &[f64], f: &F) {
    let want = space.cell(&Configuration {
        coords: optimum.to_vec(),
    });
    let cells: Vec<&Cell> = isoc.members().iter().map(|m| &m.cell).collect();
    assert!(
        cells.contains(&&want),
        "optimum cell {want:?} not in ISOC {cells:?}"
    );
    let truth = |m: &invlight_ilp::Member| f(&m.config.coords);
    let best = isoc
        .members()
        .iter()
        .max_by(|a, b| truth(a).total_cmp(&truth(b)))
        .unwrap();
    for m in isoc.members() {
        let bound = 2.0
            * isoc.z()
            * (m.estimate.std_error.powi(2) + best.estimate.std_error.powi(2)).sqrt();
        assert!(
            truth(best) - truth(m) <= bound,
            "{:?} too far below the best",
            m.config
        );
    }
}

#[test]
fn one_dimension_peak() {
    let f = |x: &[f64]| 10.0 - 40.0 * (x[0] - 0.43).powi(2);
    let space = Space::new(vec![segment("c")], &[20]);
    let mut eval = Noisy::new(f, 5.0);
    let (isoc, records, outcome) = run(
        &space,
        settings(150, Strategy::RefineOnIntersection),
        vec![0.95],
        &mut eval,
    );
    assert_eq!(outcome, Outcome::Exhausted, "20 cells, 150 candidates");
    check_optimum(&space, &isoc, &[0.43], &f);
    assert_eq!(records[0].verdict, Verdict::Initial);
    assert_eq!(records[0].iteration, 0);
    for m in isoc.members() {
        assert_eq!(m.estimate.samples, 10_000, "members are refined to N");
    }
}

#[test]
fn two_dimensions_on_a_rectangle() {
    // A 2 m × 1 m rectangle; optimum at (1.5 m, 0.2 m), i.e. (s, t) = (0.75, 0.2).
    let f = |x: &[f64]| 100.0 - 30.0 * ((2.0 * x[0] - 1.5).powi(2) + (x[1] - 0.2).powi(2));
    let space = Space::new(vec![rectangle("lamp", 2.0, 1.0)], &[10]);
    let mut eval = Noisy::new(f, 50.0);
    let (isoc, _, _) = run(
        &space,
        settings(400, Strategy::RefineOnIntersection),
        vec![0.0, 1.0],
        &mut eval,
    );
    check_optimum(&space, &isoc, &[0.75, 0.2], &f);
}

#[test]
fn several_variables() {
    // Position (2), colour (1) and sun (2) with a separable quadratic peak.
    let opt = [0.33, 0.61, 0.72, 0.3, 0.55];
    let f = move |x: &[f64]| {
        50.0 - x
            .iter()
            .zip(&opt)
            .map(|(a, b)| 40.0 * (a - b).powi(2))
            .sum::<f64>()
    };
    let space = Space::new(
        vec![
            rectangle("chair", 1.0, 1.0),
            segment("walls"),
            Variable {
                id: "sun".into(),
                domain: Domain::Hemisphere(Hemisphere::new(DVec3::Z)),
            },
        ],
        &[8],
    );
    let mut eval = Noisy::new(f, 10.0);
    let (isoc, _, _) = run(
        &space,
        settings(3000, Strategy::RefineOnIntersection),
        vec![0.0, 0.0, 0.0, 0.9, 0.9],
        &mut eval,
    );
    check_optimum(&space, &isoc, &opt, &f);
}

#[test]
fn plateau_is_found_whole() {
    // 1 on [0.6, 0.8] (cells 12–15 of 20), a slope below 0.5 elsewhere.
    let f = |x: &[f64]| {
        if (0.6..0.8).contains(&x[0]) {
            1.0
        } else {
            0.5 * (1.0 - (x[0] - 0.7).abs())
        }
    };
    let space = Space::new(vec![segment("c")], &[20]);
    let mut eval = Noisy::new(f, 2.0);
    let (isoc, _, outcome) = run(
        &space,
        settings(300, Strategy::RefineOnIntersection),
        vec![0.0],
        &mut eval,
    );
    assert_eq!(outcome, Outcome::Exhausted, "20 cells, 300 candidates");
    let mut cells: Vec<u32> = isoc.members().iter().map(|m| m.cell.0[0]).collect();
    cells.sort();
    assert_eq!(cells, vec![12, 13, 14, 15]);
}

#[test]
fn cap_makes_brighter_cells_invalid() {
    // f = 10·V under a cap of 6.4: the best valid cell is [0.60, 0.65) (centre 6.25 ± 0.1);
    // the next, 6.75 ± 0.1, has its interval [6.55, 6.95] entirely above the cap.
    let f = |x: &[f64]| 10.0 * x[0];
    let space = Space::new(vec![segment("walls")], &[20]);
    let mut eval = Noisy::new(f, 10.0);
    let mut s = settings(200, Strategy::RefineOnIntersection);
    s.cap = Some(6.4);
    let (isoc, records, _) = run(&space, s, vec![0.99], &mut eval);
    assert_eq!(
        records[0].verdict,
        Verdict::Invalid,
        "the start is above the cap"
    );
    check_optimum(&space, &isoc, &[0.64], &f);
    assert!(
        records
            .iter()
            .any(|r| r.verdict == Verdict::Invalid && r.iteration > 0)
    );
    for m in isoc.members() {
        assert!(m.estimate.mean - isoc.z() * m.estimate.std_error <= 6.4);
    }
}

#[test]
fn every_strategy_finds_the_peak() {
    let f = |x: &[f64]| 100.0 - 30.0 * ((2.0 * x[0] - 0.5).powi(2) + (x[1] - 0.72).powi(2));
    let space = Space::new(vec![rectangle("lamp", 2.0, 1.0)], &[10]);
    for strategy in [
        Strategy::RefineOnIntersection,
        Strategy::RefineOnEnd,
        Strategy::NoRefine,
        Strategy::Paired,
        Strategy::RaceOnEnd,
    ] {
        // σ = 0.1 with N, 0.2 with n: differences between neighbouring cells are a few
        // σ, so a fast draw rarely sends the optimum to case A (where the tabu cache
        // would keep it out for good).
        let mut eval = Noisy::new(f, 10.0);
        let settings = settings(400, strategy);
        let (n, full) = settings.sample_counts(&eval);
        let (isoc, records, _) = run(&space, settings, vec![1.0, 0.0], &mut eval);
        check_optimum(&space, &isoc, &[0.25, 0.72], &f);
        let want = if strategy == Strategy::NoRefine {
            n
        } else {
            full
        };
        assert!(
            isoc.members().iter().all(|m| m.estimate.samples == want),
            "{strategy:?}"
        );
        let finals = records
            .iter()
            .filter(|r| r.verdict == Verdict::Final)
            .count();
        assert_eq!(
            finals > 0,
            matches!(strategy, Strategy::RefineOnEnd | Strategy::RaceOnEnd)
        );
        let refines = records
            .iter()
            .filter(|r| r.verdict == Verdict::Refine)
            .count();
        // The sequential searches tell some candidates worse before n samples.
        let out_early = records
            .iter()
            .filter(|r| r.evaluation.goal.samples < n)
            .any(|r| matches!(r.verdict, Verdict::Bad | Verdict::Beaten));
        assert_eq!(out_early, strategy.paired(), "{strategy:?}");
        // RACE_ISOC_ON_END looks at a candidate below n before its n-sample evaluation.
        assert_eq!(
            refines > 0,
            strategy.two_stage() || strategy == Strategy::RaceOnEnd
        );
    }
}

#[test]
fn same_seed_same_records() {
    let f = |x: &[f64]| (x[0] * 7.0).sin() + x[1];
    let space = Space::new(vec![rectangle("o", 1.0, 1.0)], &[20, 6]);
    let strip = |rs: Vec<Record>| -> Vec<(u64, Vec<f64>, f64, Verdict)> {
        rs.into_iter()
            .map(|r| {
                (
                    r.iteration,
                    r.config.coords,
                    r.evaluation.goal.mean,
                    r.verdict,
                )
            })
            .collect()
    };
    let (_, a, _) = run(
        &space,
        settings(200, Strategy::RefineOnIntersection),
        vec![0.0, 0.0],
        &mut Noisy::new(f, 20.0),
    );
    let (_, b, _) = run(
        &space,
        settings(200, Strategy::RefineOnIntersection),
        vec![0.0, 0.0],
        &mut Noisy::new(f, 20.0),
    );
    assert_eq!(strip(a), strip(b));
}

#[test]
fn interrupted_run_resumes_without_retracing() {
    let f = |x: &[f64]| 100.0 - 30.0 * ((x[0] - 0.52).powi(2) + (x[1] - 0.71).powi(2));
    let space = Space::new(vec![rectangle("lamp", 1.0, 1.0)], &[10]);
    let mut eval = Noisy::new(f, 50.0);
    let mut search = Search::new(
        &space,
        settings(400, Strategy::RefineOnIntersection),
        &Configuration {
            coords: vec![0.0, 0.0],
        },
    );
    let mut log = Log {
        stop_after: Some(15),
        ..Log::default()
    };
    assert_eq!(
        search.run(&mut eval, &mut log).unwrap(),
        Outcome::Interrupted
    );
    assert_eq!(
        log.records.len(),
        15,
        "the stop is asked before every candidate"
    );
    let before: Vec<Cell> = search
        .isoc()
        .members()
        .iter()
        .map(|m| m.cell.clone())
        .collect();

    // A fresh search replays the rows: same ISOC; the evaluator (which refuses to trace
    // a configuration twice) is shared, so continuing proves no cell is re-traced.
    let mut resumed = Search::new(
        &space,
        settings(400, Strategy::RefineOnIntersection),
        &Configuration {
            coords: vec![0.0, 0.0],
        },
    );
    resumed.replay(&log.records);
    let after: Vec<Cell> = resumed
        .isoc()
        .members()
        .iter()
        .map(|m| m.cell.clone())
        .collect();
    assert_eq!(before, after);
    assert_eq!(
        resumed.iteration(),
        search
            .iteration()
            .max(log.records.last().unwrap().iteration + 1)
    );
    let mut log2 = Log::default();
    resumed.run(&mut eval, &mut log2).unwrap();
    assert!(log2.records.iter().all(|r| r.verdict != Verdict::Initial));
    check_optimum(&space, resumed.isoc(), &[0.52, 0.71], &f);
}

/// The search with every sense and constraint on functions of known optimum,
/// returning the search for its ISOC and closest configurations.
fn run_search<'s, F: Fn(&[f64]) -> f64>(
    space: &'s Space,
    settings: Settings,
    start: Vec<f64>,
    eval: &mut Noisy<F>,
) -> Search<'s> {
    let mut search = Search::new(space, settings, &Configuration { coords: start });
    search.run(eval, &mut Log::default()).unwrap();
    search
}

/// The cell of `x` in a one-segment space of `cells` cells.
fn cell_index(x: f64, cells: u32) -> u32 {
    ((x * cells as f64) as u32).min(cells - 1)
}

#[test]
fn a_target_is_met_where_the_function_crosses_it() {
    // f rises from 0 to 20 over [0, 1]; 13 is reached at x = 0.65.
    let f = |x: &[f64]| 20.0 * x[0];
    let space = Space::new(vec![segment("h")], &[20]);
    let mut eval = Noisy::new(f, 3.0);
    let settings = Settings {
        sense: Sense::Target(13.0),
        ..settings(200, Strategy::RefineOnIntersection)
    };
    let search = run_search(&space, settings, vec![0.1], &mut eval);
    let cells: Vec<u32> = search
        .isoc()
        .members()
        .iter()
        .map(|m| m.cell.0[0])
        .collect();
    assert!(cells.contains(&cell_index(0.65, 20)), "{cells:?}");
    for m in search.isoc().members() {
        // Its score is minus the distance to the target.
        assert!(m.estimate.mean <= 0.0);
        assert!((m.evaluation.goal.mean - 13.0).abs() <= 0.5 + 4.0 * m.evaluation.goal.std_error);
    }
}

#[test]
fn a_minimum_under_a_lower_bound_sits_on_the_bound() {
    // Least f = x (power) with g = 10 x (illuminance) at least 6: x ≥ 0.6.
    let space = Space::new(vec![segment("level")], &[40]);
    let mut eval = Noisy::new(|x: &[f64]| x[0], 0.0).with(|x| 10.0 * x[0], 2.0);
    let settings = Settings {
        sense: Sense::Minimize,
        constraints: vec![Bound::MinLux(6.0)],
        ..settings(300, Strategy::RefineOnIntersection)
    };
    let search = run_search(&space, settings, vec![0.95], &mut eval);
    let best = search.isoc().best().expect("a feasible level");
    let level = best.config.coords[0];
    // The least level whose one-sided 95 % bound clears 6: σ of g is 2/√N = 0.02, so
    // within a cell or two of 0.6 above it.
    assert!(
        (0.6..=0.6 + 2.0 / 40.0 + 0.01).contains(&level),
        "level {level}"
    );
    for m in search.isoc().members() {
        let g = &m.evaluation.constraints[0];
        assert!(
            g.mean - 1.645 * g.std_error >= 6.0 - 1e-12,
            "every member feasible"
        );
    }
}

#[test]
fn an_upper_bound_pulls_a_maximum_off_its_peak() {
    // Most f, peaked at 0.7, with g = 10 x at most 4: the best is x just under 0.4.
    let f = |x: &[f64]| 10.0 - 40.0 * (x[0] - 0.7).powi(2);
    let space = Space::new(vec![segment("x")], &[40]);
    let mut eval = Noisy::new(f, 2.0).with(|x| 10.0 * x[0], 1.0);
    let settings = Settings {
        constraints: vec![Bound::MaxLux(4.0)],
        ..settings(300, Strategy::RefineOnIntersection)
    };
    let search = run_search(&space, settings, vec![0.1], &mut eval);
    let cells: Vec<u32> = search
        .isoc()
        .members()
        .iter()
        .map(|m| m.cell.0[0])
        .collect();
    assert!(!cells.is_empty());
    assert!(
        cells.iter().all(|&c| c < 16),
        "feasible cells only (x < 0.4): {cells:?}"
    );
    assert!(cells.contains(&15) || cells.contains(&14), "{cells:?}");
}

#[test]
fn an_infeasible_problem_walks_toward_feasibility_and_says_what_came_closest() {
    // g = 10 − 20 |x − 0.8| never reaches 12: the closest is x = 0.8.
    let space = Space::new(vec![segment("x")], &[40]);
    let mut eval =
        Noisy::new(|x: &[f64]| x[0], 1.0).with(|x| 10.0 - 20.0 * (x[0] - 0.8).abs(), 0.5);
    let settings = Settings {
        constraints: vec![Bound::MinLux(12.0)],
        ..settings(200, Strategy::RefineOnIntersection)
    };
    let search = run_search(&space, settings, vec![0.05], &mut eval);
    let standing = search.standing();
    assert!(standing.isoc.members().is_empty());
    let (v, closest) = &standing.closest[0];
    assert_eq!(
        closest.cell.0[0],
        cell_index(0.8, 40),
        "closest at {:?}",
        closest.config
    );
    assert!((v - (1.0 - 10.0 / 12.0)).abs() < 0.03, "shortfall {v}");
    assert!(standing.closest.windows(2).all(|w| w[0].0 <= w[1].0));
}

/// [`Noisy`] that readies evaluations ahead as the photon tracer does side by side:
/// `prepare` computes them into `ready`, `evaluate` checks that a readied one is what
/// it evaluates, and counts it. It refuses x₀ > 0.9, as the tracer refuses a placement
/// outside the scene.
struct Readied<F: Fn(&[f64]) -> f64> {
    inner: Noisy<F>,
    width: usize,
    ready: Vec<(Configuration, u64, Evaluation)>,
    readied: u64,
    served: u64,
}

impl<F: Fn(&[f64]) -> f64> Evaluate for Readied<F> {
    type Error = String;

    fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Evaluation, String> {
        let e = self.inner.evaluate(c, photons)?;
        if let Some(at) = self
            .ready
            .iter()
            .position(|(r, p, _)| r == c && *p == photons)
        {
            assert_eq!(self.ready.remove(at).2, e);
            self.served += u64::from(photons > 1);
        }
        Ok(e)
    }

    fn prepare(&mut self, configs: &[Configuration], photons: u64) {
        self.ready = configs
            .iter()
            .map(|c| (c.clone(), photons, self.inner.estimate(c, photons)))
            .collect();
        // The screening's looks (1 sample) are all read; the walk's are guesses.
        if photons > 1 {
            self.readied += configs.len() as u64;
        }
    }

    fn side_by_side(&self, _photons: u64) -> usize {
        self.width
    }

    fn refuses(&self, c: &Configuration) -> Option<String> {
        (c.coords[0] > 0.9).then(|| "outside".to_string())
    }
}

/// The walk that readies candidates ahead is the walk one candidate at a time: the same
/// records (but their seconds), ISOC, outcome and counts, readying 2, 3 or 8 at once,
/// on every strategy and several seeds; with a constraint that keeps the search
/// infeasible for a while (its centre the closest), refusals, a dimming-like cheap
/// variable (every other candidate) and a grid small enough to run out of cells. The
/// guesses are right often enough to matter: most readied looks are read.
#[test]
fn readying_candidates_ahead_changes_nothing() {
    let f = |x: &[f64]| 4.0 - 9.0 * (x[0] - 0.6).powi(2) - 3.0 * (x[1] - 0.3).powi(2);
    let g = |x: &[f64]| 10.0 * x[0];
    let spaces = [
        Space::new(vec![segment("x"), segment("level")], &[24, 8]).with_cheap(&[1]),
        Space::new(vec![segment("x"), segment("y")], &[5, 4]),
    ];
    type Run = (
        Vec<(u64, Vec<f64>, Evaluation, Verdict)>,
        Vec<Cell>,
        Outcome,
        u64,
        u64,
    );
    let mut readied = (0, 0);
    for (s, space) in spaces.iter().enumerate() {
        for strategy in [
            Strategy::RefineOnIntersection,
            Strategy::RefineOnEnd,
            Strategy::NoRefine,
            Strategy::Paired,
            Strategy::RaceOnEnd,
        ] {
            for seed in [1, 2, 3] {
                let run = |width: usize| -> (Run, u64, u64) {
                    // RACE_ISOC_ON_END with n = N/16: its race looks at 4n (readied
                    // side by side) before N.
                    let fast_quality = if strategy == Strategy::RaceOnEnd {
                        1.0 / 16.0
                    } else {
                        0.25
                    };
                    let settings = Settings {
                        seed,
                        constraints: vec![Bound::MinLux(4.0)],
                        fast_quality,
                        ..settings(300, strategy)
                    };
                    let mut eval = Readied {
                        inner: Noisy::new(f, 2.0).with(g, 0.5),
                        width,
                        ready: Vec::new(),
                        readied: 0,
                        served: 0,
                    };
                    eval.inner.seed = seed;
                    let start = Configuration {
                        coords: vec![0.05, 0.5],
                    };
                    let mut search = Search::new(space, settings, &start);
                    let mut log = Log::default();
                    let outcome = search.run(&mut eval, &mut log).unwrap();
                    let rows = log
                        .records
                        .into_iter()
                        .map(|r| (r.iteration, r.config.coords, r.evaluation, r.verdict))
                        .collect();
                    let members = search.isoc().members().iter();
                    let cells = members.map(|m| m.cell.clone()).collect();
                    let counts = (search.iteration(), search.evaluations());
                    let run = (rows, cells, outcome, counts.0, counts.1);
                    (run, eval.readied, eval.served)
                };
                let (alone, none, _) = run(1);
                assert_eq!(none, 0);
                assert!(alone.0.len() > 10, "{strategy:?} seed {seed}");
                for width in [2, 3, 8] {
                    let (ahead, r, served) = run(width);
                    assert!(
                        ahead == alone,
                        "{width} ahead, space {s}, {strategy:?}, seed {seed}"
                    );
                    if width == 2 {
                        readied.0 += r;
                        readied.1 += served;
                    }
                }
            }
        }
    }
    assert!(
        2 * readied.1 > readied.0,
        "{readied:?} read of those readied"
    );
}

/// Two interchangeable lamps on a 1 m square, whose best places are off any regular
/// array: the search starts with the regular arrays, and its standing keeps the best of
/// them decided feasible ([`Standing::best_start`]) beside an ISOC that goes past it;
/// a search replaying the rows keeps the same one.
#[test]
fn the_best_regular_array_is_kept_beside_the_answer() {
    let f = |x: &[f64]| {
        100.0
            - 40.0 * ((x[0] - 0.15).powi(2) + (x[1] - 0.25).powi(2))
            - 40.0 * ((x[2] - 0.85).powi(2) + (x[3] - 0.45).powi(2))
    };
    let space = Space::new(
        vec![rectangle("A", 1.0, 1.0), rectangle("B", 1.0, 1.0)],
        &[10],
    )
    .with_exchangeable(vec![vec![vec![0], vec![1]]]);
    let start = Configuration {
        coords: vec![0.05, 0.95, 0.15, 0.95],
    };
    let arrays = space.regular_arrays(&space.snap(&start));
    assert!(!arrays.is_empty());
    // The best array by the noiseless function, as its cell's centre.
    let value = |c: &Configuration| f(&space.snap(c).coords);
    let best = arrays
        .iter()
        .max_by(|a, b| value(a).total_cmp(&value(b)))
        .unwrap();
    for strategy in [Strategy::Paired, Strategy::RaceOnEnd] {
        let mut eval = Noisy::new(f, 0.5);
        let mut search = Search::new(&space, settings(200, strategy), &start);
        let mut log = Log::default();
        search.run(&mut eval, &mut log).unwrap();
        let kept = search
            .standing()
            .best_start
            .expect("a regular array is feasible");
        assert_eq!(kept.cell, space.cell(best), "{strategy:?}");
        // The answer beats it: the optimum is irregular.
        let answer = search.isoc().best().unwrap();
        assert!(answer.estimate.mean > kept.estimate.mean, "{strategy:?}");
        let mut replayed = Search::new(&space, settings(200, strategy), &start);
        replayed.replay(&log.records);
        let again = replayed.standing().best_start.expect("replayed");
        assert_eq!(
            (&again.cell, again.estimate.mean, &again.config.coords),
            (&kept.cell, kept.estimate.mean, &kept.config.coords),
            "{strategy:?}"
        );
    }
}

/// A `<lightArray>`'s space (columns, rows, two wall fractions) under a function whose
/// best is 3 columns × 2 rows with the outer lamps 0.6 and 0.8 of a spacing from the
/// walls, away from every start (each start is half a spacing from the walls or a
/// spread of 0.3, 0.5, 0.7): the search reaches that shape from the starts.
#[test]
fn an_array_search_finds_the_best_shape() {
    let domain = ArrayDomain {
        rect: Parallelogram::from_corners(
            DVec3::ZERO,
            [
                DVec3::new(6.0, 0.0, 0.0),
                DVec3::new(6.0, 4.0, 0.0),
                DVec3::new(0.0, 4.0, 0.0),
            ],
        )
        .unwrap(),
        columns: (1, 4),
        rows: (1, 3),
        lamps: 12,
        turns: false,
        continuous: None,
    };
    let d = domain.clone();
    let f = move |x: &[f64]| {
        let s = d.shape(x);
        let (c, r) = (f64::from(s.columns), f64::from(s.rows));
        100.0
            - 5.0 * ((c - 3.0).powi(2) + (r - 2.0).powi(2))
            - 40.0 * ((s.walls[0] - 0.6).powi(2) + (s.walls[1] - 0.8).powi(2))
    };
    let space = Space::new(
        vec![Variable {
            id: "Grid".into(),
            domain: Domain::Array(domain.clone()),
        }],
        &[20],
    );
    let best = ArrayShape {
        columns: 3,
        rows: 2,
        walls: [0.6, 0.8],
        orientation: None,
    };
    let optimum = domain.coords(&best).unwrap();
    for strategy in [Strategy::Paired, Strategy::RaceOnEnd] {
        let mut eval = Noisy::new(&f, 0.5);
        let (isoc, _, _) = run(
            &space,
            settings(300, strategy),
            vec![0.1, 0.1, 0.5, 0.5],
            &mut eval,
        );
        check_optimum(&space, &isoc, &optimum, &f);
    }
}
