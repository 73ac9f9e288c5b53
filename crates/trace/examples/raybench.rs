//! Random-ray throughput of [`Accel`] on a scene file or the Cornell box, with obvhs's own
//! flat traversal as the yardstick. OBJ files are read by a minimal reader here
//! (positions and faces, an instance per group); other formats by the scene crate.
//!
//! ```text
//! unzip -o /work/shared/scenes/sponza/sponza.zip -d /tmp/scenes
//! cargo run --release -p invlight-trace --example raybench -- /tmp/scenes/sponza.obj
//! cargo run --release -p invlight-trace --example raybench -- cornell
//! cargo run --release -p invlight-trace --example raybench -- /work/shared/scenes/ilpsolver/cornell.dae
//! cargo run --release -p invlight-trace --example raybench -- /tmp/scenes/sponza.obj 1000000 --dump /tmp/rb
//! python3 benches/embree_raybench.py /tmp/rb
//! ```
//!
//! Rays start uniformly in the scene's bounding box with uniform directions (fixed seed).
//! Every figure of one run is measured on the same rays, so ratios between variants are
//! meaningful on a noisy shared machine even when absolute rates drift.
//!
//! "one instance movable" is what a search with one movable object builds
//! (`Accel::with_movable` with that instance): the instance `--movable NAME` names, or
//! else the one with the smallest box among those of at least 12 triangles, or of the
//! most any has (Sponza's relief plaque, the Cornell box's short block), as a placed
//! object is small beside the room.
//!
//! `--only TEXT` measures only the `Accel` variants whose label holds TEXT: for instruction
//! counts of one variant under callgrind, e.g.
//! `RAYON_NUM_THREADS=1 valgrind --tool=callgrind --toggle-collect='*intersect_avx2*'
//! target/release/examples/raybench /tmp/scenes/sponza.obj 200000 --only movable`
//! (6 calls per ray: 3 passes on one thread, 3 on the pool).
//!
//! `--dump DIR` writes the world-space triangles (`tris.f32`, 9 floats each), the rays
//! (`rays.f32`: origin and direction, 6 floats each) and `Accel`'s closest-hit distance
//! per ray (`t.f32`, +∞ for a miss), little-endian, for `benches/embree_raybench.py`,
//! which traces the same rays with Embree.

#[path = "../tests/common/mod.rs"]
mod common;

use common::Rng;
use glam::{Mat4, Vec3, Vec3A};
use invlight_scene::{InstanceId, Material, MaterialId, Mesh, Scene};
use invlight_trace::{Accel, Ray};
use obvhs::{
    BvhBuildParams, cwbvh::builder::build_cwbvh_from_tris, ray::RayHit, triangle::Triangle,
};
use rayon::prelude::*;
use std::time::{Duration, Instant};

const CORNELL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../tests/data/obj/cornell_box.obj"
);

/// Groups (`o`/`g`) of an OBJ file as triangle meshes: positions and fan-triangulated
/// faces only.
fn read_obj(path: &str) -> Result<Vec<(String, Mesh)>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut positions: Vec<Vec3> = Vec::new();
    let mut groups: Vec<(String, Mesh)> = vec![("default".into(), Mesh::default())];
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let bad = |what: &str| format!("{path}:{}: bad {what}", n + 1);
        match words.next() {
            Some("v") => {
                let c: Vec<f32> = words
                    .take(3)
                    .map(|w| w.parse().map_err(|_| bad("vertex")))
                    .collect::<Result<_, _>>()?;
                if c.len() != 3 {
                    return Err(bad("vertex"));
                }
                positions.push(Vec3::new(c[0], c[1], c[2]));
            }
            Some("o" | "g") => groups.push((words.collect::<Vec<_>>().join(" "), Mesh::default())),
            Some("f") => {
                let idx: Vec<u32> = words
                    .map(|w| {
                        let i: i64 = w
                            .split('/')
                            .next()
                            .unwrap_or("")
                            .parse()
                            .map_err(|_| bad("face"))?;
                        let i = if i < 0 {
                            positions.len() as i64 + i
                        } else {
                            i - 1
                        };
                        u32::try_from(i).map_err(|_| bad("face index"))
                    })
                    .collect::<Result<_, _>>()?;
                let mesh = &mut groups.last_mut().expect("a default group").1;
                for k in 1..idx.len().saturating_sub(1) {
                    mesh.triangles.push([idx[0], idx[k], idx[k + 1]]);
                    // The one material `scene_of` adds.
                    mesh.materials.push(MaterialId::from_index(0));
                }
            }
            _ => {}
        }
    }
    // Each group keeps only the vertices it uses.
    Ok(groups
        .into_iter()
        .filter(|(_, m)| !m.triangles.is_empty())
        .map(|(name, mut m)| {
            let mut map = std::collections::HashMap::new();
            for t in &mut m.triangles {
                for i in t.iter_mut() {
                    let next = map.len() as u32;
                    *i = *map.entry(*i).or_insert(next);
                }
            }
            let mut used = vec![Vec3::ZERO; map.len()];
            for (&old, &new) in &map {
                used[new as usize] = positions.get(old as usize).copied().unwrap_or(Vec3::ZERO);
            }
            m.positions = used;
            (name, m)
        })
        .collect())
}

