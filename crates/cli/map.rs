//! `invlight map`: illuminance on a regular grid of cells over a planar surface, each
//! cell with its interval, and the EN 12464-1 figures Emin, Eavg, Emax, U0
//! ([`invlight_render::illuminance_map`]).

use crate::InputError;
use crate::args::{SceneArgs, TraceArgs, positive};
use crate::progress::Progress;
use crate::render::save_image;
use clap::Args;
use invlight_photon::{Estimator, photons_traced};
use invlight_render::{MapSettings, illuminance_map, nice_ceil};
use invlight_report::file_safe;
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
    /// Largest cell side, m. A side of length L gets ⌈L/grid⌉ equal cells.
    #[arg(long, default_value_t = 0.25, value_name = "M", value_parser = positive::<f32>)]
    pub grid: f32,
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Count only the photons' arrivals in the cells. By default every photon departure
    /// is also connected to a point drawn on the surface, which counts for the cell it
    /// falls in (one ray per departure, whatever the number of cells): the same means
    /// with smaller errors.
    #[arg(long)]
    pub arrivals_only: bool,
    /// Top of the heat map's colour scale, lx (default: the largest cell, rounded up).
    #[arg(long, value_name = "LX", value_parser = positive::<f64>)]
    pub max_lux: Option<f64>,
    /// Prefix of the files written: PREFIX.csv (one row per cell) and PREFIX.png (the
    /// heat map with its scale). Default: map-SURFACE in the current directory.
    #[arg(long, short = 'o', value_name = "PREFIX")]
    pub output: Option<PathBuf>,
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
    scene.require_light(path)?;
    let pool = args.trace.pool()?;
    let start = Instant::now();
    let accel = Accel::new(&scene);
    let settings = MapSettings {
        cell: args.grid,
        trace,
        estimator: if args.arrivals_only {
            Estimator::ArrivalsOnly
        } else {
            Estimator::Connected
        },
    };
    let total = photons_traced(trace.photons).unwrap_or(trace.photons);
    let bar = Progress::new(total, "photons", "this map");
    let report = |done: u64| bar.set(done);
    let map = pool
        .install(|| illuminance_map(&scene, &accel, surface, &settings, Some(&report)))
        .map_err(|e| {
            InputError(format!(
                "{}: surface '{}': {e}",
                path.display(),
                args.surface
            ))
        })?;
    bar.finish();
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
    let max = args.max_lux.unwrap_or_else(|| nice_ceil(report.emax));
    save_image(&map.image(max), &png_path)?;

    if args.json {
        crate::print_json(&report)?;
    } else {
        let written = format!("wrote {} and {}\n", csv_path.display(), png_path.display());
        crate::print(&(report.summary() + &written))?;
    }
    Ok(ExitCode::SUCCESS)
}
