//! Lighting intentions solved by photon tracing, against closed forms: point lamps over
//! black patches (direct light alone), whose illuminance over any axis-aligned rectangle
//! is I·Ω/A with Ω the rectangle's solid angle from the lamp. Each test states what the
//! designer asked for, computes the answer from geometry, and checks the search's.

use glam::{DVec3, Mat4, Vec3};
use invlight_ilp::{
    Binding, Configuration, Member, Observer, PhotonEvaluator, Problem, Record, Search, Standing,
    VariableValue,
};
use invlight_scene::{Light, LightKind, Material, Mesh, Placement, Scene};
use std::path::Path;

struct Quiet;
impl Observer for Quiet {
    fn evaluated(&mut self, _: &Record, _: Standing<'_>, _: bool) -> std::io::Result<()> {
        Ok(())
    }
}

/// The solid angle of the rectangle [x1, x2] × [z1, z2] of the plane y = 0 seen from
/// (0, h, 0): Σ ± atan(x z / (h √(x² + z² + h²))) over its corners.
fn omega(h: f64, (x1, x2): (f64, f64), (z1, z2): (f64, f64)) -> f64 {
    let f = |x: f64, z: f64| (x * z / (h * (x * x + z * z + h * h).sqrt())).atan();
    f(x2, z2) - f(x1, z2) - f(x2, z1) + f(x1, z1)
}

/// Mean illuminance over the rectangle [x1, x2] × [z1, z2] of y = 0 from a lamp of `cd`
/// candela at `l` (above the plane), lx: exact.
fn on_rect(l: DVec3, cd: f64, (x1, x2): (f64, f64), (z1, z2): (f64, f64)) -> f64 {
    let area = (x2 - x1) * (z2 - z1);
    cd * omega(l.y, (x1 - l.x, x2 - l.x), (z1 - l.z, z2 - l.z)) / area
}

/// A black patch on y = 0 facing up (+Y).
fn patch(s: &mut Scene, name: &str, (x1, x2): (f32, f32), (z1, z2): (f32, f32)) {
    let black = s.add_material(Material::diffuse("Black", Vec3::ZERO));
    let p = Vec3::new;
    let m = s.add_mesh(Mesh::quad(
        [p(x1, 0., z1), p(x1, 0., z2), p(x2, 0., z2), p(x2, 0., z1)],
        black,
    ));
    s.add_instance(name, m, Mat4::IDENTITY);
}

fn lamp(s: &mut Scene, name: &str, at: Vec3, cd: f32) {
    s.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: name.into(),
        kind: LightKind::Point {
            position: at,
            intensity: Vec3::splat(cd),
        },
    });
}

/// A placement rectangle with corners a, b, b + d − a, d.
fn rectangle(s: &mut Scene, name: &str, a: Vec3, b: Vec3, d: Vec3) {
    s.placements.push(Placement {
        name: name.into(),
        vertices: vec![a, b, b + d - a, d],
    });
}

fn problem(conditions: &str, objectives: &str, intentions: &str) -> Problem {
    let text = format!(
        "<input><scene path=\"built-in-code.gltf\"/>\n<conditions {conditions}</conditions>\n<objectives {objectives}>{intentions}</objectives></input>"
    );
    Problem::parse(Path::new("/tests/problem.xml"), &text).unwrap()
}

struct Solved {
    binding: Binding,
    members: Vec<Member>,
    closest: Vec<(f64, Member)>,
    traces: u64,
    z: f64,
}

fn solve(problem: &Problem, mut scene: Scene) -> Solved {
    let binding = Binding::new(problem, &mut scene).unwrap();
    let mut search = Search::new(&binding.space, problem.settings(), &binding.initial);
    let mut eval = PhotonEvaluator::new(&binding, scene, problem.seed, 8, problem.photons);
    search.run(&mut eval, &mut Quiet).unwrap();
    let standing = search.standing();
    Solved {
        members: standing.isoc.members().to_vec(),
        closest: standing.closest.to_vec(),
        traces: eval.traces(),
        z: standing.isoc.z(),
        binding,
    }
}

fn position(v: &VariableValue) -> DVec3 {
    match v {
        VariableValue::Position { point, .. } => *point,
        other => panic!("{other:?} is not a position"),
    }
}

fn level(v: &VariableValue) -> f64 {
    match v {
        VariableValue::Power(l) => *l,
        other => panic!("{other:?} is not a level"),
    }
}

