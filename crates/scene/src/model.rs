//! The scene: meshes placed by instances, named surfaces over instances, lights, cameras
//! and the placement rectangles of problem files.
//!
//! # Ids
//!
//! The scene's lists refer to one another by typed ids: an [`Instance`] names its
//! [`MeshId`], a triangle its [`MaterialId`], a [`Surface`] its [`InstanceId`]s, a
//! [`crate::Material`] its [`TextureId`]; [`Scene::surface`] and [`Scene::light`] answer
//! with a [`SurfaceId`] and a [`LightId`]. Each id indexes its own list and no other,
//! and an index handed to the wrong list is a compile error:
//!
//! ```
//! use invlight_scene::{Mat4, Mesh, Scene};
//! let mut scene = Scene::default();
//! let mesh = scene.add_mesh(Mesh::default());
//! let instance = scene.add_instance("Box", mesh, Mat4::IDENTITY);
//! let placed = &scene.meshes[scene.instances[instance].mesh];
//! ```
//!
//! ```compile_fail
//! # use invlight_scene::{Mat4, Mesh, Scene};
//! # let mut scene = Scene::default();
//! # let mesh = scene.add_mesh(Mesh::default());
//! let instance = scene.add_instance("Box", mesh, Mat4::IDENTITY);
//! let placed = &scene.meshes[instance];
//! ```
//!
//! The lists stay plain `Vec`s, which loaders and tests fill and read as such: each id
//! implements `Index` and `IndexMut` on the `Vec` and the slice of what it names, and
//! on nothing else (a side table such as a `Vec<bool>` per material takes
//! [`MaterialId::index`]). An id is a `u32` (`#[repr(transparent)]`): a mesh stores one
//! [`MaterialId`] per triangle and the tracer one [`InstanceId`] per baked triangle, 4
//! bytes each, and `list[id]` compiles to the same bounds-checked load as
//! `list[id.index()]`. [`InstanceId::from_index`] makes an id of a position (as
//! `enumerate` gives it); [`InstanceId::index`] gives the position back.

use crate::daylight::Sky;
use crate::error::PhotometryError;
use crate::light::{Camera, Light, LightKind, aimed_frame, tilt_factor};
use crate::material::{Material, Texture};
use crate::mesh::Mesh;
use crate::photometry::Photometry;
use glam::{Mat4, Vec3};
use std::collections::HashMap;
use std::ops::{Index, IndexMut};
use std::sync::Arc;

/// Declares an id type indexing `Vec<$item>` and `[$item]`.
macro_rules! id {
    ($(#[$doc:meta])* $id:ident => $item:ty) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        #[repr(transparent)]
        pub struct $id(u32);

        impl $id {
            /// The id of the element at `index` of its list.
            ///
            /// # Panics
            ///
            /// When `index` does not fit in 32 bits: ids are 4 bytes because meshes store
            /// one per triangle, and a list of 2³² elements would not fit in memory anyway.
            #[inline]
            pub const fn from_index(index: usize) -> Self {
                assert!(index <= u32::MAX as usize, "more than 2³² elements in a scene list");
                $id(index as u32)
            }

            /// The position of the element in its list.
            #[inline(always)]
            pub const fn index(self) -> usize {
                self.0 as usize
            }
        }

        /// The bare index, as messages name the element ("mesh 3").
        impl std::fmt::Display for $id {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                self.0.fmt(f)
            }
        }

        impl Index<$id> for [$item] {
            type Output = $item;
            #[inline(always)]
            fn index(&self, id: $id) -> &$item {
                &self[id.index()]
            }
        }

        impl IndexMut<$id> for [$item] {
            #[inline(always)]
            fn index_mut(&mut self, id: $id) -> &mut $item {
                &mut self[id.index()]
            }
        }

        impl Index<$id> for Vec<$item> {
            type Output = $item;
            #[inline(always)]
            fn index(&self, id: $id) -> &$item {
                &self.as_slice()[id]
            }
        }

        impl IndexMut<$id> for Vec<$item> {
            #[inline(always)]
            fn index_mut(&mut self, id: $id) -> &mut $item {
                &mut self.as_mut_slice()[id]
            }
        }
    };
}

id! {
    /// A mesh: index into [`Scene::meshes`].
    MeshId => Mesh
}
id! {
    /// A material: index into [`Scene::materials`].
    MaterialId => Material
}
id! {
    /// A texture: index into [`Scene::textures`].
    TextureId => Texture
}
id! {
    /// A placed mesh: index into [`Scene::instances`].
    InstanceId => Instance
}
id! {
    /// A named surface: index into [`Scene::surfaces`].
    SurfaceId => Surface
}
id! {
    /// A point, spot, directional or goniometric light: index into [`Scene::lights`].
    LightId => Light
}

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

