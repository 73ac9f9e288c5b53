//! Photon tracing against closed-form illuminances. Every check is
//! |estimate − exact| < 4 σ with σ the standard error the estimate reports itself
//! (a 4 σ miss has probability 6·10⁻⁵ for an honest interval); seeds are fixed. Each case
//! is measured with both estimators: the photons' arrivals alone (the thesis) and
//! arrivals weighted against connections to the target (`Estimator::Connected`).

mod common;

use common::{Z, assert_near, point, rect, rect_solid_angle, roof_with_hole};
use invlight_photon::{Estimator, PILOT_PHOTONS, TraceSettings, measure, tune_roulette_for};
use invlight_scene::{Light, LightKind, Mat4, Material, Mesh, Scene, SurfaceId, Vec3};
use invlight_stats::{Confidence, Estimate};
use invlight_trace::Accel;
use std::f64::consts::PI;

/// The surface a test measures: the first its scene adds (the room, the box).
const FIRST: SurfaceId = SurfaceId::from_index(0);

/// The two estimators, in the order [`measure_both`] returns them.
const ESTIMATORS: [Estimator; 2] = [Estimator::ArrivalsOnly, Estimator::Connected];

fn settings(photons: u64) -> TraceSettings {
    TraceSettings {
        photons,
        seed: 7,
        ..TraceSettings::default()
    }
}

/// Measures the named surfaces of `scene` with both estimators: per surface, the
/// estimate from arrivals alone and the one with connections.
fn measure_both(scene: &Scene, names: &[&str], photons: u64) -> Vec<[Estimate; 2]> {
    let accel = Accel::new(scene);
    let ids: Vec<SurfaceId> = names.iter().map(|n| scene.surface(n).unwrap()).collect();
    let runs = ESTIMATORS.map(|e| measure(scene, &accel, &ids, &settings(photons), e, None));
    (0..ids.len())
        .map(|i| runs.each_ref().map(|r| r.estimate(i)))
        .collect()
}

/// Both estimates within 4 σ of `exact`.
fn assert_close(both: &[Estimate; 2], exact: f64, what: &str) {
    for (e, how) in both.iter().zip(ESTIMATORS) {
        assert_one(e, exact, &format!("{what} ({})", how.name()));
    }
}

/// `e` within 4 σ of `exact`, with σ below 2 % of it.
fn assert_one(e: &Estimate, exact: f64, what: &str) {
    assert_near(e, exact, 0.02, what);
}

/// A closed 4 × 3 × 2.5 m room (the surface "Room", area 79 m²) of reflectance `kd`
/// with a 100 cd lamp inside: every photon stays until it is absorbed.
fn closed_room(kd: Vec3) -> Scene {
    let mut scene = Scene::default();
    let m = scene.add_material(Material::diffuse("Walls", kd));
    let room = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(4.0, 3.0, 2.5), m));
    scene.add_instance("Room", room, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(1.0, 2.0, 2.0), 100.0));
    scene
}

/// The exact mean illuminance of [`closed_room`]'s walls of reflectance `rho`: every
/// photon arrives on them 1/(1 − ρ) times on average, E = Φ/(A(1 − ρ)).
fn closed_room_lux(rho: f32) -> f64 {
    let area = 2.0 * (4.0 * 3.0 + 4.0 * 2.5 + 3.0 * 2.5);
    4.0 * PI * 100.0 / (area * (1.0 - rho as f64))
}

#[test]
fn point_source_over_a_square() {
    // E_mean = I·Ω/A: the flux a point source of I cd sends into the solid angle Ω.
    let (scene, exact) = lamp_over_square();
    let e = measure_both(&scene, &["Floor"], 400_000);
    assert_close(&e[0], exact, "point over square");
}

#[test]
fn off_axis_point_source() {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.3)));
    let patch = scene.add_mesh(rect(0.5, 2.0, -0.25, 1.0, 0.0, grey));
    scene.add_instance("Patch", patch, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.0, 0.0, 0.8), 50.0));
    let e = measure_both(&scene, &["Patch"], 1_000_000);
    let area = 1.5 * 1.25;
    let exact = 50.0 * rect_solid_angle(0.5, 2.0, -0.25, 1.0, 0.8) / area;
    assert_close(&e[0], exact, "off-axis point");
}

