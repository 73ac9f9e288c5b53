//! The goal and constraints by photon tracing (thesis §3.3, §4.9.2): apply the
//! configuration's arrangement to the scene, rebuild the acceleration structure's top
//! level if an instance moved (the instances no variable moves are baked into one tree
//! once), trace once for every measured surface and grid, and read each intention from
//! the tallies.
//!
//! Every evaluation uses the same photon seed (common random numbers, DESIGN.md §2):
//! photon i of two configurations starts from the same random numbers, so their
//! difference is far less noisy than either value, and a fast estimate with n photons
//! is the first n photons of the full one. A configuration evaluated again with more
//! photons continues its kept trace ([`measure_more`]): the same numbers as tracing
//! afresh, for the photons after those traced.
//!
//! Dimming costs no photons: each dimmed light's light is tallied apart and weighed by
//! its level ([`Binding::levels`]), so every dimming of one arrangement is read from
//! one trace, kept while the search tries dimmings of it. A problem whose only
//! variables are dimming levels traces once, with N photons, whatever the search asks.

use crate::binding::Binding;
use crate::dimming::LevelSolver;
use crate::intention::Bound;
use crate::space::Configuration;
use crate::vns::{Evaluate, Evaluation};
use invlight_photon::CHUNK;
use invlight_photon::{
    Alone, Cluster, Components, Estimator, GridError, GridRequest, Measurement, Request,
    TraceSettings, cluster, measure_across, measure_more, photons_traced, tune_roulette,
};
use invlight_scene::Scene;
use invlight_stats::Estimate;
use invlight_trace::Accel;
use rayon::prelude::*;
use std::collections::HashMap;

/// The most traces the evaluator keeps for dimmings of their arrangements and for
/// continuations, and the most bytes they may hold together: `RACE_ISOC_ON_END`'s
/// race continues every survivor's trace of the look before (a hundred members on a
/// flat top), and a problem with many components and grids keeps traces of megabytes.
const KEPT_TRACES: usize = 1024;
const KEPT_BYTES: usize = 256 << 20;

/// The light a measured surface receives on each side, for the warning that much of it
/// arrives from behind.
#[derive(Debug, Clone, PartialEq)]
pub struct SideSplit {
    /// The surface.
    pub name: String,
    /// Mean illuminance on its front, lx.
    pub front: Estimate,
    /// On its back, lx.
    pub back: Estimate,
}

impl SideSplit {
    /// The warning a surface counted on both sides deserves when more than a tenth of
    /// its light arrives on its back, with both figures.
    pub fn warning(&self) -> Option<String> {
        let share = self.back_share();
        (share > 0.1).then(|| {
            format!(
                "'{}' receives {:.0} % of its light on its back ({} lx on its back, {} lx on its front, at the first configuration): add side=\"front\" where it is named if only the front counts, or side=\"back\" if its triangles face away from the room",
                self.name,
                100.0 * share,
                invlight_stats::significant(self.back.mean),
                invlight_stats::significant(self.front.mean)
            )
        })
    }

    /// The back's share of the surface's light (0 when it has none).
    pub fn back_share(&self) -> f64 {
        let total = self.front.mean + self.back.mean;
        if total > 0.0 {
            self.back.mean / total
        } else {
            0.0
        }
    }
}

/// Evaluates configurations of a bound problem by photon tracing.
pub struct PhotonEvaluator<'b> {
    binding: &'b Binding,
    stage: Stage,
    /// Copies of the stage for candidates traced side by side ([`Evaluate::prepare`]),
    /// made when first needed.
    helpers: Vec<Stage>,
    components: Components,
    seed: u64,
    max_bounces: u32,
    /// [`TraceSettings::roulette`] of every trace: given, or chosen by a pilot
    /// ([`tune_roulette`]) at the first trace, on the scene as bound (before any
    /// configuration is arranged), so that it depends on the problem and seed alone.
    roulette: Option<f32>,
    /// N: what a problem of dimming levels alone traces, once.
    full: u64,
    rays: u64,
    photons: u64,
    traces: u64,
    kept: Kept,
    /// What the kept traces hold, [`Measurement::heap_bytes`] summed.
    kept_bytes: usize,
    /// Traces made side by side ahead of their evaluation ([`Evaluate::prepare`]), each
    /// with the photons of the kept trace it continued; counted only when an
    /// evaluation reads one, so a trace the search never asks for counts nothing.
    ready: HashMap<(Vec<u64>, u64), (Measurement, Option<u64>)>,
    first_sides: Option<Vec<SideSplit>>,
    /// The threads of all the job's processes, counted once they are asked for
    /// ([`PhotonEvaluator::lanes`]).
    lanes: std::cell::OnceCell<usize>,
}

