//! Global screening before the VNS walks: a space-filling set of cells, each
//! looked at once with the fewest samples, so that the walk starts from the best of
//! them and a plateau of no light is left by screening on, not by walking at random.

use super::{Evaluate, Evaluation, Observer, Record, Search, SearchError, Sense, Verdict};
use crate::intention::Feasibility;
use crate::space::{Cell, Configuration};
use invlight_stats::{SplitMix64, mix};
use std::time::Instant;

/// The most screening points traced side by side: enough for every core of a large
/// machine, few enough that a plateau's screening stops soon after light is found.
const SCREEN_BATCH: u64 = 32;

impl Search<'_> {
    /// Global screening, before the VNS walks: points of a space-filling
    /// design, each looked at once with the fewest samples the evaluator takes, for at
    /// most a tenth of `max_iterations` — then the best of them that could be feasible
    /// is evaluated as a candidate, so the VNS starts from it if it beats the initial
    /// configuration. On a plateau (no estimate so far distinguishable from 0, as when
    /// a sun must come through a small window) random walks around a member learn
    /// nothing, so screening goes on until something is lit, the cells run out or the
    /// budget does ([`Search::plateau`]). A goal to minimise has no plateau to leave:
    /// no light is its best. Returns `false` when the observer asked to stop.
    ///
    /// The design: rounds of M = max(1, ⌊max_iterations/10⌋) points, each round a Latin
    /// hypercube over the unit cube of coordinates (McKay, Beckman & Conover 1979: every
    /// coordinate's M strata hold one point each), from the seed and the round alone,
    /// so a resumed run draws the same points.
    pub(super) fn screen<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<bool, SearchError<E::Error>> {
        let max = self.settings.max_iterations;
        let budget = (max / 10).max(1);
        let photons = eval.samples(1);
        loop {
            if observer.should_stop() {
                return Ok(false);
            }
            let seeking = !self.lit && self.settings.sense != Sense::Minimize;
            let cells_left =
                self.space.cell_count() - (self.screened.len() as f64 + self.cache.len() as f64);
            if self.iteration >= max || (self.screens >= budget && !seeking) || cells_left <= 0.0 {
                break;
            }
            // A batch of points, traced side by side (Evaluate::evaluate_all); its size
            // is fixed by the budget alone, never by the threads, so the rows are the
            // same on any machine.
            let room = if self.screens < budget {
                budget - self.screens
            } else {
                SCREEN_BATCH
            };
            let mut batch: Vec<(u64, Configuration, Cell)> = Vec::new();
            while (batch.len() as u64) < room.min(SCREEN_BATCH)
                && self.iteration < max
                && (batch.len() as f64) < cells_left
            {
                let config = self.space.snap(&self.screen_point(self.screens, budget));
                let cell = self.space.cell(&config);
                self.screens += 1;
                let iteration = self.iteration;
                self.iteration += 1;
                observer.iteration(self.iteration);
                if self.screened.contains(&cell)
                    || batch.iter().any(|(_, _, c)| *c == cell)
                    || !self.fresh((iteration, &config, &cell), eval, observer)
                {
                    continue;
                }
                batch.push((iteration, config, cell));
            }
            let configs: Vec<Configuration> = batch.iter().map(|(_, c, _)| c.clone()).collect();
            let t = Instant::now();
            let evaluations = eval.evaluate_all(&configs, photons);
            let seconds = t.elapsed().as_secs_f64() / configs.len().max(1) as f64;
            for ((iteration, config, cell), e) in batch.into_iter().zip(evaluations) {
                let mut evaluation = e.map_err(SearchError::Evaluate)?;
                self.evaluations += 1;
                evaluation.groups = Vec::new();
                self.screened_as(&cell, config.clone(), &evaluation);
                let record = Record {
                    iteration,
                    config,
                    evaluation,
                    seconds,
                    verdict: Verdict::Screened,
                };
                self.report(observer, cell, record)?;
            }
        }
        // The best screened configuration, as a candidate; not again on a resumed run.
        if let Some((_, config)) = self.best_screen.clone()
            && self.lit
            && self.iteration < max
        {
            let cell = self.space.cell(&config);
            if self.cache.get(&cell).is_none() {
                let iteration = self.iteration;
                self.iteration += 1;
                observer.iteration(self.iteration);
                self.candidate((iteration, config, cell), 0.0, eval, observer)?;
            }
        }
        Ok(true)
    }

    /// Screening point `j`: point j mod M of round ⌊j/M⌋'s Latin hypercube, in the
    /// middle of its strata's cells' reach (a uniform offset within its stratum).
    fn screen_point(&mut self, j: u64, m: u64) -> Configuration {
        let (round, k) = (j / m, (j % m) as usize);
        let seed = self.settings.seed;
        if self.round.as_ref().is_none_or(|(r, _)| *r != round) {
            let mut rng = SplitMix64::new(mix(seed ^ 0x5C_4EE4 ^ mix(round)));
            let perms = (0..self.space.dimensions())
                .map(|_| {
                    let mut p: Vec<u32> = (0..m as u32).collect();
                    for i in (1..p.len()).rev() {
                        p.swap(i, rng.below(i + 1));
                    }
                    p
                })
                .collect();
            self.round = Some((round, perms));
        }
        let perms = &self.round.as_ref().expect("set above").1;
        let mut rng = SplitMix64::new(mix(seed ^ mix(round ^ mix(k as u64 + 1))));
        Configuration {
            coords: perms
                .iter()
                .map(|p| (p[k] as f64 + rng.next_f64()) / m as f64)
                .collect(),
        }
    }

    /// Notes a screened evaluation: its cell, and whether it is the best so far.
    pub(super) fn screened_as(&mut self, cell: &Cell, config: Configuration, e: &Evaluation) {
        self.screened.insert(cell.clone());
        if self.invalid(e) || self.feasibility(e) == Feasibility::Infeasible {
            return;
        }
        let score = self.settings.sense.score(&e.goal).mean;
        if self.best_screen.as_ref().is_none_or(|(b, _)| score > *b) {
            self.best_screen = Some((score, config));
        }
    }

    /// Whether an evaluation's goal is distinguishable from 0 at the ISOC's z: the
    /// target receives light.
    pub(super) fn lights(&self, e: &Evaluation) -> bool {
        e.goal.interval(self.isoc.z()).low > 0.0
    }

    /// Whether the screening left the search on a plateau of no light: nothing
    /// evaluated was distinguishable from 0 and the goal is not to minimise.
    pub(super) fn plateau(&self) -> bool {
        !self.lit && self.screens > 0 && self.settings.sense != Sense::Minimize
    }
}
