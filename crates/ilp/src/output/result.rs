//! `result.json`: the ISOC as the search leaves it, rewritten whenever it changes, and
//! read back by `render/measure/map --config RESULT#K`. One [`ResultFile`] writes and
//! reads it.

use crate::binding::{Binding, ConfigurationError, Layout, VariableValue};
use crate::intention::{Constraint, Goal, Side};
use crate::isoc::Member;
use crate::problem::{VariableKind, VariableSpec};
use crate::vns::Standing;
use glam::DVec3;
use invlight_scene::Diagnostic;
use invlight_scene::daylight::TimeOfDay;
use invlight_stats::significant;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The version of `result.json`'s layout; readers refuse another. Version 2 added the
/// goals other than `maximizeRadiance`, the constraints and `closest`; version 1 files
/// (one surface maximised) still read.
pub const RESULT_SCHEMA: u32 = 2;

/// What `result.json` says of the goal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectiveInfo {
    /// The goal's problem-file element: `maximizeRadiance`, `minimizeRadiance`,
    /// `targetRadiance`, `maximizeUniformity`, `minimizePower` or
    /// `maximizeDaylightFactor`.
    #[serde(default = "maximize_radiance")]
    pub element: String,
    /// The surface it is about (none for `minimizePower`).
    pub surface: Option<String>,
    /// The side counted: `front`, `back` or `both`.
    #[serde(default = "both")]
    pub side: String,
    /// `maximize`, `minimize`, `target`, `maximizeUniformity` or `minimizePower`.
    pub sense: String,
    /// `lx`, `lm`, or `` for a uniformity.
    pub unit: String,
    /// `maxRadiosity`, lx.
    pub cap: Option<f64>,
    /// `targetRadiance`'s illuminance, lx.
    #[serde(default)]
    pub target: Option<f64>,
    /// The problem file solved (absolute), so that `invlight report DIR` can rebuild
    /// the report from the folder alone. Optional and absent in folders written before
    /// it was recorded: readers of this schema version read either.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub problem: Option<std::path::PathBuf>,
}

impl ObjectiveInfo {
    /// The goal's unit with a space before it (nothing for a ratio), for numbers.
    pub fn unit_suffix(&self) -> String {
        match self.unit.as_str() {
            "" => String::new(),
            u => format!(" {u}"),
        }
    }
}

fn maximize_radiance() -> String {
    "maximizeRadiance".into()
}

fn both() -> String {
    "both".into()
}

impl ObjectiveInfo {
    /// The goal of `problem` as `binding` bound it (which says what `minimizePower`
    /// counts).
    pub fn of(problem: &crate::problem::Problem, binding: &Binding) -> ObjectiveInfo {
        let goal = &problem.goal;
        ObjectiveInfo {
            element: goal.element().into(),
            surface: goal.surface().map(|s| s.name.clone()),
            side: goal.surface().map_or(Side::Both, |s| s.side).name().into(),
            sense: goal.sense().into(),
            unit: binding.goal_unit().into(),
            cap: match goal {
                Goal::Maximize { cap, .. } => *cap,
                _ => None,
            },
            target: match goal {
                Goal::Target { lux, .. } => Some(*lux),
                _ => None,
            },
            problem: std::fs::canonicalize(&problem.path).ok(),
        }
    }

    /// The goal in words, for tables and pages: "the most light of 'Desk'".
    pub fn words(&self) -> String {
        let on = |what: &str| match (&self.surface, self.side.as_str()) {
            (Some(s), "both") => format!("{what} of '{s}'"),
            (Some(s), side) => format!("{what} of '{s}' ({side})"),
            (None, _) => what.to_string(),
        };
        match self.element.as_str() {
            "minimizeRadiance" => on("the least mean illuminance"),
            "targetRadiance" => on(&format!(
                "the mean illuminance closest to {} lx",
                significant(self.target.unwrap_or_default())
            )),
            "maximizeUniformity" => on("the most uniform light (U0)"),
            "maximizeDaylightFactor" => on("the largest daylight factor (DF %, CIE overcast sky)"),
            "minimizePower" if self.unit == "W" => "the least electrical power (W)".into(),
            "minimizePower" => {
                "the least lamp power as luminous flux (lm: not every lamp's file gives watts)"
                    .into()
            }
            "minimizeGlare" => "the least glare (UGR, CIE 117) at its observer".into(),
            _ => on("the most light"),
        }
    }
}