/// "60 lx on the desk": a lamp's height over a 0.2 m desk, which gives exactly the
/// target at one height (E = I·Ω/A, close to I/h²).
#[test]
fn a_lamp_height_meets_a_target() {
    let mut s = Scene::default();
    patch(&mut s, "Desk", (-0.1, 0.1), (-0.1, 0.1));
    lamp(&mut s, "Lamp", Vec3::new(0.0, 3.0, 0.0), 100.0);
    let p = Vec3::new;
    rectangle(
        &mut s,
        "Pole",
        p(-0.01, 0.5, 0.),
        p(0.01, 0.5, 0.),
        p(-0.01, 3.0, 0.),
    );
    let pb = problem(
        "meshSize=\"1x50\"><lightInSurface id=\"Lamp\" surface=\"Pole\" anchor=\"centre\"/>",
        "maxIterations=\"200\" photons=\"20000\" seed=\"3\"",
        "<targetRadiance surface=\"Desk\" side=\"front\" lux=\"60\"/>",
    );
    let solved = solve(&pb, s);
    let e = |h: f64| on_rect(DVec3::new(0., h, 0.), 100.0, (-0.1, 0.1), (-0.1, 0.1));
    // E falls with h: bisect for E(h) = 60.
    let (mut lo, mut hi) = (0.5, 3.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if e(mid) > 60.0 { lo = mid } else { hi = mid }
    }
    let h = 0.5 * (lo + hi);
    let b = &solved.binding;
    let want = b.space.cell(&Configuration {
        coords: vec![0.5, (h - 0.5) / 2.5],
    });
    let cells: Vec<_> = solved.members.iter().map(|m| m.cell.clone()).collect();
    assert!(
        cells.contains(&want),
        "h = {h:.4} m: cell {want:?} not in {cells:?}"
    );
    // Every member is as close to the target as the best, within the comparison's
    // reach.
    let off = |m: &Member| (e(position(&b.values(&m.config)[0]).y) - 60.0).abs();
    let best = solved.members.iter().map(off).fold(f64::INFINITY, f64::min);
    for m in &solved.members {
        let se = m.evaluation.goal.std_error;
        assert!(
            off(m) - best <= 2.0 * solved.z * 2f64.sqrt() * se,
            "{:?}",
            b.values(&m.config)
        );
        assert!((m.evaluation.goal.mean - 60.0).abs() <= off(m) + 4.0 * se);
    }
}

/// "At least 40 lx on the desk with the least power": the level is 40/E_full, solved
/// from one trace.
#[test]
fn the_least_dimming_that_meets_min_lux_traces_once() {
    let mut s = Scene::default();
    patch(&mut s, "Desk", (-0.1, 0.1), (-0.1, 0.1));
    lamp(&mut s, "Lamp", Vec3::new(0.0, 1.0, 0.0), 100.0);
    let pb = problem(
        "meshSize=\"100\"><lightPower id=\"Lamp\" min=\"0\" max=\"1\"/>",
        "maxIterations=\"400\" photons=\"20000\" seed=\"4\"",
        "<minimizePower/><constraint surface=\"Desk\" minLux=\"40\"/>",
    );
    let solved = solve(&pb, s);
    assert_eq!(solved.traces, 1, "dimming costs no photons");
    let full = on_rect(DVec3::new(0., 1., 0.), 100.0, (-0.1, 0.1), (-0.1, 0.1));
    let exact = 40.0 / full;
    let b = &solved.binding;
    assert_eq!(solved.members.len(), 1, "power is exact: one least level");
    let m = &solved.members[0];
    let l = level(&b.values(&m.config)[0]);
    let c = &m.evaluation.constraints[0];
    let rel = c.std_error / c.mean;
    // The least level whose one-sided bound clears 40 lx: above the exact level by the
    // bound's margin (z₁ σ) and the noise of the estimate (a few σ), within one cell.
    assert!(
        l >= exact * (1.0 - 3.0 * rel) && l <= exact * (1.0 + 6.0 * rel) + 0.01,
        "level {l}, exact {exact} (σ/E = {rel:.4})"
    );
    let power = m.evaluation.goal.mean;
    assert!((power - l * 400.0 * std::f64::consts::PI).abs() < 1e-6 * power);
    assert_eq!(m.evaluation.goal.std_error, 0.0);
}

/// A black 2 m × 1 m floor on y = 0, two 100 cd lamps at 1 m over its middle line at the
/// given x, and a rail along that line at 1 m.
fn floor_and_rail(lamps: [(&str, f32); 2]) -> Scene {
    let mut s = Scene::default();
    patch(&mut s, "Floor", (0.0, 2.0), (0.0, 1.0));
    for (name, x) in lamps {
        lamp(&mut s, name, Vec3::new(x, 1.0, 0.5), 100.0);
    }
    let p = Vec3::new;
    rectangle(
        &mut s,
        "Rail",
        p(0., 1., 0.49),
        p(2., 1., 0.49),
        p(0., 1., 0.51),
    );
    s
}

