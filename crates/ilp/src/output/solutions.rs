//! `solutions.csv`: one row per evaluation (thesis §4.2.2), written as the search goes
//! and read back by `--resume`. One [`SolutionRow`] writes and reads a row, through the
//! `csv` crate (quoting: a variable id may hold a comma).
//!
//! Columns: `iteration`; per variable its world value — a placement's point P
//! (`<id>.x`, `<id>.y`, `<id>.z`) and anchor (`<id>.anchor.x`, …), a direction
//! (`<id>.x`, …), a colour value or a dimming level (`<id>.value`); then the goal's
//! `low`, `mean`, `high` (the interval at the run's confidence), `std_error`, `photons`,
//! `seconds` (of this evaluation), `elapsed` (since the run started) and `verdict`; then
//! per constraint (labelled `Desk.minLux`, [`Constraint::label`]) `<label>.low`,
//! `<label>.mean`, `<label>.high`, `<label>.std_error` and `<label>.verdict`
//! (`feasible`, `infeasible` or `undecided`, one-sided at the run's confidence).

use crate::binding::{Binding, ConfigurationError, VariableValue};
use crate::intention::{Constraint, Feasibility};
use crate::problem::VariableKind;
use crate::space::Domain;
use crate::vns::{Evaluation, Record, Verdict};
use glam::DVec3;
use invlight_scene::Diagnostic;
use invlight_stats::Estimate;
use std::path::Path;

/// One row of `solutions.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct SolutionRow {
    /// The candidate's number (the initial configuration is 0).
    pub iteration: u64,
    /// Each variable's world value, in variable order.
    pub values: Vec<VariableValue>,
    /// The goal's and the constraints' estimates.
    pub evaluation: Evaluation,
    /// Seconds this evaluation took.
    pub seconds: f64,
    /// Seconds since the run started (resumed runs go on counting).
    pub elapsed: f64,
    /// What the search decided.
    pub verdict: Verdict,
}

/// The header of a binding's `solutions.csv`.
pub fn header(binding: &Binding) -> Vec<String> {
    let mut h = vec!["iteration".to_string()];
    for v in binding.space.variables() {
        match v.domain {
            Domain::Parallelogram(_) => {
                h.extend(["x", "y", "z"].map(|c| format!("{}.{c}", v.id)));
                h.extend(["x", "y", "z"].map(|c| format!("{}.anchor.{c}", v.id)));
            }
            Domain::Hemisphere(_) => h.extend(["x", "y", "z"].map(|c| format!("{}.{c}", v.id))),
            Domain::Segment { .. } | Domain::Turn { .. } => h.push(format!("{}.value", v.id)),
            Domain::Array(ref a) => {
                h.extend(
                    ["columns", "rows", "walls.columns", "walls.rows"]
                        .map(|c| format!("{}.{c}", v.id)),
                );
                // Only where it is searched, so that a folder of the other kind is
                // not resumed (its header differs).
                if a.turns {
                    h.push(format!("{}.orientation", v.id));
                }
            }
        }
    }
    h.extend(
        [
            "low",
            "mean",
            "high",
            "std_error",
            "photons",
            "seconds",
            "elapsed",
            "verdict",
        ]
        .map(String::from),
    );
    for c in &binding.constraints {
        let label = c.label();
        h.extend(["low", "mean", "high", "std_error", "verdict"].map(|f| format!("{label}.{f}")));
    }
    h
}

/// Columns per constraint.
const CONSTRAINT_COLUMNS: usize = 5;

/// A CSV line (with its newline) of the fields `fields`, quoted where they need it.
pub fn line<I, S>(fields: I) -> String
where
    I: IntoIterator<Item = S>,
    S: AsRef<[u8]>,
{
    let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
    w.write_record(fields)
        .expect("a CSV record in memory always writes");
    String::from_utf8(w.into_inner().expect("an in-memory writer flushes"))
        .expect("fields are UTF-8")
}

impl SolutionRow {
    /// The row of a search record.
    pub fn of(binding: &Binding, record: &Record, elapsed: f64) -> SolutionRow {
        SolutionRow {
            iteration: record.iteration,
            values: binding.values(&record.config),
            evaluation: record.evaluation.clone(),
            seconds: record.seconds,
            elapsed,
            verdict: record.verdict,
        }
    }

