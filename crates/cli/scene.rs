//! `invlight scene`: what a scene file holds ([`invlight_scene::SceneSummary`]).

use crate::args::SceneArgs;
use clap::Args;

/// Options of `invlight scene`.
#[derive(Args, Debug)]
pub struct SceneInfoArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Print one JSON object (surfaces, lights, cameras, bounds, up, warnings) instead
    /// of tables.
    #[arg(long)]
    pub json: bool,
}

/// Runs `invlight scene`.
pub fn run(args: SceneInfoArgs) -> anyhow::Result<std::process::ExitCode> {
    let summary = args.scene.load()?.summary();
    if args.json {
        crate::print_json(&summary)?;
    } else {
        crate::warn(&summary.warnings);
        crate::print(&summary.tables())?;
    }
    Ok(std::process::ExitCode::SUCCESS)
}
