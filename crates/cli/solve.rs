//! `invlight solve`: reads a problem file, loads its scene, runs the noisy VNS with
//! photon-traced estimates, and reports the ISOC. The files (`solutions.csv`,
//! `result.json`) are written as the search goes; Ctrl-C stops it cleanly and
//! `--resume` continues it. At the end (also after Ctrl-C) every ISOC member is
//! rendered (`isoc-NN.png`) and the visited configurations plotted (`search.png`).

mod images;

use crate::InputError;
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use invlight_ilp::{
    Binding, Interval, Isoc, ObjectiveInfo, Observer, Outcome, Output, PhotonEvaluator, Record,
    RunSettings, Search, Value, read_solutions,
};
use invlight_photon::{TraceSettings, z_two_sided};
use invlight_scene::LoadOptions;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

/// Raised by Ctrl-C; the search stops after the evaluation in progress (a second
/// Ctrl-C exits at once).
static STOP: AtomicBool = AtomicBool::new(false);

/// Solve an inverse lighting problem: search the free variables of a problem file for
/// the configurations that light its surface best.
///
/// The problem file is ILPSolver's XML format (docs/problem-file.md). Results go to the
/// output folder as the search goes: solutions.csv (one row per photon trace) and
/// result.json (the best configurations, rewritten whenever they change). Ctrl-C stops
/// cleanly; --resume continues from solutions.csv. At the end, isoc-01.png, isoc-02.png,
/// … render the ISOC's configurations from the scene's camera and search.png plots the
/// configurations evaluated.
#[derive(clap::Args, Debug)]
pub struct SolveArgs {
    /// The problem file (.xml).
    pub problem: PathBuf,
    /// Folder for solutions.csv and result.json [default: the problem's <output path>,
    /// relative to the problem file].
    #[arg(long, short, value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Photons of a full evaluation, N [default: the problem's `photons`, else 100000];
    /// every evaluation traces whole groups of 64 photons, at least 2048.
    #[arg(long, value_name = "N")]
    pub photons: Option<u64>,
    /// Candidates the search draws before it stops, cache hits included [default: the
    /// problem's maxIterations, else 1000].
    #[arg(long, value_name = "K")]
    pub iterations: Option<u64>,
    /// Seed of the photons and of the search [default: the problem's `seed`, else 1].
    /// The same seed, photon count and problem give the same solutions.csv on any
    /// number of threads.
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,
    /// Bounces per photon path; Russian roulette ends paths without bias, this only
    /// bounds them [default: the problem's `maxBounces`, else the tracer's].
    #[arg(long, value_name = "K")]
    pub max_bounces: Option<u32>,
    /// Confidence of the intervals and comparisons, in (0, 1) [default: the problem's
    /// `confidence`, else 0.95].
    #[arg(long, value_name = "C")]
    pub confidence: Option<f64>,
    /// Print result.json's content instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Continue a stopped run from the output folder's solutions.csv: evaluated cells
    /// are not traced again.
    #[arg(long)]
    pub resume: bool,
    /// Worker threads [default: one per core].
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Width of the ISOC pictures, pixels; the height follows the camera's aspect.
    #[arg(long, default_value_t = 480, value_name = "W")]
    pub image_width: u32,
    /// Photons of each ISOC picture's photon map (its indirect light).
    #[arg(long, default_value_t = 300_000, value_name = "N")]
    pub image_photons: u64,
    /// Write neither the ISOC pictures nor search.png.
    #[arg(long)]
    pub no_images: bool,
}

fn input(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow::Error::new(InputError(e.to_string()))
}

