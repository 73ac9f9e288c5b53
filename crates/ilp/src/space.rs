//! The space of configurations (thesis §3.1.1, §4.4, §4.8; DESIGN.md §3): each variable's
//! domain, its neighbourhoods N(x, r) and its cells.
//!
//! A [`Configuration`] holds every variable's coordinates *normalised* to [0, 1]:
//! - a position on a placement rectangle A + s·(B−A) + t·(D−A): (s, t);
//! - a direction the light comes from, in spherical coordinates about the scene's up
//!   axis: (φ/2π, θ/(π/2)), azimuth φ and zenith angle θ ≤ π/2 (a sun shines downward,
//!   so only the upper hemisphere is searched — the thesis searched the whole sphere and
//!   suggested this restriction, §5.3.5);
//! - a colour's HSV value V ∈ [min, max]: (V − min)/(max − min).
//!
//! Normalised coordinates make the cells of §4.8 uniform: every dimension is split into
//! C equal parts, C taken in turn from the `meshSize` list (`"20x6"`: the first
//! dimension of each variable in 20, the second in 6, a third again in 20 — ILPSolver's
//! `meshSize[dimension % len]`), and a configuration is evaluated at its cell's
//! reference point, the cell centre.

use glam::DVec3;
use invlight_stats::SplitMix64;
use std::f64::consts::{FRAC_PI_2, TAU};
use std::fmt;

mod array;

pub use array::{ArrayDomain, ArrayShape, Rows};

/// A placement parallelogram: P(s, t) = A + s·e1 + t·e2, (s, t) ∈ \[0, 1\]² (thesis §4.4.1).
///
/// Its neighbourhood of radius r is the disc of radius r·diagonal around the current
/// point in the plane's metric coordinates (u along e1, v ⟂ u in the plane), clipped to
/// the parallelogram, so N(x, 1) covers it from any point (§3.2's property (c)).
#[derive(Debug, Clone, PartialEq)]
pub struct Parallelogram {
    /// Vertex A, the reference point of the placed object at (0, 0).
    pub a: DVec3,
    /// Edge from A to its first neighbour (B).
    pub e1: DVec3,
    /// Edge from A to its other neighbour.
    pub e2: DVec3,
    /// (s, t) → metric plane coordinates (x, y): x = s·m[0] + t·m[1], y = t·m[2].
    metric: [f64; 3],
    /// The longer diagonal, the neighbourhood's unit of length.
    diagonal: f64,
}

/// Why four points do not make a placement parallelogram.
#[derive(Debug, Clone, PartialEq)]
pub enum ParallelogramError {
    /// Two edges from A are parallel or of zero length.
    Degenerate,
    /// The vertex opposite A is off the parallelogram spanned by its neighbours by this
    /// distance (relative to the diagonal): the quad is not planar or not a parallelogram.
    Skewed(f64),
}

impl fmt::Display for ParallelogramError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParallelogramError::Degenerate => write!(f, "its vertices are collinear or repeated"),
            ParallelogramError::Skewed(d) => write!(
                f,
                "it is not a planar parallelogram (the vertex opposite A is {:.1} % of the diagonal away from where it should be)",
                100.0 * d
            ),
        }
    }
}

impl Parallelogram {
    /// The parallelogram of corners `a` (reference vertex) and `others` (B, C, D in any
    /// order: the one farthest from A is taken as opposite, so both ILPSolver's labelling
    /// (D opposite) and A-B-C-D around the quad (C opposite) work). e1 points to the first
    /// of the others that is a neighbour of A.
    pub fn from_corners(a: DVec3, others: [DVec3; 3]) -> Result<Parallelogram, ParallelogramError> {
        let far = (0..3)
            .max_by(|&i, &j| {
                a.distance_squared(others[i])
                    .total_cmp(&a.distance_squared(others[j]))
            })
            .unwrap_or(2);
        let mut near = (0..3).filter(|&i| i != far).map(|i| others[i]);
        let (n1, n2) = match (near.next(), near.next()) {
            (Some(n1), Some(n2)) => (n1, n2),
            _ => return Err(ParallelogramError::Degenerate),
        };
        let (e1, e2) = (n1 - a, n2 - a);
        let l1 = e1.length();
        let area = e1.cross(e2).length();
        if l1 == 0.0 || e2.length() == 0.0 || area <= 1e-9 * l1 * e2.length() {
            return Err(ParallelogramError::Degenerate);
        }
        let diagonal = (e1 + e2).length().max((e1 - e2).length());
        let off = (others[far] - (a + e1 + e2)).length() / diagonal;
        if off > 1e-3 {
            return Err(ParallelogramError::Skewed(off));
        }
        let u = e1 / l1;
        let metric = [l1, e2.dot(u), area / l1];
        Ok(Parallelogram {
            a,
            e1,
            e2,
            metric,
            diagonal,
        })
    }

