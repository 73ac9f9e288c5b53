//! The files of a search, written as it goes so they are valid after an interruption
//! (thesis §4.2.2): `solutions.csv` ([`SolutionRow`], one per evaluation, flushed row
//! by row), `result.json` ([`ResultFile`], the ISOC, rewritten atomically whenever it
//! changes) and `run.json` ([`RunFile`], the settings `--resume` checks).
//!
//! A folder belongs to one run at a time: [`Output::create`] takes a lock file and
//! refuses a folder another live process holds; it refuses a folder holding an earlier
//! run unless asked to replace it (then that run's files, pictures included, go first)
//! or to resume it. Whatever fails to write (a full disk) is cut back to what was
//! complete: no half row, no temporary file, no truncated `result.json`.

mod constraint_line;
mod lock;
mod recorder;
mod result;
mod run;
mod solutions;
mod table;

pub use lock::FolderLock;
pub use recorder::{Progress, Recorder};
pub use result::{
    ConstraintInfo, MemberError, ObjectiveInfo, RESULT_SCHEMA, ResultConstraint, ResultEstimate,
    ResultFile, ResultMember, ResultValue,
};
pub use run::{RUN_SCHEMA, RunFile};
pub use solutions::{SolutionRow, Solutions, header as csv_header, line as csv_line};

use crate::binding::Binding;
use crate::vns::{Observer, Record, Search, Settings, Standing};
use invlight_scene::{Diagnostic, write_atomically};
use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The files an earlier run leaves in its folder: replaced together, never mixed.
pub const RUN_FILES: [&str; 3] = ["solutions.csv", "result.json", "run.json"];

/// Whether a file name is one of a run's pictures (`isoc-NN.png`, `search*.png`),
/// which a new run into the folder removes with the rest.
pub fn is_run_picture(name: &str) -> bool {
    name.ends_with(".png") && (name.starts_with("isoc-") || name.starts_with("search"))
}

/// How a run treats its folder.
#[derive(Debug, Clone, PartialEq)]
pub enum Start {
    /// A new run: refuse a folder holding an earlier one, unless `replace`, which
    /// removes it first.
    Fresh {
        /// Remove an earlier run's files instead of refusing.
        replace: bool,
    },
    /// Continue the run whose rows these are.
    Resume(Solutions),
}

impl Start {
    /// How a run starts in `dir`: resuming its rows if `resume` and there are any
    /// (after checking they were traced with these settings), else fresh (replacing an
    /// earlier run if `replace`). The note says what was assumed, if anything.
    pub fn in_folder(
        dir: &Path,
        binding: &Binding,
        settings: &Settings,
        max_bounces: u32,
        resume: bool,
        replace: bool,
    ) -> Result<(Start, Option<String>), Diagnostic> {
        let csv = dir.join("solutions.csv");
        if !resume {
            return Ok((Start::Fresh { replace }, None));
        }
        if !csv.is_file() {
            let note = format!("no {} to resume; starting afresh", csv.display());
            return Ok((Start::Fresh { replace }, Some(note)));
        }
        let note = match RunFile::read(dir)? {
            Some(old) => {
                RunFile::new(settings, max_bounces, &binding.luminaires).check_resume(&old, dir)?;
                None
            }
            None => Some(format!(
                "{} has no run.json: assuming its rows were traced with this run's settings",
                dir.display()
            )),
        };
        Ok((Start::Resume(Solutions::read(&csv, binding)?), note))
    }
}

/// A search with its folder: the files it writes, the rows it goes on from.
pub struct Run<'b> {
    /// The search, with the rows of a resumed run replayed.
    pub search: Search<'b>,
    /// Its files.
    pub output: Output<'b>,
    /// Every evaluation so far (a resumed run's first), for the plots.
    pub records: Vec<Record>,
    /// What was assumed or done on opening, for the user.
    pub notes: Vec<String>,
}

impl<'b> Run<'b> {
    /// Opens `dir` for a search of `binding` with `settings`: resuming its rows if
    /// `resume` ([`Start::in_folder`]), else fresh, replacing an earlier run if
    /// `replace`.
    pub fn open(
        dir: &Path,
        binding: &'b Binding,
        objective: ObjectiveInfo,
        settings: &Settings,
        max_bounces: u32,
        (resume, replace): (bool, bool),
    ) -> Result<Run<'b>, OutputError> {
        let (start, note) = Start::in_folder(dir, binding, settings, max_bounces, resume, replace)
            .map_err(OutputError::Folder)?;
        let mut notes: Vec<String> = note.into_iter().collect();
        let mut search = Search::new(&binding.space, settings.clone(), &binding.initial);
        let mut records = Vec::new();
        if let Start::Resume(rows) = &start {
            search.replay(&rows.records);
            records = rows.records.clone();
            notes.push(format!(
                "resuming after {} evaluations (iteration {})",
                records.len(),
                search.iteration()
            ));
        }
        let output = Output::create(dir, binding, objective, settings, max_bounces, &start)?;
        Ok(Run {
            search,
            output,
            records,
            notes,
        })
    }
}

