//! The photon map (thesis §2.6.2–2.6.3; Jensen, *Realistic Image Synthesis Using Photon
//! Mapping*, 2001): photons stored where they arrive, and the irradiance at a point
//! estimated from the photons around it (thesis eq. 2.6).
//!
//! Which photons are kept depends on how the map is used ([`Paths`]): to be looked at
//! directly, only photons that did **not** come straight from a light (direct light is
//! computed exactly by shadow rays; the map holds indirect light and caustics, which
//! shadow rays cannot see); for a final gather, a global map of every arrival and a
//! caustic map of paths that met only mirrors and glass since leaving the light
//! (Jensen 2001 §7.5, §9.3).
//!
//! The spatial structure is a hashed uniform grid of cells 2r wide (Teschner et al. 2003,
//! "Optimized Spatial Hashing for Collision Detection of Deformable Objects"; the photon
//! grid of Hachisuka & Jensen 2010): every photon's cell key is computed in parallel and
//! the photons are placed by a stable counting sort, so building costs O(n) and the
//! order (hence every sum, hence the image) is independent of the number of threads. A
//! query of radius r visits the 2×2×2 cells that its ball can touch. A kd-tree would
//! answer k-nearest queries, but its build is a sequence of dependent median splits; a
//! fixed radius from the mean photon density suits the grid (BENCHMARKS.md, "Rendering benchmarks").

use glam::Vec3;
use invlight_photon::{Departure, Emitters, PathVisitor, PhotonTrace, TraceSettings, trace_chunks};
use invlight_scene::{Rgb, Scene};
use invlight_trace::{Accel, Interaction};
use rayon::prelude::*;
use std::time::Instant;

/// Where photons are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Store {
    /// On surfaces with a diffuse part, for rendering: mirrors and glass have no
    /// view-independent radiance to estimate.
    Diffuse,
    /// On every surface, for illuminance (false colour): a mirror is lit too.
    All,
}

/// How to build a photon map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonSettings {
    /// Photons emitted, N.
    pub photons: u64,
    /// Seed of the photon streams; photon i uses (seed, i).
    pub seed: u64,
    /// Bounce cap of the paths.
    pub max_bounces: u32,
    /// Which surfaces keep photons.
    pub store: Store,
    /// Gather radius, m; `None` chooses it from the mean photon density so that a disc
    /// holds about `neighbours` photons.
    pub radius: Option<f32>,
    /// Photons a gather disc holds on average when the radius is automatic.
    pub neighbours: u32,
    /// Which photon paths are kept.
    pub paths: Paths,
}

/// Which arrivals a map keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Paths {
    /// Every arrival but the first from the light: indirect light and caustics, to add
    /// to the direct light of shadow rays.
    Indirect,
    /// Every arrival, first ones included: the map carries all the light. Used by a
    /// final gather's secondary points, and, looked at directly, it makes an
    /// [`crate::Integrator`] cast no shadow rays (Jensen's "direct visualisation"),
    /// whose only error is the density estimate's: the check of the map against
    /// closed forms.
    All,
    /// Arrivals after one or more mirror or glass interactions and nothing else since
    /// the light (L S+ D paths): caustics, which a final gather cannot find.
    Caustic,
}

impl Default for PhotonSettings {
    fn default() -> Self {
        PhotonSettings {
            photons: 1_000_000,
            seed: 1,
            max_bounces: 32,
            store: Store::Diffuse,
            radius: None,
            neighbours: 100,
            paths: Paths::Indirect,
        }
    }
}

/// A stored photon: where it arrived, the normal on the side it came from, its power.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Photon {
    position: Vec3,
    side: Vec3,
    power: Rgb,
}

