//! The files of a run: written as a search goes, read back into the same search, and
//! cut back to what was complete when something goes wrong.

use super::*;
use crate::Configuration;
use crate::binding::{Layout, LuminaireUse};
use crate::problem::Problem;
use crate::vns::{Evaluate, Evaluation, Search, Sense, Settings, Strategy, Verdict};
use glam::{Mat4, Vec3};
use invlight_scene::{Light, LightKind, Material, Mesh, Scene};
use invlight_stats::{Confidence, Estimate};
use std::collections::BTreeMap;
use std::io::Write;

struct Bowl;
impl Evaluate for Bowl {
    type Error = ();
    fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Evaluation, ()> {
        let x = &c.coords;
        Ok(Evaluation::of(Estimate {
            mean: 10.0 - (x[0] - 0.3).powi(2) - (x[2] - 0.6).powi(2) - x[3],
            std_error: 0.01,
            samples: photons,
        }))
    }
}

/// A floor that moves on itself (id "Floor, left": a comma the CSV must quote), a sun
/// and a colour.
fn binding() -> (Binding, Scene) {
    let mut s = Scene::default();
    let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let floor = s.add_mesh(Mesh::quad(
        [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(0.0, 0.0, -1.0),
        ],
        grey,
    ));
    s.add_instance("Floor, left", floor, Mat4::IDENTITY);
    s.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: -Vec3::Y,
            illuminance: Vec3::ONE,
        },
    });
    let p = Problem::parse(
        Path::new("/p/x.xml"),
        "<input><scene path=\"s.gltf\"/><conditions meshSize=\"10\"><objectInSurface id=\"Floor, left\" surface=\"Floor, left\"/><directionalLight id=\"Sun\"/><color id=\"Grey\" hue=\"30\" saturation=\"0.5\"/></conditions><objectives><maximizeRadiance surface=\"Floor, left\" maxRadiosity=\"9.5\"/></objectives></input>",
    )
    .unwrap();
    (Binding::new(&p, &mut s).unwrap(), s)
}

fn settings() -> Settings {
    Settings {
        max_iterations: 60,
        photons: 1000,
        fast_quality: 0.25,
        strategy: Strategy::RefineOnIntersection,
        confidence: Confidence::DEFAULT,
        cap: Some(9.5),
        sense: Sense::Maximize,
        constraints: Vec::new(),
        seed: 4,
        tries_per_radius: None,
    }
}

fn info() -> ObjectiveInfo {
    ObjectiveInfo {
        element: "maximizeRadiance".into(),
        surface: Some("Floor, left".into()),
        side: "both".into(),
        sense: "maximize".into(),
        unit: "lx".into(),
        cap: Some(9.5),
        target: None,
        problem: None,
    }
}

fn fresh(replace: bool) -> Start {
    Start::Fresh { replace }
}

/// Runs the bowl search into `dir`.
fn run_into(dir: &Path, b: &Binding) -> u64 {
    let mut search = Search::new(&b.space, settings(), &b.initial);
    let mut out = Output::create(dir, b, info(), &settings(), 7, &fresh(false)).unwrap();
    search.run(&mut Bowl, &mut out).unwrap();
    search.evaluations()
}

