//! The search's plots from its records: [`search_plot`] turns a variable's visits
//! (`invlight_ilp::visits`) into world terms — a placement as a plan in world metres
//! with the room, the target and the rectangle; a sun direction as elevation and
//! compass azimuth — and [`convergence`] follows the configuration the search stood on.

use crate::describe::{compass, subject};
use glam::DVec3;
use invlight_ilp::{
    Axes, Binding, Domain, Goal, Hemisphere, Isoc, Parallelogram, Record, Role, VariableKind,
    Verdict, Visit, visits,
};
use invlight_render::{
    ConvergencePlot, ConvergencePoint, Mark, PlanAxis, PlanFrame, PlotKind, PlotPoint, SearchPlot,
};
use invlight_scene::Scene;

/// The most triangles of the target drawn on a plan; past it, its bounding box.
const MAX_TARGET_TRIANGLES: usize = 20_000;

/// How a plane is seen on a plan: the two world axes kept and their signs.
struct Projection {
    keep: [usize; 2],
    sign: [f64; 2],
}

impl Projection {
    /// The plan of a plane of normal `n` in a scene whose up axis is `up`: a horizontal
    /// plane is seen from above, any other from the side its normal points to; the page
    /// shows the two world axes least aligned with the viewing direction, the vertical
    /// one flipped when needed so that the page is not seen mirrored.
    fn new(n: DVec3, up: DVec3) -> Projection {
        let view = if n.dot(up).abs() > 0.7 { up } else { n };
        let drop = (0..3)
            .max_by(|&a, &b| view[a].abs().total_cmp(&view[b].abs()))
            .unwrap_or(2);
        let keep: Vec<usize> = (0..3).filter(|&k| k != drop).collect();
        let (h, v) = (keep[0], keep[1]);
        let mut eh = DVec3::ZERO;
        eh[h] = 1.0;
        let mut ev = DVec3::ZERO;
        ev[v] = 1.0;
        let flip = eh.cross(ev)[drop] * view[drop] < 0.0;
        Projection {
            keep: [h, v],
            sign: [1.0, if flip { -1.0 } else { 1.0 }],
        }
    }

    fn at(&self, p: DVec3) -> [f64; 2] {
        [
            self.sign[0] * p[self.keep[0]],
            self.sign[1] * p[self.keep[1]],
        ]
    }

    fn axes(&self) -> [PlanAxis; 2] {
        let names = ["x", "y", "z"];
        [0, 1].map(|k| PlanAxis {
            name: names[self.keep[k]].to_string(),
            sign: self.sign[k],
        })
    }
}

fn mark(role: Role) -> Mark {
    match role {
        Role::Start => Mark::Start,
        Role::Improvement => Mark::Improvement,
        Role::Visited => Mark::Visited,
        Role::Invalid => Mark::Invalid,
    }
}

/// The plot of variable `i`'s visits over `records`, in world terms; `scene` is the
/// scene as bound (for the room, the target and the compass), `cap` the objective's.
pub fn search_plot(
    scene: &Scene,
    binding: &Binding,
    cap: Option<f64>,
    i: usize,
    records: &[Record],
    isoc: &Isoc,
) -> SearchPlot {
    let (axes, cell, visited) = visits(binding, i, records, isoc);
    let spec = &binding.specs[i];
    let domain = &binding.space.variables()[i].domain;
    let title = format!("What the search tried for {}", subject(spec));
    let (kind, points) = match (axes, domain) {
        (Axes::Placement { width, height }, Domain::Parallelogram(r)) => {
            placement_plot(scene, binding, i, r, [width, height], cell, &visited)
        }
        (Axes::Direction, Domain::Hemisphere(hemi)) => sky_plot(scene, hemi, cell, &visited),
        (Axes::Value { min, max }, _) => {
            let label = match spec.kind {
                VariableKind::LightPower { .. } => "dimming level (1 = as authored)",
                VariableKind::HoleSize { .. } => "scale of the authored size",
                VariableKind::ObjectRotation { .. } => "turn (°)",
                VariableKind::SunTime { .. } => "minutes after local midnight",
                VariableKind::LightArray(_) => "lamps set out (columns × rows)",
                _ => "HSV value V",
            };
            let kind = PlotKind::Value {
                min,
                max,
                label: label.into(),
            };
            (kind, plot_points(&visited, &|c| (c, Vec::new())))
        }
        // A domain and axes that disagree cannot come out of `visits`.
        (_, _) => {
            let label = String::new();
            let kind = PlotKind::Value {
                min: 0.0,
                max: 1.0,
                label,
            };
            (kind, Vec::new())
        }
    };
    let value_plot = matches!(kind, PlotKind::Value { .. });
    SearchPlot {
        title,
        kind,
        unit: goal_unit(binding),
        quantity: binding.goal.quantity().into(),
        cap,
        points: summarised(points, &binding.goal, value_plot),
    }
}

