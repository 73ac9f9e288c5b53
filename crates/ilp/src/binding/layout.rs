//! An answer's lamps as a designer specifies them: the interchangeable lamps of one
//! placement rectangle read as a regular array — rows × columns, the spacing, the
//! distance from the walls — when they form one, else said to be irregular, with their
//! dimming levels ("2 × 3 array, 2.40 m × 2.40 m apart, 0.60 m × 0.60 m from the
//! walls, all at 72 %"). A search over free positions can return either; a regular
//! array is what a DIALux user draws and an installer sets out, so the answer says
//! which it is instead of leaving six coordinates to be read.

use super::array::EDGES;
use super::{Binding, Target, VariableValue};
use crate::problem::VariableKind;
use crate::space::{Configuration, Domain};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A group of interchangeable lamps of an answer, as laid out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Layout {
    /// The lamps' placement variables, in the problem's order.
    pub lights: Vec<String>,
    /// The placement rectangle they share.
    pub surface: String,
    /// The regular array they form, if they form one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub array: Option<ArrayLayout>,
    /// Each lamp's dimming level (its output over its authored output), in `lights`'
    /// order; 1 for a lamp no variable dims.
    pub levels: Vec<f64>,
    /// The lamps a `<lightArray>` leaves off (beyond its columns × rows).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub off: Vec<String>,
    /// The layout in a sentence.
    pub description: String,
}

/// A regular array of lamps on a placement rectangle. Columns run along the
/// rectangle's first edge (A→B), rows along the other.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArrayLayout {
    /// Lamps along the first edge.
    pub columns: u32,
    /// Lamps along the other.
    pub rows: u32,
    /// The mean distance between neighbouring columns and between neighbouring rows,
    /// m (0 for a single column or row).
    pub spacing: [f64; 2],
    /// How far the farthest lamp is from where the regular array of that spacing puts
    /// it, m: the search moves lamps in whole cells, so an array it finds is regular to
    /// within a cell.
    pub deviation: f64,
    /// The least distance from the outer columns and rows to the walls (the scene's
    /// bounds) along the rectangle's edges, m; absent when an edge is not along an axis
    /// of the scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from_walls: Option<[f64; 2]>,
    /// The clear gap between neighbouring fittings along the columns and the rows, m
    /// (the spacing less the luminaires' outline, from their photometric file): what an
    /// installer reads between two fittings; absent when the luminaires have no
    /// outline. Meaningless along an axis of one column or row.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub between: Option<[f64; 2]>,
    /// The degrees a `<lightArray>` whose orientation is searched turns its fittings
    /// about their aim, 0 or 90; absent where the problem file fixes it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation: Option<f64>,
    /// The edge of the rectangle the fittings' length lies along as turned, 0 the
    /// first (A→B), 1 the other; absent unless the orientation is searched and the
    /// fittings have an outline longer one way than the other.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lengthwise: Option<usize>,
    /// The edge continuous rows (`continuous="true"`, the fittings end to end) run
    /// along, 0 the first, 1 the other: along it the spacing is the fittings' length
    /// and nothing is between them; absent where the fittings are spaced.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub continuous: Option<usize>,
}

