//! The connected estimator (`TraceSettings::connect`: arrivals weighted against
//! connections to the target by the balance heuristic) against closed forms, lobe by lobe
//! and material by material, and the honesty of its errors.
//!
//! - Each lobe's density (`Lobe::pdf`) must be the one `Emitters::sample` draws from, or
//!   the two weights no longer add up to one: checked by histograms.
//! - A black box over a floor of one material: whatever leaves the floor, once, ends in
//!   the box, so the box's flux is Φ − IΩ + ρ·IΩ with ρ the floor's luminance albedo, a
//!   closed form for textured colours, parts summing to more than one, mirrors, glass and
//!   emitters, and the floor itself (mirror, glass, emitter as a target) gets IΩ.
//! - A spot across its cap and ring and the sun on a block, checked over 400 seeds:
//!   coverage of the 95 % intervals, the pooled mean, and the spread of the means against
//!   the reported errors; a lamp through a hole, a sheet lit from both sides and targets
//!   sharing an instance against closed forms.
//!
//! Tolerances are 4 σ of the errors the estimates report (or, for pooled checks, of their
//! observed spread); seeds are fixed.

mod common;

use common::{Z, assert_near, point, rect, rect_solid_angle, roof_with_hole};
use invlight_photon::{Emitters, Estimator, GroupKeys, Lobe, Sampler, TraceSettings, measure};
use invlight_scene::{
    Light, LightKind, Mat4, Material, Mesh, Scene, SurfaceId, Texture, Vec3, luminance,
};
use invlight_stats::{Confidence, Estimate};
use invlight_trace::Accel;
use std::f64::consts::PI;

fn settings(photons: u64, seed: u64) -> TraceSettings {
    TraceSettings {
        photons,
        seed,
        ..TraceSettings::default()
    }
}

/// The connected estimates of the named surfaces of `scene`.
fn connected(scene: &Scene, names: &[&str], photons: u64) -> Vec<Estimate> {
    let accel = Accel::new(scene);
    let ids: Vec<SurfaceId> = names.iter().map(|n| scene.surface(n).unwrap()).collect();
    let m = measure(
        scene,
        &accel,
        &ids,
        &settings(photons, 5),
        Estimator::Connected,
        None,
    );
    (0..ids.len()).map(|i| m.estimate(i)).collect()
}

/// `e` within 4 σ of `exact`, with σ below 1 % of it.
fn assert_close(e: &Estimate, exact: f64, what: &str) {
    assert_near(e, exact, 0.01, what);
}

