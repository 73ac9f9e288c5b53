//! `run.json`: the settings a search's numbers depend on, written when a search starts
//! so that `--resume` can refuse to mix rows traced differently: a different seed,
//! sample count or confidence would make the old and new estimates incomparable
//! (common random numbers are lost, intervals differ) while looking alike in the CSV.
//! The iteration budget may change: resuming with more iterations is what it is for.

use crate::binding::LuminaireUse;
use crate::vns::{Settings, Strategy};
use invlight_scene::Diagnostic;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The version of `run.json`'s layout: 2 records each luminaire's file as given, the
/// file read and its multiplier, where 1 recorded the file's name alone.
pub const RUN_SCHEMA: u32 = 2;

/// `run.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct RunFile {
    /// [`RUN_SCHEMA`]; 0 in folders written before it was recorded.
    #[serde(rename = "schema_version", default)]
    pub schema_version: u32,
    /// Seed of the photon streams and of the search.
    pub seed: u64,
    /// N, photons of a full evaluation.
    pub photons: u64,
    /// q, the fast evaluations' share of N.
    pub fast_quality: f64,
    /// The refinement strategy, as the problem file spells it.
    pub strategy: String,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// The cap on the objective, lx.
    pub cap: Option<f64>,
    /// Bounce cap of the photon paths.
    pub max_bounces: u32,
    /// [`invlight_photon::ESTIMATOR_VERSION`] of the program that traced the rows; 1 in
    /// folders written before it was recorded.
    #[serde(default = "first_estimator")]
    pub estimator: u32,
    /// The lights that emit a photometric file (none in folders written before they
    /// were recorded, and in scenes without one).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub luminaires: Vec<LuminaireUse>,
}

impl LuminaireUse {
    /// `LIGHT=FILE`, with `whole` the file read and its multiplier (`LIGHT=PATH ×M`),
    /// else the file's name alone.
    fn described(&self, whole: bool) -> String {
        if !whole {
            let name = Path::new(&self.file)
                .file_name()
                .map(|n| n.to_string_lossy());
            return format!("{}={}", self.light, name.unwrap_or_default());
        }
        let file = match &self.path {
            Some(p) => p.display().to_string(),
            None => self.file.clone(),
        };
        // Shown as the f32 it was, so that a value read back from JSON prints alike.
        let m = self
            .multiplier
            .map_or("?".into(), |m| (m as f32).to_string());
        let turned = self
            .rotation
            .map_or(String::new(), |r| format!(" turned {}°", r as f32));
        let sized = self.size.map_or(String::new(), |[l, w]| {
            format!(" sized {} m × {} m", l as f32, w as f32)
        });
        format!("{}={file} ×{m}{turned}{sized}", self.light)
    }
}

/// The estimator of a folder written before it was recorded.
fn first_estimator() -> u32 {
    1
}

impl RunFile {
    /// The settings of a search and its photon tracer, and the luminaires of its scene.
    pub fn new(settings: &Settings, max_bounces: u32, luminaires: &[LuminaireUse]) -> RunFile {
        RunFile {
            schema_version: RUN_SCHEMA,
            seed: settings.seed,
            photons: settings.photons,
            fast_quality: settings.fast_quality,
            strategy: settings.strategy.name().to_string(),
            confidence: settings.confidence.level(),
            cap: settings.cap,
            max_bounces,
            estimator: invlight_photon::ESTIMATOR_VERSION,
            luminaires: luminaires.to_vec(),
        }
    }

    /// Whether rows made with `old` may be continued with these settings: `Err` names
    /// every setting that differs, with the value the folder was made with.
    pub fn check_resume(&self, old: &RunFile, dir: &Path) -> Result<(), Diagnostic> {
        let mut differ = Vec::new();
        let mut check = |name: &str, new: String, was: String| {
            if new != was {
                differ.push(format!("{name} {new} (the folder has {was})"));
            }
        };
        check("seed", self.seed.to_string(), old.seed.to_string());
        check("photons", self.photons.to_string(), old.photons.to_string());
        check(
            "fastQuality",
            self.fast_quality.to_string(),
            old.fast_quality.to_string(),
        );
        check("strategy", self.strategy.clone(), old.strategy.clone());
        check(
            "confidence",
            self.confidence.to_string(),
            old.confidence.to_string(),
        );
        check("cap", format!("{:?}", self.cap), format!("{:?}", old.cap));
        check(
            "maxBounces",
            self.max_bounces.to_string(),
            old.max_bounces.to_string(),
        );
        check(
            "the photon estimator's version",
            self.estimator.to_string(),
            old.estimator.to_string(),
        );
        // A folder of schema 1 named each file alone: only the names can be compared.
        let whole = old.schema_version >= 2;
        let files = |l: &[LuminaireUse]| {
            let named: Vec<String> = l.iter().map(|l| l.described(whole)).collect();
            if named.is_empty() {
                "no luminaire files".into()
            } else {
                named.join(" ")
            }
        };
        if whole || !old.luminaires.is_empty() {
            check(
                "luminaires",
                files(&self.luminaires),
                files(&old.luminaires),
            );
        }
        // The same files with other tables: a file edited in place.
        if whole && differ.is_empty() {
            for (new, was) in self.luminaires.iter().zip(&old.luminaires) {
                if (new.lm - was.lm).abs() > 1e-6 * new.lm.abs().max(was.lm.abs()) {
                    differ.push(format!(
                        "the flux of {} {:.1} lm (the folder has {:.1} lm: its file {} changed)",
                        new.light, new.lm, was.lm, new.file
                    ));
                }
            }
        }
        if differ.is_empty() {
            return Ok(());
        }
        let general = "resume with the folder's settings (--seed, --photons, --confidence, --max-bounces, --luminaire, the problem file's quality, strategy and <luminaire> elements) or choose a new --output; a folder of another estimator's version was traced by another invlight and can only be continued by it";
        // Only the strategy differing has a one-flag answer: a folder made before a
        // file naming none ran RACE_ISOC_ON_END continues under the strategy it was.
        let hint = if self.strategy != old.strategy {
            format!(
                "give --strategy {} to continue the folder's search (a problem file naming no strategy runs {}); else {general}",
                old.strategy,
                Strategy::DEFAULT.name()
            )
        } else {
            general.to_string()
        };
        Err(Diagnostic::new(
            &dir.join("run.json"),
            format!(
                "cannot resume {}: its rows were traced with other settings: {}",
                dir.display(),
                differ.join(", ")
            ),
        )
        .with_hint(hint))
    }

    /// Reads `dir/run.json`; `Ok(None)` when there is none.
    pub fn read(dir: &Path) -> Result<Option<RunFile>, Diagnostic> {
        let path = dir.join("run.json");
        let text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(Diagnostic::new(&path, format!("cannot read it: {e}"))),
        };
        let run: RunFile = serde_json::from_str(&text).map_err(|e| {
            Diagnostic::at_line(&path, e.line() as u32, format!("not a run.json: {e}"))
        })?;
        if Strategy::parse(&run.strategy).is_none() {
            return Err(Diagnostic::new(
                &path,
                format!("strategy '{}' unknown", run.strategy),
            ));
        }
        Ok(Some(run))
    }
}
