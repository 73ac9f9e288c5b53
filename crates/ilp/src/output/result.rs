//! `result.json`: the ISOC as the search leaves it, rewritten whenever it changes, and
//! read back by `render/measure/map --config RESULT#K`. One [`ResultFile`] writes and
//! reads it.

use crate::binding::{Binding, VariableValue};
use crate::isoc::Isoc;
use crate::problem::VariableKind;
use glam::DVec3;
use invlight_scene::Diagnostic;
use invlight_stats::significant;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The version of `result.json`'s layout; readers refuse another.
pub const RESULT_SCHEMA: u32 = 1;

/// What `result.json` says of the objective.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectiveInfo {
    /// The surface lit.
    pub surface: String,
    /// `maximize`.
    pub sense: String,
    /// `lx`.
    pub unit: String,
    /// The cap, lx.
    pub cap: Option<f64>,
    /// The problem file solved (absolute), so that `invlight report DIR` can rebuild
    /// the report from the folder alone. Optional and absent in folders written before
    /// it was recorded: readers of this schema version read either.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub problem: Option<std::path::PathBuf>,
}

impl ObjectiveInfo {
    /// The objective of `problem`.
    pub fn of(problem: &crate::problem::Problem) -> ObjectiveInfo {
        ObjectiveInfo {
            surface: problem.objective.surface.clone(),
            sense: "maximize".into(),
            unit: "lx".into(),
            cap: problem.objective.cap,
            problem: std::fs::canonicalize(&problem.path).ok(),
        }
    }
}

/// A member's estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ResultEstimate {
    /// Mean, in the objective's unit.
    pub mean: f64,
    /// Lower end of the interval at the run's confidence.
    pub low: f64,
    /// Upper end.
    pub high: f64,
    /// Standard error of the mean.
    pub std_error: f64,
    /// Photons traced for it.
    pub photons: u64,
}

/// A variable's value in a member, tagged by its problem-file element.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind")]
pub enum ResultValue {
    /// `objectInSurface`: P and the object's anchor, m.
    #[serde(rename = "objectInSurface")]
    ObjectInSurface {
        /// The placement point P.
        position: [f64; 3],
        /// The object's bounding-box centre on the placement plane.
        anchor: [f64; 3],
    },
    /// `lightInSurface`: P and the light's position (or the emissive object's anchor).
    #[serde(rename = "lightInSurface")]
    LightInSurface {
        /// The placement point P.
        position: [f64; 3],
        /// Where the light is.
        anchor: [f64; 3],
    },
    /// `holeInSurface`: P and the hole's anchor.
    #[serde(rename = "holeInSurface")]
    HoleInSurface {
        /// The placement point P.
        position: [f64; 3],
        /// The hole's centre on the wall's plane.
        anchor: [f64; 3],
    },
    /// `directionalLight`: the unit vector the light travels along.
    #[serde(rename = "directionalLight")]
    DirectionalLight {
        /// Direction of travel.
        direction: [f64; 3],
    },
    /// `color`: the HSV value V and the linear K_d it gives.
    #[serde(rename = "color")]
    Color {
        /// V.
        value: f64,
        /// K_d, linear RGB.
        rgb: [f64; 3],
    },
}

impl ResultValue {
    /// The value of a variable of `kind`.
    pub fn new(kind: &VariableKind, value: &VariableValue) -> ResultValue {
        match (*value, kind) {
            (VariableValue::Position { point, anchor }, k) => {
                let (position, anchor) = (point.to_array(), anchor.to_array());
                match k {
                    VariableKind::LightInSurface(_) => {
                        ResultValue::LightInSurface { position, anchor }
                    }
                    VariableKind::HoleInSurface(_) => {
                        ResultValue::HoleInSurface { position, anchor }
                    }
                    _ => ResultValue::ObjectInSurface { position, anchor },
                }
            }
            (VariableValue::Direction(d), _) => ResultValue::DirectionalLight {
                direction: d.to_array(),
            },
            (VariableValue::Colour { value, rgb }, _) => ResultValue::Color { value, rgb },
        }
    }

    /// The world value it records.
    pub fn value(&self) -> VariableValue {
        match *self {
            ResultValue::ObjectInSurface { position, anchor }
            | ResultValue::LightInSurface { position, anchor }
            | ResultValue::HoleInSurface { position, anchor } => VariableValue::Position {
                point: DVec3::from_array(position),
                anchor: DVec3::from_array(anchor),
            },
            ResultValue::DirectionalLight { direction } => {
                VariableValue::Direction(DVec3::from_array(direction))
            }
            ResultValue::Color { value, rgb } => VariableValue::Colour { value, rgb },
        }
    }
}

/// An ISOC member.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResultMember {
    /// Each variable's value, by id.
    pub variables: BTreeMap<String, ResultValue>,
    /// Its estimate.
    pub estimate: ResultEstimate,
}

