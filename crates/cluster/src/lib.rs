//! invlight's traces shared by the processes of a cluster job (docs/cluster.md): every
//! process runs the same search on the same inputs, traces its share of each trace's
//! chunks, and folds every chunk in chunk order ([`invlight_photon::trace_shared`]), so
//! all of them hold the totals one process would have summed, bit for bit, and take the
//! same decisions. Rank 0 alone writes files and prints.
//!
//! - [`Local`]: K ranks as threads of one process, exchanging through memory, to check
//!   the split against one process without MPI (tests) and to count what an exchange
//!   moves.
//! - `Job` (feature `mpi`): the MPI job this process was started in (`mpirun`,
//!   `srun`), exchanging by `MPI_Allgatherv`; followers quiet, a failure on any rank
//!   named and ending the job (`MPI_Abort`).
//!
//! ```
//! use invlight_cluster::Local;
//! use invlight_photon::Cluster;
//!
//! let ranks = Local::ranks(3);
//! let gathered: Vec<Vec<u64>> = std::thread::scope(|s| {
//!     let handles: Vec<_> = ranks
//!         .iter()
//!         .map(|r| s.spawn(move || r.all_gather(&vec![r.rank() as u64; r.rank() + 1])))
//!         .collect();
//!     handles.into_iter().map(|h| h.join().unwrap()).collect()
//! });
//! // Every rank holds every rank's words, in rank order.
//! for g in &gathered {
//!     assert_eq!(g, &[0, 1, 1, 2, 2, 2]);
//! }
//! ```
#![deny(missing_docs)]

mod local;
#[cfg(feature = "mpi")]
mod mpi;

pub use local::Local;
#[cfg(feature = "mpi")]
pub use mpi::Job;
