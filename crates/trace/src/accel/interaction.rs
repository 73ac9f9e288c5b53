//! The surface at a hit: point, normal, material and texture coordinates, read from the
//! scene's mesh.

use super::Accel;
use crate::ray::{Hit, Interaction, Ray};
use glam::{Vec2, Vec3, Vec3A};
use invlight_scene::Scene;

impl Accel {
    /// The surface at `hit` (a hit of `ray` returned by [`Accel::intersect`]): point
    /// interpolated from the barycentrics, geometric normal, material and texture
    /// coordinates.
    ///
    /// `scene` is the scene the structure was built or last updated with: the vertices,
    /// texture coordinates and materials are read from its meshes, which the structure
    /// does not copy (its own triangles are in leaf order, without them).
    pub fn interaction(&self, scene: &Scene, ray: &Ray, hit: &Hit) -> Interaction {
        debug_assert_eq!(scene.meshes.len(), self.hole_bounds.len(), "another scene");
        let placed = &self.placed[hit.instance.index()];
        let mesh = &scene.meshes[placed.mesh];
        let t = hit.triangle as usize;
        let [i0, i1, i2] = mesh.triangles[t].map(|i| i as usize);
        let (p0, p1, p2) = (mesh.positions[i0], mesh.positions[i1], mesh.positions[i2]);
        let w = 1.0 - hit.u - hit.v;
        let local = w * p0 + hit.u * p1 + hit.v * p2;
        let point = placed.world_from_object.transform_point3(local);
        let n_local = (p1 - p0).cross(p2 - p0);
        let normal = Vec3::from(
            placed.object_from_world.matrix3.transpose() * Vec3A::from(n_local * placed.front_sign),
        )
        .normalize_or_zero();
        // A sliver so thin its normal vanishes in rounding still faces the ray.
        let normal = if normal == Vec3::ZERO {
            -ray.dir
        } else {
            normal
        };
        let uv = if mesh.uvs.len() == mesh.positions.len() {
            w * mesh.uvs[i0] + hit.u * mesh.uvs[i1] + hit.v * mesh.uvs[i2]
        } else {
            Vec2::ZERO
        };
        Interaction {
            point,
            normal,
            material: mesh.materials[t],
            uv,
            instance: hit.instance,
            triangle: hit.triangle,
        }
    }
}