#[test]
fn csv_and_json_round_trip() {
    let (b, _) = binding();
    assert_eq!(
        csv_line(csv_header(&b)),
        "iteration,\"Floor, left.x\",\"Floor, left.y\",\"Floor, left.z\",\"Floor, left.anchor.x\",\"Floor, left.anchor.y\",\"Floor, left.anchor.z\",Sun.x,Sun.y,Sun.z,Grey.value,low,mean,high,std_error,photons,seconds,elapsed,verdict\n"
    );
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let mut search = Search::new(&b.space, settings(), &b.initial);
    {
        let mut out = Output::create(dir, &b, info(), &settings(), 7, &fresh(false)).unwrap();
        search.run(&mut Bowl, &mut out).unwrap();
    }
    // A hard stop mid-row: the partial row is ignored, then cut off on resuming.
    let csv = dir.join("solutions.csv");
    let mut f = OpenOptions::new().append(true).open(&csv).unwrap();
    write!(f, "999,0.5,0.").unwrap();
    drop(f);
    let rows = Solutions::read(&csv, &b).unwrap();
    assert_eq!(rows.records.len() as u64, search.evaluations());
    let start = Start::Resume(rows.clone());
    let resumed = Output::create(dir, &b, info(), &settings(), 7, &start).unwrap();
    assert!(resumed.elapsed() >= rows.elapsed);
    drop(resumed);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.ends_with('\n'));
    assert_eq!(text.lines().count(), rows.records.len() + 1);
    assert!(
        rows.records.iter().any(|r| r.verdict == Verdict::Invalid),
        "cap 9.5"
    );
    // The rows rebuild the same ISOC, estimates exactly (std_error is stored).
    let mut again = Search::new(&b.space, settings(), &b.initial);
    again.replay(&rows.records);
    assert_eq!(again.isoc().members(), search.isoc().members());
    // result.json reads back into the same members, and each member maps back to its
    // configuration.
    let result = ResultFile::read(&dir.join("result.json")).unwrap();
    assert_eq!(result.schema_version, RESULT_SCHEMA);
    assert_eq!(result.objective.cap, Some(9.5));
    assert_eq!(result.isoc.len(), search.isoc().members().len());
    let by_mean = search.isoc().best_first();
    for (k, m) in by_mean.iter().enumerate() {
        assert_eq!(result.configuration(&b, k + 1).unwrap(), m.config);
    }
    assert!(result.configuration(&b, by_mean.len() + 1).is_err());
    assert!(result.configuration(&b, 0).is_err());
    let m = &result.isoc[0];
    assert!(matches!(
        m.variables["Floor, left"],
        ResultValue::ObjectInSurface { .. }
    ));
    assert!(matches!(
        m.variables["Sun"],
        ResultValue::DirectionalLight { .. }
    ));
    assert!(matches!(m.variables["Grey"], ResultValue::Color { .. }));
    assert!(m.estimate.low <= m.estimate.mean && m.estimate.mean <= m.estimate.high);
    let run = RunFile::read(dir).unwrap().unwrap();
    assert_eq!(run, RunFile::new(&settings(), 7, &[]));
}

/// `run.json` records the luminaire files a run's scene emitted, and a resume whose
/// lights emit other files (another `--luminaire`) is refused, naming both; a folder
/// written before they were recorded resumes.
#[test]
fn resume_checks_the_luminaire_files() {
    let lamp = |file: &str| LuminaireUse {
        light: "Desk".into(),
        file: file.into(),
        path: None,
        multiplier: Some(1.0),
        lm: 3000.0,
        rotation: None,
        size: None,
    };
    let dir = Path::new("/out");
    let old = RunFile::new(&settings(), 7, &[lamp("downlight.ies")]);
    let text = serde_json::to_string(&old).unwrap();
    assert!(
        text.contains("\"luminaires\":[{\"light\":\"Desk\",\"file\":\"downlight.ies\""),
        "{text}"
    );
    assert!(
        RunFile::new(&settings(), 7, &[lamp("downlight.ies")])
            .check_resume(&old, dir)
            .is_ok()
    );
    let e = RunFile::new(&settings(), 7, &[lamp("batwing.ldt")])
        .check_resume(&old, dir)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("luminaires Desk=batwing.ldt ×1 (the folder has Desk=downlight.ies ×1)"),
        "{e}"
    );
    let e = RunFile::new(&settings(), 7, &[])
        .check_resume(&old, dir)
        .unwrap_err();
    assert!(e.to_string().contains("no luminaire files"), "{e}");
    let mut before = RunFile::new(&settings(), 7, &[]);
    before.schema_version = 1;
    assert!(
        RunFile::new(&settings(), 7, &[lamp("downlight.ies")])
            .check_resume(&before, dir)
            .is_ok()
    );
}

