//! Calculation surfaces against closed forms: a point lamp of I cd over a workplane h
//! below it, in a black room, gives the plane I·Ω/A on its front (I/h² under the lamp)
//! and nothing on its back, and the floor under the plane reads what it reads without
//! the plane. Checks are |estimate − exact| < 4 σ with σ the reported standard error;
//! seeds are fixed. Both estimators are checked: arrivals alone and with connections.

mod common;

use common::{Z, assert_near, point, rect, rect_solid_angle};
use invlight_photon::{
    Components, Estimator, GridRequest, GridValues, Request, Side, SurfaceGrid, TraceSettings,
    measure, measure_with,
};
use invlight_scene::{Mat4, Material, Mesh, Scene, Vec3, Workplane};
use invlight_trace::Accel;
use std::path::Path;

/// The lamp's intensity, cd, and its height above the floor, m.
const I: f64 = 100.0;
const LAMP: f32 = 2.5;
/// The workplane's height above the floor and its border, m.
const HEIGHT: f32 = 0.85;
const BORDER: f32 = 0.5;
/// Half the floor's side, m: the workplane is [−1.55, 1.55]², 31 cells of 0.1 m.
const HALF: f32 = 2.05;

fn settings(photons: u64) -> TraceSettings {
    TraceSettings {
        photons,
        seed: 11,
        ..TraceSettings::default()
    }
}

/// A black room [−HALF, HALF]² × [0, 3] m with a separate black floor "Floor" and a
/// 100 cd lamp 2.5 m above its centre.
fn black_room() -> Scene {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let room = scene.add_mesh(Mesh::cuboid(
        Vec3::new(-HALF, -HALF, -0.01),
        Vec3::new(HALF, HALF, 3.0),
        black,
    ));
    scene.add_instance("Room", room, Mat4::IDENTITY);
    let floor = scene.add_mesh(rect(-HALF, HALF, -HALF, HALF, 0.0, black));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.0, 0.0, LAMP), I as f32));
    scene
}

/// [`black_room`] with the workplane "Task" over its floor.
fn room_with_workplane() -> Scene {
    let mut scene = black_room();
    let task = Workplane {
        id: "Task".into(),
        height: HEIGHT,
        border: BORDER,
        floor: None,
        origin: None,
    };
    scene.add_workplane(Path::new("room"), &task).unwrap();
    scene
}

/// I·Ω/A of the square [−s, s]² seen from the lamp `h` above it.
fn square_lux(s: f64, h: f64) -> f64 {
    I * rect_solid_angle(-s, s, -s, s, h) / (4.0 * s * s)
}

const ESTIMATORS: [Estimator; 2] = [Estimator::ArrivalsOnly, Estimator::Connected];

