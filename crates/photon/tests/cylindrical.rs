//! The cylindrical illuminance a `<task>` asks (`Scene::add_cylindrical_area`: small
//! vertical prisms at the points of EN 12464-1's grid, facing out) measured by photons
//! against its closed form: a point source of I cd lights a vertical face of normal n at
//! y with I·max(0, n·(s − y))/|s − y|³, integrated over every face; and that mean against
//! the cylinder's own Ez = I·sin θ/(π r²) at each point, θ from the vertical.

mod common;

use common::{Z, point};
use invlight_photon::{Estimator, Side, TraceSettings, measure};
use invlight_scene::{CYLINDER_SIDES, Mat4, Material, Mesh, Scene, SurfaceId, Vec3};
use invlight_trace::Accel;
use std::f64::consts::PI;
use std::path::Path;

const LAMP: Vec3 = Vec3::new(3.0, 2.9, 2.0);
const CANDELA: f32 = 100.0;

/// A closed black 6 m × 3 m × 4 m room (Y up), a black floor, a 1 m × 1 m desk area at
/// 0.8 m as a calculation surface, a 100 cd lamp under the ceiling: all the light is
/// direct. Returns the scene and the cylindrical illuminance's surface at 1.2 m.
fn black_office() -> (Scene, SurfaceId) {
    let mut s = Scene::default();
    let black = s.add_material(Material::diffuse("Black", Vec3::ZERO));
    let room = s.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(6.0, 3.0, 4.0), black));
    s.add_instance("Room", room, Mat4::IDENTITY);
    let quad = |y: f32, (x0, x1, z0, z1): (f32, f32, f32, f32)| {
        Mesh::quad(
            [
                Vec3::new(x0, y, z0),
                Vec3::new(x0, y, z1),
                Vec3::new(x1, y, z1),
                Vec3::new(x1, y, z0),
            ],
            black,
        )
    };
    let floor = s.add_mesh(quad(0.0, (0.0, 6.0, 0.0, 4.0)));
    s.add_instance("Floor", floor, Mat4::IDENTITY);
    let desk = s.add_mesh(quad(0.8, (2.0, 3.0, 1.5, 2.5)));
    s.add_instance("Desk", desk, Mat4::IDENTITY);
    let desk = s.surface("Desk").unwrap();
    s.make_calculation_surface(desk);
    s.lights.push(point("Lamp", LAMP, CANDELA));
    let area = s
        .add_cylindrical_area(Path::new("office.gltf"), desk, 1.2)
        .unwrap();
    (s, area.surface)
}

/// The triangles of `surface`, each with its area and the midpoints of its n² equal
/// sub-triangles (the midpoint rule).
fn quadrature(scene: &Scene, surface: SurfaceId, n: u32) -> Vec<(f64, Vec3, Vec<Vec3>)> {
    let mut out = Vec::new();
    for &i in &scene.surfaces[surface].instances {
        for t in scene.world_triangles(i) {
            let [a, b, c] = t.corners;
            let (e1, e2) = (b - a, c - a);
            let normal = e1.cross(e2);
            let mut points = Vec::new();
            let k = n as f32;
            for i in 0..n {
                for j in 0..n - i {
                    let (u, v) = (i as f32, j as f32);
                    points.push(a + e1 * (u + 1.0 / 3.0) / k + e2 * (v + 1.0 / 3.0) / k);
                    if i + j + 1 < n {
                        points.push(a + e1 * (u + 2.0 / 3.0) / k + e2 * (v + 2.0 / 3.0) / k);
                    }
                }
            }
            out.push((0.5 * f64::from(normal.length()), normal.normalize(), points));
        }
    }
    out
}

/// The exact mean illuminance on the faces' fronts from the lamp alone.
fn exact_mean(scene: &Scene, surface: SurfaceId) -> f64 {
    let (mut flux, mut area) = (0.0, 0.0);
    for (a, n, points) in quadrature(scene, surface, 8) {
        let e: f64 = points
            .iter()
            .map(|&y| {
                let d = (LAMP - y).as_dvec3();
                f64::from(CANDELA) * n.as_dvec3().dot(d).max(0.0) / d.length().powi(3)
            })
            .sum::<f64>()
            / points.len() as f64;
        flux += e * a;
        area += a;
    }
    flux / area
}

#[test]
fn the_prisms_read_the_cylinders_ez_of_a_point_source() {
    let (scene, surface) = black_office();
    let exact = exact_mean(&scene, surface);
    // The prisms' mean is the mean of the points' Ez = I·sin θ/(π r²) but for the
    // prisms' size, which reads a lamp near by low (invlight_scene's cylindrical.rs):
    // 3.5 % here, most of it at the points nearest the lamp's nadir.
    let centres = quadrature(&scene, surface, 1)
        .chunks(2 * CYLINDER_SIDES)
        .map(|faces| {
            let all: Vec<Vec3> = faces.iter().flat_map(|f| f.2.iter().copied()).collect();
            all.iter().copied().sum::<Vec3>() / all.len() as f32
        })
        .collect::<Vec<_>>();
    let cylinder: f64 = centres
        .iter()
        .map(|&c| {
            let d = (LAMP - c).as_dvec3();
            let r = d.length();
            let sin = (d.x * d.x + d.z * d.z).sqrt() / r;
            f64::from(CANDELA) * sin / (PI * r * r)
        })
        .sum::<f64>()
        / centres.len() as f64;
    assert!(
        (-0.05..-0.02).contains(&(exact / cylinder - 1.0)),
        "prisms {exact} lx, cylinders {cylinder} lx"
    );
    // The photons, both ways of counting, within 4 σ of the exact mean.
    let accel = Accel::new(&scene);
    for estimator in [Estimator::ArrivalsOnly, Estimator::Connected] {
        let settings = TraceSettings {
            photons: 400_000,
            seed: 11,
            ..TraceSettings::default()
        };
        let m = measure(&scene, &accel, &[surface], &settings, estimator, None);
        let e = m.estimate_of(0, Side::Front, &[1.0]);
        let err = (e.mean - exact).abs();
        assert!(
            err < Z * e.std_error && e.std_error < 0.02 * exact,
            "{}: Ēz {} ± {} lx, exact {exact} lx",
            estimator.name(),
            e.mean,
            e.std_error
        );
    }
}
