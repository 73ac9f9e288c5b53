//! `invlight report DIR`: rebuilds a solve's report.html from its folder's files
//! ([`invlight_report::SolveReport`]).

use crate::args::{LoadArgs, ReportArgs};
use invlight_ilp::Binding;
use invlight_photon::DEFAULT_MAX_BOUNCES;
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
    pub load: LoadArgs,
}

/// Runs `invlight report`.
pub fn run(args: ReportCommandArgs) -> anyhow::Result<ExitCode> {
    let problem = SolveFolder::problem(&args.dir, args.problem.as_deref())?;
    let requirement = args.report.requirement()?;
    let mut scene = args.load.load_problem(&problem)?;
    let binding = Binding::new(&problem, &mut scene)?;
    let folder = SolveFolder::read(&args.dir, &problem, &binding)?;
    let bounces = problem.max_bounces.unwrap_or(DEFAULT_MAX_BOUNCES);
    let report = SolveReport {
        problem: &problem,
        binding: &binding,
        scene: &scene,
        folder: &folder,
        requirement: requirement.as_ref(),
        grid: Some(args.report.grid(problem.seed, bounces)),
    };
    let written = report.write()?;
    written.no_plan.iter().for_each(|n| eprintln!("note: {n}"));
    crate::print(&format!(
        "wrote {} in {:.1} s\n",
        written.path.display(),
        written.seconds
    ))?;
    Ok(ExitCode::SUCCESS)
}
