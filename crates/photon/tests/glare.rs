//! The Unified Glare Rating traced: its background against a closed form and its
//! invariants (CIE 117:1995).
//!
//! The scene: an eye at the origin looking along +X at a square diffuse wall 3 m away,
//! lit by parallel light from behind the eye. The wall's luminance is uniform,
//! L = ρ·E⊥/π, so the indirect illuminance at the eye is L·π·F with F the form factor
//! from a small plane facing the wall's centre to the square (four corner rectangles,
//! each 1/(2π)·[A/√(1+A²)·atan(B/√(1+A²)) + B/√(1+B²)·atan(A/√(1+B²))]); the parallel
//! light reaches the eye from behind and is not counted on its front.

use glam::{Mat3, Mat4, Vec3};
use invlight_photon::glare::{
    GlareError, Observer, add_eye, eye_grid, glare_sources, position_index, unified_glare_rating,
};
use invlight_photon::{Components, Estimator, Measurement, Request, TraceSettings, measure_with};
use invlight_scene::{Light, LightKind, Material, Mesh, Scene, read_photometry};
use invlight_stats::Confidence;
use invlight_trace::Accel;
use std::sync::Arc;

const WALL_AT: f32 = 3.0;
const HALF: f32 = 4.0;
const REFLECTANCE: f32 = 0.5;
const SUN_LUX: f32 = 10_000.0;

/// A constant 1000 cd toward the lower hemisphere from a 0.6 m × 0.3 m opening (IES
/// LM-63-2002, metres).
const PANEL: &str = "IESNA:LM-63-2002\n[TEST] glare test panel\nTILT=NONE\n\
1 -1 1 3 1 1 2 0.3 0.6 0.0\n1.0 1.0 20\n0 45 90\n0\n1000 1000 1000\n";

fn wall_scene() -> Scene {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let m = scene.add_material(Material::diffuse("wall", Vec3::splat(REFLECTANCE)));
    let (x, h) = (WALL_AT, HALF);
    // Counter-clockwise seen from the eye: the front faces −X.
    let corners = [
        Vec3::new(x, -h, -h),
        Vec3::new(x, -h, h),
        Vec3::new(x, h, h),
        Vec3::new(x, h, -h),
    ];
    let mesh = scene.add_mesh(Mesh::quad(corners, m));
    scene.add_instance("Wall", mesh, Mat4::IDENTITY);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: Vec3::X,
            illuminance: Vec3::splat(SUN_LUX),
        },
    });
    scene
}

fn with_panel(mut scene: Scene, at: Vec3, multiplier: f32) -> Scene {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("panel.ies");
    std::fs::write(&path, PANEL).unwrap();
    let photometry = read_photometry(&path).unwrap();
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Panel".into(),
        kind: LightKind::Goniometric {
            position: at,
            frame: Mat3::IDENTITY,
            photometry: Arc::new(photometry),
            multiplier: Vec3::splat(multiplier),
            tilt: 1.0,
        },
    });
    scene
}

/// The form factor from a small plane to a rectangle A·d × B·d whose corner lies on
/// its normal at distance d.
fn corner_factor(a: f64, b: f64) -> f64 {
    let (sa, sb) = ((1.0 + a * a).sqrt(), (1.0 + b * b).sqrt());
    (a / sa * (b / sa).atan() + b / sb * (a / sb).atan()) / (2.0 * std::f64::consts::PI)
}

fn eye() -> Observer {
    Observer {
        eye: Vec3::ZERO,
        view: Vec3::X,
    }
}

fn settings(photons: u64) -> TraceSettings {
    TraceSettings {
        photons,
        seed: 7,
        ..TraceSettings::default()
    }
}

#[test]
fn the_background_is_the_walls_reflected_light_within_its_interval() {
    let scene = wall_scene();
    let accel = Accel::with_movable(&scene, &[]);
    let u = unified_glare_rating(
        &scene,
        &accel,
        &eye(),
        &settings(400_000),
        Confidence::DEFAULT,
    )
    .unwrap();
    let a = f64::from(HALF / WALL_AT);
    let luminance = f64::from(REFLECTANCE * SUN_LUX) / std::f64::consts::PI;
    let want = luminance * std::f64::consts::PI * 4.0 * corner_factor(a, a);
    let (got, se) = (u.indirect_illuminance, u.indirect_std_error);
    assert!(
        se > 0.0 && se < 0.05 * want,
        "standard error {se} of {want}"
    );
    assert!(
        (got - want).abs() < 4.0 * se,
        "indirect {got} ± {se} lx, closed form {want} lx"
    );
    // The sun reaches the eye from behind: nothing direct on the side facing the view.
    assert!(
        u.direct_illuminance.abs() < 4.0 * se,
        "{}",
        u.direct_illuminance
    );
    assert!((u.background_luminance - got / std::f64::consts::PI).abs() < 1e-9);
    assert_eq!(u.ugr, None, "no luminaire, no rating");
}

