//! The ISOC, *Indistinguishable Set of Optimum Configurations* (thesis §3.3.4), and its
//! SIISOC, the intersection of its members' intervals (§4.6).
//!
//! Every member is indistinguishable from every other (eq. 3.7) and better than every
//! configuration left out. A candidate whose interval lies entirely below the SIISOC is
//! worse than some member and stays out (case A). Otherwise (case B) it joins and the
//! members it beats leave. The thesis writes the new ISOC as x′ ∪ {x ∈ ISOC : x = x′},
//! which would also drop members that beat x′; here such a candidate is refused
//! instead (as ILPSolver's code does), so the members stay pairwise indistinguishable.
//! Pairwise indistinguishable estimates have pairwise overlapping intervals
//! (z·sqrt(σx² + σy²) ≤ z·(σx + σy)), and overlapping intervals on a line have a common
//! point (Helly's theorem in one dimension): the SIISOC is always a real interval.
//!
//! A paired ISOC ([`Isoc::paired`]) compares two configurations that both
//! kept their groups by the groups' paired differences (common random numbers) and
//! falls back to eq. 3.7 otherwise. Paired indistinguishability over all the groups
//! still implies overlapping intervals (var(d̄) = σx² + σy² − 2cov ≤ (σx + σy)²), but
//! over a fast estimate's fewer groups it need not: the SIISOC is then taken as the
//! intervals' common point nearest to both ends (low clamped to high). Case A still
//! screens by it: a candidate whose interval lies below it is below some member's
//! interval, which eq. 3.7 finds worse too.

use crate::space::{Cell, Configuration};
use crate::vns::Evaluation;
use invlight_stats::Estimate;
use invlight_stats::{Comparison, Interval, compare, compare_paired};

/// A member of the ISOC.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    /// The configuration (a cell's reference point).
    pub config: Configuration,
    /// Its cell.
    pub cell: Cell,
    /// Its score, the estimate the ISOC compares: the goal, or minus it for a goal to
    /// minimise, or minus its distance to a target ([`crate::Sense::score`]).
    pub estimate: Estimate,
    /// The score of each group of samples ([`crate::Sense::score_groups`]), for paired
    /// comparisons; empty when there are none.
    pub groups: Vec<f64>,
    /// What was estimated: the goal and the constraints.
    pub evaluation: Evaluation,
}

/// What happened to a candidate offered to the ISOC.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Admission {
    /// Case A: its interval lies entirely below the SIISOC.
    Below,
    /// It reaches the SIISOC but some member is better by eq. 3.7.
    Beaten,
    /// It joined; `removed` members it beats left. `was_empty` when it is the first.
    Joined {
        /// Members that left.
        removed: usize,
        /// Whether the ISOC was empty before.
        was_empty: bool,
    },
}

/// The ISOC with its SIISOC.
#[derive(Debug, Clone)]
pub struct Isoc {
    members: Vec<Member>,
    siisoc: Option<Interval>,
    z: f64,
    paired: bool,
}

impl Isoc {
    /// An empty ISOC comparing at z (e.g. 1.96 for 95 %) by eq. 3.7.
    pub fn new(z: f64) -> Isoc {
        Isoc {
            members: Vec::new(),
            siisoc: None,
            z,
            paired: false,
        }
    }

    /// An empty ISOC comparing at z by paired differences of groups where both
    /// configurations have them (see the module doc).
    pub fn paired(z: f64) -> Isoc {
        Isoc {
            paired: true,
            ..Isoc::new(z)
        }
    }

    /// An empty ISOC comparing as this one does.
    pub fn emptied(&self) -> Isoc {
        Isoc {
            paired: self.paired,
            ..Isoc::new(self.z)
        }
    }

    /// x against y: by their groups' paired differences in a paired ISOC when both
    /// share at least two groups, else by eq. 3.7.
    pub fn compare(&self, x: &Member, y: &Member) -> Comparison {
        self.paired
            .then(|| compare_paired(&x.groups, &y.groups, self.z))
            .flatten()
            .unwrap_or_else(|| compare(&x.estimate, &y.estimate, self.z))
    }

    /// The members, oldest first.
    pub fn members(&self) -> &[Member] {
        &self.members
    }

    /// The first of [`Isoc::best_first`], found without sorting (for progress shown after
    /// every evaluation).
    pub fn best(&self) -> Option<&Member> {
        self.members
            .iter()
            .min_by(|a, b| b.estimate.mean.total_cmp(&a.estimate.mean))
    }

    /// The members, best score first (equal scores oldest first): the order a reader
    /// expects in `result.json`, the pictures and the printed table, though the members
    /// cannot be told apart at the chosen confidence.
    pub fn best_first(&self) -> Vec<&Member> {
        let mut members: Vec<&Member> = self.members.iter().collect();
        members.sort_by(|a, b| b.estimate.mean.total_cmp(&a.estimate.mean));
        members
    }

    /// The SIISOC, `None` while the ISOC is empty.
    pub fn siisoc(&self) -> Option<Interval> {
        self.siisoc
    }

    /// The z of its intervals and comparisons.
    pub fn z(&self) -> f64 {
        self.z
    }

    /// Whether an estimate is not in case A: its interval reaches the SIISOC (or lies
    /// above it), so it may belong to the ISOC (§4.6, §4.7).
    pub fn reaches(&self, e: &Estimate) -> bool {
        self.reaches_at(e, self.z)
    }

