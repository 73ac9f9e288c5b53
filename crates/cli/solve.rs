//! `invlight solve`: reads a problem file, loads its scene, runs the noisy VNS with
//! photon-traced estimates ([`invlight_ilp::Search`]), and reports the ISOC. The files
//! (`solutions.csv`, `result.json`, `run.json`) are written as the search goes; Ctrl-C
//! stops it cleanly (exit 130) and `--resume` continues it. At the end (also after
//! Ctrl-C) every ISOC member is rendered (`isoc-NN.png`), the visited configurations
//! plotted (`search.png`) and all of it reported in `report.html`; a second Ctrl-C
//! exits at once and says what is left and how to finish it ([`finishing`]).

use crate::InputError;
use crate::args::{GridArgs, LoadArgs, ReportArgs, TraceArgs};
use anyhow::{Context, Result};
use finishing::{Finishing, Phase};
use invlight_ilp::{
    Binding, ObjectiveInfo, Outcome, PhotonEvaluator, Problem, Recorder, Run, Strategy,
};
use invlight_report::{Pictures, Progress, SolveFolder, SolveReport};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

mod finishing;

/// Raised by Ctrl-C; the search stops before its next candidate (a second Ctrl-C exits
/// at once).
static STOP: AtomicBool = AtomicBool::new(false);

/// Options of `invlight solve`.
#[derive(clap::Args, Debug)]
pub struct SolveArgs {
    /// The problem file (.xml).
    pub problem: PathBuf,
    /// Folder for the run's files [default: the problem's <output path>, relative to the
    /// problem file].
    #[arg(long, short = 'o', value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Candidates the search draws before it stops, cache hits included [default: the
    /// problem's maxIterations, else 1000].
    #[arg(long, value_name = "K")]
    pub iterations: Option<u64>,
    /// The search's strategy, as the problem file's `strategy` names it
    /// (docs/problem-file.md) [default: the problem's, RACE_ISOC_ON_END where it names
    /// none], to compare two on one problem.
    #[arg(long, value_name = "NAME")]
    pub strategy: Option<Strategy>,
    #[command(flatten)]
    pub trace: TraceArgs,
    #[command(flatten)]
    pub load: LoadArgs,
    /// Print result.json's content instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Continue a stopped run from the output folder's solutions.csv: evaluated cells
    /// are not traced again.
    #[arg(long, conflicts_with = "force")]
    pub resume: bool,
    /// Replace an earlier run in the output folder (its files and pictures are removed
    /// first) instead of refusing.
    #[arg(long)]
    pub force: bool,
    /// Width of the ISOC pictures, pixels; the height follows the camera's aspect.
    #[arg(long, default_value_t = 480, value_name = "W")]
    pub image_width: u32,
    /// Photons of each ISOC picture's photon map (its indirect light).
    #[arg(long, default_value_t = 300_000, value_name = "N")]
    pub image_photons: u64,
    /// Write neither the ISOC pictures nor search.png.
    #[arg(long)]
    pub no_images: bool,
    /// Write no report.html.
    #[arg(long)]
    pub no_report: bool,
    #[command(flatten)]
    pub report: ReportArgs,
    #[command(flatten)]
    pub grid: GridArgs,
}

