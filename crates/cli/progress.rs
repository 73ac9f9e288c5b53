//! Progress on stderr: a bar drawn only when stderr is a terminal, so that logs and
//! pipes stay clean, and — terminal or not — one warning when the work under way will
//! take more than an hour, from its pace over the first seconds (a photon count typed
//! with three zeros too many should not run for days without a word).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Work that takes longer than this gets a warning.
const LONG: Duration = Duration::from_secs(3600);
/// The pace is judged after this much of the work.
const SAMPLE: Duration = Duration::from_secs(3);

/// A bar over `total` units of work.
pub struct Progress {
    bar: ProgressBar,
    total: u64,
    start: Instant,
    warned: AtomicBool,
    what: String,
}

impl Progress {
    /// A bar counting `total` `unit` (e.g. "photons") for `what` (e.g. "the trace").
    pub fn new(total: u64, unit: &str, what: &str) -> Progress {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
        if !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        bar.set_style(
            ProgressStyle::with_template(&format!(
                "{{spinner}} [{{elapsed_precise}}] {{wide_bar}} {{human_pos}}/{{human_len}} {unit} ({{per_sec}}, eta {{eta}}) {{msg}}"
            ))
            .expect("the template is valid"),
        );
        Progress {
            bar,
            total,
            start: Instant::now(),
            warned: AtomicBool::new(false),
            what: what.to_string(),
        }
    }

    /// `done` units are done (callable from worker threads).
    pub fn set(&self, done: u64) {
        self.bar.set_position(done);
        let spent = self.start.elapsed();
        if done == 0 || spent < SAMPLE || self.warned.load(Ordering::Relaxed) {
            return;
        }
        let expected = spent.mul_f64(self.total as f64 / done as f64);
        if expected > LONG && !self.warned.swap(true, Ordering::Relaxed) {
            self.bar.suspend(|| {
                eprintln!(
                    "warning: {} will take about {} at this pace ({} of {} done in {:.0} s); Ctrl-C stops it",
                    self.what,
                    invlight_stats::hours_or_days(expected),
                    done,
                    self.total,
                    spent.as_secs_f64()
                )
            });
        }
    }

    /// `done` units of a total that is known only now.
    pub fn set_total(&self, done: u64, total: u64) {
        self.bar.set_length(total);
        self.bar.set_position(done);
    }

    /// A message after the counts.
    pub fn message(&self, msg: String) {
        self.bar.set_message(msg);
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
