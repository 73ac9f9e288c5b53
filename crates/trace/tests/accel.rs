//! The acceleration structure against brute force, on the trees of every build preset
//! (as obvhs's own tests run over its `BUILD_PARAM_SET`), and the geometric promises:
//! TLAS updates, holes, watertight shared edges, self-intersection-free spawned rays.

mod common;

use common::Rng;
use glam::{Mat4, Quat, Vec2, Vec3};
use invlight_scene::{InstanceId, Material, MaterialId, Mesh, MeshId, Scene};
use invlight_trace::{Accel, BuildPreset, Ray};

/// A scene of random triangles: 3 meshes of small ones, each placed twice with random
/// rotations, non-uniform scales (one mirrored) and translations, and a mesh placed as
/// it is of 100 small ones and 8 slivers across the whole scene (what the slow presets'
/// pre-splits cut into several boxes: they split triangles much larger than their
/// tree's mean).
fn random_scene(rng: &mut Rng) -> Scene {
    let mut scene = Scene::default();
    let mat = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    for m in 0..3 {
        let mut mesh = Mesh::default();
        let n = [1usize, 40, 300][m];
        for t in 0..n {
            let c = rng.in_box(Vec3::splat(-1.0), Vec3::splat(1.0));
            for _ in 0..3 {
                mesh.positions
                    .push(c + 0.3 * rng.in_box(Vec3::splat(-1.0), Vec3::splat(1.0)));
            }
            let b = 3 * t as u32;
            mesh.triangles.push([b, b + 1, b + 2]);
            mesh.materials.push(mat);
        }
        let id = scene.add_mesh(mesh);
        for k in 0..2 {
            let axis = rng.direction();
            let scale = Vec3::new(0.5 + rng.f32(), 0.5 + rng.f32(), 0.5 + rng.f32())
                * if m == 1 && k == 1 {
                    Vec3::new(-1.0, 1.0, 1.0)
                } else {
                    Vec3::ONE
                };
            let t = Mat4::from_scale_rotation_translation(
                scale,
                Quat::from_axis_angle(axis, 6.0 * rng.f32()),
                rng.in_box(Vec3::splat(-1.5), Vec3::splat(1.5)),
            );
            scene.add_instance(&format!("m{m}i{k}"), id, t);
        }
    }
    let mut mixed = Mesh::default();
    for t in 0..108u32 {
        let c = rng.in_box(Vec3::splat(-2.0), Vec3::splat(2.0));
        let corners = if t < 100 {
            [(); 3].map(|_| c + 0.3 * rng.in_box(Vec3::splat(-1.0), Vec3::splat(1.0)))
        } else {
            // A sliver 5 m long, whose box is mostly empty.
            let d = 2.5 * rng.direction();
            [c - d, c + d, c + 0.2 * rng.direction()]
        };
        mixed.positions.extend(corners);
        mixed.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
        mixed.materials.push(mat);
    }
    let id = scene.add_mesh(mixed);
    scene.add_instance("mixed", id, Mat4::IDENTITY);
    scene
}

/// All world-space hits of `ray`, in f64 (Möller–Trumbore): (t, instance, triangle,
/// smallest barycentric), sorted by t.
fn brute_force(scene: &Scene, ray: &Ray) -> Vec<(f64, InstanceId, u32, f64)> {
    let o = ray.origin.as_dvec3();
    let d = ray.dir.as_dvec3();
    let mut hits = Vec::new();
    for (i, inst) in scene.instances.iter().enumerate() {
        let mesh = &scene.meshes[inst.mesh];
        let m = inst.transform.as_dmat4();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|k| m.transform_point3(mesh.positions[k as usize].as_dvec3()));
            let (e1, e2) = (b - a, c - a);
            let p = d.cross(e2);
            let det = e1.dot(p);
            if det.abs() < 1e-300 {
                continue;
            }
            let s = o - a;
            let u = s.dot(p) / det;
            let q = s.cross(e1);
            let v = d.dot(q) / det;
            let dist = e2.dot(q) / det;
            let margin = u.min(v).min(1.0 - u - v);
            if margin >= -1e-9 && dist > 0.0 && dist < ray.t_max as f64 {
                hits.push((dist, InstanceId::from_index(i), t as u32, margin));
            }
        }
    }
    hits.sort_by(|x, y| x.0.total_cmp(&y.0));
    hits
}