/// Runs `invlight solve`.
pub fn run(args: SolveArgs) -> Result<ExitCode> {
    // 1. The problem, with command-line overrides, and its scene bound to it.
    let mut problem = problem_of(&args)?;
    let max_bounces = problem.bounces();
    let mut scene = args.load.load_problem(&mut problem)?;
    scene.require_light(&problem.scene.path)?;
    let binding = Binding::new(&problem, &mut scene)?;
    crate::warn(&binding.warnings);
    crate::warn(
        binding
            .reading
            .surfaces
            .iter()
            .filter_map(|&s| scene.reception_warning(s)),
    );
    let info = ObjectiveInfo::of(&problem, &binding);
    let pictures = (!args.no_images)
        .then(|| {
            let (w, n) = (args.image_width, args.image_photons);
            Pictures::new(&scene, &info, w, n, problem.seed, max_bounces)
                .map_err(|e| InputError(format!("--image-width: {e}")))
        })
        .transpose()?;
    let settings = problem.settings();
    let requirement = args.report.requirement(problem.maintenance_factor)?;
    let grid = args.grid.grid(problem.seed, max_bounces);
    let report_scene = (!args.no_report).then(|| scene.clone());

    // 2. The output folder: a fresh run, or the rows of the one it continues.
    let dir = args.output.clone().unwrap_or(problem.output.clone());
    let flags = (args.resume, args.force);
    let run = Run::open(&dir, &binding, info, &settings, max_bounces, flags)
        .with_context(|| format!("the output folder {}", dir.display()))?;
    run.notes.iter().for_each(|n| eprintln!("note: {n}"));
    let (mut search, output, records) = (run.search, run.output, run.records);

    // 3. Search until done or Ctrl-C. The first Ctrl-C stops before the next candidate;
    // a second one exits at once, which is safe too: every row is flushed as written
    // and result.json is replaced atomically; it says what the folder holds and what
    // was left unwritten. A second handler cannot be installed in one process (tests
    // run several solves); the first sets the same flag and reads the same state.
    let pool = args.trace.pool()?;
    let mut eval =
        PhotonEvaluator::new(&binding, scene, problem.seed, max_bounces, problem.photons);
    watch_interrupts(&args, &dir);
    let bar = Progress::new(problem.max_iterations, "iterations", "this search");
    bar.set(search.iteration());
    let mut reporter = Recorder::new(output, records, &STOP, |p| bar.show(p));
    let outcome = pool
        .install(|| search.run(&mut eval, &mut reporter))
        .with_context(|| format!("writing to {}", dir.display()))?;
    if !invlight_photon::leads() {
        return Ok(ExitCode::SUCCESS);
    }
    bar.finish();
    reporter.output.set_stopped(outcome);
    reporter
        .output
        .write_result(search.standing())
        .with_context(|| format!("writing {}", dir.join("result.json").display()))?;
    let result = reporter.output.result(search.standing());
    crate::warn(eval.first_sides().iter().filter_map(|s| s.warning()));

    // 4. Pictures of the ISOC and of the search, and the report.
    if let Ok(mut f) = finishing::FINISHING.lock()
        && let Some(f) = f.as_mut()
    {
        f.pictures = match (&pictures, result.isoc.len()) {
            (None, _) => 0,
            (Some(_), 0) => result.closest.len(),
            (Some(_), n) => n,
        };
    }
    if let Some(pictures) = &pictures {
        finishing::enter(Phase::Pictures);
        let bar = Progress::new(0, "rows", "the ISOC pictures");
        let report = |done: u64, total: u64| bar.set_total(done, total);
        let records = &reporter.records;
        let line = pool.install(|| {
            pictures.write(&dir, &binding, records, search.standing(), Some(&report))
        })?;
        bar.finish();
        eprintln!("{line}");
    }
    if let Some(scene) = &report_scene {
        finishing::enter(Phase::Report);
        let folder = SolveFolder::new(&dir, reporter.records.clone(), search.standing(), &result);
        let report = SolveReport::new(&problem, &binding, scene, &folder);
        let report = report.with(requirement.as_ref(), grid);
        eprintln!("{}", pool.install(|| report.write())?.lines());
    }

    // 5. Report.
    *finishing::FINISHING
        .lock()
        .unwrap_or_else(|e| e.into_inner()) = None;
    outcome.note().into_iter().for_each(|n| eprintln!("{n}"));
    search
        .paired_note()
        .into_iter()
        .for_each(|n| eprintln!("{n}"));
    let closing = reporter.closing(search.evaluations(), eval.work(), result.seconds, &dir);
    closing.iter().for_each(|l| eprintln!("{l}"));
    if args.json {
        crate::print_json(&result)?;
    } else {
        crate::print(&result.table(&binding))?;
    }
    Ok(match outcome {
        Outcome::Interrupted => ExitCode::from(130),
        _ => ExitCode::SUCCESS,
    })
}

/// The problem file read, its warnings printed, and the command line's overrides put on
/// it (`--photons`, `--confidence`, `--iterations`, `--strategy`, `--seed`,
/// `--max-bounces`).
fn problem_of(args: &SolveArgs) -> Result<Problem> {
    let mut problem = Problem::read(&args.problem)?;
    crate::warn(&problem.warnings);
    problem.photons = args.trace.photons(problem.photons)?;
    problem.confidence = args.trace.confidence.unwrap_or(problem.confidence);
    problem.max_iterations = args.iterations.unwrap_or(problem.max_iterations);
    problem.strategy = args.strategy.unwrap_or(problem.strategy);
    problem.seed = args.trace.seed.unwrap_or(problem.seed);
    problem.max_bounces = args.trace.max_bounces.or(problem.max_bounces);
    Ok(problem)
}

/// Clears the stop flag, records what a Ctrl-C would leave behind, and installs the
/// handler: the first Ctrl-C stops before the next candidate, a second exits at once
/// saying which files are whole and how to finish them.
fn watch_interrupts(args: &SolveArgs, dir: &std::path::Path) {
    STOP.store(false, Ordering::Relaxed);
    let mut report_flags = args.report.flags();
    report_flags.extend(args.grid.flags());
    *finishing::FINISHING
        .lock()
        .unwrap_or_else(|e| e.into_inner()) = Some(Finishing {
        phase: Phase::Searching,
        problem: args.problem.clone(),
        dir: dir.to_path_buf(),
        pictures: 0,
        report: !args.no_report,
        report_flags,
        scene_flags: args.load.given(),
    });
    let _ = ctrlc::set_handler(|| {
        let again = STOP.swap(true, Ordering::Relaxed);
        let Some(state) = finishing::current() else {
            if again {
                std::process::exit(130);
            }
            return;
        };
        if again {
            eprintln!(
                "\n{}",
                state.second_ctrl_c(&finishing::files_in(&state.dir))
            );
            std::process::exit(130);
        }
        if let Some(note) = state.first_ctrl_c() {
            eprintln!("\n{note}");
        }
    });
}

#[cfg(test)]
mod tests;