/// The groups as one scene, one identity instance per group.
fn scene_of(groups: Vec<(String, Mesh)>) -> Scene {
    let mut scene = Scene::default();
    scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    for (name, m) in groups {
        let id = scene.add_mesh(m);
        scene.add_instance(&name, id, Mat4::IDENTITY);
    }
    scene
}

/// Every traced (non-hole) triangle of `scene` in world space, as one mesh and instance.
fn flatten(scene: &Scene) -> Scene {
    let mut flat = Scene::default();
    let grey = flat.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mut all = Mesh::default();
    for inst in &scene.instances {
        let mesh = &scene.meshes[inst.mesh];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let hole = mesh
                .materials
                .get(t)
                .and_then(|&m| scene.materials.get(m.index()))
                .is_some_and(|m| m.hole);
            if hole {
                continue;
            }
            let base = all.positions.len() as u32;
            for &i in tri {
                all.positions
                    .push(inst.transform.transform_point3(mesh.positions[i as usize]));
            }
            all.triangles.push([base, base + 1, base + 2]);
            all.materials.push(grey);
        }
    }
    let id = flat.add_mesh(all);
    flat.add_instance("all", id, Mat4::IDENTITY);
    flat
}

fn rays(scene: &Scene, n: usize) -> Vec<Ray> {
    let (lo, hi) = scene.bounds().expect("a non-empty scene");
    let mut rng = Rng::new(42);
    (0..n)
        .map(|_| Ray::new(rng.in_box(lo, hi), rng.direction()))
        .collect()
}

/// CPU time this thread has run, from the scheduler (ns): unlike wall time it does not
/// count the time other processes on this shared machine take the core away.
fn thread_cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0)
}

/// Rays per CPU-second of `f` on one thread (best of 3 passes), rays per wall-second on
/// the rayon pool (best of 3), and a checksum (hits) so nothing is optimised away.
fn rate<F: Fn(&Ray) -> bool + Sync>(rays: &[Ray], f: F) -> (f64, f64, usize) {
    let mut single = 0.0f64;
    let mut parallel = 0.0f64;
    let mut hits = 0;
    for _ in 0..3 {
        let (start, wall) = (thread_cpu_ns(), Instant::now());
        hits = rays.iter().filter(|r| f(r)).count();
        let ns = thread_cpu_ns() - start;
        let secs = if ns > 0 {
            ns as f64 * 1e-9
        } else {
            wall.elapsed().as_secs_f64()
        };
        single = single.max(rays.len() as f64 / secs);
        let start = Instant::now();
        let par_hits = rays
            .par_chunks(4096)
            .map(|c| c.iter().filter(|r| f(r)).count())
            .sum::<usize>();
        parallel = parallel.max(rays.len() as f64 / start.elapsed().as_secs_f64());
        assert_eq!(hits, par_hits);
    }
    (single, parallel, hits)
}

fn report(label: &str, (single, parallel, hits): (f64, f64, usize), base: f64, n: usize) {
    println!(
        "{label:<44} {:>6.2} M/s per core  {:>6.2} M/s wall on {} threads  ({:.2}× obvhs flat)  hits {:.1} %",
        single / 1e6,
        parallel / 1e6,
        rayon::current_num_threads(),
        single / base,
        100.0 * hits as f64 / n as f64
    );
}

