//! A bounded fuzz target per scene parser (glTF JSON, GLB, COLLADA, OBJ,
//! MTL), on mutants of the repository's sample files (see `fuzz/mod.rs`). Each mutant
//! is written beside copies of the files its sample references and loaded through
//! `invlight_scene::load`, with a 256 MB memory budget; the loader must not panic or
//! hang, and a scene it accepts must pass `Scene::validate`, build an `Accel` both ways
//! without panic, and trace rays.
//!
//! `INVLIGHT_FUZZ_CASES=N` runs N cases per target (default 300).

mod fuzz;

use invlight_scene::{LoadOptions, load};
use invlight_trace::{Accel, Ray};
use std::path::{Path, PathBuf};

/// A file under tests/data.
fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data")
        .join(rel)
}

/// A fresh folder for one target, holding copies of `side` files (what the samples
/// reference), removed when dropped.
struct Folder(PathBuf);

impl Folder {
    fn new(target: &str, side: &[&str]) -> Folder {
        let dir =
            std::env::temp_dir().join(format!("invlight-fuzz-{target}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for s in side {
            let from = data(s);
            std::fs::copy(&from, dir.join(from.file_name().unwrap())).unwrap();
        }
        Folder(dir)
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn read(rel: &str) -> Vec<u8> {
    std::fs::read(data(rel)).unwrap()
}

/// Loads `path`; on success checks the promises of an accepted scene.
fn load_and_trace(path: &Path) -> bool {
    let options = LoadOptions {
        max_memory: 256 << 20,
        ..LoadOptions::default()
    };
    let Ok(scene) = load(path, &options) else {
        return false;
    };
    scene.validate().expect("load returns only valid scenes");
    // The command line refuses past its budget; so does this test.
    if Accel::estimated_bytes(&scene) > 512 << 20 {
        return true;
    }
    let (lo, hi) = scene
        .bounds()
        .unwrap_or((glam::Vec3::ZERO, glam::Vec3::ONE));
    for accel in [Accel::new(&scene), Accel::with_movable(&scene, &[])] {
        for k in 0..8 {
            let t = k as f32 / 8.0;
            let origin = lo + (hi - lo) * t - glam::Vec3::ONE;
            let ray = Ray::new(
                origin,
                (hi - origin + glam::Vec3::splat(t)).normalize_or(glam::Vec3::X),
            );
            if let Some(hit) = accel.intersect(&ray) {
                let it = accel.interaction(&scene, &ray, &hit);
                assert!(it.point.is_finite() && it.normal.is_finite(), "{it:?}");
            }
            accel.occluded(&ray);
        }
    }
    true
}

/// Writes each mutant to `name` in `folder` and loads it.
fn target(target: &str, name: &str, samples: &[Vec<u8>], side: &[&str]) {
    let folder = Folder::new(target, side);
    let path = folder.0.join(name);
    fuzz::run(target, samples, |bytes| {
        std::fs::write(&path, bytes).unwrap();
        load_and_trace(&path)
    });
}

#[test]
fn fuzz_gltf_json() {
    target(
        "gltf",
        "mutant.gltf",
        &[
            read("gltf/hierarchy.gltf"),
            read("gltf/materials.gltf"),
            read("gltf/external.gltf"),
            read("hostile/lamp_floor.gltf"),
            read("triple/room.gltf"),
        ],
        &["gltf/external.bin", "gltf/external 0.png"],
    );
}

#[test]
fn fuzz_glb() {
    target(
        "glb",
        "mutant.glb",
        &[read("gltf/hierarchy.glb"), read("gltf/materials.glb")],
        &[],
    );
}

#[test]
fn fuzz_collada() {
    target(
        "collada",
        "mutant.dae",
        &[
            read("collada/cornell.dae"),
            read("collada/lights.dae"),
            read("collada/cameras.dae"),
            read("collada/textured/scene.dae"),
            read("triple/room.dae"),
        ],
        &["collada/textured/checker 2x2.png"],
    );
}

#[test]
fn fuzz_obj() {
    // The samples name their MTL files, copied beside the mutant.
    target(
        "obj",
        "mutant.obj",
        &[
            read("obj/names.obj"),
            read("obj/cornell_box.obj"),
            read("triple/room.obj"),
        ],
        &[
            "obj/names.mtl",
            "obj/cornell_box.mtl",
            "triple/room.mtl",
            "obj/checker 2x2.png",
        ],
    );
}

#[test]
fn fuzz_mtl() {
    // One OBJ naming `mutant.mtl` and using each sample's materials.
    let folder = Folder::new("mtl", &["obj/checker 2x2.png"]);
    let mut obj = b"mtllib mutant.mtl\n".to_vec();
    obj.extend(read("obj/cornell_box.obj"));
    for m in ["Mirror", "Glass", "Light", "floor", "light", "leftWall"] {
        obj.extend(format!("usemtl {m}\nf 1 2 3\n").bytes());
    }
    let obj_path = folder.0.join("scene.obj");
    std::fs::write(&obj_path, obj).unwrap();
    let mtl = folder.0.join("mutant.mtl");
    fuzz::run(
        "mtl",
        &[
            read("obj/names.mtl"),
            read("obj/cornell_box.mtl"),
            read("triple/room.mtl"),
        ],
        |bytes| {
            std::fs::write(&mtl, bytes).unwrap();
            load_and_trace(&obj_path)
        },
    );
}