#[test]
fn a_panel_in_view_has_its_luminance_solid_angle_and_position_index() {
    let at = Vec3::new(2.0, 0.0, 1.0);
    let scene = with_panel(wall_scene(), at, 1.0);
    let accel = Accel::with_movable(&scene, &[]);
    let sources = glare_sources(&scene, &accel, &eye()).unwrap();
    assert_eq!(sources.len(), 1);
    let s = &sources[0];
    let d = at.length() as f64;
    // Seen from below at elevation atan(1/2): the face 0.18 m² projected by sin(elev).
    let projected = 0.18 * (1.0 / d);
    assert!((s.luminance - 1000.0 / projected).abs() < 1e-3 * s.luminance);
    assert!((s.solid_angle - projected / (d * d)).abs() < 1e-6);
    let p = position_index(Vec3::X, Vec3::Z, at.normalize());
    assert!((s.position_index - p).abs() < 1e-12 && p > 1.0);
    assert!(
        (s.contribution - s.luminance.powi(2) * s.solid_angle / (p * p)).abs()
            < 1e-6 * s.contribution
    );
}

#[test]
fn dimming_every_light_by_k_shifts_ugr_by_eight_log_k() {
    let at = Vec3::new(2.0, 0.5, 1.0);
    let ugr = |k: f32| {
        let mut scene = with_panel(wall_scene(), at, k);
        if let LightKind::Directional { illuminance, .. } = &mut scene.lights[0].kind {
            *illuminance *= k;
        }
        let accel = Accel::with_movable(&scene, &[]);
        unified_glare_rating(
            &scene,
            &accel,
            &eye(),
            &settings(65_536),
            Confidence::DEFAULT,
        )
        .unwrap()
        .ugr
        .unwrap()
    };
    let base = ugr(1.0);
    for k in [0.5f32, 4.0] {
        let shift = ugr(k) - base;
        assert!(
            (shift - 8.0 * f64::from(k).log10()).abs() < 1e-3,
            "k {k}: shift {shift}"
        );
    }
}

#[test]
fn a_luminaire_behind_the_eye_or_hidden_adds_nothing() {
    let behind = with_panel(wall_scene(), Vec3::new(-1.0, 0.0, 1.0), 1.0);
    let accel = Accel::with_movable(&behind, &[]);
    assert!(glare_sources(&behind, &accel, &eye()).unwrap().is_empty());
    // Beyond the wall: in front of the eye, but hidden.
    let hidden = with_panel(wall_scene(), Vec3::new(4.0, 0.0, 1.0), 1.0);
    let accel = Accel::with_movable(&hidden, &[]);
    assert!(glare_sources(&hidden, &accel, &eye()).unwrap().is_empty());
}

#[test]
fn a_point_light_in_view_is_refused_not_guessed() {
    let mut scene = wall_scene();
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Bulb".into(),
        kind: LightKind::Point {
            position: Vec3::new(2.0, 0.0, 1.0),
            intensity: Vec3::splat(100.0),
        },
    });
    let accel = Accel::with_movable(&scene, &[]);
    let err = glare_sources(&scene, &accel, &eye()).unwrap_err();
    assert!(matches!(err, GlareError::NoLuminousArea { ref light, .. } if light == "Bulb"));
    assert!(err.to_string().contains("luminous dimensions"), "{err}");
}

#[test]
fn a_measurement_carries_each_observers_glare_sum_through_a_cluster_exchange() {
    let mut scene = with_panel(wall_scene(), Vec3::new(2.0, 0.0, 1.0), 1.0);
    let accel = Accel::with_movable(&scene, &[]);
    let sum: f64 = glare_sources(&scene, &accel, &eye())
        .unwrap()
        .iter()
        .map(|s| s.contribution)
        .sum();
    assert!(sum > 0.0, "the panel is in view");
    let eye_square = add_eye(&mut scene, &eye(), "eye").unwrap();
    let accel = Accel::with_movable(&scene, &[]);
    let components = Components::one(&scene);
    let targets = [eye_square];
    let request = Request {
        grids: vec![eye_grid(&scene, eye_square, 0)],
        observers: vec![eye()],
        ..Request::means(&targets, &components, Estimator::Connected)
    };
    let m = measure_with(&scene, &accel, &request, &settings(20_000), None);
    // Exact and per component: the panel's sum at level 1, a quarter of it at half.
    assert!((m.glare_sum(0, &[1.0]) - sum).abs() < 1e-9 * sum);
    assert!((m.glare_sum(0, &[0.5]) - 0.25 * sum).abs() < 1e-9 * sum);
    // What another rank reads back is the same measurement, glare sums included.
    let mut words = Vec::new();
    m.pack(&mut words);
    let back = Measurement::unpack(&request, &mut words.into_iter());
    assert_eq!(back, m);
}