/// `result.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResultFile {
    /// [`RESULT_SCHEMA`].
    pub schema_version: u32,
    /// The objective.
    pub objective: ObjectiveInfo,
    /// N, photons of a full evaluation.
    pub photons: u64,
    /// Confidence of the intervals and comparisons.
    pub confidence: f64,
    /// Evaluations so far (a resumed run's included).
    pub evaluations: u64,
    /// Candidates not traced because they put an object or light outside the scene.
    pub refused: u64,
    /// Seconds since the run (first) started.
    pub seconds: f64,
    /// The ISOC, highest mean first.
    pub isoc: Vec<ResultMember>,
}

impl ResultFile {
    /// The members of `isoc`, highest mean first, as `binding`'s variables give them.
    pub fn members(binding: &Binding, isoc: &Isoc) -> Vec<ResultMember> {
        isoc.by_mean()
            .into_iter()
            .map(|m| {
                let variables = binding
                    .specs
                    .iter()
                    .zip(binding.values(&m.config))
                    .map(|(spec, value)| (spec.id.clone(), ResultValue::new(&spec.kind, &value)))
                    .collect();
                let i = m.estimate.interval(isoc.z());
                ResultMember {
                    variables,
                    estimate: ResultEstimate {
                        mean: m.estimate.mean,
                        low: i.low,
                        high: i.high,
                        std_error: m.estimate.std_error,
                        photons: m.estimate.samples,
                    },
                }
            })
            .collect()
    }

    /// Reads a `result.json`.
    pub fn read(path: &Path) -> Result<ResultFile, Diagnostic> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Diagnostic::new(path, format!("cannot read it: {e}")))?;
        let file: ResultFile = serde_json::from_str(&text).map_err(|e| {
            Diagnostic::at_line(
                path,
                e.line() as u32,
                format!("not a result.json of this invlight: {e}"),
            )
        })?;
        if file.schema_version != RESULT_SCHEMA {
            return Err(Diagnostic::new(
                path,
                format!(
                    "schema_version {}, expected {RESULT_SCHEMA}",
                    file.schema_version
                ),
            )
            .with_hint("it was written by another version of invlight"));
        }
        Ok(file)
    }

    /// The ISOC as a table for people, best mean first, each placed thing at its anchor
    /// with its placement point P beside it.
    pub fn table(&self, binding: &Binding) -> String {
        let surface = &self.objective.surface;
        let level = self.confidence * 100.0;
        let mut out = match self.isoc.len() {
            0 => "No configuration could be ranked: every one tried was invalid.\n".to_string(),
            1 => format!(
                "One configuration lights '{surface}' best, better at {level} % confidence than every other one tried:\n"
            ),
            n => format!(
                "{n} configurations light '{surface}' best: the ISOC, those that cannot be told apart at {level} % confidence, each better than every one left out (thesis §3.3.4):\n"
            ),
        };
        let v3 = |p: [f64; 3]| {
            format!(
                "({}, {}, {})",
                significant(p[0]),
                significant(p[1]),
                significant(p[2])
            )
        };
        for (k, m) in self.isoc.iter().enumerate() {
            let vars: Vec<String> = binding
                .specs
                .iter()
                .filter_map(|spec| Some((&spec.id, m.variables.get(&spec.id)?)))
                .map(|(id, value)| match *value {
                    ResultValue::ObjectInSurface { position, anchor }
                    | ResultValue::LightInSurface { position, anchor }
                    | ResultValue::HoleInSurface { position, anchor } => {
                        format!("{id} at {} (P = {})", v3(anchor), v3(position))
                    }
                    ResultValue::DirectionalLight { direction } => {
                        format!("{id} along {}", v3(direction))
                    }
                    ResultValue::Color { value, .. } => format!("{id} V = {}", significant(value)),
                })
                .collect();
            out += &format!(
                "{:>3}. {} lx [{}, {}]  {}\n",
                k + 1,
                significant(m.estimate.mean),
                significant(m.estimate.low),
                significant(m.estimate.high),
                vars.join(", ")
            );
        }
        out
    }

    /// Member `number` (counted from 1, as `isoc-01.png` …) mapped back to `binding`'s
    /// configuration: the one path from a result to the scene.
    pub fn configuration(
        &self,
        binding: &Binding,
        number: usize,
    ) -> Result<crate::space::Configuration, String> {
        let member = number
            .checked_sub(1)
            .and_then(|k| self.isoc.get(k))
            .ok_or_else(|| {
                format!(
                    "no ISOC member {number} (it has {}, counted from 1)",
                    self.isoc.len()
                )
            })?;
        let values = binding
            .specs
            .iter()
            .map(|spec| {
                member
                    .variables
                    .get(&spec.id)
                    .map(|v| v.value())
                    .ok_or_else(|| {
                        format!(
                            "ISOC member {number} has no value for variable '{}'",
                            spec.id
                        )
                    })
            })
            .collect::<Result<Vec<_>, String>>()?;
        binding.configuration(&values)
    }
}
