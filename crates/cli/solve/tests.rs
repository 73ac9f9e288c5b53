//! `invlight solve` in-process on the lamp room of `tests/data/ilp` (one lamp on a
//! ceiling over a desk): the files it writes, resuming, refusing and replacing an
//! earlier run, its pictures.

use super::*;
use clap::Parser;
use invlight_ilp::ResultFile;
use std::collections::HashSet;
use std::path::Path;

fn args(out: &Path) -> SolveArgs {
    SolveArgs {
        problem: Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ilp/lamp-room.xml"),
        output: Some(out.to_path_buf()),
        iterations: Some(40),
        strategy: None,
        trace: TraceArgs {
            photons: Some(8000),
            threads: Some(2),
            ..TraceArgs::default()
        },
        load: LoadArgs::default(),
        json: false,
        resume: false,
        force: false,
        image_width: 64,
        image_photons: 2000,
        no_images: true,
        no_report: true,
        report: ReportArgs {
            task: None,
            em: None,
            u0: None,
            maintenance_factor: None,
        },
        grid: GridArgs {
            report_photons: Some(20_000),
        },
    }
}

/// The rows without their timing columns (seconds, elapsed).
fn untimed(rows: &[String]) -> Vec<String> {
    rows.iter()
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            let n = c.len();
            [&c[..n - 3], &c[n - 1..]].concat().join(",")
        })
        .collect()
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

/// Solving writes a row per evaluation, result.json and a picture per ISOC member;
/// --resume goes on from the rows without tracing a cell twice and leaves no picture
/// of the earlier ISOC; a folder holding a run is refused without --resume or --force,
/// and --force replaces it. It runs the thesis' `REFINE_ISOC_ON_INTERSECTION`, where a
/// cell has a second row only as its refinement right after the first, so a cell
/// traced twice shows; the default race writes more rows per cell (its screening,
/// looks and race).
#[test]
fn solve_resume_refuse_and_replace() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let args = |out: &Path| SolveArgs {
        strategy: Some(Strategy::RefineOnIntersection),
        ..args(out)
    };
    let mut first_args = args(&out);
    first_args.no_images = false;
    first_args.no_report = false;
    first_args.report.task = Some("office".into());
    assert_eq!(run(first_args).unwrap(), ExitCode::SUCCESS);
    // The report: the answer, the desk's grid and its compliance stated.
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        page.contains("Light on Desk") && page.contains("EN 12464-1:2021"),
        "{page:.2000}"
    );
    assert!(invlight_report::external_references(&page).is_empty());
    assert!(
        page.contains("The search stopped: maxIterations candidates drawn."),
        "{page:.2000}"
    );
    let first = rows(&out);
    assert_eq!(
        first[0],
        "iteration,Lamp.x,Lamp.y,Lamp.z,Lamp.anchor.x,Lamp.anchor.y,Lamp.anchor.z,low,mean,high,std_error,photons,seconds,elapsed,verdict"
    );
    let result = ResultFile::read(&out.join("result.json")).unwrap();
    assert_eq!(result.evaluations, first.len() as u64 - 1);
    assert_eq!(result.objective.surface.as_deref(), Some("Desk"));
    // The lamp room has no camera: the default view is 4:3, 64×48 pixels, and a
    // caption under it.
    let mut expected: Vec<_> = (1..=result.isoc.len())
        .map(|k| format!("isoc-{k:02}.png"))
        .collect();
    expected.push("search.png".to_string());
    let got = pngs(&out);
    assert_eq!(
        got.iter().map(|p| p.0.clone()).collect::<Vec<_>>(),
        expected
    );
    for (name, (w, h)) in got {
        match name.as_str() {
            "search.png" => assert_eq!((w, h), invlight_render::PLOT_SIZE),
            _ => assert!(w == 64 && h > 48, "{name}: {w}×{h}"),
        }
    }
    // A picture of a larger earlier ISOC must not survive the next run's pictures.
    std::fs::write(out.join("isoc-99.png"), b"stale").unwrap();

    let err = run(args(&out)).unwrap_err();
    assert!(crate::is_input(&err), "{err:#}");
    assert!(format!("{err:#}").contains("--force"), "{err:#}");
    assert_eq!(
        rows(&out),
        first,
        "a refused run leaves the folder as it was"
    );

    let mut more = args(&out);
    more.iterations = Some(120);
    more.resume = true;
    more.no_images = false;
    run(more).unwrap();
    let second = rows(&out);
    assert!(second.len() > first.len());
    assert_eq!(second[..first.len()], first[..]);
    let mut traced = HashSet::new();
    for (i, r) in second[1..].iter().enumerate() {
        let c: Vec<&str> = r.split(',').collect();
        let refined = i > 0 && second[i].ends_with(",refine");
        assert!(
            traced.insert(c[1..4].join(",")) || refined,
            "cell traced twice: {r}"
        );
    }
    assert!(!out.join("isoc-99.png").exists());
    // Rows traced with another seed cannot be continued: an input error that names
    // the setting, and the folder is left as it was.
    let mut other = args(&out);
    other.resume = true;
    other.trace.seed = Some(99);
    let err = run(other).unwrap_err();
    let text = format!("{err:#}");
    assert!(
        text.contains("seed 99") && text.contains("cannot resume"),
        "{text}"
    );
    assert!(crate::is_input(&err), "{text}");
    assert_eq!(rows(&out), second);

    let mut replace = args(&out);
    replace.force = true;
    run(replace).unwrap();
    assert_eq!(
        untimed(&rows(&out)),
        untimed(&first),
        "the same seed and budget give the same rows"
    );
    assert!(
        pngs(&out).is_empty(),
        "the earlier run's pictures went with it"
    );
}

