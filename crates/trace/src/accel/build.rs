//! Building an [`Accel`] from a scene: the bottom level (a BVH per mesh, and the merged
//! BVH of baked static instances), the top level and the hole volumes, and the memory a
//! build takes.

use super::traverse::avx2_available;
use super::tree::{BuildPreset, build_cwbvh, build_triangle_cwbvh};
use super::{Accel, AccelStats, Blas, EMPTY_SLOT, MERGED, Placed, Receivers, TlasItem};
use crate::holes::{HOLE_THICKNESS, HoleVolume};
use crate::triangle::{Tri, TriBlock};
use crate::wide;
use glam::{Affine3A, Vec3};
use invlight_scene::{InstanceId, MAX_COORDINATE, Mesh, Scene};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::triangle::Triangle;
use std::time::Instant;

impl Accel {
    /// Builds a BVH per mesh and the top level over the instances.
    pub fn new(scene: &Scene) -> Accel {
        Accel::with_preset(scene, None, BuildPreset::default())
    }

    /// Like [`Accel::new`], but only the instances in `movable` get their own entry in
    /// the top level; every other instance is baked in world space into one shared BVH.
    ///
    /// Use it when the caller knows which instances will move (the objects, lights and
    /// holes a problem's variables place): a ray that starts inside the boxes of many
    /// overlapping static instances then walks one tree instead of entering each of them
    /// (Sponza's 34 groups as separate instances trace at 0.6–0.7× the single-tree rate;
    /// BENCHMARKS.md, "Ray casting"). [`Accel::update_instances`] still rebuilds only the top
    /// level while just the movable instances move; if a baked instance's transform
    /// changed, it rebuilds everything, correct but slow.
    ///
    /// Baking copies each static instance's triangles: when that would multiply them
    /// past 2²² triangles and twice the meshes' own (many nodes placing the same meshes),
    /// every instance stays instanced instead, as with [`Accel::new`], so that the scene
    /// fits in memory.
    pub fn with_movable(scene: &Scene, movable: &[InstanceId]) -> Accel {
        Accel::with_preset(scene, Some(movable), BuildPreset::default())
    }

    /// [`Accel::new`] (`movable` is `None`) or [`Accel::with_movable`] (`Some`) with the
    /// builder's effort chosen: both levels, and every rebuild by
    /// [`Accel::update_instances`], are built with `preset`, where the other constructors
    /// take [`BuildPreset::default`]. Traversal gives the same hits whatever the preset;
    /// only its speed and the build's time and memory differ.
    pub fn with_preset(
        scene: &Scene,
        movable: Option<&[InstanceId]>,
        preset: BuildPreset,
    ) -> Accel {
        Accel::build(scene, movable.map(<[InstanceId]>::to_vec), preset)
    }

    /// Refuses, with the figure, a scene whose build would take more than `limit` bytes
    /// ([`Accel::estimated_bytes`]): `path` names the scene file in the message.
    pub fn check_memory(
        scene: &Scene,
        path: &std::path::Path,
        limit: u64,
    ) -> Result<(), invlight_scene::Diagnostic> {
        let need = Accel::estimated_bytes(scene);
        if need <= limit {
            return Ok(());
        }
        Err(invlight_scene::Diagnostic::new(
            path,
            format!(
                "tracing the scene would need {:.1} GB for its ray-tracing structure, past the {:.1} GB limit",
                need as f64 / 1e9,
                limit as f64 / 1e9
            ),
        )
        .with_hint(format!(
            "raise --max-memory (e.g. --max-memory {}G) if the machine has the memory",
            need.div_ceil(1 << 30) + 1
        )))
    }

