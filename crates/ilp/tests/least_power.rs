//! The least-power dimming solved as a linear program (`crate::dimming`), against closed
//! forms: two isotropic lamps over two small desks in a black room, each desk lit by
//! both lamps by the inverse-square and cosine laws. The least power that gives each
//! desk its minimum is the solution of a 2 × 2 linear system, which the evaluator must
//! find from one trace, with each desk's margin the confidence asks for.

use glam::{Mat4, Vec3};
use invlight_ilp::{Binding, Configuration, Evaluate, PhotonEvaluator, Problem, Space};
use invlight_scene::{Light, LightKind, Material, Mesh, Scene};
use std::path::Path;

const CANDELA: f32 = 1000.0;
const LAMP_Y: f32 = 2.5;
const DESK_Y: f32 = 0.5;
const DESK: f32 = 0.2;
const LAMPS_X: [f32; 2] = [2.5, 7.5];
const Z: f32 = 2.0;

/// A black room 10 m × 3 m × 4 m, two black desks of DESK × DESK facing up under the
/// two lamps, and the lamps (1000 cd each, isotropic).
fn scene() -> Scene {
    let mut s = Scene::default();
    let black = s.add_material(Material::diffuse("Black", Vec3::ZERO));
    let p = Vec3::new;
    let (w, h, d) = (10.0, 3.0, 4.0);
    let walls = [
        [p(0., 0., 0.), p(w, 0., 0.), p(w, 0., d), p(0., 0., d)],
        [p(0., h, 0.), p(0., h, d), p(w, h, d), p(w, h, 0.)],
        [p(0., 0., 0.), p(0., 0., d), p(0., h, d), p(0., h, 0.)],
        [p(w, 0., 0.), p(w, h, 0.), p(w, h, d), p(w, 0., d)],
        [p(0., 0., 0.), p(0., h, 0.), p(w, h, 0.), p(w, 0., 0.)],
        [p(0., 0., d), p(w, 0., d), p(w, h, d), p(0., h, d)],
    ];
    for (k, q) in walls.into_iter().enumerate() {
        let m = s.add_mesh(Mesh::quad(q, black));
        s.add_instance(&format!("Wall{k}"), m, Mat4::IDENTITY);
    }
    for (name, x) in ["DeskA", "DeskB"].iter().zip(LAMPS_X) {
        let r = DESK / 2.0;
        let q = [
            p(x - r, DESK_Y, Z - r),
            p(x - r, DESK_Y, Z + r),
            p(x + r, DESK_Y, Z + r),
            p(x + r, DESK_Y, Z - r),
        ];
        let m = s.add_mesh(Mesh::quad(q, black));
        s.add_instance(name, m, Mat4::IDENTITY);
    }
    for (name, x) in ["LampA", "LampB"].iter().zip(LAMPS_X) {
        s.lights.push(Light {
            c0: invlight_scene::Vec3::X,
            name: (*name).into(),
            kind: LightKind::Point {
                position: p(x, LAMP_Y, Z),
                intensity: Vec3::splat(CANDELA),
            },
        });
    }
    s
}

/// The mean illuminance on the desk centred at `desk_x` from a lamp of 1 cd at
/// `lamp_x` (E = I·cos θ / r² = I·h / r³), by a 200 × 200 midpoint rule.
fn per_candela(desk_x: f64, lamp_x: f64) -> f64 {
    let h = f64::from(LAMP_Y - DESK_Y);
    let n = 200;
    let side = f64::from(DESK);
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let dx = desk_x - lamp_x + side * ((i as f64 + 0.5) / n as f64 - 0.5);
            let dz = side * ((j as f64 + 0.5) / n as f64 - 0.5);
            let r2 = dx * dx + dz * dz + h * h;
            sum += h / (r2 * r2.sqrt());
        }
    }
    sum / (n * n) as f64
}

fn problem(constraints: &str) -> Problem {
    let text = format!(
        "<input><scene path=\"built-in-code.gltf\"/>
         <conditions meshSize=\"20\">
           <lightPower id=\"LampA\" min=\"0.1\" max=\"1\"/>
           <lightPower id=\"LampB\" min=\"0.1\" max=\"1\"/>
         </conditions>
         <objectives photons=\"400000\" seed=\"3\" maxIterations=\"10\">
           <minimizePower/>{constraints}
         </objectives></input>"
    );
    Problem::parse(Path::new("/tests/problem.xml"), &text).unwrap()
}