/// The grid cells' true illuminance on the 2 m × 1 m floor of `uniformity_scene` with
/// the second lamp at x, by the closed form on each 0.25 m cell.
fn floor_cells(x: f64) -> Vec<f64> {
    let mut cells = Vec::new();
    for c in 0..8 {
        for r in 0..4 {
            let xs = (c as f64 * 0.25, (c + 1) as f64 * 0.25);
            let zs = (r as f64 * 0.25, (r + 1) as f64 * 0.25);
            let a = on_rect(DVec3::new(0.3, 1.0, 0.5), 100.0, xs, zs);
            let b = on_rect(DVec3::new(x, 1.0, 0.5), 100.0, xs, zs);
            cells.push(a + b);
        }
    }
    cells
}

fn u0(cells: &[f64]) -> f64 {
    let avg = cells.iter().sum::<f64>() / cells.len() as f64;
    cells.iter().copied().fold(f64::INFINITY, f64::min) / avg
}

/// "As even as possible on the floor": a second lamp goes where U0 peaks, which is not
/// where the mean peaks.
#[test]
fn maximize_uniformity_places_the_second_lamp_where_u0_peaks() {
    let s = floor_and_rail([("Fixed", 0.3), ("Lamp", 1.0)]);
    let pb = problem(
        "meshSize=\"20x1\"><lightInSurface id=\"Lamp\" surface=\"Rail\" anchor=\"centre\"/>",
        "maxIterations=\"200\" photons=\"40000\" seed=\"6\"",
        "<maximizeUniformity surface=\"Floor\" side=\"front\" grid=\"0.25\"/>",
    );
    let solved = solve(&pb, s);
    let b = &solved.binding;
    let centre = |k: usize| 0.05 + 0.1 * k as f64;
    let u = |k: usize| u0(&floor_cells(centre(k)));
    let mean = |k: usize| floor_cells(centre(k)).iter().sum::<f64>();
    let best_u = (0..20).max_by(|&a, &b| u(a).total_cmp(&u(b))).unwrap();
    let best_mean = (0..20)
        .max_by(|&a, &b| mean(a).total_cmp(&mean(b)))
        .unwrap();
    assert!(
        best_u.abs_diff(best_mean) >= 3,
        "U0 peaks at cell {best_u}, the mean at {best_mean}"
    );
    let cell_of = |m: &Member| (position(&b.values(&m.config)[0]).x / 0.1) as usize;
    let cells: Vec<usize> = solved.members.iter().map(cell_of).collect();
    assert!(
        cells.contains(&best_u),
        "U0's best cell {best_u} not in the ISOC {cells:?}"
    );
    assert!(
        !cells.contains(&best_mean),
        "the mean's best cell {best_mean} is in the ISOC {cells:?}"
    );
    for m in &solved.members {
        let se = m.evaluation.goal.std_error;
        assert!(u(best_u) - u(cell_of(m)) <= 2.0 * solved.z * 2f64.sqrt() * se);
    }
}

/// A desk at x ∈ [0, 0.4] and a screen at x ∈ [0.5, 0.9] on y = 0, a lamp moving along
/// x ∈ [−0.6, 1.4] at 0.8 m, and a black ground reaching the rail's ends.
fn desk_and_screen() -> Scene {
    let mut s = Scene::default();
    patch(&mut s, "Desk", (0.0, 0.4), (0.0, 0.4));
    patch(&mut s, "Screen", (0.5, 0.9), (0.0, 0.4));
    let black = s.add_material(Material::diffuse("Ground", Vec3::ZERO));
    let p = Vec3::new;
    let m = s.add_mesh(Mesh::quad(
        [
            p(-0.7, -0.01, -1.),
            p(-0.7, -0.01, 1.),
            p(1.5, -0.01, 1.),
            p(1.5, -0.01, -1.),
        ],
        black,
    ));
    s.add_instance("Ground", m, Mat4::IDENTITY);
    lamp(&mut s, "Lamp", Vec3::new(0.2, 0.8, 0.2), 100.0);
    rectangle(
        &mut s,
        "Rail",
        p(-0.6, 0.8, 0.19),
        p(1.4, 0.8, 0.19),
        p(-0.6, 0.8, 0.21),
    );
    s
}

fn lamp_at(x: f64) -> DVec3 {
    DVec3::new(x, 0.8, 0.2)
}

