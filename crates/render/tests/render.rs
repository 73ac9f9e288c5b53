//! Renders and grids with closed-form answers: a diffuse plane under point, spot, sun and
//! goniometric light; a white furnace; illuminance cells under a point light; images and grids
//! that do not depend on the number of threads; the plot files.

use glam::{Mat4, Vec3};
use invlight_photon::{Estimator, GridError, GridValues, Side, TraceSettings};
use invlight_render::{
    AreaLights, GridSpacing, IlluminanceImage, Image, Integrator, MapError, MapSettings, Mark,
    Paths, PhotonMap, PhotonSettings, PlanAxis, PlanFrame, PlotKind, PlotPoint, RenderSettings,
    SearchPlot, Store, View, illuminance_map, render, render_illuminance,
};
use invlight_scene::{
    Camera, Light, LightKind, Material, MaterialId, Mesh, PhotometricSystem, Photometry, Scene,
    aimed_frame,
};
use invlight_stats::{Confidence, Pcg32};
use invlight_trace::Accel;
use std::f32::consts::PI;
use std::sync::Arc;

fn camera(position: Vec3, forward: Vec3, up: Vec3, yfov_deg: f32) -> Camera {
    Camera {
        name: "cam".into(),
        position,
        forward,
        up,
        yfov: yfov_deg.to_radians(),
        aspect: None,
    }
}

fn settings(width: u32, height: u32) -> RenderSettings {
    RenderSettings {
        width,
        height,
        samples: 1,
        light_samples: 1,
        max_depth: 8,
        seed: 7,
    }
}

/// A 4 m square plane at z = 0 of reflectance `kd`, lit from above by a point light, a
/// spot, a sun and a goniometric light whose table depends on C and γ, aimed 20° off
/// the vertical.
fn lit_plane(kd: f32) -> (Scene, Vec<LightKind>) {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let m = scene.add_material(Material::diffuse("grey", Vec3::splat(kd)));
    let quad = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(-2.0, -2.0, 0.0),
            Vec3::new(2.0, -2.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(-2.0, 2.0, 0.0),
        ],
        m,
    ));
    scene.add_instance("Floor", quad, Mat4::IDENTITY);
    let lights = vec![
        LightKind::Point {
            position: Vec3::new(0.3, 0.2, 1.5),
            intensity: Vec3::splat(100.0),
        },
        LightKind::Spot {
            position: Vec3::new(-0.5, 0.4, 2.0),
            direction: Vec3::new(0.2, -0.1, -1.0).normalize(),
            intensity: Vec3::splat(300.0),
            inner: 0.3,
            outer: 0.6,
        },
        LightKind::Directional {
            direction: Vec3::new(0.5, 0.0, -1.0).normalize(),
            illuminance: Vec3::splat(40.0),
        },
        LightKind::Goniometric {
            position: Vec3::new(0.6, -0.7, 1.8),
            frame: aimed_frame(
                Vec3::new(0.0, 20f32.to_radians().sin(), -20f32.to_radians().cos()),
                Vec3::X,
            ),
            photometry: Arc::new(
                Photometry::from_table(
                    PhotometricSystem::C,
                    vec![0.0, 90.0, 180.0, 270.0, 360.0],
                    vec![0.0, 45.0, 90.0],
                    vec![
                        200.0, 150.0, 10.0, 200.0, 60.0, 0.0, 200.0, 20.0, 0.0, 200.0, 90.0, 30.0,
                        200.0, 150.0, 10.0,
                    ],
                )
                .unwrap(),
            ),
            multiplier: Vec3::splat(0.5),
            tilt: 1.0,
        },
    ];
    for (i, kind) in lights.iter().enumerate() {
        scene.lights.push(Light {
            c0: invlight_scene::Vec3::X,
            name: format!("l{i}"),
            kind: kind.clone(),
        });
    }
    (scene, lights)
}