/// The regular array `points` (in a plane's coordinates, m) form, each of its distinct
/// columns and rows told apart by more than `tolerance` (one search cell along each
/// axis): every column × row crossing holds one point, and neighbouring columns (and
/// rows) are spaced alike to within `tolerance`. Returns the columns' and rows'
/// positions (each the mean of its points) and the largest distance of a point from
/// the array of equal spacing through the first and last column and row.
pub fn regular_array(
    points: &[[f64; 2]],
    tolerance: [f64; 2],
) -> Option<(Vec<f64>, Vec<f64>, f64)> {
    let lines = |axis: usize| -> Vec<f64> {
        let mut v: Vec<f64> = points.iter().map(|p| p[axis]).collect();
        v.sort_by(f64::total_cmp);
        let mut groups: Vec<Vec<f64>> = Vec::new();
        for x in v {
            match groups.last_mut() {
                Some(g) if x - g[g.len() - 1] <= 0.5 * tolerance[axis] => g.push(x),
                _ => groups.push(vec![x]),
            }
        }
        groups
            .iter()
            .map(|g| g.iter().sum::<f64>() / g.len() as f64)
            .collect()
    };
    let (columns, rows) = (lines(0), lines(1));
    if columns.len() * rows.len() != points.len() {
        return None;
    }
    let nearest = |lines: &[f64], x: f64| {
        lines
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - x).abs().total_cmp(&(b.1 - x).abs()))
            .map_or(0, |(i, _)| i)
    };
    let mut taken = vec![false; points.len()];
    for p in points {
        let k = nearest(&columns, p[0]) * rows.len() + nearest(&rows, p[1]);
        if std::mem::replace(&mut taken[k], true) {
            return None;
        }
    }
    let even = |lines: &[f64], i: usize| match lines.len() {
        1 => lines[0],
        n => lines[0] + (lines[n - 1] - lines[0]) * i as f64 / (n - 1) as f64,
    };
    let mut deviation: f64 = 0.0;
    for p in points {
        let (i, j) = (nearest(&columns, p[0]), nearest(&rows, p[1]));
        let d = [p[0] - even(&columns, i), p[1] - even(&rows, j)];
        if d[0].abs() > tolerance[0] || d[1].abs() > tolerance[1] {
            return None;
        }
        deviation = deviation.max(d[0].hypot(d[1]));
    }
    Some((columns, rows, deviation))
}

impl Binding {
    /// The layout of each `<lightArray>` and of each group of interchangeable lamps at
    /// `config` (the groups of [`crate::space::Space::exchangeable`]).
    pub fn layouts(&self, config: &Configuration) -> Vec<Layout> {
        let values = self.values(config);
        let variables = self.space.variables();
        let mut out = self.array_layouts(&values);
        for group in self.space.exchangeable() {
            let first = group[0][0];
            let (Domain::Parallelogram(rect), VariableKind::LightInSurface(spec)) =
                (&variables[first].domain, &self.specs[first].kind)
            else {
                continue;
            };
            let u = rect.e1.normalize();
            let v = rect.e1.cross(rect.e2).cross(rect.e1).normalize();
            let cells = |i: usize| {
                let o: usize = variables[..first]
                    .iter()
                    .map(|x| x.domain.dimensions())
                    .sum();
                f64::from(self.space.cells_per_dimension()[o + i])
            };
            let tolerance = [rect.e1.length() / cells(0), rect.e2.dot(v).abs() / cells(1)];
            let anchors: Vec<DVec3> = group
                .iter()
                .map(|m| match values[m[0]] {
                    super::VariableValue::Position { anchor, .. } => anchor,
                    _ => rect.a,
                })
                .collect();
            let points: Vec<[f64; 2]> = anchors
                .iter()
                .map(|p| [(*p - rect.a).dot(u), (*p - rect.a).dot(v)])
                .collect();
            let levels: Vec<f64> = group.iter().map(|m| self.level_of(m, &values)).collect();
            let array = regular_array(&points, tolerance).map(|(columns, rows, deviation)| {
                let spacing = |l: &[f64]| match l.len() {
                    1 => 0.0,
                    n => (l[n - 1] - l[0]) / (n - 1) as f64,
                };
                let spacing = [spacing(&columns), spacing(&rows)];
                ArrayLayout {
                    columns: columns.len() as u32,
                    rows: rows.len() as u32,
                    spacing,
                    between: self.gaps(first, spacing, [u, v], 0.0),
                    deviation,
                    from_walls: self.bounds.and_then(|b| {
                        Some([
                            wall_distance(&b, &anchors, u)?,
                            wall_distance(&b, &anchors, v)?,
                        ])
                    }),
                    orientation: None,
                    lengthwise: None,
                    continuous: None,
                }
            });
            let lights: Vec<String> = group.iter().map(|m| variables[m[0]].id.clone()).collect();
            let description = describe(&lights, &spec.surface, array.as_ref(), &levels, &[]);
            out.push(Layout {
                lights,
                surface: spec.surface.clone(),
                array,
                levels,
                off: Vec::new(),
                description,
            });
        }
        out
    }

