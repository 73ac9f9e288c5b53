//! Connections from a photon's departures to the measured targets: next-event estimation
//! toward the sensor, as a light tracer connects every vertex of its paths to the camera
//! (pbrt-v4 `LightPathIntegrator`), with the target surface in the place of the camera.
//!
//! Why: a photon tracer that only counts arrivals (thesis §3.3) learns about a target
//! from the photons that happen to hit it. A photon that leaves a light or a diffuse
//! surface sends its expected power toward the target along every direction that sees
//! it; a connection estimates that flux from one point drawn on the target and a ray
//! toward it, before the Russian roulette decides the photon's fate, so even absorbed
//! photons report what their reflection would have brought.
//!
//! The point is drawn uniformly in the solid angle the target subtends from x when the
//! target has at most [`SOLID_ANGLE_TRIANGLES`] triangles (a floor, a desk top, a
//! board: [`Targets::solid_angles`]), which cancels the target's own cos θ_y/r², and
//! uniformly in area otherwise (and from the sun's beam). One stratified 2-D number
//! chooses the triangle (by area or by solid angle) and the point in it, so a group's
//! points stay spread over the whole target.
//!
//! Both ways of reaching a target point y from a departure x (the connection, and the
//! photon's own next ray hitting it) are kept and weighted by the balance heuristic
//! (Veach 1997, §9.2): with p_a the connection's density of y per unit area (1/A by
//! area, |cos θ_y|/(r²Ω) by solid angle) and
//! p_b = s·f(ω)·|cos θ_y|/r² the photon's (s the probability the photon leaves along
//! this lobe, f its directional density), the connection counts p_a/(p_a + p_b) and the
//! arrival p_b/(p_a + p_b). The weights add up to one for every y, so the sum stays
//! unbiased, and each is bounded: a departure next to its target (a lamp touching it, a
//! wall's corner with the floor) does not give the connection its 1/r² tail, as it
//! would alone.
//! Arrivals after a mirror or glass (a delta lobe no connection can sample) count fully.
//!
//! A calculation surface is a target that hides nothing: no ray stops at it, so a
//! connection to one of its points counts when nothing lies before the point, and the
//! photon's own ray reports its crossing there as an arrival ([`crate::PathVisitor::cross`]);
//! the two are weighed by the same densities as on any surface. Connections to other
//! targets pass it, as the photons do.
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
use invlight_trace::{Accel, Ray, crossing_slack, offset_point};
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
    /// Whether a photon leaving by this lobe leaves a point, spot or photometric light:
    /// only a light's departure has these lobes (bounces leave by the cosine or a delta
    /// lobe), so an arrival or connection from one is that light's direct light, which
    /// a grid read at points computes instead (`direct.rs`).
    #[inline]
    pub fn leaves_point_source(&self) -> bool {
        matches!(
            self,
            Lobe::Sphere | Lobe::Spot { .. } | Lobe::Goniometric { .. }
        )
    }

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
    /// Whether it carries light straight from the light: it leaves the light itself, or
    /// continues such a departure through glass or off a mirror (a delta lobe). What
    /// arrives from it is the source's direct light; what arrives from a diffuse
    /// departure has been reflected.
    pub emitted: bool,
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
            // cos θ_x/π · |cos θ_y| / r² with both cosines taken on the unnormalised
            // d = y − x: one division, no square root (the path's commonest lobe).
            Lobe::Cosine { normal } => {
                let d = y - self.point;
                let r2 = d.length_squared();
                let c = normal.dot(d);
                if !(r2 > 0.0 && c > 0.0) {
                    return (0.0, 1.0);
                }
                let density = self.survival * c * n_y.dot(d).abs() / (PI * r2 * r2);
                (density, 1.0)
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
    /// Whether each triangle is on a calculation surface, which no ray hits: a
    /// connection to it counts when nothing hides it. Empty when none is.
    receivers: Vec<bool>,
}

/// The solid angles a target's triangles subtend from a departure, when its connections
/// draw points by solid angle ([`Targets::solid_angles`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolidAngles {
    /// Each triangle's, sr (0 past the target's triangles).
    angles: [f64; SOLID_ANGLE_TRIANGLES],
    /// Their sum, Ω: a connection draws y with density |cos θ_y| / (r² Ω).
    pub total: f64,
}

