//! The glTF loader on the small scenes of tests/data/gltf (written by make.py there, whose
//! comments give the transforms the expected numbers below follow from).

use invlight_scene::{LightKind, LoadError, LoadOptions, Scene, Vec2, Vec3, load};
use std::f32::consts::FRAC_PI_4;
use std::path::PathBuf;

/// Single-precision round-off of the few products and sums in a transform chain.
const EPS: f32 = 1e-5;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/gltf")
        .join(name)
}

fn scene(name: &str) -> Scene {
    load(&data(name), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn error(name: &str) -> LoadError {
    match load(&data(name), &LoadOptions::default()) {
        Ok(_) => panic!("{name} loaded"),
        Err(e) => e,
    }
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < EPS
}

/// World positions of an instance's vertices.
fn world(s: &Scene, name: &str) -> Vec<Vec3> {
    let inst = s.instances.iter().find(|i| i.name == name).expect(name);
    s.meshes[inst.mesh]
        .positions
        .iter()
        .map(|&p| inst.transform.transform_point3(p))
        .collect()
}

fn surface_names(s: &Scene, name: &str) -> Vec<String> {
    let id = s.surface(name).expect(name);
    s.surfaces[id]
        .instances
        .iter()
        .map(|&i| s.instances[i].name.clone())
        .collect()
}

#[test]
fn hierarchy_gives_world_positions() {
    let s = scene("hierarchy.gltf");
    // Room = T(10,0,0)·R_y(90°)·S(2), R_y(90°): (x,y,z) → (z,y,−x); Table adds T(0,1,0).
    let table = world(&s, "Table");
    assert!(close(table[1], Vec3::new(10.0, 2.0, -2.0)), "{table:?}");
    // Cup adds T(0,0,1) under Table: (0,0,0) → (0,1,1) → (0,2,2) → (2,2,0) → (12,2,0).
    assert!(close(world(&s, "Cup")[0], Vec3::new(12.0, 2.0, 0.0)));
    // The unnamed node takes its mesh's name; (0,1,0) → (0,2,0) → (10,2,0).
    assert!(close(world(&s, "TriMesh")[2], Vec3::new(10.0, 2.0, 0.0)));
    assert!(close(world(&s, "Fan")[2], Vec3::new(1.0, 1.0, -5.0)));
    assert_eq!(s.up, Vec3::Y);
}

#[test]
fn names_cover_descendants_and_meshes_are_shared() {
    let s = scene("hierarchy.gltf");
    assert_eq!(surface_names(&s, "Room"), ["Table", "Cup", "TriMesh"]);
    assert_eq!(surface_names(&s, "Table"), ["Table", "Cup"]);
    assert_eq!(surface_names(&s, "Cup"), ["Cup"]);
    // Areas: quads of side 2 (scale 2) and a right triangle of legs 2.
    let area = |n| s.surface_area(s.surface(n).unwrap());
    assert!((area("Room") - 10.0).abs() < EPS);
    assert!((area("Table") - 8.0).abs() < EPS);
    // Table and Cup instance one glTF mesh: one scene mesh. Lines-only and
    // placement meshes make none; the orphan node is not placed.
    let mesh = |n: &str| s.instances.iter().find(|i| i.name == n).unwrap().mesh;
    assert_eq!(mesh("Table"), mesh("Cup"));
    // The mirrored node gets its own, rewound copy of the quad.
    assert_eq!(s.meshes.len(), 5);
    assert_eq!(s.instances.len(), 6);
    for gone in ["Wire", "Orphan", "Desk__Geometry"] {
        assert!(s.surface(gone).is_none(), "{gone}");
    }
}

#[test]
fn strips_fans_lines_and_unindexed_primitives() {
    let s = scene("hierarchy.gltf");
    for name in ["Strip", "Fan"] {
        let id = s.surface(name).unwrap();
        // The unit quad as two triangles; the strip's LINES primitive is skipped.
        assert_eq!(s.surface_triangles(id), 2, "{name}");
        assert!((s.surface_area(id) - 1.0).abs() < EPS, "{name}");
        let inst = &s.instances[s.surfaces[id].instances[0]];
        let mesh = &s.meshes[inst.mesh];
        for t in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(t);
            assert!(
                (b - a).cross(c - a).z > 0.0,
                "{name} triangle {t} turned over"
            );
        }
    }
    assert_eq!(s.surface_triangles(s.surface("TriMesh").unwrap()), 1);
}

#[test]
fn mirrored_node_keeps_its_front_face() {
    let s = scene("hierarchy.gltf");
    // glTF: under a transform of negative determinant the clockwise side is the front, so
    // the quad mirrored in x still faces +Z; the scene mesh is rewound to say so.
    for name in ["Mirrored", "Strip"] {
        let inst = s.instances.iter().find(|i| i.name == name).unwrap();
        let mesh = &s.meshes[inst.mesh];
        for t in 0..mesh.triangles.len() {
            let [a, b, c] = mesh.triangle(t).map(|p| inst.transform.transform_point3(p));
            assert!((b - a).cross(c - a).z > 0.0, "{name} triangle {t}");
        }
    }
}

#[test]
fn placement_keeps_distinct_vertices_in_file_order() {
    let s = scene("hierarchy.gltf");
    let p = s.placement("Desk__Geometry").expect("placement");
    let expected =
        [(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)].map(|(x, z)| Vec3::new(x, 1.0, z));
    assert_eq!(p.vertices, expected);
}

#[test]
fn punctual_lights_in_candela_and_lux() {
    let s = scene("hierarchy.gltf");
    let light = |n: &str| &s.lights[s.light(n).unwrap_or_else(|| panic!("{n}"))].kind;
    match light("Bulb") {
        LightKind::Point {
            position,
            intensity,
        } => {
            assert_eq!(*position, Vec3::new(1.0, 2.0, 3.0));
            assert_eq!(*intensity, Vec3::new(100.0, 50.0, 25.0));
        }
        k => panic!("{k:?}"),
    }
    match light("Spot") {
        LightKind::Spot {
            position,
            direction,
            intensity,
            inner,
            outer,
        } => {
            assert_eq!(*position, Vec3::new(0.0, 3.0, 0.0));
            assert!(close(*direction, Vec3::NEG_Y), "{direction}");
            assert_eq!(*intensity, Vec3::splat(50.0));
            assert_eq!((*inner, *outer), (0.2, 0.5));
        }
        k => panic!("{k:?}"),
    }
    // The unnamed node takes the light's name; R_y(90°) turns −Z into −X.
    match light("Sun") {
        LightKind::Directional {
            direction,
            illuminance,
        } => {
            assert!(close(*direction, Vec3::NEG_X), "{direction}");
            assert_eq!(*illuminance, Vec3::splat(1000.0));
        }
        k => panic!("{k:?}"),
    }
    match light("DefaultCone") {
        LightKind::Spot { inner, outer, .. } => assert_eq!((*inner, *outer), (0.0, FRAC_PI_4)),
        k => panic!("{k:?}"),
    }
    assert_eq!(s.lights.len(), 4);
}

#[test]
fn camera_from_node() {
    let s = scene("hierarchy.gltf");
    assert_eq!(s.cameras.len(), 1);
    let c = &s.cameras[0];
    assert_eq!(c.name, "Eye");
    assert_eq!(c.position, Vec3::new(0.0, 1.0, 5.0));
    assert!(close(c.forward, Vec3::NEG_X), "{}", c.forward);
    assert!(close(c.up, Vec3::Y), "{}", c.up);
    assert_eq!((c.yfov, c.aspect), (0.8, Some(1.5)));
}

#[test]
fn glb_equals_gltf() {
    assert_eq!(scene("hierarchy.gltf"), scene("hierarchy.glb"));
    // Textures from a data URI, a .glb buffer view and a file beside the .gltf.
    let embedded = scene("materials.gltf");
    assert_eq!(embedded, scene("materials.glb"));
    assert_eq!(embedded, scene("external.gltf"));
}

#[test]
fn materials_map_to_photon_tracing() {
    let s = scene("materials.gltf");
    let m = |n: &str| {
        let inst = s
            .instances
            .iter()
            .find(|i| i.name == n)
            .unwrap_or_else(|| panic!("{n}"));
        &s.materials[s.meshes[inst.mesh].materials[0]]
    };
    let lamp = m("Lamp");
    // emissiveFactor (1, 0.5, 0.25) × emissiveStrength 10, cd/m².
    assert_eq!(lamp.emission, Vec3::new(10.0, 5.0, 2.5));
    assert_eq!(lamp.diffuse, Vec3::ZERO);
    let mirror = m("Mirror");
    assert_eq!(
        (mirror.specular, mirror.diffuse),
        (Vec3::new(0.9, 0.8, 0.7), Vec3::ZERO)
    );
    assert_eq!(mirror.kind_name(), "mirror");
    // Default metallic 1 but roughness 0.5: taken as diffuse.
    let rough = m("RoughMetal");
    assert_eq!(
        (rough.diffuse, rough.specular),
        (Vec3::new(0.9, 0.8, 0.7), Vec3::ZERO)
    );
    let glass = m("Glass");
    assert_eq!(
        (glass.transmission, glass.ior, glass.diffuse),
        (1.0, 1.45, Vec3::ZERO)
    );
    assert_eq!(glass.kind_name(), "glass");
    // Half transmission replaces half the diffuse; ior defaults to 1.5.
    let half = m("HalfGlass");
    assert_eq!(
        (half.transmission, half.ior, half.diffuse),
        (0.5, 1.5, Vec3::splat(0.25))
    );
    assert!(m("Aperture").hole);
    assert!(!glass.hole);
    // No material: glTF's default, base colour 1.
    let plain = m("PlainMesh");
    assert_eq!((plain.diffuse, plain.kind_name()), (Vec3::ONE, "diffuse"));
}

#[test]
fn texture_is_decoded_to_linear() {
    let s = scene("materials.gltf");
    let inst = s.instances.iter().find(|i| i.name == "Checker").unwrap();
    let mesh = &s.meshes[inst.mesh];
    let mat = &s.materials[mesh.materials[0]];
    assert_eq!(mat.diffuse, Vec3::new(1.0, 0.5, 1.0));
    let tex = &s.textures[mat.texture.expect("texture")];
    assert_eq!((tex.width, tex.height), (2, 2));
    // sRGB 128 → ((128/255 + 0.055)/1.055)^2.4 (IEC 61966-2-1).
    let grey = ((128.0f32 / 255.0 + 0.055) / 1.055).powf(2.4);
    assert_eq!(
        tex.pixels,
        vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::splat(grey)]
    );
    assert_eq!(
        mesh.uvs,
        [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)].map(|(u, v)| Vec2::new(u, v))
    );
    // The second uv set when the texture names it; the image is decoded once.
    let set1 = s
        .instances
        .iter()
        .find(|i| i.name == "CheckerSet1")
        .unwrap();
    let set1 = &s.meshes[set1.mesh];
    assert_eq!(set1.uvs, mesh.uvs);
    assert_eq!(s.materials[set1.materials[0]].texture, mat.texture);
    assert_eq!(s.textures.len(), 1);
}