/// The same file name is not the same lamp: a resume is refused when the file read is
/// another one (a same-named file in another folder), its multiplier, its turn about
/// its aim or its size as installed differs, or the file was edited (its flux differs), naming what differs; a folder of schema 1, which
/// recorded names alone, resumes on the names.
#[test]
fn resume_checks_the_luminaires_path_multiplier_and_flux() {
    let lamp = |path: &str, multiplier: f64, lm: f64| LuminaireUse {
        light: "Lamp".into(),
        file: "lamp.ldt".into(),
        path: Some(path.into()),
        multiplier: Some(multiplier),
        lm,
        rotation: None,
        size: None,
    };
    let dir = Path::new("/out");
    let old = RunFile::new(&settings(), 7, &[lamp("/a/lamp.ldt", 2.0, 3000.0)]);
    let old: RunFile = serde_json::from_str(&serde_json::to_string(&old).unwrap()).unwrap();
    assert_eq!(
        old.luminaires[0].path.as_deref(),
        Some(Path::new("/a/lamp.ldt"))
    );
    let resume = |l: LuminaireUse| RunFile::new(&settings(), 7, &[l]).check_resume(&old, dir);
    assert!(resume(lamp("/a/lamp.ldt", 2.0, 3000.0)).is_ok());
    for (new, says) in [
        (
            lamp("/b/lamp.ldt", 2.0, 3000.0),
            "luminaires Lamp=/b/lamp.ldt ×2 (the folder has Lamp=/a/lamp.ldt ×2)",
        ),
        (
            lamp("/a/lamp.ldt", 1.5, 2250.0),
            "luminaires Lamp=/a/lamp.ldt ×1.5 (the folder has Lamp=/a/lamp.ldt ×2)",
        ),
        (
            lamp("/a/lamp.ldt", 2.0, 2000.0),
            "the flux of Lamp 2000.0 lm (the folder has 3000.0 lm: its file lamp.ldt changed)",
        ),
        (
            LuminaireUse {
                rotation: Some(90.0),
                ..lamp("/a/lamp.ldt", 2.0, 3000.0)
            },
            "luminaires Lamp=/a/lamp.ldt ×2 turned 90° (the folder has Lamp=/a/lamp.ldt ×2)",
        ),
        (
            LuminaireUse {
                size: Some([1.5, 0.3]),
                ..lamp("/a/lamp.ldt", 2.0, 3000.0)
            },
            "luminaires Lamp=/a/lamp.ldt ×2 sized 1.5 m × 0.3 m (the folder has Lamp=/a/lamp.ldt ×2)",
        ),
    ] {
        let e = resume(new).unwrap_err().to_string();
        assert!(e.contains(says), "{e}");
    }
    let mut names_only = old.clone();
    names_only.schema_version = 1;
    let other = RunFile::new(&settings(), 7, &[lamp("/b/lamp.ldt", 1.0, 1.0)]);
    assert!(other.check_resume(&names_only, dir).is_ok());
}

/// A folder made with another strategy (one solved before a file naming none ran the
/// race) is refused with the one flag that continues it.
#[test]
fn resume_under_another_strategy_names_the_flag_that_continues_it() {
    let dir = Path::new("/out");
    let old = RunFile::new(&settings(), 7, &[]);
    let race = Settings {
        strategy: Strategy::DEFAULT,
        ..settings()
    };
    let e = RunFile::new(&race, 7, &[])
        .check_resume(&old, dir)
        .unwrap_err();
    assert!(
        e.message
            .contains("strategy RACE_ISOC_ON_END (the folder has REFINE_ISOC_ON_INTERSECTION)"),
        "{e}"
    );
    let hint = e.hint.unwrap();
    assert!(
        hint.starts_with("give --strategy REFINE_ISOC_ON_INTERSECTION to continue"),
        "{hint}"
    );
    // Another setting differing keeps the general hint.
    let seed = Settings {
        seed: 5,
        ..settings()
    };
    let e = RunFile::new(&seed, 7, &[])
        .check_resume(&old, dir)
        .unwrap_err();
    assert!(
        e.hint
            .unwrap()
            .starts_with("resume with the folder's settings")
    );
}