    /// The layout of each `<lightArray>` at `values`: its shape in metres, its lamps'
    /// levels and the lamps it leaves off.
    fn array_layouts(&self, values: &[VariableValue]) -> Vec<Layout> {
        let mut out = Vec::new();
        for (variable, ((value, target), spec)) in values
            .iter()
            .zip(&self.targets)
            .zip(&self.specs)
            .enumerate()
        {
            let (VariableValue::Array(shape), Target::Array(lamps), VariableKind::LightArray(a)) =
                (value, target, &spec.kind)
            else {
                continue;
            };
            let rect = &lamps.rect;
            let on = (shape.lamps() as usize).min(lamps.lamps.len());
            let name = |&(l, _, _): &(invlight_scene::LightId, DVec3, _)| {
                self.light_names[l.index()].clone()
            };
            let lights: Vec<String> = lamps.lamps[..on].iter().map(name).collect();
            let off: Vec<String> = lamps.lamps[on..].iter().map(name).collect();
            let places: Vec<DVec3> = (0..on as u32)
                .map(|k| lamps.place(shape, k) + lamps.lamps[k as usize].1)
                .collect();
            let spacing = |n: u32, f: f64, edge: DVec3| match n {
                1 => 0.0,
                n => edge.length() / (f64::from(n) - 1.0 + 2.0 * f),
            };
            let (u, v) = (
                rect.e1.normalize(),
                rect.e1.cross(rect.e2).cross(rect.e1).normalize(),
            );
            let mut spacing = [
                spacing(shape.columns, shape.walls[0], rect.e1),
                spacing(shape.rows, shape.walls[1], rect.e2),
            ];
            let turn = shape.orientation.unwrap_or(0.0);
            let continuous = lamps.rows.map(|r| r.axis(shape.orientation));
            let mut between = None;
            if let (Some(axis), Some(r)) = (continuous, lamps.rows) {
                spacing[axis] = r.pitch[axis] * [rect.e1, rect.e2][axis].length();
            }
            if let Some(mut g) = self.gaps(variable, spacing, [u, v], turn) {
                // End to end: nothing between, not the rounding of a length less itself.
                if let Some(axis) = continuous {
                    g[axis] = 0.0;
                }
                between = Some(g);
            }
            let array = ArrayLayout {
                columns: shape.columns,
                rows: shape.rows,
                spacing,
                between,
                continuous,
                orientation: shape.orientation,
                lengthwise: shape
                    .orientation
                    .and_then(|o| self.lengthwise(variable, [u, v], o)),
                deviation: 0.0,
                from_walls: self.bounds.and_then(|b| {
                    Some([
                        wall_distance(&b, &places, u)?,
                        wall_distance(&b, &places, v)?,
                    ])
                }),
            };
            let levels: Vec<f64> = lamps.lamps[..on]
                .iter()
                .map(|&(l, _, _)| self.light_level(l, values))
                .collect();
            let description = format!(
                "{}: {}",
                spec.id,
                describe(&lights, &a.surface, Some(&array), &levels, &off)
            );
            out.push(Layout {
                lights,
                surface: a.surface.clone(),
                array: Some(array),
                levels,
                off,
                description,
            });
        }
        out
    }

    /// The level of an interchangeable member's lamp: its own `lightPower`, else its
    /// `<lightGroup>`'s, else 1.
    fn level_of(&self, member: &[usize], values: &[VariableValue]) -> f64 {
        if let Some(&VariableValue::Power(p)) = member.get(1).map(|&i| &values[i]) {
            return p;
        }
        match &self.targets[member[0]] {
            Target::Move(m) => m
                .lights
                .first()
                .map_or(1.0, |&(light, _)| self.light_level(light, values)),
            _ => 1.0,
        }
    }

    /// The level of `light` at `values`: its `lightPower`'s or its group's, else 1.
    fn light_level(&self, light: invlight_scene::LightId, values: &[VariableValue]) -> f64 {
        self.targets
            .iter()
            .position(|t| matches!(t, Target::Power { dimmed, .. } if dimmed.holds(light)))
            .and_then(|i| match values[i] {
                VariableValue::Power(p) => Some(p),
                _ => None,
            })
            .unwrap_or(1.0)
    }
}

/// The least distance along `axis` (a unit vector along one of the scene's axes) from
/// the outermost of `points` to the box's faces; none when `axis` is not along one.
fn wall_distance(bounds: &super::Bounds, points: &[DVec3], axis: DVec3) -> Option<f64> {
    let k = (0..3).find(|&k| axis[k].abs() > 1.0 - 1e-6)?;
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[k]), hi.max(p[k]))
        });
    Some((lo - bounds.lo[k]).min(bounds.hi[k] - hi))
}