#[test]
fn room_from_peers() {
    let s = scene("room_area.gltf");
    let floor = s.surface("Floor").unwrap();
    assert!((s.surface_area(floor) - 6.0).abs() < EPS);
    let lamp = &s.instances[s.surfaces[s.surface("Lamp").unwrap()].instances[0]];
    let mat = &s.materials[s.meshes[lamp.mesh].materials[0]];
    assert_eq!(mat.emission, Vec3::splat(127.324));
}

#[test]
fn broken_files_name_the_place() {
    let e = error("missing_bin.gltf");
    assert_eq!(e.location, "buffers[0]");
    assert!(e.message.starts_with("missing file missing_bin.bin"), "{e}");
    assert!(e.hint.is_some());
    assert!(e.path.ends_with("missing_bin.gltf"));

    let e = error("bad_accessor.gltf");
    assert_eq!(e.location, "meshes[0].primitives[0].attributes.POSITION");
    assert!(e.message.contains("accessor 99 does not exist"), "{e}");

    let e = error("bad_index.gltf");
    assert_eq!(e.location, "meshes[0].primitives[0].indices");
    assert!(
        e.message.contains("is 7, but the primitive has 4 vertices"),
        "{e}"
    );

    let e = error("cycle.gltf");
    assert_eq!(e.location, "nodes[1].children[0]");
    assert!(e.message.contains("reached twice"), "{e}");

    let e = error("bad_mode.gltf");
    assert_eq!(e.location, "meshes[0].primitives[0]");
    assert!(e.message.contains("mode"), "{e}");

    let e = error("malformed.gltf");
    assert!(
        e.message.starts_with("malformed JSON") && e.message.contains("line"),
        "{e}"
    );

    let e = error("truncated.glb");
    assert_eq!(e.location, "GLB header");
    assert!(e.message.contains("the header says"), "{e}");
}

/// An emissive texture is refused with the material and the place named, not spread
/// evenly over the whole surface.
#[test]
fn emissive_textures_are_refused() {
    let e = error("emissive_texture.gltf");
    assert_eq!(e.location, "materials[0].emissiveTexture");
    assert!(e.message.contains("'Lantern'"), "{e}");
    assert!(e.hint.as_ref().unwrap().contains("emissiveFactor"), "{e}");
}
