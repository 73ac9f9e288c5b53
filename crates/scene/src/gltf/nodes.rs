//! The node hierarchy (spec §3.5): world transforms, named surfaces covering
//! descendants, KHR_lights_punctual and EXT_lights_ies lights, cameras and `*__Geometry`
//! placements.

use super::Builder;
use crate::error::LoadError;
use crate::light::{Camera, Light, LightKind};
use crate::model::{Placement, push_distinct};
use glam::{Mat4, Quat, Vec3};
use gltf_json as json;
use json::extensions::scene::khr_lights_punctual::Type as LightType;
use json::validation::Checked;

const TREE_HINT: &str =
    "glTF node hierarchies are trees: a node has one parent at most and is listed once";

/// A node waiting to be visited, with its parent's world transform and how many named
/// ancestors it has (the depth of the name stack it sees).
struct Pending {
    node: usize,
    parent: Mat4,
    names: usize,
}

/// The node's transform relative to its parent: `matrix` (column-major) or T·R·S.
fn local_transform(node: &json::Node) -> Result<Mat4, &'static str> {
    let m = match node.matrix {
        Some(m) => Mat4::from_cols_array(&m),
        None => {
            let q = Quat::from_array(node.rotation.map_or([0.0, 0.0, 0.0, 1.0], |r| r.0));
            let len = q.length();
            if !(len.is_finite() && len > 0.0) {
                return Err("rotation is not a unit quaternion");
            }
            Mat4::from_scale_rotation_translation(
                Vec3::from_array(node.scale.unwrap_or([1.0; 3])),
                q / len,
                Vec3::from_array(node.translation.unwrap_or([0.0; 3])),
            )
        }
    };
    if m.is_finite() {
        Ok(m)
    } else {
        Err("the transform has a non-finite number")
    }
}

