//! Connections from a photon's departures to the measured targets: next-event estimation
//! toward the sensor, as a light tracer connects every vertex of its paths to the camera
//! (pbrt-v4 `LightPathIntegrator`), with the target surface in the place of the camera.
//!
//! Why: a photon tracer that only counts arrivals (thesis §3.3) learns about a target
//! from the photons that happen to hit it. A photon that leaves a light or a diffuse
//! surface sends its expected power toward the target along every direction that sees
//! it; a connection estimates that flux from one point drawn on the target (uniform in
//! area) and a ray toward it, before the Russian roulette decides the photon's fate, so even
//! absorbed photons report what their reflection would have brought.
//!
//! Both ways of reaching a target point y from a departure x (the connection, and the
//! photon's own next ray hitting it) are kept and weighted by the balance heuristic
//! (Veach 1997, §9.2): with p_a = 1/A the connection's density of y per unit area and
//! p_b = s·f(ω)·|cos θ_y|/r² the photon's (s the probability the photon leaves along
//! this lobe, f its directional density), the connection counts p_a/(p_a + p_b) and the
//! arrival p_b/(p_a + p_b). The weights add up to one for every y, so the sum stays
//! unbiased, and each is bounded: a departure next to its target (a lamp touching it, a
//! wall's corner with the floor) does not give the connection its 1/r² tail, as it
//! would alone.
//! Arrivals after a mirror or glass (a delta lobe no connection can sample) count fully.
//!
//! A goniometric light (a photometric file) draws its photons from a piecewise-constant
//! density p(ω) (each cell of the table its share of the flux, uniform inside the cell)
//! while its intensity I(ω) is bilinear in the cell: the two differ inside a cell. Its
//! photons therefore carry Φ_s·r(ω) with r = I/(Φ·p) ([`Lobe::weight`], mean 1 under p),
//! so that a photon's expected power per steradian is Φ_s·p·r = Φ_s·I/Φ: the intensity
//! the file describes. The connection to y counts the power the photon would bring along
//! ω_y, Φ_s·r(ω_y)·cos θ_y/(r_xy²·p_a) of the file's intensity, weighted by
//! p_a/(p_a + p_b) with p_b = p(ω_y)·cos θ_y/r_xy² the density the photons are really
//! drawn with: Φ_s·r(ω_y)·q/(1 + q) with q = A·p_b. The value uses the true intensity
//! (through r), the weight the true sampling density, so the sum over both strategies
//! stays unbiased for the file's intensity; for every other lobe r = 1.

use crate::sampler::Sampler;
use crate::sampling;
use glam::{Mat3, Vec3};
use invlight_scene::{InstanceId, Photometry, Scene, SurfaceId};
use invlight_stats::Distribution1D;
use invlight_trace::{Accel, OFFSET_SCALE, Ray, offset_point};
use std::f32::consts::PI;

/// How a photon leaves a point: the directional distribution of its next ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lobe<'a> {
    /// Lambertian about the unit `normal`: density cos θ / π (area lights, diffuse
    /// reflection).
    Cosine {
        /// The side the photon leaves to.
        normal: Vec3,
    },
    /// Uniform over the sphere: density 1 / (4π) (point lights).
    Sphere,
    /// A glTF spot's profile (see `emit::Source::Spot`).
    Spot {
        /// Unit axis.
        axis: Vec3,
        /// Cosine of the inner cone's half angle.
        cos_inner: f32,
        /// Cosine of the outer cone's half angle.
        cos_outer: f32,
        /// Probability of the uniform inner part.
        flat_share: f32,
    },
    /// A parallel beam along the unit `direction` whose photons start uniformly over a
    /// disk of `area` m² across it (the sun).
    Parallel {
        /// Direction of travel.
        direction: Vec3,
        /// Area of the disk the photons start from.
        area: f32,
    },
    /// A delta distribution (mirror reflection, refraction): no connection can sample it.
    Specular,
    /// A photometric table's piecewise-constant density ([`Photometry::sample`]), turned
    /// into the world by the light's frame.
    Goniometric {
        /// World → luminaire-local rotation (the transpose of the light's frame).
        to_local: Mat3,
        /// The table.
        photometry: &'a Photometry,
    },
}