    /// The fields, in [`header`]'s order, `low` and `high` at `z`, the constraints'
    /// verdicts at the one-sided `z_one_sided`. Numbers are written in Rust's shortest
    /// form that reads back to the same f64.
    pub fn fields(&self, z: f64, z_one_sided: f64, constraints: &[Constraint]) -> Vec<String> {
        let mut f = vec![self.iteration.to_string()];
        for v in &self.values {
            match *v {
                VariableValue::Position { point, anchor } => {
                    f.extend(point.to_array().map(|c| c.to_string()));
                    f.extend(anchor.to_array().map(|c| c.to_string()));
                }
                VariableValue::Direction(d) => f.extend(d.to_array().map(|c| c.to_string())),
                VariableValue::Colour { value, .. }
                | VariableValue::Power(value)
                | VariableValue::Scale(value)
                | VariableValue::Angle(value)
                | VariableValue::Time { minutes: value, .. } => f.push(value.to_string()),
                VariableValue::Array(a) => {
                    f.extend([
                        a.columns.to_string(),
                        a.rows.to_string(),
                        a.walls[0].to_string(),
                        a.walls[1].to_string(),
                    ]);
                    f.extend(a.orientation.map(|o| o.to_string()));
                }
            }
        }
        let goal = &self.evaluation.goal;
        let i = goal.interval(z);
        f.extend([
            i.low.to_string(),
            goal.mean.to_string(),
            i.high.to_string(),
            goal.std_error.to_string(),
            goal.samples.to_string(),
            format!("{:.6}", self.seconds),
            format!("{:.3}", self.elapsed),
            self.verdict.name().to_string(),
        ]);
        for (c, e) in constraints.iter().zip(&self.evaluation.constraints) {
            let i = e.interval(z);
            f.extend([
                i.low.to_string(),
                e.mean.to_string(),
                i.high.to_string(),
                e.std_error.to_string(),
                c.verdict(e, z_one_sided).name().to_string(),
            ]);
        }
        f
    }

    /// The search record of this row: its values mapped back to a configuration by
    /// [`Binding::configuration`].
    pub fn record(&self, binding: &Binding) -> Result<Record, ConfigurationError> {
        Ok(Record {
            iteration: self.iteration,
            config: binding.configuration(&self.values)?,
            evaluation: self.evaluation.clone(),
            seconds: self.seconds,
            verdict: self.verdict,
        })
    }
}

/// Rows read back from a `solutions.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct Solutions {
    /// The complete rows, as records of the search.
    pub records: Vec<Record>,
    /// `elapsed` of the last row, s.
    pub elapsed: f64,
    /// Bytes of the file up to the end of its last complete row: a row cut short by a
    /// hard stop lies beyond (and is cut off before appending).
    pub complete_len: u64,
}

impl Solutions {
    /// Reads `path`, written for `binding` (same variables in the same order), back into
    /// records. Every complete row must parse, with finite numbers: a row that does not is
    /// an error naming the line. Only a last row without its newline — cut short by a hard
    /// stop — is ignored.
    pub fn read(path: &Path, binding: &Binding) -> Result<Solutions, Diagnostic> {
        let bytes = std::fs::read(path)
            .map_err(|e| Diagnostic::new(path, format!("cannot read it: {e}")))?;
        let complete_len = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        let bad = |line: u64, msg: String| Diagnostic::at_line(path, line as u32, msg);
        let want = header(binding);
        let mut reader = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .from_reader(&bytes[..complete_len]);
        let mut rows = reader.records();
        let mut out = Solutions {
            records: Vec::new(),
            elapsed: 0.0,
            complete_len: complete_len as u64,
        };
        match rows.next() {
            None => return Ok(out),
            Some(h) => {
                let h = h.map_err(|e| bad(1, e.to_string()))?;
                if h.iter().ne(want.iter().map(String::as_str)) {
                    return Err(bad(
                        1,
                        format!(
                            "header '{}' does not match this problem's, expected '{}'",
                            h.iter().collect::<Vec<_>>().join(","),
                            want.join(",")
                        ),
                    ));
                }
            }
        }
        for row in rows {
            let row = row.map_err(|e| Diagnostic::new(path, e.to_string()))?;
            let line = row.position().map_or(0, |p| p.line());
            if row.len() != want.len() {
                return Err(bad(
                    line,
                    format!("{} columns, expected {}", row.len(), want.len()),
                ));
            }
            let cells = Cells {
                row: &row,
                want: &want,
                path,
                line,
            };
            let solution = cells.solution_row(binding, out.elapsed)?;
            out.records.push(
                solution
                    .record(binding)
                    .map_err(|e| bad(line, e.to_string()))?,
            );
            out.elapsed = solution.elapsed;
        }
        Ok(out)
    }
}

/// One complete data row of a `solutions.csv`, with what names its mistakes: the file,
/// the row's line and the header's column names.
struct Cells<'r> {
    row: &'r csv::StringRecord,
    want: &'r [String],
    path: &'r Path,
    line: u64,
}

