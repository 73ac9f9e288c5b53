//! `invlight map`: illuminance on a regular grid of cells over a planar surface, each
//! cell with its interval, and the EN 12464-1 figures Emin, Eavg, Emax, U0
//! ([`invlight_render::illuminance_map`]).

use crate::InputError;
use crate::args::{ReportArgs, SceneArgs, TraceArgs};
use crate::render::save_image;
use clap::Args;
use invlight_photon::{Estimator, GridValues, Side};
use invlight_render::{
    AreaVerdict, CylindricalReport, GridSpacing, MapPlan, MapSettings, MapTarget, MapsAndMeans,
    illuminance_maps_and_means,
};
use invlight_report::{MapPage, Progress, areas_text, compliance_text, file_safe};
use invlight_scene::AreaKind;
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
    /// them as EN 12464-1 does, p = 0.2·5^log10(d) for the surface's side d [default: a
    /// problem file's constraint on the surface's grid, else 0.25].
    #[arg(long, value_name = "M|auto")]
    pub grid: Option<GridSpacing>,
    /// The side of the surface that counts: the front (the side its area-weighted
    /// counter-clockwise normal faces, a floor's top), the back, or both [default: a
    /// problem file's constraint on the surface's side, else both].
    #[arg(long, value_name = "front|back|both")]
    pub side: Option<Side>,
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Count only the photons' arrivals in the cells. By default every photon departure
    /// is also connected to a point drawn on the surface, which counts for the cell it
    /// falls in (one ray per departure, whatever the number of cells): the same means
    /// with smaller errors.
    #[arg(long)]
    pub arrivals_only: bool,
    /// Read each cell as the mean illuminance over it instead of the illuminance at its
    /// centre. By default a grid is read at its points, as EN 12464-1 judges it: the
    /// point, spot and photometric lights' direct light computed exactly at each cell's
    /// centre, plus the photons' cell mean of the light that has bounced. A problem's
    /// constraint with values="cell-means" asks the same.
    #[arg(long)]
    pub cell_means: bool,
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
    /// With --task or --em: judge the task area alone. By default a horizontal task
    /// area is judged with EN 12464-1's areas around it, measured by the same photons:
    /// the immediate surrounding (a 0.5 m band in its plane), the background (3 m
    /// around that, within the room), the four walls and the ceiling.
    #[arg(long)]
    pub no_areas: bool,
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
    let (mut scene, problem) = args.scene.load_with_problem()?;
    let surface = scene.find_surface(path, &args.surface)?;
    crate::warn(scene.reception_warning(surface));
    scene.require_light(path)?;
    let mf = problem.as_ref().map_or(1.0, |p| p.maintenance_factor);
    let requirement = args.require.requirement(mf)?;
    let around = match &requirement {
        Some(r) if !args.no_areas => {
            areas_to_judge(&args, problem.as_ref(), r, &mut scene, surface)
        }
        _ => Around::default(),
    };
    let pool = args.trace.pool()?;
    let start = Instant::now();
    // Nothing moves: one world-space tree, as `measure` builds.
    let accel = Accel::with_movable(&scene, &[]);
    let (file, name) = (path.display(), &args.surface);
    let bad = |e| InputError(format!("{file}: surface '{name}': {e}"));
    let (spacing, side, values) = as_the_problem_reads(&args, problem.as_ref());
    let settings = MapSettings {
        spacing,
        side,
        trace,
        estimator: Estimator::arrivals_only(args.arrivals_only),
        values,
    };
    let task = MapTarget {
        surface,
        spacing,
        side,
    };
    let targets: Vec<MapTarget> = std::iter::once(task)
        .chain(around.areas.iter().map(area_target))
        .collect();
    let bar = Progress::photons(trace.photons, "this map");
    let report = |done: u64| bar.set(done);
    let means: Vec<_> = around.cylindrical.iter().map(|(a, _)| a.surface).collect();
    let what = MapsAndMeans {
        targets: &targets,
        means: &means,
    };
    let (mut maps, ez) = pool
        .install(|| {
            illuminance_maps_and_means(
                &scene,
                &accel,
                &what,
                &settings,
                Some(&report),
                invlight_photon::cluster(),
            )
        })
        .map_err(bad)?;
    bar.finish();
    if !invlight_photon::leads() {
        return Ok(ExitCode::SUCCESS);
    }
    let map = maps.remove(0);
    crate::warn(map.warning(&args.surface));
    let seconds = start.elapsed().as_secs_f64();
    let mut report = map.report(&args.surface, &settings, confidence, seconds);
    if let Some(r) = &requirement {
        judge_around(&mut report, &map, (maps, ez), around, r, confidence);
    }

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
        // The verdict the page states, with the page's confidence.
        let verdict = requirement.as_ref().map_or(String::new(), |r| {
            let confidence = invlight_ilp::Confidence::new(report.confidence).unwrap_or_default();
            let task = map.compliance(r, confidence);
            // With areas, the worst verdict comes first: the task area's alone would
            // say "meets" above an area that fails.
            let cylindrical = report.cylindrical.as_ref();
            let overall = if report.areas.is_empty() && cylindrical.is_none() {
                String::new()
            } else {
                let (worst, deciding) =
                    invlight_render::overall(task.verdict, &report.areas, cylindrical);
                format!(
                    "EN 12464-1, the task area and every area around it: {worst} ({}: {worst})\n",
                    deciding.join(", ")
                )
            };
            overall
                + &compliance_text(&task)
                + &areas_text(&report.areas, cylindrical, report.confidence)
        });
        crate::print(&(report.summary() + &verdict + &written))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The map of an EN 12464-1 area: its front, on its grid. A band's grid has at least
