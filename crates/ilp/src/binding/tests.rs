//! Binding tests on a small room built in code.

use super::*;
use glam::Vec3;
use invlight_scene::{Light, Material, Mesh, Placement};
use invlight_stats::SplitMix64;
use std::path::Path;

/// A 4 m × 3 m floor (z = 0, up = +Z), a box "Chair" with its corner at the origin,
/// a lamp, a sun, a window object, a placement rectangle on the floor.
fn scene() -> Scene {
    let mut s = Scene::default();
    s.up = Vec3::Z;
    let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let paint = s.add_material(Material::diffuse("Paint", Vec3::new(0.2, 0.4, 0.6)));
    let floor = s.add_mesh(Mesh::quad(
        [
            Vec3::ZERO,
            Vec3::new(4.0, 0.0, 0.0),
            Vec3::new(4.0, 3.0, 0.0),
            Vec3::new(0.0, 3.0, 0.0),
        ],
        paint,
    ));
    s.add_instance("Floor", floor, Mat4::IDENTITY);
    let cube = s.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::splat(0.5), grey));
    s.add_instance(
        "Chair",
        cube,
        Mat4::from_translation(Vec3::new(1.0, 1.0, 0.0)),
    );
    s.add_instance(
        "Window",
        cube,
        Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0)),
    );
    s.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Lamp".into(),
        kind: LightKind::Point {
            position: Vec3::new(1.0, 1.0, 2.5),
            intensity: Vec3::ONE,
        },
    });
    s.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: Vec3::new(0.0, 0.6, -0.8),
            illuminance: Vec3::ONE,
        },
    });
    s.placements.push(Placement {
        name: "Floor__Geometry".into(),
        vertices: vec![
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(3.0, 1.0, 0.0),
            Vec3::new(3.0, 2.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
        ],
    });
    s
}

fn problem(conditions: &str) -> Problem {
    Problem::parse(
        Path::new("/p/x.xml"),
        &format!(
            "<input><scene path=\"s.gltf\"/>\n<conditions meshSize=\"10\">\n{conditions}\n</conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>"
        ),
    )
    .unwrap()
}

#[test]
fn object_moves_by_p_minus_a() {
    let mut s = scene();
    let b = Binding::new(
        &problem("<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\"/>"),
        &mut s,
    )
    .unwrap();
    assert_eq!(b.initial.coords, vec![0.0, 0.0]);
    let config = Configuration {
        coords: vec![0.75, 0.5],
    };
    // P = (2.5, 1.5, 0); the chair's box [1, 1.5]² × [0, 0.5] moves with it, its
    // centre on the floor from (1.25, 1.25, 0) to (2.75, 1.75, 0).
    assert_eq!(
        b.values(&config),
        vec![VariableValue::Position {
            point: DVec3::new(2.5, 1.5, 0.0),
            anchor: DVec3::new(2.75, 1.75, 0.0)
        }]
    );
    assert!(b.apply(&mut s, &config));
    // Chair authored at A = (1, 1, 0): now at P.
    let t = s.instances[1].transform.w_axis.truncate();
    assert!((t - Vec3::new(2.5, 1.5, 0.0)).length() < 1e-6);
    assert!(!b.apply(&mut s, &config), "nothing moves twice");
    assert_eq!(b.movable_instances(), vec![InstanceId::from_index(1)]);
    assert_eq!(
        s.instances[2].transform.w_axis.truncate(),
        Vec3::new(0.0, 0.0, 2.0)
    );
}

/// A goniometric light (a photometric file in place of the point lamp) moves as the
/// point lamp would, keeping its aim.
#[test]
fn goniometric_light_moves_like_a_point_lamp() {
    let mut s = scene();
    s.up = Vec3::Z;
    let table = invlight_scene::Photometry::from_table(
        invlight_scene::PhotometricSystem::C,
        vec![0.0, 360.0],
        vec![0.0, 90.0],
        vec![100.0; 4],
    )
    .unwrap();
    s.set_photometry("Lamp", std::sync::Arc::new(table), 1.0)
        .unwrap();
    let b = Binding::new(
        &problem("<lightInSurface id=\"Lamp\" surface=\"Floor__Geometry\"/>"),
        &mut s,
    )
    .unwrap();
    let config = Configuration {
        coords: vec![0.75, 0.5],
    };
    // No instance moves, so nothing needs refitting.
    assert!(!b.apply(&mut s, &config));
    // Authored at (1, 1, 2.5), the rectangle's A at (1, 1, 0): moved by P − A.
    let kind = &s.lights[0].kind;
    assert_eq!(kind.name(), "goniometric");
    assert!((kind.position().unwrap() - Vec3::new(2.5, 1.5, 2.5)).length() < 1e-6);
    assert_eq!(kind.direction(), Some(Vec3::NEG_Z));
}

#[test]
fn light_hole_sun_and_colour() {
    let mut s = scene();
    let b = Binding::new(
        &problem(
            "<lightInSurface id=\"Lamp\" surface=\"Floor__Geometry\"/>\n<holeInSurface id=\"Window\" surface=\"Floor\" vertexAIndex=\"1\" vertexBIndex=\"0\" vertexCIndex=\"3\" vertexDIndex=\"2\"/>\n<directionalLight id=\"Sun\"/>\n<color id=\"Paint\" hue=\"120\" saturation=\"0.5\"/>",
        ),
        &mut s,
    )
    .unwrap();
    let kinds: Vec<&str> = b.specs.iter().map(|s| s.kind.name()).collect();
    assert_eq!(
        kinds,
        vec![
            "lightInSurface",
            "holeInSurface",
            "directionalLight",
            "color"
        ]
    );
    // The window's mesh became a hole; the chair sharing the cube mesh did not.
    let win = s.instances[2].mesh;
    assert!(s.meshes[win].materials.iter().all(|&m| s.materials[m].hole));
    assert!(!s.materials[s.meshes[s.instances[1].mesh].materials[0]].hole);
    // Initial sun coordinates reproduce its direction; initial V is Paint's 0.6.
    let init = b.values(&b.initial);
    match init[2] {
        VariableValue::Direction(d) => assert!((d - DVec3::new(0.0, 0.6, -0.8)).length() < 1e-6),
        _ => panic!(),
    }
    assert!((b.initial.coords[6] - 0.6).abs() < 1e-6);
    let config = Configuration {
        coords: vec![0.5, 1.0, 1.0, 0.0, 0.25, 0.0, 0.8],
    };
    assert!(b.apply(&mut s, &config));
    assert_eq!(s.lights[0].kind.position(), Some(Vec3::new(2.0, 2.0, 2.5)));
    // Hole on the floor quad: A is vertex 1 (4, 0, 0), B vertex 0: s runs towards −x,
    // so (s, t) = (1, 0) is the origin and the window moves by (−4, 0, 0).
    let w = s.instances[2].transform.w_axis.truncate();
    assert!((w - Vec3::new(-4.0, 0.0, 2.0)).length() < 1e-6, "{w}");
    // θ = 0: the sun straight down.
    assert!((s.lights[1].kind.direction().unwrap() + Vec3::Z).length() < 1e-6);
    // V = 0.8, hue 120°, saturation 0.5: (0.4, 0.8, 0.4).
    assert!((s.materials[1].diffuse - Vec3::new(0.4, 0.8, 0.4)).length() < 1e-6);
}

#[test]
fn a_colour_variable_replaces_a_texture() {
    // A textured Paint would make the variable "HSV × texture": the binding drops
    // the texture and says so; an untextured colour gives no warning.
    let mut s = scene();
    let colour = problem("<color id=\"Paint\" hue=\"120\" saturation=\"0.5\"/>");
    assert!(Binding::new(&colour, &mut s).unwrap().warnings.is_empty());
    let green = s.add_texture(invlight_scene::Texture {
        width: 1,
        height: 1,
        pixels: vec![Vec3::new(0.1, 0.9, 0.1)],
    });
    let paint = s.materials.iter().position(|m| m.name == "Paint").unwrap();
    s.materials[paint].texture = Some(green);
    let b = Binding::new(&colour, &mut s).unwrap();
    assert_eq!(s.materials[paint].texture, None);
    assert_eq!(b.warnings.len(), 1);
    assert!(
        b.warnings[0].message.contains("'Paint'"),
        "{}",
        b.warnings[0]
    );
}

