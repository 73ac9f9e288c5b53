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

/// The solid angle, sr, of the triangle whose corners lie at `a`, `b` and `c` from the
/// viewpoint, its plane's unit normal `n` (Van Oosterom and Strackee 1983, "The Solid
/// Angle of a Plane Triangle", IEEE Trans. Biomed. Eng. 30(2)), in double precision,
/// and whether the triangle is seen nearly edge on: the viewpoint's height over its
/// plane below [`THIN`] of its distance to the nearest corner, where the corners'
/// directions lie close to one great circle and [`spherical_triangle`] loses accuracy.
#[inline]
pub fn solid_angle(a: Vec3, b: Vec3, c: Vec3, n: Vec3) -> (f64, bool) {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c)).abs();
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    let thin = a.dot(n.as_dvec3()).abs() < THIN * la.min(lb).min(lc);
    (2.0 * numerator.atan2(denominator), thin)
}

/// The height over distance below which [`solid_angle`] calls a triangle seen edge on.
/// Seen from a centimetre over a metre-wide floor, a single-precision sampler read the
/// floor's light 0.4 % low. In double precision, strips 1 cm, 1 mm and 0.1 mm tall on
/// a floor's edge read it within 2.3 σ at 16 M photons (10⁻⁴ of it) with this ratio,
/// and 2.6 σ high with a fifth of it (`a_strip_on_the_floor_lights_it_without_bias` in
/// crates/photon/tests/closed_forms.rs).
pub const THIN: f64 = 0.005;

