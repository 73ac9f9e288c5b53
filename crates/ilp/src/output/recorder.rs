//! [`Recorder`]: the observer a command gives the search — it writes the run's files
//! ([`Output`]), keeps every evaluation for the plots and the report, counts the
//! candidates refused, and tells the caller what to show (a progress line, the first
//! refusal) through one callback, so a front end only draws.

use super::Output;
use crate::vns::{Observer, Record, Standing};
use invlight_stats::significant;
use std::sync::atomic::{AtomicBool, Ordering};

/// What a [`Recorder`] tells its caller.
#[derive(Debug, Clone, PartialEq)]
pub enum Progress<'a> {
    /// After an evaluation: the best member and the ISOC's size, in words.
    Best(String),
    /// The search reached this candidate.
    Iteration(u64),
    /// The first candidate refused (the others are only counted), and why.
    FirstRefusal(u64, &'a str),
}

/// Writes the files, keeps the records, and stops when `stop` is raised (Ctrl-C).
pub struct Recorder<'b, F: FnMut(Progress<'_>)> {
    /// The run's files.
    pub output: Output<'b>,
    /// Every evaluation so far (a resumed run's first).
    pub records: Vec<Record>,
    /// Candidates refused untraced (leaving the scene, two lamps in one cell).
    pub refused: u64,
    stop: &'b AtomicBool,
    show: F,
}

impl<'b, F: FnMut(Progress<'_>)> Recorder<'b, F> {
    /// A recorder writing to `output`, going on from `records`, stopping on `stop`.
    pub fn new(output: Output<'b>, records: Vec<Record>, stop: &'b AtomicBool, show: F) -> Self {
        Recorder {
            output,
            records,
            refused: 0,
            stop,
            show,
        }
    }

    /// The lines that close a run: the refused candidates' count when there are any,
    /// then the work (`evaluations`, photons and rays traced) and where the files are.
    pub fn closing(
        &self,
        evaluations: u64,
        (rays, photons): (u64, u64),
        seconds: f64,
        dir: &std::path::Path,
    ) -> Vec<String> {
        let mut lines = Vec::new();
        if self.refused > 0 {
            lines.push(format!(
                "{} candidates were not traced: they put an object or light outside the scene, two identical lamps in one cell, two fittings over each other, a continuous row longer than its rectangle, or more lamps in an array than it has",
                self.refused
            ));
        }
        lines.push(format!(
            "{evaluations} evaluations, {photons} photons, {rays} rays in {seconds:.1} s; results in {}",
            dir.display()
        ));
        lines
    }
}

impl<F: FnMut(Progress<'_>)> Observer for Recorder<'_, F> {
    fn evaluated(
        &mut self,
        record: &Record,
        standing: Standing<'_>,
        changed: bool,
    ) -> std::io::Result<()> {
        self.output.evaluated(record, standing, changed)?;
        self.records.push(record.clone());
        let isoc = standing.isoc;
        if let Some(best) = isoc.best() {
            let goal = &best.evaluation.goal;
            let i = goal.interval(isoc.z());
            let unit = match self.output.objective().unit.as_str() {
                "" => String::new(),
                u => format!(" {u}"),
            };
            (self.show)(Progress::Best(format!(
                "best {}{unit} [{}, {}], {} indistinguishable",
                significant(goal.mean),
                significant(i.low),
                significant(i.high),
                isoc.members().len()
            )));
        } else if let Some((v, _)) = standing.closest.first() {
            (self.show)(Progress::Best(format!(
                "none feasible yet; the closest is {} % short",
                significant(100.0 * v)
            )));
        }
        Ok(())
    }

    fn iteration(&mut self, iteration: u64) {
        (self.show)(Progress::Iteration(iteration));
    }

    fn refused(&mut self, iteration: u64, why: &str) {
        self.output.refused(iteration, why);
        if self.refused == 0 {
            (self.show)(Progress::FirstRefusal(iteration, why));
        }
        self.refused += 1;
    }

    /// The stop flag; in a cluster job rank 0's, sent to every rank (one word),
    /// since the ranks must stop at the same candidate: a rank that stopped on its own
    /// flag (a launcher such as `srun` forwards Ctrl-C to every rank, each seeing it at
    /// its own moment) would leave the others waiting in an exchange forever.
    fn should_stop(&mut self) -> bool {
        let mine = self.stop.load(Ordering::Relaxed);
        let job = invlight_photon::cluster();
        if job.ranks() == 1 {
            return mine;
        }
        let said: &[u64] = if job.rank() == 0 { &[mine as u64] } else { &[] };
        job.all_gather(said)[0] == 1
    }
}
