//! Radiance along camera rays (thesis §2.6.3; Jensen 2001 ch. 9): at a diffuse point,
//! direct light by shadow rays to every light and to the sky plus indirect light and
//! caustics from the photon map; at mirrors and glass the ray is followed recursively,
//! glass split by Fresnel into a reflected and a refracted ray; a ray that leaves the
//! scene sees the sky's luminance (black without a sky).
//!
//! Pixel values are luminances in cd/m² (RGB): a Lambertian surface of reflectance ρ
//! under illuminance E has radiance ρE/π, so an image is proportional to the
//! illuminance wherever the reflectance is uniform.

use crate::camera::View;
use crate::photon_map::PhotonMap;
use glam::Vec3;
use invlight_photon::{
    cosine_hemisphere, emissive_triangles, fresnel_dielectric, reflect, refract,
};
use invlight_scene::{LightKind, Opening, Rgb, Scene, luminance};
use invlight_stats::{Distribution1D, Pcg32};
use invlight_trace::{Accel, Interaction, Ray};
use rayon::prelude::*;
use std::f32::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};

/// How to render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Camera rays per pixel; one goes through the pixel centre, more are jittered.
    pub samples: u32,
    /// Shadow rays to area lights per shading point.
    pub light_samples: u32,
    /// Mirror and glass bounces followed.
    pub max_depth: u32,
    /// Seed of the pixels' random streams (pixel i uses (seed, i)).
    pub seed: u64,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 640,
            height: 480,
            samples: 4,
            light_samples: 2,
            max_depth: 8,
            seed: 1,
        }
    }
}

/// A linear (high dynamic range) image, row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Values per pixel: RGB luminance in cd/m² for renders.
    pub pixels: Vec<Rgb>,
}

/// Illuminance seen through every pixel, for false colour.
#[derive(Debug, Clone, PartialEq)]
pub struct IlluminanceImage {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Illuminance (luminance of the RGB irradiance) of the surface seen, lx; NaN where
    /// the pixel sees nothing.
    pub lux: Vec<f32>,
    /// |cos| between the view ray and the surface normal, to shade shapes.
    pub facing: Vec<f32>,
}

/// An emissive triangle as a light to sample by area.
#[derive(Debug, Clone, Copy)]
struct AreaTriangle {
    p0: Vec3,
    e1: Vec3,
    e2: Vec3,
    normal: Vec3,
    emission: Rgb,
    area: f32,
}

/// The emissive triangles of a scene, to sample by shadow rays. Photons are drawn from
/// every light by `invlight_photon::Emitters`; the camera's direct light needs only the
/// area lights as a distribution (each punctual and directional light is evaluated in
/// turn), and their points with the probability of drawing them.
#[derive(Debug, Clone)]
pub struct AreaLights {
    triangles: Vec<AreaTriangle>,
    /// The triangles by emitted luminous power.
    by_power: Distribution1D,
}

impl AreaLights {
    /// Collects the emissive triangles of `scene`.
    pub fn new(scene: &Scene) -> AreaLights {
        let mut triangles = Vec::new();
        let mut power = Vec::new();
        for t in emissive_triangles(scene) {
            let [a, b, c] = t.corners;
            power.push((luminance(t.emission) * t.area) as f64);
            triangles.push(AreaTriangle {
                p0: a,
                e1: b - a,
                e2: c - a,
                normal: t.normal,
                emission: t.emission,
                area: t.area,
            });
        }
        AreaLights {
            triangles,
            by_power: Distribution1D::new(power),
        }
    }

    /// Picks an emissive triangle ∝ its power: (triangle, probability).
    #[inline]
    fn pick(&self, u: f32) -> (&AreaTriangle, f32) {
        let i = self.by_power.sample(u);
        (&self.triangles[i], self.by_power.pmf(i) as f32)
    }
}

/// Everything needed to shade: the scene, its acceleration structure, its lights and
/// (optionally) a photon map of indirect light.
pub struct Integrator<'a> {
    scene: &'a Scene,
    accel: &'a Accel,
    lights: &'a AreaLights,
    map: Option<&'a PhotonMap>,
    settings: RenderSettings,
    gather: Option<(&'a PhotonMap, u32)>,
}

/// Below this product of reflectances a branch is not followed: it cannot change a
/// pixel by more than a thousandth of what lies behind it.
const MIN_WEIGHT: f32 = 1e-3;