/// Closed-form illuminance at a point of the plane z = 0 (normal +Z), lx.
fn plane_illuminance(p: Vec3, lights: &[LightKind]) -> f32 {
    lights
        .iter()
        .map(|l| match *l {
            LightKind::Point {
                position,
                intensity,
            } => {
                let d = position - p;
                intensity.x * d.z / d.length().powi(3)
            }
            LightKind::Spot {
                position,
                direction,
                intensity,
                inner,
                outer,
            } => {
                let d = position - p;
                let f = LightKind::spot_falloff((-d.normalize()).dot(direction), inner, outer);
                intensity.x * f * d.z / d.length().powi(3)
            }
            LightKind::Directional {
                direction,
                illuminance,
            } => illuminance.x * (-direction.z),
            LightKind::Goniometric {
                position,
                frame,
                ref photometry,
                multiplier,
                tilt,
            } => {
                // The angles of the direction toward p in the luminaire's frame.
                let d = position - p;
                let w = -d.normalize();
                let (x, y, z) = (
                    w.dot(frame.x_axis),
                    w.dot(frame.y_axis),
                    w.dot(frame.z_axis),
                );
                let gamma = (-z).acos().to_degrees();
                let c = y.atan2(x).to_degrees().rem_euclid(360.0);
                let i = photometry.intensity(c as f64, gamma as f64) as f32;
                multiplier.x * tilt * i * d.z / d.length().powi(3)
            }
        })
        .sum()
}

/// Every pixel of the plane is ρ/π times the closed-form illuminance. With one ray
/// through each pixel centre, point-like lights and no photon map the estimator has no
/// noise at all, so the tolerance is the f32 rounding of the geometry (1e-4 relative).
/// The image has an even size, so no camera ray runs exactly along −Z.
#[test]
fn plane_radiance_is_proportional_to_closed_form_illuminance() {
    let kd = 0.6;
    let (scene, lights) = lit_plane(kd);
    let accel = Accel::new(&scene);
    let sky = AreaLights::new(&scene);
    let cam = camera(Vec3::new(0.1, -0.2, 3.0), Vec3::NEG_Z, Vec3::Y, 60.0);
    let s = settings(40, 30);
    let view = View::from_camera(&cam, 40.0 / 30.0);
    let integrator = Integrator::new(&scene, &accel, &sky, None, s);
    let image = render(&integrator, &view, None);
    let mut checked = 0;
    for y in 0..s.height {
        for x in 0..s.width {
            let ray = view.ray((x as f32 + 0.5) / 40.0, (y as f32 + 0.5) / 30.0);
            let t = -ray.origin.z / ray.dir.z;
            let p = ray.at(t);
            let px = image.pixels[(y * s.width + x) as usize];
            if p.x.abs() < 1.99 && p.y.abs() < 1.99 {
                let expected = kd / PI * plane_illuminance(p, &lights);
                assert!(
                    (px.x - expected).abs() <= 1e-4 * expected,
                    "pixel ({x}, {y}): {} vs {expected}",
                    px.x
                );
                assert_eq!(px.x, px.y);
                checked += 1;
            } else if p.x.abs() > 2.01 || p.y.abs() > 2.01 {
                assert_eq!(px, Vec3::ZERO);
            }
        }
    }
    assert!(checked > 900);
}

/// The inside of a sphere of radius `r` as `stacks` × `slices` quads, counter-clockwise
/// seen from inside (so it emits inwards).
fn inward_sphere(r: f32, stacks: u32, slices: u32, material: MaterialId) -> Mesh {
    let mut positions = Vec::new();
    for i in 0..=stacks {
        let theta = PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let phi = 2.0 * PI * j as f32 / slices as f32;
            positions.push(
                r * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ),
            );
        }
    }
    let at = |i: u32, j: u32| i * slices + j % slices;
    let mut triangles = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            // Outward winding would be a, d, c; inward reverses it.
            if i > 0 {
                triangles.push([a, b, c]);
            }
            if i + 1 < stacks {
                triangles.push([a, c, d]);
            }
        }
    }
    Mesh {
        positions,
        uvs: Vec::new(),
        materials: vec![material; triangles.len()],
        triangles,
    }
}

