//! Traces shared by the processes of a cluster job: every process runs the
//! same program on the same inputs, each traces its share of every trace's chunks, and
//! all of them fold every chunk's tallies in chunk order, so each holds the totals a
//! single process would have summed, bit for bit, and takes the same decisions.
//!
//! Why this gives the same bits: a chunk's tallies depend on its photons alone (photon i
//! draws from the stream (seed, i), [`crate::Sampler`]), and the fold sees the chunks in
//! the order [`crate::trace_chunks`] gives them, whichever process traced them. Only the
//! order of the additions decides the bits of a floating-point sum, so the split
//! changes nothing.
//!
//! This crate knows nothing of how processes talk: a [`Cluster`] gathers words from
//! every process (MPI's `MPI_Allgatherv`, in the `invlight-cluster` crate), and
//! a visitor that can be shipped is [`Pack`]ed into words and unpacked on every process.

use crate::chunks::{BLOCK, BLOCK_MEMORY, CHUNK, PhotonTrace, trace_chunk, trace_chunks_from};
use crate::path::PathVisitor;
use rayon::prelude::*;
use std::sync::OnceLock;

/// The processes of a job, each told apart by its rank.
pub trait Cluster: Send + Sync {
    /// This process's rank, from 0 (the one that writes files and prints).
    fn rank(&self) -> usize;
    /// The number of processes, K.
    fn ranks(&self) -> usize;
    /// Every process's `mine`, concatenated in rank order, on every process (an
    /// all-gather of buffers of any lengths). Every process calls it the same number of
    /// times, in the same order.
    fn all_gather(&self, mine: &[u64]) -> Vec<u64>;
}

/// A process on its own: rank 0 of 1.
#[derive(Debug, Clone, Copy, Default)]
pub struct Alone;

impl Cluster for Alone {
    fn rank(&self) -> usize {
        0
    }
    fn ranks(&self) -> usize {
        1
    }
    fn all_gather(&self, mine: &[u64]) -> Vec<u64> {
        mine.to_vec()
    }
}

/// The cluster this process belongs to, as [`join_cluster`] set it.
static PROCESS: OnceLock<Box<dyn Cluster>> = OnceLock::new();

/// Makes every later [`crate::measure_with`] of this process a trace shared with the
/// other processes of `cluster`. Once per process, before the first trace, as the
/// process joins its job: a job is a property of the process (MPI's `MPI_COMM_WORLD`),
/// and threading it through every caller would change nothing but their signatures.
/// Gives `cluster` back if the process had joined one already.
pub fn join_cluster(cluster: Box<dyn Cluster>) -> Result<(), Box<dyn Cluster>> {
    PROCESS.set(cluster)
}

/// The cluster this process traces with: [`Alone`] unless [`join_cluster`] said another.
pub fn cluster() -> &'static dyn Cluster {
    match PROCESS.get() {
        Some(c) => c.as_ref(),
        None => &Alone,
    }
}

/// Whether this process writes the files and prints: rank 0 of its cluster.
pub fn leads() -> bool {
    cluster().rank() == 0
}

/// A visitor whose tallies travel as words: what the fold reads of a chunk, packed by
/// the process that traced it and unpacked into a fresh visitor by every process.
pub trait Pack {
    /// Appends the tallies to `out`.
    fn pack(&self, out: &mut Vec<u64>);
    /// Reads back what [`Pack::pack`] wrote into a visitor fresh from the same request.
    fn unpack(&mut self, words: &mut dyn Iterator<Item = u64>);
}

/// Squeezes runs of zero words, which most of a chunk's tallies are (cells and targets
/// its photons never reached): pairs of a zero run's length and a literal run's length,
/// each followed by the literals.
fn squeeze(words: &[u64]) -> Vec<u64> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < words.len() {
        let zeros = words[i..].iter().take_while(|&&w| w == 0).count();
        let start = i + zeros;
        let literals = words[start..].iter().take_while(|&&w| w != 0).count();
        out.extend([zeros as u64, literals as u64]);
        out.extend_from_slice(&words[start..start + literals]);
        i = start + literals;
    }
    out
}

