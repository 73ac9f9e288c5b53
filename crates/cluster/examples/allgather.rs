//! Times the exchange of a shared trace: `all_gather` of W words per rank, repeated,
//! for the cluster model of BENCHMARKS.md (latency and bandwidth of this MPI).
//!
//!     cargo build --release -p invlight-cluster --features mpi --example allgather
//!     mpirun -np 2 target/release/examples/allgather
//!
//! Prints, on rank 0, one line per size: words per rank, microseconds per exchange.

use invlight_cluster::Job;
use invlight_photon::{cluster, leads};
use std::time::Instant;

fn main() {
    let _job = Job::join();
    let world = cluster();
    for words in [1usize, 16, 256, 4096, 65_536, 1 << 20] {
        let mine = vec![world.rank() as u64 + 1; words];
        let reps = (20_000_000 / (words * world.ranks()).max(1000)).clamp(5, 2000);
        world.all_gather(&mine);
        let start = Instant::now();
        for _ in 0..reps {
            std::hint::black_box(world.all_gather(&mine));
        }
        let us = start.elapsed().as_secs_f64() * 1e6 / reps as f64;
        if leads() {
            println!(
                "{words:>8} words/rank  {:>10} B gathered  {us:>10.1} µs",
                8 * words * world.ranks()
            );
        }
    }
}
