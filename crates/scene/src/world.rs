//! The scene's triangles in world space, one record each: what emission (photon
//! emitters, the renderer's area lights), connections to measured surfaces and scene
//! summaries all need, computed the same way everywhere so that they cannot disagree
//! about where a triangle is or which way it faces.

use crate::model::{InstanceId, MaterialId, Scene};
use glam::Vec3;

/// A triangle of an instance, in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldTriangle {
    /// Corners, counter-clockwise seen from the front.
    pub corners: [Vec3; 3],
    /// Its material.
    pub material: MaterialId,
    /// (B − A) × (C − A) of the world-space corners: twice the area, along the front
    /// normal. Taken in world space, so a mirrored instance keeps its counter-clockwise
    /// front (as `invlight_trace` does).
    pub cross: Vec3,
}

impl WorldTriangle {
    /// Area, m².
    pub fn area(&self) -> f32 {
        0.5 * self.cross.length()
    }

    /// Unit front normal (NaN for a degenerate triangle: check [`WorldTriangle::area`]).
    pub fn normal(&self) -> Vec3 {
        self.cross.normalize()
    }
}

impl Scene {
    /// The triangles of instance `instance` in world space, in mesh order.
    pub fn world_triangles(
        &self,
        instance: InstanceId,
    ) -> impl Iterator<Item = WorldTriangle> + '_ {
        let inst = &self.instances[instance];
        let mesh = &self.meshes[inst.mesh];
        mesh.materials
            .iter()
            .enumerate()
            .map(move |(t, &material)| {
                let corners = mesh.triangle(t).map(|p| inst.transform.transform_point3(p));
                let [a, b, c] = corners;
                WorldTriangle {
                    corners,
                    material,
                    cross: (b - a).cross(c - a),
                }
            })
    }

    /// Every instance's triangles in world space, instance by instance in scene order.
    pub fn all_world_triangles(&self) -> impl Iterator<Item = (InstanceId, WorldTriangle)> + '_ {
        (0..self.instances.len())
            .map(InstanceId::from_index)
            .flat_map(move |i| self.world_triangles(i).map(move |t| (i, t)))
    }
}