/// two cells across it; the others follow the rule.
fn area_target(a: &invlight_scene::TaskArea) -> MapTarget {
    MapTarget {
        surface: a.surface,
        spacing: a
            .kind
            .spacing()
            .map_or(GridSpacing::Auto, |m| GridSpacing::Metres(m as f32)),
        side: Side::Front,
    }
}

/// The verdicts on the areas around the task area (`around`, measured as `measured`:
/// their maps and the cylindrical illuminance's mean) and the overall verdict, into
/// `report`.
fn judge_around(
    report: &mut invlight_render::MapReport,
    map: &invlight_render::IlluminanceMap,
    measured: (
        Vec<invlight_render::IlluminanceMap>,
        Vec<invlight_ilp::Estimate>,
    ),
    around: Around,
    r: &invlight_render::Requirement,
    confidence: invlight_ilp::Confidence,
) {
    let (maps, ez) = measured;
    let maps = around
        .areas
        .iter()
        .zip(maps)
        .map(|(a, m)| (a.kind, a.name.clone(), a.size, m))
        .collect();
    let (judged, share) = AreaVerdict::judge(maps, r, confidence, ez.len());
    report.areas = judged.iter().map(AreaVerdict::report).collect();
    report.cylindrical = around
        .cylindrical
        .zip(ez.first())
        .map(|((a, required), e)| {
            CylindricalReport::judge(&a.name, e, required, r.maintenance_factor, share)
        });
    if !report.areas.is_empty() || report.cylindrical.is_some() {
        let task = map.compliance(r, confidence).verdict;
        let overall = invlight_render::overall(task, &report.areas, report.cylindrical.as_ref());
        report.overall = Some(overall.0.into());
    }
}

/// EN 12464-1's areas around a task area, and its cylindrical illuminance with the
/// maintained Ēz required of it.
#[derive(Default)]
struct Around {
    areas: Vec<invlight_scene::TaskArea>,
    cylindrical: Option<(invlight_scene::TaskArea, f64)>,
}

