//! The results of a search, written as it goes so they are valid after an interruption
//! (thesis §4.2.2): `solutions.csv`, one row per evaluation, flushed row by row, and
//! `result.json`, the ISOC, rewritten atomically (temporary file + rename) whenever it
//! changes. `--resume` reads `solutions.csv` back into [`Record`]s, after
//! [`RunSettings::check_resume`] has made sure the rows were traced with the same
//! settings (`run.json`).

use crate::apply::{Binding, Value};
use crate::compare::Interval;
use crate::isoc::Isoc;
use crate::space::{Configuration, Domain};
use crate::vns::{Observer, Record, Settings, Strategy, Verdict};
use invlight_photon::Estimate;
use serde_json::{Value as Json, json};
use std::fs::{File, OpenOptions};
use std::io::{self, BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What `result.json` says of the objective.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveInfo {
    /// The surface lit.
    pub surface: String,
    /// The cap, lx.
    pub cap: Option<f64>,
    /// N, photons of a full evaluation.
    pub photons: u64,
}

/// The settings a search's numbers depend on, written to `run.json` when a search starts
/// so that `--resume` can refuse to mix rows traced differently: a different seed,
/// sample count or confidence would make the old and new estimates incomparable
/// (common random numbers are lost, intervals differ) while looking alike in the CSV.
/// The iteration budget may change: resuming with more iterations is what it is for.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// Seed of the photon streams.
    pub seed: u64,
    /// N, photons of a full evaluation.
    pub photons: u64,
    /// q, the fast evaluations' share of N.
    pub fast_quality: f64,
    /// The refinement strategy.
    pub strategy: Strategy,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// The cap on the objective, lx.
    pub cap: Option<f64>,
    /// Bounce cap of the photon paths.
    pub max_bounces: u32,
}

impl RunSettings {
    /// The settings of a search and its photon tracer.
    pub fn new(settings: &Settings, max_bounces: u32) -> RunSettings {
        RunSettings {
            seed: settings.seed,
            photons: settings.photons,
            fast_quality: settings.fast_quality,
            strategy: settings.strategy,
            confidence: settings.confidence,
            cap: settings.cap,
            max_bounces,
        }
    }

    fn to_json(&self) -> Json {
        json!({
            "seed": self.seed,
            "photons": self.photons,
            "fastQuality": self.fast_quality,
            "strategy": self.strategy.name(),
            "confidence": self.confidence,
            "cap": self.cap,
            "maxBounces": self.max_bounces,
        })
    }

    /// Writes `dir/run.json`.
    pub fn write(&self, dir: &Path) -> io::Result<()> {
        let mut f = File::create(dir.join("run.json"))?;
        serde_json::to_writer_pretty(&mut f, &self.to_json())?;
        writeln!(f)
    }

    /// Whether the rows in `dir` may be continued with these settings: `Err` names every
    /// setting that differs from `dir/run.json`, with the value the folder was made
    /// with. A folder without `run.json` (written by an older invlight) is accepted.
    pub fn check_resume(&self, dir: &Path) -> Result<(), String> {
        let path = dir.join("run.json");
        let Ok(text) = std::fs::read_to_string(&path) else {
            return Ok(());
        };
        let old: Json = serde_json::from_str(&text)
            .map_err(|e| format!("{}: not valid JSON ({e})", path.display()))?;
        let new = self.to_json();
        let differ: Vec<String> = new
            .as_object()
            .into_iter()
            .flatten()
            .filter(|(k, v)| old.get(k.as_str()) != Some(v))
            .map(|(k, v)| {
                let was = old
                    .get(k.as_str())
                    .map_or("nothing".to_string(), Json::to_string);
                format!("{k} {v} (the folder has {was})")
            })
            .collect();
        if differ.is_empty() {
            Ok(())
        } else {
            Err(format!(
                "cannot resume {}: its rows were traced with other settings: {}; resume with \
                 the folder's settings (--seed, --photons, --confidence, --max-bounces, the \
                 problem file's quality and strategy) or choose a new --output",
                dir.display(),
                differ.join(", ")
            ))
        }
    }
}

/// The CSV header for a binding's variables.
pub fn csv_header(binding: &Binding) -> Vec<String> {
    let mut h = vec!["iteration".to_string()];
    for v in binding.space.variables() {
        match v.domain {
            Domain::Rectangle(_) | Domain::Hemisphere(_) => {
                h.extend(["x", "y", "z"].map(|c| format!("{}.{c}", v.id)))
            }
            Domain::Segment { .. } => h.push(format!("{}.value", v.id)),
        }
    }
    h.extend(
        [
            "low", "mean", "high", "photons", "seconds", "elapsed", "verdict",
        ]
        .map(String::from),
    );
    h
}