/// A folder traced by an invlight whose estimator gave other numbers for the same seed
/// (one written before the version was recorded counts as version 1) is refused, naming
/// both versions: its rows and new ones would not pair.
#[test]
fn resume_refuses_another_estimator() {
    let dir = Path::new("/out");
    let now = RunFile::new(&settings(), 7, &[]);
    let mut text = serde_json::to_value(&now).unwrap();
    text.as_object_mut().unwrap().remove("estimator");
    let before: RunFile = serde_json::from_value(text).unwrap();
    assert_eq!(before.estimator, 1);
    let e = now.check_resume(&before, dir).unwrap_err().to_string();
    let expected = format!(
        "the photon estimator's version {} (the folder has 1)",
        invlight_photon::ESTIMATOR_VERSION
    );
    assert!(e.contains(&expected), "{e}");
    assert!(now.check_resume(&now.clone(), dir).is_ok());
}

/// Rows that do not hold what a run writes are errors naming the line; only a last row
/// without its newline is taken for a hard stop and ignored.
#[test]
fn bad_rows_are_errors_with_their_line() {
    let (b, _) = binding();
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    run_into(dir, &b);
    let csv = dir.join("solutions.csv");
    let good = std::fs::read_to_string(&csv).unwrap();
    let lines = good.lines().count();
    let last: Vec<&str> = good.lines().last().unwrap().split(',').collect();
    let with = |k: usize, value: &str| {
        let mut row = last.clone();
        row[k] = value;
        row.join(",") + "\n"
    };
    let elapsed = last.len() - 2;
    for (what, appended, line) in [
        ("columns", "1,2,3\n".to_string(), lines + 1),
        ("finite", with(elapsed, "NaN"), lines + 1),
        (
            "go back",
            with(elapsed, "1000") + &with(elapsed, "999"),
            lines + 2,
        ),
        ("verdict", with(last.len() - 1, "splendid"), lines + 1),
    ] {
        std::fs::write(&csv, format!("{good}{appended}")).unwrap();
        let e = Solutions::read(&csv, &b).unwrap_err().to_string();
        assert!(
            e.contains(&format!(":{line}:")) && e.contains(what),
            "{what}: {e}"
        );
    }
    // The clock of a resumed run goes on from the last row's elapsed time.
    std::fs::write(&csv, format!("{good}{}", with(elapsed, "12.5"))).unwrap();
    let rows = Solutions::read(&csv, &b).unwrap();
    assert_eq!(rows.elapsed, 12.5);
    let out = Output::create(dir, &b, info(), &settings(), 7, &Start::Resume(rows)).unwrap();
    assert!(out.elapsed() >= 12.5);
    drop(out);
    std::fs::write(&csv, format!("{good}1,2,3")).unwrap();
    assert_eq!(
        Solutions::read(&csv, &b).unwrap().records.len(),
        lines - 1,
        "a row without its newline is a hard stop's"
    );
}

/// A folder holding a run is refused unless asked to replace it, which removes that
/// run's files and pictures; a folder in use by a live run is refused with its pid; a
/// stale lock is taken over.
#[test]
fn folders_are_not_shared_or_silently_overwritten() {
    let (b, _) = binding();
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    {
        let _held = Output::create(dir, &b, info(), &settings(), 7, &fresh(false)).unwrap();
        let e = Output::create(dir, &b, info(), &settings(), 7, &fresh(true))
            .err()
            .unwrap();
        assert!(
            matches!(&e, OutputError::Locked(m) if m.contains(&std::process::id().to_string())),
            "{e}"
        );
    }
    std::fs::write(dir.join("isoc-07.png"), b"old").unwrap();
    std::fs::write(dir.join("notes.txt"), b"mine").unwrap();
    let e = Output::create(dir, &b, info(), &settings(), 7, &fresh(false))
        .err()
        .unwrap();
    assert!(matches!(e, OutputError::Occupied(_)), "{e}");
    assert!(e.to_string().contains("--force") && e.to_string().contains("--resume"));
    // A lock whose process is gone (pid 0 is never a user process).
    std::fs::write(dir.join(lock::LOCK_FILE), "0\n").unwrap();
    let out = Output::create(dir, &b, info(), &settings(), 7, &fresh(true)).unwrap();
    assert!(
        !dir.join("isoc-07.png").exists(),
        "the earlier run's picture"
    );
    assert!(dir.join("notes.txt").exists(), "not a run's file");
    assert_eq!(
        std::fs::read_to_string(dir.join("solutions.csv")).unwrap(),
        csv_line(csv_header(&b))
    );
    drop(out);
    assert!(!dir.join(lock::LOCK_FILE).exists(), "released");
}

