//! Closest hit, closest hit unless blocked, and any hit: one traversal core walks the
//! merged tree of the static instances, the top level and, for each instance a ray
//! enters, that instance's bottom level; the queries differ only in what they do with a
//! hit.

use super::{Accel, TlasItem};
use crate::ray::{Hit, Ray};
use crate::triangle::TriRay;
use crate::wide::{self, Kernels, NodeRay};
use glam::{Vec3, Vec3A};

impl Accel {
    /// The closest hit with `0 < t < ray.t_max`, skipping surfaces inside holes.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU reports AVX2 and FMA.
            return unsafe { self.intersect_avx2(ray) };
        }
        self.closest::<wide::Portable>(ray)
    }

    /// [`Accel::intersect`] for a visibility test that needs the closest hit only when
    /// nothing lies before `block`: the first hit found nearer than `block` ends the
    /// traversal and is returned, though a nearer one may exist; otherwise the closest
    /// hit, as `intersect` finds it.
    ///
    /// A connection (`photon::Targets::connect`) counts when its ray's closest hit is
    /// the target, within a slack of the drawn point: a hit before the slack decides
    /// that it is hidden, as any hit decides a shadow ray, and the rays that do reach
    /// their target cost what `intersect` costs.
    pub fn intersect_unless_blocked(&self, ray: &Ray, block: f32) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `intersect`.
            return unsafe { self.intersect_unless_blocked_avx2(ray, block) };
        }
        self.closest_unless::<wide::Portable>(ray, block)
    }

    /// Whether anything outside the holes blocks the ray before `ray.t_max`.
    pub fn occluded(&self, ray: &Ray) -> bool {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: as in `intersect`.
            return unsafe { self.occluded_avx2(ray) };
        }
        self.any::<wide::Portable>(ray)
    }

    /// Whether `p` lies in a hole's volume, where surfaces are cut away: no ray stops
    /// there, so nothing arrives there either.
    pub fn in_hole(&self, p: Vec3) -> bool {
        let p = Vec3A::from(p);
        self.holes.iter().any(|v| v.contains(p))
    }

    /// `intersect` compiled for AVX2 (8 child boxes per instruction), chosen at run time
    /// so one binary runs everywhere and is fast where it can be.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn intersect_avx2(&self, ray: &Ray) -> Option<Hit> {
        self.closest::<wide::Avx2>(ray)
    }

    /// `intersect_unless_blocked` compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn intersect_unless_blocked_avx2(&self, ray: &Ray, block: f32) -> Option<Hit> {
        self.closest_unless::<wide::Avx2>(ray, block)
    }

    /// `occluded` compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn occluded_avx2(&self, ray: &Ray) -> bool {
        self.any::<wide::Avx2>(ray)
    }

    #[inline(always)]
    fn closest<K: Kernels>(&self, ray: &Ray) -> Option<Hit> {
        self.closest_unless::<K>(ray, f32::NEG_INFINITY)
    }

    #[inline(always)]
    fn closest_unless<K: Kernels>(&self, ray: &Ray, block: f32) -> Option<Hit> {
        let mut best = None;
        self.trace::<K, _>(
            ray,
            #[inline(always)]
            |hit| {
                best = Some(hit);
                hit.t < block
            },
        );
        best
    }

    #[inline(always)]
    fn any<K: Kernels>(&self, ray: &Ray) -> bool {
        let mut blocked = false;
        self.trace::<K, _>(
            ray,
            #[inline(always)]
            |_| {
                blocked = true;
                true
            },
        );
        blocked
    }

    /// Walks the merged BVH of the static instances, if any, then the top level and,
    /// for each instance a ray enters, its bottom level; `accept` receives each hit
    /// nearer than every earlier accepted one (the ray is shortened to it) and returns
    /// `true` to stop.
    ///
    /// The static scene first, as its own tree rather than one more top-level entry
    /// (which would cost every ray a top-level node and could walk a movable instance
    /// before the static hit shortened the ray): a search with one movable object then
    /// pays for it only with the rays that reach its box before the static hit
    /// (BENCHMARKS.md, "Engine speed").
    ///
    /// Every closure on this path is `#[inline(always)]`: a closure does not inherit the
    /// target features of the function it is inlined into, so one left out of line
    /// would be compiled without AVX2 and call the node test out of line for every node
    /// (it did: 1.6 M rays per second in the photon loop instead of BENCHMARKS.md's figure).
    #[inline(always)]
    fn trace<K: Kernels, F: FnMut(Hit) -> bool>(&self, ray: &Ray, mut accept: F) {
        let world = WorldRay::new(ray);
        let mut t_max = ray.t_max;
        if let Some(merged) = &self.merged
            && self.trace_instance::<K, F>(merged, &world, &mut t_max, &mut accept)
        {
            return;
        }
        match self.items.len() {
            0 => {}
            // A single entry: its own root test suffices.
            1 => {
                self.trace_instance::<K, F>(&self.items[0], &world, &mut t_max, &mut accept);
            }
            _ => wide::traverse::<K, _, _, 1>(
                &self.tlas,
                &self.items,
                &world.node,
                &mut t_max,
                #[inline(always)]
                |base, mut mask, t_max| {
                    while mask != 0 {
                        let local = 31 - mask.leading_zeros();
                        mask &= !(1 << local);
                        let item = &self.items[(base + local) as usize];
                        if self.trace_instance::<K, F>(item, &world, t_max, &mut accept) {
                            return true;
                        }
                    }
                    false
                },
            ),
        }
    }

    /// Walks the bottom level of the top-level entry `item`; returns `true` when
    /// `accept` asked to stop.
    #[inline(always)]
    fn trace_instance<K: Kernels, F: FnMut(Hit) -> bool>(
        &self,
        item: &TlasItem,
        world: &WorldRay,
        t_max: &mut f32,
        accept: &mut F,
    ) -> bool {
        let blas = &self.blas[item.blas as usize];
        let holes = &self.holes[..];
        let (origin, dir) = (world.origin, world.dir);
        // The triangle constants only once a leaf is reached: many instances a ray
        // enters are left at their root.
        let (node_ray, mut tri_ray, o, d) = if item.identity {
            (world.node, Some(world.tri), origin, dir)
        } else {
            let o = item.object_from_world.transform_point3a(origin);
            let d = item.object_from_world.transform_vector3a(dir);
            (NodeRay::new(o, d), None, o, d)
        };
        let mut stop = false;
        wide::traverse::<K, _, _, 8>(
            &blas.nodes,
            &blas.blocks,
            &node_ray,
            t_max,
            #[inline(always)]
            |base, mut mask, t_max| {
                let tri_ray = tri_ray.get_or_insert_with(|| TriRay::new(o, d));
                // The node's blocks, and each block's lanes, highest slot first: the
                // order in which the triangles were tested one at a time, so that of
                // hits at one distance the same one is kept.
                while mask != 0 {
                    let at = (31 - mask.leading_zeros()) / 8;
                    let lanes = (mask >> (8 * at)) & 0xff;
                    mask &= !(0xff << (8 * at));
                    let block = (base / 8 + at) as usize;
                    let start = *t_max;
                    let hits = K::leaf(&blas.blocks[block], tri_ray, start, lanes);
                    let mut rest = hits.mask;
                    while rest != 0 {
                        let lane = (31 - rest.leading_zeros()) as usize;
                        rest &= !(1 << lane);
                        // Each lane against the distance as it stands at its turn, as
                        // when tested one at a time: once a hit before it in the block
                        // has shortened the ray, the lane is tested again.
                        let h = if *t_max == start {
                            hits.hit(lane)
                        } else {
                            match tri_ray.intersect(&blas.blocks[block].lane(lane), *t_max) {
                                Some(h) => h,
                                None => continue,
                            }
                        };
                        if !holes.is_empty() {
                            let p = origin + dir * h.t;
                            if holes.iter().any(|v| v.contains(p)) {
                                continue;
                            }
                        }
                        *t_max = h.t;
                        let slot = block * 8 + lane;
                        stop = accept(Hit {
                            t: h.t,
                            instance: if blas.instances.is_empty() {
                                item.instance
                            } else {
                                blas.instances[slot]
                            },
                            triangle: blas.triangles[slot],
                            u: h.u,
                            v: h.v,
                        });
                        if stop {
                            return true;
                        }
                    }
                }
                false
            },
        );
        stop
    }
}