/// White furnace: inside a closed sphere that emits L and reflects ρ everywhere, the
/// radiance is L/(1 − ρ) in every direction. The map holds all the light here (first
/// arrivals too; shadow rays to a faceted emitter have unbounded variance where facets
/// meet), so a pixel is L + ρ/π·E with E = πL/(1 − ρ) estimated from the photons. With
/// M photons expected in a gather disc, all of equal power, the biweight estimate has
/// relative standard deviation sqrt(E[w²]/E[w]²/M) = sqrt(1.8/M); every pixel must lie
/// within 5 σ of L/(1 − ρ). The chord-distance disc on a sphere has area exactly πr²
/// (Archimedes), so curvature adds no bias.
#[test]
fn white_furnace_renders_a_uniform_image() {
    let (le, rho) = (1.0f32, 0.5f32);
    let mut scene = Scene::default();
    let m = scene.add_material(Material {
        diffuse: Vec3::splat(rho),
        emission: Vec3::splat(le),
        ..Material::diffuse("furnace", Vec3::ZERO)
    });
    let sphere = scene.add_mesh(inward_sphere(1.0, 48, 96, m));
    scene.add_instance("Sphere", sphere, Mat4::IDENTITY);
    let accel = Accel::new(&scene);
    let radius = 0.2f32;
    let photons = PhotonSettings {
        photons: 150_000,
        seed: 3,
        max_bounces: 64,
        store: Store::Diffuse,
        radius: Some(radius),
        neighbours: 0,
        paths: Paths::All,
    };
    let map = PhotonMap::build(&scene, &accel, &photons, None);
    // Expected arrivals per photon: 1 + ρ + ρ² + … = 1/(1 − ρ).
    let expected_stored = photons.photons as f32 / (1.0 - rho);
    let m_disc = expected_stored * PI * radius * radius / (4.0 * PI);
    let sky = AreaLights::new(&scene);
    let s = settings(24, 18);
    let cam = camera(Vec3::new(0.05, 0.02, -0.03), Vec3::X, Vec3::Z, 90.0);
    let view = View::from_camera(&cam, 24.0 / 18.0);
    let integrator = Integrator::new(&scene, &accel, &sky, Some(&map), s);
    let image = render(&integrator, &view, None);
    let expected = le / (1.0 - rho);
    // ρ/π·E = ρL/(1 − ρ) carries all the noise.
    let sigma = rho * le / (1.0 - rho) * (1.8 / m_disc).sqrt();
    for (i, px) in image.pixels.iter().enumerate() {
        assert!(
            (px.x - expected).abs() < 5.0 * sigma,
            "pixel {i}: {} vs {expected} ± {sigma}",
            px.x
        );
    }
}