#[test]
fn bad_names_and_quads_name_the_line() {
    let mut s = scene();
    let e = Binding::new(
        &problem(
            "<directionalLight id=\"Sun\"/>\n<objectInSurface id=\"Table\" surface=\"Floor\"/>",
        ),
        &mut s,
    )
    .unwrap_err();
    assert_eq!(e.line, Some(4));
    assert!(
        e.message.contains("'Table'") && e.hint.as_ref().unwrap().contains("Chair"),
        "{e}"
    );
    let e = Binding::new(&problem("<directionalLight id=\"Lamp\"/>"), &mut s).unwrap_err();
    assert!(e.message.contains("directional"), "{e}");
    s.placements[0].vertices[2].z = 0.5;
    let e = Binding::new(
        &problem("<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\"/>"),
        &mut s,
    )
    .unwrap_err();
    assert!(e.message.contains("not a planar quad"), "{e}");
    let e = Binding::new(
        &problem("<objectInSurface id=\"Chair\" surface=\"Chair\"/>"),
        &mut s,
    )
    .unwrap_err();
    assert!(e.message.contains("more than 4 distinct vertices"), "{e}");
}

/// `anchor="centre"` puts the object's own centre (on the placement plane) at P; the
/// default, ILPSolver's P − A, keeps the chair's offset from vertex A and says so.
#[test]
fn the_anchor_is_where_the_object_is() {
    let mut s = scene();
    let vertex_a = Binding::new(
        &problem("<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\"/>"),
        &mut s,
    )
    .unwrap();
    assert_eq!(vertex_a.warnings.len(), 1, "{:?}", vertex_a.warnings);
    assert!(
        vertex_a.warnings[0]
            .message
            .contains("0.354 m from vertex A"),
        "{}",
        vertex_a.warnings[0]
    );
    let mut s = scene();
    let centre = Binding::new(
        &problem("<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\" anchor=\"centre\"/>"),
        &mut s,
    )
    .unwrap();
    assert!(centre.warnings.is_empty(), "{:?}", centre.warnings);
    // Authored with its centre at (1.25, 1.25) of the rectangle [1, 3] × [1, 2].
    assert_eq!(centre.initial.coords, vec![0.125, 0.25]);
    let config = Configuration {
        coords: vec![0.5, 0.5],
    };
    let VariableValue::Position { point, anchor } = centre.values(&config)[0] else {
        panic!("a position")
    };
    assert_eq!(point, DVec3::new(2.0, 1.5, 0.0));
    assert_eq!(anchor, point);
    centre.apply(&mut s, &config);
    let corner = s.instances[1].transform.w_axis.truncate();
    assert!(
        (corner - Vec3::new(1.75, 1.25, 0.0)).length() < 1e-6,
        "{corner}"
    );
}

/// A candidate that puts the chair beyond everything else in the scene is refused;
/// inside it is not.
#[test]
fn candidates_outside_the_scene_are_refused() {
    let mut s = scene();
    s.placements.push(Placement {
        name: "Wide__Geometry".into(),
        vertices: vec![
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(6.0, 1.0, 0.0),
            Vec3::new(6.0, 2.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
        ],
    });
    let b = Binding::new(
        &problem("<objectInSurface id=\"Chair\" surface=\"Wide__Geometry\"/>"),
        &mut s,
    )
    .unwrap();
    assert_eq!(
        b.leaves_scene(&Configuration {
            coords: vec![0.5, 0.5]
        }),
        None
    );
    // P at x = 5.5: the chair's box [5.5, 6] is past the floor's x = 4.
    assert_eq!(
        b.leaves_scene(&Configuration {
            coords: vec![0.9, 0.5]
        }),
        Some("Chair")
    );
}

/// A hole as large as its placement rectangle would remove the whole wall wherever it
/// goes: refused, with both sizes.
#[test]
fn a_hole_larger_than_its_wall_is_refused() {
    let mut s = scene();
    let big = s.add_mesh(Mesh::cuboid(
        Vec3::ZERO,
        Vec3::new(2.5, 1.5, 0.5),
        s.meshes[0].materials[0],
    ));
    s.add_instance("Skylight", big, Mat4::IDENTITY);
    let e = Binding::new(
        &problem("<holeInSurface id=\"Skylight\" surface=\"Floor__Geometry\"/>"),
        &mut s,
    )
    .unwrap_err();
    assert!(
        e.message.contains("2.500 m × 1.500 m") && e.message.contains("2.000 m × 1.000 m"),
        "{e}"
    );
    assert!(
        Binding::new(
            &problem("<holeInSurface id=\"Window\" surface=\"Floor__Geometry\"/>"),
            &mut s
        )
        .is_ok()
    );
}

/// `minimizePower` counts watts when every electric light has them and lumens
/// otherwise, and says which (the sun costs nothing either way).
#[test]
fn power_in_watts_when_every_lamp_has_them() {
    let least = |s: &mut Scene| {
        let p = Problem::parse(
            Path::new("/p/x.xml"),
            "<input><scene path=\"s.gltf\"/><conditions meshSize=\"10\"><lightPower id=\"Lamp\" min=\"0\" max=\"1\"/></conditions><objectives><minimizePower/><minLux surface=\"Floor\" value=\"1\"/></objectives></input>",
        )
        .unwrap();
        Binding::new(&p, s).unwrap()
    };
    let half = Configuration { coords: vec![0.5] };
    // A 1 cd point lamp sends 4π lm; it has no watts.
    let mut s = scene();
    let b = least(&mut s);
    assert_eq!((b.power_unit, b.goal_unit()), (PowerUnit::Lumens, "lm"));
    assert!((b.power(&half) - 0.5 * 4.0 * std::f64::consts::PI).abs() < 1e-4);
    // A 20 W file at multiplier 2 is two such lamps: 40 W, half of it at level 0.5.
    let mut table = invlight_scene::Photometry::from_table(
        invlight_scene::PhotometricSystem::C,
        vec![0.0, 360.0],
        vec![0.0, 90.0],
        vec![100.0; 4],
    )
    .unwrap();
    table.watts = Some(20.0);
    let table = std::sync::Arc::new(table);
    s.set_photometry("Lamp", table.clone(), 2.0).unwrap();
    let b = least(&mut s);
    assert_eq!((b.power_unit, b.goal_unit()), (PowerUnit::Watts, "W"));
    assert!((b.power(&half) - 20.0).abs() < 1e-9, "{}", b.power(&half));
    // One lamp without watts: lumens for all, not a sum of watts and lumens.
    s.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Bare".into(),
        kind: LightKind::Point {
            position: Vec3::new(2.0, 1.0, 2.5),
            intensity: Vec3::ONE,
        },
    });
    let b = least(&mut s);
    assert_eq!(b.power_unit, PowerUnit::Lumens);
    let flux = 2.0 * table.flux() * 0.5 + 4.0 * std::f64::consts::PI;
    assert!(
        (b.power(&half) - flux).abs() < 1e-3 * flux,
        "{} vs {flux}",
        b.power(&half)
    );
}