/// Traces surface `name` of `scene` with 400 seeds of 4096 photons (64 groups) and checks
/// the connected estimator's errors three ways:
/// - the 95 % intervals contain `exact` in Binomial(400, 0.95) runs (380 ± 4.36), within 4 σ;
/// - the pooled mean of the 400 runs is within 4 of its standard errors (the runs' spread
///   / 20) of `exact`: a bias check 20 times finer than one run;
/// - the observed spread of the 400 means over the root mean square of their reported
///   errors is 1 within 4 × 1/√(2·399) (the relative error of a sample standard deviation
///   of 400 near-normal values): errors neither inflated nor understated.
fn assert_honest(scene: &Scene, name: &str, exact: f64) {
    let accel = Accel::new(scene);
    let id = scene.surface(name).unwrap();
    let runs = 400;
    let e: Vec<Estimate> = (0..runs)
        .map(|seed| {
            let s = settings(4096, seed);
            measure(scene, &accel, &[id], &s, Estimator::Connected, None).estimate(0)
        })
        .collect();
    let z = Confidence::new(0.95).unwrap().z();
    let n = runs as f64;
    let covered = e.iter().filter(|e| e.interval(z).contains(exact)).count() as f64;
    assert!(
        (covered - 0.95 * n).abs() < Z * (n * 0.95 * 0.05).sqrt(),
        "{name}: {covered} of {runs} intervals covered {exact}"
    );
    let mean = e.iter().map(|e| e.mean).sum::<f64>() / n;
    let spread = (e.iter().map(|e| (e.mean - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    assert!(
        (mean - exact).abs() < Z * spread / n.sqrt(),
        "{name}: pooled mean {mean} ± {} lx, exact {exact} lx",
        spread / n.sqrt()
    );
    let reported = (e.iter().map(|e| e.std_error.powi(2)).sum::<f64>() / n).sqrt();
    let ratio = spread / reported;
    assert!(
        (ratio - 1.0).abs() < Z / (2.0 * (n - 1.0)).sqrt(),
        "{name}: the means spread {spread} lx, the errors report {reported} lx"
    );
}

/// Checks that the directions `Emitters::sample` draws from the only light of `scene`
/// follow the sample's own `Lobe::pdf`: 40 bins of cos θ about `axis` in [`lo`, 1], each
/// holding N·∫pdf 2π dcos θ of N = 262 144 samples within 4 binomial σ (stratification only
/// narrows the spread of a bin's count).
fn assert_directions_follow_pdf(scene: &Scene, axis: Vec3, lo: f64) {
    let emitters = Emitters::new(scene);
    let (groups, bins) = (4096u64, 40usize);
    let n = groups * 64;
    let mut counts = vec![0u64; bins];
    let mut lobe = None;
    for g in 0..groups {
        let keys = GroupKeys::new(3, g);
        for i in g * 64..(g + 1) * 64 {
            let s = emitters.sample(&mut Sampler::new(&keys, 3, i));
            let c = s.dir.dot(axis) as f64;
            assert!(c >= lo, "a direction outside the lobe: cos θ = {c}");
            counts[(((c - lo) / (1.0 - lo) * bins as f64) as usize).min(bins - 1)] += 1;
            lobe = Some(s.lobe);
        }
    }
    let lobe = lobe.unwrap();
    // The lobe's density at cos θ = c, along any azimuth.
    let (t, _) = invlight_photon::basis(axis);
    let pdf = |c: f64| {
        let s = (1.0 - c * c).max(0.0).sqrt();
        lobe.pdf(axis * c as f32 + t * s as f32) as f64
    };
    let width = (1.0 - lo) / bins as f64;
    for (k, &count) in counts.iter().enumerate() {
        let steps = 200;
        let p: f64 = (0..steps)
            .map(|j| {
                let c = lo + (k as f64 + (j as f64 + 0.5) / steps as f64) * width;
                pdf(c) * 2.0 * PI * width / steps as f64
            })
            .sum();
        let expected = n as f64 * p;
        let sigma = (n as f64 * p * (1.0 - p)).sqrt().max(1.0);
        assert!(
            (count as f64 - expected).abs() < Z * sigma,
            "{lobe:?}: bin {k} (cos θ from {}) holds {count}, the pdf says {expected:.1}",
            lo + k as f64 * width
        );
    }
}

#[test]
fn spot_point_and_panel_draw_what_their_pdf_says() {
    // A spot's profile has two parts (a uniform inner cap and a t² ring) drawn with two
    // formulas; the connection weights its arrivals with one density. They must agree.
    let mut scene = Scene::default();
    let axis = Vec3::new(0.3, -0.2, -1.0).normalize();
    let (inner, outer) = (0.35f32, 0.6f32);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Spot".into(),
        kind: LightKind::Spot {
            position: Vec3::ZERO,
            direction: axis,
            intensity: Vec3::splat(100.0),
            inner,
            outer,
        },
    });
    assert_directions_follow_pdf(&scene, axis, outer.cos() as f64 - 0.02);
    scene.lights[0] = point("Lamp", Vec3::ZERO, 100.0);
    assert_directions_follow_pdf(&scene, axis, -1.0);
    // A panel facing -z: Lambertian about its normal.
    let mut scene = Scene::default();
    let glow = scene.add_material(Material::emitter("Glow", Vec3::splat(100.0)));
    let panel = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ],
        glow,
    ));
    scene.add_instance("Panel", panel, Mat4::IDENTITY);
    assert_directions_follow_pdf(&scene, -Vec3::Z, 0.0);
}

