//! Calculation surfaces as the tracer sees them: instances left out of every tree, so
//! that no ray stops at them and none is shadowed by them, whose crossings a photon's
//! path asks for along each of its rays ([`Accel::crossings`]).
//!
//! They are kept as world-space triangles behind one box per instance and tested one by
//! one: a calculation surface is a plane of a few triangles (a workplane has two), and a
//! ray that misses the boxes costs a slab test per instance. Only scenes that have them
//! pay anything: with none, [`Accel::crossings`] returns at once.

use super::Accel;
use crate::ray::{Hit, OFFSET_SCALE, Ray};
use crate::triangle::{Tri, TriRay};
use glam::{Vec3, Vec3A};
use invlight_scene::{InstanceId, Scene};

/// One calculation instance: its triangles' range in [`Receivers::tris`] and their box.
#[derive(Debug, Clone, Copy)]
struct Group {
    start: u32,
    end: u32,
    lo: Vec3A,
    hi: Vec3A,
}

/// Every calculation instance's triangles in world space, for the current transforms.
#[derive(Debug, Clone, Default)]
pub(super) struct Receivers {
    /// Whether each instance of the scene is one (it is then in no tree).
    pub(super) of_instance: Vec<bool>,
    groups: Vec<Group>,
    tris: Vec<Tri>,
    /// Each triangle's instance and index in its mesh.
    ids: Vec<(InstanceId, u32)>,
}

impl Receivers {
    /// The calculation instances of `scene` (by [`Scene::calculation_instances`]), with
    /// no triangles until [`Receivers::place`].
    pub(super) fn new(scene: &Scene) -> Receivers {
        Receivers {
            of_instance: scene.calculation_instances(),
            ..Receivers::default()
        }
    }

    /// The world-space triangles of the calculation instances of `scene` as they are
    /// placed now: every triangle, whatever its material (a hole material receives too
    /// once it is a calculation surface).
    pub(super) fn place(&mut self, scene: &Scene) {
        self.groups.clear();
        self.tris.clear();
        self.ids.clear();
        for (i, _) in self.of_instance.iter().enumerate().filter(|(_, c)| **c) {
            let id = InstanceId::from_index(i);
            let start = self.tris.len() as u32;
            let (mut lo, mut hi) = (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY));
            for (t, w) in scene.world_triangles(id).enumerate() {
                if !w.corners.iter().all(|p| p.is_finite()) {
                    continue;
                }
                for &p in &w.corners {
                    lo = lo.min(p.into());
                    hi = hi.max(p.into());
                }
                self.tris.push(Tri { v: w.corners });
                self.ids.push((id, t as u32));
            }
            let end = self.tris.len() as u32;
            if end > start {
                self.groups.push(Group { start, end, lo, hi });
            }
        }
    }

    /// Triangles held.
    pub(super) fn len(&self) -> usize {
        self.tris.len()
    }
}

impl Accel {
    /// Whether the scene has calculation surfaces ([`Accel::crossings`] finds nothing
    /// when not).
    #[inline]
    pub fn has_calculation_surfaces(&self) -> bool {
        !self.receivers.groups.is_empty()
    }

    /// Calls `crossed` with each crossing of `ray` with a calculation surface before
    /// the ray's closest hit at `t_hit` (`f32::INFINITY` when it escapes): the surfaces
    /// it passes through on its way, in no particular order, each hit as
    /// [`Accel::intersect`] would report it ([`Accel::interaction`] reads it). A crossing
    /// within the rounding of the hit point (a calculation surface lying on the surface
    /// hit) counts, as a connection to it does (`photon::Targets::connect`); crossings
    /// inside a hole's volume do not, as no surface receives there.
    #[inline]
    pub fn crossings(&self, ray: &Ray, t_hit: f32, mut crossed: impl FnMut(Hit)) {
        if self.receivers.groups.is_empty() {
            return;
        }
        let end = if t_hit.is_finite() {
            t_hit + crossing_slack(ray.origin, ray.at(t_hit))
        } else {
            ray.t_max
        };
        let origin = Vec3A::from(ray.origin);
        let dir = Vec3A::from(ray.dir);
        let inv = dir.recip();
        let tri_ray = TriRay::new(origin, dir);
        for g in &self.receivers.groups {
            // Slab test of the group's box over (0, end).
            let t0 = (g.lo - origin) * inv;
            let t1 = (g.hi - origin) * inv;
            let near = t0.min(t1).max_element().max(0.0);
            let far = t0.max(t1).min_element().min(end);
            // NaN (a zero direction component on a box face) falls through to the
            // triangle tests, which decide exactly.
            if near > far {
                continue;
            }
            for k in g.start as usize..g.end as usize {
                let Some(h) = tri_ray.intersect(&self.receivers.tris[k], end) else {
                    continue;
                };
                if !self.holes.is_empty() && self.in_hole((origin + dir * h.t).into()) {
                    continue;
                }
                let (instance, triangle) = self.receivers.ids[k];
                crossed(Hit {
                    t: h.t,
                    instance,
                    triangle,
                    u: h.u,
                    v: h.v,
                });
            }
        }
    }
}

