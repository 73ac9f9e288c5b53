//! The least-power dimming of lamps where they stand, solved exactly.
//!
//! Illuminance is linear in each lamp's output (DESIGN.md §3), and a trace keeps every
//! dimmed lamp's light apart, so for one arrangement every quantity a constraint reads is
//! linear in the levels y: a surface's mean E(y) = c₀ + Σ_j a_j y_j, each grid cell's
//! mean E_i(y) likewise, and the grid's average Eavg(y). The constraints a designer
//! states become linear inequalities:
//! - `minLux` b: E(y) ≥ b; `maxLux` b: E(y) ≤ b;
//! - `minPointLux` b: E_i(y) ≥ b for every cell i that counts for Emin;
//! - `minUniformity` u: U0 = min_i E_i / Eavg ≥ u ⇔ E_i(y) − u·Eavg(y) ≥ 0 for every
//!   such cell (EN 12464-1:2021's U0 over the grid's cells, as
//!   [`invlight_photon::GridMeasurement::uniformity`] reads it);
//!
//! and `minimizePower`'s goal Σ_j P_j y_j is linear too. The least-power levels of an
//! arrangement are thus the optimum of a small linear program (a few variables, a row
//! per constraint and grid cell), which the simplex method solves exactly
//! (Dantzig 1963; here `microlp`'s bounded-variable simplex) in microseconds, where a
//! search samples levels one cell of a 20-step mesh at a time.
//!
//! The estimates are noisy and a constraint holds only at the run's confidence
//! (mean − z·σ above its bound), so each bound is moved by a margin z·σ before the
//! program is solved, σ that of the quantity at the levels found before (three rounds
//! from full output settle it to a fraction of a per cent); a constraint the levels
//! found still leave within z·σ of its bound has its margin raised by the shortfall
//! and the program is solved again. The margins are those of
//! the evaluation's own photons, so that it decides its constraints: a look with few
//! photons asks for more light than a full evaluation would, and so for more power,
//! which makes it look no better than it is. When no levels meet a look's margins, the
//! margins a full evaluation of N photons would need are tried (σ scaled by
//! √(photons/N); its constraints are then undecided, and the search traces it on), and
//! last the bounds alone.

use crate::intention::Bound;
use crate::reading::{Quantity, Reading};
use invlight_photon::Measurement;

/// One level the program chooses: the components it dims and its range.
#[derive(Debug, Clone, PartialEq)]
pub struct Dimmer {
    /// The components (lights kept apart in a trace) that take this level.
    pub components: Vec<usize>,
    /// The least level.
    pub min: f64,
    /// The greatest level.
    pub max: f64,
    /// The power of its components at level 1, in the goal's unit.
    pub power: f64,
}

/// The least-power levels of an arrangement from its trace ([`LevelSolver::solve`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LevelSolver {
    /// The levels chosen, in the order the search's variables give them.
    pub dimmers: Vec<Dimmer>,
    /// Components in a trace.
    pub components: usize,
    /// The one-sided z of the run's confidence, at which the constraints are decided.
    pub z: f64,
}

/// The levels found.
#[derive(Debug, Clone, PartialEq)]
pub struct Levels {
    /// One per dimmer.
    pub levels: Vec<f64>,
    /// Whether the constraints can be met at all, at the means: when not, `levels` are
    /// the greatest (the most light there is) and the configuration is infeasible.
    pub feasible: bool,
}

/// Rounds of margins, each from the σ at the levels of the round before.
const ROUNDS: usize = 3;

/// How much more than z·σ each margin is: the σ at the new levels differs a little
/// from the one the margin came from, and a constraint left exactly at its bound is
/// undecided.
const MARGIN_FACTOR: f64 = 1.02;

/// Rounds at most that raise the margins of constraints the levels found leave
/// undecided; one or two settle them.
const SETTLING_ROUNDS: usize = 4;