    /// The longer diagonal's length, m.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The world point at (s, t).
    pub fn point(&self, s: f64, t: f64) -> DVec3 {
        self.a + s * self.e1 + t * self.e2
    }

    /// The (s, t) of the point of the plane nearest `p`.
    pub fn coords(&self, p: DVec3) -> (f64, f64) {
        let u = self.e1 / self.metric[0];
        let n = self.e1.cross(self.e2);
        let v = n.cross(self.e1).normalize();
        let d = p - self.a;
        self.metric_to_st(d.dot(u), d.dot(v))
    }

    fn st_to_metric(&self, s: f64, t: f64) -> (f64, f64) {
        (s * self.metric[0] + t * self.metric[1], t * self.metric[2])
    }

    fn metric_to_st(&self, x: f64, y: f64) -> (f64, f64) {
        let t = y / self.metric[2];
        ((x - t * self.metric[1]) / self.metric[0], t)
    }

    /// A uniform point of the disc of radius r·diagonal around (s, t) within the
    /// parallelogram: rejection from the disc's bounding box clipped to the
    /// parallelogram's, which accepts at least about a fifth of the draws; after 64
    /// misses (a sliver-thin parallelogram) the centre is returned.
    fn neighbour(&self, s: f64, t: f64, r: f64, rng: &mut SplitMix64) -> (f64, f64) {
        let radius = r * self.diagonal;
        let (cx, cy) = self.st_to_metric(s, t);
        let xs = [
            0.0,
            self.metric[0],
            self.metric[1],
            self.metric[0] + self.metric[1],
        ];
        let (bx0, bx1) = (
            xs.iter().copied().fold(f64::INFINITY, f64::min),
            xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let (x0, x1) = ((cx - radius).max(bx0), (cx + radius).min(bx1));
        let (y0, y1) = ((cy - radius).max(0.0), (cy + radius).min(self.metric[2]));
        for _ in 0..64 {
            let (x, y) = (rng.uniform(x0, x1), rng.uniform(y0, y1));
            if (x - cx).powi(2) + (y - cy).powi(2) <= radius * radius {
                let (s2, t2) = self.metric_to_st(x, y);
                if (0.0..=1.0).contains(&s2) && (0.0..=1.0).contains(&t2) {
                    return (s2, t2);
                }
            }
        }
        (s, t)
    }
}

/// Directions in the hemisphere about `up`, or a cone of it, in spherical coordinates
/// (thesis §4.4.2): zenith angle θ ∈ [0, `max_zenith`] from `up` (π/2 for a sun's
/// hemisphere, a `lightAim`'s `maxTilt` for a lamp's cone), azimuth φ ∈ [0, 2π)
/// measured from `east` counter-clockwise about `up`. The coordinates are of the
/// direction the light comes *from*; the light travels along the opposite vector.
///
/// Neighbourhood of radius r: θ within ±r·`max_zenith` (clipped), φ within ±r·π
/// (wrapping), so N(x, 1) covers the whole hemisphere or cone (the thesis' square of
/// side π·r covered its whole sphere only at r = 2).
#[derive(Debug, Clone, PartialEq)]
pub struct Hemisphere {
    /// Zenith (the scene's up axis), unit.
    pub up: DVec3,
    /// φ = 0 axis, unit, ⟂ up: the world axis least aligned with up, orthogonalised.
    pub east: DVec3,
    /// up × east.
    pub north: DVec3,
    /// The largest zenith angle, radians, in (0, π/2].
    pub max_zenith: f64,
}

impl Hemisphere {
    /// The hemisphere about `up` (need not be normalised).
    pub fn new(up: DVec3) -> Hemisphere {
        let up = up.normalize();
        let axis = [DVec3::X, DVec3::Y, DVec3::Z]
            .into_iter()
            .min_by(|a, b| a.dot(up).abs().total_cmp(&b.dot(up).abs()))
            .unwrap_or(DVec3::X);
        let east = (axis - axis.dot(up) * up).normalize();
        Hemisphere {
            up,
            east,
            north: up.cross(east),
            max_zenith: FRAC_PI_2,
        }
    }