/// A world-space ray's constants for both the node and the triangle test, computed once
/// per ray and shared by every identity-transformed instance it enters.
#[derive(Clone, Copy)]
struct WorldRay {
    origin: Vec3A,
    dir: Vec3A,
    node: NodeRay,
    tri: TriRay,
}

impl WorldRay {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        let origin = Vec3A::from(ray.origin);
        let dir = Vec3A::from(ray.dir);
        WorldRay {
            origin,
            dir,
            node: NodeRay::new(origin, dir),
            tri: TriRay::new(origin, dir),
        }
    }
}

/// Whether the AVX2 traversal may run on this CPU.
pub(super) fn avx2_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        is_x86_feature_detected!("avx2")
            && is_x86_feature_detected!("fma")
            && is_x86_feature_detected!("bmi1")
            && is_x86_feature_detected!("bmi2")
            && is_x86_feature_detected!("lzcnt")
            && is_x86_feature_detected!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BuildPreset;
    use invlight_scene::{Mat4, Material, Mesh, Quat, Scene};

    /// The AVX2 and portable node tests must agree hit for hit, on the tree of every
    /// build preset, instanced and with one instance movable, for every query (the
    /// public functions take the AVX2 path wherever the CPU allows, so the portable one
    /// is checked here).
    #[test]
    fn portable_and_avx2_traversals_agree() {
        let mut scene = Scene::default();
        let mat = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let mut state = 1u32;
        let mut next = || {
            // Park–Miller minimal standard generator, fixed seed.
            state = ((state as u64 * 48_271) % 0x7fff_ffff) as u32;
            state as f32 / 0x7fff_ffff as f32 * 2.0 - 1.0
        };
        let mut mesh = Mesh::default();
        for t in 0..500u32 {
            let c = Vec3::new(next(), next(), next()) * 3.0;
            for _ in 0..3 {
                mesh.positions
                    .push(c + Vec3::new(next(), next(), next()) * 0.4);
            }
            mesh.triangles.push([3 * t, 3 * t + 1, 3 * t + 2]);
            mesh.materials.push(mat);
        }
        let id = scene.add_mesh(mesh);
        scene.add_instance("a", id, Mat4::IDENTITY);
        let rot = Mat4::from_rotation_translation(Quat::from_rotation_z(0.7), Vec3::X);
        let b = scene.add_instance("b", id, rot);
        let movable = [b];
        for (preset, movable) in BuildPreset::ALL
            .into_iter()
            .flat_map(|p| [(p, None), (p, Some(&movable[..]))])
        {
            let accel = Accel::with_preset(&scene, movable, preset);
            let mut hits = 0;
            for _ in 0..5000 {
                let origin = Vec3::new(next(), next(), next()) * 5.0;
                let dir = Vec3::new(next(), next(), next()).normalize_or(Vec3::X);
                let ray = Ray::new(origin, dir);
                let portable = accel.closest::<wide::Portable>(&ray);
                assert_eq!(accel.intersect(&ray), portable, "{preset:?} {movable:?}");
                let block = 2.0 * next().abs();
                assert_eq!(
                    accel.intersect_unless_blocked(&ray, block),
                    accel.closest_unless::<wide::Portable>(&ray, block),
                    "{preset:?} {movable:?}"
                );
                let any = accel.any::<wide::Portable>(&ray);
                assert_eq!(accel.occluded(&ray), any, "{preset:?} {movable:?}");
                hits += portable.is_some() as usize;
            }
            assert!(hits > 500, "{preset:?}: {hits} hits");
        }
    }
}
