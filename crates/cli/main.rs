//! The `invlight` command: parses arguments, wires the library crates together and
//! reports. Everything that computes lives in the crates under `crates/`.

mod args;
mod glare;
mod luminaire;
mod map;
mod measure;
mod render;
mod report;
mod scene;
mod solve;
mod sun;

use clap::{Parser, Subcommand};
use std::io::Write;
use std::process::ExitCode;

/// Inverse lighting: measure the light on named surfaces of a 3D scene, and search a
/// scene's free parameters (where a lamp, an object or a skylight goes, where the sun
/// comes from, how light a wall is) for the configurations that light a surface best.
///
/// Light is estimated by photon tracing on all CPU cores, in lux, with confidence
/// intervals. Scenes: glTF 2.0 (.gltf, .glb), COLLADA (.dae), Wavefront OBJ (.obj).
/// Exit status: 0 done, 1 failed, 2 bad input (a file, a name, a value), 130 a solve
/// interrupted by Ctrl-C (its files hold what it found).
#[derive(Parser)]
#[command(name = "invlight", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Mean illuminance of named surfaces, with confidence intervals.
    Measure(measure::MeasureArgs),
    /// What a scene file holds: surfaces, lights, cameras, bounds. Run it first to find
    /// the names to measure or to put in a problem file.
    Scene(scene::SceneInfoArgs),
    /// Search a problem's free variables for the configurations that maximise a
    /// surface's illuminance (the problem file is ILPSolver's XML; see
    /// docs/problem-file.md). Results are written as they are found.
    ///
    /// The output folder gets solutions.csv (one row per photon trace), result.json (the
    /// best configurations) and run.json (the settings --resume checks). Ctrl-C stops
    /// cleanly with exit status 130; --resume continues. An earlier run is refused unless
    /// --resume or --force is given. At the end isoc-NN.png render the ISOC, search.png
    /// plots the search and report.html reports it all in one page.
    Solve(solve::SolveArgs),
    /// Rebuild a solve's report.html from its output folder.
    Report(report::ReportCommandArgs),
    /// Render a picture from a scene camera by photon mapping, or a false-colour
    /// illuminance picture with a lux scale.
    Render(render::RenderArgs),
    /// Illuminance on a regular grid over a planar surface (CSV and a plan), with
    /// Emin, Eavg, Emax and uniformity U0 as lighting standards ask.
    Map(map::MapArgs),
    /// Where the sun stands at a site, date and time (NREL SPA), as a scene direction.
    Sun(sun::SunArgs),
    /// Discomfort glare at observers: the Unified Glare Rating (CIE 117) with its
    /// interval, and each luminaire's luminance, solid angle and position index.
    Glare(glare::GlareArgs),
    /// A photometric file's datasheet: flux, watts, efficacy, beam and field angles,
    /// the CIE flux code and the luminous opening with its axes.
    Luminaire(luminaire::LuminaireArgs),
}

/// An error caused by what the user gave us (a file, a name, a value): exit code 2.
#[derive(Debug)]
pub struct InputError(pub String);

impl std::fmt::Display for InputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

/// Writes `text` to standard output. A closed pipe (`invlight … --json | head`) is not
/// an error of ours: it comes back as one, and `main` ends quietly on it, as ripgrep
/// does.
pub fn print(text: &str) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// Each of `warnings` on stderr, as a warning.
pub fn warn<W: std::fmt::Display>(warnings: impl IntoIterator<Item = W>) {
    warnings.into_iter().for_each(|w| eprintln!("warning: {w}"));
}

/// Pretty JSON of `value` and a newline, to standard output.
pub fn print_json(value: &impl serde::Serialize) -> anyhow::Result<()> {
    print(&(serde_json::to_string_pretty(value)? + "\n"))
}

/// Whether `err` was caused by what the user gave us (a file, a name, a value, an
/// occupied output folder): exit code 2, as for clap's own usage errors; anything else
/// that fails (writing output) is 1.
pub fn is_input(err: &anyhow::Error) -> bool {
    err.chain().any(|e| {
        e.is::<InputError>()
            || e.is::<invlight_scene::Diagnostic>()
            || e.is::<invlight_scene::daylight::DaylightError>()
            || e.downcast_ref::<invlight_ilp::OutputError>()
                .is_some_and(|e| e.is_input())
    })
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // Every rank of an MPI job runs this program; rank 0 alone prints and writes, and
    // only measure, solve and map share their traces (docs/cluster.md).
    #[cfg(feature = "mpi")]
    let job = invlight_cluster::Job::join();
    let shared = matches!(
        cli.command,
        Command::Measure(_) | Command::Solve(_) | Command::Map(_)
    );
    if !(shared || invlight_photon::leads()) {
        return ExitCode::SUCCESS;
    }
    let result = match cli.command {
        Command::Measure(args) => measure::run(args),
        Command::Scene(args) => scene::run(args),
        Command::Solve(args) => solve::run(args),
        Command::Report(args) => report::run(args),
        Command::Render(args) => render::run(args),
        Command::Map(args) => map::run(args),
        Command::Sun(args) => sun::run(args),
        Command::Glare(args) => glare::run(args),
        Command::Luminaire(args) => luminaire::run(args),
    };
    match result {
        Ok(code) => code,
        Err(err) => {
            let broken_pipe = err.chain().any(|e| {
                e.downcast_ref::<std::io::Error>()
                    .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
            });
            if broken_pipe {
                return ExitCode::SUCCESS;
            }
            let code = if is_input(&err) { 2 } else { 1 };
            #[cfg(feature = "mpi")]
            job.fail(&format!("error: {err:#}"), code.into());
            #[cfg(not(feature = "mpi"))]
            eprintln!("error: {err:#}");
            ExitCode::from(code)
        }
    }
}