#[test]
fn sun_photons_start_uniformly_on_the_disk_of_its_lobe() {
    // The sun's arrival density is 1/area of `Lobe::Parallel`: the photons must start
    // uniformly on a disk of that area around the scene, across the direction. Half of
    // them inside radius R/√2 (4 binomial σ), none outside R, all on one plane.
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let block = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(2.0, 1.0, 0.5), grey));
    scene.add_instance("Block", block, Mat4::IDENTITY);
    let d = Vec3::new(0.4, -0.3, -1.0).normalize();
    scene.lights.push(sun(d, 1000.0));
    let (lo, hi) = scene.bounds().unwrap();
    let centre = (lo + hi) * 0.5;
    let emitters = Emitters::new(&scene);
    let n = 64 * 1024;
    let mut inside = 0u64;
    for g in 0..n / 64 {
        let keys = GroupKeys::new(9, g);
        for i in g * 64..(g + 1) * 64 {
            let s = emitters.sample(&mut Sampler::new(&keys, 9, i));
            let Lobe::Parallel { direction, area } = s.lobe else {
                panic!("{:?}", s.lobe)
            };
            assert!((direction - d).length() < 1e-6 && direction == s.dir);
            let r = (area / std::f32::consts::PI).sqrt();
            let off = s.origin - centre;
            let across = off - d * off.dot(d);
            assert!(across.length() <= r * (1.0 + 1e-5));
            // Behind the bounding sphere: nothing lies between the disk and the scene.
            assert!(off.dot(d) < -r);
            inside += (across.length_squared() <= 0.5 * r * r) as u64;
        }
    }
    let sigma = (n as f64 * 0.25).sqrt();
    assert!(
        (inside as f64 - 0.5 * n as f64).abs() < Z * sigma,
        "{inside} of {n}"
    );
}

fn sun(direction: Vec3, lux: f32) -> Light {
    Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction,
            illuminance: Vec3::splat(lux),
        },
    }
}

/// The lamp of the enclosure tests: 100 cd at (0.3, −0.2, 0.7) over the 2 × 2 m floor.
const LAMP: [f64; 3] = [0.3, -0.2, 0.7];
const CANDELA: f64 = 100.0;

/// A black box ("Box", [−1,1]² × [0,1.5] m, no bottom face unless `bottom`, then it goes
/// down to z = −1) over a 2 × 2 m floor of `floor` ("Floor", z = 0, `texture` across it)
/// and the lamp [`LAMP`]. Light leaves the floor upward only (or, through glass, down
/// into the box's bottom), so everything the floor sends out reaches the box at once.
fn enclosure(floor: Material, texture: Option<Texture>, bottom: bool) -> Scene {
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let mut floor = floor;
    if let Some(t) = texture {
        floor.texture = Some(scene.add_texture(t));
    }
    let f = scene.add_material(floor);
    let z0 = if bottom { -1.0 } else { 0.0 };
    let mut walls = Mesh::cuboid(Vec3::new(-1.0, -1.0, z0), Vec3::new(1.0, 1.0, 1.5), black);
    if !bottom {
        // The first two triangles are the -z face.
        walls.triangles.drain(0..2);
        walls.materials.drain(0..2);
    }
    let w = scene.add_mesh(walls);
    scene.add_instance("Box", w, Mat4::IDENTITY);
    let fl = scene.add_mesh(rect(-1.0, 1.0, -1.0, 1.0, 0.0, f));
    scene.add_instance("Floor", fl, Mat4::IDENTITY);
    let [x, y, z] = LAMP.map(|c| c as f32);
    scene
        .lights
        .push(point("Lamp", Vec3::new(x, y, z), CANDELA as f32));
    scene
}

/// Solid angle of the floor's part [x0,x1]×[y0,y1] seen from the lamp.
fn seen_from_lamp(x0: f64, x1: f64, y0: f64, y1: f64) -> f64 {
    let [lx, ly, h] = LAMP;
    rect_solid_angle(x0 - lx, x1 - lx, y0 - ly, y1 - ly, h)
}