/// `lightAim` turns a luminaire's whole frame from its authored one by the shortest
/// rotation (C0 turns with the aim), refuses a light without an aim and a tilt outside
/// (0, 90], and shares an id with the light's placement and dimming.
#[test]
fn light_aim_turns_the_frame() {
    let mut s = scene();
    let table = invlight_scene::Photometry::from_table(
        invlight_scene::PhotometricSystem::C,
        vec![0.0, 360.0],
        vec![0.0, 90.0],
        vec![100.0; 4],
    )
    .unwrap();
    let e = Binding::new(&problem("<lightAim id=\"Lamp\" maxTilt=\"30\"/>"), &mut s).unwrap_err();
    assert!(
        e.to_string().contains("no spot or luminaire named 'Lamp'"),
        "{e}"
    );
    s.set_photometry("Lamp", std::sync::Arc::new(table), 1.0)
        .unwrap();
    let p = problem(
        "<lightInSurface id=\"Lamp\" surface=\"Floor__Geometry\"/><lightPower id=\"Lamp\"/><lightAim id=\"Lamp\" maxTilt=\"30\"/>",
    );
    let keys: Vec<String> = (0..3).map(|i| VariableSpec::key(&p.variables, i)).collect();
    assert_eq!(keys, ["Lamp", "Lamp.power", "Lamp.aim"]);
    let b = Binding::new(&p, &mut s).unwrap();
    // The table sends 100 cd into the lower hemisphere: 200π lm, recorded for run.json.
    assert_eq!(b.luminaires.len(), 1);
    assert_eq!(b.luminaires[0].light, "Lamp");
    assert!(
        (b.luminaires[0].lm - 200.0 * std::f64::consts::PI).abs() < 0.5,
        "{:?}",
        b.luminaires
    );
    // θ = 30° (the cone's edge) at φ = 0: the cone about the authored aim −Z has
    // zenith +Z and φ = 0 along +X, and the light comes from there, so it travels
    // toward −X.
    let config = Configuration {
        coords: vec![0.0, 0.0, 1.0, 0.0, 1.0],
    };
    b.apply(&mut s, &config);
    let LightKind::Goniometric { frame, .. } = s.lights[0].kind else {
        panic!("a luminaire");
    };
    let aim = Vec3::new(-0.5, 0.0, -(3f32.sqrt()) / 2.0);
    assert!((-frame.z_axis - aim).length() < 1e-5, "{:?}", -frame.z_axis);
    // C0 (+X as authored) tilts with the aim, about +Y.
    let c0 = Vec3::new(3f32.sqrt() / 2.0, 0.0, -0.5);
    assert!((frame.x_axis - c0).length() < 1e-5, "{:?}", frame.x_axis);
    assert!((frame.y_axis - Vec3::Y).length() < 1e-5);
    for (bad, says) in [
        ("<lightAim id=\"Lamp\" maxTilt=\"95\"/>", "maxTilt"),
        ("<lightAim id=\"Lamp\"/>", "needs 'maxTilt'"),
        (
            "<lightAim id=\"Lamp\" maxTilt=\"9\"/><lightAim id=\"Lamp\" maxTilt=\"9\"/>",
            "a second variable",
        ),
    ] {
        let text = format!(
            "<input><scene path=\"s.gltf\"/><conditions>{bad}</conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>"
        );
        let e = Problem::parse(Path::new("/p/x.xml"), &text).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
    }
}

/// `holeSize` makes its object an aperture scaled about its authored centre; placed
/// as well, it is scaled first and then moved, and both keys are kept apart.
#[test]
fn hole_size_scales_then_moves() {
    let mut s = scene();
    let p = problem(
        "<holeInSurface id=\"Window\" surface=\"Floor__Geometry\" anchor=\"centre\"/><holeSize id=\"Window\" minScale=\"1\" maxScale=\"2\"/>",
    );
    let keys: Vec<String> = (0..2).map(|i| VariableSpec::key(&p.variables, i)).collect();
    assert_eq!(keys, ["Window", "Window.size"]);
    let b = Binding::new(&p, &mut s).unwrap();
    let window = InstanceId::from_index(2);
    assert!(
        s.meshes[s.instances[window].mesh]
            .materials
            .iter()
            .all(|&m| s.materials[m].hole)
    );
    assert_eq!(b.movable_instances(), vec![window]);
    assert_eq!(b.values(&b.initial)[1], VariableValue::Scale(1.0));
    // P = (2, 1.5, 0); the window's box [0, 0.5]² × [2, 2.5] has its centre
    // (0.25, 0.25, 2.25), on the floor's plane (0.25, 0.25, 0): moved by (1.75, 1.25, 0)
    // after doubling about its centre, its corner (0, 0, 2) goes to (1.5, 1, 1.75).
    let config = Configuration {
        coords: vec![0.5, 0.5, 1.0],
    };
    assert!(b.apply(&mut s, &config));
    let corner = s.instances[window].transform.transform_point3(Vec3::ZERO);
    assert!(
        (corner - Vec3::new(1.5, 1.0, 1.75)).length() < 1e-5,
        "{corner}"
    );
    // Sized alone, it stays where it is.
    let mut s = scene();
    let b = Binding::new(&problem("<holeSize id=\"Window\"/>"), &mut s).unwrap();
    b.apply(&mut s, &Configuration { coords: vec![1.0] });
    let corner = s.instances[window].transform.transform_point3(Vec3::ZERO);
    assert!(
        (corner - Vec3::new(-0.25, -0.25, 1.75)).length() < 1e-5,
        "{corner}"
    );
    for (bad, says) in [
        ("<holeSize id=\"Window\" minScale=\"0\"/>", "minScale"),
        (
            "<holeSize id=\"Window\" minScale=\"2\" maxScale=\"1\"/>",
            "minScale 2 ≥ maxScale 1",
        ),
    ] {
        let text = format!(
            "<input><scene path=\"s.gltf\"/><conditions>{bad}</conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>"
        );
        let e = Problem::parse(Path::new("/p/x.xml"), &text).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
    }
}

/// `objectRotation` turns an object about its placement's normal through its box's
/// centre, then moves it; it is refused beside a `lightAim` of the same light.
#[test]
fn object_rotation_turns_then_moves() {
    let mut s = scene();
    let p = problem(
        "<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\"/><objectRotation id=\"Chair\" min=\"0\" max=\"180\"/>",
    );
    assert_eq!(VariableSpec::key(&p.variables, 1), "Chair.rotation");
    let b = Binding::new(&p, &mut s).unwrap();
    assert_eq!(b.values(&b.initial)[1], VariableValue::Angle(0.0));
    // 90° about the floor's normal (+Z) through the chair's centre (1.25, 1.25, 0.25):
    // its corner (1, 1, 0) goes to (1.5, 1, 0); then P − A = (1.5, 0.5, 0) moves it to
    // (3, 1.5, 0).
    let config = Configuration {
        coords: vec![0.75, 0.5, 0.5],
    };
    assert!(b.apply(&mut s, &config));
    let chair = InstanceId::from_index(1);
    let corner = s.instances[chair].transform.transform_point3(Vec3::ZERO);
    assert!(
        (corner - Vec3::new(3.0, 1.5, 0.0)).length() < 1e-5,
        "{corner}"
    );
    let text = "<input><scene path=\"s.gltf\"/><conditions><lightAim id=\"L\" maxTilt=\"9\"/><objectRotation id=\"L\"/></conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>";
    let e = Problem::parse(Path::new("/p/x.xml"), text).unwrap_err();
    assert!(e.to_string().contains("a second variable"), "{e}");
    let text = text.replace(
        "<lightAim id=\"L\" maxTilt=\"9\"/><objectRotation id=\"L\"/>",
        "<objectRotation id=\"L\" min=\"0\" max=\"400\"/>",
    );
    let e = Problem::parse(Path::new("/p/x.xml"), &text).unwrap_err();
    assert!(e.to_string().contains("min + 360"), "{e}");
}