/// A lamp placed on a rail and dimmed, with a constraint: the rows and result.json carry
/// the constraint's estimate and verdict and the level, and read back into the same
/// search; a problem nothing satisfies writes its closest configurations.
#[test]
fn constraints_and_levels_round_trip() {
    let mut s = Scene::default();
    let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let floor = s.add_mesh(Mesh::quad(
        [
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(0.0, 0.0, -1.0),
        ],
        grey,
    ));
    s.add_instance("Desk", floor, Mat4::IDENTITY);
    s.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Lamp".into(),
        kind: LightKind::Point {
            position: Vec3::new(0.5, 1.0, -0.5),
            intensity: Vec3::ONE,
        },
    });
    s.placements.push(invlight_scene::Placement {
        name: "Rail".into(),
        vertices: vec![
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(0.0, 1.0, -1.0),
        ],
    });
    let problem = |limit: f64| {
        Problem::parse(
            Path::new("/p/x.xml"),
            &format!("<input><scene path=\"s.gltf\"/><conditions meshSize=\"5\"><lightInSurface id=\"Lamp\" surface=\"Rail\" anchor=\"centre\"/><lightPower id=\"Lamp\" min=\"0.1\" max=\"1\"/></conditions><objectives><minimizePower/><constraint surface=\"Desk\" side=\"front\" minLux=\"{limit}\"/></objectives></input>"),
        )
        .unwrap()
    };
    // The "illuminance": 10 × level × (1 − distance of the lamp from the rail's
    // middle), σ 0.05.
    struct Lit;
    impl Evaluate for Lit {
        type Error = ();
        fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Evaluation, ()> {
            let x = &c.coords;
            let level = 0.1 + 0.9 * x[2];
            let near = 1.0 - ((x[0] - 0.5).powi(2) + (x[1] - 0.5).powi(2)).sqrt();
            Ok(Evaluation {
                goal: Estimate {
                    mean: 100.0 * level,
                    std_error: 0.0,
                    samples: photons,
                },
                constraints: vec![Estimate {
                    mean: 10.0 * level * near,
                    std_error: 0.05,
                    samples: photons,
                }],
                groups: Vec::new(),
                solved: None,
            })
        }
    }
    for limit in [5.0, 50.0] {
        let p = problem(limit);
        let mut scene = s.clone();
        let b = Binding::new(&p, &mut scene).unwrap();
        let header = csv_line(csv_header(&b));
        assert!(
            header.ends_with("Lamp.value,low,mean,high,std_error,photons,seconds,elapsed,verdict,Desk.front.minLux.low,Desk.front.minLux.mean,Desk.front.minLux.high,Desk.front.minLux.std_error,Desk.front.minLux.verdict\n"),
            "{header}"
        );
        let dir = tempfile::tempdir().unwrap();
        let dir = dir.path();
        let settings = Settings {
            max_iterations: 80,
            ..p.settings()
        };
        let mut search = Search::new(&b.space, settings.clone(), &b.initial);
        {
            let info = ObjectiveInfo::of(&p, &b);
            let mut out = Output::create(dir, &b, info, &settings, 7, &fresh(false)).unwrap();
            search.run(&mut Lit, &mut out).unwrap();
        }
        let rows = Solutions::read(&dir.join("solutions.csv"), &b).unwrap();
        assert!(
            rows.records
                .iter()
                .all(|r| r.evaluation.constraints.len() == 1)
        );
        let mut again = Search::new(&b.space, settings.clone(), &b.initial);
        again.replay(&rows.records);
        assert_eq!(again.isoc().members(), search.isoc().members());
        let result = ResultFile::read(&dir.join("result.json")).unwrap();
        assert_eq!(result.objective.element, "minimizePower");
        assert_eq!(result.objective.unit, "lm");
        assert_eq!(result.constraints[0].label, "Desk.front.minLux");
        let table = result.table(&b);
        if limit == 5.0 {
            assert!(result.feasible && !result.isoc.is_empty() && result.closest.is_empty());
            let m = &result.isoc[0];
            assert!(matches!(
                m.variables["Lamp.power"],
                ResultValue::LightPower { .. }
            ));
            assert_eq!(m.constraints[0].verdict, "feasible");
            // Feasible one-sided at 1.645 σ (σ = 0.05): the two-sided low end at 1.96 σ
            // lies at most (1.96 − 1.645)·0.05 = 0.016 below the limit.
            assert!(m.constraints[0].estimate.low >= 5.0 - 0.02);
            assert!(
                table.contains("Desk.front.minLux") && table.contains("feasible"),
                "{table}"
            );
            assert_eq!(
                result.configuration(&b, 1).unwrap(),
                search.isoc().best_first()[0].config
            );
        } else {
            // 10 lx at most: nothing reaches 50.
            assert!(!result.feasible && result.isoc.is_empty(), "{result:?}");
            assert!(!result.closest.is_empty());
            let first = &result.closest[0];
            assert!(first.violation.unwrap() > 0.75);
            assert_eq!(first.constraints[0].verdict, "infeasible");
            assert!(
                table.starts_with("No configuration tried meets every constraint"),
                "{table}"
            );
            // --config numbers the closest when nothing is feasible.
            assert!(result.configuration(&b, 1).is_ok());
        }
    }
}

