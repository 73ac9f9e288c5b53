//! One photon's path through the scene (thesis Algorithm 2.2; the loop has pbrt-v4's
//! light-path shape, `LightPathIntegrator`): emit, then intersect → report the arrival →
//! choose by Russian roulette between diffuse reflection, mirror reflection, refraction
//! and absorption. Paths end only by absorption, escape or the bounce cap, so estimates
//! are unbiased when the cap is not reached. Calculation surfaces are reported where a
//! ray crosses them ([`PathVisitor::cross`]) and change nothing about the path.

use crate::connect::{Departure, Lobe};
use crate::emit::{EmitSample, Emitters};
use crate::sampler::Sampler;
use crate::sampling;
use glam::Vec3;
use invlight_scene::{Rgb, Scene, luminance};
use invlight_trace::{Accel, Interaction, Ray, offset_point};

/// What a path reports to whoever follows it: tallies for measurement, stored photons
/// for rendering.
pub trait PathVisitor {
    /// A photon leaves `from`: a light, or a diffuse surface before the Russian roulette
    /// decides whether it is reflected (`from.lumens` is then the expected reflected
    /// power). The place to connect it to targets ([`crate::Targets::connect`]); a visitor
    /// draws from `sampler` only what it uses.
    #[inline]
    fn depart(&mut self, _from: &Departure, _sampler: &mut Sampler<'_>) {}
    /// A photon carrying `power` arrived at `at` travelling along `dir` from `from`;
    /// `bounce` is 0 for the first hit from the light. Called for every arrival, before
    /// the surface acts.
    fn arrive(&mut self, at: &Interaction, dir: Vec3, power: Rgb, bounce: u32, from: &Departure);
    /// A photon carrying `power`, travelling along `dir` from `from` toward its next
    /// arrival (or out of the scene), crossed a calculation surface at `at`
    /// ([`Accel::crossings`]): it goes on unchanged. Measurements count it as an
    /// arrival; a visitor that stores photons leaves it alone, as nothing reflects
    /// there.
    #[inline]
    fn cross(
        &mut self,
        _at: &Interaction,
        _dir: Vec3,
        _power: Rgb,
        _bounce: u32,
        _from: &Departure,
    ) {
    }
    /// A photon carrying `power` left the scene.
    fn escape(&mut self, power: Rgb);
    /// A stratified group of photons ([`crate::GROUP`] consecutive ones, fewer at the
    /// end) has been traced (called by [`crate::trace_chunks`], not by [`trace_photon`]):
    /// the group is one independent sample, and this the place to fold its sums into a
    /// tally.
    #[inline]
    fn end_group(&mut self) {}

    /// Bytes the visitor holds: [`crate::trace_chunks`] keeps fewer chunks' visitors
    /// pending when they are large (fine grids), so that memory stays bounded.
    fn bytes(&self) -> usize {
        0
    }
}

/// What happens to a photon at a surface, with the factor its power is multiplied by.
enum Event {
    Diffuse(Rgb),
    Mirror(Rgb),
    Dielectric(f32),
    Absorbed,
}

/// Traces one photon drawn from `emitters` with `sampler`, reporting to `visitor`; at most
/// `max_bounces` surface interactions follow the first hit, and the Russian roulette
/// starts once the photon's expected reflected power falls below `roulette` times what
/// it left its light with ([`crate::TraceSettings::roulette`]). Returns the rays cast.
pub fn trace_photon(
    scene: &Scene,
    accel: &Accel,
    emitters: &Emitters,
    sampler: &mut Sampler<'_>,
    max_bounces: u32,
    roulette: f32,
    visitor: &mut impl PathVisitor,
) -> u64 {
    let EmitSample {
        origin,
        dir,
        surface_normal,
        mut power,
        lumens,
        lobe,
        source,
    } = emitters.sample(sampler);
    let mut from = Departure {
        point: origin,
        lobe,
        lumens,
        survival: 1.0,
        source,
        emitted: true,
    };
    visitor.depart(&from, sampler);
    // A share that is not a positive number plays the classic roulette.
    let floor = if roulette > 0.0 && roulette.is_finite() {
        roulette * lumens
    } else {
        lumens
    };
    let mut ray = match surface_normal {
        Some(n) => Ray::new(offset_point(origin, n), dir),
        None => Ray::new(origin, dir),
    };
    let mut rays = 0;
    for bounce in 0..=max_bounces {
        rays += 1;
        let hit = accel.intersect(&ray);
        // Calculation surfaces the ray passes before its hit receive it unchanged.
        if accel.has_calculation_surfaces() {
            let end = hit.map_or(f32::INFINITY, |h| h.t);
            accel.crossings(&ray, end, |h| {
                let at = accel.interaction(scene, &ray, &h);
                visitor.cross(&at, ray.dir, power, bounce, &from);
            });
        }
        let Some(hit) = hit else {
            visitor.escape(power);
            break;
        };
        let at = accel.interaction(scene, &ray, &hit);
        visitor.arrive(&at, ray.dir, power, bounce, &from);
        if bounce == max_bounces {
            break;
        }
        // The normal on the side the photon came from.
        let n = if at.normal.dot(ray.dir) < 0.0 {
            at.normal
        } else {
            -at.normal
        };
        let Some(roulette) = Roulette::new(scene, &at, power, floor) else {
            break;
        };
        let diffuse = Departure {
            point: at.point,
            lobe: Lobe::Cosine { normal: n },
            lumens: roulette.rho_d * luminance(power),
            survival: roulette.p_d,
            source,
            emitted: false,
        };
        if roulette.p_d > 0.0 {
            visitor.depart(&diffuse, sampler);
        }
        let dir = match roulette.choose(sampler.uniform()) {
            Event::Absorbed => break,
            Event::Diffuse(f) => {
                power *= f;
                from = diffuse;
                let (u1, u2) = sampler.uniform2();
                sampling::cosine_hemisphere(n, u1, u2)
            }
            Event::Mirror(f) => {
                power *= f;
                from = specular(at.point, power, source, from.emitted);
                reflect(ray.dir, n)
            }
            Event::Dielectric(f) => {
                power *= f;
                from = specular(at.point, power, source, from.emitted);
                let entering = at.normal.dot(ray.dir) < 0.0;
                let ior = scene.materials[at.material].ior;
                let eta = if entering { 1.0 / ior } else { ior };
                let cos_i = -ray.dir.dot(n);
                match refract(ray.dir, n, eta) {
                    Some(t) if sampler.uniform() >= fresnel_dielectric(cos_i, eta) => t,
                    _ => reflect(ray.dir, n),
                }
            }
        };
        debug_assert!(dir.is_finite() && (dir.length() - 1.0).abs() < 1e-3);
        ray = at.spawn(dir);
    }
    rays
}

/// The Russian roulette over a material's parts (thesis Algorithm 2.2): diffuse, mirror,
/// dielectric or absorbed, each surviving power scaled by (part / probability) so that
/// its expectation is the physical one.
///
/// The thesis takes ρ_d = mean(K_d). We take the parts from the photon's own luminance
/// instead, ρ_d = Y(P·K_d)/Y(P) and ρ_s = Y(P·K_s)/Y(P) (pbrt-v4's SPPM photon pass does
/// the same): with mean(K_d) a saturated colour such as (0.9, 0.05, 0.05) multiplies the
/// second moment of the red channel by K_r²/mean(K_d) = 2.7 per bounce, and in a closed
/// red room the variance is infinite: reported intervals would be far too narrow.
///
/// The photon survives with probability s = min(1, ρ·Y(P)/floor), ρ = ρ_d + ρ_s + ρ_t,
/// its parts in proportion: a photon whose expected surviving power ρ·Y(P) is at least
/// `floor` always goes on, at that reduced power, and one below it goes on at exactly
/// `floor` or not at all (pbrt-v4's path tracer plays its roulette on the throughput in
/// the same way). With ρ ≤ 1 a photon's power thus stays between `floor` and the larger
/// of `floor` and what it left its light with. With `floor` the emitted power of a
/// photon of weight 1 (every light but a photometric table's) this is the classic
/// roulette, s = ρ, where every photon keeps its power; a lower floor spends more rays
/// on each photon's first reflections, whose light then no longer hangs on one survival
/// draw ([`crate::tune_roulette`] chooses it).
struct Roulette {
    kd: Rgb,
    specular: Rgb,
    rho_d: f32,
    rho_t: f32,
    p_d: f32,
    p_s: f32,
    p_t: f32,
}

impl Roulette {
    /// The parts at `at` for a photon carrying `power`, surviving as if `floor` lumens
    /// were the least power worth tracing; `None` when nothing is left to reflect.
    #[inline]
    fn new(scene: &Scene, at: &Interaction, power: Rgb, floor: f32) -> Option<Roulette> {
        let m = &scene.materials[at.material];
        let mut kd = m.diffuse;
        if let Some(t) = m.texture {
            kd *= scene.textures[t].sample(at.uv);
        }
        let y = luminance(power);
        if y <= 0.0 {
            return None;
        }
        let rho_d = luminance(power * kd) / y;
        let rho_s = luminance(power * m.specular) / y;
        let rho_t = m.transmission;
        let total = rho_d + rho_s + rho_t;
        if total <= 0.0 {
            return None;
        }
        let survive = (total * y / floor).min(1.0);
        let norm = total / survive;
        Some(Roulette {
            kd,
            specular: m.specular,
            rho_d,
            rho_t,
            p_d: rho_d / norm,
            p_s: rho_s / norm,
            p_t: rho_t / norm,
        })
    }