    /// The travel directions within `max_tilt` radians (clamped to (0, π/2]) of
    /// `axis`, a lamp's authored aim: the cone about `−axis` as zenith, so θ = 0 is
    /// the authored aim.
    pub fn cone(axis: DVec3, max_tilt: f64) -> Hemisphere {
        Hemisphere {
            max_zenith: max_tilt.clamp(f64::MIN_POSITIVE, FRAC_PI_2),
            ..Hemisphere::new(-axis)
        }
    }

    /// The unit vector light travels along for normalised (φ/2π, θ/`max_zenith`).
    pub fn direction(&self, phi01: f64, theta01: f64) -> DVec3 {
        let (phi, theta) = (phi01 * TAU, theta01 * self.max_zenith);
        -(theta.sin() * (phi.cos() * self.east + phi.sin() * self.north) + theta.cos() * self.up)
    }

    /// Normalised (φ/2π, θ/`max_zenith`) of a travel direction; a direction outside
    /// is clamped to the edge (the horizon of a hemisphere).
    pub fn coords(&self, travel: DVec3) -> (f64, f64) {
        let from = -travel.normalize();
        let theta = from
            .dot(self.up)
            .clamp(-1.0, 1.0)
            .acos()
            .min(self.max_zenith);
        let phi = from
            .dot(self.north)
            .atan2(from.dot(self.east))
            .rem_euclid(TAU);
        ((phi / TAU).rem_euclid(1.0), theta / self.max_zenith)
    }
}

/// A variable's domain.
#[derive(Debug, Clone, PartialEq)]
pub enum Domain {
    /// A position on a placement parallelogram (2 dimensions: s, t).
    Parallelogram(Parallelogram),
    /// A direction in a hemisphere (2 dimensions: φ, θ).
    Hemisphere(Hemisphere),
    /// A scalar in [min, max] (1 dimension).
    Segment {
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// A full turn, angles in [min, max) with max = min + 360° (1 dimension): its ends
    /// are one orientation, so its neighbourhoods wrap as a sun's azimuth does and a
    /// search near 350° may step to 10° — a [`Domain::Segment`] would have to climb
    /// back across the whole range.
    Turn {
        /// The angle at normalised 0, degrees.
        min: f64,
        /// `min` + 360, degrees.
        max: f64,
    },
    /// A regular array of lamps (4 dimensions: columns, rows and the two wall
    /// fractions, and a fifth when the lamps' orientation is searched,
    /// [`ArrayDomain`]).
    Array(ArrayDomain),
}

impl Domain {
    /// Number of normalised coordinates.
    pub fn dimensions(&self) -> usize {
        match self {
            Domain::Parallelogram(_) | Domain::Hemisphere(_) => 2,
            Domain::Segment { .. } | Domain::Turn { .. } => 1,
            Domain::Array(a) => a.dimensions(),
        }
    }

    /// The cells of dimension `d` when the domain fixes them (an array's counts and
    /// wall fractions), else `None` and the mesh decides.
    fn fixed_cells(&self, d: usize) -> Option<u32> {
        match self {
            Domain::Array(a) => Some(a.cells()[d]),
            _ => None,
        }
    }

    /// Writes a neighbour of `x` (this variable's coordinates) at radius r into `out`.
    fn neighbour(&self, x: &[f64], r: f64, rng: &mut SplitMix64, out: &mut [f64]) {
        match self {
            Domain::Parallelogram(rect) => {
                let (s, t) = rect.neighbour(x[0], x[1], r, rng);
                out[0] = s;
                out[1] = t;
            }
            Domain::Hemisphere(_) => {
                out[0] = (x[0] + rng.uniform(-0.5 * r, 0.5 * r)).rem_euclid(1.0);
                out[1] = rng.uniform((x[1] - r).max(0.0), (x[1] + r).min(1.0));
            }
            Domain::Segment { .. } => {
                out[0] = rng.uniform((x[0] - r).max(0.0), (x[0] + r).min(1.0));
            }
            Domain::Turn { .. } => {
                out[0] = (x[0] + rng.uniform(-0.5 * r, 0.5 * r)).rem_euclid(1.0);
            }
            Domain::Array(_) => {
                for (o, &x) in out.iter_mut().zip(x) {
                    *o = rng.uniform((x - r).max(0.0), (x + r).min(1.0));
                }
            }
        }
    }
}

/// A free variable of the problem: its name (the problem file's `id`) and domain.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable {
    /// The problem file's `id`.
    pub id: String,
    /// Where it may range.
    pub domain: Domain,
}

/// A point of the space: every variable's normalised coordinates, in variable order.
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    /// Normalised coordinates, each in [0, 1].
    pub coords: Vec<f64>,
}