/// Relative tolerance of f32 hit distances against the f64 reference: the hit of a
/// transformed ray carries a few ulps of the coordinates' magnitude (≤ 4 here).
const T_TOL: f64 = 1e-5;

fn random_ray(rng: &mut Rng, bounded: bool) -> Ray {
    let mut r = Ray::new(
        rng.in_box(Vec3::splat(-3.0), Vec3::splat(3.0)),
        rng.direction(),
    );
    if bounded {
        r.t_max = 4.0 * rng.f32();
    }
    r
}

/// Whether `preset` cuts large triangles' boxes, so that a triangle may sit in several
/// leaves and count more than once in [`invlight_trace::AccelStats::triangles`].
fn splits(preset: BuildPreset) -> bool {
    matches!(preset, BuildPreset::Slow | BuildPreset::VerySlow)
}

/// Compares `accel` (built with `preset`) with brute force on `n` random rays (half of
/// them bounded): the closest hit's instance, triangle and distance, the point its
/// barycentrics give, the any-hit answer, and `intersect_unless_blocked` blocked before
/// and beyond the closest hit.
fn check_against_brute_force(
    accel: &Accel,
    preset: BuildPreset,
    scene: &Scene,
    rng: &mut Rng,
    n: usize,
) {
    let (mut compared, mut hits) = (0, 0);
    for i in 0..n {
        let ray = random_ray(rng, i % 2 == 1);
        let reference = brute_force(scene, &ray);
        let got = accel.intersect(&ray);
        // Rays that graze an edge (reference margin within rounding) or hit two
        // surfaces at nearly the same distance may legitimately resolve either way.
        let ambiguous = reference.first().is_some_and(|f| {
            f.3 < 1e-5
                || reference
                    .get(1)
                    .is_some_and(|s| s.0 - f.0 < T_TOL * 10.0 * f.0)
        }) || reference
            .iter()
            .any(|h| h.3.abs() < 1e-5 || ray.t_max as f64 - h.0 < 1e-4);
        if ambiguous {
            continue;
        }
        compared += 1;
        assert_eq!(
            accel.occluded(&ray),
            !reference.is_empty(),
            "{preset:?}, ray {i}: {ray:?}"
        );
        match (got, reference.first()) {
            (None, None) => assert_eq!(accel.intersect_unless_blocked(&ray, ray.t_max), None),
            (Some(h), Some(&(t, inst, tri, _))) => {
                hits += 1;
                assert_eq!((h.instance, h.triangle), (inst, tri), "{preset:?}, ray {i}");
                // Blocked only beyond the closest hit: that hit, as `intersect` finds it.
                assert_eq!(
                    accel.intersect_unless_blocked(&ray, h.t * 0.5),
                    Some(h),
                    "{preset:?}, ray {i}"
                );
                // Blocked before the farthest hit: some hit before the block, one of
                // those brute force finds.
                let last = reference.last().expect("a hit").0;
                let far = (last + 2.0 * T_TOL * last.max(1.0)) as f32;
                let b = accel
                    .intersect_unless_blocked(&ray, far)
                    .expect("a blocking hit");
                assert!(
                    b.t < far
                        && reference
                            .iter()
                            .any(|r| (r.1, r.2) == (b.instance, b.triangle)
                                && (b.t as f64 - r.0).abs() <= T_TOL * r.0.max(1.0)),
                    "{preset:?}, ray {i}: {b:?} not among {reference:?}"
                );
                assert!(
                    (h.t as f64 - t).abs() <= T_TOL * t.max(1.0),
                    "{preset:?}, ray {i}: {} vs {t}",
                    h.t
                );
                // The barycentrics reproduce the hit point.
                let it = accel.interaction(scene, &ray, &h);
                let p = ray.at(h.t);
                assert!(
                    (it.point - p).length() < 1e-4,
                    "{preset:?}, ray {i}: {:?} vs {p:?}",
                    it.point
                );
            }
            (g, r) => panic!("{preset:?}, ray {i}: accel {g:?}, brute force {r:?}"),
        }
    }
    // Ambiguous rays are rare (~1 %), and about an eighth of the rays hit.
    assert!(
        compared * 100 > n * 97,
        "{preset:?}: {compared} rays compared"
    );
    assert!(hits * 10 > n, "{preset:?}: {hits} hits compared");
}

