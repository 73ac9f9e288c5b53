//! The CIE skies of `invlight_scene::daylight` traced as emitters: photons
//! enter the scene from the dome (CIE S 011 / ISO 15469 luminance distributions), and the
//! readings match what the sky's luminance integrates to. Every check is
//! |estimate − exact| < 4 σ with σ the standard error the estimate reports itself; seeds
//! are fixed. Each case is measured with both estimators, arrivals alone and arrivals
//! weighted against connections, which for a sky photon run along its own direction.

mod common;

use common::{assert_near, rect};
use invlight_photon::{Estimator, TraceSettings, measure};
use invlight_scene::daylight::Sky;
use invlight_scene::{Mat4, Material, Mesh, Scene, SurfaceId, Vec3};
use invlight_trace::Accel;
use std::sync::Arc;

const ESTIMATORS: [Estimator; 2] = [Estimator::ArrivalsOnly, Estimator::Connected];

/// `surface` of `scene` (under the sky `case`) measured with both estimators, each within 4 σ of `exact` and
/// with σ below `informative` × exact.
fn assert_reads(
    scene: &Scene,
    surface: &str,
    case: &str,
    photons: u64,
    exact: f64,
    informative: f64,
) {
    let accel = Accel::new(scene);
    let ids: Vec<SurfaceId> = vec![scene.surface(surface).unwrap()];
    let settings = TraceSettings {
        photons,
        seed: 11,
        ..TraceSettings::default()
    };
    for estimator in ESTIMATORS {
        let e = measure(scene, &accel, &ids, &settings, estimator, None).estimate(0);
        let what = format!("{surface}, {case} ({})", estimator.name());
        eprintln!("{what}: {} ± {} lx, exact {exact} lx", e.mean, e.std_error);
        assert_near(&e, exact, informative, &what);
    }
}

/// A Z-up scene: a grey 2 × 2 m plane "Plane" at z = 0, facing up, alone.
fn open_plane() -> Scene {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let plane = scene.add_mesh(rect(-1.0, 1.0, -1.0, 1.0, 0.0, grey));
    scene.add_instance("Plane", plane, Mat4::IDENTITY);
    scene
}

/// An unobstructed horizontal plane reads the sky's horizontal illuminance, the
/// `horizontalLux` it is built from: the overcast sky and clear skies with a high and a
/// low sun (whose circumsolar peak the table's weights r = L/(p·∫L) must follow).
#[test]
fn an_open_plane_reads_the_horizontal_illuminance() {
    let skies = [
        ("overcast", Sky::cie_overcast(Vec3::Z, 10_000.0).unwrap()),
        (
            "clear, sun at 60°",
            Sky::cie_clear(Vec3::Z, Vec3::new(0.5, 0.0, 3f32.sqrt() / 2.0), 15_000.0).unwrap(),
        ),
        (
            "clear, sun at 10°",
            Sky::cie_clear(Vec3::Z, Vec3::new(0.0, 0.985, 0.174), 8_000.0).unwrap(),
        ),
    ];
    for (name, sky) in skies {
        let mut scene = open_plane();
        let e_h = sky.horizontal_illuminance();
        scene.sky = Some(Arc::new(sky));
        assert_reads(&scene, "Plane", name, 200_000, e_h, 0.02);
    }
}

/// The illuminance at (px, py, 0) from an opening [−w/2, w/2]² at height h under the
/// overcast sky of zenith luminance `lz`: ∫ L(Z) cos θ_p cos θ_o / r² dA with
/// cos Z = cos θ_p = cos θ_o = h/r, by the midpoint rule on n × n cells.
fn overcast_through_opening(px: f64, py: f64, w: f64, h: f64, lz: f64, n: usize) -> f64 {
    let cell = w / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        let x = -w / 2.0 + (i as f64 + 0.5) * cell - px;
        for j in 0..n {
            let y = -w / 2.0 + (j as f64 + 0.5) * cell - py;
            let r2 = x * x + y * y + h * h;
            let mu = h / r2.sqrt();
            sum += lz * (1.0 + 2.0 * mu) / 3.0 * mu * mu / r2;
        }
    }
    sum * cell * cell
}

/// A 0.2 × 0.2 m patch at the bottom of a black square shaft 1 m wide and 1 m deep under
/// the overcast sky reads the CIE luminance integrated over the opening it sees (the
/// walls send nothing back), averaged over the patch here by the midpoint rule.
#[test]
fn the_bottom_of_a_black_shaft_reads_the_sky_over_its_opening() {
    let (w, depth, patch) = (1.0f32, 1.0f32, 0.2f32);
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let half = w / 2.0;
    let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let walls = [
        [
            c(-half, -half, 0.0),
            c(half, -half, 0.0),
            c(half, -half, depth),
            c(-half, -half, depth),
        ],
        [
            c(half, -half, 0.0),
            c(half, half, 0.0),
            c(half, half, depth),
            c(half, -half, depth),
        ],
        [
            c(half, half, 0.0),
            c(-half, half, 0.0),
            c(-half, half, depth),
            c(half, half, depth),
        ],
        [
            c(-half, half, 0.0),
            c(-half, -half, 0.0),
            c(-half, -half, depth),
            c(-half, half, depth),
        ],
    ];
    for (k, corners) in walls.into_iter().enumerate() {
        let wall = scene.add_mesh(Mesh::quad(corners, black));
        scene.add_instance(&format!("Wall{k}"), wall, Mat4::IDENTITY);
    }
    let p = patch / 2.0;
    let target = scene.add_mesh(rect(-p, p, -p, p, 0.0, black));
    scene.add_instance("Patch", target, Mat4::IDENTITY);
    let sky = Sky::cie_overcast(Vec3::Z, 10_000.0).unwrap();
    let lz = sky.zenith_luminance();
    scene.sky = Some(Arc::new(sky));
    // The patch's mean illuminance: 20 × 20 points on it, 400 × 400 cells of the opening.
    let (m, n) = (20, 400);
    let exact = (0..m * m)
        .map(|k| {
            let at = |i: usize| -(p as f64) + (i as f64 + 0.5) * patch as f64 / m as f64;
            overcast_through_opening(at(k % m), at(k / m), w as f64, depth as f64, lz, n)
        })
        .sum::<f64>()
        / (m * m) as f64;
    // About a fifth of E_h: the opening's 1 m² seen from 1 m below.
    assert!(exact > 1_500.0 && exact < 3_000.0, "{exact}");
    assert_reads(&scene, "Patch", "overcast", 1_000_000, exact, 0.05);
}
