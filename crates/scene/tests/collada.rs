//! The COLLADA loader on real files: ILPSolver's Cornell box (the thesis' test scene
//! 1–2), Blender's light and camera exports, a small scene exercising the rest of the
//! format, and broken files that must give located errors, never a panic.

use invlight_scene::{LightKind, LoadOptions, Scene, Vec3, load};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/collada")
        .join(name)
}

fn scene(name: &str) -> Scene {
    load(&data(name), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// f32 agreement to `ulps`-scale relative error: the loader does a handful of f32
/// operations (a 4×4 product, a sum over two triangles), each rounding by 2⁻²⁴.
fn close(a: f32, b: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1.0)
}

fn close3(a: Vec3, b: Vec3, rel: f32) -> bool {
    close(a.x, b.x, rel) && close(a.y, b.y, rel) && close(a.z, b.z, rel)
}

const REL: f32 = 1e-5;

fn instance<'s>(s: &'s Scene, name: &str) -> &'s invlight_scene::Instance {
    s.instances
        .iter()
        .find(|i| i.name == name)
        .unwrap_or_else(|| panic!("no instance {name}"))
}

#[test]
fn ilpsolver_cornell_box() {
    let s = scene("cornell.dae");
    // Blender 2.70 export: metres, Z up.
    assert_eq!(s.up, Vec3::Z);
    let triangles: usize = s
        .instances
        .iter()
        .map(|i| s.meshes[i.mesh].triangles.len())
        .sum();
    assert_eq!(triangles, 2 + 6 * 12 + 8064 + 62 + 4 + 6 + 2);

    // The `Light` plane is the only emitter: emitter_001, emission 16 16 16 (unitless in
    // ILPSolver, kept as cd/m²).
    let emissive: Vec<_> = s.materials.iter().filter(|m| m.is_emissive()).collect();
    assert_eq!(emissive.len(), 1);
    assert_eq!(emissive[0].name, "emitter_001");
    assert_eq!(emissive[0].emission, Vec3::splat(16.0));
    for inst in &s.instances {
        let mesh = &s.meshes[inst.mesh];
        let emits = mesh.materials.iter().any(|&m| s.materials[m].is_emissive());
        assert_eq!(emits, inst.name == "Light", "{}", inst.name);
    }
    // A 2 × 2 plane scaled by 0.6223754, emitting downward (its front face is −Z).
    let light = instance(&s, "Light");
    let mesh = &s.meshes[light.mesh];
    assert!(close(
        mesh.area(&light.transform),
        (2.0f32 * 0.6223754).powi(2),
        REL
    ));
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh
            .triangle(t)
            .map(|p| light.transform.transform_point3(p));
        assert!(close3((b - a).cross(c - a).normalize(), Vec3::NEG_Z, REL));
    }

    // Surfaces the problem files name, and ancestors covering descendants.
    for name in ["Cone", "Cube-Ceiling", "Light", "Sphere_001"] {
        assert!(s.surface(name).is_some(), "{name}");
    }
    let cube = &s.surfaces[s.surface("Cube").unwrap()];
    let mut covered: Vec<&str> = cube
        .instances
        .iter()
        .map(|&i| s.instances[i].name.as_str())
        .collect();
    covered.sort();
    assert_eq!(covered, ["Cube-1", "Cube-2", "Cube-Ceiling"]);
    // Two primitive lists in one geometry keep their own bound materials.
    let walls = &s.meshes[instance(&s, "Cube-1").mesh];
    let mut wall_materials: Vec<&str> = walls
        .materials
        .iter()
        .map(|&m| s.materials[m].name.as_str())
        .collect();
    wall_materials.dedup();
    assert_eq!(wall_materials, ["red_001", "green_001"]);
    let ceiling = &s.meshes[instance(&s, "Cube-Ceiling").mesh];
    assert_eq!(s.materials[ceiling.materials[0]].name, "white_001");
    let cone = instance(&s, "Cone");
    assert!(close3(
        cone.transform.transform_point3(Vec3::ZERO),
        Vec3::new(2.258985, -7.008961, 0.7628853),
        REL
    ));

    // Cone__Geometry is a placement, not part of the lit scene. Its vertices come in the
    // order the index list first reaches them (0 1 3 2 of the plane's positions), as
    // ILPSolver saw them through Assimp.
    assert!(s.surface("Cone__Geometry").is_none());
    assert!(s.instances.iter().all(|i| !i.name.ends_with("__Geometry")));
    let p = s.placement("Cone__Geometry").expect("placement");
    let m = |x: f32, y: f32| {
        Vec3::new(
            -2.624975 * x + 0.3863792,
            -6.462182 * y - 1.396833,
            0.3555108,
        )
    };
    assert_eq!(p.vertices.len(), 4);
    let expected = [m(-1.0, -1.0), m(1.0, -1.0), m(1.0, 1.0), m(-1.0, 1.0)];
    for (v, e) in p.vertices.iter().zip(expected) {
        assert!(close3(*v, e, REL), "{v} vs {e}");
    }
    // cornell-move-cone.xml: vertexAIndex=3 B=0 C=2 D=1. ILPSolver's ObjectInSurface
    // tests the triangles (A, B, D) and (A, C, D): B and C are A's neighbours, D is
    // opposite, so the rectangle is a parallelogram A B D C with right angles.
    let [a, b, c, d] = [3, 0, 2, 1].map(|i| p.vertices[i]);
    let (ab, ac) = (b - a, c - a);
    assert!(ab.dot(ac).abs() <= REL * ab.length() * ac.length());
    assert!(close3(d, b + c - a, REL));

    // The mirror sphere: Blender's <reflective> 1 0.970 0.983 with reflectivity 1.
    let sphere = instance(&s, "Sphere_001");
    let mirror = &s.materials[s.meshes[sphere.mesh].materials[0]];
    assert_eq!(mirror.kind_name(), "mirror");
    assert_eq!(mirror.specular, Vec3::new(1.0, 0.9701858, 0.983386));
    assert_eq!(mirror.diffuse, Vec3::ZERO);
    // This export has no glass: every index of refraction is 1 and nothing is
    // transparent (the thesis' glass sphere is not in ILPSolver's cornell.dae).
    assert!(s.materials.iter().all(|m| m.transmission == 0.0 && !m.hole));

    // Cameras in node order; Blender writes xfov and the aspect ratio.
    assert_eq!(s.cameras.len(), 2);
    let cam = &s.cameras[0];
    assert_eq!(cam.name, "Camera");
    let yfov = 2.0 * ((49.13434f32.to_radians() / 2.0).tan() / 1.777778).atan();
    assert!(close(cam.yfov, yfov, REL));
    assert_eq!(cam.aspect, Some(1.777778));
    assert!(close3(
        cam.position,
        Vec3::new(0.4860681, -7.701452, 2.192455),
        REL
    ));
    assert!(s.lights.is_empty());
}