/// Checks the box and the floor of `scene` (an [`enclosure`]): the floor gets the lamp's
/// direct light IΩ; the box the rest of the lamp's flux, `floor_out` lm from the floor
/// (reflected or emitted) and, when `bottom`, what crosses the floor.
fn assert_enclosure(scene: &Scene, floor_out: f64, what: &str) {
    let direct = CANDELA * seen_from_lamp(-1.0, 1.0, -1.0, 1.0);
    let lamp = 4.0 * PI * CANDELA;
    let e = connected(scene, &["Box", "Floor"], 262_144);
    let box_area = scene.surface_area(scene.surface("Box").unwrap()) as f64;
    assert_close(
        &e[0],
        (lamp - direct + floor_out) / box_area,
        &format!("{what}: box"),
    );
    assert_close(&e[1], direct / 4.0, &format!("{what}: floor"));
}

#[test]
fn textured_colour_floor_reflects_its_luminance() {
    // A 2 × 2 texture of saturated colours times a coloured K_d: the roulette's diffuse
    // share is the luminance of K_d × texel under the white photon, which is what each
    // texel sends up: Σ Y(K_d·texel)·I·Ω_texel, Ω_texel the texel's solid angle from the
    // lamp (off centre, so the four differ).
    let kd = Vec3::new(0.9, 0.8, 1.0);
    let texels = [
        Vec3::new(0.9, 0.05, 0.05),
        Vec3::new(0.05, 0.8, 0.1),
        Vec3::new(0.1, 0.1, 0.9),
        Vec3::new(0.6, 0.6, 0.6),
    ];
    let texture = Texture {
        width: 2,
        height: 2,
        pixels: texels.to_vec(),
    };
    // Texel (column c, row r) covers u ∈ [c/2, (c+1)/2], v ∈ [r/2, (r+1)/2]: x ∈ [c−1, c],
    // y ∈ [r−1, r].
    let reflected: f64 = (0..4)
        .map(|k| {
            let (c, r) = ((k % 2) as f64, (k / 2) as f64);
            luminance(kd * texels[k]) as f64 * CANDELA * seen_from_lamp(c - 1.0, c, r - 1.0, r)
        })
        .sum();
    let scene = enclosure(Material::diffuse("Checker", kd), Some(texture), false);
    assert_enclosure(&scene, reflected, "textured floor");
}

#[test]
fn parts_summing_to_more_than_one_keep_their_expectation() {
    // A coloured K_d and K_s of luminances 0.70 and 0.55: the roulette normalises its
    // probabilities by 1.25, and a connection before it must count the diffuse part's own
    // luminance, not its probability.
    let m = Material {
        specular: Vec3::new(0.6, 0.5, 0.9),
        ..Material::diffuse("Over", Vec3::new(0.5, 0.8, 0.3))
    };
    let rho = (luminance(m.diffuse) + luminance(m.specular)) as f64;
    assert!(rho > 1.0);
    let direct = CANDELA * seen_from_lamp(-1.0, 1.0, -1.0, 1.0);
    let scene = enclosure(m, None, false);
    assert_enclosure(&scene, rho * direct, "K_d + K_s > 1");
}

#[test]
fn mirror_glass_and_emitter_as_targets() {
    // The floor is measured too: a coloured mirror, a glass sheet over the box's bottom
    // (every photon then ends in the box: Φ), and a black emitter (the box also gets its
    // π·L·A). A specular departure makes no connection and its arrivals count fully.
    let ks = Vec3::new(0.9, 0.5, 0.2);
    let direct = CANDELA * seen_from_lamp(-1.0, 1.0, -1.0, 1.0);
    let scene = enclosure(Material::mirror("Mirror", ks), None, false);
    assert_enclosure(&scene, luminance(ks) as f64 * direct, "mirror floor");
    let scene = enclosure(Material::glass("Glass", 1.5), None, true);
    assert_enclosure(&scene, direct, "glass floor");
    let lum = 50.0;
    let scene = enclosure(Material::emitter("Glow", Vec3::splat(lum)), None, false);
    assert_enclosure(&scene, PI * lum as f64 * 4.0, "emitting floor");
}