/// A whole turn (`max = min + 360`) is a [`Domain::Turn`]: its neighbourhoods cross 0°
/// (from 355° a small step reaches 5°, which a segment never offers), and 360° maps back
/// to the configuration of 0°; a part of a turn stays a segment.
#[test]
fn object_rotation_full_turn_wraps() {
    let mut s = scene();
    let p = problem(
        "<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\"/><objectRotation id=\"Chair\" min=\"0\" max=\"360\"/>",
    );
    let b = Binding::new(&p, &mut s).unwrap();
    assert_eq!(
        b.space.variables()[1].domain,
        Domain::Turn {
            min: 0.0,
            max: 360.0
        }
    );
    let near_end = Configuration {
        coords: vec![0.5, 0.5, 355.0 / 360.0],
    };
    let mut rng = SplitMix64::new(3);
    let angles: Vec<f64> = (0..400)
        .map(
            |_| match b.values(&b.space.neighbour(&near_end, 0.05, &mut rng))[1] {
                VariableValue::Angle(a) => a,
                ref v => panic!("{v:?}"),
            },
        )
        .collect();
    assert!(
        angles.iter().all(|&a| !(15.0..=340.0).contains(&a)),
        "±9° of 355°"
    );
    assert!(angles.iter().any(|&a| a < 5.0), "the step crosses 0°");
    let at_0 = b
        .configuration(&[b.values(&b.initial)[0], VariableValue::Angle(0.0)])
        .unwrap();
    let at_360 = b
        .configuration(&[b.values(&b.initial)[0], VariableValue::Angle(360.0)])
        .unwrap();
    assert_eq!(at_0, at_360);
    let part = problem(
        "<objectInSurface id=\"Chair\" surface=\"Floor__Geometry\"/><objectRotation id=\"Chair\" min=\"-90\" max=\"90\"/>",
    );
    let b = Binding::new(&part, &mut scene()).unwrap();
    assert!(matches!(
        b.space.variables()[1].domain,
        Domain::Segment { .. }
    ));
}

/// An IES file's TILT factors follow the aim a search gives the luminaire (LM-63 §5.4:
/// the factor at the lamp's angle from straight down), and dimming, which sets the
/// multiplier, leaves them: a floodlight aimed 30° off the vertical and dimmed to 50 %
/// sends 0.5 × 0.97 of its table, whatever the order of the variables.
#[test]
fn light_aim_recomputes_the_tilt_factor() {
    let mut table = invlight_scene::Photometry::from_table(
        invlight_scene::PhotometricSystem::C,
        vec![0.0, 360.0],
        vec![0.0, 90.0],
        vec![100.0; 4],
    )
    .unwrap();
    table.tilt = Some(invlight_scene::Tilt {
        geometry: 1,
        angles: vec![0.0, 30.0, 60.0],
        factors: vec![1.0, 0.97, 0.9],
    });
    for conditions in [
        "<lightPower id=\"Lamp\"/><lightAim id=\"Lamp\" maxTilt=\"60\"/>",
        "<lightAim id=\"Lamp\" maxTilt=\"60\"/><lightPower id=\"Lamp\"/>",
    ] {
        let mut s = scene();
        s.set_photometry("Lamp", std::sync::Arc::new(table.clone()), 1.0)
            .unwrap();
        let b = Binding::new(&problem(conditions), &mut s).unwrap();
        let power_first = conditions.starts_with("<lightPower");
        // Level 0.5 of [0, 1]; the aim at half the cone's 60°.
        let coords = if power_first {
            vec![0.5, 0.0, 0.5]
        } else {
            vec![0.0, 0.5, 0.5]
        };
        b.apply(&mut s, &Configuration { coords });
        let kind = &s.lights[0].kind;
        let aim = kind.direction().unwrap();
        assert!((aim.dot(Vec3::NEG_Z) - 30f32.to_radians().cos()).abs() < 1e-5);
        let on_axis = kind.intensity_toward(aim).x;
        assert!(
            (on_axis - 100.0 * 0.5 * 0.97).abs() < 1e-3,
            "{conditions}: {on_axis}"
        );
    }
}

/// Two spots of one `<lightGroup>`: one level dims both, one aim turns both alike, and
/// placed on one rectangle they are interchangeable members (placements alone: the
/// level and aim are the group's).
#[test]
fn a_light_group_shares_one_level_and_one_aim() {
    let mut s = scene();
    for (name, x) in [("A", 1.5f32), ("B", 2.5)] {
        s.lights.push(Light {
            c0: invlight_scene::Vec3::X,
            name: name.into(),
            kind: LightKind::Spot {
                position: Vec3::new(x, 1.5, 2.5),
                direction: -Vec3::Z,
                intensity: Vec3::splat(100.0),
                inner: 0.3,
                outer: 0.6,
            },
        });
    }
    let conditions = "<lightGroup id=\"G\" lights=\"A B\"/>
        <lightInSurface id=\"A\" surface=\"Floor__Geometry\" anchor=\"centre\"/>
        <lightInSurface id=\"B\" surface=\"Floor__Geometry\" anchor=\"centre\"/>
        <lightPower id=\"G\" min=\"0.1\" max=\"1\"/>
        <lightAim id=\"G\" maxTilt=\"30\"/>";
    let p = problem(conditions);
    assert_eq!(p.groups.len(), 1);
    let b = Binding::new(&p, &mut s).unwrap();
    assert_eq!(b.space.exchangeable(), &[vec![vec![0], vec![1]]]);
    // Both spots in the group's component, the undimmed lamp and sun in component 0.
    assert_eq!(b.component_count(), 2);
    let (a, bb) = (s.light("A").unwrap(), s.light("B").unwrap());
    let Target::Power {
        dimmed: Dimmed::Group(g),
        component: 1,
    } = &b.targets[2]
    else {
        panic!("the group's one level: {:?}", b.targets[2]);
    };
    assert_eq!(g.iter().map(|(l, _)| *l).collect::<Vec<_>>(), [a, bb]);
    // Level 0.1 + 0.5 × 0.9 = 0.55, and the aim at the cone's edge (θ = 30°, φ = 0).
    let config = Configuration {
        coords: vec![0.25, 0.5, 0.75, 0.5, 0.5, 0.0, 1.0],
    };
    assert_eq!(b.levels(&config), vec![1.0, 0.55]);
    b.apply(&mut s, &config);
    let aim = Vec3::new(-0.5, 0.0, -(3f32.sqrt()) / 2.0);
    for l in [a, bb] {
        let LightKind::Spot {
            direction,
            intensity,
            ..
        } = s.lights[l].kind
        else {
            panic!("a spot");
        };
        assert!((direction - aim).length() < 1e-5, "{direction:?}");
        assert!((intensity.x - 55.0).abs() < 1e-4, "{intensity:?}");
    }
}

#[test]
fn light_group_mistakes_name_the_lamp() {
    let bad = |conditions: &str, says: &str| {
        let mut s = scene();
        let e = Problem::parse(
            Path::new("/p/x.xml"),
            &format!(
                "<input><scene path=\"s.gltf\"/><conditions>{conditions}</conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>"
            ),
        )
        .and_then(|p| Binding::new(&p, &mut s).map(|_| ()));
        let e = e.unwrap_err().to_string();
        assert!(e.contains(says), "{e}");
    };
    bad(
        "<lightGroup id=\"G\" lights=\"Lamp Nope\"/><lightPower id=\"G\"/>",
        "no light named 'Nope'",
    );
    bad(
        "<lightGroup id=\"G\" lights=\"Lamp\"/><lightPower id=\"G\"/>",
        "expected two or more",
    );
    bad(
        "<lightGroup id=\"Lamp\" lights=\"Lamp Sun\"/><lightPower id=\"Lamp\"/>",
        "also a light's name",
    );
    bad(
        "<lightGroup id=\"G\" lights=\"Lamp Sun\"/><lightGroup id=\"H\" lights=\"Sun Lamp\"/><lightPower id=\"G\"/>",
        "in <lightGroup id=\"G\"> already",
    );
    bad(
        "<lightGroup id=\"G\" lights=\"Lamp Sun\"/><lightPower id=\"G\"/><lightPower id=\"Lamp\"/>",
        "a second <lightPower>",
    );
}

