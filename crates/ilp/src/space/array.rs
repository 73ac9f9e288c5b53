//! A regular array of lamps as a search variable (`<lightArray>`): how many columns
//! and rows, and how far the outer ones stand from the rectangle's edges, with the
//! lamps set out evenly between — the layout a designer draws in DIALux or Relux and
//! an installer sets out, searched instead of six free positions that nobody builds.
//!
//! The wall distance is a fraction f of the spacing, as the lumen method states it
//! (f = ½ is "half a spacing from the walls", the classic set-out; f = 0 puts the
//! outer lamps on the edges, f = 1 a whole spacing in): n lamps along an edge of
//! length L stand at (i + f)/(n − 1 + 2f)·L, i = 0 … n − 1, so the array is centred and
//! its spacing L/(n − 1 + 2f). Each fraction is searched in tenths, 0 to 1.
//!
//! With `orientation="search"` a fifth coordinate of two cells turns every lamp of the
//! array a quarter turn about its aim or not: a linear fitting along or across the
//! rectangle's first edge, the choice a designer makes with the layout, since glare
//! and the light between the rows turn on it.
//!
//! With `continuous="true"` the fittings of each row touch end to end, as trunking
//! rows are installed ([`Rows`]): along the edge their length lies on, the spacing is
//! the fitting's length and the row is centred, so that edge's wall fraction means
//! nothing. The coordinates stay as they are (a searched orientation still chooses
//! which edge that is); [`ArrayDomain::canonical`] maps the meaningless fraction to
//! one cell, so the search never evaluates one layout twice.

use super::Parallelogram;

/// Cells of a wall fraction: eleven, centred on 0, 0.1, …, 1.
const WALL_CELLS: u32 = 11;

/// The most starts an array gives the search ([`ArrayDomain::starts`]).
const MAX_STARTS: usize = 40;

/// The turns, degrees about each lamp's aim, a searched orientation chooses between.
const TURNS: [f64; 2] = [0.0, 90.0];

/// Where a `<lightArray>` ranges.
#[derive(Debug, Clone, PartialEq)]
pub struct ArrayDomain {
    /// The rectangle the lamps are set out on: columns along its first edge (A→B),
    /// rows along the other.
    pub rect: Parallelogram,
    /// The least and greatest number of columns.
    pub columns: (u32, u32),
    /// The least and greatest number of rows.
    pub rows: (u32, u32),
    /// The lamps the array may use: columns × rows beyond it are refused.
    pub lamps: u32,
    /// Whether the lamps' orientation is searched (a fifth coordinate, 0° or 90°);
    /// otherwise the problem file fixes it and the scene is loaded turned.
    pub turns: bool,
    /// Where the fittings lie end to end in rows (`continuous="true"`), their length.
    pub continuous: Option<Rows>,
}

/// Fittings laid end to end in rows (`<lightArray continuous="true">`): continuous
/// trunking, a row of linear luminaires with no gap between them. Each row is centred
/// on the rectangle along the edge the fittings' length lies on, its lamps one
/// fitting's length apart centre to centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rows {
    /// The edge the fittings' length lies along as loaded (before a searched
    /// orientation turns them): 0 the first (A→B), 1 the other.
    pub along: usize,
    /// The fittings' length as a fraction of each edge's.
    pub pitch: [f64; 2],
}

impl Rows {
    /// The edge the rows run along with the lamps turned `orientation` degrees (0 or
    /// 90) from their frames as loaded: a quarter turn lays them along the other.
    pub fn axis(&self, orientation: Option<f64>) -> usize {
        self.along ^ usize::from(orientation == Some(90.0))
    }
}

/// An array's columns, rows and wall fractions: a `<lightArray>`'s value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrayShape {
    /// Lamps along the rectangle's first edge.
    pub columns: u32,
    /// Lamps along the other.
    pub rows: u32,
    /// The distance from the outer columns and rows to the rectangle's edges, each a
    /// fraction of its spacing, in [0, 1].
    pub walls: [f64; 2],
    /// The degrees every lamp is turned about its aim from its frame as loaded, 0 or
    /// 90, where the search chooses it; `None` where the problem file fixes it.
    pub orientation: Option<f64>,
}

impl ArrayShape {
    /// The lamps it sets out.
    pub fn lamps(&self) -> u32 {
        self.columns * self.rows
    }

    /// The lamps along edge `axis`: the columns along the first, the rows along the
    /// other.
    pub fn count(&self, axis: usize) -> u32 {
        [self.columns, self.rows][axis]
    }

