//! Measuring surfaces: per-surface tallies of the photons' arrivals (thesis §3.3, §4.9.2),
//! accumulated without storing photons, in parallel, with results that do not depend on
//! the number of threads.
//!
//! Photons are traced by [`trace_chunks`], each chunk tallied on its own and the chunk
//! tallies summed in index order: the same seed gives the same bits on one thread or
//! many, and memory stays constant however many photons are traced.

use crate::chunks::trace_chunks;
use crate::connect::{Departure, Targets};
use crate::emit::Emitters;
use crate::estimate::Estimate;
use crate::path::PathVisitor;
use crate::sampler::{Sampler, whole_groups};
use glam::Vec3;
use invlight_scene::{Rgb, Scene, SurfaceId, luminance};
use invlight_trace::{Accel, Interaction};

/// How to trace.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceSettings {
    /// Photons to emit, N. Measurements ([`trace`], illuminance maps) round it up to
    /// [`whole_groups`].
    pub photons: u64,
    /// Seed of the random streams; photon i uses the stream (seed, i).
    pub seed: u64,
    /// Surface interactions followed after the first hit from the light. Russian
    /// roulette ends paths on its own; this is a safety cap (the thesis used 4).
    pub max_bounces: u32,
    /// Whether [`trace`] also connects every photon departure to every target
    /// ([`crate::Targets`]: next-event estimation toward the target, weighted against the
    /// arrivals by multiple importance sampling) instead of counting arrivals alone as
    /// the thesis does. Same expectation, a fraction of the variance (BENCHMARKS.md).
    /// Visitors of [`crate::trace_chunks`] (maps, photon maps) decide for themselves.
    pub connect: bool,
}

impl Default for TraceSettings {
    fn default() -> Self {
        TraceSettings {
            photons: 1_000_000,
            seed: 1,
            max_bounces: DEFAULT_MAX_BOUNCES,
            connect: true,
        }
    }
}

/// The default bounce cap: high enough that, with the reflectances of real rooms, no
/// measurable energy is cut off (0.9^1000 ≈ 2·10⁻⁴⁶), low enough to stop a photon caught
/// between perfect mirrors.
pub const DEFAULT_MAX_BOUNCES: u32 = 1000;

/// Sums over stratified groups of one target's per-group contributions X_g, in lm (the
/// luminous power a group of [`crate::GROUP`] photons brings to the target, all their
/// arrivals added): groups are the independent samples (see [`crate::Sampler`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Tally {
    /// Σ X_g.
    pub sum: f64,
    /// Σ X_g².
    pub sum_sq: f64,
    /// Number of arrivals.
    pub hits: u64,
}

impl Tally {
    /// The mean illuminance over `area` m² of what `photons` photons carrying `flux` lm in
    /// all brought, in lux, with its standard error ([`TraceResult::estimate`], whose
    /// rule for a tally nothing reached this applies: one arrival's worth, Φ/(A·N)).
    pub fn estimate(&self, area: f64, photons: u64, flux: f64) -> Estimate {
        let inv = 1.0 / area;
        let mut e = Estimate::from_groups(self.sum * inv, self.sum_sq * inv * inv, photons);
        if self.sum <= 0.0 && photons > 0 {
            e.std_error = flux * inv / photons as f64;
        }
        e
    }

    fn merge(&mut self, other: &Tally) {
        self.sum += other.sum;
        self.sum_sq += other.sum_sq;
        self.hits += other.hits;
    }
}

/// One chunk's tallies of many targets, built photon by photon: a group's arrivals on a
/// target are summed first (X_g is the group's whole contribution, all arrivals added,
/// so that Σ X_g² is the variance's), and folded in at [`PhotonTallies::end_group`].
/// Only the targets the group touched are visited then, so a photon costs its arrivals,
/// not the number of targets.
#[derive(Debug, Clone)]
pub struct PhotonTallies {
    tallies: Vec<Tally>,
    current: Vec<f64>,
    touched: Vec<u32>,
}

impl PhotonTallies {
    /// Empty tallies of `targets` targets.
    pub fn new(targets: usize) -> PhotonTallies {
        PhotonTallies {
            tallies: vec![Tally::default(); targets],
            current: vec![0.0; targets],
            touched: Vec::new(),
        }
    }

    /// The current photon arrived on `target`, counting `lumens` of its power.
    #[inline]
    pub fn arrive(&mut self, target: u32, lumens: f64) {
        self.add(target, lumens);
        self.tallies[target as usize].hits += 1;
    }

    /// The current photon brings `lumens` to `target` otherwise than by arriving (a
    /// connection).
    #[inline]
    pub fn add(&mut self, target: u32, lumens: f64) {
        if lumens == 0.0 {
            return;
        }
        let t = target as usize;
        if self.current[t] == 0.0 {
            self.touched.push(target);
        }
        self.current[t] += lumens;
    }

    /// The current group ended: its sums join the tallies.
    #[inline]
    pub fn end_group(&mut self) {
        for &t in &self.touched {
            let x = std::mem::take(&mut self.current[t as usize]);
            let tally = &mut self.tallies[t as usize];
            tally.sum += x;
            tally.sum_sq += x * x;
        }
        self.touched.clear();
    }

    /// Adds these tallies to `totals`, target by target.
    pub fn add_to(&self, totals: &mut [Tally]) {
        for (total, t) in totals.iter_mut().zip(&self.tallies) {
            total.merge(t);
        }
    }
}