/// Barycentric coordinates (b1, b2) on the triangle `v0 + b1·e1 + b2·e2` of the point
/// seen from `x` along a direction uniform in the solid angle `omega` the triangle
/// subtends ([`solid_angle`]) (Arvo 1995, "Stratified Sampling of Spherical Triangles",
/// SIGGRAPH; pbrt-v4 `SampleSphericalTriangle`, which recomputes `omega` from the
/// triangle's angles), in double precision; `None` when the triangle is seen edge on.
/// (u1, u2) map continuously onto the triangle, so stratified numbers stay stratified.
#[inline]
pub fn spherical_triangle(
    x: Vec3,
    [v0, e1, e2]: [Vec3; 3],
    omega: f64,
    u1: f64,
    u2: f32,
) -> Option<(f32, f32)> {
    let (x, v0, e1, e2) = (x.as_dvec3(), v0.as_dvec3(), e1.as_dvec3(), e2.as_dvec3());
    let u2 = u2 as f64;
    let a = (v0 - x).normalize();
    let b = (v0 + e1 - x).normalize();
    let c = (v0 + e2 - x).normalize();
    let n_ab = a.cross(b).try_normalize()?;
    let n_ca = c.cross(a).try_normalize()?;
    // The spherical angle at a, between the great circles ab and ac.
    let cos_alpha = (-n_ab.dot(n_ca)).clamp(-1.0, 1.0);
    let sin_alpha = (1.0 - cos_alpha * cos_alpha).max(0.0).sqrt();
    // The sub-triangle at a of area u1·Ω, and the point c' its third side ends at on arc
    // ac; sin and cos of (π + u1·Ω) are −sin and −cos of u1·Ω.
    let (sin_u, cos_u) = (u1 * omega).sin_cos();
    let (sin_sub, cos_sub) = (-sin_u, -cos_u);
    let sin_phi = sin_sub * cos_alpha - cos_sub * sin_alpha;
    let cos_phi = cos_sub * cos_alpha + sin_sub * sin_alpha;
    let k1 = cos_phi + cos_alpha;
    let k2 = sin_phi - sin_alpha * a.dot(b);
    let cos_bp = ((k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha)
        / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha))
        .clamp(-1.0, 1.0);
    let sin_bp = (1.0 - cos_bp * cos_bp).max(0.0).sqrt();
    let cp = cos_bp * a + sin_bp * (c - c.dot(a) * a).try_normalize()?;
    // A point on arc b c' with cos θ uniform: uniform in the sub-triangle's extension.
    let cos_theta = 1.0 - u2 * (1.0 - cp.dot(b));
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let w = cos_theta * b + sin_theta * (cp - cp.dot(b) * b).try_normalize()?;
    // Where x + t·w meets the triangle's plane (Möller–Trumbore).
    let s1 = w.cross(e2);
    let divisor = s1.dot(e1);
    if divisor == 0.0 {
        return None;
    }
    let d = x - v0;
    let mut b1 = (d.dot(s1) / divisor).clamp(0.0, 1.0);
    let mut b2 = (w.dot(d.cross(e1)) / divisor).clamp(0.0, 1.0);
    if b1 + b2 > 1.0 {
        let sum = b1 + b2;
        b1 /= sum;
        b2 /= sum;
    }
    Some((b1 as f32, b2 as f32))
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

    /// The solid angle of the square [−1, 1]² seen from height h on its axis:
    /// 4·arcsin(1/(1 + h²)) (the rectangle's closed form, two triangles summed).
    #[test]
    fn solid_angle_of_a_square() {
        for h in [0.005f32, 0.5, 1.5, 20.0] {
            let x = Vec3::new(0.0, 0.0, h);
            let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(a, b)| Vec3::new(a, b, 0.0) - x);
            let (first, thin) = solid_angle(c[0], c[1], c[2], Vec3::Z);
            let omega = first + solid_angle(c[0], c[2], c[3], Vec3::Z).0;
            let exact = 4.0 * (1.0 / (1.0 + h as f64 * h as f64)).asin();
            assert!(
                (omega - exact).abs() < 1e-6 * exact,
                "h {h}: {omega} vs {exact}"
            );
            // Edge on from 5 mm over the middle (0.35 % of the corners' distance), not
            // from 50 cm.
            assert_eq!(thin, h == 0.005, "h {h}");
        }
    }

    /// Points drawn by [`spherical_triangle`] are uniform in solid angle: over a grid of
    /// (u1, u2), the share falling in each of the four triangles the edges' midpoints cut
    /// the triangle into is that part's share of the solid angle. Seen from near a
    /// corner, far off axis and 5 cm under the triangle (nearly a hemisphere), where area
    /// sampling's shares would be far from these. From afar, where the density
    /// |cos θ_y|/(r² Ω) is smooth, the mean of its inverse is the triangle's area.
    #[test]
    fn spherical_triangle_is_uniform_in_solid_angle() {
        let corners = [
            Vec3::ZERO,
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(1.0, 2.0, 0.0),
        ];
        let [v0, v1, v2] = corners;
        let (e1, e2) = (v1 - v0, v2 - v0);
        let n = e1.cross(e2).normalize();
        let area = e1.cross(e2).length() as f64 / 2.0;
        let [m01, m12, m20] = [(v0 + v1) / 2.0, (v1 + v2) / 2.0, (v2 + v0) / 2.0];
        let parts = [
            [v0, m01, m20],
            [m01, v1, m12],
            [m20, m12, v2],
            [m01, m12, m20],
        ];
        // The part holding barycentrics (b1, b2): corners where one coordinate exceeds ½.
        let part_of = |b1: f32, b2: f32| {
            let b0 = 1.0 - b1 - b2;
            if b0 > 0.5 {
                0
            } else if b1 > 0.5 {
                1
            } else if b2 > 0.5 {
                2
            } else {
                3
            }
        };
        for x in [
            Vec3::new(-0.2, -0.1, 0.3),
            Vec3::new(-4.0, 5.0, 2.0),
            Vec3::new(1.0, 0.5, -0.05),
        ] {
            let angle = |[a, b, c]: [Vec3; 3]| solid_angle(a - x, b - x, c - x, n).0;
            let omega = angle(corners);
            let k = 1000;
            let (mut counts, mut inverse) = ([0usize; 4], 0.0f64);
            for i in 0..k {
                for j in 0..k {
                    let u = ((i as f64 + 0.5) / k as f64, (j as f32 + 0.5) / k as f32);
                    let (b1, b2) = spherical_triangle(x, [v0, e1, e2], omega, u.0, u.1).unwrap();
                    counts[part_of(b1, b2)] += 1;
                    let d = v0 + e1 * b1 + e2 * b2 - x;
                    let r2 = d.length_squared() as f64;
                    inverse += r2 * r2.sqrt() * omega / n.dot(d).abs() as f64;
                }
            }
            for (part, count) in parts.iter().zip(counts) {
                let (share, exact) = (count as f64 / (k * k) as f64, angle(*part) / omega);
                assert!(
                    (share - exact).abs() < 3e-3,
                    "from {x}: share {share}, solid angle's {exact}"
                );
            }
            if x.z > 1.0 {
                let mean = inverse / (k * k) as f64;
                assert!(
                    (mean - area).abs() < 1e-3 * area,
                    "from {x}: mean 1/p {mean}, area {area}"
                );
            }
        }
    }
}