/// A cell of §4.8: one index per dimension.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cell(pub Vec<u32>);

/// The variables, their cells and neighbourhoods.
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
    variables: Vec<Variable>,
    /// Cells per dimension, one per coordinate of a configuration.
    cells: Vec<u32>,
    /// First coordinate of each variable.
    offsets: Vec<usize>,
    /// Groups of interchangeable members, each member its variables' indices
    /// ([`Space::with_exchangeable`]).
    exchangeable: Vec<Vec<Vec<usize>>>,
    /// Per variable, whether changing it alone costs the evaluator next to nothing
    /// ([`Space::with_cheap`]).
    cheap: Vec<bool>,
    /// Per variable, whether the evaluator chooses its value itself
    /// ([`Space::with_solved`]).
    solved: Vec<bool>,
}

impl Space {
    /// The space of `variables` with `mesh` cells per dimension taken in turn (ILPSolver:
    /// the d-th dimension of every variable uses `mesh[d % mesh.len()]`). Empty or zero
    /// mesh sizes count as 1.
    pub fn new(variables: Vec<Variable>, mesh: &[u32]) -> Space {
        let mesh = if mesh.is_empty() { &[1][..] } else { mesh };
        let mut cells = Vec::new();
        let mut offsets = Vec::new();
        for v in &variables {
            offsets.push(cells.len());
            for d in 0..v.domain.dimensions() {
                let c = v.domain.fixed_cells(d).unwrap_or(mesh[d % mesh.len()]);
                cells.push(c.max(1));
            }
        }
        Space {
            variables,
            cells,
            offsets,
            exchangeable: Vec::new(),
            cheap: Vec::new(),
            solved: Vec::new(),
        }
    }

    /// This space with the variables `cheap` marked as cheap to change: a configuration
    /// that differs from an evaluated one in them alone is evaluated without new work
    /// (dimming levels, read from the trace of the same arrangement).
    pub fn with_cheap(mut self, cheap: &[usize]) -> Space {
        self.cheap = (0..self.variables.len())
            .map(|i| cheap.contains(&i))
            .collect();
        self
    }

    /// This space with the variables `solved` chosen by the evaluator rather than
    /// searched: the least-power dimming levels of an arrangement are the optimum of a
    /// small linear program over its trace's tallies, solved exactly for every
    /// arrangement instead of sampled. Their dimensions are one cell each (the cell
    /// is the arrangement's), neighbourhoods leave them where they are, and
    /// [`Space::snap`] keeps their values, which the evaluation returns
    /// ([`crate::vns::Evaluation::solved`]).
    pub fn with_solved(mut self, solved: &[usize]) -> Space {
        self.solved = (0..self.variables.len())
            .map(|i| solved.contains(&i))
            .collect();
        for &v in solved {
            let o = self.offsets[v];
            for c in &mut self.cells[o..o + self.variables[v].domain.dimensions()] {
                *c = 1;
            }
        }
        self.cheap
            .iter_mut()
            .zip(&self.solved)
            .for_each(|(c, s)| *c &= !s);
        self
    }

    /// Whether the evaluator chooses variable `i` ([`Space::with_solved`]).
    pub fn is_solved(&self, i: usize) -> bool {
        self.solved.get(i).copied().unwrap_or(false)
    }

    /// This space with variable `v`'s first dimension cut into `cells` cells instead of
    /// the mesh's: a `sunTime`'s steps, one cell centred on each.
    pub fn with_cells(mut self, v: usize, cells: u32) -> Space {
        self.cells[self.offsets[v]] = cells.max(1);
        self
    }

    /// Whether some variables are cheap and some are not: then the search spends some
    /// of its tries on the cheap ones alone.
    pub fn has_cheap_part(&self) -> bool {
        self.cheap.iter().any(|&c| c) && self.cheap.iter().any(|&c| !c)
    }

