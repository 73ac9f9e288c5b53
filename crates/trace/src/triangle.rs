//! Watertight ray/triangle intersection: Woop, Benthin & Wald, "Watertight Ray/Triangle
//! Intersection", *JCGT* 2(1), 2013.
//!
//! The ray is made the +z axis of a sheared frame; each vertex is transformed by the same
//! per-ray operations, so the 2D edge functions of two triangles sharing an edge are
//! exact negatives of each other and a ray through the edge hits one of them. Edge
//! functions that round to zero are recomputed in double precision, as the paper does.
//!
//! Leaves are stored as [`TriBlock`]s, eight triangles by coordinate, and tested eight at
//! once ([`block_hits_avx2`] where the CPU has AVX2, [`block_hits`] lane by lane
//! elsewhere); each lane gives bit for bit what [`TriRay::intersect`] gives for its
//! triangle.

use glam::{Mat3A, Vec3, Vec3A};

/// A triangle's object-space corners, as the one-triangle test takes them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tri {
    pub v: [Vec3; 3],
}

/// Eight triangles by coordinate (structure of arrays): `v[corner][axis][lane]`, 288
/// bytes, each row of eight lanes one aligned AVX2 load. A lane no triangle fills has
/// all its corners at the origin: every edge function is exactly zero, in double
/// precision too, so its determinant is zero and [`TriRay::intersect`] rejects it,
/// whatever the ray.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct TriBlock {
    pub v: [[[f32; 8]; 3]; 3],
}

impl TriBlock {
    /// Puts `tri`'s corners in lane `lane`.
    pub fn set(&mut self, lane: usize, tri: &Tri) {
        for (corner, p) in self.v.iter_mut().zip(tri.v) {
            for (axis, row) in corner.iter_mut().enumerate() {
                row[lane] = p[axis];
            }
        }
    }

    /// The triangle in lane `lane`.
    #[inline(always)]
    pub fn lane(&self, lane: usize) -> Tri {
        let corner = |c: &[[f32; 8]; 3]| Vec3::new(c[0][lane], c[1][lane], c[2][lane]);
        Tri {
            v: [corner(&self.v[0]), corner(&self.v[1]), corner(&self.v[2])],
        }
    }
}

/// The lanes of a [`TriBlock`] a ray hits: bit `i` of `mask` for lane `i`, and the
/// lane's [`TriHit`] in `t`, `u`, `v` where its bit is set (unspecified elsewhere).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LaneHits {
    pub mask: u32,
    pub t: [f32; 8],
    pub u: [f32; 8],
    pub v: [f32; 8],
}

impl LaneHits {
    /// No lane hit.
    const NONE: LaneHits = LaneHits {
        mask: 0,
        t: [0.0; 8],
        u: [0.0; 8],
        v: [0.0; 8],
    };

    /// Lane `lane`'s hit (its bit must be set).
    #[inline(always)]
    pub fn hit(&self, lane: usize) -> TriHit {
        TriHit {
            t: self.t[lane],
            u: self.u[lane],
            v: self.v[lane],
        }
    }

    /// Records `hit` for lane `lane`.
    #[inline(always)]
    fn set(&mut self, lane: usize, hit: TriHit) {
        self.mask |= 1 << lane;
        self.t[lane] = hit.t;
        self.u[lane] = hit.u;
        self.v[lane] = hit.v;
    }
}

/// Largest origin coordinate for which `vertex − origin` stays finite for vertices
/// within `MAX_COORDINATE` (10⁹), with room to spare.
const TAME_ORIGIN: f32 = 1.0e37;

/// Per-ray constants of the sheared frame: `shear · (p − origin)` gives a vertex's
/// coordinates (x, y across the ray, z along it scaled to t).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriRay {
    origin: Vec3A,
    shear: Mat3A,
    /// The shear's non-zero entries for the block test: `axes` are the paper's
    /// (kx, ky, kz), `coefficients` (−Sx, −Sy, Sz), so that a vertex's sheared
    /// coordinates are `d[kx] + (−Sx)·d[kz]`, `d[ky] + (−Sy)·d[kz]` and `Sz·d[kz]`.
    axes: [usize; 3],
    coefficients: [f32; 3],
    /// Whether `p − origin` is finite for every traced vertex `p` (|p| ≤
    /// `MAX_COORDINATE`): then the shear's zero entries add signed zeros only.
    tame: bool,
}