/// What `result.json` says of a constraint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConstraintInfo {
    /// Its label, as the columns of `solutions.csv` name it: `Desk.minLux`.
    pub label: String,
    /// The surface.
    pub surface: String,
    /// The side counted.
    pub side: String,
    /// The bound's attribute: `minLux`, `maxLux`, `minUniformity`, `minPointLux` or
    /// `minDaylightFactor`.
    pub bound: String,
    /// The limit the estimates are held to, in `unit`: for an illuminance under a
    /// maintenance factor, the new installation's (`maintained_limit` ÷ MF).
    pub limit: f64,
    /// `lx`, `` for a uniformity, or `DF %` for a daylight factor.
    pub unit: String,
    /// Under `<objectives maintenanceFactor>`, the maintenance factor an illuminance
    /// limit is divided by, and the limit as the file states it (maintained).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub maintenance_factor: Option<f64>,
    /// ″
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub maintained_limit: Option<f64>,
    /// The standard's name for it, when a `<task>` asked it:
    /// `EN 12464-1 office: immediate surrounding Ēm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub standard: Option<String>,
}

impl ConstraintInfo {
    /// The constraint `c`.
    pub fn of(c: &Constraint) -> ConstraintInfo {
        ConstraintInfo {
            label: c.label(),
            surface: c.surface.name.clone(),
            side: c.surface.side.name().into(),
            bound: c.bound.attribute().into(),
            limit: c.bound.limit(),
            unit: c.unit().into(),
            maintenance_factor: (c.maintenance_factor != 1.0).then_some(c.maintenance_factor),
            maintained_limit: (c.maintenance_factor != 1.0).then(|| c.maintained_limit()),
            standard: c.standard_name(),
        }
    }
}

/// A constraint's estimate in a member, with its verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResultConstraint {
    /// [`ConstraintInfo::label`].
    pub label: String,
    /// The estimate of the bounded quantity.
    #[serde(flatten)]
    pub estimate: ResultEstimate,
    /// `feasible`, `infeasible` or `undecided`, one-sided at the run's confidence.
    pub verdict: String,
    /// The one-sided bound that decides it, at the run's confidence: mean − z·σ for a
    /// lower limit (`minLux`, `minUniformity` …), mean + z·σ for an upper one
    /// (`maxLux`), z one-sided. Absent in files written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bound: Option<f64>,
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
    /// `lightAim`: the unit vector of the lamp's aim (a spot's axis, a luminaire's
    /// γ = 0).
    #[serde(rename = "lightAim")]
    LightAim {
        /// The aim.
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
    /// `lightPower`: the dimming level, the light's output over its authored output.
    #[serde(rename = "lightPower")]
    LightPower {
        /// The level.
        value: f64,
    },
    /// `holeSize`: the hole's size over its authored size (a uniform scale).
    #[serde(rename = "holeSize")]
    HoleSize {
        /// The scale.
        scale: f64,
    },
    /// `objectRotation`: the turn about the placement's normal, degrees.
    #[serde(rename = "objectRotation")]
    ObjectRotation {
        /// The angle, degrees, counter-clockwise about the normal.
        degrees: f64,
    },
    /// `sunTime`: the local clock time, and the sunlight's direction then.
    #[serde(rename = "sunTime")]
    SunTime {
        /// `HH:MM:SS`, local.
        time: TimeOfDay,
        /// Minutes after local midnight.
        minutes: f64,
        /// The unit vector the sunlight travels along.
        direction: [f64; 3],
    },
    /// `lightArray`: the lamps set out, as columns × rows, and how far the outer
    /// ones stand from the rectangle's edges (the member's `layouts` give the metres).
    #[serde(rename = "lightArray")]
    LightArray {
        /// Lamps along the rectangle's first edge.
        columns: u32,
        /// Lamps along the other.
        rows: u32,
        /// The distance from the outer columns and rows to the edges, each a fraction
        /// of its spacing.
        walls: [f64; 2],
        /// The degrees its lamps are turned about their aim, 0 or 90, where the search
        /// chooses it (`orientation="search"`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        orientation: Option<f64>,
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
            (VariableValue::Direction(d), VariableKind::LightAim { .. }) => ResultValue::LightAim {
                direction: d.to_array(),
            },
            (VariableValue::Direction(d), _) => ResultValue::DirectionalLight {
                direction: d.to_array(),
            },
            (VariableValue::Colour { value, rgb }, _) => ResultValue::Color { value, rgb },
            (VariableValue::Power(value), _) => ResultValue::LightPower { value },
            (VariableValue::Scale(scale), _) => ResultValue::HoleSize { scale },
            (VariableValue::Angle(degrees), _) => ResultValue::ObjectRotation { degrees },
            (VariableValue::Time { minutes, direction }, _) => ResultValue::SunTime {
                time: TimeOfDay::from_minutes(minutes),
                minutes,
                direction: direction.to_array(),
            },
            (VariableValue::Array(a), _) => ResultValue::LightArray {
                columns: a.columns,
                rows: a.rows,
                walls: a.walls,
                orientation: a.orientation,
            },
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
            ResultValue::DirectionalLight { direction } | ResultValue::LightAim { direction } => {
                VariableValue::Direction(DVec3::from_array(direction))
            }
            ResultValue::Color { value, rgb } => VariableValue::Colour { value, rgb },
            ResultValue::LightPower { value } => VariableValue::Power(value),
            ResultValue::HoleSize { scale } => VariableValue::Scale(scale),
            ResultValue::ObjectRotation { degrees } => VariableValue::Angle(degrees),
            ResultValue::SunTime {
                minutes, direction, ..
            } => VariableValue::Time {
                minutes,
                direction: DVec3::from_array(direction),
            },
            ResultValue::LightArray {
                columns,
                rows,
                walls,
                orientation,
            } => VariableValue::Array(crate::space::ArrayShape {
                columns,
                rows,
                walls,
                orientation,
            }),
        }
    }
}