#[test]
fn blender_lights() {
    let s = scene("lights.dae");
    // Point, sun, spot and Blender's area lamp (exported as a point); the hemi lamp is
    // an <ambient> light, which has no photometric reading and is skipped.
    let names: Vec<&str> = s.lights.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["Lamp", "Sun", "Spot", "Area"]);
    assert_eq!(
        s.lights[0].kind,
        LightKind::Point {
            position: Vec3::new(0.0, 1.0, 1.0),
            intensity: Vec3::ONE
        }
    );
    assert_eq!(
        s.lights[1].kind,
        LightKind::Directional {
            direction: Vec3::NEG_Z,
            illuminance: Vec3::ONE
        }
    );
    let LightKind::Spot {
        position,
        direction,
        intensity,
        inner,
        outer,
    } = s.lights[2].kind
    else {
        panic!("not a spot: {:?}", s.lights[2]);
    };
    assert_eq!(position, Vec3::new(8.888217, -5.016863, 5.336025));
    assert_eq!((direction, intensity), (Vec3::NEG_Z, Vec3::ONE));
    // falloff_angle 45 is Blender's full spotsize; spotblend 0.15 softens in cosine.
    let cos_outer = 22.5f32.to_radians().cos();
    assert!(close(outer, 22.5f32.to_radians(), REL));
    assert!(close(
        inner.cos(),
        cos_outer + 0.15 * (1.0 - cos_outer),
        REL
    ));
}

#[test]
fn blender_cameras() {
    let s = scene("cameras.dae");
    // Camera.002 is orthographic and skipped.
    let names: Vec<&str> = s.cameras.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["Camera", "Camera_003"]);
    let c = &s.cameras[0];
    assert_eq!(c.position, Vec3::new(10.0, 0.0, 0.0));
    assert!(close3(c.forward, Vec3::NEG_X, REL));
    assert!(close3(c.up, Vec3::Y, REL));
    assert!(close3(s.cameras[1].forward, Vec3::NEG_Y, REL));
}

