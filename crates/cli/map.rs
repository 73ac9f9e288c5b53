//! `invlight map`: illuminance on a regular grid of cells over a planar surface, each
//! cell with its interval, and the EN 12464-1 figures Emin, Eavg, Emax, U0.

use crate::InputError;
use crate::args::{LoadArgs, TraceArgs, find_surface, require_light};
use crate::progress;
use crate::render::save_png;
use clap::Args;
use invlight_render::{MapError, MapSettings, illuminance_map, nice_ceil};
use invlight_trace::Accel;
use serde_json::json;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `invlight map`.
#[derive(Args, Debug)]
pub struct MapArgs {
    /// Scene file: glTF 2.0 (.gltf, .glb), COLLADA (.dae) or Wavefront OBJ (.obj).
    pub scene: PathBuf,
    /// The planar surface to map, by name. `invlight scene FILE` lists the names.
    #[arg(long, short = 's', value_name = "NAME")]
    pub surface: String,
    /// Largest cell side, m. A side of length L gets ⌈L/grid⌉ equal cells.
    #[arg(long, default_value_t = 0.25, value_name = "M")]
    pub grid: f32,
    /// Photons to emit. Each cell's standard error falls as 1/√N. Rounded up to whole
    /// groups of 64 (photons are stratified in groups), at least 2048.
    #[arg(long, short = 'n', default_value_t = 4_000_000, value_name = "N")]
    pub photons: u64,
    /// Top of the heat map's colour scale, lx (default: the largest cell, rounded up).
    #[arg(long, value_name = "LX")]
    pub max_lux: Option<f64>,
    /// Prefix of the files written: PREFIX.csv (one row per cell) and PREFIX.png (the
    /// heat map with its scale). Default: map-SURFACE in the current directory.
    #[arg(long, short = 'o', value_name = "PREFIX")]
    pub output: Option<PathBuf>,
    /// Print one JSON object (surface, cell, points with mean/low/high, emin, eavg, emax,
    /// u0) instead of a summary.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub trace: TraceArgs,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `invlight map`.
pub fn run(args: MapArgs) -> anyhow::Result<()> {
    args.trace.check(args.photons)?;
    if let Some(m) = args.max_lux
        && !(m > 0.0 && m.is_finite())
    {
        return Err(InputError(format!("--max-lux {m} must be a positive illuminance")).into());
    }
    let scene = args.load.load(&args.scene)?;
    let surface = find_surface(&scene, &args.scene, &args.surface)?;
    require_light(&scene, &args.scene)?;
    let pool = args.trace.pool()?;
    let start = Instant::now();
    let accel = Accel::new(&scene);
    let settings = MapSettings {
        cell: args.grid,
        photons: args.photons,
        seed: args.trace.seed,
        max_bounces: args.trace.max_bounces,
    };
    let bar = progress::bar(invlight_photon::whole_groups(args.photons), "photons");
    let report = |done: u64| bar.set_position(done);
    let map = pool
        .install(|| illuminance_map(&scene, &accel, surface, &settings, Some(&report)))
        .map_err(|e| match e {
            MapError::Empty
            | MapError::NotPlanar { .. }
            | MapError::BadCell(_)
            | MapError::TooManyCells(_) => InputError(format!(
                "{}: surface '{}': {e}",
                args.scene.display(),
                args.surface
            )),
        })?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    let summary = map.summary();
    let z = invlight_photon::z_two_sided(args.trace.confidence);

    let prefix = args.output.clone().unwrap_or_else(|| {
        let safe: String = args
            .surface
            .chars()
            .map(|c| {
                if c.is_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        PathBuf::from(format!("map-{safe}"))
    });
    let csv_path = prefix.with_extension("csv");
    let png_path = prefix.with_extension("png");
    let mut csv = String::from("column,row,x,y,z,area,mean,low,high,std_error,hits\n");
    let mut points = Vec::new();
    for cell in map.cells.iter().flatten() {
        let e = cell.estimate;
        let (low, high) = (e.mean - z * e.std_error, e.mean + z * e.std_error);
        let p = cell.centre;
        writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{}",
            cell.index.0,
            cell.index.1,
            p.x,
            p.y,
            p.z,
            cell.area,
            e.mean,
            low,
            high,
            e.std_error,
            cell.hits
        )?;
        points.push(json!({"position": [p.x, p.y, p.z], "mean": e.mean, "low": low, "high": high}));
    }
    std::fs::write(&csv_path, csv)
        .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", csv_path.display()))?;
    let max = args.max_lux.unwrap_or_else(|| nice_ceil(summary.emax));
    save_png(&map.image(max), &png_path)?;

    if args.json {
        let out = json!({
            "surface": args.surface, "cell": args.grid,
            "cell_size": [map.cell_u, map.cell_v], "cells": [map.columns, map.rows],
            "photons": map.photons, "confidence": args.trace.confidence, "seconds": seconds,
            "points": points,
            "emin": summary.emin, "eavg": summary.eavg, "emax": summary.emax, "u0": summary.u0,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        println!(
            "{}: {}×{} cells of {:.3}×{:.3} m, {} photons, {:.2} s",
            args.surface, map.columns, map.rows, map.cell_u, map.cell_v, map.photons, seconds
        );
        println!(
            "Emin {:.4} lx  Eavg {:.4} lx  Emax {:.4} lx  U0 = Emin/Eavg {:.3}",
            summary.emin, summary.eavg, summary.emax, summary.u0
        );
        println!("wrote {} and {}", csv_path.display(), png_path.display());
    }
    Ok(())
}