impl<'a> Integrator<'a> {
    /// An integrator over `scene`; without a photon map only direct light and what
    /// mirrors and glass show of it are rendered.
    pub fn new(
        scene: &'a Scene,
        accel: &'a Accel,
        lights: &'a AreaLights,
        map: Option<&'a PhotonMap>,
        settings: RenderSettings,
    ) -> Self {
        Integrator {
            scene,
            accel,
            lights,
            map,
            settings,
            gather: None,
        }
    }

    /// Adds a final gather (Jensen 2001 §9.4; thesis §2.6.3): the indirect light at a
    /// visible diffuse point is gathered by `rays` cosine-distributed rays, each worth
    /// the radiance ρ/π·E of the diffuse point it reaches, with E from `global` (a map
    /// of [`crate::Paths::All`]); E_ind ≈ π/G·Σ L_g. Blotches of the density estimate
    /// are then averaged over many secondary points. The integrator's own map should
    /// then hold caustics only ([`crate::Paths::Caustic`]): a gather ray that meets a
    /// mirror or glass counts nothing, as that light is the caustic map's.
    pub fn with_final_gather(mut self, global: &'a PhotonMap, rays: u32) -> Self {
        self.gather = (rays > 0).then_some((global, rays));
        self
    }

    /// The gathered indirect illuminance at `at` on side `n`.
    fn gather(
        &self,
        global: &PhotonMap,
        rays: u32,
        at: &Interaction,
        n: Vec3,
        rng: &mut Pcg32,
    ) -> Rgb {
        let mut sum = Vec3::ZERO;
        for _ in 0..rays {
            let dir = cosine_hemisphere(n, rng.uniform(), rng.uniform());
            let ray = at.spawn(dir);
            let Some(hit) = self.accel.intersect(&ray) else {
                continue;
            };
            let y = self.accel.interaction(self.scene, &ray, &hit);
            let m = &self.scene.materials[y.material];
            let mut kd = m.diffuse;
            if let Some(t) = m.texture {
                kd *= self.scene.textures[t].sample(y.uv);
            }
            if kd.max_element() > 0.0 {
                let ny = if y.normal.dot(dir) < 0.0 {
                    y.normal
                } else {
                    -y.normal
                };
                sum += kd * global.irradiance(y.point, ny);
            }
        }
        // Each ray carries π/G of the cosine-weighted integral of L = ρE/π.
        sum / rays as f32
    }

    /// Direct illuminance (RGB) at `at` on the side `n` faces: point and spot lights
    /// E = I·f(θ_s)·cos θ/d², goniometric ones the same with the table's intensity
    /// toward the point (from a point of their opening drawn by area), the sun E⊥·cos θ,
    /// each if its shadow ray is free; area
    /// lights by `light_samples` points drawn by area (pdf p_tri/A_tri), each adding
    /// L·cos θ·cos θ_l/(d²·pdf) (pbrt-v4 §12.2, area sampling), and a CIE sky by
    /// `light_samples` directions drawn ∝ its luminance, each adding L·cos θ/pdf when its
    /// ray leaves the scene (under an unobstructed overcast sky the estimate varies only
    /// with cos θ, so an open floor reads the sky's horizontal illuminance).
    pub fn direct(&self, at: &Interaction, n: Vec3, rng: &mut Pcg32) -> Rgb {
        let mut e = Vec3::ZERO;
        for light in &self.scene.lights {
            match light.kind {
                LightKind::Point {
                    position,
                    intensity,
                } => e += self.punctual(at, n, position, intensity),
                LightKind::Spot {
                    position,
                    direction,
                    intensity,
                    inner,
                    outer,
                } => {
                    let wi = (position - at.point).normalize_or_zero();
                    let f = LightKind::spot_falloff(-wi.dot(direction.normalize()), inner, outer);
                    if f > 0.0 {
                        e += self.punctual(at, n, position, intensity * f);
                    }
                }
                LightKind::Directional {
                    direction,
                    illuminance,
                } => {
                    let wi = -direction.normalize();
                    let cos = n.dot(wi);
                    if cos > 0.0 && !self.accel.occluded(&at.spawn(wi)) {
                        e += illuminance * cos;
                    }
                }
                LightKind::Goniometric {
                    position,
                    frame,
                    ref photometry,
                    ..
                } => {
                    // A point of the luminous opening (its centre for a point source),
                    // uniform by area: the mean over the opening of I·cos θ/d² is the
                    // illuminance of the area source.
                    let from = match photometry.opening {
                        Opening::Point => position,
                        opening => position + frame * opening.point(rng.uniform(), rng.uniform()),
                    };
                    let wi = (from - at.point).normalize_or_zero();
                    let i = light.kind.intensity_toward(-wi);
                    if i.max_element() > 0.0 {
                        e += self.punctual(at, n, from, i);
                    }
                }
            }
        }
        if !self.lights.triangles.is_empty() && self.settings.light_samples > 0 {
            let mut area = Vec3::ZERO;
            for _ in 0..self.settings.light_samples {
                let (tri, p) = self.lights.pick(rng.uniform());
                let s = rng.uniform().sqrt();
                let (b1, b2) = (1.0 - s, rng.uniform() * s);
                let y = tri.p0 + tri.e1 * b1 + tri.e2 * b2;
                let d = y - at.point;
                let d2 = d.length_squared();
                if d2 <= 0.0 {
                    continue;
                }
                let wi = d / d2.sqrt();
                let (cos_x, cos_l) = (n.dot(wi), -tri.normal.dot(wi));
                if cos_x <= 0.0 || cos_l <= 0.0 || self.accel.occluded(&at.spawn_to(y)) {
                    continue;
                }
                area += tri.emission * (cos_x * cos_l * tri.area / (d2 * p));
            }
            e += area / self.settings.light_samples as f32;
        }
        if let Some(sky) = &self.scene.sky
            && self.settings.light_samples > 0
        {
            let mut dome = 0.0;
            for _ in 0..self.settings.light_samples {
                let s = sky.sample(rng.uniform(), rng.uniform());
                let cos = n.dot(s.to_sky);
                if cos > 0.0 && s.pdf > 0.0 && !self.accel.occluded(&at.spawn(s.to_sky)) {
                    dome += s.luminance * cos / s.pdf;
                }
            }
            e += Vec3::splat(dome / self.settings.light_samples as f32);
        }
        e
    }

