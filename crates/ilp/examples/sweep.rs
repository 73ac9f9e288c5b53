//! Sweeps the light of a `lightInSurface` problem over a grid of positions centred above
//! the objective surface and prints the objective at each: an independent check of where
//! the optimum is, with no search involved (examples/cornell-light/README.md,
//! "Independent check").
//!
//! ```text
//! cargo run --release -p invlight-ilp --example sweep -- examples/cornell-light/problem.xml \
//!     [--photons N] [--half K] [--step M] [--around X,Y] [--bounces B] [--seed S] [--json]
//! ```
//!
//! The light's centre (the centre of its bounding box, moved by P − A as the solver moves
//! it) visits (cx + i·step, cy + j·step) for i, j ∈ −K..=K, where (cx, cy) is `--around`,
//! by default the centre of the objective surface's bounding box (for the Cornell cone,
//! its axis); offsets are printed from the objective's centre. Every cell is
//! traced with its own seed (S + cell index), so the cells' estimates are independent and
//! the difference of two cells has the standard error √(σ₁² + σ₂²). Cells where part of
//! the light leaves the placement rectangle (for a ceiling: pokes through a wall) are
//! marked `*`.
//!
//! A weighted least-squares quadratic through the unmarked cells gives the maximum's
//! position; its spread is a parametric bootstrap (each cell redrawn from its mean and
//! standard error).

use glam::{DVec2, DVec3};
use invlight_ilp::{
    Binding, Domain, Evaluate, Parallelogram, PhotonEvaluator, Problem, VariableKind,
};
use invlight_photon::TraceSettings;
use invlight_scene::{LoadOptions, Scene, SurfaceId};
use invlight_stats::SplitMix64;
use std::error::Error;
use std::path::PathBuf;
use std::time::Instant;

struct Args {
    problem: PathBuf,
    photons: u64,
    half: i32,
    step: f64,
    bounces: u32,
    seed: Option<u64>,
    around: Option<(f64, f64)>,
    json: bool,
}

const USAGE: &str = "usage: sweep PROBLEM.xml [--photons N] [--half K] [--step M] [--around X,Y] [--bounces B] [--seed S] [--json]";

/// The number after option `name`.
fn number<T: std::str::FromStr>(
    name: &str,
    it: &mut impl Iterator<Item = String>,
) -> Result<T, String> {
    let v = it
        .next()
        .ok_or_else(|| format!("{name} needs a value\n{USAGE}"))?;
    v.parse()
        .map_err(|_| format!("{name} {v}: not a valid number\n{USAGE}"))
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        problem: PathBuf::new(),
        photons: 2_000_000,
        half: 3,
        step: 0.25,
        bounces: TraceSettings::default().max_bounces,
        seed: None,
        around: None,
        json: false,
    };
    let mut it = std::env::args().skip(1);
    let mut problem = None;
    while let Some(a) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| format!("{name} needs a value\n{USAGE}"))
        };
        let bad = |name: &str, v: &str| format!("{name} {v}: not a valid number\n{USAGE}");
        match a.as_str() {
            "--photons" => args.photons = number("--photons", &mut it)?,
            "--half" => args.half = number("--half", &mut it)?,
            "--step" => args.step = number("--step", &mut it)?,
            "--bounces" => args.bounces = number("--bounces", &mut it)?,
            "--seed" => args.seed = Some(number("--seed", &mut it)?),
            "--around" => {
                let v = value("--around")?;
                let xy: Vec<f64> = v
                    .split(',')
                    .map(|c| c.trim().parse())
                    .collect::<Result<_, _>>()
                    .map_err(|_| bad("--around", &v))?;
                match xy[..] {
                    [x, y] => args.around = Some((x, y)),
                    _ => return Err(format!("--around {v}: expected X,Y\n{USAGE}")),
                }
            }
            "--json" => args.json = true,
            "-h" | "--help" => return Err(USAGE.to_string()),
            _ if problem.is_none() && !a.starts_with('-') => problem = Some(PathBuf::from(a)),
            _ => return Err(format!("unexpected argument {a}\n{USAGE}")),
        }
    }
    args.problem = problem.ok_or_else(|| USAGE.to_string())?;
    if args.photons == 0 || args.half < 0 || !args.step.is_finite() || args.step <= 0.0 {
        return Err(format!(
            "--photons and --step must be positive, --half not negative\n{USAGE}"
        ));
    }
    Ok(args)
}