    /// This space with groups of interchangeable members: within a group, every member
    /// is a list of variables of the same domains and meshes, and swapping two
    /// members' values changes nothing that is measured (two identical lamps on one
    /// rectangle). A cell is then taken in its canonical order, members sorted by their
    /// cells, so the search never evaluates a swap of what it has seen.
    ///
    /// # Panics
    /// If the members of a group do not have the same cells per coordinate.
    pub fn with_exchangeable(mut self, groups: Vec<Vec<Vec<usize>>>) -> Space {
        for g in &groups {
            let shape = |m: &Vec<usize>| -> Vec<u32> {
                m.iter()
                    .flat_map(|&v| {
                        let o = self.offsets[v];
                        self.cells[o..o + self.variables[v].domain.dimensions()].to_vec()
                    })
                    .collect()
            };
            assert!(
                g.windows(2).all(|w| shape(&w[0]) == shape(&w[1])),
                "interchangeable members with different meshes"
            );
        }
        self.exchangeable = groups;
        self
    }

    /// The groups of interchangeable members ([`Space::with_exchangeable`]).
    pub fn exchangeable(&self) -> &[Vec<Vec<usize>>] {
        &self.exchangeable
    }

    /// The coordinate indices of a member of an interchangeable group.
    fn member_coords(&self, member: &[usize]) -> Vec<usize> {
        member
            .iter()
            .flat_map(|&v| {
                let o = self.offsets[v];
                o..o + self.variables[v].domain.dimensions()
            })
            .collect()
    }

    /// The variables, in order.
    pub fn variables(&self) -> &[Variable] {
        &self.variables
    }

    /// Number of normalised coordinates of a configuration.
    pub fn dimensions(&self) -> usize {
        self.cells.len()
    }

    /// Cells per dimension.
    pub fn cells_per_dimension(&self) -> &[u32] {
        &self.cells
    }

    /// Total number of distinct cells (as f64: it can exceed any integer type): a group
    /// of m interchangeable members of c cells each has C(c + m − 1, m) arrangements,
    /// not c^m.
    pub fn cell_count(&self) -> f64 {
        let mut grouped = vec![false; self.cells.len()];
        let mut count = 1.0;
        for g in &self.exchangeable {
            let coords: Vec<Vec<usize>> = g.iter().map(|m| self.member_coords(m)).collect();
            let c: f64 = coords[0].iter().map(|&i| self.cells[i] as f64).product();
            // C(c + m − 1, m) = Π_{j=1..m} (c − 1 + j)/j.
            count *= (1..=g.len())
                .map(|j| (c - 1.0 + j as f64) / j as f64)
                .product::<f64>();
            coords.iter().flatten().for_each(|&i| grouped[i] = true);
        }
        count
            * self
                .cells
                .iter()
                .zip(&grouped)
                .filter(|(_, g)| !**g)
                .map(|(&c, _)| c as f64)
                .product::<f64>()
    }