/// Why a folder cannot take a run.
#[derive(Debug)]
pub enum OutputError {
    /// Another process holds the folder.
    Locked(String),
    /// The folder holds an earlier run and replacing it was not asked for.
    Occupied(PathBuf),
    /// The earlier run's files cannot be continued (other settings, bad rows).
    Folder(Diagnostic),
    /// Reading or writing failed.
    Io(io::Error),
}

impl OutputError {
    /// Whether the user can fix it (another folder, --resume, --force, the same
    /// settings) rather than the machine (a full disk, permissions).
    pub fn is_input(&self) -> bool {
        !matches!(self, OutputError::Io(_))
    }
}

impl std::fmt::Display for OutputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OutputError::Locked(msg) => f.write_str(msg),
            OutputError::Occupied(dir) => write!(
                f,
                "{} holds an earlier run (solutions.csv, result.json): add --resume to continue it, --force to replace it, or choose another --output",
                dir.display()
            ),
            OutputError::Folder(d) => write!(f, "{d}"),
            OutputError::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for OutputError {}

impl From<io::Error> for OutputError {
    fn from(e: io::Error) -> Self {
        OutputError::Io(e)
    }
}

/// Writes `solutions.csv` and `result.json` as the search reports.
pub struct Output<'b> {
    binding: &'b Binding,
    objective: ObjectiveInfo,
    photons: u64,
    confidence: f64,
    dir: PathBuf,
    /// `None` on a follower of a cluster job ([`invlight_photon::leads`]), which writes
    /// nothing: rank 0 writes for every rank.
    csv: Option<File>,
    /// Bytes of `solutions.csv` that are complete rows.
    csv_len: u64,
    started: Instant,
    /// Elapsed seconds of the run being resumed.
    offset: f64,
    evaluations: u64,
    refused: u64,
    stopped: Option<String>,
    unlit: bool,
    z: f64,
    z_one_sided: f64,
    _lock: Option<FolderLock>,
}