#[test]
fn closest_and_any_hit_match_brute_force() {
    for preset in BuildPreset::ALL {
        let mut rng = Rng::new(7);
        let scene = random_scene(&mut rng);
        let accel = Accel::with_preset(&scene, None, preset);
        assert_eq!(accel.stats().instances, 7);
        let triangles = accel.stats().triangles;
        if splits(preset) {
            assert!(triangles > 449, "{preset:?} split no triangle: {triangles}");
        } else {
            assert_eq!(triangles, 449, "{preset:?}");
        }
        check_against_brute_force(&accel, preset, &scene, &mut rng, 3000);
    }
    // The default constructor builds the default preset's tree.
    let scene = random_scene(&mut Rng::new(7));
    let medium = Accel::with_preset(&scene, None, BuildPreset::default());
    assert_eq!(
        Accel::new(&scene).stats().blas_nodes,
        medium.stats().blas_nodes
    );
}

#[test]
fn merged_static_instances_match_brute_force_and_move() {
    for preset in BuildPreset::ALL {
        let mut rng = Rng::new(8);
        let mut scene = random_scene(&mut rng);
        // Instances 1 and 4 separate, the other five baked into one tree.
        let movable = [1, 4].map(InstanceId::from_index);
        let mut accel = Accel::with_preset(&scene, Some(&movable), preset);
        assert_eq!(accel.stats().instances, 3);
        check_against_brute_force(&accel, preset, &scene, &mut rng, 1000);

        // Moving a movable instance rebuilds the top level only.
        let nodes = accel.stats().blas_nodes;
        scene.instances[4].transform =
            Mat4::from_translation(Vec3::new(0.3, -0.2, 0.5)) * scene.instances[4].transform;
        accel.update_instances(&scene);
        assert_eq!(accel.stats().blas_nodes, nodes);
        check_against_brute_force(&accel, preset, &scene, &mut rng, 1000);

        // Moving a baked one is still traced right (by a full rebuild, with the same
        // preset).
        scene.instances[0].transform = Mat4::from_rotation_z(1.0) * scene.instances[0].transform;
        accel.update_instances(&scene);
        check_against_brute_force(&accel, preset, &scene, &mut rng, 1000);
    }
}

/// One movable instance (the search's usual case: the merged tree of the static rest,
/// then that instance alone, without a top-level node) and none (the merged tree
/// alone), moved and not, on every preset.
#[test]
fn one_or_no_movable_instance_matches_brute_force() {
    for preset in BuildPreset::ALL {
        for movable in [&[3][..], &[]] {
            let mut rng = Rng::new(11);
            let mut scene = random_scene(&mut rng);
            let movable: Vec<InstanceId> =
                movable.iter().map(|&i| InstanceId::from_index(i)).collect();
            let mut accel = Accel::with_preset(&scene, Some(&movable), preset);
            assert_eq!(accel.stats().instances, 1 + movable.len());
            check_against_brute_force(&accel, preset, &scene, &mut rng, 1500);
            scene.instances[3].transform = Mat4::from_rotation_translation(
                Quat::from_rotation_y(0.4),
                Vec3::new(-0.2, 0.3, 0.1),
            ) * scene.instances[3].transform;
            accel.update_instances(&scene);
            check_against_brute_force(&accel, preset, &scene, &mut rng, 1500);
        }
    }
}

fn quad_scene(corners: [Vec3; 4], transform: Mat4) -> Scene {
    let mut scene = Scene::default();
    let mat = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mesh = scene.add_mesh(Mesh::quad(corners, mat));
    scene.add_instance("Quad", mesh, transform);
    scene
}

#[test]
fn moving_an_instance_rebuilds_the_top_level_only() {
    let unit = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    let mut scene = quad_scene(unit, Mat4::IDENTITY);
    let mut accel = Accel::new(&scene);
    let blas_nodes = accel.stats().blas_nodes;
    let down = |x: f32| Ray::new(Vec3::new(x, 0.5, 5.0), Vec3::NEG_Z);
    assert!(accel.intersect(&down(0.5)).is_some());
    assert!(accel.intersect(&down(10.5)).is_none());

    scene.instances[0].transform = Mat4::from_translation(Vec3::new(10.0, 0.0, 1.0));
    accel.update_instances(&scene);
    assert!(
        accel.intersect(&down(0.5)).is_none(),
        "old position must be empty"
    );
    let hit = accel.intersect(&down(10.5)).expect("new position hit");
    assert!((hit.t - 4.0).abs() < 1e-6);
    assert_eq!(accel.stats().blas_nodes, blas_nodes);
}

