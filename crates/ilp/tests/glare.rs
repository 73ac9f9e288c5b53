//! Glare as the search reads it (CIE 117 UGR): the same rating `invlight glare` gives,
//! its dependence on the lamps' levels exact within one trace, a limit decided on it,
//! and `<minimizeGlare>` finding the known optimum — the lamp out of the eye's view.
//!
//! The room: 6 m × 4 m × 3 m (Z up), grey walls, floor and ceiling (ρ 0.5); two panels
//! (0.6 m × 0.3 m openings, 1000 cd below them) hung 2.9 m high at x = 2 and x = 4; the
//! eye at (1, 2, 1.2) looking along +X, so both panels are in front of it.

use glam::{Mat3, Mat4, Vec3};
use invlight_ilp::{
    Binding, Evaluate, Feasibility, Observer as SearchObserver, PhotonEvaluator, Problem, Record,
    Search, Standing,
};
use invlight_photon::TraceSettings;
use invlight_photon::glare::{Observer, unified_glare_rating};
use invlight_scene::{Light, LightKind, Material, Mesh, Scene, read_photometry};
use invlight_stats::Confidence;
use invlight_trace::Accel;
use std::path::Path;
use std::sync::Arc;

/// A constant 1000 cd toward the lower hemisphere from a 0.6 m × 0.3 m opening (IES
/// LM-63-2002, metres).
const PANEL: &str = "IESNA:LM-63-2002\n[TEST] glare test panel\nTILT=NONE\n\
1 -1 1 3 1 1 2 0.3 0.6 0.0\n1.0 1.0 20\n0 45 90\n0\n1000 1000 1000\n";

const EYE: Vec3 = Vec3::new(1.0, 2.0, 1.2);
const OBSERVER: &str = "observer=\"1,2,1.2\" view=\"1,0,0\" name=\"pupil\"";

fn room() -> Scene {
    room_with(&[("LampA", 2.0), ("LampB", 4.0)])
}