/// Mean illuminance over [x0,x1]×[y0,y1] at z = 0 from a spot of `cd` at `p` along unit
/// `axis` (glTF profile: 1 inside the inner cone, t² in the ring), by the midpoint rule on
/// an n × n grid (n = 1000: 10⁻⁶ relative, far below the tests' errors).
fn spot_on_rect(p: [f64; 3], axis: [f64; 3], cd: f64, cones: (f64, f64), r: [f64; 4]) -> f64 {
    let (ci, co) = cones;
    let [x0, x1, y0, y1] = r;
    let n = 1000;
    let (dx, dy) = ((x1 - x0) / n as f64, (y1 - y0) / n as f64);
    let mut sum = 0.0;
    for i in 0..n {
        let x = x0 + (i as f64 + 0.5) * dx;
        for j in 0..n {
            let y = y0 + (j as f64 + 0.5) * dy;
            let d = [x - p[0], y - p[1], -p[2]];
            let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            let dist = r2.sqrt();
            let c = (axis[0] * d[0] + axis[1] * d[1] + axis[2] * d[2]) / dist;
            let profile = if c >= ci {
                1.0
            } else if c > co {
                ((c - co) / (ci - co)).powi(2)
            } else {
                0.0
            };
            sum += cd * profile * (p[2] / dist) / r2;
        }
    }
    sum / (n * n) as f64
}

#[test]
fn spot_across_its_cap_and_ring() {
    // A tilted spot whose inner cap and outer ring both fall on a black patch and partly
    // beside it: connections see the profile from every point they draw, arrivals
    // weight themselves with it.
    let (inner, outer) = (0.25f32, 0.5f32);
    let axis = Vec3::new(0.3, 0.1, -1.0).normalize();
    let at = Vec3::new(0.2, 0.1, 1.0);
    let r = [-0.3, 0.9, -0.4, 0.6];
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let [x0, x1, y0, y1] = r.map(|c| c as f32);
    let patch = scene.add_mesh(rect(x0, x1, y0, y1, 0.0, black));
    scene.add_instance("Patch", patch, Mat4::IDENTITY);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Spot".into(),
        kind: LightKind::Spot {
            position: at,
            direction: axis,
            intensity: Vec3::splat(200.0),
            inner,
            outer,
        },
    });
    let cones = (inner.cos() as f64, outer.cos() as f64);
    let exact = spot_on_rect(
        at.to_array().map(|c| c as f64),
        axis.to_array().map(|c| c as f64),
        200.0,
        cones,
        r,
    );
    assert_honest(&scene, "Patch", exact);
}

#[test]
fn sun_on_a_block_from_every_side() {
    // A sun of E lx on a grey 0.6 × 0.4 × 0.3 m block: its faces catch E times its
    // projected area. The faces turned away connect through the block to the sun and must
    // find it in the way; reflected light leaves a convex block for good.
    let d = Vec3::new(0.4, -0.3, -1.0).normalize();
    let (a, b, c) = (0.6f64, 0.4f64, 0.3f64);
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let block = scene.add_mesh(Mesh::cuboid(
        Vec3::ZERO,
        Vec3::new(a as f32, b as f32, c as f32),
        grey,
    ));
    scene.add_instance("Block", block, Mat4::IDENTITY);
    scene.lights.push(sun(d, 1000.0));
    let d = d.as_dvec3();
    let projected = b * c * d.x.abs() + a * c * d.y.abs() + a * b * d.z.abs();
    let exact = 1000.0 * projected / (2.0 * (a * b + b * c + a * c));
    assert_honest(&scene, "Block", exact);
}

