//! Measuring surfaces: the mean illuminance of each target from one trace of photons
//! (thesis §3.3, §4.9.2), accumulated without storing photons, in parallel, with
//! results that do not depend on the number of threads.
//!
//! Photons are traced by [`trace_chunks`], each chunk tallied on its own
//! (per target and channel, per grid cell) and the chunk tallies summed in index order: the same seed gives
//! the same bits on one thread or many, and memory stays constant however many photons
//! are traced.

use crate::cells::{CellTallies, GridMeasurement};
use crate::channels::{Components, Side, SurfaceTallies, side_weights};
use crate::chunks::{CHUNK, PhotonTrace, TraceSettings};
use crate::cluster::{Cluster, cluster, trace_shared_from};
use crate::connect::Targets;
use crate::direct::direct_on_grid;
use crate::emit::Emitters;
use crate::estimator::{GROUP, photons_traced};
use crate::glare::{Observer, glare_sums};
use crate::grid::SurfaceGrid;
use crate::tally::{ChunkTally, Plan, TargetMap};
use glam::Vec3;
use invlight_scene::{Scene, SurfaceId};
use invlight_stats::{ChannelSums, Estimate};
use invlight_trace::Accel;

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

/// What to measure in one trace: surfaces, grids on some of them, and the components
/// whose light is kept apart.
#[derive(Debug, Clone)]
pub struct Request<'a> {
    /// The surfaces whose mean illuminance is measured (front and back apart).
    pub surfaces: &'a [SurfaceId],
    /// Grids read cell by cell: each on `surfaces[target]`, counting one side.
    pub grids: Vec<GridRequest>,
    /// Which lights' light is kept apart ([`Components::one`]: all together).
    pub components: &'a Components,
    /// How photons are counted.
    pub estimator: Estimator,
    /// Whether every group's totals are kept for [`Measurement::group_means`]: memory
    /// that grows with the photons (a 10⁹-photon measurement would hold 15.6 M groups per
    /// target), so only a search that pairs configurations asks for it.
    pub keep_groups: bool,
    /// Eyes whose luminaires' glare sums are computed, per component
    /// ([`Measurement::glare_sum`]; their backgrounds are grids of
    /// [`GridValues::Indirect`] on eye squares, [`crate::glare::eye_grid`]).
    pub observers: Vec<Observer>,
}

impl<'a> Request<'a> {
    /// The mean illuminances of `surfaces`, lights kept apart by `components`, counted
    /// by `estimator`: no grids, no groups kept.
    pub fn means(
        surfaces: &'a [SurfaceId],
        components: &'a Components,
        estimator: Estimator,
    ) -> Request<'a> {
        Request {
            surfaces,
            grids: Vec::new(),
            components,
            estimator,
            keep_groups: false,
            observers: Vec::new(),
        }
    }
}

/// A grid to read on one of a [`Request`]'s surfaces.
#[derive(Debug, Clone, PartialEq)]
pub struct GridRequest {
    /// Index in [`Request::surfaces`] of the surface the grid lies on.
    pub target: usize,
    /// The side counted.
    pub side: Side,
    /// The grid ([`SurfaceGrid::new`] or [`SurfaceGrid::en12464`] of that surface).
    pub grid: SurfaceGrid,
    /// What a cell's value is: the illuminance at its centre, or its mean.
    pub values: GridValues,
}

/// What a grid's cell reads ([`GridRequest::values`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GridValues {
    /// The illuminance at the cell's centre, as EN 12464-1 takes it: the point, spot and
    /// photometric lights' direct light computed there exactly, plus the photons' cell
    /// mean of the rest (`direct.rs`).
    #[default]
    Points,
    /// The photons' mean over the cell, all light together.
    CellMeans,
    /// The photons' mean over the cell of the light that has been reflected or
    /// transmitted at least once: every light's direct light left out, as CIE 117's
    /// background luminance takes the illuminance at an eye ([`crate::glare`]).
    Indirect,
}