impl Cells<'_> {
    fn bad(&self, msg: String) -> Diagnostic {
        Diagnostic::at_line(self.path, self.line as u32, msg)
    }

    /// Column `i` as a finite number.
    fn real(&self, i: usize) -> Result<f64, Diagnostic> {
        match self.row[i].parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(self.bad(format!(
                "'{}' in column {}, expected a finite number",
                &self.row[i], self.want[i]
            ))),
        }
    }

    /// Column `i` as a non-negative integer.
    fn integer(&self, i: usize) -> Result<u64, Diagnostic> {
        self.row[i].parse::<u64>().map_err(|_| {
            self.bad(format!(
                "'{}' in column {}, expected an integer",
                &self.row[i], self.want[i]
            ))
        })
    }

    /// Columns `c` to `c + 2` as a vector.
    fn vec3(&self, c: usize) -> Result<DVec3, Diagnostic> {
        Ok(DVec3::new(
            self.real(c)?,
            self.real(c + 1)?,
            self.real(c + 2)?,
        ))
    }

    /// The row: its variables' values, the goal's estimate, times and verdict, then the
    /// constraints' estimates; its `elapsed` may not go back before `last_elapsed`, the
    /// row above's.
    fn solution_row(
        &self,
        binding: &Binding,
        last_elapsed: f64,
    ) -> Result<SolutionRow, Diagnostic> {
        let iteration = self.integer(0)?;
        let (values, c) = self.values(binding)?;
        let (low, mean, high, std_error) = (
            self.real(c)?,
            self.real(c + 1)?,
            self.real(c + 2)?,
            self.real(c + 3)?,
        );
        let samples = self.integer(c + 4)?;
        let (seconds, elapsed) = (self.real(c + 5)?, self.real(c + 6)?);
        let verdict = Verdict::parse(&self.row[c + 7])
            .ok_or_else(|| self.bad(format!("verdict '{}' unknown", &self.row[c + 7])))?;
        if !(std_error >= 0.0 && low <= mean && mean <= high && samples > 0) {
            return Err(self.bad(
                "the estimate is inconsistent (expected low ≤ mean ≤ high, std_error ≥ 0, photons > 0)".into(),
            ));
        }
        if !(seconds >= 0.0 && elapsed >= last_elapsed) {
            return Err(self.bad(format!(
                "times {seconds} s and {elapsed} s, expected non-negative seconds and an elapsed time that does not go back ({last_elapsed} s before)"
            )));
        }
        Ok(SolutionRow {
            iteration,
            values,
            evaluation: Evaluation {
                goal: Estimate {
                    mean,
                    std_error,
                    samples,
                },
                constraints: self.constraints(binding, c + 8, samples)?,
                groups: Vec::new(),
                solved: None,
            },
            seconds,
            elapsed,
            verdict,
        })
    }

    /// The variables' world values from column 1 on, and the first column after them.
    fn values(&self, binding: &Binding) -> Result<(Vec<VariableValue>, usize), Diagnostic> {
        let mut values = Vec::new();
        let mut c = 1;
        for (v, spec) in binding.space.variables().iter().zip(&binding.specs) {
            match &v.domain {
                Domain::Parallelogram(_) => {
                    values.push(VariableValue::Position {
                        point: self.vec3(c)?,
                        anchor: self.vec3(c + 3)?,
                    });
                    c += 6;
                }
                Domain::Hemisphere(_) => {
                    values.push(VariableValue::Direction(self.vec3(c)?));
                    c += 3;
                }
                Domain::Array(a) => {
                    let count = |k: usize| -> Result<u32, Diagnostic> {
                        let x = self.real(k)?;
                        Ok(x.clamp(0.0, f64::from(u32::MAX)) as u32)
                    };
                    let orientation = if a.turns {
                        Some(self.real(c + 4)?)
                    } else {
                        None
                    };
                    values.push(VariableValue::Array(crate::space::ArrayShape {
                        columns: count(c)?,
                        rows: count(c + 1)?,
                        walls: [self.real(c + 2)?, self.real(c + 3)?],
                        orientation,
                    }));
                    c += a.dimensions();
                }
                Domain::Segment { .. } | Domain::Turn { .. } => {
                    // A colour's row holds V alone; K_d follows from it (and is not
                    // needed to map the row back to a configuration).
                    let x = self.real(c)?;
                    values.push(match spec.kind {
                        VariableKind::LightPower { .. } => VariableValue::Power(x),
                        VariableKind::HoleSize { .. } => VariableValue::Scale(x),
                        VariableKind::ObjectRotation { .. } => VariableValue::Angle(x),
                        VariableKind::SunTime { .. } => VariableValue::Time {
                            minutes: x,
                            direction: DVec3::ZERO,
                        },
                        _ => VariableValue::Colour {
                            value: x,
                            rgb: [0.0; 3],
                        },
                    });
                    c += 1;
                }
            }
        }
        Ok((values, c))
    }

    /// The constraints' estimates from column `first` on, each of `samples` photons.
    fn constraints(
        &self,
        binding: &Binding,
        first: usize,
        samples: u64,
    ) -> Result<Vec<Estimate>, Diagnostic> {
        let mut constraints = Vec::new();
        for (k, constraint) in binding.constraints.iter().enumerate() {
            let at = first + k * CONSTRAINT_COLUMNS;
            let (low, mean, high, std_error) = (
                self.real(at)?,
                self.real(at + 1)?,
                self.real(at + 2)?,
                self.real(at + 3)?,
            );
            if Feasibility::parse(&self.row[at + 4]).is_none()
                || !(std_error >= 0.0 && low <= mean && mean <= high)
            {
                return Err(self.bad(format!(
                    "the estimate of constraint {} is inconsistent (expected low ≤ mean ≤ high, std_error ≥ 0, a verdict feasible, infeasible or undecided)",
                    constraint.label()
                )));
            }
            constraints.push(Estimate {
                mean,
                std_error,
                samples,
            });
        }
        Ok(constraints)
    }
}
