//! The MPI job a process was started in: its traces shared by `MPI_Allgatherv`, its
//! followers quiet, and a failure on any rank ending the job with the rank's name.

use invlight_photon::{Cluster, join_cluster};
use mpi::Threading;
use mpi::datatype::PartitionMut;
use mpi::environment::Universe;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::io::Write;
use std::os::fd::{FromRawFd, RawFd};

/// `MPI_COMM_WORLD`, for the traces of this process.
struct World(SimpleCommunicator);

// SAFETY: MPI is initialised with MPI_THREAD_SERIALIZED: any thread may call it, one at
// a time. A process traces one measurement at a time (the search evaluates candidates
// in turn), and only the thread folding a trace calls `all_gather`.
unsafe impl Send for World {}
// SAFETY: as for Send: calls are never concurrent.
unsafe impl Sync for World {}

impl Cluster for World {
    fn rank(&self) -> usize {
        self.0.rank() as usize
    }

    fn ranks(&self) -> usize {
        self.0.size() as usize
    }

    fn all_gather(&self, mine: &[u64]) -> Vec<u64> {
        let ranks = self.ranks();
        let count = i32::try_from(mine.len()).expect("a block's tallies under 2³¹ words");
        let mut counts = vec![0i32; ranks];
        self.0.all_gather_into(&count, &mut counts[..]);
        let displs: Vec<i32> = counts
            .iter()
            .scan(0i32, |at, &c| {
                let d = *at;
                *at += c;
                Some(d)
            })
            .collect();
        let total = counts.iter().map(|&c| c as usize).sum();
        let mut all = vec![0u64; total];
        let mut partition = PartitionMut::new(&mut all[..], counts, displs);
        self.0.all_gather_varcount_into(mine, &mut partition);
        all
    }
}

/// This process's place in its MPI job: held by `main` for the whole run (dropping it
/// finalises MPI).
pub struct Job {
    _universe: Universe,
    rank: usize,
    ranks: usize,
    /// The terminal's stderr of a follower, whose own streams are quieted.
    stderr: Option<RawFd>,
}

impl Job {
    /// Joins the MPI job this process was started in (`mpirun`, `srun`; a process
    /// started alone is rank 0 of 1): every later measurement is shared with the other
    /// ranks ([`invlight_photon::join_cluster`]). On a follower (rank > 0) standard
    /// output and error are sent to /dev/null, since every rank runs the same program
    /// and rank 0 prints for all; [`Job::fail`] and a panic still reach the terminal,
    /// named by rank.
    ///
    /// When MPI cannot start, or cannot give the threading every rank needs, the
    /// process ends with the reason and exit status 1, as MPI ends a process whose
    /// `MPI_Init` fails: nothing was traced yet.
    pub fn join() -> Job {
        let started = mpi::initialize_with_threading(Threading::Serialized);
        let Some((universe, threading)) = started else {
            eprintln!("error: MPI was initialised already");
            std::process::exit(1);
        };
        if threading < Threading::Serialized {
            eprintln!(
                "error: this MPI library gives the threading {threading:?}, not Serialized, which the threads of a rank need"
            );
            std::process::exit(1);
        }
        let world = universe.world();
        let (rank, ranks) = (world.rank() as usize, world.size() as usize);
        if join_cluster(Box::new(World(world))).is_err() {
            unreachable!("MPI initialises once per process, and the cluster with it");
        }
        let stderr = (rank > 0).then(quiet);
        let job = Job {
            _universe: universe,
            rank,
            ranks,
            stderr,
        };
        let name = job.name();
        std::panic::set_hook(Box::new(move |info| {
            let _ = writeln!(terminal(stderr), "invlight: {name}: {info}");
            SimpleCommunicator::world().abort(101);
        }));
        job
    }

    /// `rank R of K`, as messages name this process.
    pub fn name(&self) -> String {
        format!("rank {} of {}", self.rank, self.ranks)
    }

    /// Ends the job because this rank failed: prints `message` named by the rank (to
    /// the terminal, even on a quiet follower) and aborts every rank with `code`
    /// (`MPI_Abort`), so that no rank waits forever for this one's tallies. A job of one
    /// process prints `message` alone and returns, for `main` to exit as usual.
    pub fn fail(&self, message: &str, code: i32) {
        if self.ranks == 1 {
            eprintln!("{message}");
            return;
        }
        let _ = writeln!(
            terminal(self.stderr),
            "invlight: {}: {message}",
            self.name()
        );
        SimpleCommunicator::world().abort(code);
    }
}

/// Sends standard output and error to /dev/null; returns a copy of the old stderr.
fn quiet() -> RawFd {
    // SAFETY: plain POSIX calls on descriptors this process owns; a failure leaves the
    // streams as they were (a noisy follower, not a wrong one).
    unsafe {
        let saved = libc::dup(2);
        let null = libc::open(c"/dev/null".as_ptr(), libc::O_WRONLY);
        if null >= 0 {
            libc::dup2(null, 1);
            libc::dup2(null, 2);
            libc::close(null);
        }
        if saved >= 0 { saved } else { 2 }
    }
}

/// The terminal's stderr: a follower's saved copy, or this process's own.
fn terminal(saved: Option<RawFd>) -> std::mem::ManuallyDrop<std::fs::File> {
    // SAFETY: the descriptor stays open for the life of the process; ManuallyDrop never
    // closes it.
    std::mem::ManuallyDrop::new(unsafe { std::fs::File::from_raw_fd(saved.unwrap_or(2)) })
}