impl GridValues {
    /// `points` or `cell-means`, as files and flags name it.
    pub fn name(self) -> &'static str {
        match self {
            GridValues::Points => "points",
            GridValues::CellMeans => "cell-means",
            GridValues::Indirect => "indirect",
        }
    }

    /// The values a file or flag may name, `points` or `cell-means` (an indirect grid is
    /// a glare rating's own).
    pub fn parse(name: &str) -> Option<GridValues> {
        [GridValues::Points, GridValues::CellMeans]
            .into_iter()
            .find(|v| v.name() == name)
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
    /// Each target's area, m², in the order the targets were given.
    pub areas: Vec<f64>,
    /// Photon arrivals on each target.
    pub hits: Vec<u64>,
    /// Each target's group sums: 2K channels, its front's per component, then its back's.
    channels: Vec<ChannelSums>,
    /// Every group's channel totals in group order: the targets' 2K channels of group
    /// 0, then of group 1, … ([`Measurement::group_means`]).
    groups: Vec<f64>,
    /// The grids, in the order asked.
    pub grids: Vec<GridMeasurement>,
    /// The luminous flux of each component, lm, as traced (undimmed).
    pub component_flux: Vec<f64>,
    /// Luminous power that left the scene, Σ over photons, lm·photons (divide by N).
    pub escaped: f64,
    /// The scene's total luminous flux Φ, lm: what each photon carries.
    pub flux: f64,
    /// Each observer's glare sum Σ L²ω/p² per component at level 1, cd²/m⁴·sr, in the
    /// request's order ([`crate::glare::glare_sums`]): exact, computed once per trace.
    pub glare: Vec<Vec<f64>>,
    /// The sums at the start of the last chunk when it is partial and the groups are
    /// kept, without the groups ([`measure_more`] continues from there).
    boundary: Option<Box<Measurement>>,
}

impl Measurement {
    /// About the bytes it holds on the heap (its sums, groups, grids and the partial
    /// chunk's boundary), for a caller that keeps many measurements within a budget.
    pub fn heap_bytes(&self) -> usize {
        let grids: usize = self
            .grids
            .iter()
            .map(|g| g.sums.heap_bytes() + g.grid.areas.len() * size_of::<f64>())
            .sum();
        size_of::<Measurement>()
            + (self.areas.len() + self.groups.len() + self.component_flux.len()) * size_of::<f64>()
            + self.hits.len() * size_of::<u64>()
            + self
                .channels
                .iter()
                .map(ChannelSums::heap_bytes)
                .sum::<usize>()
            + grids
            + self.boundary.as_ref().map_or(0, |b| b.heap_bytes())
    }

    /// The measurement [`measure_more`] continues from: this one when it ends on a chunk
    /// boundary, else its sums at the last boundary if it kept them.
    fn boundary(&self) -> Option<&Measurement> {
        if self.photons.is_multiple_of(CHUNK) {
            Some(self)
        } else {
            self.boundary.as_deref()
        }
    }

    /// The photons [`measure_more`] would not trace again when continuing this
    /// measurement: all of them on a chunk boundary, those before the last boundary when
    /// it kept its groups, none otherwise.
    pub fn resumable_photons(&self) -> u64 {
        self.boundary().map_or(0, |b| b.photons)
    }

    /// Appends this measurement to `out` as words, for another process of a cluster
    /// job to read back with [`Measurement::unpack`] (ranks that trace whole candidates
    /// of a batch exchange their measurements). Every number goes as its
    /// bits, so the reader holds the same measurement, bit for bit.
    pub fn pack(&self, out: &mut Vec<u64>) {
        let reals = |out: &mut Vec<u64>, xs: &[f64]| {
            out.push(xs.len() as u64);
            out.extend(xs.iter().map(|x| x.to_bits()));
        };
        out.extend([self.photons, self.rays, self.connection_rays]);
        reals(out, &self.areas);
        out.extend(&self.hits);
        self.channels.iter().for_each(|c| c.pack(out));
        reals(out, &self.groups);
        for g in &self.grids {
            g.sums.pack(out);
            out.extend([g.photons, g.flux.to_bits()]);
            reals(out, &g.direct);
        }
        reals(out, &self.component_flux);
        out.extend([self.escaped.to_bits(), self.flux.to_bits()]);
        self.glare.iter().for_each(|g| reals(out, g));
        match &self.boundary {
            Some(b) => {
                out.push(1);
                b.pack(out);
            }
            None => out.push(0),
        }
    }

