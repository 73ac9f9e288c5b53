//! What a second Ctrl-C leaves behind. The first stops the search before its next
//! candidate and lets the pictures and report.html be written; the second exits at
//! once. The solve's record (solutions.csv, run.json, result.json) is valid whenever
//! that happens, since each row is flushed as written and result.json is replaced
//! atomically, as is each picture; what is missing is the rest of the pictures and the
//! report, and without a word the user would not know that nor how to make them.

use invlight_ilp::{RUN_FILES, is_run_picture};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// What the solve is doing when Ctrl-C comes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Drawing and tracing candidates.
    Searching,
    /// Rendering the ISOC pictures and the search plots.
    Pictures,
    /// Writing report.html.
    Report,
}

/// A solve's state as the Ctrl-C handler sees it.
#[derive(Debug, Clone)]
pub struct Finishing {
    /// Where the solve is.
    pub phase: Phase,
    /// The problem file, as given.
    pub problem: PathBuf,
    /// The output folder.
    pub dir: PathBuf,
    /// ISOC pictures the solve writes (0 with --no-images).
    pub pictures: usize,
    /// Whether it writes report.html (not with --no-report).
    pub report: bool,
    /// The solve's flags that `invlight report` takes to check and measure alike
    /// (`--task`, `--em`, `--u0`, `--maintenance-factor`, `--report-photons`).
    pub report_flags: Vec<String>,
    /// Whether the solve was given flags that change how its scene is read
    /// (`--luminaire`, `--scale`, daylight…), which `invlight report` needs too.
    pub scene_flags: bool,
}

/// The solve in progress, if any: set as it goes from phase to phase, read by the
/// Ctrl-C handler (a thread of its own, installed once per process).
pub static FINISHING: Mutex<Option<Finishing>> = Mutex::new(None);

/// Records that the solve has entered `phase`.
pub fn enter(phase: Phase) {
    if let Ok(mut f) = FINISHING.lock()
        && let Some(f) = f.as_mut()
    {
        f.phase = phase;
    }
}

/// The solve in progress, as last recorded.
pub fn current() -> Option<Finishing> {
    FINISHING.lock().ok().and_then(|f| f.clone())
}

impl Finishing {
    /// What a first Ctrl-C after the search does: nothing but say what is being written
    /// and what a second one would leave; `None` while searching (the search says it
    /// stopped).
    pub fn first_ctrl_c(&self) -> Option<String> {
        let what = match self.phase {
            Phase::Searching => return None,
            Phase::Pictures if self.report => "the ISOC pictures and report.html",
            Phase::Pictures => "the ISOC pictures",
            Phase::Report => "report.html",
        };
        Some(format!(
            "the search is over and its files are written; writing {what} now (Ctrl-C again stops at once and leaves {} unwritten)",
            if self.phase == Phase::Report {
                "it"
            } else {
                "them"
            }
        ))
    }

    /// What a second Ctrl-C left, given the names of the files now in the folder:
    /// what was written, what was not, and the commands that finish the job.
    pub fn second_ctrl_c(&self, in_folder: &[String]) -> String {
        let has = |name: &str| in_folder.iter().any(|f| f == name);
        let dir = shell_word(&self.dir);
        let mut written: Vec<String> = RUN_FILES
            .iter()
            .filter(|f| has(f))
            .map(|f| f.to_string())
            .collect();
        // While searching, pictures in the folder are an earlier run's, removed when
        // this run draws its own.
        if self.phase != Phase::Searching {
            let mut pictures: Vec<&String> =
                in_folder.iter().filter(|f| is_run_picture(f)).collect();
            pictures.sort();
            written.extend(pictures.iter().map(|f| f.to_string()));
        }
        let isoc = |k: usize| format!("isoc-{k:02}.png");
        let mut left: Vec<String> = Vec::new();
        if self.phase != Phase::Report {
            left.extend((1..=self.pictures).map(isoc).filter(|f| !has(f)));
            if self.pictures > 0 && !in_folder.iter().any(|f| f.starts_with("search")) {
                left.push("the search plots (search.png)".into());
            }
        }
        if self.report {
            left.push("report.html".into());
        }
        let mut lines = vec![match self.phase {
            Phase::Searching => "stopped at once by a second Ctrl-C, during the search".to_string(),
            Phase::Pictures => {
                "stopped at once by a second Ctrl-C, while writing the ISOC pictures".to_string()
            }
            Phase::Report => {
                "stopped at once by a second Ctrl-C, while writing report.html".to_string()
            }
        }];
        lines.push(format!(
            "written in {dir}: {} (the search's record is valid up to its last evaluation)",
            if written.is_empty() {
                "nothing yet".into()
            } else {
                written.join(", ")
            }
        ));
        if !left.is_empty() {
            lines.push(format!("not written: {}", left.join(", ")));
        }
        let problem = shell_word(&self.problem);
        if self.phase == Phase::Searching {
            lines.push(format!(
                "to go on searching, and write the pictures and the report at its end: invlight solve {problem} --output {dir} --resume"
            ));
        }
        if self.report {
            let mut command = format!("invlight report {dir}");
            for flag in &self.report_flags {
                command += " ";
                command += flag;
            }
            let scene = if self.scene_flags {
                ", with the scene flags (--luminaire, --scale, --up, daylight…) this solve was given"
            } else {
                ""
            };
            lines.push(format!(
                "to write report.html from the folder: {command}{scene} (its gallery shows the ISOC pictures that were written)"
            ));
        }
        if self.phase != Phase::Report && left.iter().any(|f| f.starts_with("isoc-")) {
            lines.push(format!(
                "to render ISOC member K alone: invlight render {problem} --config {}#K --output member-K.png",
                shell_word(&self.dir.join("result.json"))
            ));
        }
        lines.join("\n")
    }
}

/// The names of the files in `dir` (none if it cannot be read).
pub fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default()
}

/// `path` as one word of a shell command, quoted when it needs to be, so that the
/// commands printed can be pasted.
fn shell_word(path: &Path) -> String {
    let text = path.display().to_string();
    let plain = |c: char| c.is_ascii_alphanumeric() || "/._-+,:=@%#".contains(c);
    if !text.is_empty() && text.chars().all(plain) {
        text
    } else {
        format!("'{}'", text.replace('\'', r"'\''"))
    }
}