/// A hit: distance and the barycentrics of vertices 1 and 2.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriHit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
}

impl TriRay {
    /// Constants for the ray `origin + t·dir` (`dir` need not be unit).
    #[inline(always)]
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let a = dir.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if dir[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let (sx, sy, sz) = (dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
        // Column k of the shear holds what coordinate k contributes to (x, y, z): the
        // paper's `A[kx] − Sx·A[kz]`, `A[ky] − Sy·A[kz]`, `Sz·A[kz]`, each sum having a
        // single rounded product, so every vertex is transformed exactly as in the paper.
        let mut cols = [Vec3A::ZERO; 3];
        cols[kx] = Vec3A::X;
        cols[ky] = Vec3A::Y;
        cols[kz] = Vec3A::new(-sx, -sy, sz);
        TriRay {
            origin,
            shear: Mat3A::from_cols(cols[0], cols[1], cols[2]),
            axes: [kx, ky, kz],
            coefficients: [-sx, -sy, sz],
            tame: origin.is_finite() && origin.abs().max_element() <= TAME_ORIGIN,
        }
    }

    /// The hit of this ray with `tri` at `0 < t < t_max`, from either side.
    #[inline(always)]
    pub fn intersect(&self, tri: &Tri, t_max: f32) -> Option<TriHit> {
        let a = self.shear * (Vec3A::from(tri.v[0]) - self.origin);
        let b = self.shear * (Vec3A::from(tri.v[1]) - self.origin);
        let c = self.shear * (Vec3A::from(tri.v[2]) - self.origin);
        let mut u = c.x * b.y - c.y * b.x;
        let mut v = a.x * c.y - a.y * c.x;
        let mut w = b.x * a.y - b.y * a.x;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
            u = (c.x * b.y - c.y * b.x) as f32;
            v = (a.x * c.y - a.y * c.x) as f32;
            w = (b.x * a.y - b.y * a.x) as f32;
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let t_scaled = u * a.z + v * b.z + w * c.z;
        // Two-sided: compare with the sign of det folded in, t > 0 strictly.
        let sign = det.to_bits() & 0x8000_0000;
        let t_signed = f32::from_bits(t_scaled.to_bits() ^ sign);
        if !(t_signed > 0.0 && t_signed < t_max * det.abs()) {
            return None;
        }
        let inv = 1.0 / det;
        let t = t_scaled * inv;
        // Guard the division's rounding against the strict bounds the caller relies on.
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        Some(TriHit {
            t,
            u: v * inv,
            v: w * inv,
        })
    }
}

/// The hits of `ray` with the lanes of `block` selected by the bits of `lanes`, each
/// tested with [`TriRay::intersect`] at `0 < t < t_max`.
#[inline(always)]
pub(crate) fn block_hits(block: &TriBlock, ray: &TriRay, t_max: f32, lanes: u32) -> LaneHits {
    let mut hits = LaneHits::NONE;
    lanes_one_by_one(&mut hits, block, ray, t_max, lanes & 0xff);
    hits
}

/// Tests the lanes of `block` selected by `lanes` one at a time with
/// [`TriRay::intersect`], recording their hits in `hits`.
#[inline(always)]
fn lanes_one_by_one(hits: &mut LaneHits, block: &TriBlock, ray: &TriRay, t_max: f32, lanes: u32) {
    let mut rest = lanes;
    while rest != 0 {
        let lane = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        if let Some(h) = ray.intersect(&block.lane(lane), t_max) {
            hits.set(lane, h);
        }
    }
}

/// [`block_hits`] with all eight lanes in one pass of AVX2 instructions: the operations
/// of [`TriRay::intersect`], in its order, on eight lanes (multiplies and adds apart, as
/// there: no fused multiply-add), less the shear's products with its entries of zero,
/// so each lane's result is bit for bit the one-triangle test's. Lanes with an edge
/// function of zero are left to that test, which recomputes them in double precision;
/// they are rare (a ray through an edge or a vertex). A ray from beyond 10³⁷ (never a
/// traced scene's) is tested lane by lane.
///
/// Without a target feature of its own so that it is always inlined, into the
/// traversal compiled with AVX2 (`Accel::intersect_avx2`, …), where its intrinsics are
/// inlined in turn; as a `#[target_feature]` function the compiler called it out of
/// line, with its result passed through memory.
///
/// # Safety
///
/// The CPU must have AVX2.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) unsafe fn block_hits_avx2(
    block: &TriBlock,
    ray: &TriRay,
    t_max: f32,
    lanes: u32,
) -> LaneHits {
    use std::arch::x86_64::*;
    // SAFETY: the caller runs on a CPU with AVX2; each load reads a row of 8 floats at a
    // 32-byte aligned offset of the 32-byte aligned block, each store the 8 floats of
    // its array (unaligned is allowed).
    if !ray.tame {
        return block_hits(block, ray, t_max, lanes);
    }
    let (mut hits, exact) = unsafe {
        let lanes = lanes & 0xff;
        let origin = [
            _mm256_set1_ps(ray.origin.x),
            _mm256_set1_ps(ray.origin.y),
            _mm256_set1_ps(ray.origin.z),
        ];
        let [kx, ky, kz] = ray.axes;
        let [sx, sy, sz] = ray.coefficients.map(|c| _mm256_set1_ps(c));
        // The corners in the sheared frame from the shear's non-zero entries. Each is
        // `shear * (p − origin)` as glam's `Mat3A * Vec3A` computes it but for the
        // products with the entries of zero, which add signed zeros (`d` is finite:
        // `tame`): it differs only where a coordinate is zero, in that zero's sign, and
        // a sign of zero reaches no result but through an edge function of zero, whose
        // lane is left to the one-triangle test below.
        let mut q = [[_mm256_setzero_ps(); 3]; 3];
        for (q, corner) in q.iter_mut().zip(&block.v) {
            let mut d = [_mm256_setzero_ps(); 3];
            for (d, (row, o)) in d.iter_mut().zip(corner.iter().zip(origin)) {
                *d = _mm256_sub_ps(_mm256_load_ps(row.as_ptr()), o);
            }
            *q = [
                _mm256_add_ps(d[kx], _mm256_mul_ps(sx, d[kz])),
                _mm256_add_ps(d[ky], _mm256_mul_ps(sy, d[kz])),
                _mm256_mul_ps(sz, d[kz]),
            ];
        }
        let [a, b, c] = q;
        let u = _mm256_sub_ps(_mm256_mul_ps(c[0], b[1]), _mm256_mul_ps(c[1], b[0]));
        let v = _mm256_sub_ps(_mm256_mul_ps(a[0], c[1]), _mm256_mul_ps(a[1], c[0]));
        let w = _mm256_sub_ps(_mm256_mul_ps(b[0], a[1]), _mm256_mul_ps(b[1], a[0]));
        let zero = _mm256_setzero_ps();
        let exact = _mm256_or_ps(
            _mm256_or_ps(
                _mm256_cmp_ps::<_CMP_EQ_OQ>(u, zero),
                _mm256_cmp_ps::<_CMP_EQ_OQ>(v, zero),
            ),
            _mm256_cmp_ps::<_CMP_EQ_OQ>(w, zero),
        );
        let negative = _mm256_or_ps(
            _mm256_or_ps(
                _mm256_cmp_ps::<_CMP_LT_OQ>(u, zero),
                _mm256_cmp_ps::<_CMP_LT_OQ>(v, zero),
            ),
            _mm256_cmp_ps::<_CMP_LT_OQ>(w, zero),
        );
        let positive = _mm256_or_ps(
            _mm256_or_ps(
                _mm256_cmp_ps::<_CMP_GT_OQ>(u, zero),
                _mm256_cmp_ps::<_CMP_GT_OQ>(v, zero),
            ),
            _mm256_cmp_ps::<_CMP_GT_OQ>(w, zero),
        );
        let det = _mm256_add_ps(_mm256_add_ps(u, v), w);
        let t_scaled = _mm256_add_ps(
            _mm256_add_ps(_mm256_mul_ps(u, a[2]), _mm256_mul_ps(v, b[2])),
            _mm256_mul_ps(w, c[2]),
        );
        let sign_bit = _mm256_set1_ps(-0.0);
        let t_signed = _mm256_xor_ps(t_scaled, _mm256_and_ps(det, sign_bit));
        let det_abs = _mm256_andnot_ps(sign_bit, det);
        let t_max8 = _mm256_set1_ps(t_max);
        let inv = _mm256_div_ps(_mm256_set1_ps(1.0), det);
        let t = _mm256_mul_ps(t_scaled, inv);
        let pass = _mm256_and_ps(
            _mm256_and_ps(
                _mm256_cmp_ps::<_CMP_NEQ_UQ>(det, zero),
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GT_OQ>(t_signed, zero),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(t_signed, _mm256_mul_ps(t_max8, det_abs)),
                ),
            ),
            _mm256_and_ps(
                _mm256_cmp_ps::<_CMP_GT_OQ>(t, zero),
                _mm256_cmp_ps::<_CMP_LT_OQ>(t, t_max8),
            ),
        );
        let pass = _mm256_andnot_ps(_mm256_and_ps(negative, positive), pass);
        let exact = _mm256_movemask_ps(exact) as u32 & lanes;
        let mut hits = LaneHits {
            mask: _mm256_movemask_ps(pass) as u32 & lanes & !exact,
            ..LaneHits::NONE
        };
        _mm256_storeu_ps(hits.t.as_mut_ptr(), t);
        _mm256_storeu_ps(hits.u.as_mut_ptr(), _mm256_mul_ps(v, inv));
        _mm256_storeu_ps(hits.v.as_mut_ptr(), _mm256_mul_ps(w, inv));
        (hits, exact)
    };
    lanes_one_by_one(&mut hits, block, ray, t_max, exact);
    hits
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Tri {
        Tri {
            v: [a.into(), b.into(), c.into()],
        }
    }

    #[test]
    fn hits_from_both_sides_with_barycentrics() {
        let t = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        for (z, d) in [(1.0, -1.0), (-1.0, 1.0)] {
            let r = TriRay::new(Vec3A::new(0.25, 0.5, z), Vec3A::new(0.0, 0.0, d));
            let h = r.intersect(&t, f32::INFINITY).expect("hit");
            assert!((h.t - 1.0).abs() < 1e-6);
            assert!((h.u - 0.25).abs() < 1e-6 && (h.v - 0.5).abs() < 1e-6);
            assert!(r.intersect(&t, 0.999).is_none(), "t_max is exclusive");
        }
        let behind = TriRay::new(Vec3A::new(0.25, 0.5, 1.0), Vec3A::Z);
        assert!(behind.intersect(&t, f32::INFINITY).is_none());
    }

    /// Test input drawn from the project's SplitMix64 stream.
    struct Rng(invlight_stats::SplitMix64);

    impl Rng {
        /// Uniform in [−1, 1].
        fn signed(&mut self) -> f32 {
            self.0.uniform(-1.0, 1.0) as f32
        }
        fn vec(&mut self, scale: f32) -> Vec3 {
            Vec3::new(self.signed(), self.signed(), self.signed()) * scale
        }
        fn below(&mut self, n: u64) -> u64 {
            self.0.below(n as usize) as u64
        }
    }

    /// A ray for a block: aimed at a corner, an edge's midpoint, into a triangle, along
    /// a triangle's plane, or anywhere; some directions with zero components.
    fn ray_at(rng: &mut Rng, block: &TriBlock) -> (Vec3A, Vec3A) {
        let tri = block.lane(rng.below(8) as usize).v;
        let origin = rng.vec(4.0);
        let target = match rng.below(5) {
            0 => tri[rng.below(3) as usize],
            1 => (tri[0] + tri[1]) * 0.5,
            2 => (tri[0] + tri[1] + tri[2]) / 3.0,
            3 => {
                // In the plane, along an edge: the ray is parallel to the triangle.
                let origin = tri[0] + (tri[2] - tri[0]) * 0.25 - (tri[1] - tri[0]);
                return (origin.into(), (tri[1] - tri[0]).into());
            }
            _ => rng.vec(2.0),
        };
        let mut dir = target - origin;
        if rng.below(100) == 0 {
            // From so far that only the lane-by-lane test takes it.
            return ((origin * 1.0e38).into(), dir.into());
        }
        if rng.below(8) == 0 {
            dir[rng.below(3) as usize] = 0.0;
        }
        (origin.into(), dir.into())
    }

    /// A block of triangles sharing corners and edges (a fan, so rays through a corner
    /// or an edge reach several), some of them axis aligned, with empty lanes.
    fn block(rng: &mut Rng) -> TriBlock {
        let mut block = TriBlock::default();
        let centre = rng.vec(1.0);
        let mut last = centre + rng.vec(1.0);
        for lane in 0..8 {
            if rng.below(6) == 0 {
                continue;
            }
            let mut next = centre + rng.vec(1.0);
            if rng.below(4) == 0 {
                next.z = centre.z;
                last.z = centre.z;
            }
            let v = match rng.below(3) {
                0 => [centre, last, next],
                1 => [last, next, centre],
                _ => [rng.vec(2.0), rng.vec(2.0), rng.vec(2.0)],
            };
            block.set(lane, &Tri { v });
            last = next;
        }
        block
    }

    /// Every lane of the AVX2 block test and of the portable one gives, bit for bit, the
    /// one-triangle test's result, and lanes left out of the mask and empty lanes never
    /// hit.
    #[test]
    fn lanes_match_the_one_triangle_test() {
        let mut rng = Rng(invlight_stats::SplitMix64::new(20));
        #[cfg(target_arch = "x86_64")]
        let avx2 = is_x86_feature_detected!("avx2");
        let (mut hits, mut edges) = (0, 0);
        for _ in 0..20_000 {
            let block = block(&mut rng);
            let (origin, dir) = ray_at(&mut rng, &block);
            let ray = TriRay::new(origin, dir);
            let t_max = match rng.below(3) {
                0 => f32::INFINITY,
                _ => (rng.signed() + 1.0) * 4.0,
            };
            let lanes = if rng.below(2) == 0 {
                0xff
            } else {
                rng.below(256) as u32
            };
            let mut each: Vec<LaneHits> = vec![block_hits(&block, &ray, t_max, lanes)];
            #[cfg(target_arch = "x86_64")]
            if avx2 {
                // SAFETY: the CPU has AVX2.
                each.push(unsafe { block_hits_avx2(&block, &ray, t_max, lanes) });
            }
            for lane in 0..8 {
                let tri = block.lane(lane);
                let expected = ray
                    .intersect(&tri, t_max)
                    .filter(|_| lanes >> lane & 1 == 1);
                if tri.v == [Vec3::ZERO; 3] {
                    assert!(expected.is_none(), "an empty lane hit");
                }
                if expected.is_some() {
                    hits += 1;
                    let [a, b, c] = tri.v.map(|p| ray.shear * (Vec3A::from(p) - ray.origin));
                    if c.x * b.y == c.y * b.x || a.x * c.y == a.y * c.x || b.x * a.y == b.y * a.x {
                        edges += 1;
                    }
                }
                for got in &each {
                    let hit = got.mask >> lane & 1 == 1;
                    assert_eq!(
                        hit,
                        expected.is_some(),
                        "lane {lane} of {block:?}, ray {origin} {dir}"
                    );
                    if let Some(h) = expected {
                        let g = got.hit(lane);
                        assert_eq!(
                            [g.t, g.u, g.v].map(f32::to_bits),
                            [h.t, h.u, h.v].map(f32::to_bits),
                            "lane {lane} of {block:?}, ray {origin} {dir}"
                        );
                    }
                }
            }
        }
        // The cases the test is for did occur.
        assert!(
            hits > 5_000 && edges > 100,
            "{hits} hits, {edges} on an edge"
        );
    }

    #[test]
    fn parallel_ray_misses() {
        let t = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let r = TriRay::new(Vec3A::new(-1.0, 0.2, 0.0), Vec3A::X);
        assert!(r.intersect(&t, f32::INFINITY).is_none());
    }
}