/// Four like lamps placed on one rectangle, dimmed as one group: set out on a 2 × 2
/// grid they read as that array, its spacing and distance from the room's walls (the
/// scene's bounds: the 4 m × 3 m floor) with the group's level; moved off it, as
/// irregular.
#[test]
fn interchangeable_lamps_read_as_the_array_they_form() {
    let mut s = scene();
    for name in ["A", "B", "C", "D"] {
        s.lights.push(Light {
            c0: invlight_scene::Vec3::X,
            name: name.into(),
            kind: LightKind::Point {
                position: Vec3::new(2.0, 1.5, 2.5),
                intensity: Vec3::splat(100.0),
            },
        });
    }
    let mut conditions = "<lightGroup id=\"G\" lights=\"A B C D\"/>".to_string();
    for name in ["A", "B", "C", "D"] {
        conditions += &format!(
            "<lightInSurface id=\"{name}\" surface=\"Floor__Geometry\" anchor=\"centre\"/>"
        );
    }
    conditions += "<lightPower id=\"G\" min=\"0.1\" max=\"1\"/>";
    let b = Binding::new(&problem(&conditions), &mut s).unwrap();
    // The rectangle runs 1–3 m along x and 1–2 m along y: (s, t) = (¼, ¾) × (¼, ¾) is
    // x = 1.5, 2.5 and y = 1.25, 1.75; the level 0.1 + 0.5 × 0.9.
    let grid = Configuration {
        coords: vec![0.75, 0.25, 0.25, 0.25, 0.75, 0.75, 0.25, 0.75, 0.5],
    };
    let [layout] = &b.layouts(&grid)[..] else {
        panic!("one group: {:?}", b.layouts(&grid));
    };
    assert_eq!(layout.lights, ["A", "B", "C", "D"]);
    assert_eq!(layout.levels, [0.55; 4]);
    let array = layout.array.as_ref().expect("a 2 × 2 array");
    assert_eq!((array.columns, array.rows), (2, 2));
    let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() < 1e-6 && (a[1] - b[1]).abs() < 1e-6;
    assert!(close(array.spacing, [1.0, 0.5]), "{:?}", array.spacing);
    assert!(
        close(array.from_walls.unwrap(), [1.5, 1.25]),
        "{:?}",
        array.from_walls
    );
    assert_eq!(
        layout.description,
        "A … D on Floor__Geometry: a 2 × 2 array (2 rows of 2), 1.00 m × 0.50 m apart, 1.50 m × 1.25 m from the walls; all at 55 %"
    );
    let mut moved = grid.clone();
    moved.coords[6] = 0.95;
    let layout = &b.layouts(&moved)[0];
    assert!(layout.array.is_none() && layout.description.contains("irregular"));
}

/// The test scene with six identical point lamps L1 … L6 2.5 m above the floor.
fn scene_with_six_lamps() -> Scene {
    let mut s = scene();
    for k in 1..=6 {
        s.lights.push(Light {
            c0: invlight_scene::Vec3::X,
            name: format!("L{k}"),
            kind: LightKind::Point {
                position: Vec3::new(0.5 * k as f32, 0.5, 2.5),
                intensity: Vec3::splat(100.0),
            },
        });
    }
    s
}

#[test]
fn an_array_sets_out_its_lamps_and_leaves_the_rest_off() {
    let mut s = scene_with_six_lamps();
    let b = Binding::new(
        &problem(
            "<lightArray id=\"Grid\" lights=\"L1 … L6\" surface=\"Floor__Geometry\" columns=\"1..3\" rows=\"1..2\"/>",
        ),
        &mut s,
    )
    .unwrap();
    let shape = |columns, rows| {
        b.configuration(&[VariableValue::Array(crate::space::ArrayShape {
            columns,
            rows,
            walls: [0.5, 0.5],
            orientation: None,
        })])
        .unwrap()
    };
    let two_by_two = shape(2, 2);
    b.apply(&mut s, &two_by_two);
    // The rectangle runs 1–3 m along x and 1–2 m along y: half a spacing from its
    // edges, two columns stand at x = 1.5, 2.5 and two rows at y = 1.25, 1.75, each
    // lamp at its authored 2.5 m.
    let at = |name: &str| s.lights[s.light(name).unwrap()].kind.position().unwrap();
    for (name, x, y) in [
        ("L1", 1.5, 1.25),
        ("L2", 2.5, 1.25),
        ("L3", 1.5, 1.75),
        ("L4", 2.5, 1.75),
    ] {
        assert!(
            at(name).distance(Vec3::new(x, y, 2.5)) < 1e-5,
            "{name} at {}",
            at(name)
        );
    }
    // L5 and L6 emit nothing, so a trace spends no photon on them, and draw nothing.
    let lamp_flux = 4.0 * std::f64::consts::PI * 100.0;
    let emitted = |s: &Scene| {
        let e = Emitters::new(s);
        (0..e.len() as u32)
            .filter(|&i| {
                matches!(e.origin(i), SourceOrigin::Light(l) if s.lights[l].name.starts_with("L")
                && s.lights[l].name != "Lamp")
            })
            .map(|i| e.flux(i))
            .sum::<f64>()
    };
    // The scene's own "Lamp" (1 cd) is the rest of the power.
    let other = 4.0 * std::f64::consts::PI;
    assert!((emitted(&s) - 4.0 * lamp_flux).abs() < 1e-3 * lamp_flux);
    assert!((b.power(&two_by_two) - 4.0 * lamp_flux - other).abs() < 1e-3 * lamp_flux);
    // A larger array turns them back on.
    let three_by_two = shape(3, 2);
    b.apply(&mut s, &three_by_two);
    assert!((emitted(&s) - 6.0 * lamp_flux).abs() < 1e-3 * lamp_flux);
    assert!((b.power(&three_by_two) - 6.0 * lamp_flux - other).abs() < 1e-3 * lamp_flux);
    let [layout] = &b.layouts(&two_by_two)[..] else {
        panic!("one array: {:?}", b.layouts(&two_by_two));
    };
    assert_eq!(layout.lights, ["L1", "L2", "L3", "L4"]);
    assert_eq!(layout.off, ["L5", "L6"]);
    assert_eq!(
        layout.description,
        "Grid: L1 … L4 on Floor__Geometry: a 2 × 2 array (2 rows of 2), 1.00 m × 0.50 m apart, 1.50 m × 1.25 m from the walls; all at 100 %; L5 and L6 off"
    );
    // The value goes to the outputs and back to the same cell.
    let values = b.values(&two_by_two);
    assert_eq!(b.configuration(&values).unwrap(), two_by_two);
    assert_eq!(b.refusal(&two_by_two), None);
}

#[test]
fn an_array_larger_than_its_lamps_is_refused_and_its_id_dims_them_all() {
    let mut s = scene_with_six_lamps();
    let b = Binding::new(
        &problem(
            "<lightArray id=\"Grid\" lights=\"L1 L2 L3 L4\" surface=\"Floor__Geometry\" columns=\"1..3\" rows=\"2\"/>\n<lightPower id=\"Grid\" min=\"0.1\" max=\"1\"/>",
        ),
        &mut s,
    )
    .unwrap();
    let config = |columns, level: f64| {
        b.configuration(&[
            VariableValue::Array(crate::space::ArrayShape {
                columns,
                rows: 2,
                walls: [0.5, 0.5],
                orientation: None,
            }),
            VariableValue::Power(level),
        ])
        .unwrap()
    };
    let refusal = b.refusal(&config(3, 1.0)).expect("6 lamps of 4");
    assert!(
        refusal.contains("3 × 2 = 6 lamps and 'Grid' has 4"),
        "{refusal}"
    );
    // One level for the array: four lamps at 0.595 (a cell's centre) draw 0.595 of four lamps' flux; L5,
    // L6 and the scene's 1 cd "Lamp", in no array, stay at full output.
    let lamp = 4.0 * std::f64::consts::PI * 100.0;
    let others = 2.0 * lamp + 4.0 * std::f64::consts::PI;
    let dimmed = config(2, 0.595);
    let expected = 0.595 * 4.0 * lamp + others;
    assert!(
        (b.power(&dimmed) - expected).abs() < 1e-3 * lamp,
        "{}",
        b.power(&dimmed)
    );
    // One column of two lamps: the two others off, neither drawing at any level.
    let one_column = config(1, 0.595);
    assert!((b.power(&one_column) - (0.595 * 2.0 * lamp + others)).abs() < 1e-3 * lamp);
    assert!(
        b.layouts(&dimmed)[0]
            .levels
            .iter()
            .all(|&l| (l - 0.595).abs() < 1e-12)
    );
}

