//! The walk of Algorithm 3.2 and the stopping rule's adjacent cells, with the first
//! looks of the candidates ahead readied side by side.
//!
//! A fast evaluation (2 048 photons, one chunk of the tracer) keeps one core busy, and
//! the walk decides its candidates one after another. So before evaluating a candidate
//! the walk works out which candidates it will evaluate next if none of them changes
//! its course — drawn from a copy of its random numbers, skipping the cells that will
//! be in the cache by then and the ones the evaluator refuses, as the walk itself
//! will — and asks the evaluator to ready their first looks at once
//! ([`Evaluate::prepare`]). The walk then goes on exactly as it would without: each
//! candidate is drawn and evaluated in turn, its evaluation already traced when the
//! guess was right. When a candidate changes the course (an admission moves the centres,
//! an improvement resets the radius, a closer infeasible one moves the centre while
//! there is no member), the next candidate is not the one guessed and the rest of
//! the guess is left unread; the readying counts nothing, so nothing needs rewinding
//! and the run is the run without it, for any number of candidates ahead and of
//! threads.

use super::{Evaluate, Observer, Search, SearchError, Verdict};
use crate::space::{Cell, Configuration};
use invlight_stats::SplitMix64;
use std::collections::VecDeque;
use std::time::Instant;

/// The candidates whose first looks the evaluator readied, in the order the walk will
/// evaluate them if its course does not change.
#[derive(Default)]
struct Ahead {
    cells: VecDeque<Cell>,
    /// Each readied candidate's share of the time the readying took, s.
    share: f64,
}

impl Ahead {
    /// The share of the readying time of `cell` when it is the next readied candidate
    /// (the guess was right so far); `None` otherwise.
    fn take(&mut self, cell: &Cell) -> Option<f64> {
        (self.cells.front() == Some(cell)).then(|| {
            self.cells.pop_front();
            self.share
        })
    }
}

