//! Hostile and huge inputs: files that parse but once broke a run after
//! parsing. The reproducers are in tests/data/hostile (written by make.py there); each
//! must now be refused with an error naming the file, the place and what was expected,
//! or load correctly.

use invlight_scene::{Light, Mat4, MeshId};
use invlight_scene::{
    LightKind, LoadError, LoadOptions, MAX_COORDINATE, MAX_FLUX, Material, Mesh, Scene, SceneError,
    Vec3, load,
};
use std::path::PathBuf;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/hostile")
        .join(name)
}

fn error_with(name: &str, options: &LoadOptions) -> LoadError {
    match load(&data(name), options) {
        Ok(_) => panic!("{name} loaded"),
        Err(e) => {
            assert_eq!(e.path, data(name), "{e}");
            e
        }
    }
}

fn error(name: &str) -> LoadError {
    error_with(name, &LoadOptions::default())
}

/// Asserts that `e` is located at `place` and its message mentions every one of `words`.
fn check(e: &LoadError, place: &str, words: &[&str]) {
    assert_eq!(e.location, place, "{e}");
    for w in words {
        assert!(e.message.contains(w), "{w:?} not in: {e}");
    }
    assert!(e.hint.is_some(), "no hint: {e}");
}

/// Coordinates the BVH builder could not take (obvhs indexed out of bounds on
/// each), refused in world space with the surface named.
#[test]
fn huge_coordinates_are_refused() {
    check(
        &error("huge_triangle.obj"),
        "surface 'default'",
        &["mesh's own space", "1e20", "1e9"],
    );
    check(
        &error("huge_translation.gltf"),
        "surface 'Floor'",
        &["in the world", "3e38"],
    );
    check(
        &error("huge_matrix.gltf"),
        "surface 'Floor'",
        &["in the world", "3.4e38"],
    );
    check(
        &error("huge_translate.dae"),
        "surface 'Far'",
        &["in the world", "3e38"],
    );
    check(
        &error("huge_scale.gltf"),
        "surface 'Floor'",
        &["in the world", "1e20"],
    );
}

/// `--scale` is applied before the range check, so a valid file scaled out of
/// range is refused too (it escaped the check when the scale came after it).
#[test]
fn scale_is_checked() {
    let scaled = |s: f32| LoadOptions {
        scale: s,
        ..LoadOptions::default()
    };
    assert!(load(&data("lamp_floor.gltf"), &scaled(1e3)).is_ok());
    for s in [1e15, 3e18, 1e30] {
        let e = error_with("lamp_floor.gltf", &scaled(s));
        assert!(e.message.contains("in the world"), "{e}");
        assert!(e.hint.as_deref().unwrap().contains("--scale"), "{e}");
    }
}

/// Lights whose flux overflows (NaN estimates once), alone or summed, and an
/// emitter of luminance 1e38 cd/m².
#[test]
fn overflowing_flux_is_refused() {
    check(
        &error("light_3e38cd.gltf"),
        "light 'Lamp'",
        &["luminous flux", "3.770e39 lm"],
    );
    let e = error("lights_sum_overflow.gltf");
    assert_eq!(e.location, "", "{e}");
    assert!(e.message.contains("20 emitters"), "{e}");
    check(
        &error("ke_1e38.obj"),
        "surface 'Light' (material 'Glow')",
        &["luminous flux"],
    );
}

/// A spot whose cone is so narrow its flux rounds to 0 is refused, not
/// silently dropped (the run said "the scene has no light").
#[test]
fn underflowing_flux_is_refused() {
    check(
        &error("spot_underflow.gltf"),
        "light 'Lamp'",
        &["rounds to 0 lm"],
    );
}

/// A scene just inside every bound loads; just outside, it does not.
#[test]
fn bounds_are_inclusive() {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let m = MAX_COORDINATE;
    let quad = scene.add_mesh(Mesh::quad(
        [
            Vec3::new(-m, 0.0, -m),
            Vec3::new(m, 0.0, -m),
            Vec3::new(m, 0.0, m),
            Vec3::new(-m, 0.0, m),
        ],
        grey,
    ));
    scene.add_instance("Floor", quad, Mat4::IDENTITY);
    // A point lamp of exactly MAX_FLUX (4π·I = MAX_FLUX).
    let intensity = (MAX_FLUX / (4.0 * std::f64::consts::PI)) as f32 * 0.999;
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Lamp".into(),
        kind: LightKind::Point {
            position: Vec3::new(0.0, m, 0.0),
            intensity: Vec3::splat(intensity),
        },
    });
    assert_eq!(scene.validate(), Ok(()));
    let mut far = scene.clone();
    far.instances[0].transform = Mat4::from_translation(Vec3::new(0.0, 0.0, 1e6));
    assert!(matches!(
        far.validate(),
        Err(SceneError::Coordinate {
            space: "in the world",
            ..
        })
    ));
    let mut bright = scene.clone();
    bright.lights.push(bright.lights[0].clone());
    assert!(matches!(
        bright.validate(),
        Err(SceneError::TotalFlux { emitters: 2, .. })
    ));
}