/// Why an evaluation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum EvaluationError {
    /// A measured surface moved to where no grid can be laid on it.
    Grid(String, GridError),
}

impl std::fmt::Display for EvaluationError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EvaluationError::Grid(name, e) => write!(f, "cannot lay a grid on '{name}': {e}"),
        }
    }
}

impl std::error::Error for EvaluationError {}

impl<'b> PhotonEvaluator<'b> {
    /// An evaluator owning `scene` (already prepared by [`Binding::new`]); photons use
    /// `seed` and at most `max_bounces` bounces, and a full evaluation traces `full`.
    pub fn new(binding: &'b Binding, scene: Scene, seed: u64, max_bounces: u32, full: u64) -> Self {
        let accel = Accel::with_movable(&scene, &binding.movable_instances());
        PhotonEvaluator {
            binding,
            components: binding.components(&scene),
            stage: Stage { scene, accel },
            helpers: Vec::new(),
            seed,
            max_bounces,
            roulette: None,
            full,
            rays: 0,
            photons: 0,
            traces: 0,
            kept: HashMap::new(),
            kept_bytes: 0,
            ready: HashMap::new(),
            first_sides: None,
            lanes: std::cell::OnceCell::new(),
        }
    }

    /// The threads of all the job's processes, the same figure on every process: in a
    /// cluster job each process says its own (one exchange, the first time), since nodes
    /// may differ in cores and the candidates readied side by side, which every process
    /// must choose alike, are sized by it.
    fn lanes(&self) -> usize {
        *self.lanes.get_or_init(|| {
            let mine = rayon::current_num_threads() as u64;
            let all = cluster();
            if all.ranks() == 1 {
                return mine as usize;
            }
            all.all_gather(&[mine]).iter().sum::<u64>() as usize
        })
    }

    /// Every trace with the roulette share `share` instead of one a pilot chooses.
    pub fn with_roulette(mut self, share: f32) -> Self {
        self.roulette = Some(share);
        self
    }

    /// The roulette share of every trace, chosen by a pilot on the scene as bound when
    /// first asked for ([`tune_roulette`] for N photons of every measured surface,
    /// shared by a cluster job's processes, which all ask at the same first trace); the
    /// pilot's photons and rays count as work.
    fn roulette(&mut self) -> f32 {
        if let Some(share) = self.roulette {
            return share;
        }
        let surfaces = &self.binding.reading.surfaces;
        let request = Request::means(surfaces, &self.components, Estimator::Connected);
        let settings = TraceSettings {
            photons: self.full,
            seed: self.seed,
            max_bounces: self.max_bounces,
            roulette: 1.0,
        };
        let (scene, accel) = (&self.stage.scene, &self.stage.accel);
        let choice = tune_roulette(scene, accel, &request, &settings, cluster());
        self.rays += choice.rays;
        self.photons += choice.photons;
        self.roulette = Some(choice.share);
        choice.share
    }

    /// Rays cast and photons traced so far.
    pub fn work(&self) -> (u64, u64) {
        (self.rays, self.photons)
    }

    /// Traces so far: dimmings of an arrangement already traced take none.
    pub fn traces(&self) -> u64 {
        self.traces
    }

    /// Each measured surface's light by side at the first evaluation, for surfaces an
    /// intention counts on both sides.
    pub fn first_sides(&self) -> &[SideSplit] {
        self.first_sides.as_deref().unwrap_or(&[])
    }

    fn trace(
        &mut self,
        config: &Configuration,
        photons: u64,
    ) -> Result<&Measurement, EvaluationError> {
        let key = (self.binding.arrangement(config), photons);
        if !self.kept.contains_key(&key) {
            let roulette = self.roulette();
            let previous = previous(&self.kept, &key);
            let from = previous.map(|p| p.photons);
            // A trace readied ahead is the one this would make if it continued the same
            // kept trace (the keeping may have dropped that one since).
            if let Some((m, _)) = self.ready.remove(&key).filter(|(_, f)| *f == from) {
                self.keep(key.clone(), m, from);
                return Ok(&self.kept[&key]);
            }
            let job = Job {
                binding: self.binding,
                components: &self.components,
                seed: self.seed,
                max_bounces: self.max_bounces,
                roulette,
            };
            let m = job.trace(&mut self.stage, config, photons, previous, cluster())?;
            self.keep(key.clone(), m, previous.map(|p| p.photons));
        }
        Ok(&self.kept[&key])
    }

