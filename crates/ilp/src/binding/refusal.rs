//! Candidates not worth tracing: an object or light put outside the scene, more lamps
//! than an array has, a continuous row longer than its rectangle, luminaires over each
//! other (`fittings.rs`), two interchangeable lamps in one cell. Each is refused before
//! any photon is traced, with its reason.

use super::array::{EDGES, ROW_SLACK};
use super::{Binding, Target, VariableValue};
use crate::space::{ArrayDomain, ArrayShape, Configuration, Domain, Rows};

/// Why `shape` of the array `id` is refused when its continuous `rows` are longer than
/// the rectangle: fittings end to end past its edge cannot be installed.
fn too_long(a: &ArrayDomain, shape: &ArrayShape, rows: &Rows, id: &str) -> Option<String> {
    let fraction = shape.row_length(rows);
    (fraction > 1.0 + ROW_SLACK).then(|| {
        let axis = rows.axis(shape.orientation);
        let edge = [a.rect.e1, a.rect.e2][axis].length();
        format!(
            "it lays {} fittings of '{id}' end to end, a row of {:.2} m along the {} edge, {:.2} m long",
            shape.count(axis),
            fraction * edge,
            EDGES[axis],
            edge
        )
    })
}

impl Binding {
    /// Why `config` is not worth tracing, if it is not: it puts an object or light
    /// outside the scene ([`Binding::leaves_scene`]), two luminaires' outlines over
    /// each other (`fittings.rs`), or two interchangeable lamps in
    /// one cell of their rectangle, which no design means (two fixtures in one spot)
    /// and which would make every split of their levels look like another answer.
    pub fn refusal(&self, config: &Configuration) -> Option<String> {
        if let Some(id) = self.leaves_scene(config) {
            return Some(format!("it puts '{id}' outside the scene"));
        }
        for (i, v) in self.space.variables().iter().enumerate() {
            if let Domain::Array(a) = &v.domain {
                let shape = a.shape(self.space.slice(config, i));
                if shape.lamps() > a.lamps {
                    return Some(format!(
                        "it sets out {} × {} = {} lamps and '{}' has {}",
                        shape.columns,
                        shape.rows,
                        shape.lamps(),
                        v.id,
                        a.lamps
                    ));
                }
                if let Some(why) = a.continuous.and_then(|r| too_long(a, &shape, &r, &v.id)) {
                    return Some(why);
                }
            }
        }
        if let Some(why) = self.overlapping_fittings(config) {
            return Some(why);
        }
        let cell = self.space.cell(config);
        let place = |v: usize| {
            let o: usize = self.space.variables()[..v]
                .iter()
                .map(|x| x.domain.dimensions())
                .sum();
            &cell.0[o..o + 2]
        };
        for group in self.space.exchangeable() {
            for (k, a) in group.iter().enumerate() {
                for b in &group[k + 1..] {
                    if place(a[0]) == place(b[0]) {
                        let ids = |m: &[usize]| &self.space.variables()[m[0]].id;
                        return Some(format!("it puts '{}' and '{}' in one cell", ids(a), ids(b)));
                    }
                }
            }
        }
        None
    }

    /// Where the search starts: `authored` (the scene as authored, each array at its
    /// first start, [`crate::space::ArrayDomain::starts`]) unless it is refused; then,
    /// where an array is searched, the first of the structured starts
    /// ([`crate::space::Space::regular_arrays`]) that is not. The start is evaluated
    /// whatever it is, and one whose fittings overlap (a linear array at its first
    /// orientation on a rectangle it only fits turned) would stand as an answer no one
    /// can install until something beat it.
    pub(super) fn first_start(&self, authored: Configuration) -> Configuration {
        let arrays = (self.space.variables().iter()).any(|v| matches!(v.domain, Domain::Array(_)));
        if !arrays || self.refusal(&authored).is_none() {
            return authored;
        }
        (self.space.regular_arrays(&authored).into_iter())
            .find(|c| self.refusal(c).is_none())
            .unwrap_or(authored)
    }

    /// The id of the first variable that would put its object (or light) outside the
    /// scene at `config`: beyond the bounds of everything no variable moves and of every
    /// moved thing as authored. Such a candidate is not traced: a lamp outside the room
    /// lights nothing a user means to light, and a cone through a wall is no answer.
    pub fn leaves_scene(&self, config: &Configuration) -> Option<&str> {
        let bounds = self.bounds?;
        let slack = 1e-4 * (bounds.hi - bounds.lo).length();
        for ((value, target), var) in self
            .values(config)
            .iter()
            .zip(&self.targets)
            .zip(self.space.variables())
        {
            if let (VariableValue::Position { point, .. }, Target::Move(m)) = (value, target)
                && !bounds.holds(&m.bounds.shifted(*point - m.reference), slack)
            {
                return Some(&var.id);
            }
        }
        None
    }
}