/// The most triangles a target may have for its connections to be drawn by solid angle:
/// each connection and each arrival on it computes every triangle's solid angle.
pub const SOLID_ANGLE_TRIANGLES: usize = 4;

/// The solid angles, sr, outside which a departure's connection draws by area instead
/// (of each triangle that is seen, and of their sum): below, the spherical triangle is
/// too thin to sample accurately; above, it nearly covers the hemisphere (pbrt-v4
/// `MinSphericalSampleArea`, `MaxSphericalSampleArea`). A triangle seen nearly edge on
/// ([`sampling::solid_angle`]) also sends its target to area.
const SOLID_ANGLE_RANGE: (f64, f64) = (3e-4, 6.22);

impl Shape {
    /// Each triangle's solid angle seen from `x` and their sum, when the target has at
    /// most [`SOLID_ANGLE_TRIANGLES`] triangles and the sum lies in
    /// [`SOLID_ANGLE_RANGE`]; `None` when the connection from `x` draws by area.
    #[inline]
    fn solid_angles(&self, x: Vec3) -> Option<SolidAngles> {
        if self.tris.len() > SOLID_ANGLE_TRIANGLES {
            return None;
        }
        let mut angles = [0.0; SOLID_ANGLE_TRIANGLES];
        for (a, &(p0, e1, e2, n)) in angles.iter_mut().zip(&self.tris) {
            let (angle, thin) = sampling::solid_angle(p0 - x, p0 + e1 - x, p0 + e2 - x, n);
            // A triangle seen from x at all must be seen well enough to sample: every
            // one, not only their sum (pbrt-v4 checks its one triangle).
            if angle > 0.0 && (thin || angle < SOLID_ANGLE_RANGE.0) {
                return None;
            }
            *a = angle;
        }
        let total: f64 = angles.iter().sum();
        (total > SOLID_ANGLE_RANGE.0 && total < SOLID_ANGLE_RANGE.1)
            .then_some(SolidAngles { angles, total })
    }