/// A closed room with coloured walls, a mirror box, an emissive panel and a point light.
fn small_room() -> Scene {
    let mut scene = Scene::default();
    let white = scene.add_material(Material::diffuse("white", Vec3::splat(0.7)));
    let red = scene.add_material(Material::diffuse("red", Vec3::new(0.7, 0.1, 0.1)));
    let mirror = scene.add_material(Material::mirror("mirror", Vec3::splat(0.9)));
    let glass = scene.add_material(Material::glass("glass", 1.5));
    let lamp = scene.add_material(Material::emitter("lamp", Vec3::splat(50.0)));
    // Walls: a cuboid seen from inside blocks from both sides; shading flips normals.
    let room = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0), white));
    scene.add_instance("Room", room, Mat4::IDENTITY);
    let wall = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.01, 0.0, 0.0),
            Vec3::new(0.01, 2.0, 0.0),
            Vec3::new(0.01, 2.0, 2.0),
            Vec3::new(0.01, 0.0, 2.0),
        ],
        red,
    ));
    scene.add_instance("Red", wall, Mat4::IDENTITY);
    let cube = scene.add_mesh(Mesh::cuboid(Vec3::splat(-0.25), Vec3::splat(0.25), mirror));
    scene.add_instance(
        "Mirror",
        cube,
        Mat4::from_translation(Vec3::new(0.6, 1.2, 0.25)),
    );
    let ball = scene.add_mesh(Mesh::cuboid(Vec3::splat(-0.2), Vec3::splat(0.2), glass));
    scene.add_instance(
        "Glass",
        ball,
        Mat4::from_translation(Vec3::new(1.4, 1.0, 0.2)),
    );
    let panel = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.8, 0.8, 1.99),
            Vec3::new(0.8, 1.2, 1.99),
            Vec3::new(1.2, 1.2, 1.99),
            Vec3::new(1.2, 0.8, 1.99),
        ],
        lamp,
    ));
    scene.add_instance("Lamp", panel, Mat4::IDENTITY);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "bulb".into(),
        kind: LightKind::Point {
            position: Vec3::new(1.5, 0.5, 1.5),
            intensity: Vec3::splat(5.0),
        },
    });
    scene.cameras.push(camera(
        Vec3::new(1.0, -0.0, 1.0) + Vec3::new(0.0, 0.05, 0.0),
        Vec3::Y,
        Vec3::Z,
        70.0,
    ));
    scene
}

fn render_room(threads: usize) -> (Image, IlluminanceImage, Image) {
    let scene = small_room();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let accel = Accel::new(&scene);
        let map = PhotonMap::build(
            &scene,
            &accel,
            &PhotonSettings {
                photons: 30_000,
                ..PhotonSettings::default()
            },
            None,
        );
        let sky = AreaLights::new(&scene);
        let s = RenderSettings {
            samples: 2,
            ..settings(32, 24)
        };
        let view = View::from_camera(&scene.cameras[0], 32.0 / 24.0);
        let integrator = Integrator::new(&scene, &accel, &sky, Some(&map), s);
        // A final gather over a global map, with caustics from their own map.
        let global = PhotonMap::build(
            &scene,
            &accel,
            &PhotonSettings {
                photons: 30_000,
                paths: Paths::All,
                ..PhotonSettings::default()
            },
            None,
        )
        .precompute(4);
        let caustics = PhotonMap::build(
            &scene,
            &accel,
            &PhotonSettings {
                photons: 30_000,
                paths: Paths::Caustic,
                radius: Some(global.radius()),
                ..PhotonSettings::default()
            },
            None,
        );
        let gathering =
            Integrator::new(&scene, &accel, &sky, Some(&caustics), s).with_final_gather(&global, 4);
        (
            render(&integrator, &view, None),
            render_illuminance(&integrator, &view, None),
            render(&gathering, &view, None),
        )
    })
}

#[test]
fn images_do_not_depend_on_the_thread_count() {
    let (a, la, ga) = render_room(1);
    let (b, lb, gb) = render_room(2);
    assert!(a.pixels.iter().any(|p| p.x > 0.0));
    assert_eq!(a, b);
    assert_eq!(ga, gb);
    assert!(ga.pixels.iter().any(|p| p.x > 0.0));
    assert_eq!(
        la.lux.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        lb.lux.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );
}