    /// Counts a trace's work (what it traced beyond the kept trace of `from` photons it
    /// continued) and keeps it.
    fn keep(&mut self, key: (Vec<u64>, u64), m: Measurement, from: Option<u64>) {
        let before = from.and_then(|p| self.kept.get(&(key.0.clone(), p)));
        let (reused, rays_before) = before.map_or((0, 0), |p| {
            (p.resumable_photons(), p.rays + p.connection_rays)
        });
        self.rays += m.rays + m.connection_rays - rays_before;
        self.photons += m.photons - reused;
        self.traces += 1;
        let bytes = m.heap_bytes();
        if self.kept.len() >= KEPT_TRACES || self.kept_bytes + bytes > KEPT_BYTES {
            self.kept.clear();
            self.kept_bytes = 0;
        }
        self.kept_bytes += bytes;
        if let Some(old) = self.kept.insert(key, m) {
            self.kept_bytes -= old.heap_bytes();
        }
    }
}

impl PhotonEvaluator<'_> {
    /// Traces the arrangements of `configs` not kept yet side by side, into
    /// [`PhotonEvaluator::ready`] in place of what it held (a failed trace is left for
    /// [`Evaluate::evaluate`] to make again and report). The candidates are dealt to the
    /// processes of a cluster job in turn (rank r takes the r-th, the (r + K)-th, …;
    /// a batch of one-chunk looks keeps every rank busy, where a shared trace
    /// of one chunk would keep one), each rank traces its share on as many stages at
    /// once as it has threads, each trace its own, and the ranks exchange the
    /// measurements: the exchange comes from this thread alone, in the same order on
    /// every rank, as MPI's serialised calls need.
    fn trace_side_by_side(&mut self, configs: &[Configuration], photons: u64) {
        self.ready.clear();
        let mut todo: Vec<((Vec<u64>, u64), &Configuration)> = Vec::new();
        for c in configs {
            let key = (self.binding.arrangement(c), photons);
            if !self.kept.contains_key(&key) && todo.iter().all(|(k, _)| *k != key) {
                todo.push((key, c));
            }
        }
        if todo.len() < 2 {
            return;
        }
        let (rank, ranks) = (cluster().rank(), cluster().ranks());
        let mine: Vec<usize> = (rank..todo.len()).step_by(ranks).collect();
        let stages = rayon::current_num_threads().min(mine.len()).max(1);
        while self.helpers.len() + 1 < stages {
            let copy = Stage {
                scene: self.stage.scene.clone(),
                accel: self.stage.accel.clone(),
            };
            self.helpers.push(copy);
        }
        let roulette = self.roulette();
        let job = Job {
            binding: self.binding,
            components: &self.components,
            seed: self.seed,
            max_bounces: self.max_bounces,
            roulette,
        };
        let previous: Vec<Option<&Measurement>> = todo
            .iter()
            .map(|(key, _)| previous(&self.kept, key))
            .collect();
        let from: Vec<Option<u64>> = previous.iter().map(|p| p.map(|m| m.photons)).collect();
        let work: Vec<_> = mine.iter().map(|&i| (todo[i].1, previous[i])).collect();
        let mut copies: Vec<&mut Stage> = std::iter::once(&mut self.stage)
            .chain(self.helpers.iter_mut())
            .take(stages)
            .collect();
        let per = work.len().div_ceil(stages).max(1);
        let parts: Vec<Vec<_>> = copies
            .par_iter_mut()
            .zip(work.par_chunks(per))
            .map(|(stage, part)| {
                part.iter()
                    .map(|(c, p)| job.trace(stage, c, photons, *p, &Alone).ok())
                    .collect()
            })
            .collect();
        let traced: Vec<Option<Measurement>> = parts.into_iter().flatten().collect();
        let traced = if ranks == 1 {
            traced
        } else {
            job.exchange(&mut self.stage, &todo, traced, (rank, ranks))
        };
        for (((key, _), m), from) in todo.into_iter().zip(traced).zip(from) {
            if let Some(m) = m {
                self.ready.insert(key, (m, from));
            }
        }
    }
}