#[test]
fn units_transforms_textures_glass_holes_and_instanced_nodes() {
    let s = scene("textured/scene.dae");
    assert_eq!(s.up, Vec3::Y);
    // Centimetres: translate 100 cm, then rotate 90° about Z, in document order.
    let tile = instance(&s, "Tile");
    assert!(close3(
        tile.transform.transform_point3(Vec3::X),
        Vec3::new(1.0, 0.01, 0.0),
        REL
    ));
    let mesh = &s.meshes[tile.mesh];
    assert_eq!(mesh.triangles.len(), 3, "a pentagon is a fan of 3");
    assert!(close(mesh.area(&tile.transform), 1.25e-4, REL));
    let group = &s.surfaces[s.surface("Group").unwrap()];
    assert_eq!(group.instances.len(), 1);

    // sampler2D → surface → image, with a %20 in the file name; v flipped to the
    // top-row-first texture convention: uv (0.25, 0.75) is the top-left red texel.
    let checker = &s.materials[mesh.materials[0]];
    assert_eq!((checker.name.as_str(), checker.hole), ("Checker", false));
    let texture = &s.textures[checker.texture.expect("texture")];
    assert_eq!((texture.width, texture.height), (2, 2));
    assert_eq!(texture.sample(mesh.uvs[0]), Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(texture.sample(mesh.uvs[1]), Vec3::ONE);

    // instance_node from library_nodes, under an unnamed node addressed by its id.
    let lamp = instance(&s, "Lamp");
    let lamp_mesh = &s.meshes[lamp.mesh];
    assert!(close(lamp_mesh.area(&lamp.transform), 4e-4, REL));
    assert_eq!(
        s.materials[lamp_mesh.materials[0]].emission,
        Vec3::new(2.0, 3.0, 4.0)
    );
    let fixture = &s.surfaces[s.surface("Fixture").unwrap()];
    assert_eq!(fixture.instances.len(), 1);

    // Index of refraction > 1: glass, transmission 1 − opacity (transparency 0.1 is the
    // A_ONE opacity), diffuse scaled to leave room for it.
    let pane = &s.materials[s.meshes[instance(&s, "Pane").mesh].materials[0]];
    assert_eq!((pane.kind_name(), pane.ior), ("glass", 1.5));
    assert!(close(pane.transmission, 0.9, REL));
    assert!(close(pane.diffuse.x, 0.1, REL));
    // Index of refraction < 1: ILPSolver's hole.
    let window = &s.materials[s.meshes[instance(&s, "Window").mesh].materials[0]];
    assert!(window.hole);

    // A placement from a triangle strip, 50 cm up.
    let stage = s.placement("Stage__Geometry").unwrap();
    let expected = [(0.0, 0.0), (0.01, 0.0), (0.0, 0.01), (0.01, 0.01)];
    assert_eq!(stage.vertices.len(), 4);
    for (v, (x, y)) in stage.vertices.iter().zip(expected) {
        assert!(close3(*v, Vec3::new(x, y, 0.5), REL));
    }

    // <lookat>: a spot 3 m up looking down; falloff_angle 90 is a 45° half-angle with
    // a hard edge when no Blender spotblend is given.
    let LightKind::Spot {
        position,
        direction,
        intensity,
        inner,
        outer,
    } = s.lights[0].kind
    else {
        panic!("not a spot");
    };
    assert!(close3(position, Vec3::new(0.0, 3.0, 0.0), REL));
    assert!(close3(direction, Vec3::NEG_Y, REL));
    assert_eq!(intensity, Vec3::splat(5.0));
    assert!(close(outer, std::f32::consts::FRAC_PI_4, REL) && inner == outer);
}

fn error(name: &str) -> String {
    match load(&data(name), &LoadOptions::default()) {
        Ok(_) => panic!("{name} loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_files_give_located_errors() {
    let e = error("malformed/bad-number.dae");
    assert!(
        e.contains("bad-number.dae: line 8: <float_array id=\"square-pos-array\">"),
        "{e}"
    );
    assert!(e.contains("'one'"), "{e}");
    let e = error("malformed/index-out-of-range.dae");
    assert!(
        e.contains(
            "line 14: <triangles> in <geometry id=\"square\">: vertex index 7 is out of range"
        ),
        "{e}"
    );
    let e = error("malformed/dangling-url.dae");
    assert!(
        e.contains("<instance_geometry>") && e.contains("'circle'"),
        "{e}"
    );
    let e = error("malformed/truncated.dae");
    assert!(
        e.contains("truncated.dae: line") && e.contains("malformed XML"),
        "{e}"
    );
}

/// Every prefix of a real file either loads or gives an error naming the file; none
/// panics.
#[test]
fn truncated_real_files_never_panic() {
    let dir = std::env::temp_dir().join(format!("invlight-collada-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["cornell.dae", "lights.dae"] {
        let bytes = std::fs::read(data(name)).unwrap();
        let cut = dir.join(name);
        for k in 1..24 {
            let len = bytes.len() * k / 24;
            std::fs::write(&cut, &bytes[..len]).unwrap();
            if let Err(e) = load(&cut, &LoadOptions::default()) {
                assert!(e.to_string().starts_with(&cut.display().to_string()), "{e}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