impl LevelSolver {
    /// The component weights of `levels` (1 for the components no dimmer holds).
    pub fn weights(&self, levels: &[f64]) -> Vec<f64> {
        let mut w = vec![1.0; self.components];
        for (d, &y) in self.dimmers.iter().zip(levels) {
            for &k in &d.components {
                w[k] = y;
            }
        }
        w
    }

    /// The least-power levels for the arrangement traced in `m`, under `bounds` (the
    /// problem's constraints, read as `reading` reads them), with the margins of an
    /// evaluation of `full` photons.
    pub fn solve(&self, reading: &Reading, bounds: &[Bound], m: &Measurement, full: u64) -> Levels {
        let most: Vec<f64> = self.dimmers.iter().map(|d| d.max).collect();
        let rows = Rows::new(self, reading, bounds, m);
        // This look's own margins, else a full evaluation's, else none.
        let full_scale = if m.photons >= full || full == 0 {
            1.0
        } else {
            (m.photons as f64 / full as f64).sqrt()
        };
        for scale in [1.0, full_scale, 0.0] {
            if let Some(levels) = self.with_margins(&rows, (reading, bounds), m, &most, scale) {
                return Levels {
                    levels,
                    feasible: true,
                };
            }
        }
        let levels = if m.photons < full {
            self.meeting_what_can_be_met(&rows, (reading, bounds), m, &most)
        } else {
            None
        };
        Levels {
            levels: levels.unwrap_or(most),
            feasible: false,
        }
    }

    /// A look's least-power levels for the constraints that some levels meet at its
    /// means, when they are no worse than the most light for the others: a
    /// constraint no dimming can meet and no dimming changes — a uniformity under one
    /// common level, which scales every cell alike — says nothing of the power, and
    /// the most light there is would make a look of few photons, whose uniformity
    /// reads low (the least of noisy cells is biased down), lose to the walk's
    /// incumbent on a power it would not need. The constraint left out reads as it
    /// does at the most light: decided against when it is, else undecided and traced
    /// on. `None` when no such levels exist (a constraint left out would read worse
    /// at them, as a uniformity does when some lamps are dimmed and others not).
    fn meeting_what_can_be_met(
        &self,
        rows: &Rows,
        (reading, bounds): (&Reading, &[Bound]),
        m: &Measurement,
        most: &[f64],
    ) -> Option<Vec<f64>> {
        let none = vec![0.0; bounds.len()];
        let only = |keep: &dyn Fn(usize) -> bool| {
            Rows(
                rows.0
                    .iter()
                    .filter(|r| keep(r.constraint))
                    .cloned()
                    .collect(),
            )
        };
        let met: Vec<bool> = (0..bounds.len())
            .map(|i| self.program(&only(&|c| c == i), &none).is_some())
            .collect();
        if met.iter().all(|&m| m) {
            return None;
        }
        let levels = self.program(&only(&|c| met[c]), &none)?;
        let at = |y: &[f64]| reading.read(m, &self.weights(y), 0.0).constraints;
        let (there, brightest) = (at(&levels), at(most));
        let no_worse = (0..bounds.len()).filter(|&i| !met[i]).all(|i| {
            let (a, b) = (there[i].mean, brightest[i].mean);
            let slack = 1e-9 * b.abs().max(1.0);
            if bounds[i].is_lower() {
                a >= b - slack
            } else {
                a <= b + slack
            }
        });
        no_worse.then_some(levels)
    }