/// A 10 × 10 roof at z = 3 with a 1 × 1 hole rectangle lying in its plane.
fn roof_with_hole(hole_at: Vec3) -> Scene {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let hole = scene.add_material(Material::hole("Hole"));
    let roof = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(-5.0, -5.0, 0.0),
            Vec3::new(5.0, -5.0, 0.0),
            Vec3::new(5.0, 5.0, 0.0),
            Vec3::new(-5.0, 5.0, 0.0),
        ],
        grey,
    ));
    scene.add_instance(
        "Roof",
        roof,
        Mat4::from_translation(Vec3::new(0.0, 0.0, 3.0)),
    );
    let rect = scene.add_mesh(Mesh::quad(
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        hole,
    ));
    scene.add_instance("Hole", rect, Mat4::from_translation(hole_at));
    scene
}

#[test]
fn rays_pass_through_holes_and_holes_move() {
    let mut scene = roof_with_hole(Vec3::new(0.0, 0.0, 3.0));
    let mut accel = Accel::new(&scene);
    assert_eq!(accel.stats().holes, 1);
    assert_eq!(accel.stats().instances, 1, "the hole itself is not traced");
    let up = |x: f32, y: f32| Ray::new(Vec3::new(x, y, 0.0), Vec3::Z);
    assert!(accel.intersect(&up(0.5, 0.5)).is_none(), "through the hole");
    assert!(!accel.occluded(&up(0.5, 0.5)));
    // Slanted rays through the hole, from both sides.
    let slanted = Ray::new(
        Vec3::new(-2.5, 0.5, 0.0),
        Vec3::new(1.0, 0.0, 1.0).normalize(),
    );
    assert!(accel.intersect(&slanted).is_none());
    let from_above = Ray::new(Vec3::new(0.2, 0.7, 6.0), Vec3::NEG_Z);
    assert!(accel.intersect(&from_above).is_none());
    for (x, y) in [(1.5, 0.5), (-0.5, 0.5), (0.5, 1.2), (4.0, -4.0)] {
        let hit = accel.intersect(&up(x, y)).expect("roof outside the hole");
        assert!((hit.t - 3.0).abs() < 1e-6);
        assert!(accel.occluded(&up(x, y)));
    }

    scene.instances[1].transform = Mat4::from_translation(Vec3::new(2.0, 2.0, 3.0));
    accel.update_instances(&scene);
    assert!(accel.intersect(&up(0.5, 0.5)).is_some(), "old hole closed");
    assert!(accel.intersect(&up(2.5, 2.5)).is_none(), "new hole open");

    // With the roof baked into the static tree, the hole still moves by a top-level
    // update alone.
    let mut merged = Accel::with_movable(&scene, &[]);
    let nodes = merged.stats().blas_nodes;
    assert!(merged.intersect(&up(2.5, 2.5)).is_none());
    scene.instances[1].transform = Mat4::from_translation(Vec3::new(-3.0, 1.0, 3.0));
    merged.update_instances(&scene);
    assert_eq!(merged.stats().blas_nodes, nodes);
    assert!(merged.intersect(&up(2.5, 2.5)).is_some());
    assert!(merged.intersect(&up(-2.5, 1.5)).is_none());
}

#[test]
fn a_ray_through_a_shared_edge_hits_one_of_its_triangles() {
    // The diagonal 0–2 of the quad is shared by its two triangles. Aim rays at points
    // exactly on it, from many directions, on a plain and a far-off rotated instance.
    let corners = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    let mut rng = Rng::new(11);
    for transform in [
        Mat4::IDENTITY,
        Mat4::from_scale_rotation_translation(
            Vec3::splat(3.7),
            Quat::from_rotation_y(0.3) * Quat::from_rotation_x(1.1),
            Vec3::new(1.0e3, -2.0e3, 5.0e2),
        ),
    ] {
        let scene = quad_scene(corners, transform);
        let accel = Accel::new(&scene);
        for _ in 0..5000 {
            let s = rng.f32();
            let target = transform.transform_point3(Vec3::new(s, s, 0.0));
            let mut d = rng.direction();
            let normal = transform.transform_vector3(Vec3::Z).normalize();
            if d.dot(normal).abs() < 0.05 {
                continue;
            }
            if d.dot(normal) > 0.0 {
                d = -d;
            }
            let origin = target - d * (1.0 + 10.0 * rng.f32());
            let ray = Ray::new(origin, d);
            assert!(
                accel.intersect(&ray).is_some(),
                "leak at s = {s}, dir {d:?}"
            );
        }
    }
}