    /// Reads back a measurement that [`Measurement::pack`] wrote of `request` (the same
    /// surfaces, grids and components), as the process that traced it held it.
    ///
    /// # Panics
    /// If `words` ends first or do not come from a measurement of such a request.
    pub fn unpack(request: &Request, words: &mut impl Iterator<Item = u64>) -> Measurement {
        let word = |words: &mut dyn Iterator<Item = u64>| {
            words
                .next()
                .expect("a packed measurement of the same request")
        };
        let reals = |words: &mut dyn Iterator<Item = u64>| -> Vec<f64> {
            let n = word(words) as usize;
            (0..n).map(|_| f64::from_bits(word(words))).collect()
        };
        let (photons, rays, connection_rays) = (word(words), word(words), word(words));
        let areas = reals(words);
        let targets = request.surfaces.len();
        let hits = (0..targets).map(|_| word(words)).collect();
        let k = request.components.count();
        let channels = (0..targets)
            .map(|_| {
                let mut c = ChannelSums::new(2 * k);
                c.unpack(words);
                c
            })
            .collect();
        let groups = reals(words);
        let grids = request
            .grids
            .iter()
            .map(|g| {
                let mut sums = CellTallies::new(g.grid.cells(), k).sums;
                sums.unpack(words);
                let mut m = GridMeasurement::new(g.grid.clone(), g.side, sums);
                m.photons = word(words);
                m.flux = f64::from_bits(word(words));
                m.direct = reals(words);
                m
            })
            .collect();
        let component_flux = reals(words);
        let (escaped, flux) = (f64::from_bits(word(words)), f64::from_bits(word(words)));
        let glare = request.observers.iter().map(|_| reals(words)).collect();
        let boundary = (word(words) == 1).then(|| Box::new(Measurement::unpack(request, words)));
        Measurement {
            photons,
            rays,
            connection_rays,
            areas,
            hits,
            channels,
            groups,
            grids,
            component_flux,
            escaped,
            flux,
            glare,
            boundary,
        }
    }

    /// The totals each kept group holds: every target's 2K channels.
    fn group_width(&self) -> usize {
        self.areas.len() * 2 * self.components()
    }

    /// The number of components.
    pub fn components(&self) -> usize {
        self.component_flux.len()
    }

    /// Mean illuminance of target `i`, both sides, every light at its authored output,
    /// in lux, with its standard error.
    pub fn estimate(&self, i: usize) -> Estimate {
        self.estimate_of(i, Side::Both, &vec![1.0; self.components()])
    }

    /// Observer `o`'s glare sum Σ L²ω/p² at component weights `w` (the dimming levels):
    /// each component's sum times its level squared, since a luminaire's luminance
    /// scales with its level.
    pub fn glare_sum(&self, o: usize, w: &[f64]) -> f64 {
        self.glare[o].iter().zip(w).map(|(s, w)| s * w * w).sum()
    }

    /// Mean illuminance of target `i` on `side`, each component `k` at `w[k]` times its
    /// authored output (a dimming level), in lux, with its standard error from the same
    /// groups.
    ///
    /// A target nothing reached has a sample variance of zero, which would claim the
    /// mean 0 exact and let a comparison rule the surface out on no evidence. Its
    /// standard error is then taken as the illuminance one arrival would have given,
    /// Φ/(A·N) (times the largest weight): the binomial σ with the hit probability 1/N,
    /// the smallest that is not ruled out.
    pub fn estimate_of(&self, i: usize, side: Side, w: &[f64]) -> Estimate {
        let weights = side_weights(side, w);
        let inv = 1.0 / self.areas[i];
        let groups = self.photons.div_ceil(GROUP);
        let sums = &self.channels[i];
        let mut e = sums.estimate(&weights, groups, self.photons, inv);
        if sums.total(&weights) <= 0.0 && self.photons > 0 {
            let w_max = w.iter().copied().fold(0.0, f64::max);
            e.std_error = w_max * self.flux * inv / self.photons as f64;
        }
        e
    }

    /// The mean illuminance of target `i` on `side` at weights `w` that each group of
    /// photons alone estimates, lx, in group order: their mean is
    /// [`Measurement::estimate_of`]'s, and they are the independent samples behind its
    /// standard error. Group g of every configuration is traced from the same seeds, so
    /// two configurations are compared by the differences of their groups (common
    /// random numbers). Empty unless the request kept the groups
    /// ([`Request::keep_groups`]).
    pub fn group_means(&self, i: usize, side: Side, w: &[f64]) -> Vec<f64> {
        let weights = side_weights(side, w);
        let c = weights.len();
        let per = self.areas.len() * c;
        let scale = 1.0 / (self.areas[i] * GROUP as f64);
        self.groups
            .chunks_exact(per)
            .map(|g| {
                let x = &g[i * c..(i + 1) * c];
                x.iter().zip(&weights).map(|(x, w)| x * w).sum::<f64>() * scale
            })
            .collect()
    }