/// The world positions of a surface's vertices.
fn vertices(scene: &Scene, s: SurfaceId) -> Vec<DVec3> {
    let mut out = Vec::new();
    for &i in &scene.surfaces[s].instances {
        let inst = &scene.instances[i];
        for &p in &scene.meshes[inst.mesh].positions {
            out.push(inst.transform.transform_point3(p).as_dvec3());
        }
    }
    out
}

/// The centre of the bounding box of `points`, and its half-extent.
fn bounds(points: &[DVec3]) -> (DVec3, DVec3) {
    let lo = points.iter().fold(DVec3::INFINITY, |m, &p| m.min(p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |m, &p| m.max(p));
    ((lo + hi) / 2.0, (hi - lo) / 2.0)
}

/// One traced cell.
/// Where a cell of the sweep puts the light: its centre, its (s, t) on the placement
/// rectangle, and whether part of it leaves the rectangle.
struct Place {
    centre: DVec2,
    s: f64,
    t: f64,
    clipped: bool,
}

struct Cell {
    centre: DVec2,
    p: DVec3,
    mean: f64,
    std_error: f64,
    clipped: bool,
}

fn main() {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2)
        }
    };
    if let Err(e) = run(&args) {
        eprintln!("error: {e}");
        std::process::exit(1)
    }
}

/// `--json`'s output.
#[derive(serde::Serialize)]
struct SweepReport {
    problem: String,
    light: String,
    light_centre_minus_p: [f64; 3],
    light_size: [f64; 2],
    target_centre: [f64; 3],
    photons_per_cell: u64,
    max_bounces: u32,
    seconds: f64,
    cells: Vec<SweepCell>,
    quadratic_maximum: Option<SweepFit>,
}

/// One cell of the sweep.
#[derive(serde::Serialize)]
struct SweepCell {
    centre: [f64; 2],
    #[serde(rename = "P")]
    p: [f64; 3],
    mean: f64,
    std_error: f64,
    clipped: bool,
}

/// The fitted maximum.
#[derive(serde::Serialize)]
struct SweepFit {
    centre: [f64; 2],
    std_error: [f64; 2],
    chi2_per_dof: f64,
}