    /// The parallelogram coordinates (s, t) of lamp `k` (row by row: lamp k is in
    /// column k mod columns, row k div columns); in continuous `rows`, along their
    /// edge one pitch apart and centred, whatever that edge's wall fraction.
    pub fn place(&self, k: u32, rows: Option<&Rows>) -> (f64, f64) {
        let at = |i: u32, n: u32, f: f64| {
            let span = f64::from(n) - 1.0 + 2.0 * f;
            if span <= 0.0 {
                0.5
            } else {
                (f64::from(i) + f) / span
            }
        };
        let mut st = [
            at(k % self.columns, self.columns, self.walls[0]),
            at(k / self.columns, self.rows, self.walls[1]),
        ];
        if let Some(r) = rows {
            let axis = r.axis(self.orientation);
            let i = [k % self.columns, k / self.columns][axis];
            let middle = 0.5 * (f64::from(self.count(axis)) - 1.0);
            st[axis] = 0.5 + (f64::from(i) - middle) * r.pitch[axis];
        }
        (st[0], st[1])
    }

    /// How long its continuous `rows` are, as a fraction of their edge: more than 1 is
    /// a row longer than the rectangle.
    pub fn row_length(&self, rows: &Rows) -> f64 {
        let axis = rows.axis(self.orientation);
        f64::from(self.count(axis)) * rows.pitch[axis]
    }
}

impl ArrayDomain {
    /// Its coordinates: columns, rows, the two wall fractions and, when searched, the
    /// orientation.
    pub fn dimensions(&self) -> usize {
        if self.turns { 5 } else { 4 }
    }

    /// The cells of each coordinate: one per count of columns and of rows, eleven per
    /// wall fraction (tenths from 0 to 1), two for a searched orientation.
    pub fn cells(&self) -> Vec<u32> {
        let mut cells = vec![
            self.columns.1 - self.columns.0 + 1,
            self.rows.1 - self.rows.0 + 1,
            WALL_CELLS,
            WALL_CELLS,
        ];
        if self.turns {
            cells.push(TURNS.len() as u32);
        }
        cells
    }

    /// Maps `cell` (this array's cells) to the one cell of its layout: in continuous
    /// rows, the wall fraction along the rows (which the rows, centred, ignore) to its
    /// middle cell, ½. Configurations that differ in it alone are one layout, and the
    /// search, which keys what it has seen by cell, then evaluates it once.
    pub fn canonical(&self, cell: &mut [u32]) {
        if let Some(rows) = &self.continuous {
            let orientation = self.turns.then(|| TURNS[cell[4].min(1) as usize]);
            cell[2 + rows.axis(orientation)] = WALL_CELLS / 2;
        }
    }

    /// The shape at normalised coordinates `x` (columns, rows, the two wall fractions,
    /// the orientation when searched).
    pub fn shape(&self, x: &[f64]) -> ArrayShape {
        let cells = self.cells();
        let count = |x: f64, (lo, _): (u32, u32), n: u32| {
            lo + ((x * f64::from(n)).floor().max(0.0) as u32).min(n - 1)
        };
        // In whole tenths, so that a value reads as written ("0.3", not 0.30000000000000004).
        let wall = |x: f64| {
            f64::from(((x * f64::from(WALL_CELLS)).floor().max(0.0) as u32).min(10)) / 10.0
        };
        ArrayShape {
            columns: count(x[0], self.columns, cells[0]),
            rows: count(x[1], self.rows, cells[1]),
            walls: [wall(x[2]), wall(x[3])],
            orientation: self.turns.then(|| TURNS[usize::from(x[4] >= 0.5)]),
        }
    }

    /// The normalised coordinates of `shape` (the centre of its cell), or `None` when
    /// it lies outside the domain (an orientation other than 0° or 90° where it is
    /// searched, or any where it is not, included).
    pub fn coords(&self, shape: &ArrayShape) -> Option<Vec<f64>> {
        let cells = self.cells();
        let inside = |n: u32, (lo, hi): (u32, u32)| (lo..=hi).contains(&n);
        if !inside(shape.columns, self.columns)
            || !inside(shape.rows, self.rows)
            || shape
                .walls
                .iter()
                .any(|f| !(-1e-6..=1.0 + 1e-6).contains(f))
        {
            return None;
        }
        let count = |n: u32, lo: u32, c: u32| (f64::from(n - lo) + 0.5) / f64::from(c);
        let wall = |f: f64| ((10.0 * f).round() + 0.5) / f64::from(WALL_CELLS);
        let mut coords = vec![
            count(shape.columns, self.columns.0, cells[0]),
            count(shape.rows, self.rows.0, cells[1]),
            wall(shape.walls[0]),
            wall(shape.walls[1]),
        ];
        match (self.turns, shape.orientation) {
            (false, None) => {}
            (true, Some(o)) => {
                let k = TURNS.iter().position(|t| (t - o).abs() < 1e-6)?;
                coords.push((k as f64 + 0.5) / TURNS.len() as f64);
            }
            _ => return None,
        }
        Some(coords)
    }

