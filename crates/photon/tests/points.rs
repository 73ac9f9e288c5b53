//! A grid read at its points (EN 12464-1 §5.4: the illuminance at points centred in the
//! cells), against closed forms and against small receptors: over a black floor a point
//! lamp gives I·cos θ/r² at each point, exactly, with no photon noise; in a grey room
//! each point's value (the lamp's direct light computed there, the photons' cell mean
//! of the rest) matches what a 2 cm receptor at the point measures.

mod common;

use common::{Z, point, rect};
use invlight_photon::{
    Components, Estimator, GridRequest, GridValues, Request, Side, SurfaceGrid, TraceSettings,
    measure_with,
};
use invlight_scene::{Mat4, Material, Mesh, Scene, Vec3};
use invlight_trace::Accel;

const I: f64 = 100.0;

/// I·cos θ/r² on the horizontal plane at `p` from `cd` candela at `l`.
fn exact(l: Vec3, p: Vec3, cd: f64) -> f64 {
    let d = (l - p).as_dvec3();
    cd * d.z / d.length().powi(3)
}

fn settings(photons: u64, seed: u64) -> TraceSettings {
    TraceSettings {
        photons,
        seed,
        ..TraceSettings::default()
    }
}

/// One grid on target 0 of `surfaces`, read as `values`.
fn request<'a>(
    surfaces: &'a [invlight_scene::SurfaceId],
    grid: &SurfaceGrid,
    values: GridValues,
    components: &'a Components,
) -> Request<'a> {
    Request {
        surfaces,
        grids: vec![GridRequest {
            target: 0,
            side: Side::Front,
            grid: grid.clone(),
            values,
        }],
        components,
        estimator: Estimator::Connected,
        keep_groups: false,
        observers: Vec::new(),
    }
}

#[test]
fn a_point_lamp_over_a_black_floor_gives_i_cos_over_r2_at_every_point() {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let m = scene.add_mesh(rect(0.0, 1.0, 0.0, 1.0, 0.0, black));
    scene.add_instance("Floor", m, Mat4::IDENTITY);
    let lamp = Vec3::new(0.3, 0.35, 0.8);
    scene.lights.push(point("Lamp", lamp, I as f32));
    let accel = Accel::new(&scene);
    let floor = scene.surface("Floor").unwrap();
    let grid = SurfaceGrid::new(&scene, floor, 0.25).unwrap();
    let components = Components::one(&scene);
    let surfaces = [floor];
    let m = measure_with(
        &scene,
        &accel,
        &request(&surfaces, &grid, GridValues::Points, &components),
        &settings(16_384, 3),
        None,
    );
    let g = &m.grids[0];
    assert!(g.at_points());
    let truth: Vec<f64> = (0..16).map(|i| exact(lamp, grid.centre(i), I)).collect();
    for (i, &t) in truth.iter().enumerate() {
        let e = g.cell(i, &[1.0]).unwrap();
        assert!(
            (e.mean / t - 1.0).abs() < 1e-5,
            "point {i}: {} vs {t}",
            e.mean
        );
        // Nothing bounces off black: the indirect part is zero, and only the doubt of
        // one arrival that might have been, Φ/(A·N), is left.
        let one = 4.0 * std::f64::consts::PI * I / (0.0625 * m.photons as f64);
        assert!(
            e.std_error <= one * 1.000_001,
            "point {i}: σ {}",
            e.std_error
        );
    }
    let avg = truth.iter().sum::<f64>() / 16.0;
    let min = truth.iter().copied().fold(f64::INFINITY, f64::min);
    let max = truth.iter().copied().fold(0.0, f64::max);
    let u = g.uniformity(&[1.0]);
    assert!((u.average.mean / avg - 1.0).abs() < 1e-5, "{:?}", u.average);
    assert!((u.min.mean / min - 1.0).abs() < 1e-5);
    assert!((u.max.mean / max - 1.0).abs() < 1e-5);
    assert!((u.u0.mean / (min / avg) - 1.0).abs() < 1e-5);
    // Half the level, half the light: the direct part is per component.
    let half = g.cell(0, &[0.5]).unwrap().mean;
    assert!((half / truth[0] - 0.5).abs() < 1e-6);
}

/// A closed grey room [−1.5, 1.5]² × [0, 2.5] (reflectance 0.5) lit by a 100 cd lamp off
/// its centre, with the calculation rectangle "Task" [−1.2, 1.2]² at 0.8 m and a 2 cm
/// calculation square at each of `points` in its plane.
fn grey_room(lamp: Vec3, points: &[Vec3]) -> Scene {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let room = scene.add_mesh(Mesh::cuboid(
        Vec3::new(-1.5, -1.5, 0.0),
        Vec3::new(1.5, 1.5, 2.5),
        grey,
    ));
    scene.add_instance("Room", room, Mat4::IDENTITY);
    let task = scene.add_mesh(rect(-1.2, 1.2, -1.2, 1.2, 0.8, grey));
    scene.add_instance("Task", task, Mat4::IDENTITY);
    let id = scene.surface("Task").unwrap();
    scene.make_calculation_surface(id);
    for (n, p) in points.iter().enumerate() {
        let r = 0.01;
        let mesh = scene.add_mesh(rect(p.x - r, p.x + r, p.y - r, p.y + r, p.z, grey));
        let name = format!("Receptor{n}");
        scene.add_instance(&name, mesh, Mat4::IDENTITY);
        let id = scene.surface(&name).unwrap();
        scene.make_calculation_surface(id);
    }
    scene.lights.push(point("Lamp", lamp, I as f32));
    scene
}