fn run(args: &Args) -> Result<(), Box<dyn Error>> {
    let mut problem = Problem::read(&args.problem)?;
    let mut scene = problem.load_scene(&LoadOptions::default(), None, None, &[])?;
    let binding = Binding::new(&problem, &mut scene)?;
    let (k, rect) = match binding
        .specs
        .iter()
        .zip(binding.space.variables())
        .enumerate()
        .find(|(_, (spec, _))| matches!(spec.kind, VariableKind::LightInSurface(_)))
    {
        Some((k, (_, v))) => match &v.domain {
            Domain::Parallelogram(r) => (k, r.clone()),
            _ => return Err("the lightInSurface variable has no rectangle".into()),
        },
        None => return Err("the problem has no lightInSurface variable".into()),
    };
    let id = &binding.space.variables()[k].id;
    let light = scene
        .surface(id)
        .ok_or_else(|| format!("'{id}' is not an emissive object (a point light has no extent to sweep); this sweep moves objects"))?;
    let panel = vertices(&scene, light);
    let (panel_centre, panel_half) = bounds(&panel);
    let goal = binding
        .goal
        .surface()
        .ok_or("the problem's goal is about no surface")?;
    let goal_surface = scene
        .surface(&goal.name)
        .ok_or("the goal's surface is not in the scene")?;
    let (target, target_half) = bounds(&vertices(&scene, goal_surface));
    // The solver moves the light by P − A: its centre is at P + offset.
    let offset = panel_centre - rect.a;
    let seed = args.seed.unwrap_or(problem.seed);
    if !args.json {
        print_header(
            args,
            id,
            (offset, panel_half),
            (&goal.name, target, target_half),
            seed,
        );
    }

    // The grid, checked whole before anything is traced.
    let n = 2 * args.half + 1;
    let around = args.around.unwrap_or((target.x, target.y));
    let lift = DVec3::new(0.0, 0.0, panel_centre.z) - offset;
    let grid = lay_grid(args, &rect, &panel, lift, around)?;

    // Every other variable stays as authored; the light's (s, t) follow the coordinates
    // of the variables before it.
    let first: usize = binding.space.variables()[..k]
        .iter()
        .map(|v| v.domain.dimensions())
        .sum();
    let start = Instant::now();
    let mut cells = Vec::new();
    for (
        index,
        Place {
            centre,
            s,
            t,
            clipped,
        },
    ) in grid.into_iter().enumerate()
    {
        let mut config = binding.initial.clone();
        config.coords[first] = s;
        config.coords[first + 1] = t;
        let mut eval = PhotonEvaluator::new(
            &binding,
            scene.clone(),
            seed.wrapping_add(index as u64),
            args.bounces,
            args.photons,
        );
        let e = eval.evaluate(&config, args.photons)?.goal;
        cells.push(Cell {
            centre,
            p: rect.point(s, t),
            mean: e.mean,
            std_error: e.std_error,
            clipped,
        });
    }
    let seconds = start.elapsed().as_secs_f64();

    // The light poking through a wall puts a kink in the objective: the quadratic is
    // fitted to the cells where the light is whole.
    let whole: Vec<&Cell> = cells.iter().filter(|c| !c.clipped).collect();
    let fit = quadratic_maximum(&whole, seed);
    if args.json {
        let out = SweepReport {
            problem: args.problem.display().to_string(),
            light: id.clone(),
            light_centre_minus_p: offset.to_array(),
            light_size: [2.0 * panel_half.x, 2.0 * panel_half.y],
            target_centre: target.to_array(),
            photons_per_cell: args.photons,
            max_bounces: args.bounces,
            seconds,
            cells: cells.iter().map(Cell::swept).collect(),
            quadratic_maximum: fit.map(|f| f.swept()),
        };
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }

    print_table(&cells, n as usize, target, fit, whole.len());
    println!("{} cells in {seconds:.1} s", cells.len());
    Ok(())
}

/// What the sweep moves over what, printed above the table: the light, its size and
/// offset from P, the goal's surface and its extent, the photons and seeds.
fn print_header(
    args: &Args,
    id: &str,
    (offset, panel_half): (DVec3, DVec3),
    (goal, target, target_half): (&str, DVec3, DVec3),
    seed: u64,
) {
    println!(
        "{}: '{id}' ({:.2} m × {:.2} m, centre = P + ({:.3}, {:.3}, {:.3})) over '{}' \
         (centre ({:.3}, {:.3}, {:.3}), half-extent ({:.3}, {:.3}, {:.3}))",
        args.problem.display(),
        2.0 * panel_half.x,
        2.0 * panel_half.y,
        offset.x,
        offset.y,
        offset.z,
        goal,
        target.x,
        target.y,
        target.z,
        target_half.x,
        target_half.y,
        target_half.z,
    );
    println!(
        "{} photons a cell, at most {} bounces, seeds {seed}…; `*`: the light pokes out of its rectangle",
        args.photons, args.bounces
    );
}

