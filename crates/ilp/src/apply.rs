//! Binding a problem's variables to a scene, and applying configurations to it (thesis
//! §4.5). Applying changes only what moved, as OptiX transform nodes did for ILPSolver:
//! instance transforms (so the acceleration structure rebuilds only its top level),
//! light positions and directions, material K_d.

use crate::problem::{Problem, ProblemError, VariableKind, VariableSpec};
use crate::space::{Configuration, Domain, Hemisphere, Rectangle, Space, Variable};
use glam::{DVec3, Mat4, Vec3};
use invlight_scene::{InstanceId, LightKind, Material, MaterialId, Scene, SurfaceId};
use std::path::Path;

/// A variable's value in world terms, for the CSV and `result.json`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// The placement point P, m.
    Position(DVec3),
    /// The unit vector the light travels along.
    Direction(DVec3),
    /// HSV value V and the resulting linear K_d.
    Color {
        /// V.
        value: f64,
        /// K_d, linear RGB.
        rgb: [f64; 3],
    },
}

/// What a variable changes in the scene, with the state it started from.
#[derive(Debug, Clone)]
enum Target {
    /// Instances and point/spot lights translated by P − A.
    Move {
        instances: Vec<(InstanceId, Mat4)>,
        lights: Vec<(usize, Vec3)>,
    },
    /// A directional light's direction.
    Sun { light: usize },
    /// Materials' K_d.
    Color {
        materials: Vec<MaterialId>,
        hue: f64,
        saturation: f64,
    },
}

/// A problem bound to a scene: the search space, where it starts, the objective and the
/// means to apply a configuration.
#[derive(Debug, Clone)]
pub struct Binding {
    /// The variables' space.
    pub space: Space,
    /// The scene as authored, as a configuration.
    pub initial: Configuration,
    /// The surface whose illuminance is maximised.
    pub objective: SurfaceId,
    /// The problem-file element of each variable (`objectInSurface`, …).
    pub kinds: Vec<&'static str>,
    /// Warnings found while binding (e.g. a `lightInSurface` object that emits nothing).
    pub warnings: Vec<ProblemError>,
    targets: Vec<Target>,
}

