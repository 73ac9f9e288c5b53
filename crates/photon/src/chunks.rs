//! The parallel driver every photon trace runs on: photons in chunks of [`CHUNK`]
//! consecutive indices, each chunk followed by a visitor of its own, and the chunks'
//! visitors folded in index order, [`BLOCK`] chunks at a time.
//!
//! Why results do not depend on the number of threads: photon i draws from the stream
//! (seed, i) whatever thread traces it ([`Sampler`]); a chunk's photons are traced in index
//! order by one visitor; and the chunks' visitors are handed to the fold in chunk order.
//! Every sum is therefore taken in an order fixed by the photon count alone, and the same
//! seed gives the same bits on one thread or many. Folding a block at a time keeps the
//! memory of pending chunks constant however many photons are traced.

use crate::emit::Emitters;
use crate::estimator::GROUP;
use crate::path::{PathVisitor, trace_photon};
use crate::sampler::{GroupKeys, Sampler};
use invlight_scene::Scene;
use invlight_trace::Accel;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// How to trace photons.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceSettings {
    /// Photons to emit, N. Measurements ([`crate::measure`], illuminance maps) round it
    /// up to whole groups ([`crate::photons_traced`]).
    pub photons: u64,
    /// Seed of the random streams; photon i uses the stream (seed, i).
    pub seed: u64,
    /// Surface interactions followed after the first hit from the light. Russian
    /// roulette ends paths on its own; this is a safety cap (the thesis used 4).
    pub max_bounces: u32,
    /// Where the Russian roulette starts, as a share of the power a photon leaves its
    /// light with: a photon is reflected without roulette while its expected reflected
    /// power stays above this share, and at or below it survives with the probability
    /// that keeps its power there (`path::Roulette`). 1 is the classic roulette (thesis
    /// Algorithm 2.2), where every photon keeps its power; lower values trace more of each
    /// photon's reflections, which pays where reflected light carries the variance
    /// ([`crate::tune_roulette`]). Any positive value gives the same mean; one that is
    /// not a positive number plays the classic roulette.
    pub roulette: f32,
}

impl Default for TraceSettings {
    fn default() -> Self {
        TraceSettings {
            photons: 1_000_000,
            seed: 1,
            max_bounces: DEFAULT_MAX_BOUNCES,
            roulette: 1.0,
        }
    }
}

/// The default bounce cap: high enough that, with the reflectances of real rooms, no
/// measurable energy is cut off (0.9^1000 ≈ 2·10⁻⁴⁶), low enough to stop a photon caught
/// between perfect mirrors.
pub const DEFAULT_MAX_BOUNCES: u32 = 1000;

/// Photons per chunk: large enough that a chunk's bookkeeping is negligible, small
/// enough to balance two to a hundred threads; whole stratified groups.
pub const CHUNK: u64 = 4096;
const _: () = assert!(CHUNK.is_multiple_of(GROUP));
/// Chunks reduced at a time: bounds memory, keeps all threads busy.
pub const BLOCK: u64 = 256;
/// The most memory pending visitors of a block may hold: a block of large visitors
/// (fine illuminance grids) has fewer chunks, though never fewer than the threads.
pub const BLOCK_MEMORY: usize = 256 << 20;

/// What a trace traces: the photons `settings` asks for, leaving `emitters` into
/// `scene`, whose rays `accel` casts. Every driver of a trace ([`trace_chunks`],
/// [`crate::trace_shared`]) takes these together, as the photons of a chunk need them all.
#[derive(Clone, Copy)]
pub struct PhotonTrace<'a> {
    /// The scene the photons fly through.
    pub scene: &'a Scene,
    /// Its ray accelerator.
    pub accel: &'a Accel,
    /// The lights the photons leave.
    pub emitters: &'a Emitters,
    /// How many photons, with which seed and bounce cap.
    pub settings: &'a TraceSettings,
}

/// Traces `trace.settings.photons` photons from `trace.emitters`: each chunk gets a
/// visitor from `new_visitor`, which sees its photons' arrivals and, after each
/// stratified group of photons, [`PathVisitor::end_group`]; `fold` then receives the
/// chunks' visitors in chunk order. `progress` is called from worker threads with the
/// photons traced so far. Returns the rays cast (none when the scene has no light).
pub fn trace_chunks<V: PathVisitor + Send>(
    trace: PhotonTrace<'_>,
    new_visitor: impl Fn() -> V + Sync,
    fold: impl FnMut(V),
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> u64 {
    trace_chunks_from(0, trace, new_visitor, fold, progress)
}

/// [`trace_chunks`] from chunk `first_chunk` on: the chunks before it are left out, the
/// others traced and folded exactly as a whole trace would, so a trace continued from a
/// chunk boundary adds the same terms in the same order (a candidate refined from n to
/// N photons traces the N − n more).
pub(crate) fn trace_chunks_from<V: PathVisitor + Send>(
    first_chunk: u64,
    trace: PhotonTrace<'_>,
    new_visitor: impl Fn() -> V + Sync,
    mut fold: impl FnMut(V),
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> u64 {
    if trace.emitters.is_empty() {
        return 0;
    }
    let chunks = trace.settings.photons.div_ceil(CHUNK);
    let bytes = new_visitor().bytes().max(1);
    // At least a chunk per thread, at most BLOCK unless the threads outnumber it
    // (`clamp` would panic with more than BLOCK threads).
    let block = ((BLOCK_MEMORY / bytes) as u64)
        .min(BLOCK)
        .max(rayon::current_num_threads() as u64);
    let done = AtomicU64::new(0);
    let mut rays = 0;
    let mut block_start = first_chunk;
    while block_start < chunks {
        let block_end = (block_start + block).min(chunks);
        let parts: Vec<(V, u64)> = (block_start..block_end)
            .into_par_iter()
            .map(|chunk| {
                let mut visitor = new_visitor();
                let (chunk_rays, photons) = trace_chunk(trace, chunk, &mut visitor);
                if let Some(report) = progress {
                    report(done.fetch_add(photons, Ordering::Relaxed) + photons);
                }
                (visitor, chunk_rays)
            })
            .collect();
        for (visitor, chunk_rays) in parts {
            fold(visitor);
            rays += chunk_rays;
        }
        block_start = block_end;
    }
    rays
}

/// Traces chunk `chunk` of `trace` into `visitor`: its photons in index order,
/// [`PathVisitor::end_group`] after each group. Returns the rays cast and the photons
/// traced.
pub(crate) fn trace_chunk<V: PathVisitor>(
    trace: PhotonTrace<'_>,
    chunk: u64,
    visitor: &mut V,
) -> (u64, u64) {
    let PhotonTrace {
        scene,
        accel,
        emitters,
        settings,
    } = trace;
    let first = chunk * CHUNK;
    let last = (first + CHUNK).min(settings.photons);
    let mut rays = 0;
    // A chunk starts a group: CHUNK is a multiple of GROUP.
    let mut keys = GroupKeys::new(settings.seed, first / GROUP);
    for i in first..last {
        if i % GROUP == 0 && i != first {
            keys = GroupKeys::new(settings.seed, i / GROUP);
        }
        let mut sampler = Sampler::new(&keys, settings.seed, i);
        rays += trace_photon(
            scene,
            accel,
            emitters,
            &mut sampler,
            settings.max_bounces,
            settings.roulette,
            visitor,
        );
        if (i + 1).is_multiple_of(GROUP) || i + 1 == last {
            visitor.end_group();
        }
    }
    (rays, last - first)
}