/// A scene built in code with dangling indices is refused by `validate` rather than
/// panicking whatever reads it next.
#[test]
fn dangling_indices_are_refused() {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let mut mesh = Mesh::quad([Vec3::ZERO, Vec3::X, Vec3::ONE, Vec3::Y], grey);
    mesh.triangles[1] = [0, 2, 9];
    let id = scene.add_mesh(mesh);
    scene.add_instance("Broken", id, Mat4::IDENTITY);
    let e = scene.validate().unwrap_err();
    assert_eq!(e.place(), "surface 'Broken'");
    assert!(e.to_string().contains("triangle 1"), "{e}");
    let mut scene = Scene::default();
    scene.add_instance("Nothing", MeshId::from_index(3), Mat4::IDENTITY);
    assert!(matches!(scene.validate(), Err(SceneError::Index { .. })));
}

fn with_memory(bytes: u64) -> LoadOptions {
    LoadOptions {
        max_memory: bytes,
        ..LoadOptions::default()
    }
}

fn trusting() -> LoadOptions {
    LoadOptions {
        allow_outside_paths: true,
        ..LoadOptions::default()
    }
}

/// A 4 KB glTF whose bufferless accessor claims 178 956 970 VEC3 (it aborted
/// allocating 2 GB) is refused with the figure before anything is allocated, past the
/// budget; a PNG whose header declares 13 000² pixels (2.5 GB decoded) in 118 bytes is left
/// out as unreadable before the decoder allocates (tests/memory.rs has the rest).
#[test]
fn memory_bombs_are_refused_with_the_figure() {
    let e = error_with("bufferless_accessor.gltf", &with_memory(1 << 30));
    assert_eq!(
        e.location,
        "accessors[0] (from meshes[0].primitives[0].attributes.POSITION)"
    );
    assert!(
        e.message.contains("178956970 VEC3") && e.message.contains("2.1 GB"),
        "{e}"
    );
    assert!(e.hint.as_deref().unwrap().contains("--max-memory"), "{e}");

    let s = load(&data("huge_texture.obj"), &with_memory(1 << 30)).unwrap();
    assert!(s.textures.is_empty());
    // The scene file itself counts.
    let e = error_with("instanced_200.gltf", &with_memory(1000));
    assert!(e.message.contains("the file's bytes"), "{e}");
    // Within the budget the instanced file loads instanced: one mesh, 200 instances.
    let s = load(&data("instanced_200.gltf"), &LoadOptions::default()).unwrap();
    assert_eq!((s.meshes.len(), s.instances.len()), (1, 200));
    assert_eq!(s.meshes[0].triangles.len(), 2108);
}

/// References outside the scene's folder tree (absolute paths, `file:` URIs,
/// `..` out of the folder) are refused by default, naming the reference; device files
/// are refused even when outside paths are allowed.
#[test]
fn references_stay_in_the_scene_folder() {
    for (file, place, words) in [
        (
            "buffer_absolute.gltf",
            "buffers[0]",
            "/etc/hostname is an absolute path",
        ),
        (
            "buffer_dev_zero.gltf",
            "buffers[0]",
            "/dev/zero is an absolute path",
        ),
        (
            "buffer_file_uri.gltf",
            "buffers[0]",
            "file:///etc/hostname is an absolute path",
        ),
        (
            "buffer_parent.gltf",
            "buffers[0]",
            "leads outside the scene's folder",
        ),
        (
            "image_dev_zero.gltf",
            "images[0]",
            "/dev/zero is an absolute path",
        ),
        (
            "mtllib_absolute.obj",
            "line 1",
            "/etc/hostname is an absolute path",
        ),
    ] {
        let e = error(file);
        assert_eq!(e.location, place, "{e}");
        assert!(e.message.contains(words), "{e}");
        assert!(
            e.hint.as_deref().unwrap().contains("--allow-outside-paths"),
            "{e}"
        );
    }
    let e = load(&data("map_dev_zero.obj"), &LoadOptions::default()).unwrap_err();
    assert_eq!(
        (e.path.clone(), e.location.as_str()),
        (data("map_dev_zero.mtl"), "line 3")
    );
    let e = error("init_from_absolute.dae");
    assert!(e.location.contains("<init_from>"), "{e}");
    assert!(
        e.message.contains("file:///dev/zero is an absolute path"),
        "{e}"
    );

    // Trusted, the paths resolve, but a device is never read: a buffer fails, a
    // texture is left out with a warning.
    for file in ["buffer_dev_zero.gltf", "image_dev_zero.gltf"] {
        let e = error_with(file, &trusting());
        assert!(e.message.contains("not a regular file"), "{e}");
    }
    for file in ["map_dev_zero.obj", "init_from_absolute.dae"] {
        let s = load(&data(file), &trusting()).unwrap_or_else(|e| panic!("{e}"));
        assert!(s.textures.is_empty());
    }
}

/// A link inside the scene's folder that leads out of it is refused too.
#[cfg(unix)]
#[test]
fn links_out_of_the_folder_are_refused() {
    let dir = std::env::temp_dir().join(format!("invlight-hostile-link-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("linked.gltf");
    let bin = dir.join("outside.bin");
    let _ = std::fs::remove_file(&bin);
    std::os::unix::fs::symlink(data("make.py"), &bin).unwrap();
    std::fs::write(
        &scene,
        r#"{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": "outside.bin"}]}"#,
    )
    .unwrap();
    let e = load(&scene, &LoadOptions::default()).unwrap_err();
    assert!(e.message.contains("through a link"), "{e}");
    assert!(load(&scene, &trusting()).is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}