/// The RGB of HSV (hue in degrees, saturation and value in [0, 1]) — the hexcone model
/// (A. R. Smith, "Color gamut transform pairs", SIGGRAPH 1978).
pub fn hsv_to_rgb(hue: f64, saturation: f64, value: f64) -> [f64; 3] {
    let h = hue.rem_euclid(360.0) / 60.0;
    let c = value * saturation;
    let x = c * (1.0 - (h % 2.0 - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = value - c;
    [r + m, g + m, b + m]
}

fn dvec(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

impl Binding {
    /// Binds `problem` to `scene`. The scene is changed once here: the objects of
    /// `holeInSurface` variables get a hole material on a copy of their meshes.
    pub fn new(problem: &Problem, scene: &mut Scene) -> Result<Binding, ProblemError> {
        let path = problem.path.as_path();
        let mut variables = Vec::new();
        let mut targets = Vec::new();
        let mut kinds = Vec::new();
        let mut initial = Vec::new();
        let mut warnings = Vec::new();
        for spec in &problem.variables {
            let err = |msg: String| ProblemError::at(path, spec.line, msg);
            kinds.push(spec.kind.name());
            let (domain, target) = match &spec.kind {
                VariableKind::ObjectInSurface { surface, vertices }
                | VariableKind::HoleInSurface { surface, vertices } => {
                    let s = find_surface(scene, &spec.id, path, spec)?;
                    if matches!(spec.kind, VariableKind::HoleInSurface { .. }) {
                        make_hole(scene, s, &spec.id);
                    }
                    let rect = placement(scene, surface, *vertices, path, spec)?;
                    (Domain::Rectangle(rect), move_target(scene, Some(s), None))
                }
                VariableKind::LightInSurface { surface, vertices } => {
                    let rect = placement(scene, surface, *vertices, path, spec)?;
                    let target = match scene.light(&spec.id) {
                        Some(l) => match scene.lights[l].kind {
                            LightKind::Directional { .. } => {
                                return Err(err(format!(
                                    "'{}' is a directional light, expected a point or spot light or an emissive object (use <directionalLight> for a sun)",
                                    spec.id
                                )));
                            }
                            _ => move_target(scene, None, Some(l)),
                        },
                        None => {
                            let s = find_surface(scene, &spec.id, path, spec).map_err(|e| {
                                ProblemError {
                                    message: format!(
                                        "no light or surface named '{}' in the scene, expected a point or spot light or an emissive object",
                                        spec.id
                                    ),
                                    ..e
                                }
                            })?;
                            if !surface_materials(scene, s)
                                .iter()
                                .any(|&m| scene.materials[m as usize].is_emissive())
                            {
                                warnings.push(err(format!(
                                    "'{}' emits no light; moving it only moves its shadow",
                                    spec.id
                                )));
                            }
                            move_target(scene, Some(s), None)
                        }
                    };
                    (Domain::Rectangle(rect), target)
                }
                VariableKind::DirectionalLight => {
                    let light = scene
                        .light(&spec.id)
                        .filter(|&l| matches!(scene.lights[l].kind, LightKind::Directional { .. }))
                        .ok_or_else(|| {
                            err(format!(
                                "no directional light named '{}' in the scene",
                                spec.id
                            ))
                            .with_hint(known(
                                scene
                                    .lights
                                    .iter()
                                    .filter(|l| matches!(l.kind, LightKind::Directional { .. }))
                                    .map(|l| l.name.as_str()),
                                "directional lights",
                            ))
                        })?;
                    let hemi = Hemisphere::new(dvec(scene.up));
                    (Domain::Hemisphere(hemi), Target::Sun { light })
                }
                VariableKind::Color {
                    hue,
                    saturation,
                    min,
                    max,
                } => {
                    let mut materials: Vec<MaterialId> = scene
                        .materials
                        .iter()
                        .enumerate()
                        .filter(|(_, m)| m.name == spec.id)
                        .map(|(i, _)| i as MaterialId)
                        .collect();
                    if materials.is_empty() {
                        materials = scene
                            .surface(&spec.id)
                            .map(|s| surface_materials(scene, s))
                            .unwrap_or_default();
                    }
                    if materials.is_empty() {
                        return Err(err(format!(
                            "no material or surface named '{}' in the scene, expected the material (or the surface) whose colour varies",
                            spec.id
                        ))
                        .with_hint(known(scene.materials.iter().map(|m| m.name.as_str()), "materials")));
                    }
                    // The problem states the colour (hue, saturation, free value); a
                    // base-colour texture would multiply it into another one, and the
                    // variable would no longer be the colour the file names.
                    for &m in &materials {
                        let material = &mut scene.materials[m as usize];
                        if material.texture.take().is_some() {
                            warnings.push(err(format!(
                                "material '{}' has a base-colour texture; the colour variable '{}' replaces it by the uniform colour HSV({hue}°, {saturation}, V)",
                                material.name, spec.id
                            )));
                        }
                    }
                    (
                        Domain::Segment {
                            min: *min,
                            max: *max,
                        },
                        Target::Color {
                            materials,
                            hue: *hue,
                            saturation: *saturation,
                        },
                    )
                }
            };
            initial.extend(initial_coords(scene, &domain, &target));
            variables.push(Variable {
                id: spec.id.clone(),
                domain,
            });
            targets.push(target);
        }
        let objective = scene.surface(&problem.objective.surface).ok_or_else(|| {
            ProblemError::at(
                path,
                problem.objective.line,
                format!(
                    "no surface named '{}' in the scene, expected the surface to light",
                    problem.objective.surface
                ),
            )
            .with_hint(known(
                scene.surfaces.iter().map(|s| s.name.as_str()),
                "surfaces",
            ))
        })?;
        // Illuminance is flux over area: a surface without area has none.
        if scene.surface_area(objective) <= 0.0 {
            return Err(ProblemError::at(
                path,
                problem.objective.line,
                format!(
                    "the surface '{}' has no area, expected a surface to light",
                    problem.objective.surface
                ),
            ));
        }
        Ok(Binding {
            space: Space::new(variables, &problem.mesh),
            initial: Configuration { coords: initial },
            objective,
            kinds,
            warnings,
            targets,
        })
    }

    /// The instances a configuration may move (objects, emissive objects and holes
    /// placed on rectangles), in variable order: the acceleration structure keeps them
    /// separate and bakes everything else into one tree.
    pub fn movable_instances(&self) -> Vec<InstanceId> {
        let mut out = Vec::new();
        for t in &self.targets {
            if let Target::Move { instances, .. } = t {
                out.extend(instances.iter().map(|&(i, _)| i));
            }
        }
        out
    }

    /// The world value of every variable at `config`.
    pub fn values(&self, config: &Configuration) -> Vec<Value> {
        self.space
            .variables()
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let x = self.space.slice(config, i);
                match &v.domain {
                    Domain::Rectangle(r) => Value::Position(r.point(x[0], x[1])),
                    Domain::Hemisphere(h) => Value::Direction(h.direction(x[0], x[1])),
                    Domain::Segment { min, max } => {
                        let value = min + x[0] * (max - min);
                        let rgb = match &self.targets[i] {
                            Target::Color {
                                hue, saturation, ..
                            } => hsv_to_rgb(*hue, *saturation, value),
                            _ => [value; 3],
                        };
                        Value::Color { value, rgb }
                    }
                }
            })
            .collect()
    }

    /// Applies a configuration; returns whether any instance transform changed (then
    /// the caller refits the acceleration structure's top level).
    pub fn apply(&self, scene: &mut Scene, config: &Configuration) -> bool {
        let mut moved = false;
        let values = self.values(config);
        for (i, (value, target)) in values.into_iter().zip(&self.targets).enumerate() {
            match (value, target) {
                (Value::Position(p), Target::Move { instances, lights }) => {
                    let a = match &self.space.variables()[i].domain {
                        Domain::Rectangle(r) => r.a,
                        _ => p,
                    };
                    let delta = (p - a).as_vec3();
                    let shift = Mat4::from_translation(delta);
                    for &(inst, original) in instances {
                        let t = shift * original;
                        let slot = &mut scene.instances[inst as usize].transform;
                        if *slot != t {
                            *slot = t;
                            moved = true;
                        }
                    }
                    for &(light, original) in lights {
                        match &mut scene.lights[light].kind {
                            LightKind::Point { position, .. }
                            | LightKind::Spot { position, .. } => *position = original + delta,
                            LightKind::Directional { .. } => {}
                        }
                    }
                }
                (Value::Direction(d), Target::Sun { light }) => {
                    if let LightKind::Directional { direction, .. } = &mut scene.lights[*light].kind
                    {
                        *direction = d.as_vec3().normalize();
                    }
                }
                (Value::Color { rgb, .. }, Target::Color { materials, .. }) => {
                    for &m in materials {
                        scene.materials[m as usize].diffuse =
                            Vec3::new(rgb[0] as f32, rgb[1] as f32, rgb[2] as f32);
                    }
                }
                _ => {}
            }
        }
        moved
    }
}

/// A hint listing up to 12 known names.
fn known<'n>(names: impl Iterator<Item = &'n str>, what: &str) -> String {
    let v: Vec<&str> = names.collect();
    if v.is_empty() {
        return format!("the scene has no {what}");
    }
    let more = if v.len() > 12 { ", …" } else { "" };
    format!(
        "the scene's {what}: {}{more}",
        v[..v.len().min(12)].join(", ")
    )
}