    /// Whether the estimate's interval at `z` reaches the SIISOC: case A with a
    /// sequential search's early-look z for the candidate, so that its repeated looks
    /// keep their error bound ([`crate::early_look_z`]).
    pub fn reaches_at(&self, e: &Estimate, z: f64) -> bool {
        match self.siisoc {
            None => true,
            Some(s) => !e.interval(z).below(&s),
        }
    }

    /// Whether a member is better than `candidate` by their paired differences at `z`
    /// (a sequential search's early look, with its own z): eq. 3.7 never screens here,
    /// only pairs, whether or not the ISOC pairs its own comparisons.
    pub fn screens_out(&self, candidate: &Member, z: f64) -> bool {
        self.members
            .iter()
            .any(|m| compare_paired(&candidate.groups, &m.groups, z) == Some(Comparison::Worse))
    }

    /// Offers a candidate (§4.6, cases A and B).
    pub fn admit(&mut self, candidate: Member) -> Admission {
        if !self.reaches(&candidate.estimate) {
            return Admission::Below;
        }
        let order: Vec<Comparison> = self
            .members
            .iter()
            .map(|m| self.compare(&candidate, m))
            .collect();
        if order.contains(&Comparison::Worse) {
            return Admission::Beaten;
        }
        let was_empty = self.members.is_empty();
        let before = self.members.len();
        let mut order = order.into_iter();
        self.members
            .retain(|_| order.next() != Some(Comparison::Better));
        let removed = before - self.members.len();
        self.members.push(candidate);
        self.siisoc = self.intersection();
        Admission::Joined { removed, was_empty }
    }

    /// The intersection of all members' intervals (see the module doc for why it is
    /// never empty while there are members).
    fn intersection(&self) -> Option<Interval> {
        let mut it = self.members.iter().map(|m| m.estimate.interval(self.z));
        let first = it.next()?;
        let low = it.clone().fold(first.low, |l, i| l.max(i.low));
        let high = it.fold(first.high, |h, i| h.min(i.high));
        debug_assert!(
            self.paired || low <= high,
            "pairwise indistinguishable members overlap"
        );
        Some(Interval {
            low: low.min(high),
            high,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn member(k: u32, mean: f64, std_error: f64) -> Member {
        Member {
            config: Configuration {
                coords: vec![k as f64],
            },
            cell: Cell(vec![k]),
            estimate: Estimate {
                mean,
                std_error,
                samples: 1000,
            },
            groups: Vec::new(),
            evaluation: Evaluation::of(Estimate {
                mean,
                std_error,
                samples: 1000,
            }),
        }
    }

    #[test]
    fn cases_a_and_b() {
        let mut isoc = Isoc::new(2.0);
        assert_eq!(
            isoc.admit(member(0, 10.0, 1.0)),
            Admission::Joined {
                removed: 0,
                was_empty: true
            }
        );
        assert_eq!(
            isoc.siisoc(),
            Some(Interval {
                low: 8.0,
                high: 12.0
            })
        );
        // Indistinguishable: joins, SIISOC shrinks to [9, 12].
        assert_eq!(
            isoc.admit(member(1, 11.0, 1.0)),
            Admission::Joined {
                removed: 0,
                was_empty: false
            }
        );
        assert_eq!(
            isoc.siisoc(),
            Some(Interval {
                low: 9.0,
                high: 12.0
            })
        );
        // Case A: [5, 7] is below the SIISOC.
        assert_eq!(isoc.admit(member(2, 6.0, 0.5)), Admission::Below);
        // Case B: [11.9, 13.9] beats 10 ± 1 (|Δ| = 2.9 > 2·√1.25 ≈ 2.24) but not 11 ± 1.
        assert_eq!(
            isoc.admit(member(3, 12.9, 0.5)),
            Admission::Joined {
                removed: 1,
                was_empty: false
            }
        );
        let cells: Vec<u32> = isoc.members().iter().map(|m| m.cell.0[0]).collect();
        assert_eq!(cells, vec![1, 3]);
        assert_eq!(
            isoc.siisoc(),
            Some(Interval {
                low: 11.9,
                high: 13.0
            })
        );
    }

    #[test]
    fn candidate_beaten_by_a_member_is_refused() {
        let mut isoc = Isoc::new(2.0);
        isoc.admit(member(0, 10.0, 3.0));
        isoc.admit(member(1, 14.0, 0.1));
        // SIISOC = [13.8, 14.2]; a wide candidate 11 ± 2 reaches it ([7, 15]) and no
        // member beats it (vs 14 ± 0.1: |Δ| = 3 < 2·√4.01 ≈ 4.005): it joins.
        assert!(matches!(
            isoc.admit(member(2, 11.0, 2.0)),
            Admission::Joined { .. }
        ));
        // A narrow candidate at 13.2 ± 0.2: interval [12.8, 13.6] is below [13.8, 14.2].
        assert_eq!(isoc.admit(member(3, 13.2, 0.2)), Admission::Below);
        // 13.0 ± 0.45 reaches the SIISOC ([12.1, 13.9] vs [13.8, 14.2]) but 14 ± 0.1
        // beats it: |Δ| = 1 > 2·√(0.2125) ≈ 0.92.
        assert_eq!(isoc.admit(member(4, 13.0, 0.45)), Admission::Beaten);
        assert_eq!(isoc.members().len(), 3);
        assert!(isoc.siisoc().is_some());
    }
}