    /// An upper bound of the bytes building an [`Accel`] of `scene` takes at its peak,
    /// by [`Accel::new`] or [`Accel::with_movable`] with any instances movable: the larger
    /// of the mesh triangles and the triangles baking would flatten (when it bakes) at
    /// [`BUILD_BYTES_PER_TRIANGLE`] and the instances at [`BYTES_PER_INSTANCE`]. A program
    /// can compare it with the memory it may use before building ([`Accel::check_memory`]).
    /// The scene's own meshes are not counted: interactions read them where they are.
    /// [`Accel::with_preset`] with a slow preset may take more: its pre-splits add
    /// boxes.
    pub fn estimated_bytes(scene: &Scene) -> u64 {
        let unique: u64 = scene.meshes.iter().map(|m| m.triangles.len() as u64).sum();
        let all_static = vec![false; scene.instances.len()];
        let baked: u64 = if bakes(scene, &all_static) {
            scene
                .instances
                .iter()
                .filter_map(|i| scene.meshes.get(i.mesh.index()))
                .map(|m| m.triangles.len() as u64)
                .sum()
        } else {
            0
        };
        unique.max(baked) * BUILD_BYTES_PER_TRIANGLE
            + scene.instances.len() as u64 * BYTES_PER_INSTANCE
    }

    /// Builds the bottom level (a BVH per mesh used by a separate instance, plus the
    /// merged BVH when `movable` is given), then the top level.
    fn build(scene: &Scene, movable: Option<Vec<InstanceId>>, preset: BuildPreset) -> Accel {
        let start = Instant::now();
        let hole_material: Vec<bool> = scene.materials.iter().map(|m| m.hole).collect();
        let n = scene.instances.len();
        // Calculation surfaces are in no tree: rays pass them (see `receivers`).
        let receivers = Receivers::new(scene);
        let separate: Vec<bool> = match &movable {
            None => vec![true; n],
            Some(ids) => {
                let mut v = vec![false; n];
                for &i in ids {
                    if let Some(s) = v.get_mut(i.index()) {
                        *s = true;
                    }
                }
                if bakes(scene, &v) { v } else { vec![true; n] }
            }
        };
        let mut needed = vec![false; scene.meshes.len()];
        for ((inst, &sep), &calc) in scene
            .instances
            .iter()
            .zip(&separate)
            .zip(&receivers.of_instance)
        {
            if sep
                && !calc
                && let Some(u) = needed.get_mut(inst.mesh.index())
            {
                *u = true;
            }
        }
        let mut hole_bounds = Vec::with_capacity(scene.meshes.len());
        let mut blas: Vec<Blas> = Vec::with_capacity(scene.meshes.len() + 1);
        for (m, &needed) in scene.meshes.iter().zip(&needed) {
            let (tris, holes) = mesh_triangles(m, &hole_material);
            hole_bounds.push(holes);
            blas.push(if needed {
                build_blas(tris, Vec::new(), preset)
            } else {
                Blas::default()
            });
        }
        let mut baked = vec![None; n];
        if movable.is_some() {
            let mut tris = Vec::new();
            let mut owners = Vec::new();
            for (id, inst) in scene.instances.iter().enumerate() {
                if separate[id] || receivers.of_instance[id] || inst.transform.determinant() == 0.0
                {
                    continue;
                }
                let Some(mesh) = scene.meshes.get(inst.mesh.index()) else {
                    continue;
                };
                let (local, _) = mesh_triangles(mesh, &hole_material);
                if local.is_empty() {
                    // A hole (or empty) instance: nothing to bake, free to move.
                    continue;
                }
                baked[id] = Some(inst.transform);
                for (v, t) in local {
                    let w = v.map(|p| inst.transform.transform_point3(p));
                    if w.iter().all(|&p| traceable(p)) {
                        tris.push((w, t));
                        owners.push(InstanceId::from_index(id));
                    }
                }
            }
            blas.push(build_blas(tris, owners, preset));
        }
        let stats = AccelStats {
            meshes: blas.iter().filter(|b| !b.nodes.is_empty()).count(),
            triangles: blas.iter().map(Blas::triangle_count).sum(),
            blas_nodes: blas.iter().map(|b| b.nodes.len()).sum(),
            max_depth: blas
                .iter()
                .map(|b| wide::depth(&b.nodes))
                .max()
                .unwrap_or(0),
            blas_seconds: start.elapsed().as_secs_f64(),
            ..AccelStats::default()
        };
        let mut accel = Accel {
            blas,
            hole_bounds,
            movable,
            baked,
            placed: Vec::new(),
            tlas: Vec::new(),
            items: Vec::new(),
            merged: None,
            holes: Vec::new(),
            receivers,
            stats,
            preset,
            avx2: avx2_available(),
        };
        accel.place_instances(scene);
        accel
    }