/// A place on the page for every visit: `at` turns a visit's coordinates into the
/// point drawn and the corners of its cell.
fn plot_points(
    visited: &[Visit],
    at: &dyn Fn([f64; 2]) -> ([f64; 2], Vec<[f64; 2]>),
) -> Vec<PlotPoint> {
    visited
        .iter()
        .map(|v| {
            let (at, cell) = at(v.coords);
            PlotPoint {
                at,
                cell,
                mean: v.mean,
                low: v.low,
                high: v.high,
                mark: mark(v.role),
                isoc: v.isoc,
            }
        })
        .collect()
}

/// The plan of placement variable `i` over its rectangle `r` (its sides' lengths
/// `[width, height]`, cells of `cell`): the visits where the moved thing stood, in world
/// metres on the rectangle's plane, with the room's box, the target and the range the
/// thing moved over.
fn placement_plot(
    scene: &Scene,
    binding: &Binding,
    i: usize,
    r: &Parallelogram,
    [width, height]: [f64; 2],
    cell: [f64; 2],
    visited: &[Visit],
) -> (PlotKind, Vec<PlotPoint>) {
    let initial = binding.values(&binding.initial);
    let offset = match initial[i] {
        invlight_ilp::VariableValue::Position { point, anchor } => anchor - point,
        _ => DVec3::ZERO,
    };
    let n = r.e1.cross(r.e2).normalize_or_zero();
    let up = scene.up.as_dvec3().normalize_or_zero();
    let proj = Projection::new(n, up);
    let world = |s: f64, t: f64| r.a + r.e1 * s + r.e2 * t;
    let (w, h) = (width.max(1e-12), height.max(1e-12));
    let (ds, dt) = (0.5 * cell[0] / w, 0.5 * cell[1] / h);
    let pts = plot_points(visited, &|c| {
        let (s, t) = (c[0] / w, c[1] / h);
        let corners = [(-ds, -dt), (ds, -dt), (ds, dt), (-ds, dt)]
            .map(|(a, b)| proj.at(world(s + a, t + b) + offset))
            .to_vec();
        (proj.at(world(s, t) + offset), corners)
    });
    let corners = |o: DVec3| {
        [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(s, t)| proj.at(world(s, t) + o))
    };
    let room = scene.bounds().map(|(lo, hi)| {
        let (a, b) = (proj.at(lo.as_dvec3()), proj.at(hi.as_dvec3()));
        [
            [a[0].min(b[0]), a[1].min(b[1])],
            [a[0].max(b[0]), a[1].max(b[1])],
        ]
    });
    let plan = binding.reading.plan_surface();
    let plan = PlanFrame {
        axes: proj.axes(),
        room,
        target: target_triangles(scene, binding, &proj),
        range: corners(offset),
        rectangle: (offset.length() > 1e-9).then(|| corners(DVec3::ZERO)),
        moved: subject(&binding.specs[i]),
        target_name: plan.map_or(String::new(), |(s, _)| scene.surfaces[s].name.clone()),
    };
    (PlotKind::Plan(Box::new(plan)), pts)
}