/// An ISOC member (or one of the configurations closest to feasible).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResultMember {
    /// Each variable's value, by id.
    pub variables: BTreeMap<String, ResultValue>,
    /// The goal's estimate, in its unit.
    pub estimate: ResultEstimate,
    /// Each constraint's estimate and verdict, in the problem's order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub constraints: Vec<ResultConstraint>,
    /// For a configuration closest to feasible: the largest relative shortfall of a
    /// constraint's mean from its limit (0.1: 10 % short).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub violation: Option<f64>,
    /// Each group of interchangeable lamps as laid out: a regular array (rows ×
    /// columns, spacing, distance from the walls) or not, and its levels
    /// ([`Binding::layouts`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub layouts: Vec<Layout>,
}

/// `result.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResultFile {
    /// [`RESULT_SCHEMA`].
    pub schema_version: u32,
    /// The goal.
    pub objective: ObjectiveInfo,
    /// The constraints.
    #[serde(default)]
    pub constraints: Vec<ConstraintInfo>,
    /// N, photons of a full evaluation.
    pub photons: u64,
    /// Confidence of the intervals and comparisons.
    pub confidence: f64,
    /// Evaluations so far (a resumed run's included).
    pub evaluations: u64,
    /// Candidates not traced: they put an object or light outside the scene, or two
    /// interchangeable lamps in one cell.
    pub refused: u64,
    /// Why the search stopped ([`crate::Outcome::stopped`]); absent while it runs and
    /// in files written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stopped: Option<String>,
    /// The search stopped because no configuration it tried lit the goal's surface
    /// ([`crate::Outcome::Unlit`]): the ISOC is the initial configuration, in the dark.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub unlit: bool,
    /// Seconds since the run (first) started.
    pub seconds: f64,
    /// Whether a configuration meeting every constraint was found: when not, `isoc` is
    /// empty and `closest` says which came nearest.
    #[serde(default = "yes")]
    pub feasible: bool,
    /// The ISOC, best first: feasible configurations that cannot be told apart.
    pub isoc: Vec<ResultMember>,
    /// When the ISOC is empty, the configurations that violate the constraints least,
    /// least first.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub closest: Vec<ResultMember>,
    /// The best regular array of the interchangeable lamps the search tried and found
    /// feasible ([`crate::Standing::best_start`]), as looked at: what an answer of
    /// free positions saves against the layout a designer would draw first. Absent
    /// without free interchangeable lamps (a `<lightArray>`'s answer is an array).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub best_regular_array: Option<ResultMember>,
}

fn yes() -> bool {
    true
}

impl ResultMember {
    /// For a configuration that misses an illuminance minimum with every placed lamp at
    /// full output: the lamps it has and, by the lumen method, about how many of them
    /// it would take — E = N·Φ·UF·MF/A, so at the layout's utilisation factor the
    /// illuminance grows with the lamps' count, and the count needed is N × the
    /// largest ratio of a minimum (`minLux`, `minPointLux`) to its estimate. A first
    /// count to try, as DIALux's lumen method gives one, not a bound: more lamps also
    /// change the layout and its uniformity. `alone`: whether those lamps are the
    /// scene's only light ([`Binding::lit_only_by`]); other light would not grow.
    pub fn lamps_needed(
        &self,
        constraints: &[ConstraintInfo],
        alone: impl Fn(usize) -> bool,
    ) -> Option<(u32, u32)> {
        let levels: Vec<f64> = self
            .layouts
            .iter()
            .flat_map(|l| l.levels.iter().copied())
            .collect();
        if levels.is_empty() || levels.iter().any(|&l| l < 0.999) || !alone(levels.len()) {
            return None;
        }
        let ratio = self
            .constraints
            .iter()
            .zip(constraints)
            .filter(|(_, i)| matches!(i.bound.as_str(), "minLux" | "minPointLux"))
            .filter(|(c, i)| c.estimate.mean > 0.0 && c.estimate.mean < i.limit)
            .map(|(c, i)| i.limit / c.estimate.mean)
            .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))))?;
        let have = levels.len() as u32;
        Some((have, (f64::from(have) * ratio).ceil() as u32))
    }

    /// The member `m` as `binding`'s variables give it, intervals at `z`, verdicts at
    /// the one-sided `z_one_sided`.
    pub fn new(binding: &Binding, m: &Member, (z, z_one_sided): (f64, f64)) -> ResultMember {
        let variables = binding
            .specs
            .iter()
            .zip(binding.values(&m.config))
            .enumerate()
            .map(|(i, (spec, value))| {
                (
                    VariableSpec::key(&binding.specs, i),
                    ResultValue::new(&spec.kind, &value),
                )
            })
            .collect();
        let estimate = |e: &invlight_stats::Estimate| {
            let i = e.interval(z);
            ResultEstimate {
                mean: e.mean,
                low: i.low,
                high: i.high,
                std_error: e.std_error,
                photons: e.samples,
            }
        };
        ResultMember {
            variables,
            estimate: estimate(&m.evaluation.goal),
            constraints: binding
                .constraints
                .iter()
                .zip(&m.evaluation.constraints)
                .map(|(c, e)| ResultConstraint {
                    label: c.label(),
                    estimate: estimate(e),
                    verdict: c.verdict(e, z_one_sided).name().into(),
                    bound: Some(c.one_sided_bound(e, z_one_sided)),
                })
                .collect(),
            violation: None,
            layouts: binding.layouts(&m.config),
        }
    }
}