/// `values` as little-endian `f32`s into `dir/name`.
fn dump(dir: &str, name: &str, values: impl Iterator<Item = f32>) -> Result<(), String> {
    let bytes: Vec<u8> = values.flat_map(f32::to_le_bytes).collect();
    let path = std::path::Path::new(dir).join(name);
    std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// The instance `name` names, or the one with the smallest world box among those of at
/// least 12 triangles (or as many as the largest has, when none has 12).
fn movable_of(scene: &Scene, name: Option<&str>) -> Result<usize, String> {
    if let Some(name) = name {
        return scene
            .instances
            .iter()
            .position(|i| i.name == name)
            .ok_or_else(|| format!("--movable: no instance named '{name}'"));
    }
    let diagonal = |i: &invlight_scene::Instance| {
        let mesh = &scene.meshes[i.mesh];
        let (lo, hi) = mesh.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| {
                let p = i.transform.transform_point3(p);
                (lo.min(p), hi.max(p))
            },
        );
        (hi - lo).length()
    };
    let triangles = |i: usize| scene.meshes[scene.instances[i].mesh].triangles.len();
    let least = (0..scene.instances.len())
        .map(triangles)
        .max()
        .unwrap_or(0)
        .min(12);
    (0..scene.instances.len())
        .filter(|&i| triangles(i) >= least.max(1))
        .min_by(|&a, &b| diagonal(&scene.instances[a]).total_cmp(&diagonal(&scene.instances[b])))
        .ok_or_else(|| "no instance of 12 triangles or more to move".into())
}

/// The command line: a scene (or `cornell`), a ray count and the flags of the module doc.
struct Options {
    path: String,
    rays: usize,
    dump: Option<String>,
    movable: Option<String>,
    only: Option<String>,
}

impl Options {
    fn parse() -> Result<Options, String> {
        let mut args: Vec<String> = std::env::args().skip(1).collect();
        let mut option = |flag: &str| -> Result<Option<String>, String> {
            let Some(at) = args.iter().position(|a| a == flag) else {
                return Ok(None);
            };
            if at + 1 >= args.len() {
                return Err(format!("{flag} needs a value"));
            }
            let value = args.remove(at + 1);
            args.remove(at);
            Ok(Some(value))
        };
        let (dump, movable, only) = (option("--dump")?, option("--movable")?, option("--only")?);
        let arg = args.first().cloned().unwrap_or_else(|| "cornell".into());
        let rays = args
            .get(1)
            .map_or(Ok(1_000_000), |s| s.parse())
            .map_err(|_| "bad ray count")?;
        Ok(Options {
            path: if arg == "cornell" {
                CORNELL.into()
            } else {
                arg
            },
            rays,
            dump,
            movable,
            only,
        })
    }
}

/// The scene as the file holds it: OBJ files through the minimal reader above
/// (positions only, a group per instance); anything else (glTF, COLLADA) through the
/// scene crate's loaders.
fn scene_at(path: &str) -> Result<Scene, String> {
    if path.to_ascii_lowercase().ends_with(".obj") {
        Ok(scene_of(read_obj(path)?))
    } else {
        invlight_scene::load(std::path::Path::new(path), &Default::default())
            .map_err(|e| e.to_string())
    }
}

/// The yardstick: obvhs's own traversal and Möller–Trumbore test over one flat BVH of
/// `merged`'s one mesh. Returns its triangles and its closest-hit rate.
fn yardstick(merged: &Scene, rays: &[Ray]) -> (Vec<Triangle>, (f64, f64, usize)) {
    let n = rays.len();
    let tris: Vec<Triangle> = merged.meshes[0]
        .triangles
        .iter()
        .map(|t| {
            let p = t.map(|i| Vec3A::from(merged.meshes[0].positions[i as usize]));
            Triangle {
                v0: p[0],
                v1: p[1],
                v2: p[2],
            }
        })
        .collect();
    let start = Instant::now();
    let flat = build_cwbvh_from_tris(
        &tris,
        BvhBuildParams::medium_build(),
        &mut Duration::default(),
    );
    let flat_build = start.elapsed().as_secs_f64();
    let flat_tris: Vec<Triangle> = flat
        .primitive_indices
        .iter()
        .map(|&i| tris[i as usize])
        .collect();
    let obvhs_ray = |r: &Ray| obvhs::ray::Ray::new_inf(r.origin.into(), r.dir.into());
    let base = rate(rays, |r| {
        let mut hit = RayHit::none();
        flat.ray_traverse(obvhs_ray(r), &mut hit, |ray, i| flat_tris[i].intersect(ray))
    });
    println!(
        "obvhs flat CwBvh build {flat_build:.3} s, {} nodes",
        flat.nodes.len()
    );
    report("obvhs flat: ray_traverse, Möller", base, base.0, n);
    let occl = rate(rays, |r| {
        !flat.ray_traverse_miss(obvhs_ray(r), |ray, i| flat_tris[i].intersect(ray))
    });
    report("obvhs flat: ray_traverse_miss (any hit)", occl, base.0, n);
    (tris, base)
}