impl Builder<'_> {
    /// Visits the default scene's node trees depth first (an explicit stack, so deep
    /// hierarchies cannot overflow the call stack), placing meshes, lights and cameras.
    /// Without any scene, every node that is nobody's child is a root.
    pub(super) fn place_nodes(&mut self) -> Result<(), LoadError> {
        let root = self.root;
        let (roots_at, roots): (String, Vec<usize>) = match (root.scene, root.scenes.is_empty()) {
            (None, true) => {
                let mut child = vec![false; root.nodes.len()];
                for c in root.nodes.iter().flat_map(|n| n.children.iter().flatten()) {
                    if let Some(slot) = child.get_mut(c.value()) {
                        *slot = true;
                    }
                }
                let roots = (0..root.nodes.len()).filter(|&i| !child[i]).collect();
                ("nodes".to_string(), roots)
            }
            (index, _) => {
                let s = index.map_or(0, |i| i.value());
                let scene = root.scenes.get(s).ok_or_else(|| {
                    self.err(
                        "scene",
                        format!(
                            "scene {s} does not exist ({} in the file)",
                            root.scenes.len()
                        ),
                    )
                })?;
                let roots = scene.nodes.iter().map(|n| n.value()).collect();
                (format!("scenes[{s}].nodes"), roots)
            }
        };
        let mut seen = vec![false; root.nodes.len()];
        let mut stack = Vec::new();
        let mut names: Vec<String> = Vec::new();
        let count = root.nodes.len();
        let mut claim = |node: usize| match seen.get_mut(node) {
            Some(slot) if !*slot => {
                *slot = true;
                Ok(())
            }
            None => Err(format!("node {node} does not exist ({count} in the file)")),
            Some(_) => Err(format!("node {node} is reached twice")),
        };
        for (k, &n) in roots.iter().enumerate().rev() {
            claim(n).map_err(|m| {
                self.err(&format!("{roots_at}[{k}]"), m)
                    .with_hint(TREE_HINT)
            })?;
            stack.push(Pending {
                node: n,
                parent: Mat4::IDENTITY,
                names: 0,
            });
        }
        while let Some(Pending {
            node: i,
            parent,
            names: depth,
        }) = stack.pop()
        {
            let node = &root.nodes[i];
            let here = format!("nodes[{i}]");
            let world = parent * local_transform(node).map_err(|m| self.err(&here, m))?;
            names.truncate(depth);
            let placement = node
                .name
                .as_deref()
                .is_some_and(crate::model::is_placement_name);
            if placement {
                self.placement(i, world)?;
            } else if let Some(mesh) = node.mesh {
                self.instance(i, mesh, world, &names)?;
            }
            if let Some(light) = node
                .extensions
                .as_ref()
                .and_then(|e| e.khr_lights_punctual.as_ref())
            {
                self.light(i, light.light.value(), world)?;
            }
            if let Some(ext) = self.ies_extension(i) {
                let ext = ext.clone();
                self.ies_light(i, &ext, world)?;
            }
            if let Some(camera) = node.camera {
                self.camera(i, camera.value(), world)?;
            }
            if let (Some(name), false) = (&node.name, placement) {
                names.push(name.clone());
            }
            for (k, c) in node
                .children
                .as_deref()
                .unwrap_or_default()
                .iter()
                .enumerate()
                .rev()
            {
                claim(c.value()).map_err(|m| {
                    self.err(&format!("{here}.children[{k}]"), m)
                        .with_hint(TREE_HINT)
                })?;
                stack.push(Pending {
                    node: c.value(),
                    parent: world,
                    names: names.len(),
                });
            }
        }
        Ok(())
    }

    /// Places node `i`'s mesh under its own name (node name, else mesh name) and adds it
    /// to every named ancestor's surface.
    fn instance(
        &mut self,
        i: usize,
        mesh: json::Index<json::Mesh>,
        world: Mat4,
        ancestors: &[String],
    ) -> Result<(), LoadError> {
        let Some(id) = self.mesh(mesh, world.determinant() < 0.0, &format!("nodes[{i}].mesh"))?
        else {
            return Ok(());
        };
        let node = &self.root.nodes[i];
        let name = node
            .name
            .clone()
            .or_else(|| {
                self.root
                    .meshes
                    .get(mesh.value())
                    .and_then(|m| m.name.clone())
            })
            .unwrap_or_else(|| format!("nodes[{i}]"));
        let instance = self.scene.add_instance(&name, id, world);
        for a in ancestors {
            self.scene.add_to_surface(a, instance);
        }
        Ok(())
    }

    /// A `*__Geometry` node: its mesh's distinct world-space vertices in file order.
    fn placement(&mut self, i: usize, world: Mat4) -> Result<(), LoadError> {
        let node = &self.root.nodes[i];
        let Some(index) = node.mesh else {
            return Ok(());
        };
        let m = index.value();
        let mesh = self.root.meshes.get(m).ok_or_else(|| {
            self.err(
                &format!("nodes[{i}].mesh"),
                format!(
                    "mesh {m} does not exist ({} in the file)",
                    self.root.meshes.len()
                ),
            )
        })?;
        let mut vertices: Vec<Vec3> = Vec::new();
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let (local, _) = self.positions(prim, &format!("meshes[{m}].primitives[{p}]"), None)?;
            push_distinct(
                &mut vertices,
                local.into_iter().map(|v| world.transform_point3(v)),
            );
        }
        self.scene.placements.push(Placement {
            name: node.name.clone().unwrap_or_default(),
            vertices,
        });
        Ok(())
    }

    /// A KHR_lights_punctual light at node `i`: at the node's origin, shining along its
    /// local −Z; point and spot intensities in cd, directional illuminance in lx.
    fn light(&mut self, i: usize, l: usize, world: Mat4) -> Result<(), LoadError> {
        let lights = self
            .root
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .map_or(&[][..], |k| &k.lights[..]);
        let here = format!("nodes[{i}].extensions.KHR_lights_punctual");
        let light = lights.get(l).ok_or_else(|| {
            self.err(
                &here,
                format!("light {l} does not exist ({} in the file)", lights.len()),
            )
        })?;
        let at = format!("extensions.KHR_lights_punctual.lights[{l}]");
        let strength = Vec3::from_array(light.color) * light.intensity;
        if !strength.is_finite() {
            return Err(self.err(&at, "color × intensity is not a finite number"));
        }
        let position = world.transform_point3(Vec3::ZERO);
        let direction = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        if direction == Vec3::ZERO {
            return Err(self.err(
                &format!("nodes[{i}]"),
                "the transform collapses the light's −Z axis",
            ));
        }
        let kind = match light.type_ {
            Checked::Valid(LightType::Point) => LightKind::Point {
                position,
                intensity: strength,
            },
            Checked::Valid(LightType::Directional) => LightKind::Directional {
                direction,
                illuminance: strength,
            },
            Checked::Valid(LightType::Spot) => {
                // Spec defaults when `spot` is absent: inner 0, outer π/4.
                let (inner, outer) = light
                    .spot
                    .as_ref()
                    .map_or((0.0, std::f32::consts::FRAC_PI_4), |s| {
                        (s.inner_cone_angle, s.outer_cone_angle)
                    });
                if !(0.0 <= inner
                    && inner <= outer
                    && outer > 0.0
                    && outer <= std::f32::consts::FRAC_PI_2)
                {
                    return Err(self
                        .err(&format!("{at}.spot"), format!("cone angles inner {inner}, outer {outer}"))
                        .with_hint("KHR_lights_punctual requires 0 ≤ innerConeAngle < outerConeAngle ≤ π/2"));
                }
                LightKind::Spot {
                    position,
                    direction,
                    intensity: strength,
                    inner,
                    outer,
                }
            }
            Checked::Invalid => {
                return Err(self.err(
                    &format!("{at}.type"),
                    "type must be point, spot or directional",
                ));
            }
        };
        let name = self.root.nodes[i]
            .name
            .clone()
            .or_else(|| light.name.clone())
            .unwrap_or_else(|| format!("lights[{l}]"));
        // A photometric file given to this light later takes its C0 from the node's
        // local +X (the node's rotation turns the luminaire about its aim).
        let c0 = world.transform_vector3(Vec3::X).normalize_or(Vec3::X);
        self.scene.lights.push(Light { name, kind, c0 });
        Ok(())
    }

    /// A perspective camera at node `i`, looking along its local −Z with +Y up;
    /// orthographic cameras are skipped (photon tracing renders through a pinhole).
    fn camera(&mut self, i: usize, c: usize, world: Mat4) -> Result<(), LoadError> {
        let camera = self.root.cameras.get(c).ok_or_else(|| {
            self.err(
                &format!("nodes[{i}].camera"),
                format!(
                    "camera {c} does not exist ({} in the file)",
                    self.root.cameras.len()
                ),
            )
        })?;
        let Some(p) = &camera.perspective else {
            return Ok(());
        };
        let aspect_ok = p.aspect_ratio.is_none_or(|a| a.is_finite() && a > 0.0);
        if !(p.yfov > 0.0 && p.yfov < std::f32::consts::PI && aspect_ok) {
            return Err(self.err(
                &format!("cameras[{c}].perspective"),
                "yfov must lie in (0, π) and aspectRatio be positive",
            ));
        }
        let forward = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        let up = world.transform_vector3(Vec3::Y);
        let up = (up - forward * up.dot(forward)).normalize_or_zero();
        if forward == Vec3::ZERO || up == Vec3::ZERO {
            return Err(self.err(
                &format!("nodes[{i}]"),
                "the transform collapses the camera's axes",
            ));
        }
        let name = self.root.nodes[i]
            .name
            .clone()
            .or_else(|| camera.name.clone())
            .unwrap_or_else(|| format!("cameras[{c}]"));
        self.scene.cameras.push(Camera {
            name,
            position: world.transform_point3(Vec3::ZERO),
            forward,
            up,
            yfov: p.yfov,
            aspect: p.aspect_ratio,
        });
        Ok(())
    }
}