#[test]
fn a_ray_through_a_shared_vertex_hits_one_of_its_triangles() {
    // A fan of 7 triangles around the origin; rays through the shared centre vertex.
    let mut scene = Scene::default();
    let mat = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mut fan = Mesh::default();
    fan.positions.push(Vec3::ZERO);
    for k in 0..7 {
        let a = std::f32::consts::TAU * k as f32 / 7.0 + 0.1;
        fan.positions.push(Vec3::new(a.cos(), a.sin(), 0.0));
        fan.triangles.push([0, 1 + k, 1 + (k + 1) % 7]);
        fan.materials.push(mat);
    }
    let id = scene.add_mesh(fan);
    scene.add_instance("Fan", id, Mat4::from_translation(Vec3::new(3.0, -2.0, 1.0)));
    let accel = Accel::new(&scene);
    let centre = Vec3::new(3.0, -2.0, 1.0);
    let mut rng = Rng::new(5);
    for _ in 0..2000 {
        let d = rng.direction();
        if d.z.abs() < 0.05 {
            continue;
        }
        let ray = Ray::new(centre - d * 2.0, d);
        assert!(
            accel.intersect(&ray).is_some(),
            "leak through the centre along {d:?}"
        );
    }
}

#[test]
fn spawned_rays_never_hit_their_own_surface() {
    // A large, far-off, rotated and scaled box: every ray spawned inward from a point on
    // it must hit another face (no self-hit), and every ray spawned outward must escape.
    // A point within rounding of an edge may lie a hair outside the neighbouring face,
    // so an inward ray may leave there: such leaks must start within rounding of an
    // edge. (With an offset 32 times smaller than `OFFSET_SCALE` this still passes; at
    // 2⁻²⁴ it fails.)
    let mut scene = Scene::default();
    let mat = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let cube = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::ONE, mat));
    let scale = Vec3::new(37.0, 5.0, 80.0);
    let transform = Mat4::from_scale_rotation_translation(
        scale,
        Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.7),
        Vec3::new(2.0e4, -1.5e4, 3.0e4),
    );
    scene.add_instance("Cube", cube, transform);
    let accel = Accel::new(&scene);
    let centre = transform.transform_point3(Vec3::splat(0.5));
    // Rounding of world points here: one ulp of the largest coordinate.
    let ulp = 3.0e4f32.next_up() - 3.0e4;
    let to_object = transform.as_dmat4().inverse();
    let mut rng = Rng::new(3);
    let mut surface: Option<invlight_trace::Interaction> = None;
    let mut leaks = 0;
    for i in 0..20000 {
        let ray = match surface {
            Some(ref it) => {
                let mut d = rng.direction();
                if d.dot(it.normal) < 0.0 {
                    d = -d;
                }
                assert!(
                    accel.intersect(&it.spawn(d)).is_none(),
                    "self-hit going out at {i}"
                );
                it.spawn(-d)
            }
            None => Ray::new(centre, rng.direction()),
        };
        let Some(hit) = accel.intersect(&ray) else {
            let prev = surface.expect("the first ray starts at the centre");
            // Distance of the departure point from the nearest edge: the second
            // smallest distance to a face plane.
            let c = to_object.transform_point3(prev.point.as_dvec3());
            let mut d: Vec<f64> = (0..3)
                .map(|k| c[k].min(1.0 - c[k]).abs() * scale[k] as f64)
                .collect();
            d.sort_by(f64::total_cmp);
            assert!(
                d[1] < 4.0 * ulp as f64,
                "leak at {i} from {d:?}, not at an edge"
            );
            leaks += 1;
            surface = None;
            continue;
        };
        let it = accel.interaction(&scene, &ray, &hit);
        if let Some(prev) = surface {
            // Another face: the normals differ (faces of a box are not coplanar).
            assert!(it.normal.dot(prev.normal) < 0.99, "self-hit at {i}");
        }
        surface = Some(it);
    }
    // Each leak was checked to start at an edge; a handful at most in 20 000 bounces.
    assert!(leaks * 1000 < 20000, "{leaks} leaks");
}