fn find_surface(
    scene: &Scene,
    name: &str,
    path: &Path,
    spec: &VariableSpec,
) -> Result<SurfaceId, ProblemError> {
    scene.surface(name).ok_or_else(|| {
        ProblemError::at(
            path,
            spec.line,
            format!(
                "no surface named '{name}' in the scene, expected the object that <{}> moves",
                spec.kind.name()
            ),
        )
        .with_hint(known(
            scene.surfaces.iter().map(|s| s.name.as_str()),
            "surfaces",
        ))
    })
}

/// The distinct materials of a surface's triangles, in order.
fn surface_materials(scene: &Scene, s: SurfaceId) -> Vec<MaterialId> {
    let mut out = Vec::new();
    for &i in &scene.surfaces[s as usize].instances {
        for &m in &scene.meshes[scene.instances[i as usize].mesh as usize].materials {
            if !out.contains(&m) {
                out.push(m);
            }
        }
    }
    out
}

/// Gives a surface's instances a copy of their mesh whose every triangle is a hole.
fn make_hole(scene: &mut Scene, s: SurfaceId, id: &str) {
    let mut hole = None;
    for i in scene.surfaces[s as usize].instances.clone() {
        let mesh = scene.instances[i as usize].mesh as usize;
        if scene.meshes[mesh]
            .materials
            .iter()
            .all(|&m| scene.materials[m as usize].hole)
        {
            continue;
        }
        let h = *hole
            .get_or_insert_with(|| scene.add_material(Material::hole(&format!("{id} (hole)"))));
        let mut copy = scene.meshes[mesh].clone();
        copy.materials.iter_mut().for_each(|m| *m = h);
        scene.instances[i as usize].mesh = scene.add_mesh(copy);
    }
}