/// Runs `invlight solve`.
pub fn run(args: SolveArgs) -> Result<()> {
    // 1. The problem, with command-line overrides.
    let mut problem = invlight_ilp::Problem::read(&args.problem).map_err(input)?;
    for w in &problem.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(n) = args.photons {
        if n == 0 {
            return Err(input("--photons must be positive"));
        }
        problem.photons = n;
    }
    if let Some(k) = args.iterations {
        problem.max_iterations = k;
    }
    if let Some(s) = args.seed {
        problem.seed = s;
    }
    if let Some(c) = args.confidence {
        if !(c > 0.0 && c < 1.0) {
            return Err(input(format!(
                "--confidence is {c}, expected a number in (0, 1)"
            )));
        }
        problem.confidence = c;
    }
    let max_bounces = args
        .max_bounces
        .or(problem.max_bounces)
        .unwrap_or(TraceSettings::default().max_bounces);

    // 2. The scene, bound to the problem.
    let mut scene = invlight_scene::load(&problem.scene, &LoadOptions::default())
        .with_context(|| format!("loading the scene of {}", args.problem.display()))?;
    let binding = Binding::new(&problem, &mut scene).map_err(input)?;
    for w in &binding.warnings {
        eprintln!("warning: {w}");
    }
    if !args.no_images && !(1..=16384).contains(&args.image_width) {
        return Err(input(format!(
            "--image-width {} must be between 1 and 16384 pixels",
            args.image_width
        )));
    }
    // The evaluator owns and changes its scene; the pictures start from this copy.
    let pictured = (!args.no_images).then(|| scene.clone());
    let settings = problem.settings();
    let z = z_two_sided(problem.confidence);

    // 3. Output, resuming if asked.
    let dir = args
        .output
        .clone()
        .unwrap_or_else(|| problem.output.clone());
    let csv = dir.join("solutions.csv");
    let run = RunSettings::new(&settings, max_bounces);
    let resumed = if args.resume && csv.is_file() {
        run.check_resume(&dir).map_err(input)?;
        Some(read_solutions(&csv, &binding, z).map_err(input)?)
    } else {
        if args.resume {
            eprintln!("note: no {} to resume; starting afresh", csv.display());
        }
        None
    };
    let mut search = Search::new(&binding.space, settings, &binding.initial);
    if let Some((records, _)) = &resumed {
        search.replay(records);
        eprintln!(
            "resuming after {} evaluations (iteration {})",
            records.len(),
            search.iteration()
        );
    }
    let info = ObjectiveInfo {
        surface: problem.objective.surface.clone(),
        cap: problem.objective.cap,
        photons: problem.photons,
    };
    let output = Output::create(
        &dir,
        &binding,
        info,
        z,
        resumed.as_ref().map(|(r, _)| r.as_slice()),
        resumed.as_ref().map_or(0.0, |(_, e)| *e),
    )
    .with_context(|| format!("creating the output folder {}", dir.display()))?;
    run.write(&dir)
        .with_context(|| format!("writing run.json in {}", dir.display()))?;

    // 4. Search, on a pool of the requested size, until done or Ctrl-C.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("starting the worker threads")?;
    let mut eval = PhotonEvaluator::new(&binding, scene, problem.seed, max_bounces);
    STOP.store(false, Ordering::Relaxed);
    // The first Ctrl-C stops after the evaluation in progress; a second one exits at
    // once, which is safe too: every row is flushed as written and result.json is
    // replaced atomically. A second handler cannot be installed in the same process;
    // the first one sets the same flag, so that error is harmless.
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
    });
    let mut reporter = Reporter {
        output,
        bar: progress_bar(problem.max_iterations, search.iteration()),
        z,
        records: resumed.map(|(r, _)| r).unwrap_or_default(),
    };
    let outcome = pool
        .install(|| search.run(&mut eval, &mut reporter, &STOP))
        .with_context(|| format!("writing to {}", dir.display()))?;
    reporter.bar.finish_and_clear();
    reporter
        .output
        .write_result(search.isoc())
        .with_context(|| format!("writing {}", dir.join("result.json").display()))?;

    let (rays, photons) = eval.work();
    let secs = reporter.output.elapsed();

    // 5. Pictures of the ISOC and of the search.
    if let Some(scene) = &pictured {
        let members: Vec<_> = search
            .isoc()
            .by_mean()
            .into_iter()
            .map(|m| m.config.clone())
            .collect();
        let start = std::time::Instant::now();
        let settings = images::ImageSettings {
            width: args.image_width,
            photons: args.image_photons,
            samples: 2,
            seed: problem.seed,
            max_bounces,
        };
        let mut written =
            pool.install(|| images::write_isoc_images(&dir, scene, &binding, &members, &settings))?;
        written.extend(images::write_search_plots(
            &dir,
            &binding,
            &reporter.records,
            search.isoc(),
            z,
        )?);
        eprintln!(
            "{} pictures in {:.1} s",
            written.len(),
            start.elapsed().as_secs_f64()
        );
    }

    // 6. Report.
    match outcome {
        Outcome::Interrupted => eprintln!(
            "interrupted: the files are complete up to the last evaluation; continue with --resume"
        ),
        Outcome::Exhausted => eprintln!("every cell was evaluated"),
        Outcome::Finished => {}
    }
    eprintln!(
        "{} evaluations, {photons} photons, {rays} rays in {secs:.1} s; results in {}",
        search.evaluations(),
        dir.display()
    );
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&reporter.output.result_json(search.isoc()))?
        );
    } else {
        print_table(
            &binding,
            search.isoc(),
            &problem.objective.surface,
            problem.confidence,
        );
    }
    Ok(())
}