/// View factor between two coaxial parallel rectangles a × b, distance c apart (Howell,
/// A Catalog of Radiation Heat Transfer Configuration Factors, C-11).
fn parallel_rectangles(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (x2, y2) = (x * x, y * y);
    2.0 / (PI * x * y)
        * (((1.0 + x2) * (1.0 + y2) / (1.0 + x2 + y2)).sqrt().ln()
            + x * (1.0 + y2).sqrt() * (x / (1.0 + y2).sqrt()).atan()
            + y * (1.0 + x2).sqrt() * (y / (1.0 + x2).sqrt()).atan()
            - x * x.atan()
            - y * y.atan())
}

#[test]
fn parallel_lambertian_area_source() {
    // A 1 × 0.6 m panel of luminance L facing down onto an equal panel 0.5 m below:
    // E = π·L·A·F₁₂ / A = π·L·F₁₂.
    let lum = 1000.0f32;
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let glow = scene.add_material(Material::emitter("Glow", Vec3::splat(lum)));
    let receiver = scene.add_mesh(rect(0.0, 1.0, 0.0, 0.6, 0.0, black));
    // Clockwise seen from above, so its front face looks down.
    let emitter = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.0, 0.0, 0.5),
            Vec3::new(0.0, 0.6, 0.5),
            Vec3::new(1.0, 0.6, 0.5),
            Vec3::new(1.0, 0.0, 0.5),
        ],
        glow,
    ));
    scene.add_instance("Receiver", receiver, Mat4::IDENTITY);
    scene.add_instance("Panel", emitter, Mat4::IDENTITY);
    let e = measure_both(&scene, &["Receiver"], 400_000);
    let exact = PI * lum as f64 * parallel_rectangles(1.0, 0.6, 0.5);
    assert_close(&e[0], exact, "parallel area source");
}

#[test]
fn closed_room_interreflection() {
    // Every photon arrives on the walls 1/(1 − ρ) times on average: E = Φ/(A(1 − ρ)).
    let rho = 0.8f32;
    let scene = closed_room(Vec3::splat(rho));
    let e = measure_both(&scene, &["Room"], 200_000);
    let exact = closed_room_lux(rho);
    assert_close(&e[0], exact, "closed room");
}

#[test]
fn a_lower_roulette_share_changes_no_mean() {
    // Reflections traced without roulette at reduced power, then a roulette that keeps
    // the power at the share: more rays per photon, the same E = Φ/(A(1 − ρ)).
    let rho = 0.8f32;
    let scene = closed_room(Vec3::splat(rho));
    let accel = Accel::new(&scene);
    let exact = closed_room_lux(rho);
    for estimator in ESTIMATORS {
        let mut rays = Vec::new();
        for roulette in [1.0, 0.5, 0.125] {
            let s = TraceSettings {
                roulette,
                ..settings(200_000)
            };
            let m = measure(&scene, &accel, &[FIRST], &s, estimator, None);
            assert_one(
                &m.estimate(0),
                exact,
                &format!("roulette {roulette} ({})", estimator.name()),
            );
            rays.push(m.rays);
        }
        // With ρ = 0.8 a share of ½ keeps three reflections from the roulette, ⅛ nine.
        assert!(rays[0] < rays[1] && rays[1] < rays[2], "rays {rays:?}");
    }
}

#[test]
fn the_pilot_lowers_the_roulette_where_reflections_carry_the_variance() {
    // In a closed room of ρ = 0.8 four fifths of the walls' light is reflected, and
    // tracing the first reflections without roulette pays; over a lone grey floor every
    // reflection escapes, so the longer paths cost rays and bring nothing: the classic
    // roulette stays, after the pilot has tried ½ and found it dearer.
    // Pilots of PILOT_PHOTONS per share, for a trace of 64 times that or more.
    let s = settings(64 * PILOT_PHOTONS);
    let target = (&[FIRST][..], Estimator::Connected);
    let room = closed_room(Vec3::splat(0.8));
    let room_accel = Accel::new(&room);
    let choice = tune_roulette_for(&room, &room_accel, target, &s, None);
    assert!(choice.share < 1.0, "{choice:?}");
    let best = choice
        .trials
        .iter()
        .map(|t| t.cost)
        .fold(f64::INFINITY, f64::min);
    // Measured: 0.11 of the classic roulette's cost at ⅟16, each cost known to about
    // 13 % from the pilot's 256 groups: a half is far outside their spread.
    assert!(best < 0.5 * choice.trials[0].cost, "{choice:?}");
    assert_eq!(choice.photons, PILOT_PHOTONS * choice.trials.len() as u64);
    let (floor, _) = lamp_over_square();
    let accel = Accel::new(&floor);
    let choice = tune_roulette_for(&floor, &accel, target, &s, None);
    assert_eq!(choice.share, 1.0, "{choice:?}");
    assert_eq!(choice.trials.len(), 2, "{choice:?}");
    // Too few photons for a pilot, or a share given: no pilot.
    let short = tune_roulette_for(&room, &room_accel, target, &settings(100_000), None);
    assert_eq!((short.share, short.photons), (1.0, 0), "{short:?}");
    let given = tune_roulette_for(&room, &room_accel, target, &s, Some(0.3));
    assert_eq!((given.share, given.photons), (0.3, 0), "{given:?}");
}