/// The solved levels of a configuration, as fractions of full output.
fn levels(space: &Space, config: &Configuration) -> [f64; 2] {
    [0, 1].map(|i| 0.1 + 0.9 * space.slice(config, i)[0])
}

#[test]
fn least_power_levels_solve_the_desks_linear_system() {
    let (a, b) = (200.0, 100.0);
    let pb = problem(&format!(
        "<constraint surface=\"DeskA\" side=\"front\" minLux=\"{a}\"/>
         <constraint surface=\"DeskB\" side=\"front\" minLux=\"{b}\"/>"
    ));
    let mut scene = scene();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    assert!(binding.level_solver().is_some(), "the levels are solved");
    let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
    let e = eval.evaluate(&binding.initial, pb.photons).unwrap();
    let config = e.solved.clone().expect("the evaluation returns its levels");
    let y = levels(&binding.space, &config);
    // The closed form at the solved levels: each desk's light from both lamps.
    let i = f64::from(CANDELA);
    let m = [
        [per_candela(2.5, 2.5), per_candela(2.5, 7.5)],
        [per_candela(7.5, 2.5), per_candela(7.5, 7.5)],
    ];
    let z = pb.confidence.z_one_sided();
    for (k, (bound, c)) in [a, b].iter().zip(&e.constraints).enumerate() {
        let exact = i * (m[k][0] * y[0] + m[k][1] * y[1]);
        // The estimate is the closed form within its noise…
        assert!(
            (c.mean - exact).abs() < 4.0 * c.std_error,
            "desk {k}: estimated {} ± {}, closed form {exact}",
            c.mean,
            c.std_error
        );
        // …and the least power leaves each desk just the margin the confidence asks
        // for: held (mean − z·σ ≥ bound), and not much more (a few per cent of σ,
        // what the margin's rounds leave).
        let slack = (c.mean - z * c.std_error - bound) / c.std_error;
        assert!(
            (0.0..0.2).contains(&slack),
            "desk {k}: mean {} ± {} against {bound}: slack {slack} σ",
            c.mean,
            c.std_error
        );
    }
    // The power is that of the levels, exact.
    let lumens = 4.0 * std::f64::consts::PI * i;
    assert!((e.goal.mean - lumens * (y[0] + y[1])).abs() < 1e-6 * lumens);
}

#[test]
fn least_power_under_a_cap_keeps_both_bounds() {
    // DeskA needs at least 150 lx while DeskB may take at most 60 lx: LampB must stay
    // low, and LampA alone (with LampB at its least) lights DeskA.
    let pb = problem(
        "<constraint surface=\"DeskA\" side=\"front\" minLux=\"150\"/>
         <constraint surface=\"DeskB\" side=\"front\" maxLux=\"60\"/>",
    );
    let mut scene = scene();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
    let e = eval.evaluate(&binding.initial, pb.photons).unwrap();
    let y = levels(&binding.space, e.solved.as_ref().unwrap());
    assert!((y[1] - 0.1).abs() < 1e-9, "LampB at its least: {y:?}");
    let z = pb.confidence.z_one_sided();
    let (da, db) = (&e.constraints[0], &e.constraints[1]);
    assert!(da.mean - z * da.std_error >= 150.0, "{da:?}");
    assert!(db.mean + z * db.std_error <= 60.0, "{db:?}");
    let slack = (da.mean - z * da.std_error - 150.0) / da.std_error;
    assert!(
        slack < 0.2,
        "DeskA is lit no more than it must be: {slack} σ"
    );
}

#[test]
fn impossible_bounds_leave_the_lamps_at_full_output() {
    // 2 000 lx is beyond both lamps at full output (about 265 lx).
    let pb = problem("<constraint surface=\"DeskA\" side=\"front\" minLux=\"2000\"/>");
    let mut scene = scene();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
    let e = eval.evaluate(&binding.initial, pb.photons).unwrap();
    let y = levels(&binding.space, e.solved.as_ref().unwrap());
    assert_eq!(y, [1.0, 1.0]);
    assert!(e.constraints[0].mean < 2000.0);
}

