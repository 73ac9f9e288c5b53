//! The scene: meshes placed by instances, named surfaces over instances, lights, cameras
//! and the placement rectangles of problem files.

use crate::error::PhotometryError;
use crate::light::{Camera, Light, LightKind, aimed_frame, tilt_factor};
use crate::material::{Material, Texture};
use crate::mesh::Mesh;
use crate::photometry::Photometry;
use glam::{Mat4, Vec3};
use std::sync::Arc;

/// Index into [`Scene::meshes`].
pub type MeshId = u32;
/// Index into [`Scene::materials`].
pub type MaterialId = u32;
/// Index into [`Scene::instances`].
pub type InstanceId = u32;
/// Index into [`Scene::surfaces`].
pub type SurfaceId = u32;

/// A mesh placed in the world. Moving an object changes only its instances' transforms,
/// so the acceleration structure rebuilds only its top level (DESIGN.md §7).
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    /// The mesh drawn.
    pub mesh: MeshId,
    /// Object-to-world transform.
    pub transform: Mat4,
    /// Name of the node that placed it (its own surface).
    pub name: String,
}

/// A name a user addresses: a node (glTF/COLLADA) or group (OBJ) and everything under it.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// The name.
    pub name: String,
    /// The instances it covers.
    pub instances: Vec<InstanceId>,
}

/// The suffix of ILPSolver's placement rectangles: a node named `Cone__Geometry` is not
/// part of the lit scene but the rectangle a problem file places `Cone` on. The
/// loaders set such nodes aside as [`Placement`]s; problem files name them.
pub const PLACEMENT_SUFFIX: &str = "__Geometry";

/// Whether a node name follows the placement convention ([`PLACEMENT_SUFFIX`]).
pub fn is_placement_name(name: &str) -> bool {
    name.ends_with(PLACEMENT_SUFFIX)
}

/// The placement rectangle's name for an object named `object` (`Cone` →
/// `Cone__Geometry`).
pub fn placement_name(object: &str) -> String {
    format!("{object}{PLACEMENT_SUFFIX}")
}

/// A placement rectangle (a node named `*__Geometry`, ILPSolver's convention): not part
/// of the lit scene, kept so that a problem file can place objects on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Placement {
    /// Full node name, with its `__Geometry` suffix.
    pub name: String,
    /// Distinct world-space vertices in the order the file lists them; a problem file's
    /// `vertexAIndex`… index into this list.
    pub vertices: Vec<Vec3>,
}

/// Everything that is traced and addressed by name.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Meshes in object space.
    pub meshes: Vec<Mesh>,
    /// Meshes placed in the world; the lit scene.
    pub instances: Vec<Instance>,
    /// Materials referenced by mesh triangles.
    pub materials: Vec<Material>,
    /// Base-colour textures referenced by materials.
    pub textures: Vec<Texture>,
    /// Point, spot and directional lights (area lights are emissive triangles).
    pub lights: Vec<Light>,
    /// Cameras, the first being the default view.
    pub cameras: Vec<Camera>,
    /// Named surfaces, in the order they were first seen.
    pub surfaces: Vec<Surface>,
    /// Placement rectangles.
    pub placements: Vec<Placement>,
    /// The file's up axis (unit vector). Positions are kept as written, never swapped;
    /// this only orients what needs a zenith, such as sun directions in a problem file.
    pub up: Vec3,
}

impl Default for Scene {
    fn default() -> Self {
        Scene {
            meshes: Vec::new(),
            instances: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            lights: Vec::new(),
            cameras: Vec::new(),
            surfaces: Vec::new(),
            placements: Vec::new(),
            up: Vec3::Y,
        }
    }
}

impl Scene {
    /// Adds a material and returns its id.
    pub fn add_material(&mut self, material: Material) -> MaterialId {
        self.materials.push(material);
        (self.materials.len() - 1) as MaterialId
    }

    /// Adds a mesh and returns its id.
    pub fn add_mesh(&mut self, mesh: Mesh) -> MeshId {
        self.meshes.push(mesh);
        (self.meshes.len() - 1) as MeshId
    }

