//! Measuring surfaces: the mean illuminance of each target from one trace of photons
//! (thesis §3.3, §4.9.2), accumulated without storing photons, in parallel, with
//! results that do not depend on the number of threads.
//!
//! Photons are traced by [`trace_chunks`], each chunk tallied on its own
//! ([`GroupTallies`]) and the chunk tallies summed in index order: the same seed gives
//! the same bits on one thread or many, and memory stays constant however many photons
//! are traced.

use crate::chunks::{TraceSettings, trace_chunks};
use crate::connect::{Departure, Targets};
use crate::emit::Emitters;
use crate::estimator::{GroupTallies, Tally, photons_traced};
use crate::path::PathVisitor;
use crate::sampler::Sampler;
use glam::Vec3;
use invlight_scene::{Rgb, Scene, SurfaceId, luminance};
use invlight_stats::{Confidence, Estimate};
use invlight_trace::{Accel, Interaction};
use serde::{Deserialize, Serialize};

/// How the photons' contributions to a target are counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Estimator {
    /// Every photon departure (a light, a diffuse bounce before the roulette) is also
    /// connected to a point on each target ([`crate::Targets`]: next-event estimation
    /// toward the target, weighted against the arrivals by multiple importance
    /// sampling). Same expectation as arrivals alone, a fraction of the variance for
    /// small targets and light through openings (BENCHMARKS.md); a ray per departure
    /// and target.
    Connected,
    /// Arrivals alone, as the thesis counts them (eq. 3.2): better when nearly every
    /// photon reaches the target anyway, and the reference the connected estimator is
    /// checked against.
    ArrivalsOnly,
}

impl Estimator {
    /// The estimator a command's `--arrivals-only` flag asks for.
    pub fn arrivals_only(flag: bool) -> Estimator {
        if flag {
            Estimator::ArrivalsOnly
        } else {
            Estimator::Connected
        }
    }

    /// `connected` or `arrivals`, as outputs name it.
    pub fn name(self) -> &'static str {
        match self {
            Estimator::Connected => "connected",
            Estimator::ArrivalsOnly => "arrivals",
        }
    }
}

/// What a measurement found.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// Photons emitted, N: the count asked for rounded up to whole groups
    /// ([`photons_traced`]).
    pub photons: u64,
    /// Rays cast along the photons' paths (closest-hit queries).
    pub rays: u64,
    /// Rays cast by connections (closest-hit queries toward the targets).
    pub connection_rays: u64,
    /// One tally per target, in the order the targets were given.
    pub tallies: Vec<Tally>,
    /// Each target's area, m².
    pub areas: Vec<f64>,
    /// Luminous power that left the scene, Σ over photons, lm·photons (divide by N).
    pub escaped: f64,
    /// The scene's total luminous flux Φ, lm: what each photon carries.
    pub flux: f64,
}