/// The objective surface's triangles as `proj` sees them; none when it has more than
/// [`MAX_TARGET_TRIANGLES`], so that a finely meshed surface does not swell the plot.
fn target_triangles(scene: &Scene, binding: &Binding, proj: &Projection) -> Vec<[[f64; 2]; 3]> {
    let mut target = Vec::new();
    let plan = binding.reading.plan_surface();
    let instances = plan.map_or(&[][..], |(s, _)| &scene.surfaces[s].instances[..]);
    let count: usize = instances
        .iter()
        .map(|&k| scene.world_triangles(k).count())
        .sum();
    if count <= MAX_TARGET_TRIANGLES {
        for &k in instances {
            target.extend(
                scene
                    .world_triangles(k)
                    .map(|t| t.corners.map(|c| proj.at(c.as_dvec3()))),
            );
        }
    }
    target
}

/// The sun chart of a direction variable over `hemi` (cells of `cell` degrees in
/// zenith and azimuth): the visits as compass azimuth and elevation, or as φ and
/// 90° − θ when the scene has no compass, and the axis north lies along.
fn sky_plot(
    scene: &Scene,
    hemi: &Hemisphere,
    cell: [f64; 2],
    visited: &[Visit],
) -> (PlotKind, Vec<PlotPoint>) {
    let compass = compass(scene);
    let (dt, dp) = (0.5 * cell[0], 0.5 * cell[1]);
    let angles = |theta: f64, phi: f64| {
        let d = hemi.direction(
            (phi / 360.0).rem_euclid(1.0),
            (theta / hemi.max_zenith.to_degrees()).clamp(0.0, 1.0),
        );
        compass
            .as_ref()
            .map(|c| crate::describe::sun_angles(c, d))
            .map_or([phi, 90.0 - theta], |(el, az)| [az, el])
    };
    let pts = plot_points(visited, &|c| {
        let centre = angles(c[0], c[1]);
        let corners = [(-dt, -dp), (dt, -dp), (dt, dp), (-dt, dp)]
            .map(|(a, b)| {
                let mut q = angles(c[0] + a, c[1] + b);
                // Keep a cell whole across north: azimuths near its centre's.
                q[0] = centre[0] + (q[0] - centre[0] + 180.0).rem_euclid(360.0) - 180.0;
                q
            })
            .to_vec();
        (centre, corners)
    });
    let north = compass.as_ref().map_or("φ = 0".to_string(), |c| {
        let n = c.north();
        let k = (0..3)
            .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
            .unwrap_or(0);
        let sign = if n[k] < 0.0 { "−" } else { "+" };
        format!("{sign}{}", ["x", "y", "z"][k])
    });
    (PlotKind::Sky { north }, pts)
}

/// Bins along a value plot's axis: the points of one bin are drawn as one.
const VALUE_BINS: f64 = 120.0;

/// The points drawn: the start and every improvement as they are (the line through
/// them is the walk), and of the other evaluations one per place — the best mean
/// found there, feasible before infeasible, in the ISOC when any was — so that a
/// plot, and the report holding it, stays the same size however long the search
/// ran (a place is a cell of the variable's own mesh, or a 1/120 of a value plot's
/// axis).
fn summarised(points: Vec<PlotPoint>, goal: &Goal, value_plot: bool) -> Vec<PlotPoint> {
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.at[0]), hi.max(p.at[0]))
        });
    let width = (hi - lo).max(1e-12);
    let place = |p: &PlotPoint| -> [u64; 2] {
        if value_plot {
            [((p.at[0] - lo) / width * VALUE_BINS).round() as u64, 0]
        } else {
            [p.at[0].to_bits(), p.at[1].to_bits()]
        }
    };
    // Lower is better.
    let key = |p: &PlotPoint| {
        let worse = match goal {
            Goal::Minimize { .. } | Goal::MinimizePower | Goal::MinimizeGlare { .. } => p.mean,
            Goal::Target { lux, .. } => (p.mean - lux).abs(),
            _ => -p.mean,
        };
        (matches!(p.mark, Mark::Invalid), worse)
    };
    let mut out: Vec<PlotPoint> = Vec::new();
    let mut at: std::collections::HashMap<[u64; 2], usize> = std::collections::HashMap::new();
    for p in points {
        if matches!(p.mark, Mark::Start | Mark::Improvement) {
            out.push(p);
            continue;
        }
        match at.get(&place(&p)) {
            Some(&k) => {
                let isoc = out[k].isoc || p.isoc;
                if key(&p) < key(&out[k]) {
                    out[k] = p;
                }
                out[k].isoc = isoc;
            }
            None => {
                at.insert(place(&p), out.len());
                out.push(p);
            }
        }
    }
    out
}