    /// The least-power levels with every bound moved inward by `scale` times its
    /// margin z·σ, σ at the levels of the round before (from `most`); `None` when no
    /// levels in range meet them. The rounds are then checked: a constraint still
    /// within `scale`·z·σ of its bound at the levels found (its σ there larger than
    /// the one its margin came from, or the grid's least cell another than the rows
    /// foresaw) has its margin raised by the shortfall and the program solved again,
    /// so that a full evaluation decides what its levels were chosen to meet.
    fn with_margins(
        &self,
        rows: &Rows,
        (reading, bounds): (&Reading, &[Bound]),
        m: &Measurement,
        most: &[f64],
        scale: f64,
    ) -> Option<Vec<f64>> {
        let mut levels = most.to_vec();
        let mut found = None;
        for _ in 0..ROUNDS {
            let e = reading.read(m, &self.weights(&levels), 0.0);
            let margins: Vec<f64> = e
                .constraints
                .iter()
                .map(|c| MARGIN_FACTOR * self.z * c.std_error * scale)
                .collect();
            match self.program(rows, &margins) {
                Some(y) => {
                    levels = y;
                    found = Some(margins);
                }
                // The margins of the last levels found are too much for these: keep
                // those, which met theirs.
                None => break,
            }
            if scale == 0.0 {
                break;
            }
        }
        let mut margins = found?;
        if scale == 0.0 {
            return Some(levels);
        }
        let held: Vec<bool> = (0..bounds.len())
            .map(|i| rows.0.iter().any(|r| r.constraint == i))
            .collect();
        for _ in 0..SETTLING_ROUNDS {
            let e = reading.read(m, &self.weights(&levels), 0.0);
            let mut raised = margins.clone();
            let mut short = false;
            for (i, (c, b)) in e.constraints.iter().zip(bounds).enumerate() {
                let (need, inside) = (self.z * c.std_error * scale, b.inside(c.mean));
                if held[i] && inside < need {
                    raised[i] += MARGIN_FACTOR * (need - inside) + 1e-9 * b.limit().abs();
                    short = true;
                }
            }
            if !short {
                break;
            }
            match self.program(rows, &raised) {
                Some(y) => {
                    levels = y;
                    margins = raised;
                }
                None => break,
            }
        }
        Some(levels)
    }

    /// The least-power levels with each constraint's bound moved inward by its margin,
    /// or `None` when no levels in range meet them.
    fn program(&self, rows: &Rows, margins: &[f64]) -> Option<Vec<f64>> {
        use microlp::{ComparisonOp, OptimizationDirection, Problem};
        let mut lp = Problem::new(OptimizationDirection::Minimize);
        let vars: Vec<_> = self
            .dimmers
            .iter()
            .map(|d| lp.add_var(d.power, (d.min, d.max)))
            .collect();
        for row in &rows.0 {
            let margin = margins[row.constraint];
            let (a, rhs): (Vec<f64>, f64) = match &row.ratio {
                // E_i − (u + δ)·Eavg ≥ 0.
                Some((avg, avg_c)) => (
                    row.a.iter().zip(avg).map(|(a, v)| a - margin * v).collect(),
                    row.rhs + margin * avg_c,
                ),
                None if row.lower => (row.a.clone(), row.rhs + margin),
                None => (row.a.clone(), row.rhs - margin),
            };
            let terms: Vec<_> = vars.iter().copied().zip(a).collect();
            let op = if row.lower {
                ComparisonOp::Ge
            } else {
                ComparisonOp::Le
            };
            lp.add_constraint(&terms, op, rhs);
        }
        // No time or node limit is set, so the simplex runs to its answer: the same
        // levels for the same trace on every machine.
        let solution = match lp.solve().ok()? {
            microlp::SolveOutcome::Solution(s) => s,
            microlp::SolveOutcome::Interrupted(_) => return None,
        };
        Some(
            vars.iter()
                .zip(&self.dimmers)
                .map(|(&v, d)| solution[v].clamp(d.min, d.max))
                .collect(),
        )
    }
}

/// One linear inequality over the levels, Σ a_j y_j ≥ rhs (or ≤), from constraint
/// `constraint`, whose margin δ moves rhs by δ; a uniformity row E_i − u·Eavg ≥ 0
/// keeps Eavg's coefficients and constant part in `ratio` instead, for δ to raise u.
#[derive(Clone)]
struct Row {
    constraint: usize,
    a: Vec<f64>,
    rhs: f64,
    lower: bool,
    ratio: Option<(Vec<f64>, f64)>,
}

/// The program's rows for one trace.
struct Rows(Vec<Row>);