impl Measurement {
    /// Mean illuminance of target `i`, in lux, with its standard error
    /// ([`Tally::estimate`]).
    pub fn estimate(&self, i: usize) -> Estimate {
        self.tallies[i].estimate(self.areas[i], self.photons, self.flux)
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
    tallies: GroupTallies,
    escaped: f64,
    connection_rays: u64,
}

impl PathVisitor for ChunkTally<'_> {
    #[inline]
    fn depart(&mut self, from: &Departure, sampler: &mut Sampler<'_>) {
        if let Some((targets, accel)) = self.connect {
            for t in 0..targets.len() {
                if let Some(c) = targets.connect(t, from, accel, sampler) {
                    self.connection_rays += 1;
                    self.tallies.add(t as u32, c.lumens);
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
/// ([`photons_traced`]; [`Measurement::photons`] says how many), from the lights of
/// `scene` and tallies what they bring to the surfaces `targets`. `progress` is called
/// from worker threads with the number of photons traced so far.
///
/// # Panics
/// If the photon count overflows when rounded up to whole groups (callers check it
/// with [`photons_traced`] where it comes from a user).
pub fn measure(
    scene: &Scene,
    accel: &Accel,
    targets: &[SurfaceId],
    settings: &TraceSettings,
    estimator: Estimator,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Measurement {
    let settings = &TraceSettings {
        photons: photons_traced(settings.photons).expect("a photon count that fits in u64"),
        ..*settings
    };
    let emitters = Emitters::new(scene);
    let map = TargetMap::new(scene, targets);
    let shapes = Targets::new(scene, targets);
    let connect = estimator == Estimator::Connected;
    let mut result = Measurement {
        photons: settings.photons,
        rays: 0,
        connection_rays: 0,
        tallies: vec![Tally::default(); targets.len()],
        areas: targets
            .iter()
            .map(|&s| scene.surface_area(s) as f64)
            .collect(),
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
            connect: connect.then_some((&shapes, accel)),
            tallies: GroupTallies::new(targets.len()),
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

/// One surface of a [`MeasureReport`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceReport {
    /// Its name.
    pub name: String,
    /// Its area, m².
    pub area: f64,
    /// Mean illuminance, lx.
    pub mean: f64,
    /// Lower end of the interval at the report's confidence, lx.
    pub low: f64,
    /// Upper end, lx.
    pub high: f64,
    /// Standard error of the mean, lx.
    pub std_error: f64,
    /// Photon arrivals counted.
    pub hits: u64,
}

/// `invlight measure --json`: a measurement with its settings and costs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeasureReport {
    /// The measured surfaces, in the order asked.
    pub surfaces: Vec<SurfaceReport>,
    /// Photons traced (whole groups).
    pub photons: u64,
    /// Rays along the photons' paths.
    pub rays: u64,
    /// Rays of connections to the surfaces.
    pub connection_rays: u64,
    /// [`Estimator::name`].
    pub estimator: String,
    /// The scene's luminous flux, lm.
    pub flux_lm: f64,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Seed of the photon streams.
    pub seed: u64,
    /// Bounce cap.
    pub max_bounces: u32,
    /// Seconds from the start of the build to the end of the trace.
    pub seconds: f64,
    /// Seconds building the acceleration structure.
    pub build_seconds: f64,
}

impl MeasureReport {
    /// The report as a table for people: a row per surface, then the costs.
    pub fn table(&self) -> String {
        use invlight_stats::significant;
        let width = self
            .surfaces
            .iter()
            .map(|s| s.name.len())
            .max()
            .unwrap_or(7)
            .max(7);
        let mut out = format!(
            "{:<width$}  {:>10}  {:>12}  {:>27}  {:>10}\n",
            "surface",
            "area m²",
            "mean lx",
            format!("{:.0} % interval lx", self.confidence * 100.0),
            "hits"
        );
        for s in &self.surfaces {
            out += &format!(
                "{:<width$}  {:>10.4}  {:>12}  {:>27}  {:>10}\n",
                s.name,
                s.area,
                significant(s.mean),
                format!("[{}, {}]", significant(s.low), significant(s.high)),
                s.hits
            );
        }
        out += &format!(
            "{} photons, {} rays and {} connection rays, {:.2} s ({:.2} M photons/s), {} lm emitted\n",
            self.photons,
            self.rays,
            self.connection_rays,
            self.seconds,
            self.photons as f64 / self.seconds / 1e6,
            significant(self.flux_lm)
        );
        out
    }
}

impl Measurement {
    /// The report of this measurement of surfaces named `names` (in target order), with
    /// intervals at `confidence`, traced with `settings` and `estimator`.
    pub fn report(
        &self,
        names: &[String],
        confidence: Confidence,
        settings: &TraceSettings,
        estimator: Estimator,
        (seconds, build_seconds): (f64, f64),
    ) -> MeasureReport {
        let z = confidence.z();
        MeasureReport {
            surfaces: names
                .iter()
                .enumerate()
                .map(|(i, name)| {
                    let e = self.estimate(i);
                    let interval = e.interval(z);
                    SurfaceReport {
                        name: name.clone(),
                        area: self.areas[i],
                        mean: e.mean,
                        low: interval.low,
                        high: interval.high,
                        std_error: e.std_error,
                        hits: self.tallies[i].hits,
                    }
                })
                .collect(),
            photons: self.photons,
            rays: self.rays,
            connection_rays: self.connection_rays,
            estimator: estimator.name().into(),
            flux_lm: self.flux,
            confidence: confidence.level(),
            seed: settings.seed,
            max_bounces: settings.max_bounces,
            seconds,
            build_seconds,
        }
    }
}