/// The best configuration so far against the photons traced: the search's start and
/// each improvement it moved to (a fast estimate's refinement with N is the move), then
/// the final ISOC's best member (re-measured with N when the strategy says so).
pub fn convergence(records: &[Record], isoc: &Isoc, binding: &Binding) -> ConvergencePlot {
    let z = isoc.z();
    let mut photons = 0u64;
    let mut points = Vec::new();
    let mut push = |photons: u64, e: &invlight_ilp::Estimate| {
        let i = e.interval(z);
        points.push(ConvergencePoint {
            photons,
            mean: e.mean,
            low: i.low,
            high: i.high,
        });
    };
    for r in records {
        photons += r.evaluation.goal.samples;
        if matches!(r.verdict, Verdict::Initial | Verdict::Better) {
            push(photons, &r.evaluation.goal);
        }
    }
    if let Some(best) = isoc.best() {
        push(photons, &best.evaluation.goal);
    }
    ConvergencePlot {
        title: "Convergence: the best configuration so far".into(),
        unit: goal_unit(binding),
        points,
    }
}

/// The unit a plot labels the goal's values with: lx, W or lm, U0 for a uniformity, UGR
/// for a glare rating.
pub fn goal_unit(binding: &Binding) -> String {
    match (binding.goal_unit(), &binding.goal) {
        ("", Goal::MinimizeGlare { .. }) => "UGR".into(),
        ("", _) => "U0".into(),
        (u, _) => u.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(at: [f64; 2], mean: f64, mark: Mark) -> PlotPoint {
        PlotPoint {
            at,
            cell: Vec::new(),
            mean,
            low: mean - 1.0,
            high: mean + 1.0,
            mark,
            isoc: false,
        }
    }

    /// However many evaluations land on a place, the plot draws one there: the best
    /// by the goal's sense, a feasible one before an infeasible one, in the ISOC if
    /// any was; the start and the improvements stay as they are.
    #[test]
    fn a_plot_draws_one_point_per_place_whatever_the_rows() {
        let mut points = vec![point([0.0, 0.0], 300.0, Mark::Start)];
        for k in 0..2_000 {
            let place = [f64::from(k % 10), 1.0];
            let mark = if k % 3 == 0 {
                Mark::Invalid
            } else {
                Mark::Visited
            };
            points.push(point(place, 100.0 + f64::from(k % 97), mark));
        }
        points.push(point([5.0, 1.0], 400.0, Mark::Improvement));
        points[7].isoc = true;
        let least = Goal::MinimizePower;
        let drawn = summarised(points.clone(), &least, false);
        assert_eq!(drawn.len(), 1 + 10 + 1);
        assert!(matches!(drawn[0].mark, Mark::Start));
        assert!(matches!(drawn[11].mark, Mark::Improvement));
        for p in &drawn[1..11] {
            let here: Vec<&PlotPoint> = points[1..2001].iter().filter(|q| q.at == p.at).collect();
            let best = here
                .iter()
                .filter(|q| matches!(q.mark, Mark::Visited))
                .map(|q| q.mean)
                .fold(f64::INFINITY, f64::min);
            assert!(
                matches!(p.mark, Mark::Visited) && p.mean == best,
                "{:?}",
                p.at
            );
            assert_eq!(p.isoc, here.iter().any(|q| q.isoc));
        }
        // Under a maximisation the best is the largest.
        let most = Goal::Maximize {
            surface: invlight_ilp::SurfaceRef {
                name: "Desk".into(),
                side: invlight_photon::Side::Both,
            },
            cap: None,
        };
        let drawn = summarised(points, &most, false);
        assert!(drawn[1..11].iter().all(|p| p.mean >= 195.0), "{drawn:?}");
        // A value plot bins its axis.
        let values: Vec<PlotPoint> = (0..5_000)
            .map(|k| {
                point(
                    [f64::from(k) / 5_000.0, 0.0],
                    f64::from(k % 13),
                    Mark::Visited,
                )
            })
            .collect();
        assert!(summarised(values, &least, true).len() <= VALUE_BINS as usize + 1);
    }
}
