//! `invlight map`: illuminance on a regular grid of cells over a planar surface, each
//! cell with its interval, and the EN 12464-1 figures Emin, Eavg, Emax, U0
//! ([`invlight_render::illuminance_map`]).

use crate::InputError;
use crate::args::{ReportArgs, SceneArgs, TraceArgs};
use crate::render::save_image;
use clap::Args;
use invlight_photon::{Estimator, Side};
use invlight_render::{GridSpacing, MapPlan, MapSettings, illuminance_map};
use invlight_report::{MapPage, Progress, file_safe};
use invlight_trace::Accel;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Options of `invlight map`.
#[derive(Args, Debug)]
pub struct MapArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The planar surface to map, by name. `invlight scene FILE` lists the names.
    #[arg(long, short = 's', value_name = "NAME")]
    pub surface: String,
    /// Largest cell side, m: a side of length L gets ⌈L/grid⌉ equal cells; `auto` spaces
    /// them as EN 12464-1 does, p = 0.2·5^log10(d) for the surface's side d.
    #[arg(long, default_value = "0.25", value_name = "M|auto")]
    pub grid: GridSpacing,
    /// The side of the surface that counts: the front (the side its area-weighted
    /// counter-clockwise normal faces, a floor's top), the back, or both.
    #[arg(long, default_value = "both", value_name = "front|back|both")]
    pub side: Side,
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Count only the photons' arrivals in the cells. By default every photon departure
    /// is also connected to a point drawn on the surface, which counts for the cell it
    /// falls in (one ray per departure, whatever the number of cells): the same means
    /// with smaller errors.
    #[arg(long)]
    pub arrivals_only: bool,
    /// Prefix of the files written: PREFIX.csv (one row per cell) and PREFIX.png (the
    /// plan with isolux lines). Default: map-SURFACE in the current directory.
    #[arg(long, short = 'o', value_name = "PREFIX")]
    pub output: Option<PathBuf>,
    /// Also write this page: the plan, the figures, every cell and the compliance with
    /// --task or --em/--u0, in one self-contained HTML file.
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
    #[command(flatten)]
    pub require: ReportArgs,
    /// Print one JSON object (surface, cells, points with mean/low/high, emin, eavg,
    /// emax, u0) instead of a summary.
    #[arg(long)]
    pub json: bool,
}

/// Runs `invlight map`.
pub fn run(args: MapArgs) -> anyhow::Result<ExitCode> {
    let trace = args.trace.settings(4_000_000)?;
    let confidence = args.trace.confidence.unwrap_or_default();
    let path = &args.scene.scene;
    let scene = args.scene.load()?;
    let surface = scene.find_surface(path, &args.surface)?;
    crate::warn(scene.reception_warning(surface));
    scene.require_light(path)?;
    let pool = args.trace.pool()?;
    let start = Instant::now();
    // Nothing moves: one world-space tree, as `measure` builds.
    let accel = Accel::with_movable(&scene, &[]);
    let requirement = args.require.requirement(1.0)?;
    let (file, name) = (path.display(), &args.surface);
    let bad = |e| InputError(format!("{file}: surface '{name}': {e}"));
    let settings = MapSettings {
        spacing: args.grid,
        side: args.side,
        trace,
        estimator: Estimator::arrivals_only(args.arrivals_only),
    };
    let bar = Progress::photons(trace.photons, "this map");
    let report = |done: u64| bar.set(done);
    let map = pool
        .install(|| illuminance_map(&scene, &accel, surface, &settings, Some(&report)))
        .map_err(bad)?;
    bar.finish();
    if !invlight_photon::leads() {
        return Ok(ExitCode::SUCCESS);
    }
    crate::warn(map.warning(&args.surface));
    let seconds = start.elapsed().as_secs_f64();
    let report = map.report(&args.surface, &settings, confidence, seconds);

    let prefix = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("map-{}", file_safe(&args.surface))));
    let csv_path = prefix.with_extension("csv");
    let png_path = prefix.with_extension("png");
    map.write_csv(&csv_path, confidence)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", csv_path.display()))?;
    let plan = MapPlan::new(&map, &args.surface, confidence).from_above(scene.up);
    let plan = plan.image()?.0;
    save_image(&plan, &png_path)?;
    if let Some(html) = &args.report {
        let file = path.display().to_string();
        MapPage::new(&map, &report, file, scene.up, requirement.as_ref()).write(html)?;
    }

    if args.json {
        crate::print_json(&report)?;
    } else {
        let written = format!("wrote {} and {}\n", csv_path.display(), png_path.display());
        crate::print(&(report.summary() + &written))?;
    }
    Ok(ExitCode::SUCCESS)
}