    /// The density per unit area, at `y` on a triangle of unit normal `n_y`, of the
    /// connection's point from `x` given [`Shape::solid_angles`]'s `total`:
    /// |cos θ_y| / (r² Ω), or 1/A when it draws by area.
    #[inline]
    fn connection_density(&self, x: Vec3, y: Vec3, n_y: Vec3, total: Option<f64>) -> f32 {
        match total {
            Some(total) => {
                let d = (y - x).as_dvec3();
                let r2 = d.length_squared();
                (n_y.as_dvec3().dot(d).abs() / (r2.sqrt() * r2 * total)) as f32
            }
            None => 1.0 / self.area,
        }
    }
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
        let calculation = scene.calculation_instances();
        let shapes = targets
            .iter()
            .map(|&s| {
                let mut shape = Shape::default();
                let mut areas = Vec::new();
                shape.instances = scene.surfaces[s].instances.clone();
                shape.instances.sort_unstable();
                shape.instances.dedup();
                let any_receiver = shape.instances.iter().any(|i| calculation[i.index()]);
                for &i in &scene.surfaces[s].instances {
                    let receiver = calculation[i.index()];
                    for t in scene.world_triangles(i) {
                        let area = t.area();
                        // A calculation surface receives whatever its material.
                        let hole = scene.materials[t.material].hole && !receiver;
                        if hole || !(area > 0.0 && area.is_finite()) {
                            continue;
                        }
                        let [a, b, c] = t.corners;
                        areas.push(area as f64);
                        shape.tris.push((a, b - a, c - a, t.cross / (2.0 * area)));
                        if any_receiver {
                            shape.receivers.push(receiver);
                        }
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

    /// The solid angles target `t`'s triangles subtend from `from` when its connection
    /// draws by solid angle: a target of at most [`SOLID_ANGLE_TRIANGLES`] triangles,
    /// seen from a point (not the sun's beam) within a solid angle that can be sampled
    /// accurately. `None` when it draws by area.
    ///
    /// Why: a uniform point on the target's area gives the connection the factor
    /// cos θ_y / r² of the target's own geometry, which swings widely from a wall's
    /// foot to a floor's far corner; a point uniform in solid angle cancels it, leaving
    /// the departure's cosine and visibility. On the Mitsuba comparison's floor (two
    /// triangles) it cuts the variance to 0.57 of area sampling's (BENCHMARKS.md). Each
    /// solid angle costs an arc tangent per triangle, hence the limit.
    #[inline]
    pub fn solid_angles(&self, t: usize, from: &Departure) -> Option<SolidAngles> {
        match from.lobe {
            Lobe::Parallel { .. } | Lobe::Specular => None,
            _ => self.shapes[t].solid_angles(from.point),
        }
    }

    /// The share of an arrival at `y` (unit normal `n_y`) on target `t` that the arrival
    /// counts, p_b/(p_a + p_b), from its [`Departure::arrival_density`] p_b (which does
    /// not depend on the target, so an arrival on several targets computes it once) and
    /// the density p_a with which a connection from `from` draws y, by solid angle when
    /// `solid` is [`Targets::solid_angles`]'s total, else by area; 1 for a target with
    /// nothing to connect to.
    #[inline]
    pub fn arrival_weight(
        &self,
        t: usize,
        (from, y, n_y): (&Departure, Vec3, Vec3),
        density: f32,
        solid: Option<f64>,
    ) -> f32 {
        let shape = &self.shapes[t];
        if shape.area <= 0.0 || density.is_infinite() {
            return 1.0;
        }
        let p_a = shape.connection_density(from.point, y, n_y, solid);
        if !(p_a > 0.0 && p_a.is_finite()) {
            return 1.0;
        }
        let q = density / p_a;
        if q.is_infinite() { 1.0 } else { q / (1.0 + q) }
    }

    /// Connects `from` to a point drawn on target `t`, by solid angle when `solid` is
    /// [`Targets::solid_angles`]'s for this departure, else by area: the point and the
    /// luminous power, lm, this connection counts toward the target's total (zero when
    /// the point is hidden), or `None` when no ray was needed (the point is in a hole or
    /// outside the lobe). Draws one stratified 2-D number from `sampler` whatever
    /// happens, so the photons of a stratified group stay aligned.
    #[inline]
    pub fn connect(
        &self,
        t: usize,
        from: &Departure,
        solid: Option<&SolidAngles>,
        accel: &Accel,
        sampler: &mut Sampler<'_>,
    ) -> Option<Connection> {
        let (u1, u2) = sampler.uniform2();
        let shape = &self.shapes[t];
        if shape.area <= 0.0 || from.survival <= 0.0 || from.lumens <= 0.0 {
            return None;
        }
        let (y, n_y, i) = match solid {
            Some(&SolidAngles { ref angles, total }) => {
                let (i, u1) = pick(angles, total, u1 as f64);
                let (p0, e1, e2, n_y) = shape.tris[i];
                let (b1, b2) =
                    sampling::spherical_triangle(from.point, [p0, e1, e2], angles[i], u1, u2)?;
                (p0 + e1 * b1 + e2 * b2, n_y, i)
            }
            None => {
                let (i, u1) = shape.by_area.sample_continuous(u1 as f64);
                let (p0, e1, e2, n_y) = shape.tris[i];
                let (b1, b2) = sampling::triangle(u1 as f32, u2);
                (p0 + e1 * b1 + e2 * b2, n_y, i)
            }
        };
        // q = p_b/p_a; the connection's estimate f·g·V/p_a weighted by p_a/(p_a + p_b)
        // is lumens·r/s · q/(1 + q) (r the lobe's weight toward y, 1 but for tables).
        let (density, weight) = from.density_and_weight(y, n_y);
        let p_a = shape.connection_density(from.point, y, n_y, solid.map(|s| s.total));
        let q = density / p_a;
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
        let slack = crossing_slack(origin, y);
        let ray = Ray {
            origin,
            dir: d / dist,
            t_max: dist + slack,
        };
        // A hit before dist − slack hides y whether or not it is the closest, so the
        // traversal may stop at the first one it meets. A point on a calculation surface,
        // which no ray hits, is reached when nothing hides it: the photon's own ray
        // counts its crossing there unless it hit something before, within the same
        // slack ([`invlight_trace::crossing_slack`]).
        let reached = if shape.receivers.get(i).copied().unwrap_or(false) {
            let before = Ray {
                t_max: dist - slack,
                ..ray
            };
            !(before.t_max > 0.0 && accel.occluded(&before))
        } else {
            accel
                .intersect_unless_blocked(&ray, dist - slack)
                .is_some_and(|hit| {
                    (hit.t - dist).abs() <= slack
                        && shape.instances.binary_search(&hit.instance).is_ok()
                })
        };
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

/// The entry of `angles` (summing to `total`) that `u` falls in, in proportion to its
/// angle, and where in it, rescaled to [0, 1) ([`Distribution1D::sample_continuous`]).
#[inline]
fn pick(angles: &[f64], total: f64, u: f64) -> (usize, f64) {
    let target = u * total;
    // The last entry of positive angle takes what rounding leaves past the others.
    let last = angles.iter().rposition(|&a| a > 0.0).unwrap_or(0);
    let (mut i, mut below) = (0, 0.0);
    while i < last && target >= below + angles[i] {
        below += angles[i];
        i += 1;
    }
    let r = if angles[i] > 0.0 {
        (target - below) / angles[i]
    } else {
        0.0
    };
    (i, r.clamp(0.0, 1.0 - f64::EPSILON / 2.0))
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

    /// The integral over the whole sphere of `f` along each unit direction, on a grid
    /// of `n` bands in cos θ and `2n` in φ (midpoint rule).
    fn over_sphere(n: usize, f: impl Fn(Vec3) -> f64) -> f64 {
        let (mut total, cell) = (0.0, 2.0 / n as f64 * std::f64::consts::PI / n as f64);
        for i in 0..n {
            let c = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            let s = (1.0 - c * c).sqrt();
            for j in 0..2 * n {
                let phi = std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
                let w = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, c as f32);
                total += f(w) * cell;
            }
        }
        total
    }

    /// Lobes that are not symmetric about Z: a cosine and a spot about a tilted axis, and
    /// a linear luminaire's table (a batwing across its length, cosine-like along it)
    /// turned in the world. Each density integrates to one over the sphere, the
    /// table's intensity I = Φ·p·r to its flux, its density is the same read alone or
    /// with its weight, and the turned table reads in the world what the unturned one
    /// reads at the turned direction.
    #[test]
    fn asymmetric_and_turned_lobes_integrate_to_one() {
        let tilted = Vec3::new(0.6, -0.3, 0.74).normalize();
        for lobe in [
            Lobe::Cosine { normal: tilted },
            Lobe::Spot {
                axis: tilted,
                cos_inner: 0.9,
                cos_outer: 0.7,
                flat_share: 0.1 / (0.1 + 0.2 / 3.0),
            },
        ] {
            let total = over_sphere(400, |w| f64::from(lobe.pdf(w)));
            assert!((total - 1.0).abs() < 2e-3, "{lobe:?}: {total}");
        }
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/photometry/linear.ldt");
        let photometry = invlight_scene::read_photometry(&file).unwrap();
        // A quarter turn about the aim and a tilt: C0 and C90 swap places in the world.
        let frame = Mat3::from_rotation_x(0.4) * Mat3::from_rotation_z(std::f32::consts::FRAC_PI_2);
        let lobe = Lobe::Goniometric {
            to_local: frame.transpose(),
            photometry: &photometry,
        };
        let density = over_sphere(400, |w| f64::from(lobe.pdf(w)));
        assert!((density - 1.0).abs() < 2e-3, "density {density}");
        let flux = photometry.flux();
        let intensity = over_sphere(400, |w| {
            let (p, r) = lobe.pdf_and_weight(w);
            f64::from(p) * f64::from(r) * flux
        });
        assert!(
            (intensity / flux - 1.0).abs() < 5e-3,
            "{intensity} lm of {flux}"
        );
        let unturned = Lobe::Goniometric {
            to_local: Mat3::IDENTITY,
            photometry: &photometry,
        };
        for w in [Vec3::X, Vec3::Y, Vec3::new(0.5, 0.2, -0.84).normalize()] {
            let turned = lobe.pdf_and_weight(frame * w);
            assert_eq!(turned, unturned.pdf_and_weight(w));
            assert_eq!(lobe.pdf(frame * w), turned.0);
            assert_eq!(lobe.weight(frame * w), turned.1);
        }
        // The table is not symmetric: along C0 and C90 at 60° it differs.
        let at = |c: f32| {
            let g = 60f32.to_radians();
            Vec3::new(g.sin() * c.cos(), g.sin() * c.sin(), -g.cos())
        };
        let (c0, c90) = (
            unturned.pdf(at(0.0)),
            unturned.pdf(at(std::f32::consts::FRAC_PI_2)),
        );
        assert!((c0 - c90).abs() > 0.2 * c0.max(c90), "C0 {c0}, C90 {c90}");
    }
}
