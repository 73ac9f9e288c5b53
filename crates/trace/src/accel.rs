//! The two-level acceleration structure: one BVH per mesh in object space (bottom level)
//! and one over the instances' world bounds (top level). Moving instances rebuilds only
//! the top level, as OptiX transform nodes did for ILPSolver (DESIGN.md §7).

use crate::holes::{HOLE_THICKNESS, HoleVolume};
use crate::ray::{Hit, Interaction, Ray};
use crate::triangle::{Tri, TriRay};
use crate::wide::{self, NodeRay, NodeTest};
use glam::{Affine3A, Mat4, Vec2, Vec3, Vec3A};
use invlight_scene::{InstanceId, MAX_COORDINATE, Mesh, MeshId, Scene};
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::node::Bvh2Node;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::cwbvh::{CwBvh, bvh2_to_cwbvh::bvh2_to_cwbvh};
use obvhs::ploc::PlocBuilder;
use obvhs::triangle::Triangle;
use obvhs::{Boundable, BvhBuildParams};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};
use std::time::Instant;

/// Counts and timings of a build, for logs and benchmarks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AccelStats {
    /// Bottom-level BVHs: one per mesh a separate instance uses, plus the merged one of
    /// [`Accel::with_movable`].
    pub meshes: usize,
    /// Entries of the top level: separate instances (holes and empty meshes are not)
    /// and the merged BVH.
    pub instances: usize,
    /// Hole volumes.
    pub holes: usize,
    /// Triangles over all bottom-level BVHs (each mesh once, however often instanced).
    pub triangles: usize,
    /// Bottom-level nodes (80 bytes each).
    pub blas_nodes: usize,
    /// Top-level nodes.
    pub tlas_nodes: usize,
    /// Deepest bottom-level tree, in nodes.
    pub max_depth: u32,
    /// Bytes of nodes and triangles traversal touches.
    pub bytes: usize,
    /// Seconds spent building the bottom level.
    pub blas_seconds: f64,
    /// Seconds spent building the top level (the last time it was built).
    pub tlas_seconds: f64,
}

/// A mesh's bottom-level BVH and its triangles laid out in the BVH's leaf order, so a
/// leaf's triangles are read from one place without an index indirection.
#[derive(Debug, Clone, Default)]
struct Blas {
    nodes: Vec<CwBvhNode>,
    tris: Vec<Tri>,
    /// Bounds of the traced triangles, or `None` when there are none.
    bounds: Option<(Vec3, Vec3)>,
    /// For the merged BVH of static instances ([`Accel::with_movable`]): the instance of
    /// each slot's triangle. Empty for a mesh's own BVH.
    instances: Vec<InstanceId>,
}

/// An instance as the top level stores it.
#[derive(Debug, Clone, Copy)]
struct TlasItem {
    object_from_world: Affine3A,
    /// The transform is the identity: the world ray's constants serve as they are.
    identity: bool,
    blas: u32,
    /// The instance hit; [`MERGED`] for the merged BVH, whose hits take theirs from
    /// [`Blas::instances`].
    instance: InstanceId,
}

/// The top-level entry of the merged BVH of static instances stands for no one instance.
const MERGED: InstanceId = InstanceId::from_index(u32::MAX as usize);

/// Each scene instance's transforms.
#[derive(Debug, Clone, Copy)]
struct Placed {
    world_from_object: Affine3A,
    object_from_world: Affine3A,
    mesh: MeshId,
    /// −1 when the transform mirrors (negative determinant), else 1. The front face is
    /// the counter-clockwise side *in world space*, as emission (`photon::Emitters`) and
    /// the loaders (glTF re-winds mirrored meshes) take it; the inverse transpose alone
    /// would give the opposite side for a mirrored instance.
    front_sign: f32,
}