/// Stored photons in a hashed grid, ready for density estimation.
#[derive(Debug, Clone)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// `photons[start[k]..start[k+1]]` lie in the cells whose hash is k.
    start: Vec<u32>,
    mask: u64,
    radius: f32,
    inv_cell: f32,
    /// 1 / (N π r²) times the biweight normalisation, applied to every estimate.
    scale: f32,
    /// Whether `photons` carry precomputed irradiance (see [`PhotonMap::precompute`]).
    precomputed: bool,
    emitted: u64,
    direct: bool,
    /// Seconds spent tracing photons and building the grid.
    seconds: (f64, f64),
}

/// Collects one chunk's photons.
struct Collector<'a> {
    scene: &'a Scene,
    store: Store,
    paths: Paths,
    /// Whether the current photon met only mirrors and glass since its light.
    specular_only: bool,
    photons: Vec<Photon>,
}

impl PathVisitor for Collector<'_> {
    #[inline]
    fn arrive(&mut self, at: &Interaction, dir: Vec3, power: Rgb, bounce: u32, _from: &Departure) {
        if bounce == 0 {
            self.specular_only = true;
        }
        let keep = match self.paths {
            Paths::Indirect => bounce > 0,
            Paths::All => true,
            Paths::Caustic => bounce > 0 && self.specular_only,
        };
        let m = &self.scene.materials[at.material];
        // The path leaves this surface diffusely if it has a diffuse part (for a mixed
        // material the event is not reported; calling it diffuse errs toward the global
        // map, which the gather reaches anyway).
        let diffuse = m.diffuse.max_element() > 0.0 || m.texture.is_some();
        self.specular_only &= !diffuse;
        if !keep || m.hole || (self.store == Store::Diffuse && !diffuse) {
            return;
        }
        let side = if at.normal.dot(dir) < 0.0 {
            at.normal
        } else {
            -at.normal
        };
        self.photons.push(Photon {
            position: at.point,
            side,
            power,
        });
    }

    #[inline]
    fn escape(&mut self, _power: Rgb) {}
}

/// Total area of the surfaces that store photons under `store`, m².
fn storing_area(scene: &Scene, store: Store) -> f64 {
    let mut area = 0.0f64;
    for inst in &scene.instances {
        let mesh = &scene.meshes[inst.mesh];
        for (t, &m) in mesh.materials.iter().enumerate() {
            let m = &scene.materials[m];
            if m.hole || (store == Store::Diffuse && m.diffuse.max_element() <= 0.0) {
                continue;
            }
            area += mesh.triangle_area(t, &inst.transform) as f64;
        }
    }
    area
}

/// Teschner et al.'s spatial hash of an integer cell.
#[inline]
fn hash(c: [i32; 3]) -> u64 {
    ((c[0] as u32 as u64).wrapping_mul(73_856_093)
        ^ (c[1] as u32 as u64).wrapping_mul(19_349_663)
        ^ (c[2] as u32 as u64).wrapping_mul(83_492_791))
    .wrapping_mul(0x9e37_79b9_7f4a_7c15)
        >> 20
}

impl PhotonMap {
    /// Traces `settings.photons` photons from the lights of `scene` (by
    /// [`trace_chunks`], chunks in parallel, concatenated in index order) and builds the grid.
    /// `progress` receives the photons traced so far.
    pub fn build(
        scene: &Scene,
        accel: &Accel,
        settings: &PhotonSettings,
        progress: Option<&(dyn Fn(u64) + Sync)>,
    ) -> PhotonMap {
        let start = Instant::now();
        let trace = TraceSettings {
            photons: settings.photons,
            seed: settings.seed,
            max_bounces: settings.max_bounces,
            ..TraceSettings::default()
        };
        let mut photons = Vec::new();
        let emitters = Emitters::new(scene);
        let photon_trace = PhotonTrace {
            scene,
            accel,
            emitters: &emitters,
            settings: &trace,
        };
        trace_chunks(
            photon_trace,
            || Collector {
                scene,
                store: settings.store,
                paths: settings.paths,
                specular_only: true,
                photons: Vec::new(),
            },
            |collector| photons.extend(collector.photons),
            progress,
        );
        let radius = settings.radius.unwrap_or_else(|| {
            let area = storing_area(scene, settings.store);
            let n = photons.len().max(1) as f64;
            let r = (settings.neighbours.max(1) as f64 * area / (std::f64::consts::PI * n)).sqrt();
            // Never wider than a tenth of the scene.
            let extent = scene
                .bounds()
                .map(|(lo, hi)| (hi - lo).length() as f64)
                .unwrap_or(1.0);
            r.min(0.1 * extent).max(1e-6) as f32
        });
        let trace_seconds = start.elapsed().as_secs_f64();
        let grid_start = Instant::now();
        let mut map = PhotonMap::from_photons(photons, radius, settings.photons);
        map.direct = settings.paths == Paths::All;
        map.seconds = (trace_seconds, grid_start.elapsed().as_secs_f64());
        map
    }