/// A black 2 m square (so only direct arrivals) under a point light: each cell's mean
/// is the average of E = I·h/d³ over the cell, integrated here by a 64×64 midpoint rule
/// (error far below the noise). Each of the 16 cells must hold it within 4 standard
/// errors (a two-sided 95 % interval would miss in one cell of twenty by chance; 4σ
/// makes a false failure of the test about 1 in 1000).
#[test]
fn grid_cells_match_the_closed_form_under_a_point_light() {
    let mut scene = Scene::default();
    let black = scene.add_material(Material::diffuse("black", Vec3::ZERO));
    let quad = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ],
        black,
    ));
    scene.add_instance("Floor", quad, Mat4::IDENTITY);
    let (light, intensity) = (Vec3::new(0.7, 1.3, 1.0), 100.0f64);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "bulb".into(),
        kind: LightKind::Point {
            position: light,
            intensity: Vec3::splat(intensity as f32),
        },
    });
    let accel = Accel::new(&scene);
    let exact = |x0: f64, y0: f64| {
        let n = 64;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let x = x0 + (i as f64 + 0.5) / n as f64 * 0.5;
                let y = y0 + (j as f64 + 0.5) / n as f64 * 0.5;
                let d = (light.as_dvec3() - glam::DVec3::new(x, y, 0.0)).length();
                sum += intensity * light.z as f64 / d.powi(3);
            }
        }
        sum / (n * n) as f64
    };
    // Both estimators within 4 σ of every cell's exact value; the connected one's mean
    // relative σ below half the arrivals' (direct light on a black floor is where a
    // connection per departure pays most).
    let mut relative_errors = Vec::new();
    let mut last = None;
    for estimator in [Estimator::ArrivalsOnly, Estimator::Connected] {
        let settings = MapSettings {
            spacing: GridSpacing::Metres(0.5),
            side: Side::Both,
            trace: TraceSettings {
                photons: 400_000,
                seed: 11,
                max_bounces: 4,
                ..TraceSettings::default()
            },
            estimator,
            values: GridValues::CellMeans,
        };
        let floor = scene.surface("Floor").unwrap();
        let map = illuminance_map(&scene, &accel, floor, &settings, None).unwrap();
        assert_eq!((map.columns, map.rows), (4, 4));
        let mut total = 0.0;
        let mut relative = 0.0;
        for cell in map.cells.iter().map(|c| c.unwrap()) {
            assert!((cell.area - 0.25).abs() < 1e-6);
            let corner = map.origin
                + map.u * (cell.index.0 as f32 * 0.5)
                + map.v * (cell.index.1 as f32 * 0.5);
            let e = exact(corner.x as f64, corner.y as f64);
            let est = cell.estimate;
            assert!(
                (est.mean - e).abs() < 4.0 * est.std_error,
                "{estimator:?} cell {:?}: {} ± {} vs {e}",
                cell.index,
                est.mean,
                est.std_error
            );
            // The check above means something only if the interval is informative.
            assert!(
                est.std_error < 0.05 * e,
                "cell {:?}: σ {}",
                cell.index,
                est.std_error
            );
            relative += est.std_error / e / 16.0;
            total += est.mean * cell.area;
        }
        relative_errors.push(relative);
        last = Some((map, total));
    }
    assert!(
        relative_errors[1] < 0.5 * relative_errors[0],
        "relative σ: arrivals {}, connected {}",
        relative_errors[0],
        relative_errors[1]
    );
    let (map, total) = last.unwrap();
    let summary = map.summary();
    assert!((summary.eavg - total / 4.0).abs() < 1e-9 * total);
    assert!((summary.u0 - summary.emin / summary.eavg).abs() < 1e-12);
    assert!(summary.emin <= summary.eavg && summary.eavg <= summary.emax);
    assert_eq!(summary.max_ratio(), Some(summary.emax / summary.emin));
    assert_eq!(
        map.spacing_rule,
        "0.5 m as asked (EN 12464-1's grid rule would take 0.32 m)"
    );
    // The whole surface's estimate is the cells' area-weighted mean, with an error no
    // larger than the cells' own (it pools their photons).
    assert!((map.mean.mean - summary.eavg).abs() < 1e-9 * summary.eavg);
    let worst = map
        .cells
        .iter()
        .flatten()
        .map(|c| c.estimate.std_error)
        .fold(0.0, f64::max);
    assert!(map.mean.std_error > 0.0 && map.mean.std_error < worst);
    // U0's interval covers the ratio of the exact least cell to the exact mean.
    let exact_cells: Vec<f64> = map
        .cells
        .iter()
        .flatten()
        .map(|c| {
            let corner = c.centre - (map.u + map.v) * 0.25;
            exact(corner.x as f64, corner.y as f64)
        })
        .collect();
    let exact_u0 = exact_cells.iter().copied().fold(f64::INFINITY, f64::min)
        / (exact_cells.iter().sum::<f64>() / 16.0);
    assert!(
        (map.u0.mean - exact_u0).abs() < 4.0 * map.u0.std_error && map.u0.std_error < 0.05,
        "U0 {} ± {} vs {exact_u0}",
        map.u0.mean,
        map.u0.std_error
    );
    // All the light arrives on the floor's front: its back reads nothing, so no warning.
    assert!(map.front_back.1 == 0.0 && map.warning("Floor").is_none());
    let floor = scene.surface("Floor").unwrap();
    let back = MapSettings {
        spacing: GridSpacing::Auto,
        side: Side::Back,
        trace: TraceSettings {
            photons: 20_000,
            seed: 11,
            max_bounces: 4,
            ..TraceSettings::default()
        },
        estimator: Estimator::Connected,
        values: GridValues::Points,
    };
    let back_settings = back;
    let back = illuminance_map(&scene, &accel, floor, &back, None).unwrap();
    assert_eq!(back.mean.mean, 0.0);
    // EN 12464-1 spaces a 2 m square by 0.2·5^log10(2) = 0.325 m: 7 × 7 cells.
    assert_eq!((back.columns, back.rows), (7, 7));
    assert!((back.spacing - 0.2 * 5f32.powf(2f32.log10())).abs() < 1e-6);
    assert!(
        back.spacing_rule
            .contains("= 0.32 m, d = 2.00 m (the longer side)"),
        "{}",
        back.spacing_rule
    );
    // Nothing on the back: no Emin, so no Emax/Emin either, and the lines say so.
    assert_eq!(back.summary().max_ratio(), None);
    let lines = back
        .report("Floor", &back_settings, Confidence::DEFAULT, 0.0)
        .summary();
    assert!(
        lines.contains("grid: EN 12464-1's grid rule") && lines.contains("Emax/Emin ∞"),
        "{lines}"
    );
}