/// Writes `solutions.csv` and `result.json` as the search reports.
pub struct Output<'b> {
    binding: &'b Binding,
    objective: ObjectiveInfo,
    csv: File,
    result: PathBuf,
    started: Instant,
    /// Elapsed seconds of the run being resumed.
    offset: f64,
    evaluations: u64,
    z: f64,
}

impl<'b> Output<'b> {
    /// Creates `dir` and its files. With `resume`, `solutions.csv` is appended to and
    /// the clock and evaluation count go on from `resumed` (the rows read back).
    pub fn create(
        dir: &Path,
        binding: &'b Binding,
        objective: ObjectiveInfo,
        z: f64,
        resumed: Option<&[Record]>,
        resumed_elapsed: f64,
    ) -> io::Result<Output<'b>> {
        std::fs::create_dir_all(dir)?;
        let path = dir.join("solutions.csv");
        let csv = match resumed {
            Some(_) => {
                // A row cut short by a hard stop is ignored by `read_solutions`; cut it
                // off so the next row starts on its own line.
                let text = std::fs::read(&path)?;
                let keep = text.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
                let f = OpenOptions::new().append(true).open(&path)?;
                f.set_len(keep as u64)?;
                f
            }
            None => {
                let mut f = File::create(&path)?;
                writeln!(f, "{}", csv_header(binding).join(","))?;
                f
            }
        };
        Ok(Output {
            binding,
            objective,
            csv,
            result: dir.join("result.json"),
            started: Instant::now(),
            offset: resumed_elapsed,
            evaluations: resumed.map_or(0, |r| r.len() as u64),
            z,
        })
    }

    /// Seconds since the run (first) started.
    pub fn elapsed(&self) -> f64 {
        self.offset + self.started.elapsed().as_secs_f64()
    }

    /// The `result.json` document for an ISOC.
    pub fn result_json(&self, isoc: &Isoc) -> Json {
        let members: Vec<Json> = isoc
            .by_mean()
            .into_iter()
            .map(|m| {
                let mut vars = serde_json::Map::new();
                for ((v, value), kind) in self
                    .binding
                    .space
                    .variables()
                    .iter()
                    .zip(self.binding.values(&m.config))
                    .zip(&self.binding.kinds)
                {
                    let mut o = json!({ "kind": kind });
                    match value {
                        Value::Position(p) => o["position"] = json!(p.to_array()),
                        Value::Direction(d) => o["direction"] = json!(d.to_array()),
                        Value::Color { value, rgb } => {
                            o["value"] = json!(value);
                            o["rgb"] = json!(rgb);
                        }
                    }
                    vars.insert(v.id.clone(), o);
                }
                let i = Interval::of(&m.estimate, self.z);
                json!({
                    "variables": vars,
                    "estimate": {
                        "mean": m.estimate.mean,
                        "low": i.low,
                        "high": i.high,
                        "photons": m.estimate.photons,
                    }
                })
            })
            .collect();
        json!({
            "objective": {
                "surface": self.objective.surface,
                "sense": "maximize",
                "unit": "lx",
                "cap": self.objective.cap,
            },
            "photons": self.objective.photons,
            "evaluations": self.evaluations,
            "seconds": self.elapsed(),
            "isoc": members,
        })
    }

    /// Rewrites `result.json` atomically: readers see the old or the new file, never
    /// half of one. No fsync: the rename is atomic for readers, and syncing on every
    /// ISOC change (every evaluation while the ISOC is a plateau of zeros) cost more
    /// than the tracing of small scenes.
    pub fn write_result(&self, isoc: &Isoc) -> io::Result<()> {
        let tmp = self.result.with_extension("json.tmp");
        {
            let mut f = File::create(&tmp)?;
            serde_json::to_writer_pretty(&mut f, &self.result_json(isoc))?;
            writeln!(f)?;
        }
        std::fs::rename(&tmp, &self.result)
    }

    fn row(&self, r: &Record) -> String {
        let mut cols = vec![r.iteration.to_string()];
        for v in self.binding.values(&r.config) {
            match v {
                Value::Position(p) | Value::Direction(p) => {
                    cols.extend(p.to_array().map(|c| c.to_string()))
                }
                Value::Color { value, .. } => cols.push(value.to_string()),
            }
        }
        let i = Interval::of(&r.estimate, self.z);
        cols.extend([
            i.low.to_string(),
            r.estimate.mean.to_string(),
            i.high.to_string(),
            r.estimate.photons.to_string(),
            format!("{:.6}", r.seconds),
            format!("{:.3}", self.elapsed()),
            r.verdict.name().to_string(),
        ]);
        cols.join(",")
    }
}