/// Forwards the search's reports to the files and the progress bar.
struct Reporter<'b> {
    output: Output<'b>,
    bar: ProgressBar,
    z: f64,
    /// Every evaluation so far, for search.png.
    records: Vec<Record>,
}

impl Observer for Reporter<'_> {
    fn evaluated(&mut self, record: &Record, isoc: &Isoc, changed: bool) -> std::io::Result<()> {
        self.output.evaluated(record, isoc, changed)?;
        self.records.push(record.clone());
        if let Some(best) = best(isoc) {
            let i = Interval::of(&best.estimate, self.z);
            self.bar.set_message(format!(
                "best {} lx [{}, {}], ISOC of {}",
                sig(best.estimate.mean),
                sig(i.low),
                sig(i.high),
                isoc.members().len()
            ));
        }
        Ok(())
    }

    fn iteration(&mut self, iteration: u64) {
        self.bar.set_position(iteration);
    }
}

/// The first of the highest-mean members, as `Isoc::by_mean` orders them, without
/// sorting (this runs after every evaluation).
fn best(isoc: &Isoc) -> Option<&invlight_ilp::Member> {
    isoc.members()
        .iter()
        .min_by(|a, b| b.estimate.mean.total_cmp(&a.estimate.mean))
}

/// A bar over the iterations on stderr, hidden when stderr is not a terminal.
fn progress_bar(total: u64, start: u64) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    if !std::io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::hidden());
    }
    bar.set_style(
        ProgressStyle::with_template("[{elapsed_precise}] {bar:30} {pos}/{len} iterations  {msg}")
            .expect("the template is valid"),
    );
    bar.set_position(start);
    bar
}

/// Four significant digits, in plain or scientific notation as the size asks.
fn sig(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e5).contains(&a) {
        format!("{x:.3e}")
    } else {
        let decimals = if a == 0.0 {
            0
        } else {
            (3 - a.log10().floor() as i32).max(0) as usize
        };
        format!("{x:.decimals$}")
    }
}