    fn from_photons(photons: Vec<Photon>, radius: f32, emitted: u64) -> PhotonMap {
        let inv_cell = 1.0 / (2.0 * radius);
        let buckets = (photons.len().max(1) * 2).next_power_of_two();
        let mask = buckets as u64 - 1;
        let keys: Vec<u32> = photons
            .par_iter()
            .map(|p| (hash(cell_of(p.position, inv_cell)) & mask) as u32)
            .collect();
        let mut start = vec![0u32; buckets + 1];
        for &k in &keys {
            start[k as usize + 1] += 1;
        }
        for k in 0..buckets {
            start[k + 1] += start[k];
        }
        let mut next = start.clone();
        let mut sorted = vec![
            Photon {
                position: Vec3::ZERO,
                side: Vec3::ZERO,
                power: Vec3::ZERO,
            };
            photons.len()
        ];
        for (p, &k) in photons.iter().zip(&keys) {
            sorted[next[k as usize] as usize] = *p;
            next[k as usize] += 1;
        }
        // Silverman's biweight kernel K(d) = 3/(π r²)·(1 − d²/r²)², which integrates to
        // one over the disc (Silverman 1986, eq. 4.5; Jensen 2001 §7.2 filters likewise).
        let scale = 3.0 / (std::f32::consts::PI * radius * radius * emitted.max(1) as f32);
        PhotonMap {
            photons: sorted,
            start,
            mask,
            radius,
            inv_cell,
            scale,
            precomputed: false,
            emitted,
            direct: false,
            seconds: (0.0, 0.0),
        }
    }

    /// Photons stored.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// Whether no photon was stored.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The gather radius, m.
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Wall-clock seconds spent (tracing the photons, building the grid).
    pub fn seconds(&self) -> (f64, f64) {
        self.seconds
    }

    /// Whether the map holds direct light too ([`Paths::All`]).
    pub fn includes_direct(&self) -> bool {
        self.direct
    }

    /// Photons emitted to build the map, N.
    pub fn emitted(&self) -> u64 {
        self.emitted
    }

    /// Irradiance (RGB, lux when the lights are photometric) at `point` on the side of
    /// the surface that unit `side` points to, from the photons within the radius whose
    /// own side agrees (so light on one face of a wall never leaks to the other):
    /// E ≈ Σ_p Φ_p K(‖x − x_p‖) / N (thesis eq. 2.6 with a smooth kernel).
    pub fn irradiance(&self, point: Vec3, side: Vec3) -> Rgb {
        let r2 = self.radius * self.radius;
        let inv_r2 = 1.0 / r2;
        let mut sum = Vec3::ZERO;
        let mut nearest = (r2, Vec3::ZERO);
        self.visit(point, |p| {
            let d2 = (p.position - point).length_squared();
            if d2 < r2 && p.side.dot(side) > 0.8 {
                if self.precomputed {
                    if d2 < nearest.0 {
                        nearest = (d2, p.power);
                    }
                } else {
                    let w = 1.0 - d2 * inv_r2;
                    sum += p.power * (w * w);
                }
            }
        });
        if self.precomputed {
            nearest.1
        } else {
            sum * self.scale
        }
    }

