//! Sampling of directions and points (pbrt-v4 `util/sampling.h`).

use glam::Vec3;
use std::f32::consts::PI;

/// An orthonormal basis around unit `n` (Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited", JCGT 6(1)): branch-free and robust near ±z.
#[inline]
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// A direction about unit `n` with density cos θ / π (Malley's method).
#[inline]
pub fn cosine_hemisphere(n: Vec3, u1: f32, u2: f32) -> Vec3 {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let (t, b) = basis(n);
    let z = (1.0 - u1).max(0.0).sqrt();
    (t * (r * phi.cos()) + b * (r * phi.sin()) + n * z).normalize()
}

/// A direction about unit `axis` with cos θ uniform in [cos_max, 1] (a uniform cone
/// when cos_max > -1; the whole sphere when cos_max = -1).
#[inline]
pub fn cone(axis: Vec3, cos_theta: f32, u: f32) -> Vec3 {
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.0 * PI * u;
    let (t, b) = basis(axis);
    (t * (sin_theta * phi.cos()) + b * (sin_theta * phi.sin()) + axis * cos_theta).normalize()
}

/// A uniformly distributed direction on the unit sphere.
#[inline]
pub fn sphere(u1: f32, u2: f32) -> Vec3 {
    cone(Vec3::Z, 1.0 - 2.0 * u1, u2)
}

/// Barycentric coordinates (b1, b2) of a uniform point on a triangle (the square-root
/// parameterisation, pbrt-v4 `SampleUniformTriangle`).
#[inline]
pub fn triangle(u1: f32, u2: f32) -> (f32, f32) {
    let s = u1.sqrt();
    (1.0 - s, u2 * s)
}

/// A uniform point on the unit disk (polar).
#[inline]
pub fn disk(u1: f32, u2: f32) -> (f32, f32) {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    (r * phi.cos(), r * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use invlight_stats::Pcg32;

    #[test]
    fn basis_is_orthonormal() {
        let mut rng = Pcg32::new(0, 0);
        for _ in 0..1000 {
            let n = sphere(rng.uniform(), rng.uniform());
            let (t, b) = basis(n);
            assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5);
            assert!(t.dot(b).abs() < 1e-5 && t.dot(n).abs() < 1e-5 && b.dot(n).abs() < 1e-5);
        }
    }

    #[test]
    fn cosine_hemisphere_has_mean_cosine_two_thirds() {
        // E[cos θ] under p = cos θ/π is 2/3; Var = 1/2 − 4/9 = 1/18. Tolerance 5 σ.
        let n = 100_000;
        let mut rng = Pcg32::new(1, 0);
        let axis = Vec3::new(0.3, -0.5, 0.8).normalize();
        let mean: f64 = (0..n)
            .map(|_| cosine_hemisphere(axis, rng.uniform(), rng.uniform()).dot(axis) as f64)
            .sum::<f64>()
            / n as f64;
        assert!((mean - 2.0 / 3.0).abs() < 5.0 * (1.0f64 / 18.0 / n as f64).sqrt());
    }
}