/// Appends to `vertices` each of `points` it does not hold yet, in order: a placement's
/// distinct vertices. A set of the bit patterns (−0 taken as +0, as `==` takes it)
/// keeps this linear; a hostile `*__Geometry` mesh of 100 000 vertices made the
/// list search quadratic.
pub(crate) fn push_distinct(vertices: &mut Vec<Vec3>, points: impl IntoIterator<Item = Vec3>) {
    let key = |p: Vec3| (p + Vec3::ZERO).to_array().map(f32::to_bits);
    let mut seen: std::collections::HashSet<[u32; 3]> = vertices.iter().map(|&p| key(p)).collect();
    for p in points {
        if seen.insert(key(p)) {
            vertices.push(p);
        }
    }
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
    /// The sky over the scene, a light from every direction of the upper hemisphere
    /// about [`Scene::up`] (CIE skies, [`crate::daylight`]); none by default, as no
    /// scene file describes one.
    pub sky: Option<Arc<Sky>>,
    /// Named surfaces, in the order they were first seen. Read it freely; add to it
    /// through [`Scene::add_instance`] and [`Scene::add_to_surface`], which keep the name
    /// index in step (a list pushed to directly is still searched correctly by
    /// [`Scene::surface`], by a linear scan; a surface renamed in place is not seen by
    /// [`Scene::add_to_surface`], which would add a second one of the new name).
    pub surfaces: Vec<Surface>,
    /// Placement rectangles.
    pub placements: Vec<Placement>,
    /// The calculation surfaces: named surfaces that receive light without touching
    /// it (`crate::calculation`; read it through [`Scene::calculation_surfaces`]).
    pub(crate) calculation: Vec<SurfaceId>,
    /// The file's up axis (unit vector). Positions are kept as written, never swapped;
    /// this only orients what needs a zenith, such as sun directions in a problem file.
    pub up: Vec3,
    /// `surfaces` by name.
    names: SurfaceIndex,
}

/// Surface name → index into [`Scene::surfaces`]: a cache of that list, so that
/// loading a file of 100 000 named parts does not search the names linearly for each
/// (for 83 334 OBJ objects, 17 s). It is derived from `surfaces` and
/// checked against it on use, so it takes no part in comparing scenes.
#[derive(Debug, Clone, Default)]
struct SurfaceIndex(HashMap<String, SurfaceId>);

impl PartialEq for SurfaceIndex {
    fn eq(&self, _: &Self) -> bool {
        true
    }
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
            sky: None,
            surfaces: Vec::new(),
            placements: Vec::new(),
            calculation: Vec::new(),
            up: Vec3::Y,
            names: SurfaceIndex::default(),
        }
    }
}

impl Scene {
    /// Adds a material and returns its id.
    pub fn add_material(&mut self, material: Material) -> MaterialId {
        self.materials.push(material);
        MaterialId::from_index(self.materials.len() - 1)
    }

    /// Adds a texture and returns its id.
    pub fn add_texture(&mut self, texture: Texture) -> TextureId {
        self.textures.push(texture);
        TextureId::from_index(self.textures.len() - 1)
    }

    /// Adds a mesh and returns its id.
    pub fn add_mesh(&mut self, mesh: Mesh) -> MeshId {
        self.meshes.push(mesh);
        MeshId::from_index(self.meshes.len() - 1)
    }

    /// Places `mesh` with `transform` under the surface `name` (created when new).
    pub fn add_instance(&mut self, name: &str, mesh: MeshId, transform: Mat4) -> InstanceId {
        self.instances.push(Instance {
            mesh,
            transform,
            name: name.to_string(),
        });
        let id = InstanceId::from_index(self.instances.len() - 1);
        self.add_to_surface(name, id);
        id
    }

    /// Adds an instance to the surface `name` too (an ancestor node's name covers its
    /// descendants' triangles).
    ///
    /// O(1) on average as the loaders call it: the surface is found through the name
    /// index, and an instance newer than every one the surface holds (the loaders add
    /// each instance right after creating it) is appended without searching the list.
    pub fn add_to_surface(&mut self, name: &str, instance: InstanceId) {
        if self.names.0.len() != self.surfaces.len() {
            self.reindex();
        }
        let found = self
            .names
            .0
            .get(name)
            .copied()
            .filter(|&i| self.surfaces.get(i.index()).is_some_and(|s| s.name == name));
        match found {
            Some(i) => {
                let list = &mut self.surfaces[i].instances;
                match list.last() {
                    Some(&last) if last >= instance => {
                        if !list.contains(&instance) {
                            list.push(instance)
                        }
                    }
                    _ => list.push(instance),
                }
            }
            None => {
                self.surfaces.push(Surface {
                    name: name.to_string(),
                    instances: vec![instance],
                });
                let id = SurfaceId::from_index(self.surfaces.len() - 1);
                self.names.0.insert(name.to_string(), id);
            }
        }
    }

