//! The OBJ loader on real files: both Cornell boxes, Sponza and the conference room
//! (the thesis' test scenes 3–5, unzipped from tests/data/obj), a file exercising names,
//! index forms and materials, and broken files that must give located errors.

use invlight_scene::{LoadOptions, Scene, Vec3, load};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/obj")
        .join(name)
}

fn scene(path: &Path) -> Scene {
    load(path, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn triangles(s: &Scene) -> usize {
    s.instances
        .iter()
        .map(|i| s.meshes[i.mesh].triangles.len())
        .sum()
}

fn surface_names(s: &Scene) -> Vec<&str> {
    s.surfaces.iter().map(|x| x.name.as_str()).collect()
}

/// Extracts `member` of a zip in tests/data/obj into a fresh temporary directory.
fn unzip(zip: &str, member: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("invlight-obj-{}-{zip}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = std::fs::File::open(data(zip)).unwrap();
    let mut archive = zip::ZipArchive::new(file).unwrap();
    let mut entry = archive.by_name(member).unwrap();
    let out = dir.join(member);
    std::io::copy(&mut entry, &mut std::fs::File::create(&out).unwrap()).unwrap();
    out
}

#[test]
fn mcguire_cornell_box_light_from_ke() {
    let s = scene(&data("CornellBox-Original.obj"));
    assert_eq!(s.up, Vec3::Y);
    assert_eq!(triangles(&s), 36);
    // The file's own grouping: the short box's faces come before `g shortBox`, so they
    // belong to leftWall; the tall box's to shortBox; `g tallBox` has no faces.
    assert_eq!(
        surface_names(&s),
        [
            "floor",
            "ceiling",
            "backWall",
            "rightWall",
            "leftWall",
            "shortBox",
            "light"
        ]
    );
    let left = s.surface("leftWall").unwrap();
    assert_eq!(s.surface_triangles(left), 2 + 12);
    // The light: Ke 17 12 4 on a 0.47 × 0.38 quad facing down; the only emitter.
    let emitters: Vec<_> = s.materials.iter().filter(|m| m.is_emissive()).collect();
    assert_eq!(emitters.len(), 1);
    assert_eq!(emitters[0].emission, Vec3::new(17.0, 12.0, 4.0));
    let light = s.surface("light").unwrap();
    assert!((s.surface_area(light) - 0.47 * 0.38).abs() <= 1e-6);
    let inst = &s.instances[s.surfaces[light].instances[0]];
    let mesh = &s.meshes[inst.mesh];
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t);
        assert_eq!((b - a).cross(c - a).normalize(), Vec3::NEG_Y);
    }
    let left_wall = s.materials.iter().find(|m| m.name == "leftWall").unwrap();
    assert_eq!(left_wall.diffuse, Vec3::new(0.63, 0.065, 0.05));
}

#[test]
fn measured_cornell_box_has_no_emitter() {
    let s = scene(&data("cornell_box.obj"));
    assert_eq!(triangles(&s), 36);
    // `o front_wall` has its face commented out, so it is no surface.
    assert_eq!(
        surface_names(&s),
        [
            "floor",
            "light",
            "ceiling",
            "back_wall",
            "green_wall",
            "red_wall",
            "short_block",
            "tall_block"
        ]
    );
    // Its "light" material has only `Ka 20 20 20` (ambient), which is not emission.
    assert!(s.materials.iter().all(|m| !m.is_emissive()));
    let light = s.surface("light").unwrap();
    // Millimetres, as measured; --scale converts.
    assert!((s.surface_area(light) - 130.0 * 105.0).abs() <= 1e-2);
}

#[test]
fn names_index_forms_and_materials() {
    let s = scene(&data("names.obj"));
    // Three name sets: {Table, top, wood} (a quad, then a triangle when the same names
    // come back), {Table, leg, wood} and {Lamp} (a pentagon fan).
    assert_eq!(s.instances.len(), 3);
    assert_eq!(surface_names(&s), ["Table", "top", "wood", "leg", "Lamp"]);
    let count = |n: &str| s.surface_triangles(s.surface(n).unwrap());
    assert_eq!(
        [
            count("Table"),
            count("top"),
            count("wood"),
            count("leg"),
            count("Lamp")
        ],
        [4, 3, 4, 1, 3]
    );
    let kind = |inst: usize, t: usize| {
        let mesh = &s.meshes[s.instances[inst].mesh];
        &s.materials[mesh.materials[t]]
    };
    // illum 3: Ks is a mirror; the later `usemtl Unknown` gets grey.
    assert_eq!(kind(0, 0).kind_name(), "mirror");
    assert_eq!(kind(0, 0).specular, Vec3::splat(0.8));
    assert_eq!(
        (kind(0, 2).name.as_str(), kind(0, 2).diffuse),
        ("Unknown", Vec3::splat(0.8))
    );
    // illum 7 with Tf and Ni: glass. The face used negative and v//vn indices: 1 2 3.
    let glass = kind(1, 0);
    assert_eq!(
        (glass.kind_name(), glass.ior, glass.transmission),
        ("glass", 1.45, 1.0)
    );
    let leg = &s.meshes[s.instances[1].mesh];
    assert_eq!(
        leg.triangle(0),
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)]
    );
    // Ke makes the lamp an emitter; map_Kd after its options, with a space in the name.
    let lamp = kind(2, 0);
    assert_eq!(lamp.emission, Vec3::splat(10.0));
    let texture = &s.textures[lamp.texture.expect("texture")];
    assert_eq!((texture.width, texture.height), (2, 2));
    // The quad's texture coordinates, v flipped: vt 0.25 0.25 is in the bottom-left
    // (blue) texel.
    let top = &s.meshes[s.instances[0].mesh];
    assert_eq!(texture.sample(top.uvs[0]), Vec3::new(0.0, 0.0, 1.0));
    assert!(s.meshes[s.instances[2].mesh].uvs.is_empty());
}