impl Lobe<'_> {
    /// The factor r(w) = I(w)/(Φ·p(w)) on the power of a photon leaving along the unit
    /// vector `w` (see the module doc): 1 for every lobe but the goniometric one, and 0
    /// where that one's density is 0.
    #[inline]
    pub fn weight(&self, w: Vec3) -> f32 {
        self.pdf_and_weight(w).1
    }

    /// [`Lobe::pdf`] and [`Lobe::weight`] along `w` from one look-up of the table.
    #[inline]
    pub fn pdf_and_weight(&self, w: Vec3) -> (f32, f32) {
        match *self {
            Lobe::Goniometric {
                to_local,
                photometry,
            } => photometry.pdf_and_weight(to_local * w),
            _ => (self.pdf(w), 1.0),
        }
    }

    /// Density per steradian of leaving along the unit vector `w` (zero for the parallel
    /// and specular lobes, whose densities are not per steradian).
    #[inline]
    pub fn pdf(&self, w: Vec3) -> f32 {
        match *self {
            Lobe::Goniometric {
                to_local,
                photometry,
            } => photometry.pdf_and_weight(to_local * w).0,
            Lobe::Cosine { normal } => normal.dot(w).max(0.0) / PI,
            Lobe::Sphere => 0.25 / PI,
            Lobe::Spot {
                axis,
                cos_inner,
                cos_outer,
                flat_share,
            } => {
                let c = axis.dot(w);
                if c >= cos_inner {
                    // Uniform in solid angle over the inner cap.
                    if cos_inner < 1.0 {
                        flat_share / (2.0 * PI * (1.0 - cos_inner))
                    } else {
                        0.0
                    }
                } else if c > cos_outer {
                    // Density 3t² in t = (cos θ − cos_outer)/(cos_inner − cos_outer).
                    let width = cos_inner - cos_outer;
                    let t = (c - cos_outer) / width;
                    (1.0 - flat_share) * 3.0 * t * t / (width * 2.0 * PI)
                } else {
                    0.0
                }
            }
            Lobe::Parallel { .. } | Lobe::Specular => 0.0,
        }
    }
}

/// A point a photon leaves from, as a connection needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Departure<'a> {
    /// Where the photon leaves: the point on the light or on the surface.
    pub point: Vec3,
    /// Its directional distribution.
    pub lobe: Lobe<'a>,
    /// The luminous power expected to leave along the lobe, lm: what the photon carries
    /// when it leaves this way (along a direction of [`Lobe::weight`] 1), times the
    /// probability `survival` that it does.
    pub lumens: f32,
    /// Probability that the photon's next ray follows this lobe (the Russian roulette's
    /// share of diffuse reflection; 1 when it leaves a light).
    pub survival: f32,
    /// The source the photon left ([`crate::EmitSample::source`]): its light reaches
    /// every surface it arrives on or connects to as that source's light.
    pub source: u32,
}

impl Departure<'_> {
    /// Density per unit area at `y` (unit normal `n_y`, either side) with which the
    /// photon's next ray reaches y, visibility aside: p_b of the module's weights.
    /// Infinite for a specular lobe, whose arrivals no connection competes with.
    #[inline]
    pub fn arrival_density(&self, y: Vec3, n_y: Vec3) -> f32 {
        self.density_and_weight(y, n_y).0
    }

    /// [`Departure::arrival_density`] at `y` and the lobe's [`Lobe::weight`] toward it,
    /// from one look-up of a table.
    #[inline]
    fn density_and_weight(&self, y: Vec3, n_y: Vec3) -> (f32, f32) {
        match self.lobe {
            Lobe::Specular => (f32::INFINITY, 1.0),
            Lobe::Parallel { direction, area } => {
                (self.survival * n_y.dot(direction).abs() / area, 1.0)
            }
            lobe => {
                let d = y - self.point;
                let r2 = d.length_squared();
                if r2 <= 0.0 {
                    return (0.0, 0.0);
                }
                let w = d / r2.sqrt();
                let (pdf, weight) = lobe.pdf_and_weight(w);
                (self.survival * pdf * n_y.dot(w).abs() / r2, weight)
            }
        }
    }
}

/// What one connection found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Connection {
    /// The point drawn on the target.
    pub point: Vec3,
    /// The luminous power it counts toward the target, lm (0 when hidden).
    pub lumens: f64,
    /// Whether it reaches the target's front: the side its counter-clockwise normal faces.
    pub front: bool,
}

/// A target's triangles in world space, to draw points on uniformly by area.
#[derive(Debug, Clone, Default)]
struct Shape {
    /// (corner, edge 1, edge 2, unit normal) of each triangle of positive area.
    tris: Vec<(Vec3, Vec3, Vec3, Vec3)>,
    /// The triangles by area.
    by_area: Distribution1D,
    /// Total area, m²: 1/area is the connection's density p_a.
    area: f32,
    /// The instances the target covers, sorted: a connection counts when its ray's first
    /// hit is one of them.
    instances: Vec<InstanceId>,
}

/// The measured targets as connections see them: the triangles photons can arrive on
/// (every traced triangle of the target's instances; hole apertures are left out, as
/// photons pass through them).
#[derive(Debug, Clone, Default)]
pub struct Targets {
    shapes: Vec<Shape>,
}

impl Targets {
    /// The surfaces `targets` of `scene` with their current instance transforms.
    pub fn new(scene: &Scene, targets: &[SurfaceId]) -> Targets {
        let shapes = targets
            .iter()
            .map(|&s| {
                let mut shape = Shape::default();
                let mut areas = Vec::new();
                shape.instances = scene.surfaces[s].instances.clone();
                shape.instances.sort_unstable();
                shape.instances.dedup();
                for &i in &scene.surfaces[s].instances {
                    for t in scene.world_triangles(i) {
                        let area = t.area();
                        if scene.materials[t.material].hole || !(area > 0.0 && area.is_finite()) {
                            continue;
                        }
                        let [a, b, c] = t.corners;
                        areas.push(area as f64);
                        shape.tris.push((a, b - a, c - a, t.cross / (2.0 * area)));
                    }
                }
                shape.by_area = Distribution1D::new(areas);
                shape.area = shape.by_area.total() as f32;
                shape
            })
            .collect();
        Targets { shapes }
    }

