//! Watertight ray/triangle intersection: Woop, Benthin & Wald, "Watertight Ray/Triangle
//! Intersection", *JCGT* 2(1), 2013.
//!
//! The ray is made the +z axis of a sheared frame; each vertex is transformed by the same
//! per-ray operations, so the 2D edge functions of two triangles sharing an edge are
//! exact negatives of each other and a ray through the edge hits one of them. Edge
//! functions that round to zero are recomputed in double precision, as the paper does.

use glam::{Mat3A, Vec3, Vec3A};

/// A triangle as stored for intersection: its object-space corners and its index in the
/// mesh (40 bytes, so that a leaf's triangles sit in one or two cache lines).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tri {
    pub v: [Vec3; 3],
    pub index: u32,
}

/// Per-ray constants of the sheared frame: `shear · (p − origin)` gives a vertex's
/// coordinates (x, y across the ray, z along it scaled to t).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriRay {
    origin: Vec3A,
    shear: Mat3A,
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

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Tri {
        Tri {
            v: [a.into(), b.into(), c.into()],
            index: 0,
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

    #[test]
    fn parallel_ray_misses() {
        let t = tri([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let r = TriRay::new(Vec3A::new(-1.0, 0.2, 0.0), Vec3A::X);
        assert!(r.intersect(&t, f32::INFINITY).is_none());
    }
}