    /// Calls `f` on every photon of the 2×2×2 cells that a ball of the gather radius
    /// around `point` can touch.
    #[inline]
    fn visit(&self, point: Vec3, mut f: impl FnMut(&Photon)) {
        let lo = cell_of(point - Vec3::splat(self.radius), self.inv_cell);
        let mut seen = [u64::MAX; 8];
        for i in 0..8 {
            let c = [
                lo[0] + (i & 1) as i32,
                lo[1] + ((i >> 1) & 1) as i32,
                lo[2] + ((i >> 2) & 1) as i32,
            ];
            let k = hash(c) & self.mask;
            // Two neighbouring cells may share a bucket: visit each bucket once.
            if seen[..i].contains(&k) {
                continue;
            }
            seen[i] = k;
            let (a, b) = (self.start[k as usize], self.start[k as usize + 1]);
            self.photons[a as usize..b as usize].iter().for_each(&mut f);
        }
    }

    /// Precomputed irradiance (Christensen 1999, "Faster photon map global
    /// illumination", JGT 4(3)): the irradiance estimate at every `stride`-th photon,
    /// computed once in parallel, in a map whose [`PhotonMap::irradiance`] returns the
    /// nearest such value within the radius. A final gather asks for thousands of
    /// times more estimates than there are photons; this makes each a search among
    /// 1/stride of the photons without the kernel sum.
    pub fn precompute(&self, stride: usize) -> PhotonMap {
        let points: Vec<Photon> = self
            .photons
            .par_iter()
            .step_by(stride.max(1))
            .map(|p| Photon {
                power: self.irradiance(p.position, p.side),
                ..*p
            })
            .collect();
        let mut map = PhotonMap::from_photons(points, self.radius, self.emitted);
        map.direct = self.direct;
        map.precomputed = true;
        map.seconds = self.seconds;
        map
    }
}

#[inline]
fn cell_of(p: Vec3, inv_cell: f32) -> [i32; 3] {
    let c = (p * inv_cell).floor();
    [c.x as i32, c.y as i32, c.z as i32]
}

#[cfg(test)]
mod tests {
    use super::*;
    use invlight_stats::Pcg32;

    #[test]
    fn uniform_photons_give_their_density() {
        // Photons of power 1 on a jittered grid of spacing h on the plane z = 0, emitted
        // count N: irradiance = (1/h²)/N away from the edges, up to the quadrature error
        // of the kernel on the grid.
        let h = 0.01f32;
        let mut photons = Vec::new();
        let mut rng = Pcg32::new(9, 0);
        for i in 0..200 {
            for j in 0..200 {
                photons.push(Photon {
                    position: Vec3::new(
                        (i as f32 + rng.uniform()) * h,
                        (j as f32 + rng.uniform()) * h,
                        0.0,
                    ),
                    side: Vec3::Z,
                    power: Vec3::ONE,
                });
            }
        }
        let map = PhotonMap::from_photons(photons, 0.1, 10);
        let e = map.irradiance(Vec3::new(1.0, 1.0, 0.0), Vec3::Z);
        let expected = 1.0 / (h * h) / 10.0;
        // About 314 photons in the disc, jittered: relative noise ≈ sqrt(1.8/314) ≈ 7.6 %.
        assert!(
            (e.x - expected).abs() < 4.0 * 0.076 * expected,
            "{e} vs {expected}"
        );
        // Precomputed at every 4th photon, the nearest value is an estimate of the same.
        let pre = map.precompute(4);
        let e4 = pre.irradiance(Vec3::new(1.0, 1.0, 0.0), Vec3::Z);
        assert!(
            (e4.x - expected).abs() < 4.0 * 0.076 * expected,
            "{e4} vs {expected}"
        );
        assert_eq!(pre.len(), 10_000);
        // The other side of the plane sees nothing.
        assert_eq!(
            map.irradiance(Vec3::new(1.0, 1.0, 0.0), Vec3::NEG_Z),
            Vec3::ZERO
        );
    }
}