/// The cells of the sweep, rows from +y to −y: each the light's centre around `(gx,
/// gy)`, its (s, t) on the placement rectangle `rect`, and whether part of the light's
/// `panel` leaves the rectangle there; `lift` takes a centre at height 0 to P (the
/// panel's height less the light's offset from A). Refused whole when a cell puts P
/// outside the rectangle.
fn lay_grid(
    args: &Args,
    rect: &Parallelogram,
    panel: &[DVec3],
    lift: DVec3,
    (gx, gy): (f64, f64),
) -> Result<Vec<Place>, Box<dyn Error>> {
    let mut grid = Vec::new();
    for j in (-args.half..=args.half).rev() {
        for i in -args.half..=args.half {
            let centre = DVec2::new(gx + i as f64 * args.step, gy + j as f64 * args.step);
            let p = DVec3::new(centre.x, centre.y, 0.0) + lift;
            let (s, t) = rect.coords(p);
            if !(0.0..=1.0).contains(&s) || !(0.0..=1.0).contains(&t) {
                return Err(format!(
                    "cell ({:.2}, {:.2}) puts P outside the placement rectangle; use a smaller --half or --step",
                    centre.x, centre.y
                )
                .into());
            }
            let delta = p - rect.a;
            let clipped = panel.iter().any(|&v| {
                let (s, t) = rect.coords(v + delta);
                !(-1e-6..=1.0 + 1e-6).contains(&s) || !(-1e-6..=1.0 + 1e-6).contains(&t)
            });
            grid.push(Place {
                centre,
                s,
                t,
                clipped,
            });
        }
    }
    Ok(grid)
}

/// The sweep as a table: rows from +y (top) to −y, columns from −x to +x, as seen from
/// above; each cell the light's centre with its offset from the target's centre, then
/// the best cell and the quadratic's maximum over the `whole` cells it was fitted to.
fn print_table(cells: &[Cell], n: usize, target: DVec3, fit: Option<Fit>, whole: usize) {
    print!("{:>14} |", "y \\ x");
    for c in &cells[..n] {
        let x = format!("{:.2} ({:+.2})", c.centre.x, c.centre.x - target.x);
        print!(" {x:>16}");
    }
    println!();
    for row in cells.chunks(n) {
        let y = format!(
            "{:.2} ({:+.2})",
            row[0].centre.y,
            row[0].centre.y - target.y
        );
        print!("{y:>14} |");
        for c in row {
            let mark = if c.clipped { '*' } else { ' ' };
            print!(" {:>7.4} ± {:.4}{mark}", c.mean, c.std_error);
        }
        println!();
    }
    let best = cells
        .iter()
        .max_by(|a, b| a.mean.total_cmp(&b.mean))
        .expect("the grid has a cell");
    println!(
        "best cell: centre ({:.2}, {:.2}) = P ({:.3}, {:.3}), {:.4} ± {:.4} lx; its offset from the target's centre: ({:+.2}, {:+.2}) m",
        best.centre.x,
        best.centre.y,
        best.p.x,
        best.p.y,
        best.mean,
        best.std_error,
        best.centre.x - target.x,
        best.centre.y - target.y
    );
    match fit {
        Some(f) => println!(
            "quadratic fit to the {} unmarked cells: maximum at ({:.3} ± {:.3}, {:.3} ± {:.3}), offset ({:+.3}, {:+.3}) m from the target's centre; χ²/dof {:.2}",
            whole,
            f.at.x,
            f.spread.x,
            f.at.y,
            f.spread.y,
            f.at.x - target.x,
            f.at.y - target.y,
            f.chi2_per_dof
        ),
        None => println!("quadratic fit: no maximum (the surface is not concave over the grid)"),
    }
}

impl Cell {
    /// The cell as `--json` writes it.
    fn swept(&self) -> SweepCell {
        SweepCell {
            centre: self.centre.to_array(),
            p: self.p.to_array(),
            mean: self.mean,
            std_error: self.std_error,
            clipped: self.clipped,
        }
    }
}

impl Fit {
    /// The fit as `--json` writes it.
    fn swept(&self) -> SweepFit {
        SweepFit {
            centre: self.at.to_array(),
            std_error: self.spread.to_array(),
            chi2_per_dof: self.chi2_per_dof,
        }
    }
}