#[test]
fn a_lamp_placed_twice_is_refused_at_the_second_placement() {
    let mut s = scene_with_six_lamps();
    let err = Binding::new(
        &problem(
            "<lightArray id=\"Grid\" lights=\"L1 … L4\" surface=\"Floor__Geometry\" columns=\"2\" rows=\"2\"/>\n<lightInSurface id=\"L3\" surface=\"Floor__Geometry\"/>",
        ),
        &mut s,
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("x.xml:4") && err.contains("'L3' is placed by <lightArray id=\"Grid\"> (line 3) and by <lightInSurface id=\"L3\">"),
        "{err}"
    );
}

/// A lamp's frame set by two variables is refused at the second: a rotation of a lamp
/// whose array searches its orientation, and an aim of a continuous row.
#[test]
fn a_lamp_turned_by_its_array_and_another_variable_is_refused() {
    let refused = |variables: &str| {
        let mut s = scene_with_six_lamps();
        Binding::new(&problem(variables), &mut s)
            .unwrap_err()
            .to_string()
    };
    let err = refused(
        "<lightArray id=\"Grid\" lights=\"L1 … L4\" surface=\"Floor__Geometry\" columns=\"2\" rows=\"2\" orientation=\"search\"/>\n<objectRotation id=\"L2\"/>",
    );
    assert!(
        err.contains("x.xml:4")
            && err.contains(
                "<objectRotation id=\"L2\"> turns a lamp of <lightArray id=\"Grid\"> (line 3)"
            )
            && err.contains("orientation=\"search\""),
        "{err}"
    );
    let err = refused(
        "<lightArray id=\"Grid\" lights=\"L1 … L4\" surface=\"Floor__Geometry\" columns=\"2\" rows=\"2\" continuous=\"true\"/>\n<lightAim id=\"Grid\" maxTilt=\"20\"/>",
    );
    assert!(
        err.contains("x.xml:4") && err.contains("continuous=\"true\""),
        "{err}"
    );
}

/// A CIE clear sky is drawn about the sun: under a `<sunTime>` variable it follows each
/// time's sun, and with the sun below the horizon (the clear sky undefined, the beam 0)
/// the scene has no sky.
#[test]
fn a_clear_sky_follows_the_sun_time() {
    use invlight_scene::daylight::SkyKind;
    let text = "<input><scene path=\"s.gltf\"/>\n<site latitude=\"0\" longitude=\"0\" timezone=\"0\"/><sky type=\"cie-clear\" horizontalLux=\"9000\"/>\n<conditions><sunTime id=\"Sun\" date=\"2026-03-20\" from=\"04:00\" to=\"12:00\" step=\"60\"/></conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>";
    let p = Problem::parse(Path::new("/p/x.xml"), text).unwrap();
    let mut s = scene();
    let b = Binding::new(&p, &mut s).unwrap();
    let sun = |s: &Scene| s.lights[1].kind.direction().unwrap();
    // Nine cells, 04:00 … 12:00: 04:00 is night, 08:00 and 12:00 are two suns.
    for (k, up) in [(0, false), (4, true), (8, true)] {
        let config = Configuration {
            coords: vec![(k as f64 + 0.5) / 9.0],
        };
        assert!(!b.apply(&mut s, &config), "no instance moves");
        match (&s.sky, up) {
            (Some(sky), true) => {
                let to_sun = sky.sun().expect("a clear sky has a sun");
                assert!((to_sun + sun(&s)).length() < 1e-5, "{to_sun} {}", sun(&s));
                assert_eq!(sky.kind(), SkyKind::CieClear);
            }
            (None, false) => {}
            (sky, _) => panic!("cell {k}: {:?}", sky.as_ref().map(|s| s.sun())),
        }
    }
}

/// Linear luminaires (1.52 m long along C90, here along y) in a `<lightArray>` over the
/// 2 m × 1 m placement rectangle: two rows half a spacing from its edges stand 0.5 m
/// apart, end to end closer than their length, and are refused, while two columns
/// stand side by side 1 m apart; turned a quarter turn, the columns collide and the
/// rows do not.
#[test]
fn an_array_whose_fittings_overlap_is_refused() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry/linear.ldt");
    let table = std::sync::Arc::new(invlight_scene::read_photometry(&path).unwrap());
    let binding = |turn: f32| {
        let mut s = scene_with_six_lamps();
        for k in 1..=4 {
            let name = format!("L{k}");
            s.set_photometry(&name, table.clone(), 1.0).unwrap();
            let l = s.light(&name).unwrap();
            s.lights[l].kind.turn_about_aim(turn);
        }
        Binding::new(
            &problem(
                "<lightArray id=\"Grid\" lights=\"L1 L2 L3 L4\" surface=\"Floor__Geometry\" columns=\"1..2\" rows=\"1..2\"/>",
            ),
            &mut s,
        )
        .unwrap()
    };
    let shape = |b: &Binding, columns, rows| {
        b.configuration(&[VariableValue::Array(crate::space::ArrayShape {
            columns,
            rows,
            walls: [0.5, 0.5],
            orientation: None,
        })])
        .unwrap()
    };
    let along_y = binding(0.0);
    let why = along_y
        .refusal(&shape(&along_y, 1, 2))
        .expect("rows 0.5 m apart, fittings 1.52 m long");
    assert!(
        why.contains("over each other") && why.contains("0.50 m apart"),
        "{why}"
    );
    assert_eq!(along_y.refusal(&shape(&along_y, 2, 1)), None);
    // Side by side 1 m apart, 0.08 m wide: 0.92 m between the fittings.
    let layout = &along_y.layouts(&shape(&along_y, 2, 1))[0];
    let array = layout.array.as_ref().unwrap();
    let gap = array.between.expect("fittings with an outline")[0];
    assert!((gap - 0.92).abs() < 1e-6, "{gap}");
    assert!(
        layout.description.contains("(0.92 m × — between fittings)"),
        "{}",
        layout.description
    );
    let along_x = binding(90.0);
    let why = along_x
        .refusal(&shape(&along_x, 2, 1))
        .expect("columns 1 m apart, fittings 1.52 m long");
    assert!(why.contains("1.00 m apart"), "{why}");
    assert_eq!(along_x.refusal(&shape(&along_x, 1, 2)), None);
}

