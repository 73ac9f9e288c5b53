//! Ranks as threads of one process: the exchange of an MPI job without MPI.

use invlight_photon::Cluster;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Barrier, Mutex};

/// One of K ranks that are threads of this process, each calling
/// [`Cluster::all_gather`] from its own thread, as processes of an MPI job do.
#[derive(Debug, Clone)]
pub struct Local {
    rank: usize,
    shared: Arc<Exchange>,
}

#[derive(Debug)]
struct Exchange {
    ranks: usize,
    slots: Mutex<Vec<Vec<u64>>>,
    barrier: Barrier,
    words: AtomicU64,
    exchanges: AtomicU64,
}

impl Local {
    /// K ranks sharing one exchange, rank 0 first.
    ///
    /// # Panics
    /// If `k` is 0.
    pub fn ranks(k: usize) -> Vec<Local> {
        assert!(k > 0, "a job has at least one rank");
        let shared = Arc::new(Exchange {
            ranks: k,
            slots: Mutex::new(vec![Vec::new(); k]),
            barrier: Barrier::new(k),
            words: AtomicU64::new(0),
            exchanges: AtomicU64::new(0),
        });
        (0..k)
            .map(|rank| Local {
                rank,
                shared: shared.clone(),
            })
            .collect()
    }

    /// Words every rank has sent so far, summed over the ranks (each gather sends a
    /// rank's words to K − 1 others: multiply by K − 1 for the words received).
    pub fn words_sent(&self) -> u64 {
        self.shared.words.load(Ordering::Relaxed)
    }

    /// All-gathers so far (each rank takes part in every one).
    pub fn exchanges(&self) -> u64 {
        self.shared.exchanges.load(Ordering::Relaxed)
    }
}

impl Cluster for Local {
    fn rank(&self) -> usize {
        self.rank
    }

    fn ranks(&self) -> usize {
        self.shared.ranks
    }

    fn all_gather(&self, mine: &[u64]) -> Vec<u64> {
        let shared = &self.shared;
        shared.words.fetch_add(mine.len() as u64, Ordering::Relaxed);
        if self.rank == 0 {
            shared.exchanges.fetch_add(1, Ordering::Relaxed);
        }
        shared.slots.lock().expect("no rank panicked")[self.rank] = mine.to_vec();
        // Everyone's words are in before anyone reads, and read before anyone writes
        // the next exchange's.
        shared.barrier.wait();
        let all = shared.slots.lock().expect("no rank panicked").concat();
        shared.barrier.wait();
        all
    }
}