/// How far past a hit at `end` of a ray from `origin` a calculation surface still
/// counts as crossed: the rounding of the two ends, a few times over. A connection from
/// `origin` to a point `end` of a calculation surface is hidden only by a hit nearer than
/// this before it (`photon::Targets::connect`), so that both ways of reaching the point
/// see the same surfaces.
#[inline]
pub fn crossing_slack(origin: Vec3, end: Vec3) -> f32 {
    8.0 * OFFSET_SCALE * origin.abs().max(end.abs()).max_element().max(1.0 / 32.0)
}

#[cfg(test)]
mod tests {
    use crate::{Accel, Ray};
    use invlight_scene::{Mat4, Material, Mesh, Scene, Vec3};

    /// A unit square at z = 1 made a calculation surface over a grey floor at z = 0: rays
    /// pass it and stop at the floor; its crossing is reported before the hit only.
    #[test]
    fn rays_pass_a_calculation_surface_and_report_crossing_it() {
        let mut scene = Scene::default();
        let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let quad = |z: f32| {
            Mesh::quad(
                [
                    Vec3::new(0.0, 0.0, z),
                    Vec3::new(1.0, 0.0, z),
                    Vec3::new(1.0, 1.0, z),
                    Vec3::new(0.0, 1.0, z),
                ],
                grey,
            )
        };
        let (floor_mesh, plane_mesh) = (scene.add_mesh(quad(0.0)), scene.add_mesh(quad(1.0)));
        let floor = scene.add_instance("Floor", floor_mesh, Mat4::IDENTITY);
        let plane = scene.add_instance("Plane", plane_mesh, Mat4::IDENTITY);
        scene.make_calculation_surface(scene.surface("Plane").unwrap());
        let accel = Accel::new(&scene);
        assert_eq!(accel.stats().calculation_triangles, 2);
        let down = Ray::new(Vec3::new(0.3, 0.6, 2.0), Vec3::NEG_Z);
        let hit = accel.intersect(&down).unwrap();
        assert_eq!((hit.instance, hit.t), (floor, 2.0));
        let mut crossed = Vec::new();
        accel.crossings(&down, hit.t, |h| crossed.push(h));
        assert_eq!(crossed.len(), 1);
        assert_eq!((crossed[0].instance, crossed[0].t), (plane, 1.0));
        let at = accel.interaction(&scene, &down, &crossed[0]);
        assert!(at.point.distance(Vec3::new(0.3, 0.6, 1.0)) < 1e-6);
        assert_eq!(at.normal, Vec3::Z);
        // Up from the floor: nothing blocks, the crossing is on the way out.
        let up = Ray::new(Vec3::new(0.3, 0.6, 0.001), Vec3::Z);
        assert!(!accel.occluded(&up) && accel.intersect(&up).is_none());
        let mut n = 0;
        accel.crossings(&up, f32::INFINITY, |_| n += 1);
        assert_eq!(n, 1);
        // A ray ending before the plane, and one beside it, cross nothing.
        accel.crossings(&up, 0.5, |_| n += 1);
        let beside = Ray::new(Vec3::new(1.5, 0.6, 2.0), Vec3::NEG_Z);
        accel.crossings(&beside, f32::INFINITY, |_| n += 1);
        assert_eq!(n, 1);
        // Without calculation surfaces the plane blocks as any surface does.
        let mut plain = Scene::default();
        plain.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        plain.meshes = scene.meshes.clone();
        plain.add_instance("Floor", floor_mesh, Mat4::IDENTITY);
        plain.add_instance("Plane", plane_mesh, Mat4::IDENTITY);
        let accel = Accel::new(&plain);
        assert!(!accel.has_calculation_surfaces());
        assert_eq!(accel.intersect(&down).unwrap().instance, plane);
    }
}
