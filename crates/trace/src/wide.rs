//! Traversal of obvhs's compressed 8-wide BVH (Ylitie, Karras & Laine, "Efficient
//! Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", HPG 2017): 80-byte
//! nodes whose eight child boxes are quantised to 8 bits per plane relative to the
//! node's box, children ordered so that the ray octant gives a near-to-far order.
//!
//! obvhs builds the trees (PLOC + reinsertion); the traversal here is its `traverse!`
//! loop with our own node test, because obvhs's test culls boxes that end before
//! t = 10⁻⁴ (a hit that close to a spawned ray's origin would be lost) and does not
//! widen the box exit distance, which robust traversal needs (Ize, "Robust BVH Ray
//! Traversal", *JCGT* 2(2), 2013: scale t_far by 1 + 2γ₃).

use glam::{UVec2, Vec3A, Vec4};
use obvhs::cwbvh::node::CwBvhNode;

/// 1 + 2γ₃ with γₙ = nε/(1 − nε), ε = 2⁻²⁴ (Ize 2013, §3).
const EXIT_SCALE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Largest magnitude of an inverse direction component: keeps `0 · (1/0)` from giving NaN
/// in the slab test while leaving every product finite for scenes up to 10⁸ units.
const INV_DIR_LIMIT: f32 = 1.0e30;

/// Bound of the traversal stack. The stack holds at most one entry per tree level;
/// PLOC trees over real meshes are far shallower (obvhs validates depth < 32).
const STACK_SIZE: usize = 64;

/// Per-ray constants of the node test.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NodeRay {
    origin: Vec3A,
    inv_dir: Vec3A,
    negative: [bool; 3],
    oct_inv4: u32,
}

impl NodeRay {
    /// Constants for the ray `origin + t·dir`.
    #[inline(always)]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let inv = |d: f32| (1.0 / d).clamp(-INV_DIR_LIMIT, INV_DIR_LIMIT);
        NodeRay {
            origin,
            inv_dir: Vec3A::new(inv(dir.x), inv(dir.y), inv(dir.z)),
            negative: [dir.x < 0.0, dir.y < 0.0, dir.z < 0.0],
            // The octant in obvhs's encoding (`ray_get_octant_inv4`).
            oct_inv4: (if dir.x < 0.0 { 0 } else { 0x0404_0404 })
                | (if dir.y < 0.0 { 0 } else { 0x0202_0202 })
                | (if dir.z < 0.0 { 0 } else { 0x0101_0101 }),
        }
    }
}

/// The hit mask of `node`'s children for `ray` within `0 ≤ t ≤ t_max`, in obvhs's
/// layout: internal children in the high byte at their octant-ordered slot, leaf
/// triangles in the low 24 bits.
#[inline(always)]
fn intersect_node(node: &CwBvhNode, ray: &NodeRay, t_max: f32) -> u32 {
    let scale = node.compute_extent() * ray.inv_dir;
    let shift = (Vec3A::from(node.p) - ray.origin) * ray.inv_dir;
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(ray.oct_inv4);
    let quad = |v: &[u8; 8], i: usize| {
        Vec4::new(
            v[4 * i] as f32,
            v[4 * i + 1] as f32,
            v[4 * i + 2] as f32,
            v[4 * i + 3] as f32,
        )
    };
    let mut hit_mask = 0u32;
    for i in 0..2 {
        let slab = |lo: &[u8; 8], hi: &[u8; 8], neg: bool, s: f32, o: f32| {
            let (near, far) = if neg {
                (quad(hi, i), quad(lo, i))
            } else {
                (quad(lo, i), quad(hi, i))
            };
            let (s, o) = (Vec4::splat(s), Vec4::splat(o));
            (near * s + o, far * s + o)
        };
        let (nx, fx) = slab(
            &node.child_min_x,
            &node.child_max_x,
            ray.negative[0],
            scale.x,
            shift.x,
        );
        let (ny, fy) = slab(
            &node.child_min_y,
            &node.child_max_y,
            ray.negative[1],
            scale.y,
            shift.y,
        );
        let (nz, fz) = slab(
            &node.child_min_z,
            &node.child_max_z,
            ray.negative[2],
            scale.z,
            shift.z,
        );
        let near = nx.max(ny).max(nz).max(Vec4::ZERO);
        let far = (fx.min(fy).min(fz) * EXIT_SCALE).min(Vec4::splat(t_max));
        let mask = near.cmple(far).bitmask();
        for j in 0..4 {
            if mask & (1 << j) != 0 {
                let child = 4 * i + j;
                let bits = ((child_bits8 >> (8 * child)) & 0xff) as u32;
                let index = ((bit_index8 >> (8 * child)) & 0xff) as u32;
                hit_mask |= bits << index;
            }
        }
    }
    hit_mask
}

/// Visits, near to far, the primitive slots of `nodes` whose leaves the ray reaches
/// before `*t_max`. `leaf(slot, t_max)` may shrink `*t_max` (closest hit) and returns
/// `true` to end the traversal (any hit). Allocates nothing.
#[inline(always)]
pub(crate) fn traverse<F>(nodes: &[CwBvhNode], ray: &NodeRay, t_max: &mut f32, mut leaf: F)
where
    F: FnMut(u32, &mut f32) -> bool,
{
    if nodes.is_empty() {
        return;
    }
    let mut stack = [UVec2::ZERO; STACK_SIZE];
    let mut depth = 0usize;
    // The root as the only internal child of a virtual parent at index 0.
    let mut nodes_group = UVec2::new(0, 0x8000_0000);
    let mut prims_group = UVec2::ZERO;
    loop {
        while prims_group.y != 0 {
            let local = 31 - prims_group.y.leading_zeros();
            prims_group.y &= !(1u32 << local);
            if leaf(prims_group.x + local, t_max) {
                return;
            }
        }
        if nodes_group.y & 0xff00_0000 != 0 {
            let hits = nodes_group.y;
            let offset = 31 - hits.leading_zeros();
            nodes_group.y &= !(1u32 << offset);
            if nodes_group.y & 0xff00_0000 != 0 {
                // Deeper than any real tree: overwrite the top rather than fail; the
                // build reports the depth (`AccelStats::max_depth`).
                stack[depth] = nodes_group;
                depth = (depth + 1).min(STACK_SIZE - 1);
            }
            let slot = (offset - 24) ^ (ray.oct_inv4 & 0xff);
            let relative = (hits & !(0xffff_ffffu32 << slot)).count_ones();
            let node = &nodes[(nodes_group.x + relative) as usize];
            let mask = intersect_node(node, ray, *t_max);
            nodes_group = UVec2::new(
                node.child_base_idx,
                (mask & 0xff00_0000) | node.imask as u32,
            );
            prims_group = UVec2::new(node.primitive_base_idx, mask & 0x00ff_ffff);
        } else {
            nodes_group = UVec2::ZERO;
        }
        if prims_group.y == 0 && nodes_group.y & 0xff00_0000 == 0 {
            if depth == 0 {
                return;
            }
            depth -= 1;
            nodes_group = stack[depth];
        }
    }
}

/// Depth of the tree (root = 1), for the stack bound and statistics.
pub(crate) fn depth(nodes: &[CwBvhNode]) -> u32 {
    fn go(nodes: &[CwBvhNode], i: usize) -> u32 {
        let node = &nodes[i];
        (0..8)
            .filter(|&c| !node.is_child_empty(c) && !node.is_leaf(c))
            .map(|c| go(nodes, node.child_node_index(c) as usize))
            .max()
            .unwrap_or(0)
            + 1
    }
    if nodes.is_empty() { 0 } else { go(nodes, 0) }
}