    /// The coordinates of variable `i` within a configuration.
    pub fn slice<'c>(&self, config: &'c Configuration, i: usize) -> &'c [f64] {
        let o = self.offsets[i];
        &config.coords[o..o + self.variables[i].domain.dimensions()]
    }

    /// The coordinates of variable `i` within a configuration, to change.
    pub fn slice_mut<'c>(&self, config: &'c mut Configuration, i: usize) -> &'c mut [f64] {
        let o = self.offsets[i];
        &mut config.coords[o..o + self.variables[i].domain.dimensions()]
    }

    /// The cell a configuration lies in, interchangeable members in canonical order
    /// and each array's coordinates its layout ignores at one value
    /// ([`ArrayDomain::canonical`]).
    pub fn cell(&self, config: &Configuration) -> Cell {
        let mut cell: Vec<u32> = config
            .coords
            .iter()
            .zip(&self.cells)
            .map(|(&x, &c)| ((x * c as f64).floor().max(0.0) as u32).min(c - 1))
            .collect();
        for (v, &o) in self.variables.iter().zip(&self.offsets) {
            if let Domain::Array(a) = &v.domain {
                a.canonical(&mut cell[o..o + a.dimensions()]);
            }
        }
        for g in &self.exchangeable {
            let coords: Vec<Vec<usize>> = g.iter().map(|m| self.member_coords(m)).collect();
            let mut tuples: Vec<Vec<u32>> = coords
                .iter()
                .map(|c| c.iter().map(|&i| cell[i]).collect())
                .collect();
            tuples.sort_unstable();
            for (c, t) in coords.iter().zip(tuples) {
                for (&i, k) in c.iter().zip(t) {
                    cell[i] = k;
                }
            }
        }
        Cell(cell)
    }

    /// The reference point (centre) of a cell.
    pub fn cell_centre(&self, cell: &Cell) -> Configuration {
        Configuration {
            coords: cell
                .0
                .iter()
                .zip(&self.cells)
                .map(|(&k, &c)| (k as f64 + 0.5) / c as f64)
                .collect(),
        }
    }

    /// The configuration a candidate is evaluated as: its cell's reference point, with
    /// the solved variables' values as they are ([`Space::with_solved`]).
    pub fn snap(&self, config: &Configuration) -> Configuration {
        let mut out = self.cell_centre(&self.cell(config));
        for i in (0..self.variables.len()).filter(|&i| self.is_solved(i)) {
            let o = self.offsets[i];
            let n = self.variables[i].domain.dimensions();
            out.coords[o..o + n].copy_from_slice(&config.coords[o..o + n]);
        }
        out
    }

    /// Regular arrays of each group of interchangeable placements on one parallelogram
    /// ([`Space::with_exchangeable`]), as a designer lays luminaires out first: for a
    /// group of m members, every r × c = m, members in rows along the parallelogram's
    /// second edge and columns along its first, each row and column spaced evenly with
    /// the outer columns `f` of a spacing from their edges and the outer rows `g`,
    /// for every f and g in `WALL_FRACTIONS` (½ is the usual "half a spacing from the
    /// walls"; the least power of a long room often keeps its rows nearer a spacing
    /// from the long walls than its columns from the short ones). Every other coordinate is
    /// `x`'s. The configurations are snapped to their cells and distinct; the search
    /// starts from them as well as from `x`, so a regular layout is always among what
    /// it compares. A `<lightArray>` variable ([`Domain::Array`]) starts from every
    /// count of columns and rows its lamps can fill, at a spread of wall distances
    /// ([`ArrayDomain::starts`]).
    pub fn regular_arrays(&self, x: &Configuration) -> Vec<Configuration> {
        const WALL_FRACTIONS: [f64; 3] = [0.5, 0.75, 1.0];
        let mut out: Vec<Configuration> = Vec::new();
        for (i, v) in self.variables.iter().enumerate() {
            let Domain::Array(a) = &v.domain else {
                continue;
            };
            for shape in a.starts() {
                let mut config = x.clone();
                if let Some(c) = a.coords(&shape) {
                    self.slice_mut(&mut config, i).copy_from_slice(&c);
                    out.push(self.snap(&config));
                }
            }
        }
        // Member i of n evenly spaced, the outer ones f of a spacing from the edges.
        let at = |i: usize, n: usize, f: f64| (i as f64 + f) / (n as f64 - 1.0 + 2.0 * f);
        for group in &self.exchangeable {
            let m = group.len();
            let placed = group.iter().all(|member| {
                member
                    .first()
                    .is_some_and(|&v| matches!(self.variables[v].domain, Domain::Parallelogram(_)))
            });
            if !placed {
                continue;
            }
            for columns in (1..=m).filter(|c| m % c == 0) {
                let rows = m / columns;
                let fractions = WALL_FRACTIONS
                    .iter()
                    .flat_map(|&a| WALL_FRACTIONS.iter().map(move |&b| (a, b)));
                for (fc, fr) in fractions {
                    let mut config = x.clone();
                    for (k, member) in group.iter().enumerate() {
                        let c = self.slice_mut(&mut config, member[0]);
                        c[0] = at(k % columns, columns, fc);
                        c[1] = at(k / columns, rows, fr);
                    }
                    let config = self.snap(&config);
                    if out.iter().all(|o| self.cell(o) != self.cell(&config)) {
                        out.push(config);
                    }
                }
            }
        }
        out
    }

    /// A random neighbour in N(x, r) = N₁(x₁, r) × … × Nₙ(xₙ, r) (thesis §3.2): every
    /// variable moves within its own neighbourhood of radius r.
    pub fn neighbour(&self, x: &Configuration, r: f64, rng: &mut SplitMix64) -> Configuration {
        self.neighbour_moving(x, r, rng, |_| true)
    }

    /// A random neighbour in N(x, r) that moves the cheap variables alone
    /// ([`Space::with_cheap`]).
    pub fn cheap_neighbour(
        &self,
        x: &Configuration,
        r: f64,
        rng: &mut SplitMix64,
    ) -> Configuration {
        self.neighbour_moving(x, r, rng, |i| self.cheap.get(i).copied().unwrap_or(false))
    }

    fn neighbour_moving(
        &self,
        x: &Configuration,
        r: f64,
        rng: &mut SplitMix64,
        moves: impl Fn(usize) -> bool,
    ) -> Configuration {
        let mut out = x.clone();
        for (i, v) in self.variables.iter().enumerate() {
            if !moves(i) || self.is_solved(i) {
                continue;
            }
            let o = self.offsets[i];
            let n = v.domain.dimensions();
            v.domain
                .neighbour(&x.coords[o..o + n], r, rng, &mut out.coords[o..o + n]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(side: f64) -> Parallelogram {
        Parallelogram::from_corners(
            DVec3::ZERO,
            [
                DVec3::new(side, 0.0, 0.0),
                DVec3::new(side, side, 0.0),
                DVec3::new(0.0, side, 0.0),
            ],
        )
        .unwrap()
    }

    #[test]
    fn opposite_vertex_is_found_in_either_labelling() {
        let a = DVec3::new(1.0, 2.0, 3.0);
        let (b, c, d) = (
            a + DVec3::X * 2.0,
            a + DVec3::new(2.0, 0.0, 1.0),
            a + DVec3::Z,
        );
        let around = Parallelogram::from_corners(a, [b, c, d]).unwrap();
        let ilpsolver = Parallelogram::from_corners(a, [b, d, c]).unwrap();
        assert_eq!(around.e1, b - a);
        assert_eq!(around.e2, d - a);
        assert_eq!(ilpsolver, around);
        assert_eq!(around.point(1.0, 1.0), c);
        let (s, t) = around.coords(a + 0.25 * (b - a) + 0.5 * (d - a) + DVec3::Y * 7.0);
        assert!((s - 0.25).abs() < 1e-12 && (t - 0.5).abs() < 1e-12);
    }

    #[test]
    fn non_planar_quad_is_rejected() {
        let err = Parallelogram::from_corners(
            DVec3::ZERO,
            [DVec3::X, DVec3::new(1.0, 0.3, 1.0), DVec3::Z],
        );
        assert!(matches!(err, Err(ParallelogramError::Skewed(_))));
        let err =
            Parallelogram::from_corners(DVec3::ZERO, [DVec3::X, DVec3::X * 2.0, DVec3::X * 3.0]);
        assert_eq!(err, Err(ParallelogramError::Degenerate));
    }

    #[test]
    fn rectangle_neighbours_lie_in_disc_and_rectangle() {
        let rect = Parallelogram::from_corners(
            DVec3::ZERO,
            [
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(4.0, 0.0, 1.0),
                DVec3::new(0.0, 0.0, 1.0),
            ],
        )
        .unwrap();
        let diag = 17f64.sqrt();
        let mut rng = SplitMix64::new(3);
        for &r in &[0.05, 0.3, 1.0] {
            for _ in 0..500 {
                let (s, t) = rect.neighbour(0.9, 0.1, r, &mut rng);
                assert!((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
                let d = rect.point(s, t).distance(rect.point(0.9, 0.1));
                assert!(d <= r * diag + 1e-9);
            }
        }
    }

    #[test]
    fn radius_one_reaches_the_far_corner() {
        let rect = square(1.0);
        let mut rng = SplitMix64::new(5);
        let far = (0..2000)
            .map(|_| rect.neighbour(0.0, 0.0, 1.0, &mut rng))
            .any(|(s, t)| s > 0.95 && t > 0.95);
        assert!(far);
    }

    #[test]
    fn hemisphere_round_trip_and_downward() {
        let h = Hemisphere::new(DVec3::Z);
        for &(p, t) in &[(0.1, 0.3), (0.7, 0.9), (0.45, 0.01)] {
            let d = h.direction(p, t);
            assert!((d.length() - 1.0).abs() < 1e-12);
            assert!(d.dot(DVec3::Z) <= 0.0, "light travels downward");
            let (p2, t2) = h.coords(d);
            assert!((p2 - p).abs() < 1e-9 && (t2 - t).abs() < 1e-9);
        }
        assert!((h.direction(0.3, 0.0) + DVec3::Z).length() < 1e-12);
    }

    #[test]
    fn cells_cycle_mesh_sizes_per_variable() {
        let space = Space::new(
            vec![
                Variable {
                    id: "a".into(),
                    domain: Domain::Parallelogram(square(1.0)),
                },
                Variable {
                    id: "c".into(),
                    domain: Domain::Segment { min: 0.0, max: 1.0 },
                },
                Variable {
                    id: "sun".into(),
                    domain: Domain::Hemisphere(Hemisphere::new(DVec3::Y)),
                },
            ],
            &[20, 6],
        );
        assert_eq!(space.cells_per_dimension(), &[20, 6, 20, 20, 6]);
        let x = Configuration {
            coords: vec![0.0, 1.0, 0.51, 0.999, 0.3],
        };
        assert_eq!(space.cell(&x), Cell(vec![0, 5, 10, 19, 1]));
        let c = space.snap(&x);
        assert_eq!(c.coords, vec![0.025, 11.0 / 12.0, 0.525, 0.975, 1.5 / 6.0]);
        assert_eq!(space.cell(&c), space.cell(&x));
        assert_eq!(space.cell_count(), 20.0 * 6.0 * 20.0 * 20.0 * 6.0);
    }

    #[test]
    fn regular_arrays_lay_every_factorisation_evenly() {
        let lamps: Vec<Variable> = (0..6)
            .map(|k| Variable {
                id: format!("L{k}"),
                domain: Domain::Parallelogram(square(6.0)),
            })
            .collect();
        let space =
            Space::new(lamps, &[60]).with_exchangeable(vec![(0..6).map(|k| vec![k]).collect()]);
        let x = Configuration {
            coords: vec![0.5; 12],
        };
        let arrays = space.regular_arrays(&x);
        // 1 × 6 and 6 × 1 at three distances of the rows (or columns) from the
        // edges, a single one always in the middle; 2 × 3 and 3 × 2 at three of the
        // columns times three of the rows.
        assert_eq!(arrays.len(), 3 + 9 + 9 + 3);
        // Two rows of three, half a spacing from the edges: columns at 1, 3 and 5 m
        // and rows at 1.5 and 4.5 m, each snapped to its cell (0.1 m).
        let mut points: Vec<(f64, f64)> = arrays[3 + 9]
            .coords
            .chunks(2)
            .map(|c| (6.0 * c[0], 6.0 * c[1]))
            .collect();
        points.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let expect = [
            (1.0, 1.5),
            (1.0, 4.5),
            (3.0, 1.5),
            (3.0, 4.5),
            (5.0, 1.5),
            (5.0, 4.5),
        ];
        for (p, e) in points.iter().zip(expect) {
            let near = (p.0 - e.0).abs() <= 0.05 + 1e-9 && (p.1 - e.1).abs() <= 0.05 + 1e-9;
            assert!(near, "{points:?}");
        }
        // Every array is a distinct cell.
        for (i, a) in arrays.iter().enumerate() {
            for b in &arrays[i + 1..] {
                assert_ne!(space.cell(a), space.cell(b));
            }
        }
    }

    #[test]
    fn solved_variables_are_one_cell_and_keep_their_values() {
        let space = Space::new(
            vec![
                Variable {
                    id: "lamp".into(),
                    domain: Domain::Parallelogram(square(1.0)),
                },
                Variable {
                    id: "level".into(),
                    domain: Domain::Segment { min: 0.1, max: 1.0 },
                },
            ],
            &[10],
        )
        .with_cheap(&[1])
        .with_solved(&[1]);
        assert_eq!(space.cells_per_dimension(), &[10, 10, 1]);
        assert!(!space.has_cheap_part(), "a solved level is not searched");
        let x = Configuration {
            coords: vec![0.33, 0.71, 0.4321],
        };
        assert_eq!(space.snap(&x).coords, vec![0.35, 0.75, 0.4321]);
        let mut rng = SplitMix64::new(9);
        for _ in 0..100 {
            assert_eq!(space.neighbour(&x, 0.5, &mut rng).coords[2], 0.4321);
        }
    }
}
