//! What a search visited, variable by variable, as points a plot can draw (the thesis'
//! figures 5.6, 5.8 and 5.11): each evaluated cell once, with its latest estimate and
//! its role — the start, the improvements the search moved to, the other visits, the
//! invalid ones — and whether it ended in the ISOC.

use crate::binding::Binding;
use crate::isoc::Isoc;
use crate::space::Domain;
use crate::vns::{Record, Verdict};
use std::collections::HashMap;

/// A variable's axes: what a point's two coordinates are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Axes {
    /// A placement: metres from vertex A along AB and along AD of a `width` × `height`
    /// parallelogram.
    Placement {
        /// |AB|, m.
        width: f64,
        /// |AD|, m.
        height: f64,
    },
    /// A sun direction: (θ, φ) in degrees, θ from the zenith, φ the azimuth.
    Direction,
    /// A colour value V in [min, max] (the second coordinate is 0).
    Value {
        /// Smallest V.
        min: f64,
        /// Largest V.
        max: f64,
    },
}

/// The role of a point in the search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The initial configuration.
    Start,
    /// An improvement the search moved to.
    Improvement,
    /// Evaluated, not moved to.
    Visited,
    /// Evaluated and invalid (above the cap).
    Invalid,
}

/// One evaluated cell of a variable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Visit {
    /// Coordinates as the [`Axes`] say.
    pub coords: [f64; 2],
    /// Mean, lx.
    pub mean: f64,
    /// Lower end of its interval, lx.
    pub low: f64,
    /// Upper end, lx.
    pub high: f64,
    /// Its role.
    pub role: Role,
    /// Whether it is in the final ISOC.
    pub isoc: bool,
}

/// Variable `i`'s visits over the evaluations `records` (in order; rows of a resumed
/// run first), with its axes and the size of a cell in their units. A fast estimate
/// that was refined shows its full re-evaluation, and a re-evaluated cell its latest
/// estimate.
pub fn visits(
    binding: &Binding,
    i: usize,
    records: &[Record],
    isoc: &Isoc,
) -> (Axes, [f64; 2], Vec<Visit>) {
    let space = &binding.space;
    let cells = space.cells_per_dimension();
    let first = (0..i)
        .map(|j| space.variables()[j].domain.dimensions())
        .sum::<usize>();
    let domain = &space.variables()[i].domain;
    let (axes, cell) = match domain {
        Domain::Parallelogram(r) => {
            let (w, h) = (r.e1.length(), r.e2.length());
            (
                Axes::Placement {
                    width: w,
                    height: h,
                },
                [w / cells[first] as f64, h / cells[first + 1] as f64],
            )
        }
        Domain::Hemisphere(h) => (
            Axes::Direction,
            [
                h.max_zenith.to_degrees() / cells[first + 1] as f64,
                360.0 / cells[first] as f64,
            ],
        ),
        &Domain::Segment { min, max } | &Domain::Turn { min, max } => (
            Axes::Value { min, max },
            [(max - min) / cells[first] as f64, 0.0],
        ),
        // An array is drawn by the lamps it sets out.
        Domain::Array(a) => (
            Axes::Value {
                min: f64::from(a.columns.0 * a.rows.0),
                max: f64::from((a.columns.1 * a.rows.1).min(a.lamps)),
            },
            [1.0, 0.0],
        ),
    };
    let mut points: Vec<Visit> = Vec::new();
    let mut index: HashMap<Vec<u64>, usize> = HashMap::new();
    let key = |r: &Record| -> Vec<u64> { r.config.coords.iter().map(|c| c.to_bits()).collect() };
    for r in records.iter().filter(|r| r.verdict != Verdict::Refine) {
        let interval = r.evaluation.goal.interval(isoc.z());
        // A screened row is only looked at, but one whose look breaks a constraint is
        // as infeasible as a decided one, and drawn so. The intervals' two-sided z is
        // stricter than the search's one-sided verdicts: a row drawn grey is one every
        // verdict calls infeasible.
        let breaks = || {
            binding
                .constraints
                .iter()
                .zip(&r.evaluation.constraints)
                .any(|(c, e)| c.verdict(e, isoc.z()) == crate::Feasibility::Infeasible)
        };
        let role = match r.verdict {
            Verdict::Initial => Role::Start,
            Verdict::Better => Role::Improvement,
            Verdict::Invalid | Verdict::Infeasible => Role::Invalid,
            Verdict::Screened if breaks() => Role::Invalid,
            _ => Role::Visited,
        };
        let point = Visit {
            coords: coords(domain, space.slice(&r.config, i)),
            mean: r.evaluation.goal.mean,
            low: interval.low,
            high: interval.high,
            role,
            isoc: isoc.members().iter().any(|m| m.config == r.config),
        };
        match index.get(&key(r)) {
            // A later estimate of the same cell keeps the earlier role unless it is a
            // move of the search.
            Some(&j) => {
                let earlier = points[j].role;
                points[j] = Visit {
                    role: if role == Role::Visited { earlier } else { role },
                    ..point
                };
            }
            None => {
                index.insert(key(r), points.len());
                points.push(point);
            }
        }
    }
    // An invalid start is still where the search started.
    if let Some(&p) = records
        .iter()
        .find(|r| r.iteration == 0)
        .and_then(|r| index.get(&key(r)))
    {
        points[p].role = Role::Start;
    }
    (axes, cell, points)
}

/// A variable's normalised coordinates `x` in the units of its [`Axes`].
fn coords(domain: &Domain, x: &[f64]) -> [f64; 2] {
    match domain {
        Domain::Parallelogram(r) => [x[0] * r.e1.length(), x[1] * r.e2.length()],
        Domain::Hemisphere(h) => [x[1] * h.max_zenith.to_degrees(), x[0] * 360.0],
        Domain::Segment { min, max } | Domain::Turn { min, max } => [min + x[0] * (max - min), 0.0],
        Domain::Array(a) => [f64::from(a.shape(x).lamps()), 0.0],
    }
}