#[test]
fn interaction_reports_front_normal_material_and_uv() {
    let mut scene = Scene::default();
    let _grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let red = scene.add_material(Material::diffuse("Red", Vec3::new(0.8, 0.1, 0.1)));
    let mut mesh = Mesh::quad(
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        red,
    );
    mesh.uvs = vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    let id = scene.add_mesh(mesh);
    // Rotated so that its front (+z in object space) faces +x in the world.
    let t = Mat4::from_translation(Vec3::new(2.0, 0.0, 0.0))
        * Mat4::from_rotation_y(std::f32::consts::FRAC_PI_2);
    scene.add_instance("Card", id, t);
    let accel = Accel::new(&scene);
    // Hit from behind: the normal still names the front.
    let ray = Ray::new(Vec3::new(0.0, 0.25, -0.75), Vec3::X);
    let hit = accel.intersect(&ray).unwrap();
    let it = accel.interaction(&scene, &ray, &hit);
    assert!((it.normal - Vec3::X).length() < 1e-6, "{:?}", it.normal);
    assert_eq!(it.material, red);
    let object = t.inverse().transform_point3(it.point);
    assert!(
        (it.uv - Vec2::new(object.x, object.y)).length() < 1e-5,
        "{:?} at {object:?}",
        it.uv
    );
    assert!((it.point - Vec3::new(2.0, 0.25, -0.75)).length() < 1e-5);
    // The shadow ray from the surface to a point behind it is free; to a point past a
    // second card is blocked.
    assert!(!accel.occluded(&it.spawn_to(Vec3::new(5.0, 0.25, -0.75))));
}

#[test]
fn degenerate_input_does_not_panic() {
    let empty = Accel::new(&Scene::default());
    assert!(empty.intersect(&Ray::new(Vec3::ZERO, Vec3::X)).is_none());
    let mut scene = quad_scene(
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        Mat4::ZERO,
    );
    scene.meshes[0].triangles.push([0, 1, 99]);
    scene.meshes[0].materials.push(MaterialId::from_index(0));
    let accel = Accel::new(&scene);
    assert_eq!(accel.stats().instances, 0, "a zero transform is not traced");
    let nan = Ray::new(Vec3::NAN, Vec3::X);
    assert!(accel.intersect(&nan).is_none());
    let axis = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::Z);
    assert!(
        Accel::new(&quad_scene(
            [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            Mat4::IDENTITY
        ))
        .intersect(&axis)
        .is_some()
    );
}

#[test]
fn accel_is_shared_across_threads() {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<Accel>();
}

#[test]
fn closest_hit_is_the_nearer_of_stacked_planes() {
    // Ten parallel instances of one quad; the closest from each side.
    let mut scene = Scene::default();
    let mat = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let q = scene.add_mesh(Mesh::quad(
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        mat,
    ));
    for k in 0..10 {
        scene.add_instance(
            &format!("q{k}"),
            q,
            Mat4::from_translation(Vec3::new(0.0, 0.0, k as f32)),
        );
    }
    let accel = Accel::new(&scene);
    let up = Ray::new(Vec3::new(0.3, 0.6, 2.5), Vec3::Z);
    let h = accel.intersect(&up).unwrap();
    assert_eq!(h.instance, InstanceId::from_index(3));
    assert!((h.t - 0.5).abs() < 1e-6);
    let down = Ray::new(Vec3::new(0.3, 0.6, 2.5), Vec3::NEG_Z);
    assert_eq!(
        accel.intersect(&down).unwrap().instance,
        InstanceId::from_index(2)
    );
    let short = Ray { t_max: 0.4, ..up };
    assert!(!accel.occluded(&short) && accel.intersect(&short).is_none());
}