#[test]
fn bad_input_is_an_input_error() {
    let dir = tempfile::tempdir().unwrap();
    let mut missing = args(dir.path());
    missing.problem = dir.path().join("no-such-problem.xml");
    let err = run(missing).unwrap_err();
    assert!(
        err.chain().any(|e| e.is::<invlight_scene::Diagnostic>()),
        "{err:#}"
    );
    let mut a = args(dir.path());
    a.trace.photons = Some(u64::MAX);
    let err = run(a).unwrap_err();
    assert!(format!("{err:#}").contains("--photons"), "{err:#}");
}

/// `--strategy PAIRED_ISOC` and `RACE_ISOC_ON_END`: the same `solutions.csv`
/// on 1 and 2 threads (the groups paired are the same photons whatever the thread
/// count), the strategy kept in run.json, and why the search stopped in result.json.
/// The race runs on examples/cornell-cone, whose flat top keeps many members: with
/// n = 2 048 and N = 40 000 photons its ISOC is looked at with 8 192 and 32 768 first.
#[test]
fn paired_search_is_the_same_on_any_thread_count_and_says_why_it_stopped() {
    let dir = tempfile::tempdir().unwrap();
    let cone = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cornell-cone/problem.xml");
    for strategy in [Strategy::Paired, Strategy::RaceOnEnd] {
        let mut runs = Vec::new();
        for threads in [1, 2] {
            let out = dir.path().join(format!("{}-{threads}", strategy.name()));
            let mut a = args(&out);
            a.iterations = Some(200);
            a.strategy = Some(strategy);
            a.trace.threads = Some(threads);
            if strategy == Strategy::RaceOnEnd {
                a.problem = cone.clone();
                a.iterations = Some(120);
                a.trace.photons = Some(40_000);
            }
            assert_eq!(run(a).unwrap(), ExitCode::SUCCESS);
            let result = ResultFile::read(&out.join("result.json")).unwrap();
            let stopped = result.stopped.expect("a finished search says why");
            assert!(
                stopped.starts_with("decided") || stopped.starts_with("maxIterations"),
                "{stopped}"
            );
            let run_file = std::fs::read_to_string(out.join("run.json")).unwrap();
            assert!(run_file.contains(strategy.name()), "{run_file}");
            runs.push(untimed(&rows(&out)));
        }
        if strategy == Strategy::RaceOnEnd {
            let look = |photons: &str, verdict: &str| {
                runs[0]
                    .iter()
                    .filter(|r| r.contains(photons) && r.ends_with(verdict))
                    .count()
            };
            assert!(look(",8192,", ",beaten") > 0, "nobody raced out at 4n");
            assert!(look(",32768,", ",refine") > 1);
            assert_eq!(look(",32768,", ",refine"), look(",40000,", ",final"));
        }
        assert_eq!(runs[0], runs[1], "{}", strategy.name());
    }
}