    /// Rebuilds the top level and the hole volumes from the scene's instance transforms,
    /// keeping every mesh's BVH. The scene's meshes, instances' meshes and materials'
    /// hole flags must be those the structure was built with; if the number of meshes or
    /// instances changed, the calculation surfaces changed, or (see
    /// [`Accel::with_movable`]) a baked instance moved, everything is rebuilt.
    pub fn update_instances(&mut self, scene: &Scene) {
        let moved_baked = self.movable.is_some()
            && scene
                .instances
                .iter()
                .zip(&self.baked)
                .any(|(inst, b)| b.is_some_and(|m| m != inst.transform));
        if scene.meshes.len() != self.hole_bounds.len()
            || scene.instances.len() != self.baked.len()
            || moved_baked
            || scene.calculation_instances() != self.receivers.of_instance
        {
            *self = Accel::build(scene, self.movable.take(), self.preset);
            return;
        }
        self.place_instances(scene);
    }

    /// The top level and hole volumes for the current transforms.
    fn place_instances(&mut self, scene: &Scene) {
        let start = Instant::now();
        self.placed = scene
            .instances
            .iter()
            .map(|inst| {
                let world_from_object = Affine3A::from_mat4(inst.transform);
                Placed {
                    world_from_object,
                    object_from_world: world_from_object.inverse(),
                    mesh: inst.mesh,
                    front_sign: if world_from_object.matrix3.determinant() < 0.0 {
                        -1.0
                    } else {
                        1.0
                    },
                }
            })
            .collect();
        let invertible = |p: &Placed| {
            p.world_from_object.matrix3.determinant() != 0.0
                && p.object_from_world.matrix3.is_finite()
                && p.object_from_world.translation.is_finite()
        };
        let mut boxes = Vec::new();
        let mut candidates = Vec::new();
        for (id, p) in self.placed.iter().enumerate() {
            if self.baked[id].is_some() || self.receivers.of_instance[id] {
                continue;
            }
            let Some(blas) = self.blas.get(p.mesh.index()) else {
                continue;
            };
            if let Some((lo, hi)) = blas.bounds
                && invertible(p)
                && let b = world_box(lo, hi, &p.world_from_object)
                && traceable(b.min.into())
                && traceable(b.max.into())
            {
                boxes.push(b);
                candidates.push(TlasItem {
                    object_from_world: p.object_from_world,
                    identity: p.world_from_object == Affine3A::IDENTITY,
                    blas: p.mesh.index() as u32,
                    instance: InstanceId::from_index(id),
                });
            }
        }
        // The merged BVH of the static instances stays out of the top level: every ray
        // walks it first, and the movable instances' small tree after it, with the
        // distance the static scene left (see `Accel::trace`).
        let mut merged_box = None;
        self.merged = None;
        if self.movable.is_some()
            && let Some(merged) = self.blas.last()
            && let Some((lo, hi)) = merged.bounds
        {
            merged_box = Some(Aabb::new(lo.into(), hi.into()));
            self.merged = Some(TlasItem {
                object_from_world: Affine3A::IDENTITY,
                identity: true,
                blas: (self.blas.len() - 1) as u32,
                instance: MERGED,
            });
        }
        let tlas = if boxes.is_empty() {
            CwBvh::default()
        } else {
            build_cwbvh(&boxes, self.preset)
        };
        self.items = tlas
            .primitive_indices
            .iter()
            .map(|&i| candidates[i as usize])
            .collect();
        self.tlas = tlas.nodes;

        // The scene's size from the instance boxes just computed (not from every vertex:
        // this runs at every move).
        let diagonal = boxes
            .iter()
            .chain(&merged_box)
            .fold(Aabb::empty(), |all, b| all.union(b))
            .diagonal()
            .length();
        let thickness = if diagonal.is_finite() && diagonal > 0.0 {
            diagonal * HOLE_THICKNESS
        } else {
            HOLE_THICKNESS
        };
        // A calculation surface of a hole material receives: it cuts no hole.
        self.holes = scene
            .instances
            .iter()
            .zip(&self.receivers.of_instance)
            .filter(|(_, calc)| !**calc)
            .filter_map(|(inst, _)| {
                let (lo, hi) = (*self.hole_bounds.get(inst.mesh.index())?)?;
                HoleVolume::new(lo, hi, &inst.transform, thickness)
            })
            .collect();
        self.receivers.place(scene);

        self.stats.instances = self.items.len() + self.merged.is_some() as usize;
        self.stats.holes = self.holes.len();
        self.stats.calculation_triangles = self.receivers.len();
        self.stats.tlas_nodes = self.tlas.len();
        self.stats.tlas_seconds = start.elapsed().as_secs_f64();
        let (blocks, slots) = self.blas.iter().fold((0, 0), |(b, s), blas| {
            (b + blas.blocks.len(), s + blas.triangles.len())
        });
        self.stats.bytes = (self.stats.blas_nodes + self.stats.tlas_nodes) * size_of::<CwBvhNode>()
            + blocks * size_of::<TriBlock>()
            + slots * size_of::<u32>()
            + self.stats.instances * size_of::<TlasItem>();
    }
}