#[test]
fn lamp_through_a_hole_and_a_roof_around_it() {
    // A 100 cd lamp 1 m above a 10 × 10 m roof with a 1 × 1 m hole: the black floor 3 m
    // below gets I·Ω_hole, the roof (measured over its whole area, the hole included)
    // I·(Ω_roof − Ω_hole). Connection rays pass the hole and nothing else.
    let mut scene = roof_with_hole(4.0);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.2, 0.3, 4.0), 100.0));
    let hole = rect_solid_angle(-0.2, 0.8, -0.3, 0.7, 1.0);
    let roof = rect_solid_angle(-5.2, 4.8, -5.3, 4.7, 1.0);
    let e = connected(&scene, &["Floor", "Roof"], 524_288);
    assert_close(&e[0], 100.0 * hole / 64.0, "floor under the hole");
    assert_close(&e[1], 100.0 * (roof - hole) / 100.0, "roof around the hole");
}

#[test]
fn targets_sharing_an_instance() {
    // A closed grey room whose floor is its own instance, measured both as "Floor" and
    // as part of "Room": each target connects on its own, and the room still gets
    // Φ/(A(1 − ρ)).
    let rho = 0.6f32;
    let mut scene = Scene::default();
    let m = scene.add_material(Material::diffuse("Walls", Vec3::splat(rho)));
    let mut walls = Mesh::cuboid(Vec3::ZERO, Vec3::new(4.0, 3.0, 2.5), m);
    walls.triangles.drain(0..2);
    walls.materials.drain(0..2);
    let w = scene.add_mesh(walls);
    scene.add_instance("Room", w, Mat4::IDENTITY);
    // Facing up, into the room.
    let f = scene.add_mesh(rect(0.0, 4.0, 0.0, 3.0, 0.0, m));
    let floor = scene.add_instance("Floor", f, Mat4::IDENTITY);
    scene.add_to_surface("Room", floor);
    scene
        .lights
        .push(point("Lamp", Vec3::new(1.0, 2.0, 2.0), 100.0));
    let area = 2.0 * (4.0 * 3.0 + 4.0 * 2.5 + 3.0 * 2.5);
    let e = connected(&scene, &["Floor", "Room"], 262_144);
    assert_close(
        &e[1],
        4.0 * PI * 100.0 / (area * (1.0 - rho as f64)),
        "room around its floor",
    );
}

#[test]
fn a_thin_target_lit_from_both_sides() {
    // A single black quad between a point lamp above and a spot below aimed up at it:
    // arrivals and connections on either face, photons drawn from two kinds of lights in
    // proportion to their flux. The spot's part is the mirror image of a spot above.
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let r = [-0.5, 0.7, -0.4, 0.4];
    let [x0, x1, y0, y1] = r.map(|c| c as f32);
    let sheet = scene.add_mesh(rect(x0, x1, y0, y1, 0.0, black));
    scene.add_instance("Sheet", sheet, Mat4::IDENTITY);
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.1, -0.1, 0.6), 30.0));
    let (inner, outer) = (0.3f32, 0.7f32);
    let axis = Vec3::new(-0.2, 0.1, 1.0).normalize();
    let at = Vec3::new(0.3, 0.0, -0.8);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Spot".into(),
        kind: LightKind::Spot {
            position: at,
            direction: axis,
            intensity: Vec3::splat(80.0),
            inner,
            outer,
        },
    });
    let area = (r[1] - r[0]) * (r[3] - r[2]);
    let above = 30.0 * rect_solid_angle(r[0] - 0.1, r[1] - 0.1, r[2] + 0.1, r[3] + 0.1, 0.6) / area;
    let mirrored = |v: Vec3| [v.x as f64, v.y as f64, -v.z as f64];
    let below = spot_on_rect(
        mirrored(at),
        mirrored(axis),
        80.0,
        (inner.cos() as f64, outer.cos() as f64),
        r,
    );
    let e = connected(&scene, &["Sheet"], 262_144);
    assert_close(&e[0], above + below, "sheet lit from both sides");
}