/// The words [`squeeze`] squeezed.
fn unsqueeze(squeezed: &[u64]) -> Vec<u64> {
    let mut out = Vec::new();
    let mut i = 0;
    while i + 1 < squeezed.len() {
        let (zeros, literals) = (squeezed[i] as usize, squeezed[i + 1] as usize);
        out.resize(out.len() + zeros, 0);
        out.extend_from_slice(&squeezed[i + 2..i + 2 + literals]);
        i += 2 + literals;
    }
    out
}

/// [`trace_chunks`](crate::trace_chunks) shared by the processes of `cluster`: each block's chunks are split
/// into K runs of consecutive chunks, run r traced by rank r on its threads, packed,
/// gathered by every rank and folded in chunk order. A block holds K times the chunks a
/// process alone would trace at a time, so each rank's memory is the same as alone and
/// a trace of up to 256·K chunks (10⁶·K photons) takes one exchange. `progress` hears
/// of every block once gathered. On one process it is [`trace_chunks`](crate::trace_chunks) itself.
pub fn trace_shared<V: PathVisitor + Pack + Send>(
    trace: PhotonTrace<'_>,
    new_visitor: impl Fn() -> V + Sync,
    fold: impl FnMut(V),
    progress: Option<&(dyn Fn(u64) + Sync)>,
    cluster: &dyn Cluster,
) -> u64 {
    trace_shared_from(0, trace, new_visitor, fold, progress, cluster)
}

/// [`trace_shared`] from chunk `first_chunk` on, as
/// [`trace_chunks_from`](crate::chunks::trace_chunks_from) continues a trace: the chunks
/// before it are left out, the others split and folded as a whole trace would.
pub(crate) fn trace_shared_from<V: PathVisitor + Pack + Send>(
    first_chunk: u64,
    trace: PhotonTrace<'_>,
    new_visitor: impl Fn() -> V + Sync,
    mut fold: impl FnMut(V),
    progress: Option<&(dyn Fn(u64) + Sync)>,
    cluster: &dyn Cluster,
) -> u64 {
    let (rank, ranks) = (cluster.rank() as u64, cluster.ranks() as u64);
    if ranks <= 1 {
        return trace_chunks_from(first_chunk, trace, new_visitor, fold, progress);
    }
    if trace.emitters.is_empty() {
        return 0;
    }
    let chunks = trace.settings.photons.div_ceil(CHUNK);
    let bytes = new_visitor().bytes().max(1);
    // The same on every rank: it depends on the request and K alone, not on threads.
    let block = ((BLOCK_MEMORY / bytes) as u64).clamp(1, BLOCK) * ranks;
    let mut rays = 0;
    let mut block_start = first_chunk;
    while block_start < chunks {
        let block_end = (block_start + block).min(chunks);
        let n = block_end - block_start;
        let mine = block_start + n * rank / ranks..block_start + n * (rank + 1) / ranks;
        let parts: Vec<(V, u64)> = mine
            .into_par_iter()
            .map(|chunk| {
                let mut visitor = new_visitor();
                let (chunk_rays, _) = trace_chunk(trace, chunk, &mut visitor);
                (visitor, chunk_rays)
            })
            .collect();
        let mut words = Vec::new();
        for (visitor, chunk_rays) in &parts {
            words.push(*chunk_rays);
            visitor.pack(&mut words);
        }
        drop(parts);
        let all = unsqueeze(&cluster.all_gather(&squeeze(&words)));
        let mut all = all.into_iter();
        for _ in block_start..block_end {
            rays += all
                .next()
                .expect("a packed chunk for every chunk of the block");
            let mut visitor = new_visitor();
            visitor.unpack(&mut all);
            fold(visitor);
        }
        if let Some(report) = progress {
            report((block_end * CHUNK).min(trace.settings.photons) - first_chunk * CHUNK);
        }
        block_start = block_end;
    }
    rays
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squeezed_words_come_back_whole() {
        let cases: [&[u64]; 6] = [
            &[],
            &[0],
            &[0, 0, 0],
            &[7],
            &[0, 0, 5, 6, 0, 1, 0, 0],
            &[1, 2, 3, 0, 0, 0, 0, 0, 0, 0, 0, 9],
        ];
        for words in cases {
            assert_eq!(unsqueeze(&squeeze(words)), words, "{words:?}");
        }
        // Ten zeros and a value take three words instead of eleven.
        let mut sparse = vec![0; 10];
        sparse.push(3);
        assert_eq!(squeeze(&sparse), [10, 1, 3]);
    }
}