    /// The event for the uniform number `xi`.
    #[inline]
    fn choose(&self, xi: f32) -> Event {
        let (p_d, p_s, p_t) = (self.p_d, self.p_s, self.p_t);
        if xi < p_d {
            Event::Diffuse(self.kd / p_d)
        } else if xi < p_d + p_s {
            Event::Mirror(self.specular / p_s)
        } else if xi < p_d + p_s + p_t {
            Event::Dielectric(self.rho_t / p_t)
        } else {
            Event::Absorbed
        }
    }
}

/// A departure along a delta lobe (mirror, glass), which no connection competes with.
/// It keeps `emitted` from the departure it continues: a lamp's light through a glass
/// cover or off a mirror is still that lamp's direct light, not reflected light a glare
/// background counts ([`crate::GridValues::Indirect`]).
#[inline]
fn specular(point: Vec3, power: Rgb, source: u32, emitted: bool) -> Departure<'static> {
    Departure {
        point,
        lobe: Lobe::Specular,
        lumens: luminance(power),
        survival: 1.0,
        source,
        emitted,
    }
}

/// Mirror reflection of `d` about the unit normal `n`.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refraction of unit `d` through unit normal `n` (facing against `d`) with relative
/// index `eta = n_from / n_to`; `None` on total internal reflection (Snell's law).
#[inline]
pub fn refract(d: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((d * eta + n * (eta * cos_i - cos_t)).normalize())
}

/// Unpolarised Fresnel reflectance of a dielectric interface for incidence cosine
/// `cos_i` and relative index `eta = n_from / n_to` (pbrt-v4 `FrDielectric`).
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    // With n_from = eta·n_to: r_parl = (n_to cos_i − n_from cos_t)/(…+…), etc.
    let r_parl = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let r_perp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (r_parl * r_parl + r_perp * r_perp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_at_normal_incidence() {
        // ((n1 − n2)/(n1 + n2))² = (0.5/2.5)² = 0.04 for glass of index 1.5, both ways.
        assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        // Total internal reflection beyond the critical angle inside glass.
        assert_eq!(fresnel_dielectric(0.5, 1.5), 1.0);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::Z;
        let d = Vec3::new(0.6, 0.0, -0.8);
        let t = refract(d, n, 1.0 / 1.5).unwrap();
        let sin_i = 0.6f32;
        let sin_t = t.x / t.length();
        assert!((sin_i - 1.5 * sin_t).abs() < 1e-6);
        assert!(t.z < 0.0);
        assert!(refract(Vec3::new(0.9, 0.0, -0.436).normalize(), n, 1.5).is_none());
    }
}