/// The ISOC, best mean first.
fn print_table(binding: &Binding, isoc: &Isoc, surface: &str, confidence: f64) {
    let members = isoc.by_mean();
    println!(
        "{} configuration(s) light '{surface}' best, indistinguishable at {} % confidence:",
        members.len(),
        confidence * 100.0
    );
    for (k, m) in members.iter().enumerate() {
        let i = Interval::of(&m.estimate, isoc.z());
        let vars: Vec<String> = binding
            .space
            .variables()
            .iter()
            .zip(binding.values(&m.config))
            .map(|(v, value)| match value {
                Value::Position(p) => {
                    format!("{} at ({}, {}, {})", v.id, sig(p.x), sig(p.y), sig(p.z))
                }
                Value::Direction(d) => {
                    format!("{} along ({}, {}, {})", v.id, sig(d.x), sig(d.y), sig(d.z))
                }
                Value::Color { value, .. } => format!("{} V = {}", v.id, sig(value)),
            })
            .collect();
        println!(
            "{:>3}. {} lx [{}, {}]  {}",
            k + 1,
            sig(m.estimate.mean),
            sig(i.low),
            sig(i.high),
            vars.join(", ")
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn args(problem: &str, out: &Path) -> SolveArgs {
        SolveArgs {
            problem: Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("tests/data/ilp")
                .join(problem),
            output: Some(out.to_path_buf()),
            photons: Some(8000),
            iterations: Some(40),
            seed: None,
            max_bounces: None,
            confidence: None,
            json: false,
            resume: false,
            threads: Some(2),
            image_width: 64,
            image_photons: 2000,
            no_images: true,
        }
    }

    fn rows(out: &Path) -> Vec<String> {
        std::fs::read_to_string(out.join("solutions.csv"))
            .unwrap()
            .lines()
            .map(String::from)
            .collect()
    }

    /// The PNG files in `out`, by name, with their sizes.
    fn pngs(out: &Path) -> Vec<(String, (u32, u32))> {
        let mut found: Vec<_> = std::fs::read_dir(out)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "png"))
            .map(|p| {
                let size = invlight_render::image::image_dimensions(&p).unwrap();
                (p.file_name().unwrap().to_string_lossy().into_owned(), size)
            })
            .collect();
        found.sort();
        found
    }

    /// Solving writes a row per evaluation, a result.json, a picture per ISOC member
    /// and search.png; --resume goes on from the rows without tracing a cell twice; an
    /// interruption leaves valid files; --no-images writes no picture.
    /// (One test: Ctrl-C's flag is process-wide.)
    #[test]
    fn solve_resume_and_interrupt() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let mut with_images = args("lamp-room.xml", &out);
        with_images.no_images = false;
        run(with_images).unwrap();
        let first = rows(&out);
        assert_eq!(
            first[0],
            "iteration,Lamp.x,Lamp.y,Lamp.z,low,mean,high,photons,seconds,elapsed,verdict"
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("result.json")).unwrap())
                .unwrap();
        assert_eq!(json["evaluations"].as_u64(), Some(first.len() as u64 - 1));
        assert_eq!(json["objective"]["surface"], "Desk");
        assert!(!json["isoc"].as_array().unwrap().is_empty());
        // The lamp room has no camera: the default view is 4:3, 64×48 pixels (of the
        // closed room from outside, so dark: the check is of the files, not the light).
        let members = json["isoc"].as_array().unwrap().len();
        let mut expected: Vec<_> = (1..=members)
            .map(|k| (format!("isoc-{k:02}.png"), (64, 48)))
            .collect();
        expected.push(("search.png".to_string(), invlight_render::PLOT_SIZE));
        assert_eq!(pngs(&out), expected);

        let mut more = args("lamp-room.xml", &out);
        more.iterations = Some(120);
        more.resume = true;
        run(more).unwrap();
        let second = rows(&out);
        assert!(second.len() > first.len());
        assert_eq!(second[..first.len()], first[..]);
        let mut traced = std::collections::HashSet::new();
        for (i, r) in second[1..].iter().enumerate() {
            let c: Vec<&str> = r.split(',').collect();
            let key = c[1..4].join(",");
            let refined = i > 0 && second[i].ends_with(",refine");
            assert!(traced.insert(key) || refined, "cell traced twice: {r}");
        }
        // Rows traced with another seed cannot be continued: an input error that names
        // the setting, and the folder is left as it was.
        let mut other = args("lamp-room.xml", &out);
        other.resume = true;
        other.seed = Some(99);
        let err = run(other).unwrap_err();
        let text = format!("{err:#}");
        assert!(
            text.contains("seed 99") && text.contains("cannot resume"),
            "{text}"
        );
        assert!(err.chain().any(|e| e.is::<InputError>()), "{text}");
        assert_eq!(rows(&out), second);

        // Interrupt a long run once it has written a few rows.
        let out2 = dir.path().join("interrupted");
        let watch = out2.join("solutions.csv");
        let stopper = std::thread::spawn(move || {
            for _ in 0..2000 {
                let n = std::fs::read_to_string(&watch).map_or(0, |s| s.lines().count());
                if n > 4 {
                    STOP.store(true, Ordering::Relaxed);
                    return;
                }
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        });
        let mut long = args("lamp-room.xml", &out2);
        long.iterations = Some(100_000);
        run(long).unwrap();
        stopper.join().unwrap();
        let cut = rows(&out2);
        assert!(cut.len() > 4 && cut.len() < 1000, "{} rows", cut.len());
        assert!(cut.iter().all(|r| r.split(',').count() == 11));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out2.join("result.json")).unwrap())
                .unwrap();
        assert_eq!(json["evaluations"].as_u64(), Some(cut.len() as u64 - 1));
        assert!(pngs(&out2).is_empty(), "--no-images wrote pictures");
    }

    #[test]
    fn bad_input_is_an_input_error() {
        let dir = tempfile::tempdir().unwrap();
        let err = run(args("no-such-problem.xml", dir.path())).unwrap_err();
        assert!(err.chain().any(|e| e.is::<InputError>()), "{err:#}");
        let mut a = args("lamp-room.xml", dir.path());
        a.confidence = Some(1.5);
        let err = run(a).unwrap_err();
        assert!(format!("{err:#}").contains("--confidence"), "{err:#}");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(sig(165.23), "165.2");
        assert_eq!(sig(0.5022), "0.5022");
        assert_eq!(sig(0.0003), "3.000e-4");
        assert_eq!(sig(0.0), "0");
        assert_eq!(sig(123456.0), "1.235e5");
    }
}