impl ResultFile {
    /// The ISOC of `standing`, best first, and when it is empty the closest, as
    /// `binding`'s variables give them.
    pub fn members(
        binding: &Binding,
        standing: Standing<'_>,
        z: (f64, f64),
    ) -> (Vec<ResultMember>, Vec<ResultMember>) {
        let isoc = standing
            .isoc
            .best_first()
            .into_iter()
            .map(|m| ResultMember::new(binding, m, z))
            .collect::<Vec<_>>();
        let closest = if isoc.is_empty() {
            standing
                .closest
                .iter()
                .map(|(v, m)| ResultMember {
                    violation: Some(*v),
                    ..ResultMember::new(binding, m, z)
                })
                .collect()
        } else {
            Vec::new()
        };
        (isoc, closest)
    }

    /// The answer: the best ISOC member, else the configuration closest to feasible.
    pub fn answer(&self) -> Option<&ResultMember> {
        self.isoc.first().or(self.closest.first())
    }

    /// The best regular array tried, when the answer is not that array (then it is
    /// worth printing beside it).
    pub fn regular_beside(&self) -> Option<&ResultMember> {
        let r = self.best_regular_array.as_ref()?;
        let answer = self.isoc.first()?;
        (r.variables != answer.variables).then_some(r)
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
        if !(1..=RESULT_SCHEMA).contains(&file.schema_version) {
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

    /// Member `number` (counted from 1, as `isoc-01.png` …) mapped back to `binding`'s
    /// configuration: the one path from a result to the scene.
    pub fn configuration(
        &self,
        binding: &Binding,
        number: usize,
    ) -> Result<crate::space::Configuration, MemberError> {
        // A problem without a feasible configuration has its closest ones instead.
        let members = if self.isoc.is_empty() {
            &self.closest
        } else {
            &self.isoc
        };
        let member =
            number
                .checked_sub(1)
                .and_then(|k| members.get(k))
                .ok_or(MemberError::Missing {
                    number,
                    count: members.len(),
                })?;
        let values = (0..binding.specs.len())
            .map(|i| {
                let key = VariableSpec::key(&binding.specs, i);
                member
                    .variables
                    .get(&key)
                    .map(|v| v.value())
                    .ok_or(MemberError::NoValue { number, key })
            })
            .collect::<Result<Vec<_>, MemberError>>()?;
        binding
            .configuration(&values)
            .map_err(MemberError::Configuration)
    }
}

/// Why a `result.json`'s member maps to no configuration ([`ResultFile::configuration`]).
#[derive(Debug, Clone, PartialEq)]
pub enum MemberError {
    /// No member has this number.
    Missing {
        /// The number asked for, from 1.
        number: usize,
        /// The members there are.
        count: usize,
    },
    /// Member `number` has no value for the variable of key `key`
    /// ([`VariableSpec::key`]).
    NoValue {
        /// The member's number, from 1.
        number: usize,
        /// The variable's key.
        key: String,
    },
    /// The member's values make no configuration of the binding.
    Configuration(ConfigurationError),
}

impl std::fmt::Display for MemberError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MemberError::Missing { number, count } => {
                write!(
                    f,
                    "no ISOC member {number} (it has {count}, counted from 1)"
                )
            }
            MemberError::NoValue { number, key } => {
                write!(f, "ISOC member {number} has no value for variable '{key}'")
            }
            MemberError::Configuration(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for MemberError {}