/// What a trace measured.
#[derive(Debug, Clone, PartialEq)]
pub struct TraceResult {
    /// Photons emitted, N: the settings' count rounded up to [`whole_groups`].
    pub photons: u64,
    /// Rays cast (closest-hit queries).
    pub rays: u64,
    /// Rays cast by connections (closest-hit queries toward the targets).
    pub connection_rays: u64,
    /// One tally per target, in the order the targets were given.
    pub tallies: Vec<Tally>,
    /// Luminous power that left the scene, Σ over photons, lm·photons (divide by N).
    pub escaped: f64,
    /// The scene's total luminous flux Φ, lm: what each photon carries.
    pub flux: f64,
}

impl TraceResult {
    /// Mean illuminance of target `i` of area `area` m², in lux, with its standard
    /// error: F_N = Σ_g X_g / (A·N) (thesis eq. 3.2, the photons summed group by group),
    /// the standard error from the spread of the groups' sums.
    ///
    /// A target nothing reached (no arrival, no connection) has a sample variance of
    /// zero, which would claim the mean 0 exact and let a comparison rule the surface out
    /// on no evidence. Its standard error is then taken as the illuminance one arrival
    /// would have given, Φ/(A·N): the binomial σ with the hit probability 1/N, the
    /// smallest that is not ruled out.
    pub fn estimate(&self, i: usize, area: f64) -> Estimate {
        self.tallies[i].estimate(area, self.photons, self.flux)
    }
}

/// Which targets each instance belongs to (a compressed sparse row table: an instance
/// may be under several names, e.g. a node and its parent).
struct TargetMap {
    offsets: Vec<u32>,
    targets: Vec<u32>,
}

impl TargetMap {
    fn new(scene: &Scene, targets: &[SurfaceId]) -> TargetMap {
        let mut per_instance: Vec<Vec<u32>> = vec![Vec::new(); scene.instances.len()];
        for (t, &s) in targets.iter().enumerate() {
            for &i in &scene.surfaces[s as usize].instances {
                per_instance[i as usize].push(t as u32);
            }
        }
        let mut offsets = vec![0u32];
        let mut flat = Vec::new();
        for list in per_instance {
            flat.extend(list);
            offsets.push(flat.len() as u32);
        }
        TargetMap {
            offsets,
            targets: flat,
        }
    }

    #[inline]
    fn of(&self, instance: u32) -> &[u32] {
        let i = instance as usize;
        &self.targets[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

/// Tallies one chunk of photons on the measured targets.
struct ChunkTally<'a> {
    map: &'a TargetMap,
    /// The targets to connect departures to; `None` counts arrivals alone.
    connect: Option<(&'a Targets, &'a Accel)>,
    tallies: PhotonTallies,
    escaped: f64,
    connection_rays: u64,
}

impl PathVisitor for ChunkTally<'_> {
    #[inline]
    fn depart(&mut self, from: &Departure, sampler: &mut Sampler<'_>) {
        if let Some((targets, accel)) = self.connect {
            for t in 0..targets.len() {
                if let Some(lumens) = targets.connect(t, from, accel, sampler) {
                    self.connection_rays += 1;
                    self.tallies.add(t as u32, lumens);
                }
            }
        }
    }

    #[inline]
    fn arrive(&mut self, at: &Interaction, _dir: Vec3, power: Rgb, _bounce: u32, from: &Departure) {
        let on = self.map.of(at.instance);
        if on.is_empty() {
            return;
        }
        let lumens = luminance(power);
        let weighing = self
            .connect
            .map(|(targets, _)| (targets, from.arrival_density(at.point, at.normal)));
        for &t in on {
            let w = match weighing {
                Some((targets, density)) => targets.arrival_weight(t as usize, density),
                None => 1.0,
            };
            self.tallies.arrive(t, (lumens * w) as f64);
        }
    }

    #[inline]
    fn escape(&mut self, power: Rgb) {
        self.escaped += luminance(power) as f64;
    }

    #[inline]
    fn end_group(&mut self) {
        self.tallies.end_group();
    }
}

/// Traces `settings.photons` photons, rounded up to whole stratified groups
/// ([`whole_groups`]; [`TraceResult::photons`] says how many), from the lights of `scene`
/// and tallies their arrivals on the surfaces `targets`. `progress` is called from worker
/// threads with the number of photons traced so far.
pub fn trace(
    scene: &Scene,
    accel: &Accel,
    targets: &[SurfaceId],
    settings: &TraceSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> TraceResult {
    let settings = &TraceSettings {
        photons: whole_groups(settings.photons),
        ..*settings
    };
    let emitters = Emitters::new(scene);
    let map = TargetMap::new(scene, targets);
    let shapes = Targets::new(scene, targets);
    let mut result = TraceResult {
        photons: settings.photons,
        rays: 0,
        connection_rays: 0,
        tallies: vec![Tally::default(); targets.len()],
        escaped: 0.0,
        flux: emitters.total_flux(),
    };
    result.rays = trace_chunks(
        scene,
        accel,
        &emitters,
        settings,
        || ChunkTally {
            map: &map,
            connect: settings.connect.then_some((&shapes, accel)),
            tallies: PhotonTallies::new(targets.len()),
            escaped: 0.0,
            connection_rays: 0,
        },
        |part| {
            part.tallies.add_to(&mut result.tallies);
            result.escaped += part.escaped;
            result.connection_rays += part.connection_rays;
        },
        progress,
    );
    result
}
