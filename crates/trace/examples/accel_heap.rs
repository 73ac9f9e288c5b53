//! The heap an [`Accel`] keeps once built, as `invlight measure` builds it
//! (`Accel::with_movable(&scene, &[])`), counted by a global allocator that tallies the
//! bytes live, beside [`AccelStats::bytes`](invlight_trace::AccelStats) (what traversal
//! touches) and the resident memory. The resident figures alone cannot show what the
//! structure keeps: its build's temporaries are freed before it is complete, and what it
//! allocates afterwards reuses their pages.
//!
//! ```text
//! unzip -o /work/shared/scenes/sponza/sponza.zip -d /tmp/sponza
//! cargo run --release -p invlight-trace --example accel_heap -- /tmp/sponza/sponza.obj
//! ```

use invlight_scene::{LoadOptions, load};
use invlight_trace::Accel;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// The system allocator, counting the bytes live.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is passed on to the system allocator unchanged.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LIVE.fetch_add(layout.size(), Relaxed);
        // SAFETY: the caller's contract is the system allocator's.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Relaxed);
        // SAFETY: `ptr` came from `alloc` above with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// A line of `/proc/self/status` (Linux), kB; 0 elsewhere.
fn status_kb(key: &str) -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let line = s.lines().find(|l| l.starts_with(key))?;
            line.split_whitespace().nth(1)?.parse().ok()
        })
        .unwrap_or(0)
}

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: accel_heap SCENE");
        std::process::exit(2);
    };
    let scene = load(path.as_ref(), &LoadOptions::default()).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1);
    });
    let (live, resident) = (LIVE.load(Relaxed), status_kb("VmRSS:"));
    let accel = Accel::with_movable(&scene, &[]);
    let kept = LIVE.load(Relaxed) - live;
    let s = accel.stats();
    println!(
        "{path}: {} triangles, {} bottom-level nodes; AccelStats::bytes {}; heap kept {} bytes; \
         resident {} → {} kB (peak {} kB)",
        s.triangles,
        s.blas_nodes,
        s.bytes,
        kept,
        resident,
        status_kb("VmRSS:"),
        status_kb("VmHWM:")
    );
    drop(accel);
}