fn move_target(scene: &Scene, surface: Option<SurfaceId>, light: Option<usize>) -> Target {
    let instances = surface
        .map(|s| {
            scene.surfaces[s as usize]
                .instances
                .iter()
                .map(|&i| (i, scene.instances[i as usize].transform))
                .collect()
        })
        .unwrap_or_default();
    let lights = light
        .and_then(|l| scene.lights[l].kind.position().map(|p| (l, p)))
        .into_iter()
        .collect();
    Target::Move { instances, lights }
}

/// The placement rectangle `name` with vertex indices A, B, C, D: a `*__Geometry`
/// placement, else a surface with four distinct vertices, else `name__Geometry`.
fn placement(
    scene: &Scene,
    name: &str,
    idx: [usize; 4],
    path: &Path,
    spec: &VariableSpec,
) -> Result<Rectangle, ProblemError> {
    let err = |msg: String| ProblemError::at(path, spec.line, msg);
    let vertices: Vec<Vec3> = if let Some(p) = scene.placement(name) {
        p.vertices.clone()
    } else if let Some(s) = scene.surface(name) {
        let mut v: Vec<Vec3> = Vec::new();
        for &i in &scene.surfaces[s as usize].instances {
            let inst = &scene.instances[i as usize];
            for &p in &scene.meshes[inst.mesh as usize].positions {
                let w = inst.transform.transform_point3(p);
                if !v.contains(&w) {
                    v.push(w);
                }
            }
        }
        v
    } else if let Some(p) = scene.placement(&format!("{name}__Geometry")) {
        p.vertices.clone()
    } else {
        return Err(err(format!(
            "no placement rectangle or surface named '{name}' in the scene"
        ))
        .with_hint(known(
            scene.placements.iter().map(|p| p.name.as_str()),
            "placement rectangles",
        )));
    };
    if vertices.len() != 4 {
        return Err(err(format!(
            "placement '{name}' has {} distinct vertices, expected a planar quad (4)",
            vertices.len()
        )));
    }
    if let Some(&bad) = idx.iter().find(|&&i| i >= 4) {
        return Err(err(format!(
            "vertex index {bad} on '{name}', expected 0–3 (it has 4 vertices)"
        )));
    }
    let mut sorted = idx;
    sorted.sort();
    if sorted != [0, 1, 2, 3] {
        return Err(err(format!(
            "vertex indices {idx:?} on '{name}', expected each of 0, 1, 2, 3 once"
        )));
    }
    let v = |k: usize| dvec(vertices[idx[k]]);
    Rectangle::from_corners(v(0), [v(1), v(2), v(3)])
        .map_err(|e| err(format!("placement '{name}' is not a planar quad: {e}")))
}