/// The room with panels named and hung at x as `lamps` say.
fn room_with(lamps: &[(&str, f32)]) -> Scene {
    let mut s = Scene::default();
    s.up = Vec3::Z;
    let grey = s.add_material(Material::diffuse("grey", Vec3::splat(0.5)));
    let p = Vec3::new;
    let (w, d, h) = (6.0, 4.0, 3.0);
    // Each face counter-clockwise seen from inside the room.
    let faces = [
        (
            "Floor",
            [p(0., 0., 0.), p(w, 0., 0.), p(w, d, 0.), p(0., d, 0.)],
        ),
        (
            "Ceiling",
            [p(0., 0., h), p(0., d, h), p(w, d, h), p(w, 0., h)],
        ),
        (
            "South",
            [p(0., 0., 0.), p(0., 0., h), p(w, 0., h), p(w, 0., 0.)],
        ),
        (
            "North",
            [p(0., d, 0.), p(w, d, 0.), p(w, d, h), p(0., d, h)],
        ),
        (
            "West",
            [p(0., 0., 0.), p(0., d, 0.), p(0., d, h), p(0., 0., h)],
        ),
        ("East", [p(w, 0., 0.), p(w, 0., h), p(w, d, h), p(w, d, 0.)]),
    ];
    for (name, q) in faces {
        let m = s.add_mesh(Mesh::quad(q, grey));
        s.add_instance(name, m, Mat4::IDENTITY);
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("panel.ies");
    std::fs::write(&path, PANEL).unwrap();
    let photometry = Arc::new(read_photometry(&path).unwrap());
    for &(name, x) in lamps {
        s.lights.push(Light {
            c0: Vec3::X,
            name: name.into(),
            kind: LightKind::Goniometric {
                position: p(x, 2.0, 2.9),
                frame: Mat3::IDENTITY,
                photometry: photometry.clone(),
                multiplier: Vec3::ONE,
                tilt: 1.0,
            },
        });
    }
    s
}

fn problem(conditions: &str, objectives: &str, iterations: u32) -> Problem {
    let text = format!(
        "<input><scene path=\"built-in-code.gltf\"/>
         <conditions meshSize=\"10\">{conditions}</conditions>
         <objectives photons=\"100000\" seed=\"5\" maxIterations=\"{iterations}\">
           {objectives}
         </objectives></input>"
    );
    Problem::parse(Path::new("/tests/problem.xml"), &text).unwrap()
}

const DIMMED: &str = "<lightPower id=\"LampA\" min=\"0.1\" max=\"1\"/>
                      <lightPower id=\"LampB\" min=\"0.1\" max=\"1\"/>";

#[test]
fn the_searchs_ugr_is_the_glare_commands() {
    let pb = problem(DIMMED, &format!("<minimizeGlare {OBSERVER}/>"), 10);
    let mut scene = room();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
    // Both lamps at full output: every coordinate of a level at its top.
    let mut full = binding.initial.clone();
    full.coords.iter_mut().for_each(|c| *c = 1.0);
    let search = eval.evaluate(&full, pb.photons).unwrap().goal;
    let scene = room();
    let accel = Accel::with_movable(&scene, &[]);
    let settings = TraceSettings {
        photons: 200_000,
        seed: 11,
        ..TraceSettings::default()
    };
    let observer = Observer {
        eye: EYE,
        view: Vec3::X,
    };
    let glare =
        unified_glare_rating(&scene, &accel, &observer, &settings, Confidence::default()).unwrap();
    let ugr = glare.ugr.unwrap();
    // Independent traces: the two ratings agree within their combined noise (the
    // command's σ from its background's, as the search's is).
    let sigma_glare =
        8.0 / std::f64::consts::LN_10 * glare.indirect_std_error / glare.indirect_illuminance;
    let sigma = search.std_error.hypot(sigma_glare);
    assert!(
        (search.mean - ugr).abs() < 4.0 * sigma,
        "search {search:?}, glare {ugr} ± {sigma_glare}"
    );
    assert!(ugr > 10.0, "both panels in view glare: {ugr}");
}

#[test]
fn dimming_the_lamps_moves_the_rating_exactly_within_one_trace() {
    let pb = problem(DIMMED, &format!("<minimizeGlare {OBSERVER}/>"), 10);
    let mut scene = room();
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
    let at = |eval: &mut PhotonEvaluator, levels: [f64; 2]| {
        let mut c = binding.initial.clone();
        for (v, y) in levels.iter().enumerate() {
            binding.space.slice_mut(&mut c, v)[0] = (y - 0.1) / 0.9;
        }
        eval.evaluate(&c, pb.photons).unwrap().goal.mean
    };
    // Both by k: L² ω/p² by k², Lb by k, so UGR by 8·log10 k, exactly (one trace, two
    // weightings of it).
    let (full, half) = (at(&mut eval, [1.0, 1.0]), at(&mut eval, [0.5, 0.5]));
    assert!(
        (half - full - 8.0 * 0.5f64.log10()).abs() < 1e-9,
        "full {full}, half {half}"
    );
    assert_eq!(eval.traces(), 1, "dimming re-reads the one trace");
}

#[test]
fn a_ugr_limit_is_decided_with_its_interval() {
    let level = |limit: f64| {
        let pb = problem(
            DIMMED,
            &format!(
                "<maximizeRadiance surface=\"Floor\"/>
                 <constraint maxUGR=\"{limit}\" {OBSERVER}/>"
            ),
            10,
        );
        let mut scene = room();
        let binding = Binding::new(&pb, &mut scene).unwrap();
        let mut eval = PhotonEvaluator::new(&binding, scene, pb.seed, 8, pb.photons);
        let mut full = binding.initial.clone();
        full.coords.iter_mut().for_each(|c| *c = 1.0);
        let e = eval.evaluate(&full, pb.photons).unwrap();
        let c = e.constraints[0];
        let verdict = pb.constraints[0].verdict(&c, pb.confidence.z_one_sided());
        (c, verdict)
    };
    let (c, _) = level(30.0);
    let z = 1.645;
    let (_, above) = level(c.mean + 2.0 * z * c.std_error + 0.5);
    let (_, below) = level(c.mean - 2.0 * z * c.std_error - 0.5);
    assert_eq!(above, Feasibility::Feasible, "{c:?}");
    assert_eq!(below, Feasibility::Infeasible, "{c:?}");
}

struct Quiet;
impl SearchObserver for Quiet {
    fn evaluated(&mut self, _: &Record, _: Standing<'_>, _: bool) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn minimize_glare_puts_the_lamp_out_of_the_eyes_view() {
    // One lamp, free on a rectangle just under the ceiling. In view it rates above 10;
    // behind the eye (x ≤ 1) nothing is in view and the rating is 0, exactly: the
    // known optimum, two of the ten columns of cells.
    let mut scene = room_with(&[("LampA", 3.0)]);
    let black = scene.add_material(Material::diffuse("zone", Vec3::ZERO));
    let p = Vec3::new;
    let zone = [
        p(0.1, 0.1, 2.9),
        p(0.1, 3.9, 2.9),
        p(5.9, 3.9, 2.9),
        p(5.9, 0.1, 2.9),
    ];
    let m = scene.add_mesh(Mesh::quad(zone, black));
    scene.add_instance("Zone", m, Mat4::IDENTITY);
    let zone_id = scene.surface("Zone").unwrap();
    scene.make_calculation_surface(zone_id);
    let pb = problem(
        "<lightInSurface id=\"LampA\" surface=\"Zone\" anchor=\"centre\"/>",
        &format!("<minimizeGlare {OBSERVER}/>"),
        60,
    );
    let binding = Binding::new(&pb, &mut scene).unwrap();
    let mut search = Search::new(&binding.space, pb.settings(), &binding.initial);
    let mut eval = PhotonEvaluator::new(&binding, scene.clone(), pb.seed, 8, pb.photons);
    search.run(&mut eval, &mut Quiet).unwrap();
    let best = &search.isoc().members()[0];
    assert_eq!(best.evaluation.goal.mean, 0.0, "{:?}", best.evaluation.goal);
    binding.apply_arrangement(&mut scene, &best.config);
    let lamp = scene.lights[0].kind.position().unwrap();
    assert!(lamp.x <= EYE.x, "the lamp behind the eye: {lamp}");
    // And a lamp in view does glare, so the optimum is a real one.
    let mut ahead = best.config.clone();
    ahead.coords.iter_mut().for_each(|c| *c = 0.5);
    binding.apply_arrangement(&mut scene, &ahead);
    let lamp = scene.lights[0].kind.position().unwrap();
    assert!(lamp.x > 2.0, "{lamp}");
    let seen = eval.evaluate(&ahead, pb.photons).unwrap().goal;
    assert!(seen.mean > 10.0, "{seen:?}");
}

#[test]
fn a_lamp_without_a_luminous_area_or_an_eye_outside_is_refused_before_the_search() {
    let mut scene = room();
    scene.lights.push(Light {
        c0: Vec3::X,
        name: "Bulb".into(),
        kind: LightKind::Point {
            position: Vec3::new(5.0, 3.0, 2.5),
            intensity: Vec3::splat(100.0),
        },
    });
    let pb = problem(
        DIMMED,
        &format!("<maximizeRadiance surface=\"Floor\"/><constraint maxUGR=\"19\" {OBSERVER}/>"),
        10,
    );
    let Err(e) = Binding::new(&pb, &mut scene) else {
        panic!("a point light in a glare problem is refused")
    };
    assert!(
        e.message
            .contains("the light 'Bulb' is a point light without a luminous area"),
        "{e}"
    );
    let outside = problem(
        DIMMED,
        "<maximizeRadiance surface=\"Floor\"/><constraint maxUGR=\"19\" observer=\"9,2,1.2\" view=\"1,0,0\"/>",
        10,
    );
    let Err(e) = Binding::new(&outside, &mut room()) else {
        panic!("an eye outside the room is refused")
    };
    assert!(e.message.contains("is outside the scene"), "{e}");
}

#[test]
fn an_observer_named_as_a_surface_is_refused_and_a_scene_bound_twice_keeps_its_eye() {
    let named_floor = problem(
        DIMMED,
        "<maximizeRadiance surface=\"Floor\"/><constraint maxUGR=\"19\" observer=\"1,2,1.2\" view=\"1,0,0\" name=\"Floor\"/>",
        10,
    );
    let Err(e) = Binding::new(&named_floor, &mut room()) else {
        panic!("an observer named as a surface is refused")
    };
    assert!(e.message.contains("has the name of a surface"), "{e}");
    let pb = problem(DIMMED, &format!("<minimizeGlare {OBSERVER}/>"), 10);
    let mut scene = room();
    Binding::new(&pb, &mut scene).unwrap();
    let surfaces = scene.surfaces.len();
    Binding::new(&pb, &mut scene).unwrap();
    assert_eq!(
        scene.surfaces.len(),
        surfaces,
        "the eye square is added once"
    );
}