impl Search<'_> {
    /// Algorithm 3.2: up to `tries` candidates in N(x, r); `Some(true)` on the first
    /// improvement, `None` when the observer asked to stop.
    pub(super) fn first_improvement<E: Evaluate, O: Observer>(
        &mut self,
        r: f64,
        tries: u32,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<Option<bool>, SearchError<E::Error>> {
        let mut ahead = Ahead::default();
        for t in 0..tries {
            if observer.should_stop() {
                return Ok(None);
            }
            if self.iteration >= self.settings.max_iterations || self.exhausted() {
                return Ok(Some(false));
            }
            let closest_before = self.closest.first().map(|(v, _)| *v);
            let mut rng = self.rng.clone();
            let candidate = self.draw(r, self.iteration, &mut rng);
            self.rng = rng;
            let cell = self.space.cell(&candidate);
            let iteration = self.iteration;
            self.iteration += 1;
            observer.iteration(self.iteration);
            if !self.fresh((iteration, &candidate, &cell), eval, observer) {
                continue;
            }
            let lead = match ahead.take(&cell) {
                Some(share) => share,
                None => {
                    let others = eval.side_by_side(self.first_look(eval)).saturating_sub(1);
                    let next = self.draws_ahead(r, tries - t - 1, &cell, &*eval, others);
                    self.ready(eval, &mut ahead, &candidate, next)
                }
            };
            let verdict = self.candidate((iteration, candidate, cell), lead, eval, observer)?;
            if verdict == Verdict::Better {
                return Ok(Some(true));
            }
            // With no feasible configuration yet, coming closer to one is the
            // improvement.
            let closer = self.closest.first().map(|(v, _)| *v);
            if self.isoc.members().is_empty()
                && closer.is_some_and(|v| closest_before.is_none_or(|b| v < b))
            {
                return Ok(Some(true));
            }
        }
        Ok(Some(false))
    }

    /// A candidate of iteration `iteration` in N(x, r), snapped to its cell: x a random
    /// ISOC member (they are indistinguishable, so any is "the current solution"); while
    /// there is none, the configuration closest to meeting the constraints (the search
    /// first walks toward feasibility), else the start. Every other iteration moves the
    /// cheap variables alone (dimming levels: the evaluator reads them from the
    /// arrangement's trace, for no photons).
    fn draw(&self, r: f64, iteration: u64, rng: &mut SplitMix64) -> Configuration {
        let members = self.isoc.members();
        let centre = if !members.is_empty() {
            &members[rng.below(members.len())].config
        } else if let Some((_, m)) = self.closest.first() {
            &m.config
        } else {
            &self.start
        };
        let neighbour = if self.space.has_cheap_part() && iteration % 2 == 1 {
            self.space.cheap_neighbour(centre, r, rng)
        } else {
            self.space.neighbour(centre, r, rng)
        };
        self.space.snap(&neighbour)
    }

    /// Up to `count` candidates that the next `tries` tries of Algorithm 3.2 will
    /// evaluate after the one at `cell` if none of them changes the walk's course, drawn
    /// as [`Search::first_improvement`] will draw them from a copy of its random numbers:
    /// the cells in the cache by then (this one's included) and the refused ones are
    /// skipped, and the guess ends where the walk would stop for the iterations or the
    /// cells.
    fn draws_ahead<E: Evaluate>(
        &self,
        r: f64,
        tries: u32,
        cell: &Cell,
        eval: &E,
        count: usize,
    ) -> Vec<(Cell, Configuration)> {
        let mut rng = self.rng.clone();
        let mut taken = vec![cell.clone()];
        let mut out = Vec::new();
        for t in 0..u64::from(tries) {
            let iteration = self.iteration + t;
            if out.len() >= count
                || iteration >= self.settings.max_iterations
                || (self.cache.len() + taken.len()) as f64 >= self.space.cell_count()
            {
                break;
            }
            let config = self.draw(r, iteration, &mut rng);
            let next = self.space.cell(&config);
            if self.cache.get(&next).is_some() || taken.contains(&next) {
                continue;
            }
            taken.push(next.clone());
            if eval.refuses(&config).is_none() {
                out.push((next, config));
            }
        }
        out
    }

    /// Readies the first looks of the candidate `now` and of the guessed `next` ones
    /// side by side, and remembers the guess in `ahead`; returns each one's share of
    /// the time (0 when there is no guess to ready with it).
    fn ready<E: Evaluate>(
        &self,
        eval: &mut E,
        ahead: &mut Ahead,
        now: &Configuration,
        next: Vec<(Cell, Configuration)>,
    ) -> f64 {
        ahead.cells.clear();
        if next.is_empty() {
            return 0.0;
        }
        let mut configs = Vec::with_capacity(next.len() + 1);
        configs.push(now.clone());
        for (cell, config) in next {
            ahead.cells.push_back(cell);
            configs.push(config);
        }
        let t = Instant::now();
        eval.prepare(&configs, self.first_look(eval));
        ahead.share = t.elapsed().as_secs_f64() / configs.len() as f64;
        ahead.share
    }

    /// The stopping rule's last check: evaluates every cell next to an ISOC member
    /// (one step along one coordinate) not evaluated yet, as candidates. Random draws
    /// can miss the one better cell beside a member (in 2-D a sweep misses a given
    /// adjacent cell about half the time); after this the ISOC is a local optimum over
    /// its adjacent cells. `Some(true)` when one was admitted, `None` when the observer
    /// asked to stop. The list is fixed before the first is evaluated, so the cells
    /// ahead are readied as [`Search::first_improvement`]'s are, and always guessed
    /// right.
    pub(super) fn adjacent<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<Option<bool>, SearchError<E::Error>> {
        let admitted = self.admissions;
        let mut cells = Vec::new();
        for m in self.isoc.members() {
            for (i, &c) in self.space.cells_per_dimension().iter().enumerate() {
                let k = m.cell.0[i];
                for next in [k.checked_sub(1), (k + 1 < c).then_some(k + 1)]
                    .into_iter()
                    .flatten()
                {
                    let mut cell = m.cell.clone();
                    cell.0[i] = next;
                    let config = self.space.snap(&self.space.cell_centre(&cell));
                    cells.push((self.space.cell(&config), config));
                }
            }
        }
        let mut ahead = Ahead::default();
        for at in 0..cells.len() {
            if observer.should_stop() {
                return Ok(None);
            }
            if self.iteration >= self.settings.max_iterations {
                break;
            }
            let (cell, config) = cells[at].clone();
            if self.cache.get(&cell).is_some() {
                continue;
            }
            let iteration = self.iteration;
            self.iteration += 1;
            observer.iteration(self.iteration);
            if !self.fresh((iteration, &config, &cell), eval, observer) {
                continue;
            }
            let lead = match ahead.take(&cell) {
                Some(share) => share,
                None => {
                    let others = eval.side_by_side(self.first_look(eval)).saturating_sub(1);
                    let next = self.cells_ahead(&cells[at + 1..], &cell, &*eval, others);
                    self.ready(eval, &mut ahead, &config, next)
                }
            };
            self.candidate((iteration, config, cell), lead, eval, observer)?;
        }
        Ok(Some(self.admissions > admitted))
    }

    /// Up to `count` of `cells` that [`Search::adjacent`] will evaluate after the one
    /// at `cell`: those not in the cache by then, nor refused, within the iterations
    /// left.
    fn cells_ahead<E: Evaluate>(
        &self,
        cells: &[(Cell, Configuration)],
        cell: &Cell,
        eval: &E,
        count: usize,
    ) -> Vec<(Cell, Configuration)> {
        let mut taken = vec![cell.clone()];
        let mut out = Vec::new();
        let mut iteration = self.iteration;
        for (next, config) in cells {
            if out.len() >= count || iteration >= self.settings.max_iterations {
                break;
            }
            if self.cache.get(next).is_some() || taken.contains(next) {
                continue;
            }
            taken.push(next.clone());
            iteration += 1;
            if eval.refuses(config).is_none() {
                out.push((next.clone(), config.clone()));
            }
        }
        out
    }
}