/// Linear luminaires (1.52 m long along C90, here along y as loaded) in two rows of
/// one over the 2 m × 1 m rectangle, their orientation searched: the rows stand at
/// most 1 m apart along y, so as loaded the fittings always collide end to end, and
/// turned a quarter turn they stand side by side. Every 0° configuration is refused
/// with the fittings named, every 90° one is traced, and the search starts from the
/// first start that fits and answers with the turned array; its layout says so.
#[test]
fn a_searched_orientation_finds_the_one_way_the_fittings_fit() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry/linear.ldt");
    let table = std::sync::Arc::new(invlight_scene::read_photometry(&path).unwrap());
    let mut s = scene_with_six_lamps();
    for name in ["L1", "L2"] {
        s.set_photometry(name, table.clone(), 1.0).unwrap();
    }
    let p = Problem::parse(
        Path::new("/p/x.xml"),
        "<input><scene path=\"s.gltf\"/><conditions><lightArray id=\"Grid\" lights=\"L1 L2\" surface=\"Floor__Geometry\" columns=\"1\" rows=\"2\" orientation=\"search\"/></conditions><objectives photons=\"2000\" maxIterations=\"30\" seed=\"3\"><maximizeRadiance surface=\"Floor\"/></objectives></input>",
    )
    .unwrap();
    let b = Binding::new(&p, &mut s).unwrap();
    let orientation = |c: &Configuration| match b.values(c)[0] {
        VariableValue::Array(shape) => shape.orientation,
        _ => panic!("an array"),
    };
    // Not from the first start, whose fittings collide, but from the first that fits.
    assert_eq!(orientation(&b.initial), Some(90.0));
    for tenth in 0..=10 {
        for turn in [0.0, 90.0] {
            let config = b
                .configuration(&[VariableValue::Array(crate::space::ArrayShape {
                    columns: 1,
                    rows: 2,
                    walls: [0.5, f64::from(tenth) / 10.0],
                    orientation: Some(turn),
                })])
                .unwrap();
            match (turn, b.refusal(&config)) {
                (0.0, Some(why)) => assert!(why.contains("'L1' and 'L2'"), "{why}"),
                (90.0, None) => {}
                (turn, why) => panic!("{turn}° at wall {tenth}/10: {why:?}"),
            }
        }
    }
    // A column of its own in solutions.csv: a folder of a fixed orientation, whose
    // header lacks it, is not resumed as this one.
    let header = crate::csv_header(&b);
    assert_eq!(
        header[1..6],
        [
            "Grid.columns",
            "Grid.rows",
            "Grid.walls.columns",
            "Grid.walls.rows",
            "Grid.orientation"
        ]
    );
    let mut search = crate::Search::new(&b.space, p.settings(), &b.initial);
    let mut eval = crate::PhotonEvaluator::new(&b, s.clone(), p.seed, 4, p.photons);
    struct Quiet;
    impl crate::Observer for Quiet {
        fn evaluated(
            &mut self,
            _: &crate::Record,
            _: crate::Standing<'_>,
            _: bool,
        ) -> std::io::Result<()> {
            Ok(())
        }
    }
    search.run(&mut eval, &mut Quiet).unwrap();
    let members = search.isoc().members();
    assert!(!members.is_empty());
    for m in members {
        assert_eq!(orientation(&m.config), Some(90.0), "{:?}", m.config);
    }
    let layout = &b.layouts(&members[0].config)[0];
    assert!(
        layout
            .description
            .contains("fittings turned 90°, lengthwise along the first edge"),
        "{}",
        layout.description
    );
}

/// Two linear luminaires side by side 1 m apart in a `<lightArray>`: the file's
/// outline (0.08 m wide) lets them stand there; `<luminaire size>` of 1.2 m across
/// refuses it, and the gap an installer reads is the size's. The photometry is the
/// file's either way.
#[test]
fn a_size_as_installed_is_the_outline_kept_apart() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry/linear.ldt");
    let table = std::sync::Arc::new(invlight_scene::read_photometry(&path).unwrap());
    let binding = |sizes: &str| {
        let mut s = scene_with_six_lamps();
        for name in ["L1", "L2"] {
            s.set_photometry(name, table.clone(), 1.0).unwrap();
        }
        let luminaires: String = ["L1", "L2"]
            .map(|l| format!("<luminaire light=\"{l}\" file=\"linear.ldt\"{sizes}/>"))
            .concat();
        let p = Problem::parse(
            Path::new("/p/x.xml"),
            &format!("<input><scene path=\"s.gltf\">{luminaires}</scene><conditions><lightArray id=\"Grid\" lights=\"L1 L2\" surface=\"Floor__Geometry\" columns=\"2\" rows=\"1\"/></conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>"),
        )
        .unwrap();
        (Binding::new(&p, &mut s).unwrap(), s)
    };
    let side_by_side = |b: &Binding| {
        b.configuration(&[VariableValue::Array(crate::space::ArrayShape {
            columns: 2,
            rows: 1,
            walls: [0.5, 0.5],
            orientation: None,
        })])
        .unwrap()
    };
    let (file, s) = binding("");
    assert_eq!(file.refusal(&side_by_side(&file)), None);
    let (sized, t) = binding(" size=\"1.52,1.2\"");
    let why = sized
        .refusal(&side_by_side(&sized))
        .expect("1.2 m wide, 1 m apart");
    assert!(
        why.contains("'L1' and 'L2'") && why.contains("1.00 m apart"),
        "{why}"
    );
    // 1 m apart: the gap between 1.2 m wide fittings is −0.2 m, between the file's 0.92 m.
    let gap = |b: &Binding| {
        b.layouts(&side_by_side(b))[0]
            .array
            .as_ref()
            .unwrap()
            .between
            .unwrap()[0]
    };
    assert!((gap(&file) - 0.92).abs() < 1e-6, "{}", gap(&file));
    assert!((gap(&sized) + 0.2).abs() < 1e-6, "{}", gap(&sized));
    assert_eq!(s.lights, t.lights, "the same photometry and frames");
}

/// A `<lightArray continuous="true">` over L1 … L4 of `scene_with_six_lamps`, each a
/// linear luminaire (linear.ldt, its length along C90: y as loaded) given `sizes` as
/// `<luminaire>` attributes (`None`: no file, point lamps), the element on line 3.
fn continuous_array(
    array: &str,
    sizes: [Option<&str>; 4],
) -> Result<(Binding, Scene), invlight_scene::Diagnostic> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry/linear.ldt");
    let table = std::sync::Arc::new(invlight_scene::read_photometry(&path).unwrap());
    let mut s = scene_with_six_lamps();
    let mut luminaires = String::new();
    for (k, size) in (1..=4).zip(sizes) {
        let name = format!("L{k}");
        if let Some(size) = size {
            s.set_photometry(&name, table.clone(), 1.0).unwrap();
            luminaires += &format!("<luminaire light=\"{name}\" file=\"linear.ldt\"{size}/>");
        }
    }
    let p = Problem::parse(
        Path::new("/p/x.xml"),
        &format!(
            "<input><scene path=\"s.gltf\">{luminaires}</scene>\n<conditions>\n<lightArray id=\"Grid\" lights=\"L1 L2 L3 L4\" surface=\"Floor__Geometry\" continuous=\"true\"{array}/>\n</conditions><objectives><maximizeRadiance surface=\"Floor\"/></objectives></input>"
        ),
    )
    .unwrap();
    Binding::new(&p, &mut s).map(|b| (b, s))
}

/// Fittings 0.4 m long (`<luminaire size>`).
const SHORT: Option<&str> = Some(" size=\"0.4,0.08\"");

/// The configuration of one array's `shape`.
fn array_config(
    b: &Binding,
    (columns, rows): (u32, u32),
    walls: [f64; 2],
    orientation: Option<f64>,
) -> Configuration {
    b.configuration(&[VariableValue::Array(crate::space::ArrayShape {
        columns,
        rows,
        walls,
        orientation,
    })])
    .unwrap()
}