#[test]
fn saturated_colour_room_keeps_an_honest_interval() {
    // A closed room of red walls K_d = (0.9, 0.05, 0.05) under a white lamp: each channel
    // interreflects on its own, E_c = Φ/(A(1 − ρ_c)), and the reported value is their
    // luminance. Roulette on mean(K_d) has infinite variance here (the red channel's
    // second moment grows 2.7× per bounce); on the photon's luminance it is finite.
    let kd = Vec3::new(0.9, 0.05, 0.05);
    let scene = closed_room(kd);
    let e = measure_both(&scene, &["Room"], 400_000);
    let area = 2.0 * (4.0 * 3.0 + 4.0 * 2.5 + 3.0 * 2.5);
    let flux = 4.0 * PI * 100.0;
    let per_channel = |rho: f32| flux / (area * (1.0 - rho as f64));
    let exact =
        0.2126 * per_channel(kd.x) + 0.7152 * per_channel(kd.y) + 0.0722 * per_channel(kd.z);
    assert_close(&e[0], exact, "red room");
}

#[test]
fn a_surface_no_photon_reaches_is_not_exactly_dark() {
    // Zero arrivals give a sample variance of 0; the reported error is one arrival's worth.
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let floor = scene.add_mesh(rect(-1.0, 1.0, -1.0, 1.0, 0.0, grey));
    let hidden = scene.add_mesh(rect(-1.0, 1.0, -1.0, 1.0, -1.0, grey));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene.add_instance("Below", hidden, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.0, 0.0, 1.0), 10.0));
    let one_arrival = 4.0 * PI * 10.0 / (4.0 * 4096.0);
    for e in &measure_both(&scene, &["Below"], 4096)[0] {
        assert_eq!(e.mean, 0.0);
        // The flux is summed in f32 by the emitters: equal to f32 rounding.
        assert!((e.std_error - one_arrival).abs() < 1e-6 * one_arrival);
    }
}

#[test]
fn thesis_bounce_cap_under_counts_a_bright_room() {
    // With at most 4 bounces after the first hit the room gets Φ(1 − ρ⁵)/(A(1 − ρ)).
    let rho = 0.8f32;
    let scene = closed_room(Vec3::splat(rho));
    let accel = Accel::new(&scene);
    let area = 2.0 * (4.0 * 3.0 + 4.0 * 2.5 + 3.0 * 2.5);
    let both = ESTIMATORS.map(|estimator| {
        let s = TraceSettings {
            max_bounces: 4,
            ..settings(200_000)
        };
        measure(&scene, &accel, &[FIRST], &s, estimator, None).estimate(0)
    });
    let exact = 4.0 * PI * 100.0 * (1.0 - (rho as f64).powi(5)) / (area * (1.0 - rho as f64));
    assert_close(&both, exact, "capped room");
}

#[test]
fn sun_on_a_tilted_plane() {
    // A plane tilted 35° from the horizontal under a vertical sun of E lx gets E·cos 35°.
    let tilt = 35f32.to_radians();
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let plane = scene.add_mesh(rect(-1.0, 1.0, -0.5, 0.5, 0.0, grey));
    scene.add_instance("Roof", plane, Mat4::from_rotation_x(tilt));
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: -Vec3::Z,
            illuminance: Vec3::splat(10_000.0),
        },
    });
    let e = measure_both(&scene, &["Roof"], 400_000);
    assert_close(&e[0], 10_000.0 * (tilt as f64).cos(), "tilted plane");
}

