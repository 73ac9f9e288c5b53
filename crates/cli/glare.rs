//! `invlight glare`: the Unified Glare Rating at observers
//! ([`invlight_photon::glare::unified_glare_rating`]).

use crate::InputError;
use crate::args::{SceneArgs, TraceArgs};
use clap::Args;
use invlight_photon::glare::{GlareSource, Observer, Ugr, rating, unified_glare_rating};
use invlight_scene::Vec3;
use invlight_stats::Confidence;
use invlight_trace::Accel;
use serde::Serialize;
use std::fmt::Write;
use std::process::ExitCode;

/// Options of `invlight glare`.
#[derive(Args, Debug)]
pub struct GlareArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The eye, X,Y,Z in the scene's metres (EN 12464-1 takes 1.2 m above the floor
    /// seated, 1.5 m standing). Repeat it for several observers: each is rated and the
    /// worst is reported first.
    #[arg(long = "observer", value_name = "X,Y,Z", required = true, allow_hyphen_values = true, value_parser = point)]
    pub observers: Vec<Vec3>,
    /// The line of sight, DX,DY,DZ (any length; usually horizontal). One for every
    /// observer, or one per --observer in order. Without it each observer looks the four
    /// horizontal ways along the scene's axes (as EN 12464-1's glare check and DIALux
    /// rate an observer), and the worst is reported.
    #[arg(long = "view", value_name = "DX,DY,DZ", allow_hyphen_values = true, value_parser = point)]
    pub views: Vec<Vec3>,
    #[command(flatten)]
    pub trace: TraceArgs,
    /// Print one JSON object instead of tables: the worst observer's ugr, ugr_interval,
    /// background_luminance, background_interval, eye_illuminance, direct_illuminance,
    /// indirect_illuminance, indirect_std_error, sources (name, luminance, solid_angle,
    /// position_index, contribution, intensity, distance, off_axis), observer and view;
    /// `observers`, every observer's the same way; photons, seed and confidence.
    #[arg(long)]
    pub json: bool,
}

/// Three numbers separated by commas.
fn point(s: &str) -> Result<Vec3, String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|x| x.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            format!("'{s}': expected three numbers separated by commas, e.g. 2.4,1.2,1.2")
        })?;
    match v[..] {
        [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok(Vec3::new(x, y, z)),
        _ => Err(format!(
            "'{s}': expected three finite numbers separated by commas, e.g. 2.4,1.2,1.2"
        )),
    }
}

/// One observer's rating, as `--json` writes it.
#[derive(Serialize)]
struct Rated {
    observer: [f32; 3],
    view: [f32; 3],
    #[serde(flatten)]
    ugr: Ugr,
}

/// What `--json` prints.
#[derive(Serialize)]
struct GlareReport {
    #[serde(flatten)]
    worst: Rated,
    observers: Vec<Rated>,
    photons: u64,
    seed: u64,
    confidence: f64,
}