/// "The most light on the desk, at most X lx on the screen": the lamp leaves the desk's
/// centre for where the screen's bound is met.
#[test]
fn a_max_lux_constraint_pulls_the_goal_away() {
    let desk = |x: f64| on_rect(lamp_at(x), 100.0, (0.0, 0.4), (0.0, 0.4));
    let screen = |x: f64| on_rect(lamp_at(x), 100.0, (0.5, 0.9), (0.0, 0.4));
    let limit = 0.6 * screen(0.2);
    let pb = problem(
        "meshSize=\"40x1\"><lightInSurface id=\"Lamp\" surface=\"Rail\" anchor=\"centre\"/>",
        "maxIterations=\"300\" photons=\"20000\" seed=\"8\"",
        &format!(
            "<maximizeRadiance surface=\"Desk\"/><constraint surface=\"Screen\" maxLux=\"{limit}\"/>"
        ),
    );
    let solved = solve(&pb, desk_and_screen());
    let b = &solved.binding;
    // Left of the desk's centre the desk gets more light as x grows and so does the
    // screen: the optimum is where the screen reaches its limit.
    let (mut lo, mut hi) = (-0.6, 0.2);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if screen(mid) < limit {
            lo = mid
        } else {
            hi = mid
        }
    }
    let x_c = lo;
    assert!(!solved.members.is_empty());
    let x = |m: &Member| position(&b.values(&m.config)[0]).x;
    for m in &solved.members {
        let c = &m.evaluation.constraints[0];
        // Admitted only when its upper bound is under the limit: truly under it but
        // for the estimate's own noise.
        assert!(
            screen(x(m)) <= limit + 3.0 * c.std_error,
            "x = {}: {} lx",
            x(m),
            screen(x(m))
        );
        assert!(x(m) < 0.2, "the unconstrained optimum (0.2) is infeasible");
    }
    let best = solved
        .members
        .iter()
        .map(|m| desk(x(m)))
        .fold(0.0, f64::max);
    let se = solved.members[0].evaluation.goal.std_error;
    assert!(
        desk(x_c) - best <= 0.05 * (desk(0.2) - desk(-0.6)) + 4.0 * se,
        "best {best} lx, the constrained optimum {} lx at x = {x_c:.3}",
        desk(x_c)
    );
}

/// An infeasible problem says which configuration came closest.
#[test]
fn an_infeasible_problem_reports_the_least_violating_configuration() {
    let screen = |x: f64| on_rect(lamp_at(x), 100.0, (0.5, 0.9), (0.0, 0.4));
    let best_possible = screen(0.7);
    let pb = problem(
        "meshSize=\"40x1\"><lightInSurface id=\"Lamp\" surface=\"Rail\" anchor=\"centre\"/>",
        "maxIterations=\"200\" photons=\"20000\" seed=\"9\"",
        &format!(
            "<maximizeRadiance surface=\"Desk\"/><constraint surface=\"Screen\" minLux=\"{}\"/>",
            3.0 * best_possible
        ),
    );
    let solved = solve(&pb, desk_and_screen());
    assert!(
        solved.members.is_empty(),
        "nothing meets 3× the most the screen can get"
    );
    let b = &solved.binding;
    let (violation, closest) = &solved.closest[0];
    let x = position(&b.values(&closest.config)[0]).x;
    assert!(
        (x - 0.7).abs() <= 0.1,
        "closest at x = {x}, the screen's best is 0.7"
    );
    assert!((violation - (1.0 - screen(x) / (3.0 * best_possible))).abs() < 0.05);
    for w in solved.closest.windows(2) {
        assert!(w[0].0 <= w[1].0, "least violation first");
    }
}

/// Two identical lamps on one rail: a configuration and its swap are one cell, so the
/// ISOC never holds both.
#[test]
fn swapping_identical_lamps_is_one_member() {
    let s = floor_and_rail([("A", 0.5), ("B", 1.5)]);
    let pb = problem(
        "meshSize=\"10x1\"><lightInSurface id=\"A\" surface=\"Rail\" anchor=\"centre\"/><lightInSurface id=\"B\" surface=\"Rail\" anchor=\"centre\"/>",
        "maxIterations=\"150\" photons=\"20000\" seed=\"2\"",
        "<maximizeUniformity surface=\"Floor\" grid=\"0.25\"/>",
    );
    let solved = solve(&pb, s);
    let b = &solved.binding;
    // 10 cells a lamp: 55 unordered pairs, not 100.
    assert_eq!(b.space.cell_count(), 55.0);
    let swapped = |m: &Member| {
        let c = &m.config.coords;
        Configuration {
            coords: vec![c[2], c[3], c[0], c[1]],
        }
    };
    for m in &solved.members {
        assert_eq!(b.space.cell(&swapped(m)), m.cell, "a swap is the same cell");
        let x = |i: usize| position(&b.values(&m.config)[i]).x;
        assert!(
            x(0) < x(1),
            "canonical order, and never two lamps in one cell"
        );
    }
}