#[test]
fn grids_need_a_plane_and_do_not_depend_on_threads() {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("grey", Vec3::splat(0.5)));
    let cube = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::ONE, grey));
    scene.add_instance("Box", cube, Mat4::IDENTITY);
    let accel = Accel::new(&scene);
    let settings = MapSettings {
        spacing: GridSpacing::Metres(0.25),
        side: Side::Both,
        trace: TraceSettings {
            photons: 1000,
            seed: 1,
            max_bounces: 4,
            ..TraceSettings::default()
        },
        estimator: Estimator::Connected,
        values: GridValues::Points,
    };
    assert!(matches!(
        illuminance_map(
            &scene,
            &accel,
            scene.surface("Box").unwrap(),
            &settings,
            None
        ),
        Err(MapError::Grid(GridError::NotPlanar { .. }))
    ));
    let room = small_room();
    let accel = Accel::new(&room);
    let red = room.surface("Red").unwrap();
    let settings = MapSettings {
        trace: TraceSettings {
            photons: 50_000,
            ..settings.trace
        },
        ..settings
    };
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| illuminance_map(&room, &accel, red, &settings, None).unwrap())
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a, b);
    assert_eq!((a.columns, a.rows), (8, 8));
}

/// Pixels of `img` above `bottom` whose colour is within 8 of `c` on every channel.
fn pixels_like(img: &image::RgbImage, c: [u8; 3], bottom: u32) -> Vec<(u32, u32)> {
    img.enumerate_pixels()
        .filter(|(_, y, p)| *y < bottom && (0..3).all(|k| (p.0[k] as i32 - c[k] as i32).abs() <= 8))
        .map(|(x, y, _)| (x, y))
        .collect()
}