/// Runs `invlight glare`.
pub fn run(args: GlareArgs) -> anyhow::Result<ExitCode> {
    let settings = args.trace.settings(1_000_000)?;
    let confidence = args.trace.confidence.unwrap_or_default();
    let scene = args.scene.load()?;
    let observers = observers(&args, scene.up)?;
    if let Some((lo, hi)) = scene.bounds() {
        for o in &observers {
            if o.eye.cmplt(lo).any() || o.eye.cmpgt(hi).any() {
                return Err(InputError(format!(
                    "the observer {} is outside the scene, whose bounds are {} to {}; expected an eye inside the room (EN 12464-1: 1.2 m above the floor seated)",
                    triple(o.eye),
                    triple(lo),
                    triple(hi)
                ))
                .into());
            }
        }
    }
    let pool = args.trace.pool()?;
    let accel = Accel::with_movable(&scene, &[]);
    let mut rated = Vec::new();
    for o in &observers {
        let ugr = pool
            .install(|| unified_glare_rating(&scene, &accel, o, &settings, confidence))
            .map_err(|e| InputError(format!("{}: {e}", args.scene.scene.display())))?;
        rated.push(Rated {
            observer: o.eye.to_array(),
            view: o.view.to_array(),
            ugr,
        });
    }
    let worst = worst(&rated);
    if args.json {
        let report = GlareReport {
            worst: Rated {
                observer: rated[worst].observer,
                view: rated[worst].view,
                ugr: rated[worst].ugr.clone(),
            },
            observers: rated,
            photons: invlight_photon::photons_traced(settings.photons).unwrap_or(settings.photons),
            seed: settings.seed,
            confidence: confidence.level(),
        };
        crate::print_json(&report)?;
    } else {
        let mut text = String::new();
        for (i, r) in rated.iter().enumerate() {
            text += &table(r, confidence, rated.len() > 1 && i == worst);
        }
        crate::print(&text)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The observers asked for: each --observer with its --view (one view for all), or
/// looking the four horizontal ways when no --view is given.
fn observers(args: &GlareArgs, up: Vec3) -> anyhow::Result<Vec<Observer>> {
    let (n, v) = (args.observers.len(), args.views.len());
    if v == 0 {
        let ways = four_ways(up);
        return Ok(args
            .observers
            .iter()
            .flat_map(|&eye| ways.map(|view| Observer { eye, view }))
            .collect());
    }
    if v != 1 && v != n {
        return Err(InputError(format!(
            "{n} --observer and {v} --view: expected one --view for all observers or one per --observer"
        ))
        .into());
    }
    Ok(args
        .observers
        .iter()
        .enumerate()
        .map(|(i, &eye)| Observer {
            eye,
            view: args.views[if v == 1 { 0 } else { i }],
        })
        .collect())
}

/// The four horizontal lines of sight along the scene's axes for a zenith `up`: the
/// first axis not along `up`, the one at right angles to both, and their opposites.
fn four_ways(up: Vec3) -> [Vec3; 4] {
    let along = [Vec3::X, Vec3::Z, Vec3::Y]
        .into_iter()
        .find(|a| a.dot(up).abs() < 0.5)
        .unwrap_or(Vec3::X);
    let a = (along - up * along.dot(up)).normalize();
    let b = up.cross(a).normalize();
    [a, b, -a, -b]
}

/// The observer with the highest UGR (the first when none has a luminaire in view).
fn worst(rated: &[Rated]) -> usize {
    let key = |r: &Rated| r.ugr.ugr.unwrap_or(f64::NEG_INFINITY);
    (0..rated.len())
        .max_by(|&a, &b| key(&rated[a]).total_cmp(&key(&rated[b])).then(b.cmp(&a)))
        .unwrap_or(0)
}

/// A point or direction as tables print it (a negative zero printed as 0).
fn triple(v: Vec3) -> String {
    let v = v + Vec3::ZERO;
    format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z)
}

/// One observer's rating and its luminaires as a table.
fn table(r: &Rated, confidence: Confidence, worst: bool) -> String {
    let u = &r.ugr;
    let at = format!(
        "UGR at {} looking {}{}",
        triple(Vec3::from(r.observer)),
        triple(Vec3::from(r.view)),
        if worst { " (the worst)" } else { "" }
    );
    let mut s = match (u.ugr, u.ugr_interval) {
        (Some(ugr), Some([lo, hi])) => format!(
            "{at}: {} [{}, {}] at {} %\n",
            rating(ugr),
            rating(lo),
            rating(hi),
            confidence.level() * 100.0
        ),
        _ => format!("{at}: no luminaire in view, no discomfort glare to rate\n"),
    };
    let [lo, hi] = u.background_interval;
    let _ = writeln!(
        s,
        "background luminance Lb {:.2} cd/m² [{lo:.2}, {hi:.2}]: the indirect {:.1} lx of {:.1} lx at the eye, over π",
        u.background_luminance, u.indirect_illuminance, u.eye_illuminance
    );
    if !u.sources.is_empty() {
        s += &sources(&u.sources);
    }
    s + "\n"
}

fn sources(sources: &[GlareSource]) -> String {
    let total: f64 = sources.iter().map(|s| s.contribution).sum();
    let width = sources
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(9);
    let mut s = format!(
        "  {:<width$}  {:>12}  {:>10}  {:>6}  {:>7}  {:>6}\n",
        "luminaire", "L cd/m²", "ω sr", "p", "off°", "share"
    );
    for g in sources {
        let _ = writeln!(
            s,
            "  {:<width$}  {:>12.0}  {:>10.3e}  {:>6.2}  {:>7.1}  {:>5.1} %",
            g.name,
            g.luminance,
            g.solid_angle,
            g.position_index,
            g.off_axis,
            100.0 * g.contribution / total
        );
    }
    s
}