/// The evaluation of `config`'s arrangement, traced in `m`, at the least-power levels
/// that meet its constraints with the margins of a full evaluation of `full` photons
/// ([`LevelSolver::solve`]); the configuration with those levels goes with it. The
/// power of those levels is exact, as any configuration's is: the noise of the
/// estimate that chose them is in its constraints, which decide at the confidence
/// whether they hold, and with fewer than `full` photons they are undecided, so that
/// an arrangement is admitted only once traced with N.
fn solved(
    binding: &Binding,
    variables: &[usize],
    solver: &LevelSolver,
    config: &Configuration,
    m: &Measurement,
    full: u64,
) -> Evaluation {
    let bounds: Vec<Bound> = binding.constraints.iter().map(|c| c.bound).collect();
    let found = solver.solve(&binding.reading, &bounds, m, full);
    let mut config = config.clone();
    for ((&v, &y), d) in variables.iter().zip(&found.levels).zip(&solver.dimmers) {
        let range = d.max - d.min;
        binding.space.slice_mut(&mut config, v)[0] = if range > 0.0 {
            ((y - d.min) / range).clamp(0.0, 1.0)
        } else {
            0.0
        };
    }
    let power = binding.power(&config);
    let mut evaluation = binding.reading.read(m, &binding.levels(&config), power);
    evaluation.solved = Some(config);
    evaluation
}

/// The kept trace that a trace of `key` continues: its arrangement's largest of fewer
/// photons (a candidate looked at with n, 4n, … then N photons traces N in all).
fn previous<'k>(kept: &'k Kept, key: &(Vec<u64>, u64)) -> Option<&'k Measurement> {
    kept.iter()
        .filter(|((a, p), _)| *a == key.0 && *p < key.1)
        .max_by_key(|((_, p), _)| *p)
        .map(|(_, m)| m)
}

/// Traces kept for dimmings and continuations, by arrangement and photon count.
type Kept = HashMap<(Vec<u64>, u64), Measurement>;

/// A scene and its acceleration structure, arranged as the last configuration traced.
struct Stage {
    scene: Scene,
    accel: Accel,
}

/// What every trace of one evaluator shares.
#[derive(Clone, Copy)]
struct Job<'a> {
    binding: &'a Binding,
    components: &'a Components,
    seed: u64,
    max_bounces: u32,
    roulette: f32,
}

impl Job<'_> {
    /// Arranges `stage` as `config`, rebuilding the top level if an instance moved, and
    /// gives the request a trace of it makes (its grids follow the surfaces).
    fn arrange(
        &self,
        stage: &mut Stage,
        config: &Configuration,
    ) -> Result<Request<'_>, EvaluationError> {
        if self.binding.apply_arrangement(&mut stage.scene, config) {
            stage.accel.update_instances(&stage.scene);
        }
        let grids = self
            .binding
            .reading
            .grid_requests(&stage.scene)
            .map_err(|(name, e)| EvaluationError::Grid(name, e))?;
        Ok(self.request(grids))
    }

    /// The request of a trace laying `grids`.
    fn request(&self, grids: Vec<GridRequest>) -> Request<'_> {
        Request {
            surfaces: &self.binding.reading.surfaces,
            grids,
            components: self.components,
            estimator: Estimator::Connected,
            // The paired search compares configurations by their groups.
            keep_groups: true,
            observers: self
                .binding
                .reading
                .observers
                .iter()
                .map(|(_, o)| *o)
                .collect(),
        }
    }

    /// Every rank's measurements of a batch `todo` dealt in turn to `ranks` processes,
    /// from this rank's share `mine` ([`PhotonEvaluator::trace_side_by_side`]): packed,
    /// gathered from all ranks and read back in `todo`'s order (this rank's own kept as
    /// they are), each other's read with the request of its configuration, which
    /// `stage` is arranged as to know its grids when there are any. A failed trace
    /// travels as a failure (one word), to be traced again, and reported, one by one.
    fn exchange(
        &self,
        stage: &mut Stage,
        todo: &[((Vec<u64>, u64), &Configuration)],
        mine: Vec<Option<Measurement>>,
        (rank, ranks): (usize, usize),
    ) -> Vec<Option<Measurement>> {
        let mut words = Vec::new();
        let mut lengths = Vec::with_capacity(mine.len());
        for m in &mine {
            let start = words.len();
            match m {
                Some(m) => {
                    words.push(1);
                    m.pack(&mut words);
                }
                None => words.push(0),
            }
            lengths.push(words.len() - start);
        }
        let all = cluster().all_gather(&words);
        let mut all = all.into_iter();
        let mut out: Vec<Option<Measurement>> = todo.iter().map(|_| None).collect();
        let mut own = mine.into_iter().zip(lengths);
        for r in 0..ranks {
            for i in (r..todo.len()).step_by(ranks) {
                if r == rank {
                    let (m, length) = own.next().expect("this rank's share");
                    all.nth(length - 1);
                    out[i] = m;
                } else if all.next() == Some(1) {
                    // Without grids the request is the same for every configuration.
                    let request = if self.binding.reading.grids.is_empty() {
                        self.request(Vec::new())
                    } else {
                        self.arrange(stage, todo[i].1)
                            .expect("a configuration another rank could trace")
                    };
                    out[i] = Some(Measurement::unpack(&request, &mut all));
                }
            }
        }
        out
    }

    /// Arranges `stage` as `config` (rebuilding the top level if an instance moved) and
    /// traces `photons`, continuing `previous` if given. The numbers depend on the
    /// configuration and the seed alone, not on what the stage held before, so any
    /// stage may trace any configuration.
    fn trace(
        &self,
        stage: &mut Stage,
        config: &Configuration,
        photons: u64,
        previous: Option<&Measurement>,
        cluster: &dyn Cluster,
    ) -> Result<Measurement, EvaluationError> {
        let request = self.arrange(stage, config)?;
        let settings = TraceSettings {
            photons,
            seed: self.seed,
            max_bounces: self.max_bounces,
            roulette: self.roulette,
        };
        let (scene, accel) = (&stage.scene, &stage.accel);
        Ok(match previous {
            Some(p) => measure_more(scene, accel, &request, &settings, None, p, cluster),
            None => measure_across(scene, accel, &request, &settings, None, cluster),
        })
    }
}

