//! The two-level acceleration structure: one BVH per mesh in object space (bottom level)
//! and one over the instances' world bounds (top level). Moving instances rebuilds only
//! the top level, as OptiX transform nodes did for ILPSolver (DESIGN.md §7).
//!
//! - `build`: the bottom level (a BVH per mesh, and the merged BVH of the static
//!   instances [`Accel::with_movable`] bakes) with its leaves laid out as blocks of
//!   eight triangles, the top level and the hole volumes, and what a build costs in
//!   memory.
//! - `tree`: one compressed 8-wide BVH over a list of boxes: obvhs's builder, and the
//!   groups of coincident boxes built apart from it.
//! - `traverse`: closest hit and any hit, through the merged BVH of the static
//!   instances, then the top level's loop over instances into each bottom level, with
//!   AVX2 where the CPU has it (eight child boxes, then eight triangles, at a time).
//! - `interaction`: the surface at a hit, read from the scene's mesh.
//! - `receivers`: calculation surfaces, in no tree: the crossings of a ray with them.
//!
//! The hole volumes are `crate::holes`, the node test and the loop over a tree
//! `crate::wide`, the triangle test and the blocks of eight `crate::triangle`.

mod build;
mod interaction;
mod receivers;
mod traverse;
mod tree;

pub use build::{BUILD_BYTES_PER_TRIANGLE, BYTES_PER_INSTANCE};
pub use receivers::crossing_slack;
pub use tree::BuildPreset;

use crate::holes::HoleVolume;
use crate::triangle::TriBlock;
use glam::{Affine3A, Mat4, Vec3};
use invlight_scene::{InstanceId, MeshId};
use obvhs::cwbvh::node::CwBvhNode;
use receivers::Receivers;

/// Counts and timings of a build, for logs and benchmarks.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AccelStats {
    /// Bottom-level BVHs: one per mesh a separate instance uses, plus the merged one of
    /// [`Accel::with_movable`].
    pub meshes: usize,
    /// Trees a ray may enter below the top level: separate instances (holes and empty
    /// meshes are not) and the merged BVH, which rays walk before the top level.
    pub instances: usize,
    /// Hole volumes.
    pub holes: usize,
    /// Triangles of calculation surfaces, which no tree holds
    /// ([`Accel::crossings`]).
    pub calculation_triangles: usize,
    /// Triangles over all bottom-level BVHs (each mesh once, however often instanced);
    /// with a preset that pre-splits ([`BuildPreset::Slow`]), a triangle counts once per
    /// leaf that holds it.
    pub triangles: usize,
    /// Bottom-level nodes (80 bytes each).
    pub blas_nodes: usize,
    /// Top-level nodes (over the separate instances only).
    pub tlas_nodes: usize,
    /// Deepest bottom-level tree, in nodes.
    pub max_depth: u32,
    /// Bytes of nodes and triangles traversal touches: the blocks of eight, empty lanes
    /// included, with each slot's triangle index.
    pub bytes: usize,
    /// Seconds spent building the bottom level.
    pub blas_seconds: f64,
    /// Seconds spent building the top level (the last time it was built).
    pub tlas_seconds: f64,
}

/// A mesh's bottom-level BVH and its triangles laid out in the BVH's leaf order, so a
/// leaf's triangles are read from one place without an index indirection.
///
/// The triangles of each node's leaves are [`TriBlock`]s of eight, tested eight at a
/// time: the node's `primitive_base_idx` is its first block times eight, and the leaf
/// bits of its hit mask (below 24) are the slots `8 · block + lane` from there, so one
/// bit per triangle still names it. A node with fewer than a multiple of eight
/// triangles leaves lanes empty (`TriBlock`'s padding, never hit).
#[derive(Debug, Clone, Default)]
struct Blas {
    nodes: Vec<CwBvhNode>,
    blocks: Vec<TriBlock>,
    /// Each slot's triangle, by its index in the mesh (or in the instance's mesh for the
    /// merged BVH); [`EMPTY_SLOT`] for an empty lane.
    triangles: Vec<u32>,
    /// Bounds of the traced triangles, or `None` when there are none.
    bounds: Option<(Vec3, Vec3)>,
    /// For the merged BVH of static instances ([`Accel::with_movable`]): the instance of
    /// each slot's triangle. Empty for a mesh's own BVH.
    instances: Vec<InstanceId>,
}

impl Blas {
    /// Triangles in the leaves, empty lanes left out (a pre-split triangle once per
    /// leaf that holds it).
    fn triangle_count(&self) -> usize {
        self.triangles.iter().filter(|&&t| t != EMPTY_SLOT).count()
    }
}

/// A tree a ray enters and how: an instance as the top level stores it, or the merged
/// BVH of the static instances.
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

/// The entry of the merged BVH of static instances stands for no one instance.
const MERGED: InstanceId = InstanceId::from_index(u32::MAX as usize);

/// [`Blas::triangles`]' entry for a lane of a block no triangle fills.
const EMPTY_SLOT: u32 = u32::MAX;

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

/// Ray casting against a [`Scene`](invlight_scene::Scene): closest hit, any hit (shadow
/// rays) and surface interactions. Build with [`Accel::new`]; after moving instances (or
/// holes) call [`Accel::update_instances`]. Shared by reference across threads.
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
    /// The top level over the separate instances, and its entries in leaf order.
    tlas: Vec<CwBvhNode>,
    items: Vec<TlasItem>,
    /// With [`Accel::with_movable`]: the entry of the merged BVH of the static instances,
    /// which rays walk before the top level rather than through it.
    merged: Option<TlasItem>,
    holes: Vec<HoleVolume>,
    /// The calculation surfaces' instances, which no tree holds.
    receivers: Receivers,
    stats: AccelStats,
    /// How both levels are built, now and at every rebuild.
    preset: BuildPreset,
    /// Whether the CPU runs the AVX2 traversal.
    avx2: bool,
}

impl Accel {
    /// Counts and build times.
    pub fn stats(&self) -> AccelStats {
        self.stats
    }
}
