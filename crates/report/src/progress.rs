//! Progress on stderr for the command line: a bar drawn only when stderr is a terminal,
//! so that logs and pipes stay clean, and — terminal or not — one warning when the work
//! under way will take more than an hour ([`invlight_stats::Pace`]). It lives here,
//! beside the other things made for people to look at, so that the CLI only wires.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use invlight_stats::Pace;
use std::io::IsTerminal;

/// A bar over `total` units of work.
pub struct Progress {
    bar: ProgressBar,
    pace: Pace,
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
            pace: Pace::new(total),
            what: what.to_string(),
        }
    }

    /// A bar over the photons a trace of `requested` traces, whole groups
    /// ([`invlight_photon::photons_traced`]), for `what`.
    pub fn photons(requested: u64, what: &str) -> Progress {
        let total = invlight_photon::photons_traced(requested).unwrap_or(requested);
        Progress::new(total, "photons", what)
    }

    /// `done` units are done (callable from worker threads).
    pub fn set(&self, done: u64) {
        self.bar.set_position(done);
        if let Some(long) = self.pace.long_once(done) {
            let what = &self.what;
            let line = format!("warning: {what} will take {long}; Ctrl-C stops it");
            self.bar.suspend(|| eprintln!("{line}"));
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

    /// Shows what a solve's [`invlight_ilp::Recorder`] tells: the best member after the
    /// counts, the candidate reached, and the first candidate refused as a warning.
    pub fn show(&self, told: invlight_ilp::Progress<'_>) {
        use invlight_ilp::Progress as Told;
        match told {
            Told::Best(line) => self.message(line),
            Told::Iteration(i) => self.set(i),
            Told::FirstRefusal(i, why) => eprintln!(
                "warning: candidate {i} is not traced: {why} (and so is any other that leaves it; their count comes at the end)"
            ),
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
