//! Hostile and huge inputs: [`Accel`] never panics on what a [`Scene`]
//! holds, builds tens of thousands of coincident triangles in time proportional to
//! their number, and keeps instances instanced where flattening them would not fit.

use glam::{Mat4, Vec3};
use invlight_scene::{InstanceId, MAX_COORDINATE, Material, Mesh, Scene};
use invlight_trace::{Accel, Ray};
use std::time::Instant;

/// One triangle in the xz-plane near the origin, to aim rays at.
fn floor_triangle() -> [Vec3; 3] {
    [
        Vec3::ZERO,
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    ]
}

fn scene_of(triangles: &[[Vec3; 3]], transforms: &[Mat4]) -> Scene {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mut mesh = Mesh::default();
    for (t, tri) in triangles.iter().enumerate() {
        mesh.positions.extend(tri);
        let b = 3 * t as u32;
        mesh.triangles.push([b, b + 1, b + 2]);
        mesh.materials.push(grey);
    }
    let id = scene.add_mesh(mesh);
    for (i, &m) in transforms.iter().enumerate() {
        scene.add_instance(&format!("part{i}"), id, m);
    }
    scene
}

fn down_at(x: f32, z: f32) -> Ray {
    Ray::new(Vec3::new(x, 1.0, z), Vec3::NEG_Y)
}

/// Coordinates obvhs could not take (it indexed out of bounds building boxes
/// whose areas overflow) in a scene that skipped `Scene::validate`: the structure
/// builds, those triangles are not traced, the others are.
#[test]
fn huge_coordinates_do_not_panic() {
    let huge = [
        [
            Vec3::ZERO,
            Vec3::new(1e20, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1e20),
        ],
        [Vec3::splat(3.4e38), Vec3::splat(-3.4e38), Vec3::ZERO],
        [Vec3::splat(f32::NAN), Vec3::ONE, Vec3::ZERO],
    ];
    for bad in huge {
        let scene = scene_of(&[floor_triangle(), bad], &[Mat4::IDENTITY]);
        assert!(scene.validate().is_err());
        for accel in [Accel::new(&scene), Accel::with_movable(&scene, &[])] {
            assert_eq!(accel.stats().triangles, 1);
            assert!(accel.intersect(&down_at(0.2, 0.2)).is_some());
        }
    }
    let first = InstanceId::from_index(0);
    for m in [
        Mat4::from_translation(Vec3::new(3e38, 0.0, 0.0)),
        Mat4::from_scale(Vec3::splat(3.4e38)),
        Mat4::from_scale(Vec3::splat(1e30)),
    ] {
        let scene = scene_of(&[floor_triangle()], &[Mat4::IDENTITY, m]);
        assert!(scene.validate().is_err());
        let accel = Accel::new(&scene);
        assert_eq!(accel.intersect(&down_at(0.2, 0.2)).unwrap().instance, first);
        let merged = Accel::with_movable(&scene, &[]);
        assert_eq!(
            merged.intersect(&down_at(0.2, 0.2)).unwrap().instance,
            first
        );
    }
    // Just inside the range builds and traces.
    let m = MAX_COORDINATE;
    let edge = [
        Vec3::new(-m, 0.0, -m),
        Vec3::new(m, 0.0, -m),
        Vec3::new(0.0, 0.0, m),
    ];
    let scene = scene_of(&[edge], &[Mat4::IDENTITY]);
    assert_eq!(scene.validate(), Ok(()));
    assert!(Accel::new(&scene).intersect(&down_at(0.0, 0.0)).is_some());
}

/// 30 000 copies of one triangle took 38 s to build (2 000: 0.28 s), PLOC
/// merging about one pair of equal boxes per pass; now a few hundredths of a second
/// (BENCHMARKS.md). The bound leaves room for a debug build and a busy machine.
#[test]
fn coincident_triangles_build_in_linear_time() {
    let scene = scene_of(&vec![floor_triangle(); 30_000], &[Mat4::IDENTITY]);
    let start = Instant::now();
    let accel = Accel::new(&scene);
    let seconds = start.elapsed().as_secs_f64();
    assert!(seconds < 5.0, "{seconds} s");
    assert_eq!(accel.stats().triangles, 30_000);
    let hit = accel.intersect(&down_at(0.2, 0.2)).unwrap();
    assert!((hit.t - 1.0).abs() < 1e-6);
    assert!(accel.intersect(&down_at(0.8, 0.8)).is_none());
    // 30 000 instances at one place: the top level has the same trouble.
    let scene = scene_of(&[floor_triangle()], &vec![Mat4::IDENTITY; 30_000]);
    let start = Instant::now();
    let accel = Accel::new(&scene);
    assert!(start.elapsed().as_secs_f64() < 5.0, "{:?}", start.elapsed());
    assert!(accel.intersect(&down_at(0.2, 0.2)).is_some());
}

/// 50 000 nodes placing one 2 108-triangle mesh flatten to 105 M triangles,
/// which aborted on an allocation in `Accel::with_movable`; they now stay instanced,
/// while a scene whose flattening is small is still baked into one tree.
#[test]
fn many_instances_stay_instanced() {
    let tris: Vec<[Vec3; 3]> = (0..2108)
        .map(|t| {
            let x = (t % 62) as f32 / 62.0;
            let z = (t / 62) as f32 / 34.0;
            [
                Vec3::new(x, 0.0, z),
                Vec3::new(x + 0.016, 0.0, z),
                Vec3::new(x, 0.0, z + 0.029),
            ]
        })
        .collect();
    let places: Vec<Mat4> = (0..50_000)
        .map(|i| {
            Mat4::from_translation(Vec3::new(
                (i % 250) as f32 * 2.0,
                0.0,
                (i / 250) as f32 * 2.0,
            ))
        })
        .collect();
    let scene = scene_of(&tris, &places);
    let estimate = Accel::estimated_bytes(&scene);
    assert!(estimate < 200 << 20, "{estimate} bytes");
    let accel = Accel::with_movable(&scene, &[]);
    assert_eq!(accel.stats().triangles, 2108);
    assert_eq!(accel.stats().instances, 50_000);
    let hit = accel
        .intersect(&down_at(2.0 * 7.0 + 0.1, 2.0 * 3.0 + 0.01))
        .unwrap();
    assert_eq!(hit.instance, InstanceId::from_index(3 * 250 + 7));
    // Few instances: baked, one entry.
    let scene = scene_of(&tris, &places[..10]);
    let baked = Accel::with_movable(&scene, &[]);
    assert_eq!(baked.stats().triangles, 21_080);
    assert_eq!(baked.stats().instances, 1);
    assert!(Accel::estimated_bytes(&scene) >= 21_080 * invlight_trace::BUILD_BYTES_PER_TRIANGLE);
}
