//! EN 12464-1's areas around a task area, measured against a closed form: in a black
//! room an isotropic point source of intensity I brings a surface the flux I·Ω (Ω the
//! solid angle it subtends), so the mean illuminance of every area is I·Ω/A, whatever
//! the bands' frame shape or the walls' orientation.

use glam::{Mat4, Vec3};
use invlight_photon::{Estimator, GridValues, TraceSettings, cluster};
use invlight_render::{GridSpacing, MapSettings, MapTarget, illuminance_maps_across};
use invlight_scene::{AreaKind, Light, LightKind, Material, Mesh, Scene};
use invlight_trace::Accel;
use std::path::Path;

/// The solid angle of triangle `t` seen from `p` (A. Van Oosterom and J. Strackee, "The
/// solid angle of a plane triangle", IEEE Trans. Biomed. Eng. 30(2), 1983).
fn solid_angle(p: Vec3, t: [Vec3; 3]) -> f64 {
    let [a, b, c] = t.map(|v| (v - p).as_dvec3());
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let num = a.dot(b.cross(c)).abs();
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * num.atan2(den)
}

#[test]
fn every_area_reads_the_point_sources_flux_over_its_area() {
    let mut scene = Scene::default();
    scene.up = Vec3::Y;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let room = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(6.0, 3.0, 4.0), black));
    scene.add_instance("Room", room, Mat4::IDENTITY);
    let desk = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(1.0, 0.8, 1.0),
            Vec3::new(1.0, 0.8, 2.0),
            Vec3::new(2.0, 0.8, 2.0),
            Vec3::new(2.0, 0.8, 1.0),
        ],
        black,
    ));
    scene.add_instance("Desk", desk, Mat4::IDENTITY);
    let task = scene.surface("Desk").unwrap();
    scene.make_calculation_surface(task);
    let source = Vec3::new(2.2, 2.0, 1.7);
    let intensity = 100.0;
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Lamp".into(),
        kind: LightKind::Point {
            position: source,
            intensity: Vec3::splat(intensity as f32),
        },
    });
    let areas = scene
        .add_task_areas(Path::new("room.gltf"), task, &AreaKind::ALL)
        .expect("a horizontal desk in a closed room");
    assert_eq!(areas.len(), 7);
    let accel = Accel::with_movable(&scene, &[]);
    let settings = MapSettings {
        spacing: GridSpacing::Auto,
        side: invlight_photon::Side::Front,
        trace: TraceSettings {
            photons: 400_000,
            seed: 3,
            ..TraceSettings::default()
        },
        estimator: Estimator::Connected,
        values: GridValues::CellMeans,
    };
    let targets: Vec<MapTarget> = areas
        .iter()
        .map(|a| MapTarget {
            surface: a.surface,
            spacing: GridSpacing::Auto,
            side: invlight_photon::Side::Front,
        })
        .collect();
    let maps =
        illuminance_maps_across(&scene, &accel, &targets, &settings, None, cluster()).unwrap();
    for (a, map) in areas.iter().zip(&maps) {
        let i = scene.surfaces[a.surface].instances.clone();
        let omega: f64 = i
            .iter()
            .flat_map(|&i| scene.world_triangles(i))
            .map(|t| solid_angle(source, t.corners))
            .sum();
        let want = intensity * omega / f64::from(scene.surface_area(a.surface));
        let got = map.mean;
        let tolerance = 4.0 * got.std_error + 1e-3 * want;
        assert!(
            (got.mean - want).abs() <= tolerance,
            "{} ({:?}): {} ± {} lx, closed form {want} lx",
            a.name,
            a.kind,
            got.mean,
            got.std_error
        );
        assert!(got.std_error < 0.02 * want, "{}: too noisy to tell", a.name);
    }
    // The bands lie in the task's plane, below the source: the surrounding, nearer,
    // is brighter on average than the background.
    let mean = |k: AreaKind| {
        let i = areas.iter().position(|a| a.kind == k).unwrap();
        maps[i].mean.mean
    };
    assert!(mean(AreaKind::Surrounding) > mean(AreaKind::Background));
}