/// Whether a position lies where the BVH builder can take it: finite and within the
/// range [`Scene::validate`] accepts. obvhs indexes out of bounds on boxes whose areas
/// overflow (a triangle 1e20 m wide, a node translated by 3e38 m), so what a
/// scene that skipped validation holds beyond it is not traced rather than built.
fn traceable(p: Vec3) -> bool {
    p.is_finite() && p.abs().max_element() <= MAX_COORDINATE
}

/// Peak bytes per bottom-level triangle while [`Accel`] builds: PLOC's nodes, Morton
/// codes and the input boxes, the reinsertion pass and the 8-wide tree. The peak is
/// PLOC's: the leaf blocks (36 bytes a slot and 4 for its index, empty lanes included)
/// are laid out after its temporaries are freed. Measured: 1 M triangles in one mesh
/// peaked at 355 bytes each (`hostile_bench memory 1000000 1`, VmHWM); rounded up.
pub const BUILD_BYTES_PER_TRIANGLE: u64 = 400;

/// Bytes per instance: its transforms, its top-level entry and box, and the top level's
/// share of PLOC. Measured: 200 000 instances of a 10-triangle mesh built by
/// [`Accel::new`] peaked at 618 bytes each (`hostile_bench memory 10 200000`); rounded
/// up.
pub const BYTES_PER_INSTANCE: u64 = 700;

/// Most triangles [`Accel::with_movable`] bakes into its world-space tree when baking
/// multiplies them (static instances sharing meshes): 2²² triangles, about
/// [`BUILD_BYTES_PER_TRIANGLE`] × 4.2 M ≈ 1 GB while it is built. Past that, and past
/// twice the triangles of the meshes themselves, the instances stay instanced: 50 000
/// nodes placing one 2 108-triangle mesh are 105 M triangles baked (an allocation that
/// fails) but 2 108 triangles and 50 000 top-level entries instanced.
const MAX_BAKED_TRIANGLES: usize = 1 << 22;

/// Whether [`Accel::with_movable`] bakes the instances not marked `separate`: when the
/// flattened triangles stay within [`MAX_BAKED_TRIANGLES`] or within twice those of the
/// meshes they place (a scene whose meshes are placed once costs nothing to bake).
fn bakes(scene: &Scene, separate: &[bool]) -> bool {
    let mut flattened = 0usize;
    let mut used = vec![false; scene.meshes.len()];
    for (inst, _) in scene.instances.iter().zip(separate).filter(|(_, s)| !**s) {
        if let Some(mesh) = scene.meshes.get(inst.mesh.index()) {
            flattened += mesh.triangles.len();
            used[inst.mesh.index()] = true;
        }
    }
    let unique: usize = scene
        .meshes
        .iter()
        .zip(&used)
        .filter(|(_, u)| **u)
        .map(|(m, _)| m.triangles.len())
        .sum();
    flattened <= MAX_BAKED_TRIANGLES.max(2 * unique)
}

/// World bounds of the object box `lo..hi` under `m`, from its eight corners.
fn world_box(lo: Vec3, hi: Vec3, m: &Affine3A) -> Aabb {
    let mut b = Aabb::empty();
    for i in 0..8 {
        let c = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        b.extend(m.transform_point3a(c.into()));
    }
    b
}