#[test]
fn search_plots_put_points_where_their_world_coordinates_say() {
    let dir = tempfile::tempdir().unwrap();
    let mut rng = Pcg32::new(5, 0);
    let mut points = Vec::new();
    for i in 0..40 {
        let (x, y) = (
            1.0 + rng.uniform() as f64 * 3.0,
            1.0 + rng.uniform() as f64 * 2.0,
        );
        let mean = 100.0 + 50.0 * (x - 1.0);
        let cell = vec![
            [x - 0.05, y - 0.05],
            [x + 0.05, y - 0.05],
            [x + 0.05, y + 0.05],
            [x - 0.05, y + 0.05],
        ];
        points.push(PlotPoint {
            at: [x, y],
            cell,
            mean,
            low: mean - 5.0,
            high: mean + 5.0,
            mark: match i {
                0 => Mark::Start,
                5 | 12 | 30 => Mark::Improvement,
                7 => Mark::Invalid,
                _ => Mark::Visited,
            },
            isoc: false,
        });
    }
    // One ISOC member at a known place: (2.5, 2.0) m.
    points[30].at = [2.5, 2.0];
    points[30].isoc = true;
    let axis = |name: &str| PlanAxis {
        name: name.into(),
        sign: 1.0,
    };
    let plan = PlanFrame {
        axes: [axis("x"), axis("y")],
        room: Some([[0.0, 0.0], [6.0, 4.0]]),
        target: vec![[[2.0, 1.5], [3.0, 1.5], [2.5, 2.5]]],
        range: [[1.0, 1.0], [4.0, 1.0], [4.0, 3.0], [1.0, 3.0]],
        rectangle: None,
        moved: "Cone centre".into(),
        target_name: "Cone".into(),
    };
    let kinds = [
        PlotKind::Plan(Box::new(plan)),
        PlotKind::Sky {
            north: "−z".into()
        },
        PlotKind::Value {
            min: 0.0,
            max: 5.0,
            label: "dimming level (1 = as authored)".into(),
        },
    ];
    for (k, kind) in kinds.into_iter().enumerate() {
        let plot = SearchPlot {
            title: "search".into(),
            kind,
            unit: "lx".into(),
            quantity: "mean illuminance".into(),
            cap: (k == 2).then_some(240.0),
            points: points.clone(),
        };
        let path = dir.path().join(format!("search-{k}.png"));
        plot.write(&path).unwrap();
        let img = image::open(&path).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), invlight_render::PLOT_SIZE);
        let svg = plot.svg().unwrap();
        assert!(svg.starts_with("<svg"));
        if k == 2 {
            // The value axis says what the variable is; the key what an invalid mark is.
            assert!(svg.contains("dimming level (1 = as authored)"));
            assert!(svg.contains("mean illuminance (lx)"));
            assert!(svg.contains("over the cap or infeasible"));
        }
        // The colour bar runs over the valid means' range, not a rounded one.
        let scale = plot.scale();
        let valid: Vec<f64> = points
            .iter()
            .filter(|p| p.mark != Mark::Invalid)
            .map(|p| p.mean)
            .collect();
        assert_eq!(
            scale.min,
            valid.iter().cloned().fold(f64::INFINITY, f64::min)
        );
        assert_eq!(
            scale.max,
            valid.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        );
        let bar_x = invlight_render::PLOT_SIZE.0 - 100;
        let column: Vec<[u8; 3]> = (0..img.height())
            .map(|y| img.get_pixel(bar_x, y).0)
            .collect();
        for end in [invlight_render::viridis(0.0), invlight_render::viridis(1.0)] {
            assert!(
                column
                    .iter()
                    .any(|c| (0..3).all(|i| (c[i] as i32 - end[i] as i32).abs() <= 3)),
                "plot {k}: the bar lacks the colour {end:?} of an end of the data's range"
            );
        }
        if k != 0 {
            continue;
        }
        // The ISOC ring is centred on the pixel of (2.5, 2.0) m, and a metre is as
        // long across as up the page.
        let (_, frame) = plot.image().unwrap();
        let red = pixels_like(&img, [214, 39, 40], invlight_render::PLOT_SIZE.1 - 40);
        assert!(red.len() > 20, "{} ISOC pixels", red.len());
        let cx = red.iter().map(|p| p.0 as f64).sum::<f64>() / red.len() as f64;
        let cy = red.iter().map(|p| p.1 as f64).sum::<f64>() / red.len() as f64;
        let (px, py) = frame.pixel(2.5, 2.0);
        assert!(
            (cx - px as f64).abs() <= 1.5 && (cy - py as f64).abs() <= 1.5,
            "ring at ({cx}, {cy}), expected ({px}, {py})"
        );
        let per_m_x = (frame.columns.1 - frame.columns.0) as f64 / (frame.x.1 - frame.x.0);
        let per_m_y = (frame.rows.0 - frame.rows.1) as f64 / (frame.y.1 - frame.y.0);
        assert!(
            (per_m_x / per_m_y - 1.0).abs() < 0.01,
            "{per_m_x} vs {per_m_y} px/m"
        );
        // The room's corners are inside the frame.
        assert!(frame.x.0 <= 0.0 && frame.x.1 >= 6.0 && frame.y.0 <= 0.0 && frame.y.1 >= 4.0);
    }
}