    #[inline]
    fn punctual(&self, at: &Interaction, n: Vec3, position: Vec3, intensity: Rgb) -> Rgb {
        let d = position - at.point;
        let d2 = d.length_squared();
        let cos = n.dot(d) / d2.sqrt();
        if cos <= 0.0 || d2 <= 0.0 || self.accel.occluded(&at.spawn_to(position)) {
            return Vec3::ZERO;
        }
        intensity * (cos / d2)
    }

    /// Total illuminance (RGB) at `at` on side `n`: direct plus the photon map's plus
    /// the final gather's (only the map's when it holds direct light too).
    pub fn irradiance(&self, at: &Interaction, n: Vec3, rng: &mut Pcg32) -> Rgb {
        let mut e = match self.map {
            Some(map) if map.includes_direct() => return map.irradiance(at.point, n),
            Some(map) => self.direct(at, n, rng) + map.irradiance(at.point, n),
            None => self.direct(at, n, rng),
        };
        if let Some((global, rays)) = self.gather {
            e += self.gather(global, rays, at, n, rng);
        }
        e
    }

    /// Radiance (RGB luminance, cd/m²) arriving along `ray`.
    pub fn radiance(&self, ray: &Ray, rng: &mut Pcg32) -> Rgb {
        self.radiance_at_depth(ray, rng, 0, 1.0)
    }

    fn radiance_at_depth(&self, ray: &Ray, rng: &mut Pcg32, depth: u32, weight: f32) -> Rgb {
        let Some(hit) = self.accel.intersect(ray) else {
            let sky = self.scene.sky.as_ref();
            return Vec3::splat(sky.map_or(0.0, |s| s.luminance(ray.dir)));
        };
        let at = self.accel.interaction(self.scene, ray, &hit);
        let m = &self.scene.materials[at.material];
        let front = at.normal.dot(ray.dir) < 0.0;
        let n = if front { at.normal } else { -at.normal };
        let mut l = if front { m.emission } else { Vec3::ZERO };
        let mut kd = m.diffuse;
        if let Some(t) = m.texture {
            kd *= self.scene.textures[t].sample(at.uv);
        }
        if kd.max_element() > 0.0 {
            l += kd / PI * self.irradiance(&at, n, rng);
        }
        if depth >= self.settings.max_depth {
            return l;
        }
        let ks = m.specular.max_element();
        if ks > 0.0 && weight * ks > MIN_WEIGHT {
            let r = at.spawn(reflect(ray.dir, n));
            l += m.specular * self.radiance_at_depth(&r, rng, depth + 1, weight * ks);
        }
        let t = m.transmission;
        if t > 0.0 {
            let eta = if front { 1.0 / m.ior } else { m.ior };
            let cos_i = -ray.dir.dot(n);
            let (fr, refracted) = match refract(ray.dir, n, eta) {
                Some(dir) => (fresnel_dielectric(cos_i, eta), Some(dir)),
                None => (1.0, None),
            };
            if weight * t * fr > MIN_WEIGHT {
                let r = at.spawn(reflect(ray.dir, n));
                l += t * fr * self.radiance_at_depth(&r, rng, depth + 1, weight * t * fr);
            }
            if let Some(dir) = refracted
                && weight * t * (1.0 - fr) > MIN_WEIGHT
            {
                let w = t * (1.0 - fr);
                l += w * self.radiance_at_depth(&at.spawn(dir), rng, depth + 1, weight * w);
            }
        }
        l
    }

