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

use crate::triangle::{self, LaneHits, TriBlock, TriRay};
use glam::{UVec2, Vec3A, Vec4};
use obvhs::cwbvh::node::CwBvhNode;
use std::mem::MaybeUninit;

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
            // The sign bit, not `< 0.0`: a component of −0.0 has the inverse −∞ (clamped
            // to −10³⁰), so the slab test must take it as negative too, or near and far
            // swap and the ray misses everything (a sun along `-Vec3::Z` did).
            negative: [
                dir.x.is_sign_negative(),
                dir.y.is_sign_negative(),
                dir.z.is_sign_negative(),
            ],
            // The octant in obvhs's encoding (`ray_get_octant_inv4`).
            oct_inv4: (if dir.x.is_sign_negative() {
                0
            } else {
                0x0404_0404
            }) | (if dir.y.is_sign_negative() {
                0
            } else {
                0x0202_0202
            }) | (if dir.z.is_sign_negative() {
                0
            } else {
                0x0101_0101
            }),
        }
    }
}

/// The two tests traversal repeats, in one implementation per instruction set: the
/// child boxes of a node and the triangles of a leaf block.
pub(crate) trait Kernels {
    /// The hit mask of `node`'s children for `ray` within `0 ≤ t ≤ t_max`, in obvhs's
    /// layout (internal children in the high byte at their octant-ordered slot, leaf
    /// triangles in the low 24 bits).
    fn hits(node: &CwBvhNode, ray: &NodeRay, t_max: f32) -> u32;

    /// The hits of `ray` with the lanes `lanes` of `block` at `0 < t < t_max`
    /// ([`triangle::block_hits`]).
    fn leaf(block: &TriBlock, ray: &TriRay, t_max: f32, lanes: u32) -> LaneHits;
}

/// Four children at a time with `glam::Vec4` (SSE2 on x86-64, scalar elsewhere), and
/// one triangle at a time.
pub(crate) struct Portable;

/// Eight children and eight triangles at a time with AVX2; only called where the CPU
/// has it (see `Accel::intersect`), inlined into functions compiled with the feature.
#[cfg(target_arch = "x86_64")]
pub(crate) struct Avx2;

/// The hit mask from the 8-bit mask of intersected children.
#[inline(always)]
fn child_mask(node: &CwBvhNode, ray: &NodeRay, mut hit: u32) -> u32 {
    let (child_bits8, bit_index8) = node.get_child_and_index_bits(ray.oct_inv4);
    let mut mask = 0u32;
    while hit != 0 {
        let child = hit.trailing_zeros();
        hit &= hit - 1;
        let bits = ((child_bits8 >> (8 * child)) & 0xff) as u32;
        let index = ((bit_index8 >> (8 * child)) & 0xff) as u32;
        mask |= bits << index;
    }
    mask
}

impl Kernels for Portable {
    #[inline(always)]
    fn leaf(block: &TriBlock, ray: &TriRay, t_max: f32, lanes: u32) -> LaneHits {
        triangle::block_hits(block, ray, t_max, lanes)
    }

    #[inline(always)]
    fn hits(node: &CwBvhNode, ray: &NodeRay, t_max: f32) -> u32 {
        let scale = node.compute_extent() * ray.inv_dir;
        let shift = (Vec3A::from(node.p) - ray.origin) * ray.inv_dir;
        let quad = |v: &[u8; 8], i: usize| {
            Vec4::new(
                v[4 * i] as f32,
                v[4 * i + 1] as f32,
                v[4 * i + 2] as f32,
                v[4 * i + 3] as f32,
            )
        };
        let mut hit = 0u32;
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
            hit |= near.cmple(far).bitmask() << (4 * i);
        }
        child_mask(node, ray, hit)
    }
}

#[cfg(target_arch = "x86_64")]
impl Kernels for Avx2 {
    #[inline(always)]
    fn hits(node: &CwBvhNode, ray: &NodeRay, t_max: f32) -> u32 {
        // SAFETY: `Avx2` is only used inside functions compiled with AVX2 enabled, which
        // are only called after detecting it.
        unsafe { hits_avx2(node, ray, t_max) }
    }

    #[inline(always)]
    fn leaf(block: &TriBlock, ray: &TriRay, t_max: f32, lanes: u32) -> LaneHits {
        // SAFETY: as for `hits`.
        unsafe { triangle::block_hits_avx2(block, ray, t_max, lanes) }
    }
}

/// The eight children's near/far distances along one axis: quantised planes (8 bytes
/// each, widened to floats) times `s` plus `o`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn slab_avx2(
    lo: &[u8; 8],
    hi: &[u8; 8],
    negative: bool,
    s: f32,
    o: f32,
) -> (std::arch::x86_64::__m256, std::arch::x86_64::__m256) {
    use std::arch::x86_64::*;
    let (near, far) = if negative { (hi, lo) } else { (lo, hi) };
    // SAFETY: each load reads exactly the 8 bytes of its array (unaligned is allowed).
    let (near, far) = unsafe {
        (
            _mm_loadl_epi64(near.as_ptr() as *const __m128i),
            _mm_loadl_epi64(far.as_ptr() as *const __m128i),
        )
    };
    let (near, far) = (
        _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(near)),
        _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(far)),
    );
    let (s, o) = (_mm256_set1_ps(s), _mm256_set1_ps(o));
    (
        _mm256_add_ps(_mm256_mul_ps(near, s), o),
        _mm256_add_ps(_mm256_mul_ps(far, s), o),
    )
}

