//! `RACE_ISOC_ON_END`'s last step: the ISOC of a walk made with n samples
//! raced to N, instead of every member re-evaluated with N as `REFINE_ISOC_ON_END`
//! does (thesis §4.7).
//!
//! On a flat top the walk's ISOC holds a hundred members or more, and re-tracing each
//! with N is most of the search's time (cornell-cone: 116 members × 100 032 photons,
//! 81–89 % of it). Most of them are told worse than another after a few times n:
//! racing them (Maron & Moore, "Hoeffding races", NIPS 1993; Birattari et al.'s F-race,
//! GECCO 2002) looks at all survivors together with 4n, 16n, … samples — the schedule
//! of [`looks`] — and a member another survivor beats by the paired differences of
//! their groups at an early look's level ([`early_look_z`]) goes no further. The
//! survivors are then evaluated with N and the ISOC rebuilt from those estimates, as
//! `REFINE_ISOC_ON_END` rebuilds it ([`Search::finish`]).
//!
//! Why it stays honest: a member as good as another is wrongly found worse at some
//! early look with probability at most α/4 (each of the `early` looks at one-sided
//! α/(4·early), Bonferroni over the fixed schedule, whatever their correlation), then
//! at N with the ISOC's own two-sided α as the thesis' rebuild does: 3α/4 in all for a
//! comparison the thesis' rebuild makes at α/2 one-sided (the same argument as the
//! candidates' looks of `PAIRED_ISOC`). A score without groups (a uniformity, a power,
//! a target) is compared by eq. 3.7 at the same level. Each look continues the trace of
//! the one before (the evaluator's `measure_more`), so a survivor costs N photons in
//! all, not N plus its looks.

use super::{Evaluate, Observer, Record, Search, SearchError, Verdict, early_look_z, looks};
use crate::intention::Feasibility;
use crate::isoc::Member;
use invlight_stats::{Comparison, compare, compare_paired};
use std::time::Instant;

impl Search<'_> {
    /// Races the ISOC to N and rebuilds it from the survivors' N-sample estimates.
    /// Returns `false` when the observer asked to stop between two looks: the ISOC is
    /// then the walk's, unchanged, and the rows written so far are valid.
    pub(super) fn race<E: Evaluate, O: Observer>(
        &mut self,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<bool, SearchError<E::Error>> {
        let (n, full) = self.settings.sample_counts(eval);
        if n >= full {
            return Ok(true);
        }
        // The walk's members have their n-sample estimates: the race starts at 4n.
        let rounds: Vec<u64> = looks(n, full, |m| eval.samples(m))
            .into_iter()
            .skip(1)
            .collect();
        let z = early_look_z(self.settings.confidence, rounds.len());
        let mut survivors = self.isoc.members().to_vec();
        for photons in rounds {
            if survivors.len() < 2 {
                break;
            }
            if observer.should_stop() {
                return Ok(false);
            }
            survivors = self.look(survivors, photons, z, eval, observer)?;
        }
        self.finish(survivors, eval, observer)?;
        Ok(true)
    }

    /// One look of the race: every survivor evaluated with `photons` (readied side by
    /// side where a trace alone would leave cores idle), and the ones that stay in.
    /// A member leaves when its goal lies above the cap or a constraint fails at `z`
    /// (`invalid`, `infeasible`), or another member that stays valid and not
    /// infeasible beats it at `z` (`beaten`); the others' rows say `refine`.
    fn look<E: Evaluate, O: Observer>(
        &mut self,
        survivors: Vec<Member>,
        photons: u64,
        z: f64,
        eval: &mut E,
        observer: &mut O,
    ) -> Result<Vec<Member>, SearchError<E::Error>> {
        let configs: Vec<_> = survivors.iter().map(|m| m.config.clone()).collect();
        let t = Instant::now();
        if eval.side_by_side(photons) > 1 {
            eval.prepare(&configs, photons);
        }
        let mut lead = t.elapsed().as_secs_f64();
        let mut looked = Vec::with_capacity(survivors.len());
        for m in survivors {
            let (evaluation, seconds) = self.evaluate(eval, &m.config, photons)?;
            let seconds = seconds + std::mem::take(&mut lead);
            let out = if self.invalid_at(&evaluation, z) {
                Some(Verdict::Invalid)
            } else if self.feasibility_at(&evaluation, z) == Feasibility::Infeasible {
                Some(Verdict::Infeasible)
            } else {
                None
            };
            let member = self.member(m.config, m.cell, &evaluation);
            looked.push((member, evaluation, seconds, out));
        }
        let beaten: Vec<bool> = looked
            .iter()
            .map(|(x, _, _, out)| {
                out.is_none()
                    && looked
                        .iter()
                        .any(|(y, _, _, o)| o.is_none() && worse(x, y, z))
            })
            .collect();
        let mut stay = Vec::new();
        for ((member, evaluation, seconds, out), beaten) in looked.into_iter().zip(beaten) {
            let verdict = match out {
                Some(v) => v,
                None if beaten => Verdict::Beaten,
                None => Verdict::Refine,
            };
            let record = Record {
                iteration: self.iteration,
                config: member.config.clone(),
                evaluation,
                seconds,
                verdict,
            };
            self.report(observer, member.cell.clone(), record)?;
            if verdict == Verdict::Refine {
                stay.push(member);
            }
        }
        Ok(stay)
    }
}

/// Whether `y` beats `x` at `z`: by their groups' paired differences when both kept
/// at least two, else by eq. 3.7.
fn worse(x: &Member, y: &Member, z: f64) -> bool {
    compare_paired(&x.groups, &y.groups, z).unwrap_or_else(|| compare(&x.estimate, &y.estimate, z))
        == Comparison::Worse
}