#[test]
fn each_point_reads_what_a_small_receptor_there_measures() {
    let lamp = Vec3::new(0.35, -0.25, 2.2);
    // The grid's points: 4 × 4 cells of 0.6 m over Task, centred at ±0.3 and ±0.9.
    let shape = grey_room(lamp, &[]);
    let task = shape.surface("Task").unwrap();
    let grid = SurfaceGrid::new(&shape, task, 0.6).unwrap();
    assert_eq!(grid.cells(), 16);
    let chosen = [0usize, 5, 6, 10, 15];
    let points: Vec<Vec3> = chosen.iter().map(|&i| grid.centre(i)).collect();
    let scene = grey_room(lamp, &points);
    let accel = Accel::new(&scene);
    let mut surfaces = vec![scene.surface("Task").unwrap()];
    surfaces.extend((0..points.len()).map(|n| scene.surface(&format!("Receptor{n}")).unwrap()));
    let grid = SurfaceGrid::new(&scene, surfaces[0], 0.6).unwrap();
    let components = Components::one(&scene);
    let at = |values| {
        measure_with(
            &scene,
            &accel,
            &request(&surfaces, &grid, values, &components),
            &settings(400_000, 7),
            None,
        )
    };
    let m = at(GridValues::Points);
    let means = at(GridValues::CellMeans);
    for (n, &i) in chosen.iter().enumerate() {
        let p = m.grids[0].cell(i, &[1.0]).unwrap();
        let r = m.estimate_of(n + 1, Side::Front, &[1.0]);
        // The indirect light read as its cell mean (0.6 m cells) stands for its value at
        // the centre: allowed 1 % of the point's light beside the two intervals.
        let allowed = Z * (p.std_error.powi(2) + r.std_error.powi(2)).sqrt() + 0.01 * p.mean;
        assert!(
            (p.mean - r.mean).abs() < allowed,
            "point {i}: {} ± {} at the point, {} ± {} on the receptor",
            p.mean,
            p.std_error,
            r.mean,
            r.std_error
        );
        // The direct part carries no noise: the point's σ is the indirect light's alone,
        // below the cell mean's of all light.
        let c = means.grids[0].cell(i, &[1.0]).unwrap();
        assert!(
            p.std_error < c.std_error,
            "point {i}: σ {} vs {}",
            p.std_error,
            c.std_error
        );
    }
    // Under the lamp the point sees more than the cell's mean, at the far corner less:
    // the cell means flatten the peak a search would otherwise hide behind.
    let under = (0..16)
        .min_by(|&a, &b| {
            let d = |i| grid.centre(i).truncate().distance(lamp.truncate());
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    let (p, c) = (
        m.grids[0].cell(under, &[1.0]).unwrap(),
        means.grids[0].cell(under, &[1.0]).unwrap(),
    );
    assert!(p.mean - c.mean > Z * (p.std_error.powi(2) + c.std_error.powi(2)).sqrt());
}

/// The direct illuminance at two points of a black floor 1 m from the foot of a linear
/// luminaire (tests/data/photometry/linear.ldt, 1.5 m long, its length along C90) hung
/// 2 m up in a Y-up scene, one along +X and one along +Z, with the point light it is
/// given to carrying `c0` (its node's local +X) and the fitting turned `rotation`
/// degrees about its aim.
fn along_and_across(c0: Vec3, rotation: f32) -> (f64, f64) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry/linear.ldt");
    let table = invlight_scene::read_photometry(&path).unwrap();
    let mut scene = Scene::default();
    scene.up = Vec3::Y;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let floor = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(-2.0, 0.0, -2.0),
            Vec3::new(-2.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, -2.0),
        ],
        black,
    ));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    let lamp = Vec3::new(0.25, 2.0, 0.25);
    scene.lights.push(invlight_scene::Light {
        c0,
        ..point("Lamp", lamp, 1.0)
    });
    scene
        .set_photometry("Lamp", std::sync::Arc::new(table), 1.0)
        .unwrap();
    scene.lights[0].kind.turn_about_aim(rotation);
    let accel = Accel::new(&scene);
    let id = scene.surface("Floor").unwrap();
    let grid = SurfaceGrid::new(&scene, id, 0.5).unwrap();
    let components = Components::one(&scene);
    let surfaces = [id];
    let m = measure_with(
        &scene,
        &accel,
        &request(&surfaces, &grid, GridValues::Points, &components),
        &settings(4096, 1),
        None,
    );
    let at = |p: Vec3| {
        let i = (0..grid.cells())
            .find(|&i| grid.centre(i).distance(p) < 1e-4)
            .expect("a grid point there");
        m.grids[0].cell(i, &[1.0]).unwrap().mean
    };
    (
        at(Vec3::new(1.25, 0.0, 0.25)),
        at(Vec3::new(0.25, 0.0, 1.25)),
    )
}

#[test]
fn turning_a_linear_luminaire_a_quarter_turn_swaps_along_and_across() {
    let (x, z) = along_and_across(Vec3::X, 0.0);
    // Across the luminaire (C0, along X) it sends more at 27° than along its length.
    assert!(x > 1.1 * z, "across {x} lx, along {z} lx");
    // Its node turned a quarter turn about the vertical (local +X now along −Z), or the
    // fitting turned 90° on its mounting: the two points trade their light.
    for (c0, rotation) in [(Vec3::NEG_Z, 0.0), (Vec3::X, 90.0)] {
        let (tx, tz) = along_and_across(c0, rotation);
        assert!(
            (tx / z - 1.0).abs() < 1e-4,
            "{c0}, {rotation}°: {tx} vs {z}"
        );
        assert!(
            (tz / x - 1.0).abs() < 1e-4,
            "{c0}, {rotation}°: {tz} vs {x}"
        );
    }
}