/// A search that lights nothing: result.json says so (`unlit`, and
/// `stopped` naming the surface), the table opens with it instead of calling the dark
/// initial configuration the best, the screened rows read back as `screened`, and a
/// search replaying them rebuilds the same one-member ISOC.
#[test]
fn an_unlit_search_says_so_in_its_files() {
    struct Dark;
    impl Evaluate for Dark {
        type Error = ();
        fn evaluate(&mut self, _: &Configuration, photons: u64) -> Result<Evaluation, ()> {
            Ok(Evaluation::of(Estimate {
                mean: 0.0,
                std_error: 0.01,
                samples: photons,
            }))
        }
    }
    let (b, _) = binding();
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let settings = Settings {
        strategy: Strategy::Paired,
        cap: None,
        ..settings()
    };
    let mut search = Search::new(&b.space, settings.clone(), &b.initial);
    let mut out = Output::create(dir, &b, info(), &settings, 7, &fresh(false)).unwrap();
    let outcome = search.run(&mut Dark, &mut out).unwrap();
    assert_eq!(outcome, crate::Outcome::Unlit);
    out.set_stopped(outcome);
    out.write_result(search.standing()).unwrap();
    drop(out);
    let result = ResultFile::read(&dir.join("result.json")).unwrap();
    assert!(result.unlit);
    let stopped = result.stopped.as_deref().unwrap();
    assert!(
        stopped.starts_with("no configuration tried lights 'Floor, left'"),
        "{stopped}"
    );
    assert_eq!(result.isoc.len(), 1);
    let table = result.table(&b);
    assert!(
        table.starts_with("No configuration tried lights 'Floor, left'"),
        "{table}"
    );
    let rows = Solutions::read(&dir.join("solutions.csv"), &b).unwrap();
    assert_eq!(
        rows.records
            .iter()
            .filter(|r| r.verdict == Verdict::Screened)
            .count() as u64,
        search.evaluations() - 1
    );
    let mut again = Search::new(&b.space, settings, &b.initial);
    again.replay(&rows.records);
    assert_eq!(again.isoc().members(), search.isoc().members());
}