/// Ray casting against a [`Scene`]: closest hit, any hit (shadow rays) and surface
/// interactions. Build with [`Accel::new`]; after moving instances (or holes) call
/// [`Accel::update_instances`]. Shared by reference across threads.
#[derive(Debug, Clone)]
pub struct Accel {
    /// A BVH per mesh (empty for meshes no separate instance uses), then the merged BVH
    /// of static instances.
    blas: Vec<Blas>,
    /// Object-space bounds of each mesh's hole triangles: one entry per mesh of the
    /// scene built from.
    hole_bounds: Vec<Option<(Vec3, Vec3)>>,
    /// With [`Accel::with_movable`]: the instances kept separate, and the transform each
    /// merged instance was baked with (`None` for separate ones).
    movable: Option<Vec<InstanceId>>,
    baked: Vec<Option<Mat4>>,
    placed: Vec<Placed>,
    tlas: Vec<CwBvhNode>,
    items: Vec<TlasItem>,
    holes: Vec<HoleVolume>,
    stats: AccelStats,
    /// Whether the CPU runs the AVX2 traversal.
    avx2: bool,
}

/// The build quality of both levels: obvhs's "medium" preset (PLOC with search radius
/// and reinsertion, up to 3 triangles per leaf). Its "fast", "slow" (spatial pre-splits)
/// and "very slow" presets traced Sponza within ±10 % of it, inside the noise, while
/// "slow" took twice and "very slow" six times as long to build (BENCHMARKS.md, "Ray casting").
fn build_params() -> BvhBuildParams {
    BvhBuildParams::medium_build()
}

/// obvhs's `build_cwbvh` (PLOC, reinsertion, conversion to 8-wide) without the validation
/// it runs in debug builds, which asserts a depth below 32 levels: the conference room's
/// tree reaches that (our traversal stack holds 64), and validating is slow.
///
/// Primitives sharing one bounding box, when [`COINCIDENT_GROUP`] or more do, are built
/// apart ([`coincident_groups`]): PLOC pairs a node with its cheapest neighbour, and
/// among equal boxes every candidate costs the same, so each node picks the farthest
/// one in its search window and almost no two agree: a pass merged about one pair per
/// run of equal boxes, and 30 000 copies of one triangle took 38 s to build (2 000 took
/// 0.28 s; BENCHMARKS.md, "Hostile inputs"). PLOC now sees one box per such group, and
/// each group's leaf is replaced by a balanced tree over its members
/// ([`expand_groups`]). A scene without such groups is built exactly as before.
fn build_cwbvh<T: Boundable>(prims: &[T]) -> CwBvh {
    let p = build_params();
    let ploc = |boxes: &[Aabb]| {
        PlocBuilder::with_capacity(boxes.len()).build(
            p.ploc_search_distance,
            boxes,
            (0..boxes.len() as u32).collect(),
            p.sort_precision,
            p.search_depth_threshold,
        )
    };
    let boxes: Vec<Aabb> = prims.iter().map(|t| t.aabb()).collect();
    let mut bvh2 = match coincident_groups(&boxes) {
        None => ploc(&boxes),
        Some(groups) => {
            let firsts: Vec<Aabb> = groups.iter().map(|g| boxes[g[0] as usize]).collect();
            expand_groups(&ploc(&firsts), &groups)
        }
    };
    ReinsertionOptimizer::default().run(&mut bvh2, p.reinsertion_batch_ratio, None);
    bvh2_to_cwbvh(&bvh2, p.max_prims_per_leaf.clamp(1, 3), true, false)
}

/// How many primitives must share a bounding box before they are built as a group:
/// PLOC's cost grows with the length of the longest run of equal boxes (about one
/// merge per run and pass), so runs this short cost a few passes at most, and the two
/// triangles of an axis-aligned quad, which always share their box, are left alone.
const COINCIDENT_GROUP: usize = 32;

/// FxHash (rustc-hash's multiply-rotate) over a box's bit patterns: the keys need no
/// defence against collisions chosen by an attacker, and are hashed once per box of
/// every build.
#[derive(Default)]
struct BoxHasher(u64);