/// "Lamp1 … Lamp6 on LampZone: a 2 × 3 array (2 rows of 3), 2.40 m × 2.40 m apart,
/// 0.60 m × 0.60 m from the walls; all at 72 %", with the fittings' orientation after
/// the shape where the search chose it ("fittings turned 90°, lengthwise along the
/// first edge") and, before it, fittings laid end to end ("continuous rows along the
/// other edge", 0 m between them along the rows).
fn describe(
    lights: &[String],
    surface: &str,
    array: Option<&ArrayLayout>,
    levels: &[f64],
    off: &[String],
) -> String {
    let who = match lights {
        [one] => one.clone(),
        [first, .., last] => format!("{first} … {last}"),
        [] => String::new(),
    };
    let m = |x: f64| format!("{x:.2} m");
    let shape = match array {
        Some(a) => {
            let mut s = format!(
                "a {} × {} array ({} rows of {}), ",
                a.rows, a.columns, a.rows, a.columns,
            );
            if let Some(e) = a.continuous {
                s += &format!("continuous rows along the {} edge, ", EDGES[e]);
            }
            if let Some(o) = a.orientation {
                s += &if o == 0.0 {
                    "fittings as authored (0°)".to_string()
                } else {
                    format!("fittings turned {o}°")
                };
                // Continuous rows lie lengthwise by what they are: said once, above.
                if let Some(e) = a.lengthwise.filter(|_| a.continuous.is_none()) {
                    s += [
                        ", lengthwise along the first edge",
                        ", lengthwise along the other edge",
                    ][e];
                }
                s += ", ";
            }
            s += &format!("{} × {} apart", m(a.spacing[0]), m(a.spacing[1]));
            if let Some(g) = a.between {
                // Along an axis of one column or row there is no neighbour to stand apart from.
                let gap = |i: usize, n: u32| if n > 1 { m(g[i]) } else { "—".into() };
                s += &format!(
                    " ({} × {} between fittings)",
                    gap(0, a.columns),
                    gap(1, a.rows)
                );
            }
            if let Some(w) = a.from_walls {
                s += &format!(", {} × {} from the walls", m(w[0]), m(w[1]));
            }
            if a.deviation > 1e-6 {
                s += &format!(" (regular to within {})", m(a.deviation));
            }
            s
        }
        None => format!(
            "{} lamps at irregular positions, not a regular array",
            lights.len()
        ),
    };
    let pct = |x: f64| format!("{:.0} %", 100.0 * x);
    let (lo, hi) = levels
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    let dimmed = if levels.is_empty() {
        String::new()
    } else if hi - lo <= 0.005 {
        format!("; all at {}", pct(lo))
    } else {
        format!(
            "; at {}–{} ({})",
            pct(lo),
            pct(hi),
            levels
                .iter()
                .map(|&x| pct(x))
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let off = match off {
        [] => String::new(),
        [one] => format!("; {one} off"),
        [a, b] => format!("; {a} and {b} off"),
        [first, .., last] => format!("; {first} … {last} off"),
    };
    format!("{who} on {surface}: {shape}{dimmed}{off}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_of_points_is_a_regular_array() {
        // 3 columns 2.4 m apart, 2 rows 2.4 m apart, in any order.
        let p = [
            [4.8, 0.0],
            [0.0, 0.0],
            [2.4, 2.4],
            [0.0, 2.4],
            [2.4, 0.0],
            [4.8, 2.4],
        ];
        let (columns, rows, deviation) = regular_array(&p, [0.36, 0.36]).unwrap();
        assert_eq!(columns, vec![0.0, 2.4, 4.8]);
        assert_eq!(rows, vec![0.0, 2.4]);
        assert!(deviation < 1e-12);
        // Within a cell of regular: still an array, with its deviation.
        let mut q = p;
        q[0] = [4.8 + 0.1, 0.1];
        let (_, _, d) = regular_array(&q, [0.36, 0.36]).unwrap();
        assert!(d > 0.05 && d < 0.2, "{d}");
        // A single row is an array of one row.
        let (c, r, _) = regular_array(&[[0.0, 1.0], [2.0, 1.0], [4.0, 1.0]], [0.3, 0.3]).unwrap();
        assert_eq!((c.len(), r.len()), (3, 1));
    }

    #[test]
    fn irregular_points_are_not_an_array() {
        // Six positions of a search's answer: three distinct rows, no grid.
        let p = [
            [1.2, 1.4],
            [1.2, 3.0],
            [3.1, 1.6],
            [3.5, 2.8],
            [5.4, 0.7],
            [5.4, 2.8],
        ];
        assert!(regular_array(&p, [0.36, 0.24]).is_none());
        // A full grid whose columns are unevenly spaced (0, 1, 4 m) is not regular.
        let q = [
            [0.0, 0.0],
            [1.0, 0.0],
            [4.0, 0.0],
            [0.0, 2.0],
            [1.0, 2.0],
            [4.0, 2.0],
        ];
        assert!(regular_array(&q, [0.3, 0.3]).is_none());
        // Two lamps on one crossing and a crossing empty: not an array.
        let r = [[0.0, 0.0], [0.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        assert!(regular_array(&r, [0.3, 0.3]).is_none());
    }

    #[test]
    fn a_layout_reads_as_a_designer_writes_it() {
        let lights: Vec<String> = (1..=6).map(|i| format!("Lamp{i}")).collect();
        let array = ArrayLayout {
            columns: 3,
            rows: 2,
            spacing: [2.4, 2.4],
            deviation: 0.0,
            from_walls: Some([1.2, 1.2]),
            between: None,
            orientation: None,
            lengthwise: None,
            continuous: None,
        };
        assert_eq!(
            describe(&lights, "LampZone", Some(&array), &[0.72; 6], &[]),
            "Lamp1 … Lamp6 on LampZone: a 2 × 3 array (2 rows of 3), 2.40 m × 2.40 m apart, 1.20 m × 1.20 m from the walls; all at 72 %"
        );
        // Fittings 1.52 m long along the rows: the gap an installer measures.
        let fitted = ArrayLayout {
            between: Some([2.32, 0.88]),
            ..array
        };
        assert!(
            describe(&lights, "LampZone", Some(&fitted), &[0.72; 6], &[])
                .contains("2.40 m × 2.40 m apart (2.32 m × 0.88 m between fittings)")
        );
        // The orientation the search chose, and which way the fittings' length lies.
        let turned = ArrayLayout {
            orientation: Some(90.0),
            lengthwise: Some(0),
            ..fitted.clone()
        };
        assert!(
            describe(&lights, "LampZone", Some(&turned), &[0.72; 6], &[]).contains(
                "(2 rows of 3), fittings turned 90°, lengthwise along the first edge, 2.40 m × 2.40 m apart"
            )
        );
        let authored = ArrayLayout {
            orientation: Some(0.0),
            lengthwise: Some(1),
            ..fitted.clone()
        };
        assert!(
            describe(&lights, "LampZone", Some(&authored), &[0.72; 6], &[])
                .contains("fittings as authored (0°), lengthwise along the other edge, 2.40 m")
        );
        // End to end along the other edge: the fittings' length apart, none between.
        let rows = ArrayLayout {
            spacing: [2.4, 1.52],
            between: Some([2.32, 0.0]),
            orientation: Some(90.0),
            lengthwise: Some(1),
            continuous: Some(1),
            ..fitted.clone()
        };
        assert!(
            describe(&lights, "LampZone", Some(&rows), &[0.72; 6], &[]).contains(
                "(2 rows of 3), continuous rows along the other edge, fittings turned 90°, 2.40 m × 1.52 m apart (2.32 m × 0.00 m between fittings)"
            ),
            "{}",
            describe(&lights, "LampZone", Some(&rows), &[0.72; 6], &[])
        );
        let one_row = ArrayLayout { rows: 1, ..fitted };
        assert!(
            describe(&lights[..3], "LampZone", Some(&one_row), &[1.0; 3], &[])
                .contains("(2.32 m × — between fittings)")
        );
        assert_eq!(
            describe(&lights[..2], "LampZone", None, &[0.5, 1.0], &[]),
            "Lamp1 … Lamp2 on LampZone: 2 lamps at irregular positions, not a regular array; at 50 %–100 % (50 %, 100 %)"
        );
    }
}
