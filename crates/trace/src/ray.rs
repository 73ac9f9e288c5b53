//! Rays, hits and surface interactions, and the offsets that let a ray leave a surface
//! without hitting it again.

use glam::{Vec2, Vec3};
use invlight_scene::{InstanceId, MaterialId};

/// A ray `origin + t·dir` for `0 < t < t_max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts, world space.
    pub origin: Vec3,
    /// Unit direction, world space; `t` is then a distance in scene units.
    pub dir: Vec3,
    /// Hits at `t >= t_max` are ignored (`f32::INFINITY` for an unbounded ray).
    pub t_max: f32,
}

impl Ray {
    /// An unbounded ray from `origin` along the unit vector `dir`.
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Ray {
            origin,
            dir,
            t_max: f32::INFINITY,
        }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// The closest hit of a ray: which triangle of which instance, where along the ray and
/// where on the triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Distance along the ray (the ray's `t`).
    pub t: f32,
    /// The instance hit.
    pub instance: InstanceId,
    /// Index of the triangle in its mesh's `triangles`.
    pub triangle: u32,
    /// Barycentric coordinate of the triangle's vertex 1.
    pub u: f32,
    /// Barycentric coordinate of the triangle's vertex 2 (vertex 0 has `1 − u − v`).
    pub v: f32,
}

/// What a photon or camera ray needs to know about the surface it hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interaction {
    /// The hit point, world space.
    pub point: Vec3,
    /// Unit geometric normal in world space on the triangle's front side (the side from
    /// which its vertices wind counter-clockwise in object space; normals transform by the
    /// inverse transpose, so a mirroring instance keeps the physical front side, as glTF
    /// prescribes for negative-determinant nodes).
    pub normal: Vec3,
    /// Material of the triangle.
    pub material: MaterialId,
    /// Interpolated texture coordinates, `Vec2::ZERO` when the mesh has none.
    pub uv: Vec2,
    /// The instance hit.
    pub instance: InstanceId,
    /// Index of the triangle in its mesh's `triangles`.
    pub triangle: u32,
}

/// Fraction of a shadow ray's length left out at its far end, so that the surface the
/// target lies on does not occlude it (pbrt's `ShadowEpsilon`, Pharr et al.,
/// *Physically Based Rendering* 3rd ed., §3.9.5).
pub const SHADOW_EPSILON: f32 = 1.0e-4;

impl Interaction {
    /// A ray leaving the surface along the unit vector `dir`, starting on the side `dir`
    /// points to, offset so that it cannot hit this surface again; `t_max = ∞`.
    pub fn spawn(&self, dir: Vec3) -> Ray {
        Ray::new(offset_point(self.point, self.side_normal(dir)), dir)
    }

    /// A shadow ray from the surface towards `target`, ending just short of it (by
    /// [`SHADOW_EPSILON`] of its length) so that a surface the target lies on does not
    /// count as a blocker. A target on the surface itself gives a zero-length ray that
    /// nothing occludes.
    pub fn spawn_to(&self, target: Vec3) -> Ray {
        let origin = offset_point(self.point, self.side_normal(target - self.point));
        let d = target - origin;
        let dist = d.length();
        if dist > 0.0 && dist.is_finite() {
            Ray {
                origin,
                dir: d / dist,
                t_max: dist * (1.0 - SHADOW_EPSILON),
            }
        } else {
            Ray {
                origin,
                dir: self.normal,
                t_max: 0.0,
            }
        }
    }

    /// The normal flipped to the side of `dir`.
    fn side_normal(&self, dir: Vec3) -> Vec3 {
        if dir.dot(self.normal) >= 0.0 {
            self.normal
        } else {
            -self.normal
        }
    }
}

/// Relative size of the offset in [`offset_point`]: 2⁻¹⁷, 64 units in the last place
/// of the largest coordinate.
pub const OFFSET_SCALE: f32 = 1.0 / 131_072.0;

/// Moves `p` off its surface along its unit normal `n` (to the side the new ray goes)
/// by [`OFFSET_SCALE`] times its largest coordinate magnitude (at least 1/32).
///
/// The rounding error of a hit point interpolated from barycentrics and carried through
/// an instance transform, and of the next ray's transformation back into object space,
/// is a few units in the last place of the coordinates (pbrt's bounds: Pharr et al.,
/// *Physically Based Rendering* 3rd ed., §3.9); 64 ulps exceed it with room to spare,
/// so the watertight test (which accepts only `t > 0`) finds the surface strictly
/// behind the new origin. Moving along the normal, not per coordinate as in Wächter &
/// Binder (*Ray Tracing Gems*, 2019, ch. 6), never pushes a point near an edge through
/// the neighbouring face of a convex corner.
pub fn offset_point(p: Vec3, n: Vec3) -> Vec3 {
    p + n * (OFFSET_SCALE * p.abs().max_element().max(1.0 / 32.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_moves_along_the_normal_at_every_magnitude() {
        for scale in [0.0f32, 1.0e-3, 1.0, 1.0e3, 1.0e6] {
            let p = Vec3::new(scale, -scale, 0.5 * scale);
            let n = Vec3::new(1.0, 2.0, -2.0) / 3.0;
            let q = offset_point(p, n);
            let d = q - p;
            // Each coordinate moves in the normal's direction, and strictly.
            for i in 0..3 {
                assert!(d[i] * n[i] > 0.0, "scale {scale} axis {i}: {d:?}");
            }
        }
    }

    #[test]
    fn shadow_ray_stops_short_of_its_target() {
        let it = Interaction {
            point: Vec3::ZERO,
            normal: Vec3::Z,
            material: MaterialId::from_index(0),
            uv: Vec2::ZERO,
            instance: InstanceId::from_index(0),
            triangle: 0,
        };
        let r = it.spawn_to(Vec3::new(0.0, 0.0, -2.0));
        assert!(
            r.origin.z < 0.0,
            "starts below the surface, towards the target"
        );
        assert!((r.dir - Vec3::NEG_Z).length() < 1.0e-6);
        let end = r.at(r.t_max).z;
        assert!(end > -2.0 && end < -2.0 + 2.0 * 2.0 * SHADOW_EPSILON);
    }
}