#[test]
fn zero_direction_components_of_either_sign() {
    // `-Vec3::Z` is (−0, −0, −1): a −0 component has the inverse −∞, and the slab test
    // must treat it as negative. Every sign combination of the zero components, on a
    // few origins over a quad and over an instanced copy moved aside.
    let mut scene = quad_scene(
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        Mat4::IDENTITY,
    );
    scene.add_instance(
        "Copy",
        MeshId::from_index(0),
        Mat4::from_translation(Vec3::new(3.0, 0.0, 0.0)),
    );
    let accel = Accel::new(&scene);
    for (sx, sy) in [(0.0f32, 0.0f32), (-0.0, 0.0), (0.0, -0.0), (-0.0, -0.0)] {
        for (x, y) in [(0.5, 0.5), (0.1, 0.9), (3.5, 0.25), (3.99, 0.01)] {
            let down = Ray::new(Vec3::new(x, y, 2.0), Vec3::new(sx, sy, -1.0));
            let hit = accel
                .intersect(&down)
                .unwrap_or_else(|| panic!("missed {down:?}"));
            assert!((hit.t - 2.0).abs() < 1e-6);
            let up = Ray::new(Vec3::new(x, y, -2.0), Vec3::new(sx, sy, 1.0));
            assert!(accel.occluded(&up), "{up:?}");
        }
        let beside = Ray::new(Vec3::new(2.0, 0.5, 2.0), Vec3::new(sx, sy, -1.0));
        assert!(accel.intersect(&beside).is_none());
    }
}

/// The front of a mirrored instance is the counter-clockwise side in world space, the
/// side its emission leaves from (regression: the inverse transpose alone flipped it).
#[test]
fn mirrored_instance_front_is_the_world_winding() {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let corners = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let quad = scene.add_mesh(Mesh::quad(corners, grey));
    let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    scene.add_instance("Mirrored", quad, mirror);
    let [a, b, c] = [corners[0], corners[1], corners[2]].map(|p| mirror.transform_point3(p));
    let front = (b - a).cross(c - a).normalize();
    for accel in [Accel::new(&scene), Accel::with_movable(&scene, &[])] {
        let ray = Ray::new(Vec3::new(-0.3, 0.4, 2.0), -Vec3::Z);
        let hit = accel.intersect(&ray).expect("the quad is below");
        let at = accel.interaction(&scene, &ray, &hit);
        assert!(
            (at.normal - front).length() < 1e-6,
            "{} vs {front}",
            at.normal
        );
    }
}

/// 64 different triangles sharing one bounding box (each spans the box's
/// diagonal) and 200 copies of one triangle are built as groups apart from PLOC
/// (`COINCIDENT_GROUP`); with the random scene around them, every ray still finds what
/// brute force finds.
#[test]
fn boxes_shared_by_many_triangles_match_brute_force() {
    let mut rng = Rng::new(19);
    let mut scene = random_scene(&mut rng);
    let mat = MaterialId::from_index(scene.materials.len() - 1);
    let mut mesh = Mesh::default();
    for t in 0..64u32 {
        let inner = rng.in_box(Vec3::splat(-0.5), Vec3::splat(0.5));
        mesh.positions
            .extend([Vec3::splat(-0.5), Vec3::splat(0.5), inner]);
        mesh.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
        mesh.materials.push(mat);
    }
    let id = scene.add_mesh(mesh);
    scene.add_instance(
        "same box",
        id,
        Mat4::from_translation(Vec3::new(0.5, 0.0, 0.0)),
    );
    for preset in BuildPreset::ALL {
        let accel = Accel::with_preset(&scene, None, preset);
        check_against_brute_force(&accel, preset, &scene, &mut rng, 4000);
        let merged = Accel::with_preset(&scene, Some(&[]), preset);
        check_against_brute_force(&merged, preset, &scene, &mut rng, 2000);
    }

    let mut copies = Mesh::default();
    for t in 0..200u32 {
        copies.positions.extend([
            Vec3::new(-1.0, -1.0, 2.0),
            Vec3::new(1.0, -1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
        ]);
        copies.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
        copies.materials.push(mat);
    }
    let id = scene.add_mesh(copies);
    scene.add_instance("copies", id, Mat4::IDENTITY);
    for preset in BuildPreset::ALL {
        let accel = Accel::with_preset(&scene, None, preset);
        if !splits(preset) {
            assert_eq!(accel.stats().triangles, 1 + 40 + 300 + 108 + 64 + 200);
        }
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z);
        let hit = accel.intersect(&ray).unwrap();
        assert_eq!(
            hit.instance,
            InstanceId::from_index(scene.instances.len() - 1),
            "{preset:?}"
        );
        assert!((hit.t - 3.0).abs() < 1e-6, "{preset:?}: {}", hit.t);
    }
}