/// [`Kernels::hits`] for all eight children in one pass of 8-lane instructions.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn hits_avx2(node: &CwBvhNode, ray: &NodeRay, t_max: f32) -> u32 {
    use std::arch::x86_64::*;
    let scale = node.compute_extent() * ray.inv_dir;
    let shift = (Vec3A::from(node.p) - ray.origin) * ray.inv_dir;
    let (nx, fx) = slab_avx2(
        &node.child_min_x,
        &node.child_max_x,
        ray.negative[0],
        scale.x,
        shift.x,
    );
    let (ny, fy) = slab_avx2(
        &node.child_min_y,
        &node.child_max_y,
        ray.negative[1],
        scale.y,
        shift.y,
    );
    let (nz, fz) = slab_avx2(
        &node.child_min_z,
        &node.child_max_z,
        ray.negative[2],
        scale.z,
        shift.z,
    );
    let near = _mm256_max_ps(
        _mm256_max_ps(nx, ny),
        _mm256_max_ps(nz, _mm256_setzero_ps()),
    );
    let far = _mm256_min_ps(
        _mm256_mul_ps(
            _mm256_min_ps(_mm256_min_ps(fx, fy), fz),
            _mm256_set1_ps(EXIT_SCALE),
        ),
        _mm256_set1_ps(t_max),
    );
    let hit = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
    child_mask(node, ray, hit)
}

/// Asks the cache for the lines holding `*p` (a hint: any address is allowed).
#[inline(always)]
fn prefetch<P>(p: *const P) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let p = p as *const i8;
        let mut offset = 0;
        while offset < size_of::<P>() {
            // SAFETY: a prefetch never faults, whatever the address.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(offset)) };
            offset += 64;
        }
        // SAFETY: as above.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(size_of::<P>().max(1) - 1)) };
    }
}

/// Visits, near to far, the leaves of `nodes` the ray reaches before `*t_max`, a node's
/// at a time: `leaves(base, mask, t_max)` gets the primitive slots `base + i` for the
/// set bits `i` of `mask` (below 24), to be tested highest bit first; it may shrink
/// `*t_max` (closest hit) and returns `true` to end the traversal (any hit).
///
/// `prims` are the primitives, `PER` slots to an element (eight
/// for the bottom level's [`TriBlock`]s, one for the top level's instances): when a
/// node is tested, the children and the primitives it lets through are prefetched all
/// at once, so their cache misses overlap instead of following one another (the trees
/// outgrow the caches; a miss costs ~100 ns here). Allocates nothing.
#[inline(always)]
pub(crate) fn traverse<K: Kernels, P, F, const PER: u32>(
    nodes: &[CwBvhNode],
    prims: &[P],
    ray: &NodeRay,
    t_max: &mut f32,
    mut leaves: F,
) where
    F: FnMut(u32, u32, &mut f32) -> bool,
{
    if nodes.is_empty() {
        return;
    }
    let mut stack = [MaybeUninit::<UVec2>::uninit(); STACK_SIZE];
    let mut depth = 0usize;
    // The root as the only internal child of a virtual parent at index 0.
    let mut nodes_group = UVec2::new(0, 0x8000_0000);
    let mut prims_group = UVec2::ZERO;
    loop {
        if prims_group.y != 0 {
            if leaves(prims_group.x, prims_group.y, t_max) {
                return;
            }
            prims_group.y = 0;
        }
        if nodes_group.y & 0xff00_0000 != 0 {
            let hits = nodes_group.y;
            let offset = 31 - hits.leading_zeros();
            nodes_group.y &= !(1u32 << offset);
            if nodes_group.y & 0xff00_0000 != 0 {
                // Deeper than any real tree: overwrite the top rather than fail; the
                // build reports the depth (`AccelStats::max_depth`).
                stack[depth] = MaybeUninit::new(nodes_group);
                depth = (depth + 1).min(STACK_SIZE - 1);
            }
            let slot = (offset - 24) ^ (ray.oct_inv4 & 0xff);
            let relative = (hits & !(0xffff_ffffu32 << slot)).count_ones();
            let node = &nodes[(nodes_group.x + relative) as usize];
            let mask = K::hits(node, ray, *t_max);
            let mut inner = mask >> 24;
            while inner != 0 {
                let slot = inner.trailing_zeros() ^ (ray.oct_inv4 & 0xff);
                inner &= inner - 1;
                let relative = (node.imask as u32 & !(0xffff_ffffu32 << slot)).count_ones();
                prefetch(
                    nodes
                        .as_ptr()
                        .wrapping_add((node.child_base_idx + relative) as usize),
                );
            }
            let mut rest = mask & 0x00ff_ffff;
            while rest != 0 {
                let slot = node.primitive_base_idx + rest.trailing_zeros();
                let element = slot / PER;
                // The element's other slots need no prefetch of their own.
                let next = (element + 1) * PER - node.primitive_base_idx;
                rest &= u32::MAX.checked_shl(next).unwrap_or(0);
                prefetch(prims.as_ptr().wrapping_add(element as usize));
            }
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
            // SAFETY: every entry below `depth` was written by a push.
            nodes_group = unsafe { stack[depth].assume_init() };
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