#[test]
fn sponza_atrium() {
    let path = unzip("sponza.zip", "sponza.obj");
    let s = scene(&path);
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
    assert_eq!(triangles(&s), 66_454);
    // 34 named groups; the file's 34 bare `g` lines precede vertex lists, not faces.
    assert_eq!(s.surfaces.len(), 34);
    assert!(s.surface("default").is_none());
    let count = |n: &str| s.surface_triangles(s.surface(n).unwrap());
    assert_eq!(
        (count("ceiling"), count("walls"), count("relief")),
        (10_370, 3_322, 16)
    );
    let (lo, hi) = s.bounds().unwrap();
    let size = hi - lo;
    assert!((size.y - 16.5).abs() < 0.5, "{size}");
}

#[test]
fn conference_room() {
    let path = unzip("conference.zip", "conference.obj");
    let s = scene(&path);
    std::fs::remove_dir_all(path.parent().unwrap()).unwrap();
    assert_eq!(triangles(&s), 331_179);
    // No groups: every face is in OBJ's default group; positions only, all used.
    assert_eq!(surface_names(&s), ["default"]);
    assert_eq!(s.meshes[0].positions.len(), 194_399);
    assert!(s.meshes[0].uvs.is_empty());
}

fn error(name: &str) -> String {
    match load(&data(name), &LoadOptions::default()) {
        Ok(_) => panic!("{name} loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_files_give_located_errors() {
    let cases = [
        (
            "bad-number.obj",
            "bad-number.obj: line 4: expected a number, found '1,5'",
        ),
        (
            "index-out-of-range.obj",
            "index-out-of-range.obj: line 5: vertex index 4 is out of range: 3 defined so far",
        ),
        (
            "short-face.obj",
            "short-face.obj: line 5: a face needs at least 3 vertices, found 2",
        ),
        (
            "truncated.obj",
            "truncated.obj: line 4: 'v' needs 3 numbers, found 2",
        ),
        (
            "bad-mtl.obj",
            "bad-colour.mtl: line 3: 'Kd' needs 1 or 3 numbers",
        ),
    ];
    for (file, expected) in cases {
        let e = error(&format!("malformed/{file}"));
        assert!(e.ends_with(expected), "{e}");
    }
}

#[test]
fn a_missing_material_library_is_a_warning() {
    let s = scene(&data("malformed/missing-mtl.obj"));
    assert_eq!(triangles(&s), 1);
    assert_eq!(s.materials[0].name, "red");
    assert_eq!(s.materials[0].diffuse, Vec3::splat(0.8));
}