/// The maximum of a weighted least-squares quadratic through the cells.
struct Fit {
    at: DVec2,
    spread: DVec2,
    chi2_per_dof: f64,
}

/// Fits z = c₀ + c₁x + c₂y + c₃x² + c₄xy + c₅y² (weights 1/σ²) and returns its
/// stationary point if it is a maximum; the spread is the standard deviation of that
/// point over 400 bootstrap fits, each to the cells redrawn as mean + σ·N(0, 1).
fn quadratic_maximum(cells: &[&Cell], seed: u64) -> Option<Fit> {
    if cells.len() < 6 {
        return None;
    }
    let origin = cells.iter().fold(DVec2::ZERO, |s, c| s + c.centre) / cells.len() as f64;
    let basis = |c: &&Cell| {
        let d = c.centre - origin;
        [1.0, d.x, d.y, d.x * d.x, d.x * d.y, d.y * d.y]
    };
    let fit = |z: &dyn Fn(usize) -> f64| -> Option<([f64; 6], f64)> {
        let mut a = [[0.0; 6]; 6];
        let mut b = [0.0; 6];
        for (k, c) in cells.iter().enumerate() {
            let w = 1.0 / (c.std_error * c.std_error);
            let f = basis(c);
            for r in 0..6 {
                b[r] += w * f[r] * z(k);
                for q in 0..6 {
                    a[r][q] += w * f[r] * f[q];
                }
            }
        }
        let coef = solve(a, b)?;
        let chi2 = cells
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let f = basis(c);
                let m: f64 = (0..6).map(|r| coef[r] * f[r]).sum();
                ((z(k) - m) / c.std_error).powi(2)
            })
            .sum::<f64>();
        Some((coef, chi2))
    };
    let stationary = |c: &[f64; 6]| -> Option<DVec2> {
        // ∇z = 0: [2c₃ c₄; c₄ 2c₅]·d = −[c₁; c₂]; a maximum if that matrix is negative
        // definite.
        let (h11, h12, h22) = (2.0 * c[3], c[4], 2.0 * c[5]);
        let det = h11 * h22 - h12 * h12;
        if !(h11 < 0.0 && det > 0.0) {
            return None;
        }
        Some(
            origin
                + DVec2::new(
                    (-c[1] * h22 + c[2] * h12) / det,
                    (c[1] * h12 - c[2] * h11) / det,
                ),
        )
    };
    let (coef, chi2) = fit(&|k| cells[k].mean)?;
    let at = stationary(&coef)?;
    let mut rng = SplitMix64::new(seed ^ 0x5EED);
    let mut sum = DVec2::ZERO;
    let mut sum_sq = DVec2::ZERO;
    let mut count = 0.0;
    for _ in 0..400 {
        let noise: Vec<f64> = cells.iter().map(|_| normal(&mut rng)).collect();
        let redrawn = |k: usize| cells[k].mean + cells[k].std_error * noise[k];
        if let Some(p) = fit(&redrawn).and_then(|(c, _)| stationary(&c)) {
            sum += p;
            sum_sq += p * p;
            count += 1.0;
        }
    }
    let mean = sum / count;
    let spread = (sum_sq / count - mean * mean).max(DVec2::ZERO);
    Some(Fit {
        at,
        spread: DVec2::new(spread.x.sqrt(), spread.y.sqrt()),
        chi2_per_dof: chi2 / (cells.len() - 6).max(1) as f64,
    })
}

/// A standard normal draw (Box–Muller).
fn normal(rng: &mut SplitMix64) -> f64 {
    let u1 = 1.0 - rng.next_f64();
    let u2 = rng.next_f64();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Solves a·x = b by Gaussian elimination with partial pivoting; None if singular.
fn solve(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> Option<[f64; 6]> {
    for col in 0..6 {
        let pivot = (col..6).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..6 {
            let f = a[row][col] / a[col][col];
            let pivot_row = a[col];
            for (x, p) in a[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let s: f64 = (row + 1..6).map(|q| a[row][q] * x[q]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    Some(x)
}