#[test]
fn a_workplane_reads_the_lamp_and_nothing_from_behind() {
    let scene = room_with_workplane();
    let task = scene.surface("Task").unwrap();
    let h = f64::from(LAMP - HEIGHT);
    let s = f64::from(HALF - BORDER);
    let grid = SurfaceGrid::new(&scene, task, 0.1).unwrap();
    assert_eq!(grid.cells(), 31 * 31);
    let centre = (0..grid.cells())
        .min_by(|&a, &b| {
            let d = |i| grid.centre(i).truncate().length();
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    assert!(grid.centre(centre).distance(Vec3::new(0.0, 0.0, HEIGHT)) < 1e-4);
    // The mean over the 0.1 m cell under the lamp is I/h² to 0.3 %: cos³θ falls by
    // 3/2·r²/h² at its corners, r = 0.07 m.
    let below = square_lux(0.05, h);
    assert!((below / (I / (h * h)) - 1.0).abs() < 3e-3, "{below}");
    let accel = Accel::new(&scene);
    for estimator in ESTIMATORS {
        let components = Components::one(&scene);
        let request = Request {
            surfaces: &[task],
            grids: vec![GridRequest {
                target: 0,
                side: Side::Front,
                grid: grid.clone(),
                values: GridValues::CellMeans,
            }],
            components: &components,
            estimator,
            keep_groups: false,
            observers: Vec::new(),
        };
        let m = measure_with(&scene, &accel, &request, &settings(1_000_000), None);
        let what = estimator.name();
        let front = m.estimate_of(0, Side::Front, &[1.0]);
        assert_near(
            &front,
            square_lux(s, h),
            0.01,
            &format!("Task front ({what})"),
        );
        let back = m.estimate_of(0, Side::Back, &[1.0]);
        assert_eq!(
            back.mean, 0.0,
            "nothing lights the plane from below ({what})"
        );
        let both = m.estimate_of(0, Side::Both, &[1.0]);
        assert_eq!(both.mean, front.mean, "{what}");
        let cell = m.grids[0].cell(centre, &[1.0]).unwrap();
        // A cell is 1/961 of the plane: its error is some percent either way.
        let informative = 0.1;
        assert_near(
            &cell,
            below,
            informative,
            &format!("cell under the lamp ({what})"),
        );
        // A small square off the axis: the closed-form mean of I·cos θ/r² over it.
        let off = (0..grid.cells())
            .find(|&i| grid.centre(i).truncate().distance([0.8, 0.3].into()) < 1e-3)
            .unwrap();
        let exact = I * rect_solid_angle(0.75, 0.85, 0.25, 0.35, h) / 0.01;
        let e = m.grids[0].cell(off, &[1.0]).unwrap();
        assert_near(
            &e,
            exact,
            informative,
            &format!("cell at (0.8, 0.3) ({what})"),
        );
    }
}

#[test]
fn the_floor_reads_as_if_the_workplane_were_not_there() {
    let with = room_with_workplane();
    let without = black_room();
    let exact = square_lux(f64::from(HALF), f64::from(LAMP));
    let floor = |s: &Scene| s.surface("Floor").unwrap();
    for estimator in ESTIMATORS {
        let what = estimator.name();
        // The floor alone: the same photons, the same connections, the same bits.
        let alone = |s: &Scene| {
            let m = measure(
                s,
                &Accel::new(s),
                &[floor(s)],
                &settings(200_000),
                estimator,
                None,
            );
            (m.estimate(0), m.rays, m.connection_rays)
        };
        let (a, b) = (alone(&with), alone(&without));
        assert_eq!(a, b, "floor with and without the workplane ({what})");
        assert_near(&a.0, exact, 0.02, &format!("floor ({what})"));
        // Measured beside the workplane, whose connections draw numbers of their own:
        // another sample of the same floor.
        let task = with.surface("Task").unwrap();
        let m = measure(
            &with,
            &Accel::new(&with),
            &[floor(&with), task],
            &settings(200_000),
            estimator,
            None,
        );
        let e = m.estimate(0);
        let sigma = (e.std_error.powi(2) + b.0.std_error.powi(2)).sqrt();
        assert!(
            (e.mean - b.0.mean).abs() < Z * sigma,
            "floor beside the workplane {} vs {} lx without it ({what})",
            e.mean,
            b.0.mean
        );
    }
    // The same rectangle as an opaque black plane shades the floor: the test can fail.
    let mut opaque = black_room();
    let black = opaque.add_material(Material::diffuse("Black plane", Vec3::ZERO));
    let s = HALF - BORDER;
    let plane = opaque.add_mesh(rect(-s, s, -s, s, HEIGHT, black));
    opaque.add_instance("Plane", plane, Mat4::IDENTITY);
    let id = floor(&opaque);
    let shaded = measure(
        &opaque,
        &Accel::new(&opaque),
        &[id],
        &settings(200_000),
        Estimator::Connected,
        None,
    )
    .estimate(0);
    assert!(
        shaded.mean < 0.5 * exact,
        "an opaque plane shades the floor: {} of {exact} lx",
        shaded.mean
    );
}

/// A calculation surface facing down reads the lamp on its back; one of a hole
/// material receives (it is no hole once it is a calculation surface).
#[test]
fn sides_and_materials_of_calculation_surfaces() {
    let mut scene = black_room();
    let hole = scene.add_material(Material::hole("Opening"));
    let s = HALF - BORDER;
    let h = f64::from(LAMP - HEIGHT);
    // Clockwise seen from above: its front faces down.
    let down = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(-s, -s, HEIGHT),
            Vec3::new(-s, s, HEIGHT),
            Vec3::new(s, s, HEIGHT),
            Vec3::new(s, -s, HEIGHT),
        ],
        hole,
    ));
    scene.add_instance("Down", down, Mat4::IDENTITY);
    let id = scene.surface("Down").unwrap();
    assert!(scene.reception_warning(id).unwrap().contains("reads 0 lx"));
    scene.make_calculation_surface(id);
    assert_eq!(scene.reception_warning(id), None);
    let accel = Accel::new(&scene);
    assert_eq!(accel.stats().holes, 0);
    let m = measure(
        &scene,
        &accel,
        &[id],
        &settings(200_000),
        Estimator::Connected,
        None,
    );
    let back = m.estimate_of(0, Side::Back, &[1.0]);
    assert_near(
        &back,
        square_lux(f64::from(s), h),
        0.01,
        "downward plane's back",
    );
    assert_eq!(m.estimate_of(0, Side::Front, &[1.0]).mean, 0.0);
}