impl Evaluate for PhotonEvaluator<'_> {
    type Error = EvaluationError;

    fn evaluate(
        &mut self,
        config: &Configuration,
        photons: u64,
    ) -> Result<Evaluation, EvaluationError> {
        let photons = self.samples(photons);
        let levels = self.binding.levels(config);
        let power = self.binding.power(config);
        let binding = self.binding;
        let first = self.first_sides.is_none();
        let full = self.full;
        let m = self.trace(config, photons)?;
        let evaluation = match binding.level_solver() {
            Some((variables, solver)) => solved(binding, variables, solver, config, m, full),
            None => binding.reading.read(m, &levels, power),
        };
        if first {
            let reading = &binding.reading;
            let sides = (0..reading.surfaces.len())
                .filter(|&t| reading.both_sides[t])
                .map(|t| SideSplit {
                    name: reading.names[t].clone(),
                    front: m.estimate_of(t, invlight_photon::Side::Front, &levels),
                    back: m.estimate_of(t, invlight_photon::Side::Back, &levels),
                })
                .collect();
            self.first_sides = Some(sides);
        }
        Ok(evaluation)
    }

    /// Traces side by side when a trace of `photons` alone would leave cores idle
    /// ([`Evaluate::side_by_side`]), each thread on its own copy of the scene and
    /// acceleration structure (made once, when first needed), a cluster job's batch
    /// dealt to its processes. Every trace's numbers depend on its configuration and
    /// the seed alone, so the evaluations that read them are those of
    /// [`Evaluate::evaluate`] alone, bit for bit, on any number of threads and
    /// processes; their work is counted when read, where a trace alone would have been
    /// made, so the kept traces and the counts are those of the run without readying.
    fn prepare(&mut self, configs: &[Configuration], photons: u64) {
        let photons = self.samples(photons);
        if configs.len() > 1 && self.side_by_side(photons) > 1 {
            self.trace_side_by_side(configs, photons);
        }
    }

    /// As many as there are threads, of all the job's processes
    /// (`PhotonEvaluator::lanes`), for each trace's chunks of [`CHUNK`] photons to keep
    /// one busy (the screening's and the
    /// fast looks' 2 048 photons are one chunk), once the first evaluation is made; 1
    /// when one trace alone keeps every core busy.
    fn side_by_side(&self, photons: u64) -> usize {
        if self.first_sides.is_none() {
            return 1;
        }
        let chunks = self.samples(photons).div_ceil(CHUNK).max(1);
        (self.lanes() as u64 / chunks).max(1) as usize
    }

    /// Whole groups of photons, at least the tracer's minimum; a count past `u64` is
    /// held at the largest whole number of groups (no run gets near either). A problem
    /// of dimming levels alone always traces N: its one trace serves every evaluation.
    fn samples(&self, requested: u64) -> u64 {
        let requested = if self.binding.dimming_only() {
            requested.max(self.full)
        } else {
            requested
        };
        photons_traced(requested).unwrap_or(u64::MAX - u64::MAX % invlight_photon::GROUP)
    }

    fn refuses(&self, config: &Configuration) -> Option<String> {
        self.binding.refusal(config)
    }
}