/// `--luminaire` files reach run.json as given, where they were found and with their
/// multiplier, and `--resume` refuses a folder whose lamp emitted another file, even one
/// of the same name in another folder (its rows would mix two lamps' light).
#[test]
fn run_json_records_the_luminaire_flags_and_resume_checks_them() {
    let dir = tempfile::tempdir().unwrap();
    let photometry = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/photometry");
    for (folder, file) in [("a", "downlight.ldt"), ("b", "batwing.ldt")] {
        std::fs::create_dir(dir.path().join(folder)).unwrap();
        let to = dir.path().join(folder).join("lamp.ldt");
        std::fs::copy(photometry.join(file), to).unwrap();
    }
    let out = dir.path().join("out");
    let with = |folder: &str| {
        let mut a = args(&out);
        let given = dir.path().join(folder).join("lamp.ldt");
        a.load.luminaire = vec![format!("Lamp={}", given.display()).parse().unwrap()];
        a
    };
    assert_eq!(run(with("a")).unwrap(), ExitCode::SUCCESS);
    let run_file: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("run.json")).unwrap()).unwrap();
    let lamp = &run_file["luminaires"][0];
    let given = dir.path().join("a/lamp.ldt");
    assert_eq!(lamp["light"], "Lamp", "{run_file:#}");
    assert_eq!(lamp["file"], given.display().to_string(), "{run_file:#}");
    let found = given.canonicalize().unwrap();
    assert_eq!(lamp["path"], found.display().to_string(), "{run_file:#}");
    assert_eq!(lamp["multiplier"], 1.0, "{run_file:#}");

    let rows_before = rows(&out);
    let mut other = with("b");
    other.resume = true;
    let err = run(other).unwrap_err();
    let text = format!("{err:#}");
    assert!(crate::is_input(&err), "{text}");
    assert!(
        text.contains("cannot resume")
            && text.contains("luminaires")
            && text.contains("b/lamp.ldt"),
        "{text}"
    );
    assert_eq!(rows(&out), rows_before, "a refused resume leaves the rows");
    let mut same = with("a");
    same.resume = true;
    same.iterations = Some(60);
    assert_eq!(run(same).unwrap(), ExitCode::SUCCESS);
}

/// The command lines of `text` that follow "…: invlight ", cut at " (" or at "," as
/// the message puts its remarks after them, split into words.
fn commands(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter_map(|l| l.split_once(": invlight ").map(|(_, c)| c))
        .map(|c| {
            let c = c.split(" (").next().unwrap().split(", ").next().unwrap();
            std::iter::once("invlight")
                .chain(c.split(' '))
                .map(|w| w.replace("#K", "#1").replace("-K", "-1"))
                .collect()
        })
        .collect()
}

/// A second Ctrl-C while the pictures are written says which files the folder holds,
/// which were left, and commands that finish the job, which the program accepts as
/// written (with the solve's report flags passed on); during the search it says how to
/// go on; while writing report.html only the report is left.
#[test]
fn a_second_ctrl_c_says_what_is_left_and_how_to_finish() {
    let state = |phase| finishing::Finishing {
        phase,
        problem: "rooms/problem.xml".into(),
        dir: "rooms/out".into(),
        pictures: 3,
        report: true,
        report_flags: vec!["--task".into(), "office".into()],
        scene_flags: false,
    };
    let folder: Vec<String> = ["run.json", "solutions.csv", "result.json", "isoc-01.png"]
        .map(String::from)
        .to_vec();
    let text = state(Phase::Pictures).second_ctrl_c(&folder);
    for words in [
        "while writing the ISOC pictures",
        "written in rooms/out: solutions.csv, result.json, run.json, isoc-01.png",
        "not written: isoc-02.png, isoc-03.png, the search plots (search.png), report.html",
        "invlight report rooms/out --task office",
        "invlight render rooms/problem.xml --config rooms/out/result.json#K",
    ] {
        assert!(text.contains(words), "{words:?} in\n{text}");
    }
    assert!(!text.contains("--resume"), "{text}");
    let found = commands(&text);
    assert_eq!(found.len(), 2, "{text}");
    for command in &found {
        if let Err(e) = crate::Cli::try_parse_from(command) {
            panic!("{command:?} is not a command the program takes: {e}");
        }
    }

    let text = state(Phase::Searching).second_ctrl_c(&folder);
    assert!(text.contains("during the search"), "{text}");
    assert!(
        text.contains("written in rooms/out: solutions.csv, result.json, run.json ("),
        "an earlier run's pictures are not this one's: {text}"
    );
    assert!(
        text.contains("invlight solve rooms/problem.xml --output rooms/out --resume"),
        "{text}"
    );
    for command in &commands(&text) {
        if let Err(e) = crate::Cli::try_parse_from(command) {
            panic!("{command:?} is not a command the program takes: {e}");
        }
    }

    let mut all = folder.clone();
    all.extend(["isoc-02.png", "isoc-03.png", "search.png"].map(String::from));
    let text = state(Phase::Report).second_ctrl_c(&all);
    assert!(text.contains("not written: report.html\n"), "{text}");
    assert!(!text.contains("invlight render"), "{text}");

    let mut quiet = state(Phase::Report);
    quiet.dir = "my rooms/out".into();
    quiet.scene_flags = true;
    let text = quiet.second_ctrl_c(&all);
    assert!(
        text.contains("invlight report 'my rooms/out' --task office, with the scene flags"),
        "{text}"
    );
    assert_eq!(state(Phase::Searching).first_ctrl_c(), None);
    let first = state(Phase::Pictures).first_ctrl_c().unwrap();
    assert!(first.contains("Ctrl-C again"), "{first}");
}