impl<'b> Output<'b> {
    /// Takes `dir` for a run of `binding` with `settings` (the folder is created when
    /// missing and locked for the run) and opens its files as `start` says; a fresh run
    /// writes `run.json`. A follower of a cluster job leaves the folder alone: it has
    /// read the rows it resumes, and its rank 0 writes the same rows.
    pub fn create(
        dir: &Path,
        binding: &'b Binding,
        objective: ObjectiveInfo,
        settings: &Settings,
        max_bounces: u32,
        start: &Start,
    ) -> Result<Output<'b>, OutputError> {
        let run = RunFile::new(settings, max_bounces, &binding.luminaires);
        let lead = invlight_photon::leads();
        if lead {
            std::fs::create_dir_all(dir)?;
        }
        let lock = lead.then(|| FolderLock::take(dir)).transpose()?;
        let path = dir.join("solutions.csv");
        let (csv, csv_len, offset, evaluations) = match start {
            Start::Resume(rows) if !lead => (
                None,
                rows.complete_len,
                rows.elapsed,
                rows.records.len() as u64,
            ),
            Start::Fresh { .. } if !lead => (None, 0, 0.0, 0),
            Start::Resume(rows) => {
                // A row cut short by a hard stop is not part of the run; cut it off so
                // the next row starts on its own line.
                let f = OpenOptions::new().append(true).open(&path)?;
                f.set_len(rows.complete_len)?;
                (
                    Some(f),
                    rows.complete_len,
                    rows.elapsed,
                    rows.records.len() as u64,
                )
            }
            Start::Fresh { replace } => {
                let earlier = RUN_FILES.iter().any(|f| dir.join(f).exists());
                if earlier && !replace {
                    return Err(OutputError::Occupied(dir.to_path_buf()));
                }
                remove_run(dir)?;
                let mut f = File::create(&path)?;
                let header = csv_line(csv_header(binding));
                f.write_all(header.as_bytes())?;
                write_atomically(&dir.join("run.json"), |w| {
                    serde_json::to_writer_pretty(&mut *w, &run)?;
                    writeln!(w)
                })?;
                (Some(f), header.len() as u64, 0.0, 0)
            }
        };
        Ok(Output {
            binding,
            objective,
            photons: run.photons,
            confidence: run.confidence,
            dir: dir.to_path_buf(),
            csv,
            csv_len,
            started: Instant::now(),
            offset,
            evaluations,
            refused: 0,
            stopped: None,
            unlit: false,
            z: settings.confidence.z(),
            z_one_sided: settings.confidence.z_one_sided(),
            _lock: lock,
        })
    }

    /// The goal, as `result.json` gives it.
    pub fn objective(&self) -> &ObjectiveInfo {
        &self.objective
    }

    /// Seconds since the run (first) started.
    pub fn elapsed(&self) -> f64 {
        self.offset + self.started.elapsed().as_secs_f64()
    }

    /// The `result.json` document for where a search stands.
    pub fn result(&self, standing: Standing<'_>) -> ResultFile {
        let (isoc, closest) =
            ResultFile::members(self.binding, standing, (self.z, self.z_one_sided));
        ResultFile {
            schema_version: RESULT_SCHEMA,
            objective: self.objective.clone(),
            constraints: self
                .binding
                .constraints
                .iter()
                .map(ConstraintInfo::of)
                .collect(),
            photons: self.photons,
            confidence: self.confidence,
            evaluations: self.evaluations,
            refused: self.refused,
            stopped: self.stopped.clone(),
            unlit: self.unlit,
            seconds: self.elapsed(),
            feasible: !isoc.is_empty() || closest.is_empty(),
            isoc,
            closest,
            // Only beside free positions: under a <lightArray> every answer is one.
            best_regular_array: standing
                .best_start
                .filter(|_| !self.binding.space.exchangeable().is_empty())
                .map(|m| ResultMember::new(self.binding, m, (self.z, self.z_one_sided))),
        }
    }

    /// Records why the search stopped ([`crate::Outcome::stopped`], naming the goal's
    /// surface), for the `result.json` written after it.
    pub fn set_stopped(&mut self, outcome: crate::Outcome) {
        self.stopped = Some(outcome.stopped(self.objective.surface.as_deref()));
        self.unlit = outcome == crate::Outcome::Unlit;
    }

    /// Rewrites `result.json` atomically: readers see the old or the new file, never
    /// half of one. No fsync: the rename is atomic for readers, and syncing on every
    /// ISOC change (every evaluation while the ISOC is a plateau of zeros) cost more
    /// than the tracing of small scenes.
    pub fn write_result(&self, standing: Standing<'_>) -> io::Result<()> {
        if self.csv.is_none() {
            return Ok(());
        }
        let result = self.result(standing);
        write_atomically(&self.dir.join("result.json"), |w| {
            serde_json::to_writer_pretty(&mut *w, &result)?;
            writeln!(w)
        })
    }

    /// Appends a row; on failure the file is cut back to its complete rows.
    fn append(&mut self, line: &str) -> io::Result<()> {
        let Some(csv) = &mut self.csv else {
            return Ok(());
        };
        let written = csv.write_all(line.as_bytes()).and_then(|()| csv.flush());
        match written {
            Ok(()) => {
                self.csv_len += line.len() as u64;
                Ok(())
            }
            Err(e) => {
                let _ = csv.set_len(self.csv_len);
                Err(e)
            }
        }
    }
}

impl Observer for Output<'_> {
    fn evaluated(
        &mut self,
        record: &Record,
        standing: Standing<'_>,
        changed: bool,
    ) -> io::Result<()> {
        let row = SolutionRow::of(self.binding, record, self.elapsed());
        self.append(&csv_line(row.fields(
            self.z,
            self.z_one_sided,
            &self.binding.constraints,
        )))?;
        self.evaluations += 1;
        if changed {
            self.write_result(standing)?;
        }
        Ok(())
    }

    fn refused(&mut self, _iteration: u64, _why: &str) {
        self.refused += 1;
    }
}

/// Removes an earlier run's files and pictures from `dir`.
fn remove_run(dir: &Path) -> io::Result<()> {
    for f in RUN_FILES {
        match std::fs::remove_file(dir.join(f)) {
            Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
            _ => {}
        }
    }
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        if entry.file_name().to_str().is_some_and(is_run_picture) {
            std::fs::remove_file(entry.path())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