    /// Places `mesh` with `transform` under the surface `name` (created when new).
    pub fn add_instance(&mut self, name: &str, mesh: MeshId, transform: Mat4) -> InstanceId {
        self.instances.push(Instance {
            mesh,
            transform,
            name: name.to_string(),
        });
        let id = (self.instances.len() - 1) as InstanceId;
        self.add_to_surface(name, id);
        id
    }

    /// Adds an instance to the surface `name` too (an ancestor node's name covers its
    /// descendants' triangles).
    pub fn add_to_surface(&mut self, name: &str, instance: InstanceId) {
        match self.surfaces.iter_mut().find(|s| s.name == name) {
            Some(s) => {
                if !s.instances.contains(&instance) {
                    s.instances.push(instance)
                }
            }
            None => self.surfaces.push(Surface {
                name: name.to_string(),
                instances: vec![instance],
            }),
        }
    }

    /// The surface called `name`.
    pub fn surface(&self, name: &str) -> Option<SurfaceId> {
        self.surfaces
            .iter()
            .position(|s| s.name == name)
            .map(|i| i as SurfaceId)
    }

    /// The light called `name`.
    pub fn light(&self, name: &str) -> Option<usize> {
        self.lights.iter().position(|l| l.name == name)
    }

    /// Makes the point or spot light `name` the luminaire `photometry` describes, with
    /// its candela × `multiplier`, at the light's position: a spot keeps its aim, a point
    /// light is aimed down (−[`Scene::up`]); C0 lies along world +X as far as the aim
    /// allows (see [`aimed_frame`]). An IES tilt factor is applied for the angle between
    /// the aim and straight down. A goniometric light keeps its position and frame and
    /// takes the new table.
    pub fn set_photometry(
        &mut self,
        name: &str,
        photometry: Arc<Photometry>,
        multiplier: f32,
    ) -> Result<(), PhotometryError> {
        if !(multiplier.is_finite() && multiplier >= 0.0) {
            return Err(PhotometryError::BadMultiplier { multiplier });
        }
        let up = self.up;
        let Some(light) = self.lights.iter_mut().find(|l| l.name == name) else {
            return Err(PhotometryError::NoSuchLight {
                name: name.to_string(),
                lights: self.lights.iter().map(|l| l.name.clone()).collect(),
            });
        };
        let (position, frame) = match &light.kind {
            LightKind::Point { position, .. } => (*position, aimed_frame(-up, Vec3::X)),
            LightKind::Spot {
                position,
                direction,
                ..
            } => (*position, aimed_frame(*direction, Vec3::X)),
            LightKind::Goniometric {
                position, frame, ..
            } => (*position, *frame),
            LightKind::Directional { .. } => {
                return Err(PhotometryError::NotAtAPoint {
                    name: name.to_string(),
                });
            }
        };
        let tilt = tilt_factor(&photometry, -frame.z_axis, up);
        light.kind = LightKind::Goniometric {
            position,
            frame,
            photometry,
            multiplier: Vec3::splat(multiplier * tilt),
        };
        Ok(())
    }

    /// The placement rectangle called `name`.
    pub fn placement(&self, name: &str) -> Option<&Placement> {
        self.placements.iter().find(|p| p.name == name)
    }

    /// World-space area of a surface, m².
    pub fn surface_area(&self, surface: SurfaceId) -> f32 {
        self.surfaces[surface as usize]
            .instances
            .iter()
            .map(|&i| self.instance_area(i) as f64)
            .sum::<f64>() as f32
    }

    /// World-space area of an instance, m².
    pub fn instance_area(&self, instance: InstanceId) -> f32 {
        let inst = &self.instances[instance as usize];
        self.meshes[inst.mesh as usize].area(&inst.transform)
    }

    /// Number of triangles of a surface.
    pub fn surface_triangles(&self, surface: SurfaceId) -> usize {
        self.surfaces[surface as usize]
            .instances
            .iter()
            .map(|&i| {
                self.meshes[self.instances[i as usize].mesh as usize]
                    .triangles
                    .len()
            })
            .sum()
    }

    /// World-space bounding box of the lit scene and its point lights, or `None` when the
    /// scene is empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for inst in &self.instances {
            for &p in &self.meshes[inst.mesh as usize].positions {
                let w = inst.transform.transform_point3(p);
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        for light in &self.lights {
            if let Some(p) = light.kind.position() {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        (lo.x <= hi.x).then_some((lo, hi))
    }
}
