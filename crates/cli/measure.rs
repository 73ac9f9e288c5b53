//! `invlight measure`: mean illuminance of named surfaces ([`invlight_photon::measure`]).

use crate::args::{SceneArgs, TraceArgs, positive};
use clap::Args;
use invlight_photon::{Estimator, Side, measure, tune_roulette_for};
use invlight_report::Progress;
use invlight_scene::daylight::daylight_factor_scene;
use invlight_trace::Accel;
use std::process::ExitCode;
use std::time::Instant;

/// Options of `invlight measure`.
#[derive(Args, Debug)]
pub struct MeasureArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// A surface to measure, by name (node, mesh, group or object name; repeat the option
    /// for several). `invlight scene FILE` lists the names.
    #[arg(long = "surface", short = 's', value_name = "NAME", required = true)]
    pub surfaces: Vec<String>,
    /// The side of the surfaces that counts: the front (the side the surface's
    /// counter-clockwise normal faces, a desk's top), the back, or both. Front and back
    /// are reported apart either way.
    #[arg(long, default_value = "both", value_name = "front|back|both")]
    pub side: Side,
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Share of a photon's power below which Russian roulette starts (1: the thesis'; lower
    /// traces more reflections; same mean) [default: from 262 144 photons a pilot of ≤ 16
    /// 384 per share tries 1, ½, ¼, … and keeps the most efficient; fewer keep 1].
    #[arg(long, value_name = "SHARE", value_parser = positive::<f32>)]
    pub roulette: Option<f32>,
    /// Count only the photons' arrivals on the surfaces, as the thesis does (eq. 3.2),
    /// without connecting each photon's departures to them. The same mean with a larger
    /// standard error, except when nearly every photon reaches the surface anyway.
    #[arg(long)]
    pub arrivals_only: bool,
    /// Report each surface's daylight factor, E / E_unobstructed × 100 %, under the CIE
    /// overcast sky (--sky's or the problem file's, else 10 000 lx) with every light off.
    #[arg(long)]
    pub daylight_factor: bool,
    /// Print one JSON object (surfaces with mean, low, high, std_error, hits, side,
    /// front, back, daylight_factor; photons, rays, estimator, flux, settings, seconds,
    /// unobstructed_lux) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `invlight measure`.
pub fn run(args: MeasureArgs) -> anyhow::Result<ExitCode> {
    let settings = args.trace.settings(1_000_000)?;
    let path = &args.scene.scene;
    let mut scene = args.scene.load()?;
    let df = args
        .daylight_factor
        .then(|| daylight_factor_scene(&mut scene));
    let unobstructed = df.transpose()?;
    let ids = args
        .surfaces
        .iter()
        .map(|name| scene.find_surface(path, name))
        .collect::<Result<Vec<_>, _>>()?;
    crate::warn(ids.iter().filter_map(|&s| scene.reception_warning(s)));
    scene.require_light(path)?;
    let pool = args.trace.pool()?;
    let start = Instant::now();
    // Nothing moves: every instance is baked into one world-space tree, which traces
    // faster than a top level over overlapping instances (BENCHMARKS.md).
    let accel = Accel::with_movable(&scene, &[]);
    let build_seconds = start.elapsed().as_secs_f64();
    let estimator = Estimator::arrivals_only(args.arrivals_only);
    let (given, targets) = (args.roulette, (&ids[..], estimator));
    let choice = pool.install(|| tune_roulette_for(&scene, &accel, targets, &settings, given));
    let settings = choice.apply(settings);
    let bar = Progress::photons(settings.photons, "this measurement");
    let report = |done: u64| bar.set(done);
    let m = pool.install(|| measure(&scene, &accel, &ids, &settings, estimator, Some(&report)));
    bar.finish();
    let seconds = start.elapsed().as_secs_f64();
    let report = m.report(
        &args.surfaces,
        args.side,
        args.trace.confidence.unwrap_or_default(),
        (&settings, estimator, &choice),
        (seconds, build_seconds),
    );
    let report = report.with_daylight_factor(unobstructed);
    crate::warn(report.surfaces.iter().filter_map(|s| s.warning()));
    if args.json {
        crate::print_json(&report)?;
    } else {
        crate::print(&report.table())?;
    }
    Ok(ExitCode::SUCCESS)
}