    /// The regular arrays the search starts from: every count of columns and rows of
    /// at most [`ArrayDomain::lamps`] lamps, most lamps first, half a spacing from the
    /// walls, in each orientation when it is searched; then, while there are fewer
    /// than 40, each of them with its outer lamps 0.3, 0.5 or 0.7 of a spacing from
    /// each pair of walls. A look with few photons can misjudge a shape's uniformity,
    /// and the wall distance is what uniformity turns on, so the walk starts from a
    /// spread of them rather than one; an orientation can decide feasibility outright
    /// (fittings that only fit one way, glare across them), so both are started from.
    /// Continuous rows ignore the fraction along them, so it is spread across only.
    pub fn starts(&self) -> Vec<ArrayShape> {
        let mut shapes: Vec<(u32, u32)> = (self.rows.0..=self.rows.1)
            .flat_map(|rows| (self.columns.0..=self.columns.1).map(move |c| (c, rows)))
            .filter(|(c, r)| c * r <= self.lamps)
            .collect();
        shapes.sort_by_key(|(c, r)| std::cmp::Reverse(c * r));
        let orientations: Vec<Option<f64>> = if self.turns {
            TURNS.iter().map(|&t| Some(t)).collect()
        } else {
            vec![None]
        };
        let turned: Vec<((u32, u32), Option<f64>)> = shapes
            .iter()
            .flat_map(|&s| orientations.iter().map(move |&o| (s, o)))
            .collect();
        let shape = |((columns, rows), orientation): ((u32, u32), Option<f64>), walls| ArrayShape {
            columns,
            rows,
            walls,
            orientation,
        };
        let mut out: Vec<ArrayShape> = turned.iter().map(|&s| shape(s, [0.5, 0.5])).collect();
        const SPREAD: [f64; 3] = [0.3, 0.5, 0.7];
        for &s in &turned {
            // Continuous rows ignore the wall fraction along them: spread the other.
            let ignored = self.continuous.map(|r| r.axis(s.1));
            for a in SPREAD {
                for b in SPREAD {
                    let walls = [a, b];
                    let fresh = walls != [0.5, 0.5] && ignored.is_none_or(|i| walls[i] == 0.5);
                    if out.len() < MAX_STARTS && fresh {
                        out.push(shape(s, walls));
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn domain() -> ArrayDomain {
        ArrayDomain {
            rect: Parallelogram::from_corners(
                DVec3::ZERO,
                [
                    DVec3::new(6.0, 0.0, 0.0),
                    DVec3::new(6.0, 0.0, 4.0),
                    DVec3::new(0.0, 0.0, 4.0),
                ],
            )
            .unwrap(),
            columns: (2, 6),
            rows: (2, 4),
            lamps: 6,
            turns: false,
            continuous: None,
        }
    }

    #[test]
    fn lamps_are_set_out_evenly_at_their_wall_fraction() {
        let s = ArrayShape {
            columns: 3,
            rows: 2,
            walls: [0.5, 0.0],
            orientation: None,
        };
        let along: Vec<f64> = (0..3).map(|k| s.place(k, None).0).collect();
        // Half a spacing from the edges: 1/6, 3/6, 5/6 of the length.
        for (a, b) in along.iter().zip([1.0 / 6.0, 0.5, 5.0 / 6.0]) {
            assert!((a - b).abs() < 1e-12, "{along:?}");
        }
        // On the edges, second row on the far edge.
        assert_eq!(s.place(0, None).1, 0.0);
        assert_eq!(s.place(3, None).1, 1.0);
        // One lamp alone stands in the middle whatever its fraction.
        let one = ArrayShape {
            columns: 1,
            rows: 1,
            walls: [0.0, 1.0],
            orientation: None,
        };
        assert_eq!(one.place(0, None), (0.5, 0.5));
    }

    #[test]
    fn shapes_go_to_coordinates_and_back() {
        let d = domain();
        for columns in 2..=6 {
            for rows in 2..=4 {
                for tenth in 0..=10 {
                    let f = f64::from(tenth) / 10.0;
                    let s = ArrayShape {
                        columns,
                        rows,
                        walls: [f, 1.0 - f],
                        orientation: None,
                    };
                    let back = d.shape(&d.coords(&s).unwrap());
                    assert_eq!((back.columns, back.rows), (columns, rows));
                    assert!((back.walls[0] - f).abs() < 1e-12);
                    assert!((back.walls[1] - (1.0 - f)).abs() < 1e-12);
                }
            }
        }
        let outside = ArrayShape {
            columns: 7,
            rows: 2,
            walls: [0.5, 0.5],
            orientation: None,
        };
        assert_eq!(d.coords(&outside), None);
    }

    #[test]
    fn starts_are_the_arrays_the_lamps_can_make() {
        let starts: Vec<(u32, u32)> = domain()
            .starts()
            .iter()
            .map(|s| (s.columns, s.rows))
            .collect();
        assert_eq!(starts[..3], [(3, 2), (2, 3), (2, 2)]);
        // Then each at a spread of wall distances, as long as there is room.
        assert_eq!(starts.len(), 3 + 3 * 8);
        let mut d = domain();
        (d.columns, d.rows, d.lamps) = ((1, 10), (1, 10), 100);
        // Every shape once at half a spacing, and no spread past the cap.
        assert_eq!(d.starts().len(), 100);
    }

    /// A searched orientation is a fifth coordinate of two cells, 0° below its middle
    /// and 90° above; a shape goes to its cell and back, and one of the other kind (an
    /// orientation where none is searched, none where it is) lies outside.
    #[test]
    fn a_searched_orientation_is_a_coordinate_of_two_cells() {
        let mut d = domain();
        d.turns = true;
        assert_eq!((d.dimensions(), d.cells()[4]), (5, 2));
        assert_eq!(d.shape(&[0.5, 0.5, 0.5, 0.5, 0.49]).orientation, Some(0.0));
        assert_eq!(d.shape(&[0.5, 0.5, 0.5, 0.5, 0.5]).orientation, Some(90.0));
        for orientation in [0.0, 90.0] {
            let s = ArrayShape {
                columns: 3,
                rows: 2,
                walls: [0.3, 0.7],
                orientation: Some(orientation),
            };
            assert_eq!(d.shape(&d.coords(&s).unwrap()), s);
        }
        let fixed = ArrayShape {
            columns: 3,
            rows: 2,
            walls: [0.5, 0.5],
            orientation: None,
        };
        assert_eq!(d.coords(&fixed), None);
        let askew = ArrayShape {
            orientation: Some(45.0),
            ..fixed
        };
        assert_eq!(d.coords(&askew), None);
        let turned = ArrayShape {
            orientation: Some(90.0),
            ..fixed
        };
        assert_eq!(domain().coords(&turned), None);
        assert_eq!(domain().dimensions(), 4);
    }

    /// Both orientations start every shape, before any spread of wall distances, and
    /// the spread stops at the cap.
    #[test]
    fn a_searched_orientation_starts_both_ways() {
        let mut d = domain();
        d.turns = true;
        let starts = d.starts();
        let first: Vec<(u32, u32, Option<f64>)> = starts[..6]
            .iter()
            .map(|s| (s.columns, s.rows, s.orientation))
            .collect();
        assert_eq!(
            first,
            [
                (3, 2, Some(0.0)),
                (3, 2, Some(90.0)),
                (2, 3, Some(0.0)),
                (2, 3, Some(90.0)),
                (2, 2, Some(0.0)),
                (2, 2, Some(90.0)),
            ]
        );
        assert!(starts[..6].iter().all(|s| s.walls == [0.5, 0.5]));
        assert_eq!(starts.len(), MAX_STARTS);
    }

    /// Continuous rows (here along the first edge as loaded) ignore the wall fraction
    /// along them: the starts spread the other alone, and a cell's ignored fraction
    /// goes to its middle, along the other edge where a searched 90° turns the rows.
    #[test]
    fn continuous_rows_start_and_keep_one_cell_per_layout() {
        let mut d = domain();
        d.continuous = Some(Rows {
            along: 0,
            pitch: [0.25, 0.375],
        });
        let starts = d.starts();
        assert!(starts.iter().all(|s| s.walls[0] == 0.5), "{starts:?}");
        assert_eq!(starts.len(), 3 + 3 * 2);
        let mut cell = [0, 0, 2, 7];
        d.canonical(&mut cell);
        assert_eq!(cell, [0, 0, 5, 7]);
        d.turns = true;
        let mut turned = [0, 0, 2, 7, 1];
        d.canonical(&mut turned);
        assert_eq!(turned, [0, 0, 2, 5, 1]);
        // Four along the first edge, a quarter of it each: the whole edge, centred.
        let s = ArrayShape {
            columns: 4,
            rows: 1,
            walls: [0.0, 0.5],
            orientation: Some(0.0),
        };
        let rows = d.continuous.unwrap();
        let along: Vec<f64> = (0..4).map(|k| s.place(k, Some(&rows)).0).collect();
        assert_eq!(along, [0.125, 0.375, 0.625, 0.875]);
        assert_eq!(s.row_length(&rows), 1.0);
    }
}