/// Under a CIE overcast sky and nothing else, an open floor's direct illuminance is the
/// sky's horizontal illuminance (the `horizontalLux` it is made from), within 4 σ of the
/// shadow rays' own spread; a camera ray that leaves the scene sees the sky's luminance,
/// the zenith's looking straight up, the CIE gradation's at 45°, and nothing below the
/// horizon.
#[test]
fn the_sky_lights_the_render_and_is_seen_through_it() {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let floor = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(-10.0, -10.0, 0.0),
            Vec3::new(10.0, -10.0, 0.0),
            Vec3::new(10.0, 10.0, 0.0),
            Vec3::new(-10.0, 10.0, 0.0),
        ],
        grey,
    ));
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    let sky = invlight_scene::daylight::Sky::cie_overcast(Vec3::Z, 10_000.0).unwrap();
    let lz = sky.zenith_luminance() as f32;
    scene.sky = Some(Arc::new(sky));
    let accel = Accel::new(&scene);
    let lights = AreaLights::new(&scene);
    let integrator = Integrator::new(&scene, &accel, &lights, None, settings(8, 8));
    let down = invlight_trace::Ray::new(Vec3::new(0.3, 0.2, 1.0), Vec3::NEG_Z);
    let n = 20_000;
    let readings: Vec<f64> = (0..n)
        .map(|i| {
            let mut rng = Pcg32::new(11, i);
            integrator.illuminance(&down, &mut rng).unwrap().0 as f64
        })
        .collect();
    let mean = readings.iter().sum::<f64>() / n as f64;
    let var = readings.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let sigma = (var / n as f64).sqrt();
    assert!(sigma > 0.0 && sigma < 0.01 * mean, "{sigma}");
    assert!((mean - 10_000.0).abs() < 4.0 * sigma, "{mean} ± {sigma} lx");

    let mut rng = Pcg32::new(1, 1);
    let up = invlight_trace::Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::Z);
    assert!((integrator.radiance(&up, &mut rng).x - lz).abs() < 1e-3 * lz);
    let slant = Vec3::new(1.0, 0.0, 1.0).normalize();
    let seen = integrator
        .radiance(
            &invlight_trace::Ray::new(Vec3::new(0.0, 0.0, 1.0), slant),
            &mut rng,
        )
        .x;
    let cie = lz * (1.0 + 2.0 * slant.z) / 3.0;
    assert!((seen - cie).abs() < 1e-3 * cie, "{seen} vs {cie}");
    let below = invlight_trace::Ray::new(Vec3::new(0.0, 0.0, -1.0), Vec3::NEG_Z);
    assert_eq!(integrator.radiance(&below, &mut rng), Vec3::ZERO);
}