/// A damaged complete row of `solutions.csv` is an error naming its line and what was
/// expected: a number that is not one, an integer that is not one, a missing column, an
/// unknown verdict, an estimate out of order, a negative time.
#[test]
fn damaged_rows_are_errors_naming_the_line() {
    let (b, _) = binding();
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    run_into(dir, &b);
    let csv = dir.join("solutions.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    // The second data row, line 3: iteration, six placement columns, three of the
    // sun, Grey.value (10), low, mean, high, std_error, photons (15), seconds (16),
    // elapsed, verdict (18).
    // `None` drops the last column.
    let damaged = |k: usize, value: Option<&str>| -> Diagnostic {
        let mut fields: Vec<&str> = lines[2].split(',').collect();
        match value {
            Some(v) => fields[k] = v,
            None => {
                fields.pop();
            }
        }
        let mut out = lines.clone();
        let row = fields.join(",");
        out[2] = &row;
        std::fs::write(&csv, out.join("\n") + "\n").unwrap();
        let e = Solutions::read(&csv, &b).unwrap_err();
        assert_eq!(e.line, Some(3), "{e}");
        e
    };
    for (k, value, message) in [
        (
            10,
            Some("NaN"),
            "'NaN' in column Grey.value, expected a finite number",
        ),
        (15, Some("x"), "'x' in column photons, expected an integer"),
        (18, None, "18 columns, expected 19"),
        (18, Some("maybe"), "verdict 'maybe' unknown"),
        (
            11,
            Some("1e9"),
            "the estimate is inconsistent (expected low ≤ mean ≤ high, std_error ≥ 0, photons > 0)",
        ),
    ] {
        assert_eq!(damaged(k, value).message, message);
    }
    let e = damaged(16, Some("-1"));
    assert!(
        e.message.starts_with("times -1 s and ")
            && e.message.contains("expected non-negative seconds"),
        "{e}"
    );
}

/// Eight lamps all at full output giving 490 lx where 625 lx is needed: the lumen
/// method asks for ⌈8 × 625/490⌉ = 11; one lamp dimmed, or the minimum met, asks for
/// nothing, and a uniformity short is not a count of lamps.
#[test]
fn a_layout_at_full_output_short_of_its_minimum_gets_a_lamp_count() {
    let estimate = |mean: f64| ResultEstimate {
        mean,
        low: mean - 5.0,
        high: mean + 5.0,
        std_error: 2.5,
        photons: 200_000,
    };
    let info = |bound: &str, limit: f64| ConstraintInfo {
        label: format!("Desks.{bound}"),
        surface: "Desks".into(),
        side: "front".into(),
        bound: bound.into(),
        limit,
        unit: "lx".into(),
        maintenance_factor: None,
        maintained_limit: None,
        standard: None,
    };
    let constraints = [info("minLux", 625.0), info("minUniformity", 0.6)];
    let member = |levels: Vec<f64>, lux: f64, u0: f64| ResultMember {
        variables: BTreeMap::new(),
        estimate: estimate(296.0),
        constraints: [("minLux", lux), ("minUniformity", u0)]
            .iter()
            .map(|&(b, mean)| ResultConstraint {
                bound: None,
                label: format!("Desks.{b}"),
                estimate: estimate(mean),
                verdict: "infeasible".into(),
            })
            .collect(),
        violation: Some(0.2),
        layouts: vec![Layout {
            lights: (1..=levels.len()).map(|k| format!("Lamp{k}")).collect(),
            surface: "Zone".into(),
            array: None,
            levels,
            off: Vec::new(),
            description: String::new(),
        }],
    };
    assert_eq!(
        member(vec![1.0; 8], 490.0, 0.5).lamps_needed(&constraints, |n| n == 8),
        Some((8, 11))
    );
    let mut dimmed = vec![1.0; 8];
    dimmed[3] = 0.8;
    let alone = |n| n == 8;
    assert_eq!(
        member(dimmed, 490.0, 0.5).lamps_needed(&constraints, alone),
        None
    );
    assert_eq!(
        member(vec![1.0; 8], 630.0, 0.5).lamps_needed(&constraints, alone),
        None
    );
    // Other light in the scene (fixed lamps, a sky) would not grow with the count.
    assert_eq!(
        member(vec![1.0; 8], 490.0, 0.5).lamps_needed(&constraints, |_| false),
        None
    );
}
