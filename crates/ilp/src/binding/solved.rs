//! Which variables the evaluator solves rather than the search samples: the dimming
//! levels of a least-power problem ([`crate::dimming`]).

use super::{Binding, Target};
use crate::dimming::{Dimmer, LevelSolver, solvable};
use crate::intention::Goal;
use crate::space::Domain;
use invlight_stats::Confidence;

impl Binding {
    /// Makes the `lightPower` levels of a `minimizePower` problem whose constraints are
    /// all linear in them ([`solvable`]) the evaluator's to choose: the space keeps
    /// them as solved variables ([`crate::space::Space::with_solved`]) and
    /// [`Binding::level_solver`] holds the program, decided at `confidence`.
    pub(super) fn solve_levels(&mut self, confidence: Confidence) {
        let bounds: Vec<_> = self.constraints.iter().map(|c| c.bound).collect();
        if self.goal != Goal::MinimizePower || bounds.is_empty() || !solvable(&bounds) {
            return;
        }
        let mut variables = Vec::new();
        let mut dimmers = Vec::new();
        for (i, (t, v)) in self.targets.iter().zip(self.space.variables()).enumerate() {
            if let (Target::Power { component, .. }, Domain::Segment { min, max }) = (t, &v.domain)
            {
                variables.push(i);
                dimmers.push(Dimmer {
                    components: vec![*component],
                    min: *min,
                    max: *max,
                    power: self.electric_power[*component],
                });
            }
        }
        if dimmers.is_empty() {
            return;
        }
        self.space = self.space.clone().with_solved(&variables);
        self.level_solver = Some((
            variables,
            LevelSolver {
                dimmers,
                components: self.component_count(),
                z: confidence.z_one_sided(),
            },
        ));
    }

    /// The program of the least-power levels, with the variables it chooses (in
    /// order, one per dimmer), when the evaluator solves them ([`Binding::new`]).
    pub fn level_solver(&self) -> Option<(&[usize], &LevelSolver)> {
        self.level_solver.as_ref().map(|(v, s)| (v.as_slice(), s))
    }
}