impl Hasher for BoxHasher {
    fn finish(&self) -> u64 {
        self.0.rotate_left(26)
    }
    fn write(&mut self, bytes: &[u8]) {
        for word in bytes.chunks(8) {
            let mut w = [0u8; 8];
            w[..word.len()].copy_from_slice(word);
            self.write_u64(u64::from_le_bytes(w));
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// A map keyed by a box's six coordinates as bits.
type BoxMap<V> = HashMap<[u32; 6], V, BuildHasherDefault<BoxHasher>>;

/// The primitives grouped by bounding box (bit for bit), each group in input order and
/// the groups in the order of their first member; `None` when no box is shared by
/// [`COINCIDENT_GROUP`] primitives. Groups shorter than that are split back into single
/// primitives, so that only the large groups change the build.
fn coincident_groups(boxes: &[Aabb]) -> Option<Vec<Vec<u32>>> {
    let key = |b: &Aabb| {
        let (lo, hi) = (b.min.to_array(), b.max.to_array());
        [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]].map(f32::to_bits)
    };
    // 1. A filter, one cheap pass in the usual case: saturating counters indexed by the
    //    boxes' hash, as many as there are boxes, in a byte each. Equal boxes share a
    //    counter, so if none reaches COINCIDENT_GROUP no box does. Counting exactly in
    //    a map from the start cost a quarter of a second per million triangles.
    let bits = boxes.len().next_power_of_two().trailing_zeros().max(4);
    let mut counters = vec![0u8; 1 << bits];
    let mut suspect = false;
    for b in boxes {
        let mut h = BoxHasher::default();
        key(b).hash(&mut h);
        let slot = (h.finish().wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - bits)) as usize;
        counters[slot] = counters[slot].saturating_add(1);
        suspect |= counters[slot] as usize >= COINCIDENT_GROUP;
    }
    if !suspect {
        return None;
    }
    // 2. Exact counts, then the groups.
    let mut count: BoxMap<u32> = BoxMap::with_capacity_and_hasher(boxes.len(), Default::default());
    for b in boxes {
        *count.entry(key(b)).or_insert(0) += 1;
    }
    if count.values().all(|&c| (c as usize) < COINCIDENT_GROUP) {
        return None;
    }
    let mut slot: BoxMap<usize> = BoxMap::default();
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for (i, b) in boxes.iter().enumerate() {
        let k = key(b);
        if (count[&k] as usize) < COINCIDENT_GROUP {
            groups.push(vec![i as u32]);
            continue;
        }
        let g = *slot.entry(k).or_insert_with(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[g].push(i as u32);
    }
    Some(groups)
}

/// The BVH2 of `tree` (built over one box per group) with each group's leaf replaced
/// by a balanced binary tree over the group's primitives, all of the group's box.
/// Nodes are laid out breadth first, children in adjacent slots after their parent, as
/// obvhs's own builders leave them.
fn expand_groups(tree: &Bvh2, groups: &[Vec<u32>]) -> Bvh2 {
    let total: usize = groups.iter().map(Vec::len).sum();
    let mut nodes = Vec::with_capacity(2 * total);
    let mut indices = Vec::with_capacity(total);
    /// What a new node stands for: a node of `tree`, or a slice of a group's members.
    enum Part<'g> {
        Tree(usize),
        Members(&'g [u32], Aabb),
    }
    let mut queue = std::collections::VecDeque::new();
    nodes.push(Bvh2Node::default());
    queue.push_back((0usize, Part::Tree(0), 1usize));
    let mut depth = 0usize;
    while let Some((at, part, level)) = queue.pop_front() {
        depth = depth.max(level);
        let (aabb, children) = match part {
            Part::Tree(i) => {
                let node = tree.nodes[i];
                if node.is_leaf() {
                    let group = &groups[tree.primitive_indices[node.first_index as usize] as usize];
                    (*node.aabb(), ChildPair::Members(group))
                } else {
                    let c = node.first_index as usize;
                    (*node.aabb(), ChildPair::Tree(c, c + 1))
                }
            }
            Part::Members(m, aabb) => (aabb, ChildPair::Members(m)),
        };
        let split = match children {
            ChildPair::Members(&[one]) => {
                nodes[at] = Bvh2Node::new(aabb, 1, indices.len() as u32);
                indices.push(one);
                continue;
            }
            ChildPair::Members(m) => {
                let (a, b) = m.split_at(m.len() / 2);
                (Part::Members(a, aabb), Part::Members(b, aabb))
            }
            ChildPair::Tree(a, b) => (Part::Tree(a), Part::Tree(b)),
        };
        let first = nodes.len();
        nodes[at] = Bvh2Node::new(aabb, 0, first as u32);
        nodes.push(Bvh2Node::default());
        nodes.push(Bvh2Node::default());
        queue.push_back((first, split.0, level + 1));
        queue.push_back((first + 1, split.1, level + 1));
    }
    Bvh2 {
        nodes,
        primitive_indices: indices,
        children_are_ordered_after_parents: true,
        max_depth: tree.max_depth.max(depth),
        ..Bvh2::default()
    }
}

/// The children an expanded node gets: two nodes of the PLOC tree, or the members of a
/// group still to be split (a single member makes a leaf).
enum ChildPair<'g> {
    Tree(usize, usize),
    Members(&'g [u32]),
}

impl Accel {
    /// Builds a BVH per mesh and the top level over the instances.
    pub fn new(scene: &Scene) -> Accel {
        Accel::build(scene, None)
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
    /// past [`MAX_BAKED_TRIANGLES`] (many nodes placing the same meshes), every instance
    /// stays instanced instead, as with [`Accel::new`], so that the scene fits in memory.
    pub fn with_movable(scene: &Scene, movable: &[InstanceId]) -> Accel {
        Accel::build(scene, Some(movable.to_vec()))
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
    fn build(scene: &Scene, movable: Option<Vec<InstanceId>>) -> Accel {
        let start = Instant::now();
        let hole_material: Vec<bool> = scene.materials.iter().map(|m| m.hole).collect();
        let n = scene.instances.len();
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
        for (inst, &sep) in scene.instances.iter().zip(&separate) {
            if sep && let Some(u) = needed.get_mut(inst.mesh.index()) {
                *u = true;
            }
        }
        let mut hole_bounds = Vec::with_capacity(scene.meshes.len());
        let mut blas: Vec<Blas> = Vec::with_capacity(scene.meshes.len() + 1);
        for (m, &needed) in scene.meshes.iter().zip(&needed) {
            let (tris, holes) = mesh_triangles(m, &hole_material);
            hole_bounds.push(holes);
            blas.push(if needed {
                build_blas(tris, Vec::new())
            } else {
                Blas::default()
            });
        }
        let mut baked = vec![None; n];
        if movable.is_some() {
            let mut tris = Vec::new();
            let mut owners = Vec::new();
            for (id, inst) in scene.instances.iter().enumerate() {
                if separate[id] || inst.transform.determinant() == 0.0 {
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
            blas.push(build_blas(tris, owners));
        }
        let stats = AccelStats {
            meshes: blas.iter().filter(|b| !b.nodes.is_empty()).count(),
            triangles: blas.iter().map(|b| b.tris.len()).sum(),
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
            holes: Vec::new(),
            stats,
            avx2: avx2_available(),
        };
        accel.place_instances(scene);
        accel
    }

    /// Rebuilds the top level and the hole volumes from the scene's instance transforms,
    /// keeping every mesh's BVH. The scene's meshes, instances' meshes and materials'
    /// hole flags must be those the structure was built with; if the number of meshes or
    /// instances changed, or (see [`Accel::with_movable`]) a baked instance moved,
    /// everything is rebuilt.
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
        {
            *self = Accel::build(scene, self.movable.take());
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
            if self.baked[id].is_some() {
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
        if self.movable.is_some()
            && let Some(merged) = self.blas.last()
            && let Some((lo, hi)) = merged.bounds
        {
            boxes.push(Aabb::new(lo.into(), hi.into()));
            candidates.push(TlasItem {
                object_from_world: Affine3A::IDENTITY,
                identity: true,
                blas: (self.blas.len() - 1) as u32,
                instance: MERGED,
            });
        }
        let tlas = if boxes.is_empty() {
            CwBvh::default()
        } else {
            build_cwbvh(&boxes)
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
            .fold(Aabb::empty(), |all, b| all.union(b))
            .diagonal()
            .length();
        let thickness = if diagonal.is_finite() && diagonal > 0.0 {
            diagonal * HOLE_THICKNESS
        } else {
            HOLE_THICKNESS
        };
        self.holes = scene
            .instances
            .iter()
            .filter_map(|inst| {
                let (lo, hi) = (*self.hole_bounds.get(inst.mesh.index())?)?;
                HoleVolume::new(lo, hi, &inst.transform, thickness)
            })
            .collect();

        self.stats.instances = self.items.len();
        self.stats.holes = self.holes.len();
        self.stats.tlas_nodes = self.tlas.len();
        self.stats.tlas_seconds = start.elapsed().as_secs_f64();
        self.stats.bytes = (self.stats.blas_nodes + self.stats.tlas_nodes) * size_of::<CwBvhNode>()
            + self.stats.triangles * size_of::<Tri>()
            + self.items.len() * size_of::<TlasItem>();
    }

    /// Counts and build times.
    pub fn stats(&self) -> AccelStats {
        self.stats
    }

    /// The closest hit with `0 < t < ray.t_max`, skipping surfaces inside holes.
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU reports AVX2 and FMA.
            return unsafe { self.intersect_avx2(ray) };
        }
        self.closest::<wide::Portable>(ray)
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

    /// `occluded` compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt,popcnt")]
    unsafe fn occluded_avx2(&self, ray: &Ray) -> bool {
        self.any::<wide::Avx2>(ray)
    }

    #[inline(always)]
    fn closest<T: NodeTest>(&self, ray: &Ray) -> Option<Hit> {
        let mut best = None;
        self.trace::<T, _>(
            ray,
            #[inline(always)]
            |hit| {
                best = Some(hit);
                false
            },
        );
        best
    }

    #[inline(always)]
    fn any<T: NodeTest>(&self, ray: &Ray) -> bool {
        let mut blocked = false;
        self.trace::<T, _>(
            ray,
            #[inline(always)]
            |_| {
                blocked = true;
                true
            },
        );
        blocked
    }

    /// Walks both levels; `accept` receives each hit nearer than every earlier accepted
    /// one (the ray is shortened to it) and returns `true` to stop.
    ///
    /// Every closure on this path is `#[inline(always)]`: a closure does not inherit the
    /// target features of the function it is inlined into, so one left out of line
    /// would be compiled without AVX2 and call the node test out of line for every node
    /// (it did: 1.6 M rays per second in the photon loop instead of BENCHMARKS.md's figure).
    #[inline(always)]
    fn trace<T: NodeTest, F: FnMut(Hit) -> bool>(&self, ray: &Ray, mut accept: F) {
        let world = WorldRay::new(ray);
        let mut t_max = ray.t_max;
        if self.items.len() == 1 {
            // A single entry (one instance, or everything baked): its own root test
            // suffices.
            self.trace_instance::<T, F>(0, &world, &mut t_max, &mut accept);
        } else {
            wide::traverse::<T, _, _>(
                &self.tlas,
                &self.items,
                &world.node,
                &mut t_max,
                #[inline(always)]
                |slot, t_max| self.trace_instance::<T, F>(slot, &world, t_max, &mut accept),
            );
        }
    }

    /// Walks the bottom level of the top level's entry `slot`; returns `true` when
    /// `accept` asked to stop.
    #[inline(always)]
    fn trace_instance<T: NodeTest, F: FnMut(Hit) -> bool>(
        &self,
        slot: u32,
        world: &WorldRay,
        t_max: &mut f32,
        accept: &mut F,
    ) -> bool {
        let item = &self.items[slot as usize];
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
        wide::traverse::<T, _, _>(
            &blas.nodes,
            &blas.tris,
            &node_ray,
            t_max,
            #[inline(always)]
            |slot, t_max| {
                let tri = &blas.tris[slot as usize];
                let tri_ray = tri_ray.get_or_insert_with(|| TriRay::new(o, d));
                let Some(h) = tri_ray.intersect(tri, *t_max) else {
                    return false;
                };
                if !holes.is_empty() {
                    let p = origin + dir * h.t;
                    if holes.iter().any(|v| v.contains(p)) {
                        return false;
                    }
                }
                *t_max = h.t;
                stop = accept(Hit {
                    t: h.t,
                    instance: if blas.instances.is_empty() {
                        item.instance
                    } else {
                        blas.instances[slot as usize]
                    },
                    triangle: tri.index,
                    u: h.u,
                    v: h.v,
                });
                stop
            },
        );
        stop
    }

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
fn avx2_available() -> bool {
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

/// Whether a position lies where the BVH builder can take it: finite and within the
/// range [`Scene::validate`] accepts. obvhs indexes out of bounds on boxes whose areas
/// overflow (issue 19: a triangle 1e20 m wide, a node translated by 3e38 m), so what a
/// scene that skipped validation holds beyond it is not traced rather than built.
fn traceable(p: Vec3) -> bool {
    p.is_finite() && p.abs().max_element() <= MAX_COORDINATE
}

/// Peak bytes per bottom-level triangle while [`Accel`] builds: PLOC's nodes, Morton
/// codes and the input boxes, the reinsertion pass and the 8-wide tree, our triangle
/// copies in leaf order. Measured: 1 M triangles in one mesh peaked at 355 bytes each
/// (`hostile_bench memory 1000000 1`, VmHWM); rounded up.
pub const BUILD_BYTES_PER_TRIANGLE: u64 = 400;

/// Bytes per instance: its transforms, its top-level entry and box, and the top level's
/// share of PLOC. Measured: 200 000 instances of a 10-triangle mesh built by
/// [`Accel::new`] peaked at 622 bytes each (`hostile_bench memory 10 200000`); rounded
/// up.
pub const BYTES_PER_INSTANCE: u64 = 700;

/// Most triangles [`Accel::with_movable`] bakes into its world-space tree when baking
/// multiplies them (static instances sharing meshes): 2²² triangles, about
/// [`BUILD_BYTES_PER_TRIANGLE`] × 4.2 M ≈ 1 GB while it is built. Past that, and past
/// twice the triangles of the meshes themselves, the instances stay instanced: 50 000
/// nodes placing one 2 108-triangle mesh are 105 M triangles baked (which aborted on
/// an allocation, issue 19) but 2 108 triangles and 50 000 top-level entries instanced.
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

/// The BVH over `tris`, with `owners[i]` the instance of `tris[i]` for a merged BVH
/// (empty otherwise); the triangles are stored in the BVH's leaf order.
fn build_blas(tris: Vec<Corners>, owners: Vec<InstanceId>) -> Blas {
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
    let bvh = build_cwbvh(&prims);
    let mut lo = Vec3::splat(f32::INFINITY);
    let mut hi = Vec3::splat(f32::NEG_INFINITY);
    for (v, _) in &tris {
        for &p in v {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    let order = &bvh.primitive_indices;
    Blas {
        tris: order
            .iter()
            .map(|&i| {
                let (v, index) = tris[i as usize];
                Tri { v, index }
            })
            .collect(),
        instances: if owners.is_empty() {
            Vec::new()
        } else {
            order.iter().map(|&i| owners[i as usize]).collect()
        },
        nodes: bvh.nodes,
        bounds: Some((lo, hi)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use invlight_scene::{Mat4, Material, Quat};

    /// The AVX2 and portable node tests must agree hit for hit (the public functions
    /// take the AVX2 path wherever the CPU allows, so the portable one is checked here).
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
        scene.add_instance("b", id, rot);
        let accel = Accel::new(&scene);
        let mut hits = 0;
        for _ in 0..5000 {
            let origin = Vec3::new(next(), next(), next()) * 5.0;
            let dir = Vec3::new(next(), next(), next()).normalize_or(Vec3::X);
            let ray = Ray::new(origin, dir);
            let portable = accel.closest::<wide::Portable>(&ray);
            assert_eq!(accel.intersect(&ray), portable);
            assert_eq!(accel.occluded(&ray), accel.any::<wide::Portable>(&ray));
            hits += portable.is_some() as usize;
        }
        assert!(hits > 500, "{hits} hits");
    }
}