/// The normalised coordinates of the scene as authored.
fn initial_coords(scene: &Scene, domain: &Domain, target: &Target) -> Vec<f64> {
    match (domain, target) {
        (Domain::Rectangle(_), _) => vec![0.0, 0.0],
        (Domain::Hemisphere(h), Target::Sun { light }) => {
            let d = scene.lights[*light]
                .kind
                .direction()
                .map(dvec)
                .unwrap_or(-h.up);
            let (p, t) = h.coords(d);
            vec![p, t]
        }
        (Domain::Segment { min, max }, Target::Color { materials, .. }) => {
            let v = materials
                .first()
                .map(|&m| scene.materials[m as usize].diffuse.max_element() as f64)
                .unwrap_or(*max);
            vec![((v - min) / (max - min)).clamp(0.0, 1.0)]
        }
        (d, _) => vec![0.5; d.dimensions()],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use invlight_scene::{Light, Mesh, Placement};

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
            name: "Lamp".into(),
            kind: LightKind::Point {
                position: Vec3::new(1.0, 1.0, 2.5),
                intensity: Vec3::ONE,
            },
        });
        s.lights.push(Light {
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
        assert_eq!(
            b.values(&config),
            vec![Value::Position(DVec3::new(2.5, 1.5, 0.0))]
        );
        assert!(b.apply(&mut s, &config));
        // Chair authored at A = (1, 1, 0): now at P.
        let t = s.instances[1].transform.w_axis.truncate();
        assert!((t - Vec3::new(2.5, 1.5, 0.0)).length() < 1e-6);
        assert!(!b.apply(&mut s, &config), "nothing moves twice");
        assert_eq!(b.movable_instances(), vec![1]);
        assert_eq!(
            s.instances[2].transform.w_axis.truncate(),
            Vec3::new(0.0, 0.0, 2.0)
        );
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
        assert_eq!(
            b.kinds,
            vec![
                "lightInSurface",
                "holeInSurface",
                "directionalLight",
                "color"
            ]
        );
        // The window's mesh became a hole; the chair sharing the cube mesh did not.
        let win = s.instances[2].mesh as usize;
        assert!(
            s.meshes[win]
                .materials
                .iter()
                .all(|&m| s.materials[m as usize].hole)
        );
        assert!(!s.materials[s.meshes[s.instances[1].mesh as usize].materials[0] as usize].hole);
        // Initial sun coordinates reproduce its direction; initial V is Paint's 0.6.
        let init = b.values(&b.initial);
        match init[2] {
            Value::Direction(d) => assert!((d - DVec3::new(0.0, 0.6, -0.8)).length() < 1e-6),
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
        s.textures.push(invlight_scene::Texture {
            width: 1,
            height: 1,
            pixels: vec![Vec3::new(0.1, 0.9, 0.1)],
        });
        let paint = s.materials.iter().position(|m| m.name == "Paint").unwrap();
        s.materials[paint].texture = Some(0);
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
        assert!(e.message.contains("8 distinct vertices"), "{e}");
    }

    #[test]
    fn hsv_primaries() {
        assert_eq!(hsv_to_rgb(0.0, 1.0, 1.0), [1.0, 0.0, 0.0]);
        assert_eq!(hsv_to_rgb(240.0, 1.0, 0.5), [0.0, 0.0, 0.5]);
        assert_eq!(hsv_to_rgb(77.0, 0.0, 0.3), [0.3, 0.3, 0.3]);
        let [r, g, b] = hsv_to_rgb(39.0, 0.23, 1.0);
        assert!((r - 1.0).abs() < 1e-12 && (b - 0.77).abs() < 1e-12 && g > b && g < r);
    }
}