impl Rows {
    fn new(solver: &LevelSolver, reading: &Reading, bounds: &[Bound], m: &Measurement) -> Rows {
        let unit = |k: usize| {
            let mut w = vec![0.0; solver.components];
            w[k] = 1.0;
            w
        };
        // A linear quantity's coefficient on each dimmer and its constant part, from
        // its value at each component's unit weight.
        let linear = |value: &dyn Fn(&[f64]) -> f64| -> (Vec<f64>, f64) {
            let per: Vec<f64> = (0..solver.components).map(|k| value(&unit(k))).collect();
            let mut held = vec![false; solver.components];
            let a = solver
                .dimmers
                .iter()
                .map(|d| {
                    d.components
                        .iter()
                        .map(|&k| {
                            held[k] = true;
                            per[k]
                        })
                        .sum()
                })
                .collect();
            let c = (0..solver.components)
                .filter(|&k| !held[k])
                .map(|k| per[k])
                .sum();
            (a, c)
        };
        let mut rows = Vec::new();
        for (i, (bound, q)) in bounds.iter().zip(&reading.constraints).enumerate() {
            match (*bound, *q) {
                (Bound::MinLux(b) | Bound::MaxLux(b), Quantity::Mean { target, side }) => {
                    let (a, c) = linear(&|w| m.estimate_of(target, side, w).mean);
                    rows.push(Row {
                        constraint: i,
                        a,
                        rhs: b - c,
                        lower: bound.is_lower(),
                        ratio: None,
                    });
                }
                (Bound::MinLux(b) | Bound::MaxLux(b), Quantity::Average { grid }) => {
                    let (a, c) = linear(&|w| m.grids[grid].average(w).mean);
                    rows.push(Row {
                        constraint: i,
                        a,
                        rhs: b - c,
                        lower: bound.is_lower(),
                        ratio: None,
                    });
                }
                (Bound::MinPointLux(b, _), Quantity::MinPoint { grid }) => {
                    let g = &m.grids[grid];
                    for cell in g.points() {
                        let (a, c) = linear(&|w| g.cell(cell, w).map_or(0.0, |e| e.mean));
                        rows.push(Row {
                            constraint: i,
                            a,
                            rhs: b - c,
                            lower: true,
                            ratio: None,
                        });
                    }
                }
                (Bound::MinUniformity(u, _), Quantity::Uniformity { grid }) => {
                    let g = &m.grids[grid];
                    let (avg, avg_c) = linear(&|w| g.average(w).mean);
                    for cell in g.points() {
                        let (a, c) = linear(&|w| g.cell(cell, w).map_or(0.0, |e| e.mean));
                        rows.push(Row {
                            constraint: i,
                            a: a.iter().zip(&avg).map(|(a, v)| a - u * v).collect(),
                            rhs: u * avg_c - c,
                            lower: true,
                            ratio: Some((avg.clone(), avg_c)),
                        });
                    }
                }
                _ => {}
            }
        }
        Rows(rows)
    }
}

/// Whether every constraint of a problem is one the program can hold or one it may
/// leave to the evaluation: the lamps' light is linear in their levels for the
/// illuminances and U0, and not for a daylight factor (lamps are off under its sky). A
/// UGR limit is not linear (L² over Lb), and is judged at the levels found: an
/// arrangement is rejected when its least-power levels glare. Dimming every lamp by k
/// lowers UGR by 8·log10(1/k), but dimming the lamps out of view lowers the background
/// and raises it, so another dimming of a rejected arrangement, at more power, might
/// pass: the search answers the least power among the arrangements whose least-power
/// levels meet the limit.
pub fn solvable(bounds: &[Bound]) -> bool {
    bounds.iter().all(|b| {
        matches!(
            b,
            Bound::MinLux(_)
                | Bound::MaxLux(_)
                | Bound::MinPointLux(..)
                | Bound::MinUniformity(..)
                | Bound::MaxUgr(_)
        )
    })
}