#[test]
fn mirror_adds_the_image_source() {
    // A lamp 1 m above a large mirror (K_s = 0.9); a black target 2 m above the lamp
    // sees the lamp at 2 m and its image at 4 m: E = I(Ω₂ + K_s Ω₄)/A.
    let mut scene = Scene::default();
    let mirror = scene.add_material(Material::mirror("Mirror", Vec3::splat(0.9)));
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let m = scene.add_mesh(rect(-50.0, 50.0, -50.0, 50.0, 0.0, mirror));
    let t = scene.add_mesh(rect(-0.5, 0.5, -0.5, 0.5, 3.0, black));
    scene.add_instance("Mirror", m, Mat4::IDENTITY);
    scene.add_instance("Target", t, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.0, 0.0, 1.0), 100.0));
    let e = measure_both(&scene, &["Target"], 1_000_000);
    let direct = rect_solid_angle(-0.5, 0.5, -0.5, 0.5, 2.0);
    let image = rect_solid_angle(-0.5, 0.5, -0.5, 0.5, 4.0);
    assert_close(&e[0], 100.0 * (direct + 0.9 * image), "mirror image");
}

#[test]
fn glass_slab_transmits_by_fresnel() {
    // A sun at normal incidence through a clear slab of index 1.5 (R = 0.04 per face,
    // all inner reflections summed): T = (1 − R)/(1 + R).
    let mut scene = Scene::default();
    let glass = scene.add_material(Material::glass("Glass", 1.5));
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let slab = scene.add_mesh(Mesh::cuboid(
        Vec3::new(-2.0, -2.0, 1.0),
        Vec3::new(2.0, 2.0, 1.2),
        glass,
    ));
    let target = scene.add_mesh(rect(-0.5, 0.5, -0.5, 0.5, 0.0, black));
    scene.add_instance("Slab", slab, Mat4::IDENTITY);
    scene.add_instance("Target", target, Mat4::IDENTITY);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: -Vec3::Z,
            illuminance: Vec3::splat(1000.0),
        },
    });
    let e = measure_both(&scene, &["Target"], 2_000_000);
    let r = 0.04;
    assert_close(&e[0], 1000.0 * (1.0 - r) / (1.0 + r), "glass slab");
}

#[test]
fn spot_light_flux_reaches_the_floor() {
    // All of a spot's flux 2πI((1 − cos θi) + (cos θi − cos θo)/3) lands on a floor that
    // covers its cone.
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let floor = scene.add_mesh(rect(-10.0, 10.0, -10.0, 10.0, 0.0, black));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    let (inner, outer) = (0.3f32, 0.6f32);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Spot".into(),
        kind: LightKind::Spot {
            position: Vec3::new(1.0, 0.0, 2.0),
            direction: -Vec3::Z,
            intensity: Vec3::splat(500.0),
            inner,
            outer,
        },
    });
    let (ci, co) = (inner.cos() as f64, outer.cos() as f64);
    let flux = 2.0 * PI * 500.0 * ((1.0 - ci) + (ci - co) / 3.0);
    let [arrivals, connected] = measure_both(&scene, &["Floor"], 100_000)[0];
    // Every photon lands: arrivals alone have no variance, so compare to rounding.
    assert!((arrivals.mean - flux / 400.0).abs() < 1e-4 * flux / 400.0);
    // Connections see the spot's profile from every floor point they draw.
    assert_one(&connected, flux / 400.0, "spot (connected)");
}

#[test]
fn energy_is_conserved() {
    // In an open grey box (ρ = 0.5) lit by a lamp, absorbed + escaped = emitted:
    // (1 − ρ)·E·A + escaped/N = Φ. The two terms are correlated per photon, so the
    // tolerance adds their standard errors (Cauchy–Schwarz bound on the sum's σ).
    let rho = 0.5f64;
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(rho as f32)));
    let mut open_box = Mesh::cuboid(Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0), grey);
    open_box.triangles.truncate(2); // keep the floor…
    let walls = Mesh::cuboid(Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0), grey);
    open_box.triangles.extend_from_slice(&walls.triangles[4..]); // …and the four walls
    open_box.materials = vec![grey; open_box.triangles.len()];
    let b = scene.add_mesh(open_box);
    scene.add_instance("Box", b, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.7, 1.2, 1.0), 10.0));
    let accel = Accel::new(&scene);
    for estimator in ESTIMATORS {
        energy_balance(&scene, &accel, rho, estimator);
    }
}

