//! One compressed 8-wide BVH over a list of boxes, as both levels build it: obvhs's
//! PLOC builder and reinsertion, converted to its CWBVH, with the groups of coincident
//! boxes built apart.

use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::node::Bvh2Node;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::cwbvh::{CwBvh, bvh2_to_cwbvh::bvh2_to_cwbvh};
use obvhs::ploc::PlocBuilder;
use obvhs::splits::split_aabbs_preset;
use obvhs::triangle::Triangle;
use obvhs::{Boundable, BvhBuildParams};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

/// How hard the builder works on both levels: one of obvhs's presets
/// (`BvhBuildParams::fastest_build` … `very_slow_build`), for [`Accel::with_preset`].
///
/// The default, [`BuildPreset::Medium`], is what every other constructor builds: the
/// fast, slow and very slow presets traced Sponza within ±10 % of it, inside the noise,
/// while slow took twice and very slow six times as long to build (BENCHMARKS.md, "Ray
/// casting"). The others are there to check that traversal does not depend on the tree's
/// shape (the brute-force tests run over [`BuildPreset::ALL`]) and to measure them again.
///
/// [`Accel::with_preset`]: super::Accel::with_preset
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum BuildPreset {
    /// PLOC pairing each node with its nearest neighbours only (search radius 1), no
    /// reinsertion, one primitive per leaf.
    Fastest,
    /// Search radius 1, 1 % of the nodes reinserted, up to 3 primitives per leaf (the
    /// 8-wide tree's limit, as for every preset below).
    VeryFast,
    /// Search radius 6, 2 % reinserted.
    Fast,
    /// Search radius 14, 5 % reinserted.
    #[default]
    Medium,
    /// Spatial pre-splits (a large triangle gets several tight boxes, so it may sit in
    /// several leaves), search radius 24, 20 % reinserted, 128-bit Morton codes.
    Slow,
    /// Pre-splits, search radius 14, every node considered for reinsertion once.
    VerySlow,
}

impl BuildPreset {
    /// Every preset, the fastest to build first, as obvhs's tests list them
    /// (`BUILD_PARAM_SET`).
    pub const ALL: [BuildPreset; 6] = [
        BuildPreset::Fastest,
        BuildPreset::VeryFast,
        BuildPreset::Fast,
        BuildPreset::Medium,
        BuildPreset::Slow,
        BuildPreset::VerySlow,
    ];

    /// obvhs's parameters of the preset.
    fn params(self) -> BvhBuildParams {
        match self {
            BuildPreset::Fastest => BvhBuildParams::fastest_build(),
            BuildPreset::VeryFast => BvhBuildParams::very_fast_build(),
            BuildPreset::Fast => BvhBuildParams::fast_build(),
            BuildPreset::Medium => BvhBuildParams::medium_build(),
            BuildPreset::Slow => BvhBuildParams::slow_build(),
            BuildPreset::VerySlow => BvhBuildParams::very_slow_build(),
        }
    }
}

/// The BVH over the boxes of `prims` (the top level's instances), built with `preset`;
/// its leaves name the primitives by index. Pre-splits need triangles
/// ([`build_triangle_cwbvh`]), so boxes are never split.
pub(super) fn build_cwbvh<T: Boundable>(prims: &[T], preset: BuildPreset) -> CwBvh {
    let boxes: Vec<Aabb> = prims.iter().map(|t| t.aabb()).collect();
    build(&boxes, None, &preset.params())
}

/// The BVH over `tris` (a bottom level), built with `preset`; its leaves name the
/// triangles by index. With a preset that pre-splits, large triangles are cut into
/// several tight boxes (obvhs's `split_aabbs_preset`, as its `build_cwbvh_from_tris`
/// does), and such a triangle is named by every leaf one of its boxes went to.
pub(super) fn build_triangle_cwbvh(tris: &[Triangle], preset: BuildPreset) -> CwBvh {
    let p = preset.params();
    let mut boxes: Vec<Aabb> = tris.iter().map(|t| t.aabb()).collect();
    if !p.pre_split || tris.is_empty() {
        return build(&boxes, None, &p);
    }
    let largest = boxes.iter().map(Aabb::half_area).fold(0.0, f32::max);
    let mean = boxes.iter().map(Aabb::half_area).sum::<f32>() / boxes.len() as f32;
    let mut owner: Vec<u32> = (0..tris.len() as u32).collect();
    split_aabbs_preset(&mut boxes, &mut owner, tris, mean, largest);
    build(&boxes, Some(&owner), &p)
}