impl Observer for Output<'_> {
    fn evaluated(&mut self, record: &Record, isoc: &Isoc, changed: bool) -> io::Result<()> {
        self.evaluations += 1;
        let line = self.row(record);
        writeln!(self.csv, "{line}")?;
        self.csv.flush()?;
        if changed {
            self.write_result(isoc)?;
        }
        Ok(())
    }
}

/// Reads a `solutions.csv` written for `binding` back into records, and the last row's
/// `elapsed`. Rows must have the header this binding writes (same variables, same
/// order); each row's coordinates are mapped back to the normalised configuration and
/// its interval to an estimate (σ = (high − low)/(2z)). A last row cut short by an
/// interruption is ignored.
pub fn read_solutions(path: &Path, binding: &Binding, z: f64) -> io::Result<(Vec<Record>, f64)> {
    let bad = |line: usize, msg: String| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("{}:{line}: {msg}", path.display()),
        )
    };
    let file = BufReader::new(File::open(path)?);
    let mut lines = file.lines().enumerate();
    let want = csv_header(binding);
    let header = match lines.next() {
        Some((_, h)) => h?,
        None => return Ok((Vec::new(), 0.0)),
    };
    if header.trim() != want.join(",") {
        return Err(bad(
            1,
            format!(
                "header '{}' does not match this problem's, expected '{}'",
                header.trim(),
                want.join(",")
            ),
        ));
    }
    let mut records = Vec::new();
    let mut elapsed = 0.0;
    let rows: Vec<(usize, String)> = lines
        .map(|(i, l)| l.map(|l| (i + 1, l)))
        .collect::<io::Result<_>>()?;
    let last = rows.len();
    for (k, (n, line)) in rows.into_iter().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let cols: Vec<&str> = line.trim().split(',').collect();
        if cols.len() != want.len() {
            if k + 1 == last {
                break;
            }
            return Err(bad(
                n,
                format!("{} columns, expected {}", cols.len(), want.len()),
            ));
        }
        let num = |i: usize| -> io::Result<f64> {
            cols[i].parse::<f64>().map_err(|_| {
                bad(
                    n,
                    format!("'{}' in column {}, expected a number", cols[i], want[i]),
                )
            })
        };
        let iteration = cols[0]
            .parse::<u64>()
            .map_err(|_| bad(n, format!("iteration '{}', expected an integer", cols[0])))?;
        let mut coords = Vec::new();
        let mut c = 1;
        for v in binding.space.variables() {
            match &v.domain {
                Domain::Rectangle(r) => {
                    let p = glam::DVec3::new(num(c)?, num(c + 1)?, num(c + 2)?);
                    let (s, t) = r.coords(p);
                    coords.extend([s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)]);
                    c += 3;
                }
                Domain::Hemisphere(h) => {
                    let d = glam::DVec3::new(num(c)?, num(c + 1)?, num(c + 2)?);
                    let (p, t) = h.coords(d);
                    coords.extend([p, t]);
                    c += 3;
                }
                Domain::Segment { min, max } => {
                    coords.push(((num(c)? - min) / (max - min)).clamp(0.0, 1.0));
                    c += 1;
                }
            }
        }
        let (low, mean, high) = (num(c)?, num(c + 1)?, num(c + 2)?);
        let photons = cols[c + 3]
            .parse::<u64>()
            .map_err(|_| bad(n, format!("photons '{}', expected an integer", cols[c + 3])))?;
        let seconds = num(c + 4)?;
        elapsed = num(c + 5)?;
        let verdict = Verdict::parse(cols[c + 6])
            .ok_or_else(|| bad(n, format!("verdict '{}' unknown", cols[c + 6])))?;
        records.push(Record {
            iteration,
            config: Configuration { coords },
            estimate: Estimate {
                mean,
                std_error: (high - low) / (2.0 * z),
                photons,
            },
            seconds,
            verdict,
        });
    }
    Ok((records, elapsed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::Problem;
    use crate::vns::{Evaluate, Search, Settings, Strategy};
    use glam::{Mat4, Vec3};
    use invlight_scene::{Light, LightKind, Material, Mesh, Scene};
    use std::sync::atomic::AtomicBool;

    struct Bowl;
    impl Evaluate for Bowl {
        type Error = ();
        fn evaluate(&mut self, c: &Configuration, photons: u64) -> Result<Estimate, ()> {
            let x = &c.coords;
            Ok(Estimate {
                mean: 10.0 - (x[0] - 0.3).powi(2) - (x[2] - 0.6).powi(2) - x[3],
                std_error: 0.01,
                photons,
            })
        }
    }

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
        s.add_instance("Floor", floor, Mat4::IDENTITY);
        s.lights.push(Light {
            name: "Sun".into(),
            kind: LightKind::Directional {
                direction: -Vec3::Y,
                illuminance: Vec3::ONE,
            },
        });
        let p = Problem::parse(
            Path::new("/p/x.xml"),
            "<input><scene path=\"s.gltf\"/><conditions meshSize=\"10\"><objectInSurface id=\"Floor\" surface=\"Floor\"/><directionalLight id=\"Sun\"/><color id=\"Grey\" hue=\"30\" saturation=\"0.5\"/></conditions><objectives><maximizeRadiance surface=\"Floor\" maxRadiosity=\"9.5\"/></objectives></input>",
        )
        .unwrap();
        (Binding::new(&p, &mut s).unwrap(), s)
    }

    #[test]
    fn csv_and_json_round_trip() {
        let (b, _) = binding();
        assert_eq!(
            csv_header(&b).join(","),
            "iteration,Floor.x,Floor.y,Floor.z,Sun.x,Sun.y,Sun.z,Grey.value,low,mean,high,photons,seconds,elapsed,verdict"
        );
        let dir = std::env::temp_dir().join(format!("invlight-ilp-output-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let z = invlight_photon::z_two_sided(0.95);
        let info = ObjectiveInfo {
            surface: "Floor".into(),
            cap: Some(9.5),
            photons: 1000,
        };
        let settings = Settings {
            max_iterations: 60,
            photons: 1000,
            fast_quality: 0.25,
            strategy: Strategy::RefineOnIntersection,
            confidence: 0.95,
            cap: Some(9.5),
            seed: 4,
            tries_per_radius: None,
        };
        let mut search = Search::new(&b.space, settings.clone(), &b.initial);
        {
            let mut out = Output::create(&dir, &b, info.clone(), z, None, 0.0).unwrap();
            search
                .run(&mut Bowl, &mut out, &AtomicBool::new(false))
                .unwrap();
        }
        // A hard stop mid-row: the partial row is ignored, then cut off on resuming.
        let csv = dir.join("solutions.csv");
        let mut f = OpenOptions::new().append(true).open(&csv).unwrap();
        write!(f, "999,0.5,0.").unwrap();
        drop(f);
        let (records, elapsed) = read_solutions(&csv, &b, z).unwrap();
        Output::create(&dir, &b, info.clone(), z, Some(&records), elapsed).unwrap();
        let text = std::fs::read_to_string(&csv).unwrap();
        assert!(text.ends_with('\n'));
        assert_eq!(text.lines().count(), records.len() + 1);
        assert_eq!(records.len() as u64, search.evaluations());
        assert!(elapsed >= 0.0);
        assert!(
            records.iter().any(|r| r.verdict == Verdict::Invalid),
            "cap 9.5"
        );
        let mut again = Search::new(&b.space, settings, &b.initial);
        again.replay(&records);
        let cells =
            |s: &Search| -> Vec<_> { s.isoc().members().iter().map(|m| m.cell.clone()).collect() };
        assert_eq!(cells(&again), cells(&search));
        for (a, m) in again.isoc().members().iter().zip(search.isoc().members()) {
            assert_eq!(a.config, m.config);
            assert!((a.estimate.mean - m.estimate.mean).abs() < 1e-12);
            assert!((a.estimate.std_error - m.estimate.std_error).abs() < 1e-9);
        }
        let json: Json =
            serde_json::from_reader(File::open(dir.join("result.json")).unwrap()).unwrap();
        assert_eq!(json["objective"]["sense"], "maximize");
        assert_eq!(json["objective"]["cap"], 9.5);
        let isoc = json["isoc"].as_array().unwrap();
        assert_eq!(isoc.len(), search.isoc().members().len());
        let means: Vec<f64> = isoc
            .iter()
            .map(|m| m["estimate"]["mean"].as_f64().unwrap())
            .collect();
        assert!(means.windows(2).all(|w| w[0] >= w[1]), "{means:?}");
        let m = &isoc[0];
        assert_eq!(m["variables"]["Floor"]["kind"], "objectInSurface");
        assert_eq!(
            m["variables"]["Floor"]["position"]
                .as_array()
                .unwrap()
                .len(),
            3
        );
        assert_eq!(m["variables"]["Sun"]["kind"], "directionalLight");
        assert!(m["variables"]["Grey"]["rgb"].is_array());
        assert!(m["estimate"]["low"].as_f64().unwrap() <= m["estimate"]["mean"].as_f64().unwrap());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