/// Checks absorbed + escaped = emitted in the open box of `energy_is_conserved`.
fn energy_balance(scene: &Scene, accel: &Accel, rho: f64, estimator: Estimator) {
    let r = measure(scene, accel, &[FIRST], &settings(400_000), estimator, None);
    let area = r.areas[0];
    let e = r.estimate(0);
    let absorbed = (1.0 - rho) * e.mean * area;
    let n = r.photons as f64;
    let escaped = r.escaped / n;
    let flux = 4.0 * PI * 10.0;
    // Each photon's escape is 0 or Φ: a Bernoulli mean with σ = Φ·sqrt(p(1 − p)/N).
    let p = escaped / flux;
    let se = (1.0 - rho) * area * e.std_error + flux * (p * (1.0 - p) / n).sqrt();
    assert!(
        (absorbed + escaped - flux).abs() < Z * se,
        "{absorbed} + {escaped} vs {flux}"
    );
    assert!(p > 0.1 && p < 0.9);
}

#[test]
fn same_bits_on_one_and_two_threads() {
    // The room (twelve triangles: connections by area) and a patch floating in it (two:
    // by solid angle), at the classic roulette and at a share of ¼; and the pilot's
    // choice.
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.7)));
    let room = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(3.0, 2.0, 2.5), grey));
    scene.add_instance("Room", room, Mat4::IDENTITY);
    let patch = scene.add_mesh(rect(0.5, 1.0, 0.5, 1.2, 0.8, grey));
    scene.add_instance("Patch", patch, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(1.0, 1.0, 2.0), 100.0));
    let accel = Accel::new(&scene);
    let targets = [FIRST, scene.surface("Patch").unwrap()];
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    for estimator in ESTIMATORS {
        for roulette in [1.0, 0.25] {
            let s = TraceSettings {
                roulette,
                ..settings(3 * invlight_photon::CHUNK + 17)
            };
            let run = |threads| {
                on(threads).install(|| measure(&scene, &accel, &targets, &s, estimator, None))
            };
            assert_eq!(run(1), run(2));
            assert_eq!(run(2), run(3));
        }
        let s = settings(64 * invlight_photon::CHUNK);
        let tune = |threads| {
            on(threads)
                .install(|| tune_roulette_for(&scene, &accel, (&targets[..], estimator), &s, None))
        };
        assert_eq!(tune(1), tune(2));
    }
}

#[test]
fn intervals_cover_the_exact_value_at_their_confidence() {
    // An honest 95 % interval contains the exact value in 95 % of independent runs.
    // Interreflection in a closed room gives per-group contributions with a long tail,
    // the hard case for a normal interval; with the roulette from a share of ¼, photons
    // of unequal powers after their first reflections.
    let rho = 0.6f32;
    let scene = closed_room(Vec3::splat(rho));
    let exact = closed_room_lux(rho);
    for roulette in [1.0, 0.25] {
        for estimator in ESTIMATORS {
            assert_intervals_cover(&scene, exact, 4096, estimator, roulette);
        }
    }
}

/// Traces surface 0 of `scene` with 400 seeds of `photons` photons each, the Russian
/// roulette starting at `roulette` ([`TraceSettings::roulette`]), and checks that the 95 % intervals contain `exact` as often as they claim: the count
/// of covering runs is Binomial(400, 0.95) (mean 380, σ 4.36), accepted within 4 σ.
fn assert_intervals_cover(
    scene: &Scene,
    exact: f64,
    photons: u64,
    estimator: Estimator,
    roulette: f32,
) {
    let accel = Accel::new(scene);
    let z = Confidence::new(0.95).unwrap().z();
    let runs = 400;
    let covered = (0..runs)
        .filter(|&seed| {
            let s = TraceSettings {
                seed,
                roulette,
                ..settings(photons)
            };
            measure(scene, &accel, &[FIRST], &s, estimator, None)
                .estimate(0)
                .interval(z)
                .contains(exact)
        })
        .count() as f64;
    let (mean, sd) = (0.95 * runs as f64, (runs as f64 * 0.95 * 0.05).sqrt());
    assert!(
        (covered - mean).abs() < Z * sd,
        "{covered} of {runs} intervals covered ({})",
        estimator.name()
    );
}