/// EN 12464-1's areas around the task area `surface`: those a problem's `<task>` on
/// it built with the scene, else built now (the cylindrical illuminance where the
/// `requirement`'s task has an Ēz, at a seated eye's height); none, with a warning,
/// where the surface has no room around it to build them in.
fn areas_to_judge(
    args: &MapArgs,
    problem: Option<&invlight_ilp::Problem>,
    requirement: &invlight_render::Requirement,
    scene: &mut invlight_scene::Scene,
    surface: invlight_scene::SurfaceId,
) -> Around {
    let built = problem.and_then(|p| {
        p.tasks
            .iter()
            .find(|t| t.surface.name == args.surface && !t.built.is_empty())
    });
    let warned = |e: invlight_scene::Diagnostic| {
        crate::warn(Some(format!("{e}; the areas around it are not judged")));
    };
    let (all, ez) = match built {
        Some(t) => (t.built.clone(), t.ez),
        None => {
            let mut all = scene
                .add_task_areas(&args.scene.scene, surface, &AreaKind::ALL)
                .unwrap_or_else(|e| {
                    warned(e);
                    Vec::new()
                });
            let ez = requirement.task.and_then(|t| t.ez);
            if ez.is_some() && !all.is_empty() {
                let seated = invlight_scene::SEATED;
                match scene.add_cylindrical_area(&args.scene.scene, surface, seated) {
                    Ok(a) => all.push(a),
                    Err(e) => warned(e),
                }
            }
            (all, ez)
        }
    };
    let (cylindrical, areas): (Vec<_>, Vec<_>) = all
        .into_iter()
        .partition(|a| a.kind == AreaKind::Cylindrical);
    Around {
        areas,
        cylindrical: cylindrical.into_iter().next().zip(ez),
    }
}

/// The grid and side to map: those given, else those of the first constraint on the
/// surface in a problem file — `map` of a solve's answer then reads it as the search
/// did (a uniformity on EN 12464-1's grid of the task area's front is not the one on a
/// finer grid of both sides), and says so — else a 0.25 m grid of both sides.
fn as_the_problem_reads(
    args: &MapArgs,
    problem: Option<&invlight_ilp::Problem>,
) -> (GridSpacing, Side, GridValues) {
    let (mut grid, mut side) = (args.grid, args.side);
    let mut values = if args.cell_means {
        GridValues::CellMeans
    } else {
        GridValues::Points
    };
    let path = &args.scene.scene;
    if let Some(problem) = problem.filter(|_| grid.is_none() || side.is_none()) {
        let on = |c: &&invlight_ilp::Constraint| c.surface.name == args.surface;
        let constraint = problem
            .constraints
            .iter()
            .filter(on)
            .find(|c| c.bound.grid().is_some())
            .or_else(|| problem.constraints.iter().find(on));
        if let Some(c) = constraint {
            let mut taken = Vec::new();
            if side.is_none() {
                side = Some(c.surface.side);
                taken.push(format!("side {}", c.surface.side.name()));
            }
            if let (false, Some(g)) = (args.cell_means, c.bound.grid())
                && g.values == GridValues::CellMeans
            {
                values = g.values;
                taken.push("cell means".to_string());
            }
            if let (None, Some(g)) = (grid, c.bound.grid()) {
                let g = match g.spacing {
                    invlight_ilp::Spacing::Auto => GridSpacing::Auto,
                    invlight_ilp::Spacing::Metres(m) => GridSpacing::Metres(m as f32),
                };
                grid = Some(g);
                taken.push(match g {
                    GridSpacing::Auto => "grid auto (EN 12464-1's rule)".to_string(),
                    GridSpacing::Metres(m) => format!("grid {m} m"),
                });
            }
            if !taken.is_empty() {
                eprintln!(
                    "note: {} of {}:{}'s constraint on {} (--side, --grid to choose others)",
                    taken.join(" and "),
                    path.display(),
                    c.line,
                    args.surface
                );
            }
        }
    }
    (
        grid.unwrap_or(GridSpacing::Metres(0.25)),
        side.unwrap_or(Side::Both),
        values,
    )
}