    /// Rebuilds the name index from `surfaces` (after it was changed directly); the
    /// first surface of a name wins, as [`Scene::surface`]'s scan finds it.
    fn reindex(&mut self) {
        self.names.0.clear();
        for (i, s) in self.surfaces.iter().enumerate() {
            self.names
                .0
                .entry(s.name.clone())
                .or_insert(SurfaceId::from_index(i));
        }
    }

    /// The surface called `name`.
    pub fn surface(&self, name: &str) -> Option<SurfaceId> {
        let indexed = self.names.0.len() == self.surfaces.len();
        match self.names.0.get(name) {
            Some(&i) if self.surfaces.get(i.index()).is_some_and(|s| s.name == name) => Some(i),
            None if indexed => None,
            // Stale: `surfaces` was changed without the index.
            _ => self
                .surfaces
                .iter()
                .position(|s| s.name == name)
                .map(SurfaceId::from_index),
        }
    }

    /// The light called `name`.
    pub fn light(&self, name: &str) -> Option<LightId> {
        self.lights
            .iter()
            .position(|l| l.name == name)
            .map(LightId::from_index)
    }

    /// Makes the point or spot light `name` the luminaire `photometry` describes, with
    /// its candela × `multiplier`, at the light's position: a spot keeps its aim, a point
    /// light is aimed down (−[`Scene::up`]); C0 lies along the light's [`Light::c0`]
    /// (its node's local +X) as far as the aim allows (see [`aimed_frame`]), so a
    /// luminaire turned with its node is turned in the scene. An IES tilt factor is applied for the angle between
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
            LightKind::Point { position, .. } => (*position, aimed_frame(-up, light.c0)),
            LightKind::Spot {
                position,
                direction,
                ..
            } => (*position, aimed_frame(*direction, light.c0)),
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
            multiplier: Vec3::splat(multiplier),
            tilt,
        };
        Ok(())
    }

    /// The placement rectangle called `name`.
    pub fn placement(&self, name: &str) -> Option<&Placement> {
        self.placements.iter().find(|p| p.name == name)
    }

    /// World-space area of a surface, m².
    pub fn surface_area(&self, surface: SurfaceId) -> f32 {
        self.surfaces[surface]
            .instances
            .iter()
            .map(|&i| self.instance_area(i) as f64)
            .sum::<f64>() as f32
    }

    /// World-space area of an instance, m².
    pub fn instance_area(&self, instance: InstanceId) -> f32 {
        let inst = &self.instances[instance];
        self.meshes[inst.mesh].area(&inst.transform)
    }

    /// Number of triangles of a surface.
    pub fn surface_triangles(&self, surface: SurfaceId) -> usize {
        self.surfaces[surface]
            .instances
            .iter()
            .map(|&i| self.meshes[self.instances[i].mesh].triangles.len())
            .sum()
    }

    /// World-space bounding box of the lit scene and its point lights, or `None` when the
    /// scene is empty.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for inst in &self.instances {
            for &p in &self.meshes[inst.mesh].positions {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;

    /// 100 000 named parts under one common ancestor: every name found, the ancestor
    /// covering every part once. The index makes it milliseconds (a linear name search
    /// and `contains` on the ancestor's list take tens of seconds); that is not timed
    /// here — a shared machine's clock would make the test flaky, not the code wrong.
    #[test]
    fn many_names_are_indexed() {
        let mut scene = Scene::default();
        let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let quad = scene.add_mesh(Mesh::quad([Vec3::ZERO, Vec3::X, Vec3::ONE, Vec3::Y], grey));
        let n = 100_000;
        for i in 0..n {
            let id = scene.add_instance(&format!("part {i}"), quad, Mat4::IDENTITY);
            scene.add_to_surface("Building", id);
            scene.add_to_surface("Building", id);
        }
        assert_eq!(scene.surfaces.len(), n + 1);
        assert_eq!(
            scene.surface("part 77777"),
            Some(SurfaceId::from_index(77_778))
        );
        let building = scene.surface("Building").unwrap();
        assert_eq!(scene.surfaces[building].instances.len(), n);
        // An older instance added again is not duplicated.
        scene.add_to_surface("Building", InstanceId::from_index(5));
        assert_eq!(scene.surfaces[building].instances.len(), n);
    }

    /// A surface list changed directly is still searched correctly.
    #[test]
    fn a_list_changed_directly_is_still_searched() {
        let instance = InstanceId::from_index;
        let mut scene = Scene::default();
        scene.add_to_surface("A", instance(0));
        scene.surfaces.push(Surface {
            name: "B".into(),
            instances: vec![instance(1)],
        });
        assert_eq!(scene.surface("B"), Some(SurfaceId::from_index(1)));
        assert_eq!(scene.surface("C"), None);
        scene.add_to_surface("B", instance(2));
        assert_eq!(scene.surfaces.len(), 2);
        assert_eq!(scene.surfaces[1].instances, [instance(1), instance(2)]);
        scene.surfaces.clear();
        assert_eq!(scene.surface("A"), None);
    }
}