    /// The luminous flux of the lights at weights `w`, lm: exact, not estimated.
    pub fn power(&self, w: &[f64]) -> f64 {
        self.component_flux.iter().zip(w).map(|(f, w)| f * w).sum()
    }
}

/// Traces `settings.photons` photons, rounded up to whole stratified groups
/// ([`photons_traced`]; [`Measurement::photons`] says how many), from the lights of
/// `scene` and tallies what they bring to the surfaces `targets`, every light together
/// ([`measure_with`] keeps lights, sides and grid cells apart). `progress` is called
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
    let components = Components::one(scene);
    let request = Request::means(targets, &components, estimator);
    measure_with(scene, accel, &request, settings, progress)
}

/// [`measure`] with the lights kept apart by component, each target's front and back
/// apart, and the grids of `request` read cell by cell; shared by the processes of this
/// process's [`cluster`] (alone unless it joined one).
///
/// # Panics
/// As [`measure`]; and if a grid's target is not one of the request's surfaces.
pub fn measure_with(
    scene: &Scene,
    accel: &Accel,
    request: &Request,
    settings: &TraceSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Measurement {
    measure_across(scene, accel, request, settings, progress, cluster())
}

/// [`measure_with`] shared by the processes of `cluster` ([`trace_shared`](crate::trace_shared)): the same
/// measurement, bit for bit, on every process, whatever K.
///
/// # Panics
/// As [`measure_with`].
pub fn measure_across(
    scene: &Scene,
    accel: &Accel,
    request: &Request,
    settings: &TraceSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    cluster: &dyn Cluster,
) -> Measurement {
    trace_into(scene, accel, request, settings, progress, None, cluster)
}

/// [`measure_with`] of `settings.photons` photons continued from `previous`, a
/// measurement of fewer photons with the same scene, request and seed: only the photons
/// after it are traced, so a candidate the search refines from n to N photons costs
/// N − n more, not N again (the thesis re-traced). Photon i draws from the
/// stream (seed, i) and the chunks are folded in index order, so the result is the
/// same, bit for bit, as tracing `settings.photons` at once (its `rays` aside, which
/// count what this call cast too). `previous` continues from its last photon when it
/// ends on a chunk boundary ([`CHUNK`](crate::CHUNK)), else from the boundary before, which a measurement
/// keeping its groups remembers (the part of a chunk after it is traced again); any
/// other `previous`, or one of at least as many photons, is traced from the start or
/// returned as it is. The processes of `cluster` share the trace as
/// [`measure_across`]'s do.
///
/// # Panics
/// As [`measure_with`].
pub fn measure_more(
    scene: &Scene,
    accel: &Accel,
    request: &Request,
    settings: &TraceSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    previous: &Measurement,
    cluster: &dyn Cluster,
) -> Measurement {
    let photons = photons_traced(settings.photons).expect("a photon count that fits in u64");
    if photons == previous.photons {
        return previous.clone();
    }
    match previous.boundary() {
        Some(state) if photons > previous.photons => {
            let mut state = state.clone();
            // The boundary's groups are a prefix of the previous measurement's.
            let kept = (state.photons / GROUP) as usize * previous.group_width();
            state.groups = previous.groups[..previous.groups.len().min(kept)].to_vec();
            state.rays = previous.rays;
            trace_into(
                scene,
                accel,
                request,
                settings,
                progress,
                Some(state),
                cluster,
            )
        }
        _ => measure_across(scene, accel, request, settings, progress, cluster),
    }
}

impl Measurement {
    /// A measurement of no photons yet of `request` on `scene`: its targets' areas,
    /// zero sums, and each grid with `direct`'s computed direct light (empty for a grid
    /// of cell means).
    fn empty(
        scene: &Scene,
        request: &Request,
        emitters: &Emitters,
        direct: impl Fn(&GridRequest) -> Vec<f64>,
    ) -> Measurement {
        let targets = request.surfaces;
        let k = request.components.count();
        let flux = emitters.total_flux();
        Measurement {
            photons: 0,
            rays: 0,
            connection_rays: 0,
            areas: targets
                .iter()
                .map(|&s| scene.surface_area(s) as f64)
                .collect(),
            hits: vec![0; targets.len()],
            channels: vec![ChannelSums::new(2 * k); targets.len()],
            groups: Vec::new(),
            grids: request
                .grids
                .iter()
                .map(|g| {
                    let mut m = GridMeasurement::new(
                        g.grid.clone(),
                        g.side,
                        CellTallies::new(g.grid.cells(), k).sums,
                    );
                    m.flux = flux;
                    m.direct = direct(g);
                    m
                })
                .collect(),
            component_flux: request.components.flux(emitters),
            escaped: 0.0,
            flux,
            glare: Vec::new(),
            boundary: None,
        }
    }
}

/// Traces the photons of `settings` after those `from` holds (all of them when `None`)
/// and adds them to it.
fn trace_into(
    scene: &Scene,
    accel: &Accel,
    request: &Request,
    settings: &TraceSettings,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    from: Option<Measurement>,
    cluster: &dyn Cluster,
) -> Measurement {
    let settings = &TraceSettings {
        photons: photons_traced(settings.photons).expect("a photon count that fits in u64"),
        ..*settings
    };
    let targets = request.surfaces;
    let emitters = Emitters::new(scene);
    let k = request.components.count();
    let mut grids_of = vec![Vec::new(); targets.len()];
    for (g, grid) in request.grids.iter().enumerate() {
        grids_of[grid.target].push(g);
    }
    let plan = Plan {
        map: TargetMap::new(scene, targets),
        grids_of,
        grids: &request.grids,
        component_of: request.components.of_sources(&emitters),
        components: k,
    };
    let shapes = Targets::new(scene, targets);
    let connect = request.estimator == Estimator::Connected;
    let mut result = from.unwrap_or_else(|| {
        let mut m = Measurement::empty(scene, request, &emitters, |g| match g.values {
            GridValues::Points => {
                direct_on_grid(&emitters, accel, &g.grid, g.side, &plan.component_of, k)
            }
            GridValues::CellMeans | GridValues::Indirect => Vec::new(),
        });
        m.glare = request
            .observers
            .iter()
            .map(|o| glare_sums(scene, accel, o, request.components))
            .collect();
        m
    });
    debug_assert!(result.photons.is_multiple_of(CHUNK));
    let first_chunk = result.photons / CHUNK;
    result.photons = settings.photons;
    for g in &mut result.grids {
        g.photons = settings.photons;
    }
    // A measurement ending inside a chunk remembers its sums at the chunk's start, where
    // a continuation picks up ([`measure_more`]); only the search, which keeps groups,
    // continues measurements.
    let partial = (request.keep_groups && !settings.photons.is_multiple_of(CHUNK))
        .then_some(settings.photons / CHUNK);
    let mut chunk = first_chunk;
    let mut boundary = None;
    let trace = PhotonTrace {
        scene,
        accel,
        emitters: &emitters,
        settings,
    };
    let rays = trace_shared_from(
        first_chunk,
        trace,
        || ChunkTally {
            plan: &plan,
            connect: connect.then_some((&shapes, accel)),
            surfaces: SurfaceTallies::new(targets.len(), k, request.keep_groups),
            cells: request
                .grids
                .iter()
                .map(|g| CellTallies::new(g.grid.cells(), k))
                .collect(),
            escaped: 0.0,
            connection_rays: 0,
            departed: Vec3::NAN,
            solid: vec![None; targets.len()],
        },
        |part| {
            if partial == Some(chunk) {
                let groups = std::mem::take(&mut result.groups);
                let mut state = result.clone();
                state.photons = chunk * CHUNK;
                state.rays = 0;
                for g in &mut state.grids {
                    g.photons = state.photons;
                }
                boundary = Some(Box::new(state));
                result.groups = groups;
            }
            chunk += 1;
            part.surfaces.add_to(&mut result.channels, &mut result.hits);
            result.groups.extend_from_slice(&part.surfaces.groups);
            for (total, cells) in result.grids.iter_mut().zip(&part.cells) {
                total.merge(&cells.sums);
            }
            result.escaped += part.escaped;
            result.connection_rays += part.connection_rays;
        },
        progress,
        cluster,
    );
    result.rays += rays;
    result.boundary = boundary;
    result
}
