//! Load and build times of large, hostile scenes, generated in a temporary folder
//! rather than committed:
//!
//! - `parts`: 1 M triangles in 100 k named parts (10 triangles each, in a grid), as
//!   an OBJ file (`o` per part) and a glTF file (a named node and mesh per part, under
//!   one named root node), loaded by `invlight_scene::load` and built by `Accel::new`
//!   and `Accel::with_movable(&scene, &[])`;
//! - `coincident N`: N copies of one triangle, built by `Accel::new`;
//! - `big`: 1 M distinct triangles in one mesh, built by `Accel::new` (what the search
//!   for coincident boxes costs a build without any);
//! - `memory T I`: the peak memory of `Accel::new` over a mesh of T triangles placed
//!   I times, against `Accel::estimated_bytes`.
//!
//! ```text
//! cargo run --release -p invlight-trace --example hostile_bench -- parts
//! cargo run --release -p invlight-trace --example hostile_bench -- coincident 2000 30000
//! ```
//!
//! Each figure is the best of 3 wall-clock runs.

use invlight_scene::{LoadOptions, Mat4, Material, Mesh, Scene, Vec3, load};
use invlight_trace::Accel;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

const PARTS: usize = 100_000;
const TRIANGLES_PER_PART: usize = 10;

/// The best of three runs of `f`, seconds.
fn best_of_3(mut f: impl FnMut()) -> f64 {
    (0..3)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Corners of part `p`'s triangle `t`: a strip of 10 triangles in a 1 m cell of a
/// 317 × 317 grid.
fn corners(p: usize, t: usize) -> [[f32; 3]; 3] {
    let (x, z) = ((p % 317) as f32, (p / 317) as f32);
    let u = x + t as f32 * 0.1;
    [
        [u, 0.0, z],
        [u + 0.1, 0.0, z],
        [u, 0.1 * (t % 3) as f32 + 0.1, z + 0.5],
    ]
}

fn write_obj(path: &Path) {
    let mut s = String::with_capacity(64 << 20);
    let mut v = 0;
    for p in 0..PARTS {
        writeln!(s, "o part{p}").unwrap();
        for t in 0..TRIANGLES_PER_PART {
            for c in corners(p, t) {
                writeln!(s, "v {} {} {}", c[0], c[1], c[2]).unwrap();
            }
            writeln!(s, "f {} {} {}", v + 1, v + 2, v + 3).unwrap();
            v += 3;
        }
    }
    std::fs::write(path, s).unwrap();
}

fn write_gltf(path: &Path) {
    let per_part = TRIANGLES_PER_PART * 3 * 12;
    let mut bin = Vec::with_capacity(PARTS * per_part);
    for p in 0..PARTS {
        for t in 0..TRIANGLES_PER_PART {
            for c in corners(p, t) {
                c.iter().for_each(|x| bin.extend(x.to_le_bytes()));
            }
        }
    }
    std::fs::write(path.with_extension("bin"), &bin).unwrap();
    let mut s = String::with_capacity(32 << 20);
    s.push_str(r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"parts.bin","byteLength":"#);
    write!(s, "{}", bin.len()).unwrap();
    s.push_str(r#"}],"bufferViews":["#);
    for p in 0..PARTS {
        let sep = if p > 0 { "," } else { "" };
        write!(
            s,
            r#"{sep}{{"buffer":0,"byteOffset":{},"byteLength":{per_part}}}"#,
            p * per_part
        )
        .unwrap();
    }
    s.push_str(r#"],"accessors":["#);
    for p in 0..PARTS {
        let sep = if p > 0 { "," } else { "" };
        write!(
            s,
            r#"{sep}{{"bufferView":{p},"componentType":5126,"count":{},"type":"VEC3"}}"#,
            TRIANGLES_PER_PART * 3
        )
        .unwrap();
    }
    s.push_str(r#"],"meshes":["#);
    for p in 0..PARTS {
        let sep = if p > 0 { "," } else { "" };
        write!(
            s,
            r#"{sep}{{"name":"mesh{p}","primitives":[{{"attributes":{{"POSITION":{p}}}}}]}}"#
        )
        .unwrap();
    }
    s.push_str(r#"],"nodes":[{"name":"Building","children":["#);
    for p in 0..PARTS {
        let sep = if p > 0 { "," } else { "" };
        write!(s, "{sep}{}", p + 1).unwrap();
    }
    s.push_str("]}");
    for p in 0..PARTS {
        write!(s, r#",{{"name":"part{p}","mesh":{p}}}"#).unwrap();
    }
    s.push_str(r#"],"scenes":[{"nodes":[0]}]}"#);
    std::fs::write(path, s).unwrap();
}

fn parts() {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("invlight-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let obj = dir.join("parts.obj");
    let gltf = dir.join("parts.gltf");
    write_obj(&obj);
    write_gltf(&gltf);
    println!("file,load_s,accel_new_s,accel_movable_s,triangles,surfaces");
    for file in [&obj, &gltf] {
        let mut scene = None;
        let load_s = best_of_3(|| scene = Some(load(file, &LoadOptions::default()).unwrap()));
        let scene = scene.unwrap();
        let new_s = best_of_3(|| drop(Accel::new(&scene)));
        let movable_s = best_of_3(|| drop(Accel::with_movable(&scene, &[])));
        let triangles: usize = scene
            .instances
            .iter()
            .map(|i| scene.meshes[i.mesh].triangles.len())
            .sum();
        println!(
            "{},{load_s:.3},{new_s:.3},{movable_s:.3},{triangles},{}",
            file.file_name().unwrap().to_string_lossy(),
            scene.surfaces.len()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

fn coincident(n: usize) {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mut mesh = Mesh::default();
    for t in 0..n as u32 {
        mesh.positions
            .extend([Vec3::ZERO, Vec3::X, Vec3::new(0.0, 1.0, 1.0)]);
        mesh.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
        mesh.materials.push(grey);
    }
    let id = scene.add_mesh(mesh);
    scene.add_instance("Stack", id, Mat4::IDENTITY);
    let s = best_of_3(|| drop(Accel::new(&scene)));
    println!("{n},{s:.3}");
}

/// Peak resident memory so far, bytes (Linux `VmHWM`).
fn peak_rss() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb * 1024)
}

/// Peak memory of building `Accel::new` over `triangles` distinct triangles in one mesh
/// placed `instances` times, per triangle and per instance, against
/// `Accel::estimated_bytes`.
fn memory(triangles: usize, instances: usize) {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mut mesh = Mesh::default();
    for t in 0..triangles as u32 {
        let c = Vec3::new(
            (t % 1000) as f32,
            (t / 1000 % 1000) as f32,
            (t / 1_000_000) as f32,
        );
        mesh.positions
            .extend([c, c + Vec3::X * 0.5, c + Vec3::new(0.0, 0.5, 0.5)]);
        mesh.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
        mesh.materials.push(grey);
    }
    let id = scene.add_mesh(mesh);
    for i in 0..instances {
        scene.add_instance(
            &format!("i{i}"),
            id,
            Mat4::from_translation(Vec3::Y * i as f32 * 2e3),
        );
    }
    let before = peak_rss();
    let accel = Accel::new(&scene);
    let used = peak_rss() - before;
    println!(
        "{triangles},{instances},{used},{:.0},{}",
        used as f64 / (triangles + instances) as f64,
        Accel::estimated_bytes(&scene)
    );
    drop(accel);
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("parts") => parts(),
        Some("coincident") => {
            println!("triangles,build_s");
            for n in &args[1..] {
                coincident(n.parse().expect("a triangle count"));
            }
        }
        Some("big") => {
            let mut scene = Scene::default();
            let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
            let mut mesh = Mesh::default();
            for t in 0..1_000_000u32 {
                let c = Vec3::new((t % 1000) as f32, (t / 1000 % 1000) as f32, 0.0);
                mesh.positions
                    .extend([c, c + Vec3::X * 0.5, c + Vec3::new(0.0, 0.5, 0.5)]);
                mesh.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
                mesh.materials.push(grey);
            }
            let id = scene.add_mesh(mesh);
            scene.add_instance("a", id, Mat4::IDENTITY);
            println!("{:.3}", best_of_3(|| drop(Accel::new(&scene))));
        }
        Some("memory") => {
            println!("triangles,instances,peak_bytes,bytes_per_item,estimated_bytes");
            memory(args[1].parse().unwrap(), args[2].parse().unwrap());
        }
        _ => eprintln!(
            "usage: hostile_bench parts | coincident N... | big | memory TRIANGLES INSTANCES"
        ),
    }
}
