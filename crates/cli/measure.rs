//! `invlight measure`: mean illuminance of named surfaces.

use crate::InputError;
use crate::args::{LoadArgs, check_confidence, find_surface};
use crate::progress;
use clap::Args;
use invlight_photon::{DEFAULT_MAX_BOUNCES, Emitters, TraceSettings, trace};
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
    /// Photons to emit. The standard error falls as 1/√N.
    #[arg(long, short = 'n', default_value_t = 1_000_000, value_name = "N")]
    pub photons: u64,
    /// Seed of the random streams: the same seed gives the same numbers on any number
    /// of threads.
    #[arg(long, default_value_t = 1, value_name = "S")]
    pub seed: u64,
    /// Surface interactions followed after the first hit. Russian roulette ends paths
    /// without bias; this is a safety cap. 4 reproduces the thesis, which under-counts
    /// light in bright rooms.
    #[arg(long, default_value_t = DEFAULT_MAX_BOUNCES, value_name = "K")]
    pub max_bounces: u32,
    /// Confidence level of the reported intervals.
    #[arg(long, default_value_t = 0.95, value_name = "C")]
    pub confidence: f64,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "T")]
    pub threads: Option<usize>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `invlight measure`.
pub fn run(args: MeasureArgs) -> anyhow::Result<()> {
    check_confidence(args.confidence)?;
    if args.photons == 0 {
        return Err(InputError("--photons must be at least 1".into()).into());
    }
    let scene = args.load.load(&args.scene)?;
    let ids = args
        .surfaces
        .iter()
        .map(|name| find_surface(&scene, &args.scene, name))
        .collect::<anyhow::Result<Vec<_>>>()?;
    if Emitters::new(&scene).is_empty() {
        return Err(InputError(format!(
            "{}: the scene has no light: no point, spot or directional light and no emissive surface",
            args.scene.display()
        ))
        .into());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()?;
    let start = Instant::now();
    // Nothing moves: every instance is baked into one world-space tree, which traces
    // faster than a top level over overlapping instances (BENCHMARKS.md).
    let accel = Accel::with_movable(&scene, &[]);
    let build_seconds = start.elapsed().as_secs_f64();
    let settings = TraceSettings {
        photons: args.photons,
        seed: args.seed,
        max_bounces: args.max_bounces,
    };
    let bar = progress::bar(args.photons, "photons");
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
            let (low, high) = e.interval(args.confidence);
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
        let out = json!({"photons": result.photons, "rays": result.rays, "seconds": seconds,
                         "build_seconds": build_seconds, "confidence": args.confidence, "seed": args.seed,
                         "max_bounces": args.max_bounces, "flux_lm": result.flux,
                         "surfaces": surfaces});
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        let width = rows.iter().map(|r| r.0.len()).max().unwrap_or(7).max(7);
        println!(
            "{:<width$}  {:>10}  {:>12}  {:>27}  {:>10}",
            "surface",
            "area m²",
            "mean lx",
            format!("{:.0} % interval lx", args.confidence * 100.0),
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
            "{} photons, {} rays, {:.2} s ({:.2} M photons/s), {:.0} lm emitted",
            result.photons,
            result.rays,
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