/// A triangle's corners and its index in its mesh.
type Corners = ([Vec3; 3], u32);

/// A mesh's traced (non-hole) triangles, and the bounds of its hole triangles; triangles
/// with out-of-range vertex indices or positions beyond [`MAX_COORDINATE`] are left
/// out.
fn mesh_triangles(mesh: &Mesh, hole_material: &[bool]) -> (Vec<Corners>, Option<(Vec3, Vec3)>) {
    let is_hole = |t: usize| {
        let m = mesh.materials.get(t).map_or(usize::MAX, |m| m.index());
        hole_material.get(m).copied().unwrap_or(false)
    };
    let corners = |t: usize| -> Option<[Vec3; 3]> {
        let [a, b, c] = mesh.triangles[t];
        Some([
            *mesh.positions.get(a as usize)?,
            *mesh.positions.get(b as usize)?,
            *mesh.positions.get(c as usize)?,
        ])
    };
    let mut tris = Vec::new();
    let mut hole_bounds: Option<(Vec3, Vec3)> = None;
    for t in 0..mesh.triangles.len() {
        let Some(v) = corners(t).filter(|v| v.iter().all(|&p| traceable(p))) else {
            continue;
        };
        if is_hole(t) {
            let (lo, hi) = hole_bounds.unwrap_or((v[0], v[0]));
            hole_bounds = Some((
                lo.min(v[0]).min(v[1]).min(v[2]),
                hi.max(v[0]).max(v[1]).max(v[2]),
            ));
        } else {
            tris.push((v, t as u32));
        }
    }
    (tris, hole_bounds)
}

/// The BVH over `tris` built with `preset`, with `owners[i]` the instance of `tris[i]`
/// for a merged BVH (empty otherwise); the triangles are stored in the BVH's leaf order,
/// a pre-split triangle once in each leaf that holds it, each node's in blocks of eight
/// (see [`Blas`]).
fn build_blas(tris: Vec<Corners>, owners: Vec<InstanceId>, preset: BuildPreset) -> Blas {
    if tris.is_empty() {
        return Blas::default();
    }
    let prims: Vec<Triangle> = tris
        .iter()
        .map(|(v, _)| Triangle {
            v0: v[0].into(),
            v1: v[1].into(),
            v2: v[2].into(),
        })
        .collect();
    let bvh = build_triangle_cwbvh(&prims, preset);
    drop(prims);
    let mut lo = Vec3::splat(f32::INFINITY);
    let mut hi = Vec3::splat(f32::NEG_INFINITY);
    for (v, _) in &tris {
        for &p in v {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let order = &bvh.primitive_indices;
    let mut nodes = bvh.nodes;
    let mut blocks = Vec::new();
    let mut triangles = Vec::new();
    let mut instances = Vec::new();
    for node in &mut nodes {
        // The node's slots run from its base to the end of its last leaf.
        let slots = (0..8)
            .filter(|&c| node.is_leaf(c) && !node.is_child_empty(c))
            .map(|c| {
                let (start, n) = node.child_primitives(c);
                (start - node.primitive_base_idx + n) as usize
            })
            .max()
            .unwrap_or(0);
        let first = node.primitive_base_idx as usize;
        // Nodes without leaves get the running base too: their hit masks name no slot.
        node.primitive_base_idx = (8 * blocks.len()) as u32;
        for chunk in order[first..first + slots].chunks(8) {
            let mut block = TriBlock::default();
            for (lane, &i) in chunk.iter().enumerate() {
                let (v, index) = tris[i as usize];
                block.set(lane, &Tri { v });
                triangles.push(index);
                if !owners.is_empty() {
                    instances.push(owners[i as usize]);
                }
            }
            blocks.push(block);
            triangles.resize(8 * blocks.len(), EMPTY_SLOT);
            if !owners.is_empty() {
                instances.resize(8 * blocks.len(), MERGED);
            }
        }
    }
    // Grown by doubling: cut to length, as the node lists are.
    blocks.shrink_to_fit();
    triangles.shrink_to_fit();
    instances.shrink_to_fit();
    Blas {
        nodes,
        blocks,
        triangles,
        instances,
        bounds: Some((lo, hi)),
    }
}