/// A point lamp 1.5 m above a 2 m square: the floor's exact mean illuminance.
fn lamp_over_square() -> (Scene, f64) {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let floor = scene.add_mesh(rect(-1.0, 1.0, -1.0, 1.0, 0.0, grey));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.0, 0.0, 1.5), 100.0));
    let exact = 100.0 * rect_solid_angle(-1.0, 1.0, -1.0, 1.0, 1.5) / 4.0;
    (scene, exact)
}

#[test]
fn stratified_intervals_cover_direct_light() {
    // Direct light is where the stratified groups (invlight_photon::Sampler) take away
    // most variance, and where an interval computed as if photons were independent would
    // be far too wide, or, from too few groups, too narrow. 4096 photons: 64 groups.
    let (scene, exact) = lamp_over_square();
    for estimator in ESTIMATORS {
        assert_intervals_cover(&scene, exact, 4096, estimator, 1.0);
    }
}

#[test]
fn stratification_shrinks_the_error_of_direct_light() {
    // Arrivals alone. Independent photons would give the binomial standard error of eq. 3.4:
    // (Φ/A)·sqrt(p(1 − p)/N) with p the fraction of the flux that reaches the floor.
    // Stratified over groups of 64, only the strata the square's outline crosses in the
    // (cos θ, φ) plane keep their variance: about a quarter of the 8 × 8 here, so σ
    // halves (measured: 0.0726 against 0.149 lx). The test asks for σ below binomial/1.5:
    // σ itself is estimated from 6250 groups, to about 1 %, so independent photons (ratio
    // 1) cannot pass and working stratification (ratio 2) cannot fail. That the smaller
    // error is also honest is `stratified_intervals_cover_direct_light`'s part.
    let (scene, exact) = lamp_over_square();
    let [e, _] = measure_both(&scene, &["Floor"], 400_000)[0];
    let flux = 4.0 * PI * 100.0;
    let p = exact * 4.0 / flux;
    let binomial = flux / 4.0 * (p * (1.0 - p) / 400_000.0).sqrt();
    assert!(
        e.std_error < binomial / 1.5,
        "σ {} lx, binomial σ {binomial} lx",
        e.std_error
    );
    assert_one(&e, exact, "stratified point over square (arrivals)");
}

/// View factor from an l × w rectangle to an l × h one standing on their common edge of
/// length l at a right angle (Howell, C-14).
fn perpendicular_rectangles(l: f64, w: f64, h: f64) -> f64 {
    let (w, h) = (w / l, h / l);
    let (w2, h2) = (w * w, h * h);
    let s = (w2 + h2).sqrt();
    let log = ((1.0 + w2) * (1.0 + h2) / (1.0 + w2 + h2)).ln()
        + w2 * (w2 * (1.0 + w2 + h2) / ((1.0 + w2) * (w2 + h2))).ln()
        + h2 * (h2 * (1.0 + h2 + w2) / ((1.0 + h2) * (h2 + w2))).ln();
    (w * (1.0 / w).atan() + h * (1.0 / h).atan() - s * (1.0 / s).atan() + 0.25 * log) / (PI * w)
}

/// A glowing panel of luminance `lum`, 1 m wide and `height` tall, standing on the far
/// edge of a black 1 × 0.8 m floor ("Floor", two triangles) and facing it.
fn panel_on_the_floor(lum: f32, height: f32) -> Scene {
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let glow = scene.add_material(Material::emitter("Glow", Vec3::splat(lum)));
    let floor = scene.add_mesh(rect(0.0, 1.0, 0.0, 0.8, 0.0, black));
    // In the plane y = 0, counter-clockwise seen from +y: its front faces the floor.
    let panel = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, height),
            Vec3::new(1.0, 0.0, height),
            Vec3::new(1.0, 0.0, 0.0),
        ],
        glow,
    ));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene.add_instance("Panel", panel, Mat4::IDENTITY);
    scene
}

#[test]
fn lamp_touching_its_target() {
    // A 1 × 0.5 m panel standing on the edge of a 1 × 0.8 m floor, facing it: E = π·L·F
    // with F from the floor to the panel. Along the common edge the distance goes to zero,
    // where a connection alone would have an unbounded 1/r² weight; weighted against the
    // arrivals it stays bounded, and the interval honest.
    let lum = 500.0f32;
    let scene = panel_on_the_floor(lum, 0.5);
    let exact = PI * lum as f64 * perpendicular_rectangles(1.0, 0.8, 0.5);
    assert_close(
        &measure_both(&scene, &["Floor"], 400_000)[0],
        exact,
        "touching panel",
    );
    for estimator in ESTIMATORS {
        assert_intervals_cover(&scene, exact, 4096, estimator, 1.0);
    }
}

