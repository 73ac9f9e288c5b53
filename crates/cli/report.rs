//! `invlight report DIR`: rebuilds a solve's report.html from its folder's files
//! ([`invlight_report::SolveReport`]).

use crate::args::{GridArgs, LoadArgs, ReportArgs};
use invlight_report::{SolveFolder, SolveReport};
use std::path::PathBuf;
use std::process::ExitCode;

/// Options of `invlight report`.
#[derive(clap::Args, Debug)]
pub struct ReportCommandArgs {
    /// A solve's output folder (solutions.csv, result.json, run.json, isoc-NN.png).
    pub dir: PathBuf,
    /// The problem file [default: the one result.json records].
    #[arg(long, value_name = "FILE")]
    pub problem: Option<PathBuf>,
    #[command(flatten)]
    pub report: ReportArgs,
    #[command(flatten)]
    pub grid: GridArgs,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `invlight report`.
pub fn run(args: ReportCommandArgs) -> anyhow::Result<ExitCode> {
    let mut problem = SolveFolder::problem(&args.dir, args.problem.as_deref())?;
    let requirement = args.report.requirement(problem.maintenance_factor)?;
    let grid = args.grid.grid(problem.seed, problem.bounces());
    let scene = args.load.load_problem(&mut problem)?;
    let written = SolveReport::rebuild(&args.dir, &problem, scene, requirement.as_ref(), grid)?;
    crate::print(&(written.lines() + "\n"))?;
    Ok(ExitCode::SUCCESS)
}
