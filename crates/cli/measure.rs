//! `invlight measure`: mean illuminance of named surfaces.

use crate::args::{LoadArgs, TraceArgs, find_surface, require_light};
use crate::progress;
use clap::Args;
use invlight_photon::trace;
use invlight_trace::Accel;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `invlight measure`.
#[derive(Args, Debug)]
pub struct MeasureArgs {
    /// Scene file: glTF 2.0 (.gltf, .glb), COLLADA (.dae) or Wavefront OBJ (.obj).
    pub scene: PathBuf,
    /// A surface to measure, by name (node, mesh, group or object name; repeat the option
    /// for several). `invlight scene FILE` lists the names.
    #[arg(long = "surface", short = 's', value_name = "NAME", required = true)]
    pub surfaces: Vec<String>,
    /// Photons to emit. The standard error falls as 1/√N. Rounded up to whole groups of
    /// 64 (photons are stratified in groups), at least 2048; the output says how many.
    #[arg(long, short = 'n', default_value_t = 1_000_000, value_name = "N")]
    pub photons: u64,
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Count only the photons' arrivals on the surfaces, as the thesis does (eq. 3.2),
    /// without connecting each photon's departures to them. The same mean with a larger
    /// standard error: for comparisons with the thesis and checks of the estimator.
    #[arg(long)]
    pub arrivals_only: bool,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `invlight measure`.
pub fn run(args: MeasureArgs) -> anyhow::Result<()> {
    args.trace.check(args.photons)?;
    let scene = args.load.load(&args.scene)?;
    let ids = args
        .surfaces
        .iter()
        .map(|name| find_surface(&scene, &args.scene, name))
        .collect::<anyhow::Result<Vec<_>>>()?;
    require_light(&scene, &args.scene)?;
    let pool = args.trace.pool()?;
    let start = Instant::now();
    // Nothing moves: every instance is baked into one world-space tree, which traces
    // faster than a top level over overlapping instances (BENCHMARKS.md).
    let accel = Accel::with_movable(&scene, &[]);
    let build_seconds = start.elapsed().as_secs_f64();
    let settings = invlight_photon::TraceSettings {
        connect: !args.arrivals_only,
        ..args.trace.settings(args.photons)
    };
    let bar = progress::bar(invlight_photon::whole_groups(args.photons), "photons");
    let report = |done: u64| bar.set_position(done);
    let result = pool.install(|| trace(&scene, &accel, &ids, &settings, Some(&report)));
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();

    let rows: Vec<_> = args
        .surfaces
        .iter()
        .zip(&ids)
        .enumerate()
        .map(|(i, (name, &id))| {
            let area = scene.surface_area(id) as f64;
            let e = result.estimate(i, area);
            let (low, high) = e.interval(args.trace.confidence);
            (name, area, e, low, high, result.tallies[i].hits)
        })
        .collect();
    if args.json {
        let surfaces: Vec<_> = rows
            .iter()
            .map(|(name, area, e, low, high, hits)| {
                json!({"name": name, "area": area, "mean": e.mean, "low": low, "high": high,
                       "std_error": e.std_error, "hits": hits})
            })
            .collect();
        let out = json!({"photons": result.photons, "rays": result.rays,
                         "connection_rays": result.connection_rays,
                         "estimator": if settings.connect { "connected" } else { "arrivals" },
                         "seconds": seconds,
                         "build_seconds": build_seconds, "confidence": args.trace.confidence, "seed": args.trace.seed,
                         "max_bounces": args.trace.max_bounces, "flux_lm": result.flux,
                         "surfaces": surfaces});
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        let width = rows.iter().map(|r| r.0.len()).max().unwrap_or(7).max(7);
        println!(
            "{:<width$}  {:>10}  {:>12}  {:>27}  {:>10}",
            "surface",
            "area m²",
            "mean lx",
            format!("{:.0} % interval lx", args.trace.confidence * 100.0),
            "hits"
        );
        for (name, area, e, low, high, hits) in &rows {
            println!(
                "{name:<width$}  {area:>10.4}  {:>12}  {:>27}  {hits:>10}",
                fmt_lux(e.mean),
                format!("[{}, {}]", fmt_lux(*low), fmt_lux(*high)),
            );
        }
        println!(
            "{} photons, {} rays and {} connection rays, {:.2} s ({:.2} M photons/s), {:.0} lm emitted",
            result.photons,
            result.rays,
            result.connection_rays,
            seconds,
            result.photons as f64 / seconds / 1e6,
            result.flux
        );
    }
    Ok(())
}

/// Lux with four significant digits, whatever the magnitude.
fn fmt_lux(x: f64) -> String {
    if x == 0.0 || (1e-3..1e7).contains(&x.abs()) {
        let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}