    /// The number of targets.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// The share of an arrival on target `t` that the arrival counts, p_b/(p_a + p_b),
    /// from its [`Departure::arrival_density`] p_b (which does not depend on the target,
    /// so an arrival on several targets computes it once); 1 for a target with nothing
    /// to connect to.
    #[inline]
    pub fn arrival_weight(&self, t: usize, density: f32) -> f32 {
        let area = self.shapes[t].area;
        if area <= 0.0 {
            return 1.0;
        }
        let q = area * density;
        if q.is_infinite() { 1.0 } else { q / (1.0 + q) }
    }

    /// Connects `from` to a point drawn on target `t`: the point and the luminous power,
    /// lm, this connection counts toward the target's total (zero when the point is
    /// hidden), or `None` when no ray was needed (the point is in a hole or outside the
    /// lobe). Draws three numbers from `sampler` whatever happens, so the photons of a
    /// stratified group stay aligned.
    #[inline]
    pub fn connect(
        &self,
        t: usize,
        from: &Departure,
        accel: &Accel,
        sampler: &mut Sampler<'_>,
    ) -> Option<Connection> {
        let pick = sampler.uniform();
        let (u1, u2) = sampler.uniform2();
        let shape = &self.shapes[t];
        if shape.area <= 0.0 || from.survival <= 0.0 || from.lumens <= 0.0 {
            return None;
        }
        let (p0, e1, e2, n_y) = shape.tris[shape.by_area.sample(pick)];
        let (b1, b2) = sampling::triangle(u1, u2);
        let y = p0 + e1 * b1 + e2 * b2;
        // q = A·p_b; the connection's estimate f·g·V/p_a weighted by p_a/(p_a + p_b)
        // is lumens·r/s · q/(1 + q) (r the lobe's weight toward y, 1 but for tables).
        let (density, weight) = from.density_and_weight(y, n_y);
        let q = shape.area * density;
        if !(q > 0.0 && q.is_finite()) || accel.in_hole(y) {
            return None;
        }
        // The connection's ray goes the way the photon would: from the departure (offset
        // as a spawned ray is; for the sun, from behind the scene) toward y, and counts
        // when its first hit is the target at y. A ray from y back to the departure
        // would pass surfaces lying on the target or within the offset of it (a decal on
        // a floor, a box standing on a table), which the photons' own rays stop at: the
        // two estimators would then measure different things.
        let origin = match from.lobe {
            Lobe::Parallel { direction, area } => y - direction * (2.02 * (area / PI).sqrt()),
            Lobe::Cosine { normal } => offset_point(from.point, normal),
            _ => from.point,
        };
        let d = y - origin;
        let dist = d.length();
        if !(dist > 0.0 && dist.is_finite()) {
            return None;
        }
        // The rounding of the two ends: the offsets' own scale, a few times over.
        let slack = 8.0 * OFFSET_SCALE * origin.abs().max(y.abs()).max_element().max(1.0 / 32.0);
        let ray = Ray {
            origin,
            dir: d / dist,
            t_max: dist + slack,
        };
        // A hit before dist − slack hides y whether or not it is the closest, so the
        // traversal may stop at the first one it meets.
        let reached = accel
            .intersect_unless_blocked(&ray, dist - slack)
            .is_some_and(|hit| {
                (hit.t - dist).abs() <= slack
                    && shape.instances.binary_search(&hit.instance).is_ok()
            });
        let lumens = if reached {
            (from.lumens * weight / from.survival * q / (1.0 + q)) as f64
        } else {
            0.0
        };
        Some(Connection {
            point: y,
            lumens,
            front: d.dot(n_y) < 0.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each lobe's density integrates to one over the sphere (midpoint rule in cos θ).
    #[test]
    fn lobe_densities_integrate_to_one() {
        let lobes = [
            Lobe::Cosine { normal: Vec3::Z },
            Lobe::Sphere,
            Lobe::Spot {
                axis: Vec3::Z,
                cos_inner: 0.9,
                cos_outer: 0.7,
                flat_share: 0.1 / (0.1 + 0.2 / 3.0),
            },
        ];
        for lobe in lobes {
            let n = 200_000;
            let total: f64 = (0..n)
                .map(|i| {
                    let c = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
                    let s = (1.0 - c * c).sqrt();
                    let w = Vec3::new(s as f32, 0.0, c as f32);
                    lobe.pdf(w) as f64 * 2.0 * std::f64::consts::PI * 2.0 / n as f64
                })
                .sum();
            assert!((total - 1.0).abs() < 1e-3, "{lobe:?}: {total}");
        }
    }
}