/// Builds one `Accel` variant (with `movable` instances baked when given), prints its
/// build, update and size figures and its rates against `base`, and returns it.
fn measure_accel(
    label: &str,
    scene: &Scene,
    bake: Option<&[InstanceId]>,
    rays: &[Ray],
    base: f64,
) -> Accel {
    let start = Instant::now();
    let accel = match bake {
        Some(movable) => Accel::with_movable(scene, movable),
        None => Accel::new(scene),
    };
    let build = start.elapsed().as_secs_f64();
    let s = accel.stats();
    let start = Instant::now();
    let mut again = accel.clone();
    let clone_time = start.elapsed().as_secs_f64();
    let start = Instant::now();
    again.update_instances(scene);
    let update = start.elapsed().as_secs_f64();
    println!(
        "Accel, {label}: build {build:.3} s (BLAS {:.3} s), TLAS update {:.2} ms (clone {:.2} ms); {} instances, {} BLAS + {} TLAS nodes, depth {}, {:.1} MB",
        s.blas_seconds,
        update * 1e3,
        clone_time * 1e3,
        s.instances,
        s.blas_nodes,
        s.tlas_nodes,
        s.max_depth,
        s.bytes as f64 / 1e6
    );
    let n = rays.len();
    report(
        &format!("Accel, {label}: intersect"),
        rate(rays, |r| accel.intersect(r).is_some()),
        base,
        n,
    );
    report(
        &format!("Accel, {label}: occluded"),
        rate(rays, |r| accel.occluded(r)),
        base,
        n,
    );
    accel
}

/// The files of `--dump DIR` for benches/embree_raybench.py.
fn dump_all(dir: &str, tris: &[Triangle], rays: &[Ray], accel: &Accel) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{dir}: {e}"))?;
    dump(
        dir,
        "tris.f32",
        tris.iter()
            .flat_map(|t| [t.v0, t.v1, t.v2])
            .flat_map(|p| p.to_array()),
    )?;
    dump(
        dir,
        "rays.f32",
        rays.iter()
            .flat_map(|r| [r.origin, r.dir])
            .flat_map(|p| p.to_array()),
    )?;
    dump(
        dir,
        "t.f32",
        rays.iter()
            .map(|r| accel.intersect(r).map_or(f32::INFINITY, |h| h.t)),
    )
}

fn main() -> Result<(), String> {
    let options = Options::parse()?;
    let (path, n) = (&options.path, options.rays);
    let per_group = scene_at(path)?;
    let merged = flatten(&per_group);
    println!(
        "{path}: {} triangles in {} instances of {} meshes; {n} random rays",
        merged.meshes[0].triangles.len(),
        per_group.instances.len(),
        per_group.meshes.len()
    );
    let rays = rays(&merged, n);
    let (tris, base) = yardstick(&merged, &rays);
    let movable = movable_of(&per_group, options.movable.as_deref())?;
    let moved = &per_group.instances[movable];
    println!(
        "movable instance: '{}', {} triangles",
        moved.name,
        per_group.meshes[moved.mesh].triangles.len()
    );
    let one_movable = [InstanceId::from_index(movable)];
    let one_movable_label = format!("instance '{}' movable", moved.name);
    for (label, scene, bake) in [
        ("one mesh", &merged, None),
        ("instances as in the file", &per_group, None),
        ("instances baked (with_movable)", &per_group, Some(&[][..])),
        (&one_movable_label[..], &per_group, Some(&one_movable[..])),
    ] {
        if options.only.as_deref().is_some_and(|o| !label.contains(o)) {
            continue;
        }
        let accel = measure_accel(label, scene, bake, &rays, base.0);
        if let Some(dir) = options.dump.as_deref()
            && label == "one mesh"
        {
            dump_all(dir, &tris, &rays, &accel)?;
        }
    }
    Ok(())
}