/// Continuous rows of 0.4 m fittings along y on the 2 m × 1 m rectangle (x 1–3,
/// y 1–2): each row's lamps exactly one fitting's length apart, centre to centre,
/// centred on the rectangle whatever the wall fraction along the rows; across them
/// the columns keep theirs (half a spacing: x = 1.5, 2.5). Fittings that touch are
/// not over each other, and the layout says the rows are continuous.
#[test]
fn continuous_rows_lie_end_to_end_centred_on_the_rectangle() {
    let (b, mut s) = continuous_array(" columns=\"1..2\" rows=\"1..2\"", [SHORT; 4]).unwrap();
    let at = |s: &Scene, name: &str| s.lights[s.light(name).unwrap()].kind.position().unwrap();
    for wall in [0.0, 0.2, 1.0] {
        let config = array_config(&b, (2, 2), [0.5, wall], None);
        b.apply(&mut s, &config);
        for (name, x, y) in [
            ("L1", 1.5, 1.3),
            ("L2", 2.5, 1.3),
            ("L3", 1.5, 1.7),
            ("L4", 2.5, 1.7),
        ] {
            assert!(
                at(&s, name).distance(Vec3::new(x, y, 2.5)) < 1e-5,
                "{name} at {} (wall {wall})",
                at(&s, name)
            );
        }
        let pitch = f64::from(at(&s, "L3").y - at(&s, "L1").y);
        assert!((pitch - 0.4).abs() < 1e-6, "{pitch}");
        assert_eq!(b.refusal(&config), None, "fittings that touch");
    }
    // One layout, one cell: the search evaluates it once. The columns' fraction counts.
    let cell = |walls| b.space.cell(&array_config(&b, (2, 2), walls, None));
    assert_eq!(cell([0.5, 0.0]), cell([0.5, 0.9]));
    assert_ne!(cell([0.5, 0.0]), cell([0.3, 0.0]));
    let layout = &b.layouts(&array_config(&b, (2, 2), [0.5, 0.2], None))[0];
    let array = layout.array.as_ref().unwrap();
    assert_eq!(array.continuous, Some(1));
    assert!(
        layout.description.contains(
            "(2 rows of 2), continuous rows along the other edge, 1.00 m × 0.40 m apart (0.92 m × 0.00 m between fittings)"
        ),
        "{}",
        layout.description
    );
}

/// Turned a quarter turn, the fittings' length lies along x and so do the rows: a
/// searched 90° lays three 0.4 m fittings end to end about x = 2 and keeps the rows
/// at their wall fraction; 0° in the same configuration lays them along y. A fixed
/// `orientation="90"` (the lamps loaded turned) lays them along x too. The fraction
/// the rows ignore is the one along them, so which it is turns with them.
#[test]
fn turned_a_quarter_turn_the_rows_run_along_the_other_edge() {
    let (b, mut s) = continuous_array(
        " columns=\"1..3\" rows=\"1..2\" orientation=\"search\"",
        [SHORT; 4],
    )
    .unwrap();
    let at = |s: &Scene, name: &str| s.lights[s.light(name).unwrap()].kind.position().unwrap();
    let turned = array_config(&b, (3, 1), [0.1, 0.5], Some(90.0));
    b.apply(&mut s, &turned);
    for (name, x) in [("L1", 1.6), ("L2", 2.0), ("L3", 2.4)] {
        assert!(
            at(&s, name).distance(Vec3::new(x, 1.5, 2.5)) < 1e-5,
            "{name} at {}",
            at(&s, name)
        );
    }
    assert_eq!(b.refusal(&turned), None);
    assert!(
        b.layouts(&turned)[0]
            .description
            .contains("continuous rows along the first edge, fittings turned 90°, 0.40 m × 0.00 m apart (0.00 m × — between fittings)"),
        "{}",
        b.layouts(&turned)[0].description
    );
    let cell = |walls, o| b.space.cell(&array_config(&b, (1, 2), walls, Some(o)));
    assert_eq!(cell([0.1, 0.5], 90.0), cell([0.8, 0.5], 90.0));
    assert_ne!(cell([0.1, 0.5], 0.0), cell([0.8, 0.5], 0.0));
    assert_eq!(cell([0.5, 0.1], 0.0), cell([0.5, 0.8], 0.0));
    // As loaded, two end to end along y about y = 1.5, one column in the middle.
    let along_y = array_config(&b, (1, 2), [0.1, 0.5], Some(0.0));
    b.apply(&mut s, &along_y);
    assert!(at(&s, "L1").distance(Vec3::new(2.0, 1.3, 2.5)) < 1e-5);
    assert!(at(&s, "L2").distance(Vec3::new(2.0, 1.7, 2.5)) < 1e-5);
    // A fixed 90°: the problem loads the scene turned, as here by hand.
    let (b, mut s) = {
        let mut s = scene_with_six_lamps();
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/photometry/linear.ldt");
        let table = std::sync::Arc::new(invlight_scene::read_photometry(&path).unwrap());
        for k in 1..=4 {
            let name = format!("L{k}");
            s.set_photometry(&name, table.clone(), 1.0).unwrap();
            let l = s.light(&name).unwrap();
            s.lights[l].kind.turn_about_aim(90.0);
        }
        let b = Binding::new(
            &problem(
                "<lightArray id=\"Grid\" lights=\"L1 L2 L3 L4\" surface=\"Floor__Geometry\" columns=\"1..2\" rows=\"1..2\" orientation=\"90\" continuous=\"true\"/>",
            ),
            &mut s,
        )
        .unwrap();
        (b, s)
    };
    // linear.ldt's own 1.52 m: one fits the 2 m edge, two do not.
    let one = array_config(&b, (1, 2), [0.0, 0.5], None);
    b.apply(&mut s, &one);
    assert!(at(&s, "L1").distance(Vec3::new(2.0, 1.25, 2.5)) < 1e-5);
    assert!(at(&s, "L2").distance(Vec3::new(2.0, 1.75, 2.5)) < 1e-5);
    assert!(
        b.refusal(&array_config(&b, (2, 1), [0.5, 0.5], None))
            .is_some()
    );
}

/// A shape whose row is longer than its rectangle's edge is refused before it is
/// traced, with the row's length and the edge's: three 0.4 m fittings along the 1 m
/// edge; two fit.
#[test]
fn a_continuous_row_longer_than_its_rectangle_is_refused() {
    let (b, _) = continuous_array(" columns=\"1\" rows=\"2..3\"", [SHORT; 4]).unwrap();
    assert_eq!(b.refusal(&array_config(&b, (1, 2), [0.5, 0.5], None)), None);
    let why = b
        .refusal(&array_config(&b, (1, 3), [0.5, 0.5], None))
        .expect("1.2 m of fittings on a 1 m edge");
    assert_eq!(
        why,
        "it lays 3 fittings of 'Grid' end to end, a row of 1.20 m along the other edge, 1.00 m long"
    );
}

/// What continuous rows need is checked at load, with the element's line (3) and a
/// hint: a lamp with a length (no file here, so none), one length for every lamp, and
/// a least row that fits.
#[test]
fn continuous_rows_of_lamps_without_one_length_are_refused_at_load() {
    let refused = |array: &str, sizes| continuous_array(array, sizes).unwrap_err().to_string();
    let counts = " columns=\"1..2\" rows=\"1..2\"";
    let e = refused(counts, [SHORT, SHORT, None, SHORT]);
    assert!(
        e.starts_with("/p/x.xml:3: 'L3' has no length")
            && e.contains("hint: give it <luminaire light=\"L3\" size=\"L,W\">"),
        "{e}"
    );
    let e = refused(counts, [SHORT, Some(""), SHORT, SHORT]);
    assert!(
        e.starts_with("/p/x.xml:3: 'L1' is 0.400 m long and 'L2' 1.520 m")
            && e.contains("hint: give them one <luminaire size>"),
        "{e}"
    );
    let e = refused(" columns=\"1\" rows=\"3\"", [SHORT; 4]);
    assert!(
        e.starts_with("/p/x.xml:3: <lightArray id=\"Grid\" continuous=\"true\"> lays at least 3 fittings of 0.40 m end to end, a row of 1.20 m along the other edge of 'Floor__Geometry', 1.00 m long")
            && e.contains("hint: lower the least 'rows'"),
        "{e}"
    );
    // Searched, the least row need only fit one way: three along the 2 m edge do.
    assert!(
        continuous_array(
            " columns=\"1\" rows=\"3\" orientation=\"search\"",
            [SHORT; 4]
        )
        .is_ok()
    );
}
