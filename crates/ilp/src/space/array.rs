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

use super::Parallelogram;

/// Cells of a wall fraction: eleven, centred on 0, 0.1, …, 1.
const WALL_CELLS: u32 = 11;

/// The most starts an array gives the search ([`ArrayDomain::starts`]).
const MAX_STARTS: usize = 40;

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
}

impl ArrayShape {
    /// The lamps it sets out.
    pub fn lamps(&self) -> u32 {
        self.columns * self.rows
    }

    /// The parallelogram coordinates (s, t) of lamp `k` (row by row: lamp k is in
    /// column k mod columns, row k div columns).
    pub fn place(&self, k: u32) -> (f64, f64) {
        let at = |i: u32, n: u32, f: f64| {
            let span = f64::from(n) - 1.0 + 2.0 * f;
            if span <= 0.0 {
                0.5
            } else {
                (f64::from(i) + f) / span
            }
        };
        (
            at(k % self.columns, self.columns, self.walls[0]),
            at(k / self.columns, self.rows, self.walls[1]),
        )
    }
}

impl ArrayDomain {
    /// The cells of each of its four coordinates: one per count of columns and of
    /// rows, eleven per wall fraction (tenths from 0 to 1).
    pub fn cells(&self) -> [u32; 4] {
        [
            self.columns.1 - self.columns.0 + 1,
            self.rows.1 - self.rows.0 + 1,
            WALL_CELLS,
            WALL_CELLS,
        ]
    }

    /// The shape at normalised coordinates `x` (columns, rows, the two wall fractions).
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
        }
    }

    /// The normalised coordinates of `shape` (the centre of its cell), or `None` when
    /// it lies outside the domain.
    pub fn coords(&self, shape: &ArrayShape) -> Option<[f64; 4]> {
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
        Some([
            count(shape.columns, self.columns.0, cells[0]),
            count(shape.rows, self.rows.0, cells[1]),
            wall(shape.walls[0]),
            wall(shape.walls[1]),
        ])
    }

    /// The regular arrays the search starts from: every count of columns and rows of
    /// at most [`ArrayDomain::lamps`] lamps, most lamps first, half a spacing from the
    /// walls; then, while there are fewer than 40, each of them with its
    /// outer lamps 0.3, 0.5 or 0.7 of a spacing from each pair of walls. A look with
    /// few photons can misjudge a shape's uniformity, and the wall distance is what
    /// uniformity turns on, so the walk starts from a spread of them rather than one.
    pub fn starts(&self) -> Vec<ArrayShape> {
        let mut shapes: Vec<(u32, u32)> = (self.rows.0..=self.rows.1)
            .flat_map(|rows| (self.columns.0..=self.columns.1).map(move |c| (c, rows)))
            .filter(|(c, r)| c * r <= self.lamps)
            .collect();
        shapes.sort_by_key(|(c, r)| std::cmp::Reverse(c * r));
        let shape = |(columns, rows): (u32, u32), walls| ArrayShape {
            columns,
            rows,
            walls,
        };
        let mut out: Vec<ArrayShape> = shapes.iter().map(|&s| shape(s, [0.5, 0.5])).collect();
        const SPREAD: [f64; 3] = [0.3, 0.5, 0.7];
        for &s in &shapes {
            for a in SPREAD {
                for b in SPREAD {
                    if out.len() < MAX_STARTS && (a, b) != (0.5, 0.5) {
                        out.push(shape(s, [a, b]));
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
        }
    }

    #[test]
    fn lamps_are_set_out_evenly_at_their_wall_fraction() {
        let s = ArrayShape {
            columns: 3,
            rows: 2,
            walls: [0.5, 0.0],
        };
        let along: Vec<f64> = (0..3).map(|k| s.place(k).0).collect();
        // Half a spacing from the edges: 1/6, 3/6, 5/6 of the length.
        for (a, b) in along.iter().zip([1.0 / 6.0, 0.5, 5.0 / 6.0]) {
            assert!((a - b).abs() < 1e-12, "{along:?}");
        }
        // On the edges, second row on the far edge.
        assert_eq!(s.place(0).1, 0.0);
        assert_eq!(s.place(3).1, 1.0);
        // One lamp alone stands in the middle whatever its fraction.
        let one = ArrayShape {
            columns: 1,
            rows: 1,
            walls: [0.0, 1.0],
        };
        assert_eq!(one.place(0), (0.5, 0.5));
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
}