#[test]
fn a_strip_on_the_floor_lights_it_without_bias() {
    // A strip 1 cm, 1 mm, then 0.1 mm tall on the floor's edge: every departure lies
    // within a hair of the floor's plane, where the floor's triangles are thin slivers
    // of the sky seen from it and sampling them by solid angle loses precision. Drawn
    // by solid angle in single precision and without falling back to area where a
    // triangle is seen edge on, they read 0.4 % and 3.8 % low (60 and 460 σ at 4 M
    // photons).
    for height in [0.01f32, 0.001, 0.0001] {
        let lum = 500.0f32;
        let scene = panel_on_the_floor(lum, height);
        let exact = PI * lum as f64 * perpendicular_rectangles(1.0, 0.8, height as f64);
        let accel = Accel::new(&scene);
        let s = settings(2_000_000);
        let m = measure(&scene, &accel, &[FIRST], &s, Estimator::Connected, None);
        assert_one(&m.estimate(0), exact, &format!("strip {height} m tall"));
    }
}

#[test]
fn sun_through_a_hole_in_the_roof() {
    // A vertical sun of E lx through a 1 × 1 m hole in a 10 × 10 m roof onto a black
    // 4 × 4 m floor below it: the floor gets E·1/16 on average. Connection rays and photons
    // must both pass through the hole and nowhere else.
    let mut scene = roof_with_hole(2.0);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: -Vec3::Z,
            illuminance: Vec3::splat(10_000.0),
        },
    });
    // The roof's lit side gets E over everything but the hole (measured over its whole
    // area), plus what the black floor sends back: nothing.
    let e = measure_both(&scene, &["Floor", "Roof"], 1_000_000);
    assert_close(&e[0], 10_000.0 / 16.0, "floor under the hole");
    assert_close(&e[1], 10_000.0 * 99.0 / 100.0, "roof around the hole");
}

#[test]
fn connections_cut_the_error() {
    // Same photons, two estimators: connections must leave a smaller standard error on
    // direct light (the point lamp over a square: the connection sees the lamp from every
    // point it draws) and on a patch in a closed room (its reflected light), by at least
    // half the measured ratios (8.1 and 5.7; without connections they would be 1). Each σ
    // is estimated from 3125–6250 groups, to about 2 %. (On the whole room as target
    // connections gain little: there the variance is that of the paths' lengths, which
    // only absorption decides.)
    let (square, _) = lamp_over_square();
    let [arrivals, connected] = measure_both(&square, &["Floor"], 400_000)[0];
    let ratio = arrivals.std_error / connected.std_error;
    assert!(ratio > 4.0, "direct light: σ ratio {ratio}");
    let mut room = closed_room(Vec3::splat(0.6));
    let black = room.add_material(Material::diffuse("Black", Vec3::ZERO));
    let patch = room.add_mesh(rect(3.0, 3.5, 0.5, 1.0, 0.5, black));
    room.add_instance("Patch", patch, Mat4::IDENTITY);
    let [arrivals, connected] = measure_both(&room, &["Patch"], 200_000)[0];
    let ratio = arrivals.std_error / connected.std_error;
    assert!(ratio > 3.0, "patch in a closed room: σ ratio {ratio}");
}

#[test]
fn a_target_just_under_another_surface_stays_dark() {
    // A 1 × 1 m patch 2 µm under a lit floor, closer than the rays' offsets: photons stop
    // at the floor, and so must connections (their rays run from the departure toward
    // the target and count only when the target is what they hit first).
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let floor = scene.add_mesh(rect(-2.0, 2.0, -2.0, 2.0, 0.0, grey));
    let patch = scene.add_mesh(rect(-0.5, 0.5, -0.5, 0.5, -2.0e-6, black));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene.add_instance("Patch", patch, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.0, 0.0, 1.5), 100.0));
    for e in &measure_both(&scene, &["Patch"], 100_000)[0] {
        assert_eq!(e.mean, 0.0);
    }
}