/// obvhs's `build_cwbvh` (PLOC, reinsertion, conversion to 8-wide) with the parameters
/// `p`, without the validation it runs in debug builds, which asserts a depth below 32
/// levels: the conference room's tree reaches that (our traversal stack holds 64), and
/// validating is slow, and with the node list cut to its length. `owner[i]` is the
/// primitive box `i` bounds (several boxes of one primitive after pre-splits); `None`
/// when box `i` is primitive `i`.
///
/// Primitives sharing one bounding box, when [`COINCIDENT_GROUP`] or more do, are built
/// apart ([`coincident_groups`]): PLOC pairs a node with its cheapest neighbour, and
/// among equal boxes every candidate costs the same, so each node picks the farthest
/// one in its search window and almost no two agree: a pass merged about one pair per
/// run of equal boxes, and 30 000 copies of one triangle took 38 s to build (2 000 took
/// 0.28 s; BENCHMARKS.md, "Hostile inputs"). PLOC now sees one box per such group, and
/// each group's leaf is replaced by a balanced tree over its members
/// ([`expand_groups`]). Boxes without such groups are built by PLOC alone.
fn build(boxes: &[Aabb], owner: Option<&[u32]>, p: &BvhBuildParams) -> CwBvh {
    let ploc = |boxes: &[Aabb]| {
        PlocBuilder::with_capacity(boxes.len()).build(
            p.ploc_search_distance,
            boxes,
            (0..boxes.len() as u32).collect(),
            p.sort_precision,
            p.search_depth_threshold,
        )
    };
    let mut bvh2 = match coincident_groups(boxes) {
        None => ploc(boxes),
        Some(groups) => {
            let firsts: Vec<Aabb> = groups.iter().map(|g| boxes[g[0] as usize]).collect();
            expand_groups(&ploc(&firsts), &groups)
        }
    };
    ReinsertionOptimizer::default().run(&mut bvh2, p.reinsertion_batch_ratio, None);
    if let Some(owner) = owner {
        for i in &mut bvh2.primitive_indices {
            *i = owner[*i as usize];
        }
    }
    let mut cwbvh = bvh2_to_cwbvh(&bvh2, p.max_prims_per_leaf.clamp(1, 3), true, false);
    // obvhs reserves a node per primitive, about ten times what the 8-wide tree uses
    // (Sponza's baked tree: 6 923 nodes of 80 bytes for 66 456 triangles); the rest was
    // 4.8 MB of the structure's 8.3 MB of heap.
    cwbvh.nodes.shrink_to_fit();
    cwbvh
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    /// A tree keeps no spare nodes, on either level's path.
    #[test]
    fn node_lists_are_cut_to_their_length() {
        let boxes: Vec<Aabb> = (0..1000)
            .map(|i| Aabb::new(Vec3A::splat(i as f32), Vec3A::splat(i as f32 + 0.5)))
            .collect();
        let tree = build_cwbvh(&boxes, BuildPreset::default());
        assert!(
            tree.nodes.len() * 4 < boxes.len(),
            "{} nodes",
            tree.nodes.len()
        );
        assert_eq!(tree.nodes.capacity(), tree.nodes.len());
        let tris: Vec<Triangle> = boxes
            .iter()
            .map(|b| Triangle {
                v0: b.min,
                v1: b.max,
                v2: b.min + Vec3A::X,
            })
            .collect();
        let tree = build_triangle_cwbvh(&tris, BuildPreset::Slow);
        assert_eq!(tree.nodes.capacity(), tree.nodes.len());
    }
}