    /// Illuminance (lx) and |cos| of the first surface along `ray`, if any.
    pub fn illuminance(&self, ray: &Ray, rng: &mut Pcg32) -> Option<(f32, f32)> {
        let hit = self.accel.intersect(ray)?;
        let at = self.accel.interaction(self.scene, ray, &hit);
        let cos = at.normal.dot(ray.dir);
        let n = if cos < 0.0 { at.normal } else { -at.normal };
        Some((luminance(self.irradiance(&at, n, rng)), cos.abs()))
    }
}

/// The image point of sample `s` of pixel (x, y): the centre for the first sample,
/// uniformly jittered for the others.
#[inline]
fn sample_point(x: u32, y: u32, s: u32, settings: &RenderSettings, rng: &mut Pcg32) -> (f32, f32) {
    let (jx, jy) = if s == 0 {
        (0.5, 0.5)
    } else {
        (rng.uniform(), rng.uniform())
    };
    (
        (x as f32 + jx) / settings.width as f32,
        (y as f32 + jy) / settings.height as f32,
    )
}

/// Stream offset separating the pixels' random numbers from the photons'.
const PIXEL_STREAM: u64 = 0x5049_5845_4c53;

/// Computes every pixel in parallel (rows handed to rayon), each from its own random
/// stream keyed by its index, so the result is the same on any number of threads.
/// `pixel(x, y, rng)` gives one pixel's value; `progress` receives the rows done.
fn per_pixel<T: Send + Clone>(
    s: &RenderSettings,
    empty: T,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    pixel: impl Fn(u32, u32, &mut Pcg32) -> T + Sync,
) -> Vec<T> {
    let mut pixels = vec![empty; s.width as usize * s.height as usize];
    let done = AtomicU64::new(0);
    pixels
        .par_chunks_mut(s.width as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, px) in row.iter_mut().enumerate() {
                let index = y as u64 * s.width as u64 + x as u64;
                let mut rng = Pcg32::new(s.seed ^ PIXEL_STREAM, index);
                *px = pixel(x as u32, y as u32, &mut rng);
            }
            if let Some(report) = progress {
                report(done.fetch_add(1, Ordering::Relaxed) + 1);
            }
        });
    pixels
}

/// Renders `view` of the integrator's scene: every pixel in parallel, each from its own
/// random stream, so the image is the same on any number of threads. `progress`
/// receives the rows done.
pub fn render(
    integrator: &Integrator,
    view: &View,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Image {
    let s = integrator.settings;
    let samples = s.samples.max(1);
    let pixels = per_pixel(&s, Vec3::ZERO, progress, |x, y, rng| {
        let mut sum = Vec3::ZERO;
        for k in 0..samples {
            let (sx, sy) = sample_point(x, y, k, &s, rng);
            sum += integrator.radiance(&view.ray(sx, sy), rng);
        }
        sum / samples as f32
    });
    Image {
        width: s.width,
        height: s.height,
        pixels,
    }
}

/// The illuminance of the surface seen through every pixel (averaged over its samples
/// that hit something), for false colour. Parallel and deterministic as [`render`].
pub fn render_illuminance(
    integrator: &Integrator,
    view: &View,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> IlluminanceImage {
    let s = integrator.settings;
    let values = per_pixel(&s, (f32::NAN, 0.0f32), progress, |x, y, rng| {
        let (mut lux, mut facing, mut hits) = (0.0f32, 0.0f32, 0u32);
        for k in 0..s.samples.max(1) {
            let (sx, sy) = sample_point(x, y, k, &s, rng);
            if let Some((e, c)) = integrator.illuminance(&view.ray(sx, sy), rng) {
                lux += e;
                facing += c;
                hits += 1;
            }
        }
        if hits > 0 {
            (lux / hits as f32, facing / hits as f32)
        } else {
            (f32::NAN, 0.0)
        }
    });
    IlluminanceImage {
        width: s.width,
        height: s.height,
        lux: values.iter().map(|v| v.0).collect(),
        facing: values.iter().map(|v| v.1).collect(),
    }
}