#[test]
fn a_group_takes_the_one_level_its_neediest_desk_asks_for() {
    // One level for both lamps: DeskA's 200 lx decides it, DeskB gets what it gets.
    let text = "<input><scene path=\"built-in-code.gltf\"/>
         <conditions meshSize=\"20\">
           <lightGroup id=\"Both\" lights=\"LampA LampB\"/>
           <lightPower id=\"Both\" min=\"0.1\" max=\"1\"/>
         </conditions>
         <objectives photons=\"400000\" seed=\"3\" maxIterations=\"10\">
           <minimizePower/>
           <constraint surface=\"DeskA\" side=\"front\" minLux=\"200\"/>
           <constraint surface=\"DeskB\" side=\"front\" minLux=\"100\"/>
         </objectives></input>";
    let pb = Problem::parse(Path::new("/tests/problem.xml"), text).unwrap();
    let mut scene = scene();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
    let e = eval.evaluate(&binding.initial, pb.photons).unwrap();
    let config = e.solved.clone().unwrap();
    let y = 0.1 + 0.9 * binding.space.slice(&config, 0)[0];
    let i = f64::from(CANDELA);
    let per_level = i * (per_candela(2.5, 2.5) + per_candela(2.5, 7.5));
    let z = pb.confidence.z_one_sided();
    let a = &e.constraints[0];
    let needed = (200.0 + z * a.std_error) / per_level;
    assert!(
        (y - needed).abs() < 4.0 * a.std_error / per_level,
        "level {y}, closed form {needed}"
    );
    // Both lamps draw at that level: the power is twice one lamp's.
    let lumens = 4.0 * std::f64::consts::PI * i;
    assert!((e.goal.mean - 2.0 * lumens * y).abs() < 1e-6 * lumens);
    assert!(e.constraints[1].mean > 150.0, "{:?}", e.constraints[1]);
}

#[test]
fn the_levels_found_decide_a_uniformity_they_were_chosen_to_meet() {
    // examples/open-office: six downlights in a grey room, least watts for Em ≥ 500 lx
    // and U0 ≥ 0.6, each of the search's regular 3 × 2 starts evaluated at N as the
    // search's final evaluation does. U0 is a ratio of noisy cell means whose σ
    // changes with the levels, so a margin from the levels of the round before can
    // fall short at the levels found (0.6139 ± 0.0088 read once: undecided); whatever
    // the trace, the levels returned must leave every constraint decided
    // (mean − z·σ ≥ bound) and the binding one not much more lit than that.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/open-office/problem.xml");
    let mut pb = Problem::read(&path).unwrap();
    let mut scene = pb
        .load_scene(&invlight_scene::LoadOptions::default(), None, None, &[])
        .unwrap();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let arrays: Vec<Configuration> = binding
        .space
        .regular_arrays(&binding.space.snap(&binding.initial))
        .into_iter()
        .filter(|c| {
            // Three columns: three distinct first coordinates (snapped, so exact).
            let mut xs: Vec<f64> = (0..6).map(|k| binding.space.slice(c, k)[0]).collect();
            xs.sort_by(f64::total_cmp);
            xs.dedup();
            xs.len() == 3
        })
        .collect();
    assert!(arrays.len() >= 4, "3 × 2 arrays: {}", arrays.len());
    let z = pb.confidence.z_one_sided();
    let mut off = Vec::new();
    let mut evaluated = 0;
    for seed in 1..=4 {
        let mut eval =
            PhotonEvaluator::new(&binding, scene.clone(), seed, pb.bounces(), pb.photons);
        for (a, config) in arrays.iter().enumerate() {
            let e = eval.evaluate(config, pb.photons).unwrap();
            // An array no levels light enough: at full output, undecided or not.
            if e.constraints
                .iter()
                .zip([500.0, 0.6])
                .any(|(c, b)| c.mean < b)
            {
                continue;
            }
            evaluated += 1;
            let slack: Vec<f64> = e
                .constraints
                .iter()
                .zip([500.0, 0.6])
                .map(|(c, bound)| (c.mean - z * c.std_error - bound) / c.std_error)
                .collect();
            // Every constraint decided, and the one that holds the power down left
            // just its margin (2 % of z·σ over it, what MARGIN_FACTOR asks): no
            // more light than the confidence needs.
            let least = slack.iter().copied().fold(f64::INFINITY, f64::min);
            if !(0.0..0.2).contains(&least) {
                off.push((seed, a, slack));
            }
        }
    }
    assert!(evaluated >= 8, "levels that meet the bounds: {evaluated}");
    assert!(
        off.is_empty(),
        "(seed, array, slack of Em and U0 in σ): {off:?}"
    );
}
