//! Whether an illuminance grid meets a lighting requirement (EN 12464-1:2021: the
//! maintained average Ēm over the task area and the uniformity U0 = Emin/Ē over its
//! calculation grid), said with a stated confidence: **meets**, **fails**, or **cannot
//! tell at this photon count**. A grid's values are estimates; a verdict that ignores
//! their noise can call a grid compliant on luck. No peer (DIALux, Relux) qualifies its
//! verdict so.
//!
//! # The statistics
//!
//! With the confidence c = 1 − α of the run, each of the k criteria checked (Em, U0 or
//! both) gets α/k (Bonferroni), so the grid's verdict holds jointly at c and each
//! criterion's on its own at ≥ c. All bounds are one-sided normal bounds: the estimates
//! are means over at least 32 stratified photon groups, their errors the groups' spread
//! (`invlight_photon::MIN_GROUPS`; the t quantile of 31 degrees of freedom is within
//! 4 % of the normal one).
//!
//! - **Em.** The surface's mean Ē is measured as one estimate with its own standard
//!   error ([`IlluminanceMap::mean`]): the cells' estimates come from the same photons
//!   and are correlated, so the spread of the cells says nothing of Ē's error. The
//!   maintained value is MF·Ē (MF the maintenance factor of EN 12464-1 and CIE 97:2005), its
//!   bounds MF·(Ē ∓ z·σ) with z = Φ⁻¹(1 − α/k). *Meets* when the lower bound is ≥ Em,
//!   *fails* when the upper bound is below it, else *cannot tell*.
//! - **U0.** Emin over noisy cells is biased low (a minimum picks the cells that came out
//!   low) and U0 is a ratio of correlated estimates, so no plug-in interval is honest.
//!   U0 ≥ u holds exactly when every cell i has Dᵢ = Eᵢ − u·Ē ≥ 0. The n cells are
//!   tested together, α/k shared among them (Bonferroni: z′ = Φ⁻¹(1 − α/(k·n))), and
//!   with a standard deviation bound valid whatever their correlation with Ē:
//!   sd(Dᵢ) ≤ σᵢ + u·σ (Cauchy–Schwarz). *Meets* when every cell's lower bound
//!   Dᵢ − z′(σᵢ + uσ) is ≥ 0 — equivalently the U0 lower bound
//!   minᵢ(Eᵢ − z′σᵢ)/(Ē + z′σ) is ≥ u; *fails* when some cell's upper bound is below 0 —
//!   the U0 upper bound minᵢ(Eᵢ + z′σᵢ)/(Ē − z′σ) is below u; else *cannot tell*. The
//!   maintenance factor scales Emin and Ē alike and leaves U0 unchanged.
//!
//! The cells are the means over the cells of the grid (centred on its points), not
//! values at the points; a cell mean smooths the light within it, so with cells larger
//! than the norm's spacing (`invlight_photon::en12464_spacing`) Emin can come out high. Cells the
//! surface covers less than half of are left out of Emin, as [`IlluminanceMap::summary`]
//! leaves them out.

use crate::map::IlluminanceMap;
use invlight_scene::en12464::{TASKS, Task, task};
use invlight_stats::{Confidence, Estimate, normal_quantile};
use std::fmt;

/// What a grid must meet.
#[derive(Debug, Clone, PartialEq)]
pub struct Requirement {
    /// The task's name and description, when it came from [`TASKS`].
    pub task: Option<Task>,
    /// Required maintained average illuminance, lx.
    pub em: Option<f64>,
    /// Required uniformity Emin/Ē.
    pub u0: Option<f64>,
    /// Maintenance factor MF in (0, 1]: maintained = MF × the computed (new) values.
    pub maintenance_factor: f64,
}

impl Requirement {
    /// The requirement of `task`, with the maintenance factor `mf`.
    pub fn of_task(task: &Task, mf: f64) -> Requirement {
        Requirement {
            task: Some(*task),
            em: Some(task.em),
            u0: Some(task.u0),
            maintenance_factor: mf,
        }
    }
}

/// A requirement the command line cannot ask for.
#[derive(Debug, Clone, PartialEq)]
pub enum RequirementError {
    /// A `--maintenance-factor` outside (0, 1].
    MaintenanceFactor(f64),
    /// A `--task` that names no task of [`TASKS`].
    UnknownTask(String),
}

impl fmt::Display for RequirementError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RequirementError::MaintenanceFactor(mf) => {
                write!(f, "--maintenance-factor {mf}: expected a factor in (0, 1]")
            }
            RequirementError::UnknownTask(name) => {
                let names: Vec<&str> = TASKS.iter().map(|t| t.name).collect();
                write!(
                    f,
                    "--task {name}: not a task of the table; it has {}",
                    names.join(", ")
                )
            }
        }
    }
}

impl std::error::Error for RequirementError {}

impl Requirement {
    /// The requirement the command line asks for: a task's (`--task`), with `em` and
    /// `u0` given replacing its values, or these alone; `None` when nothing is asked.
    pub fn from_flags(
        task_name: Option<&str>,
        em: Option<f64>,
        u0: Option<f64>,
        maintenance_factor: f64,
    ) -> Result<Option<Requirement>, RequirementError> {
        if !(maintenance_factor > 0.0 && maintenance_factor <= 1.0) {
            return Err(RequirementError::MaintenanceFactor(maintenance_factor));
        }
        let task = match task_name {
            Some(name) => {
                Some(*task(name).ok_or_else(|| RequirementError::UnknownTask(name.to_string()))?)
            }
            None => None,
        };
        if task.is_none() && em.is_none() && u0.is_none() {
            return Ok(None);
        }
        Ok(Some(Requirement {
            em: em.or(task.map(|t| t.em)),
            u0: u0.or(task.map(|t| t.u0)),
            task,
            maintenance_factor,
        }))
    }
}

/// The answer for one criterion, or for the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Met with the stated confidence.
    Meets,
    /// Not met, with the stated confidence.
    Fails,
    /// The interval straddles the requirement: more photons would tell.
    CannotTell,
}

impl Verdict {
    /// The verdict in one word as tables and `--json` give it: `meets`, `fails`,
    /// `cannot tell`.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Meets => "meets",
            Verdict::Fails => "fails",
            Verdict::CannotTell => "cannot tell",
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Verdict::Meets => "meets",
            Verdict::Fails => "fails",
            Verdict::CannotTell => "cannot tell at this photon count — trace more",
        })
    }
}

/// One criterion checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Criterion {
    /// `Em` or `U0`.
    pub name: &'static str,
    /// The value required (a minimum).
    pub required: f64,
    /// The estimate (maintained Ē, lx; or Emin/Ē).
    pub value: f64,
    /// Lower and upper one-sided bounds at the criterion's level.
    pub bounds: (f64, f64),
    /// The level each bound holds at, 1 − α/k.
    pub level: f64,
    /// Its verdict.
    pub verdict: Verdict,
}

impl Criterion {
    /// The sentence a report prints: "meets Em ≥ 500 lx with 95 % confidence".
    pub fn sentence(&self, confidence: f64) -> String {
        let req = match self.name {
            "Em" => format!("Em ≥ {} lx", plain(self.required)),
            _ => format!("U0 ≥ {:.2}", self.required),
        };
        let pct = format!("{} %", plain(confidence * 100.0));
        match self.verdict {
            Verdict::Meets => format!("meets {req} with {pct} confidence"),
            Verdict::Fails => format!("fails {req} with {pct} confidence"),
            Verdict::CannotTell => {
                format!("cannot tell whether it meets {req} at this photon count — trace more")
            }
        }
    }
}

/// A grid's compliance.
#[derive(Debug, Clone, PartialEq)]
pub struct Compliance {
    /// What was required.
    pub requirement: Requirement,
    /// The joint confidence c of the verdict.
    pub confidence: f64,
    /// Each criterion checked.
    pub criteria: Vec<Criterion>,
    /// Meets when every criterion meets, fails when any fails, else cannot tell.
    pub verdict: Verdict,
}

/// `x` with four significant digits and no trailing zeros: 500, 0.6, 99.5.
pub fn plain(x: f64) -> String {
    let s = invlight_stats::significant(x);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn verdict(low: f64, high: f64, required: f64) -> Verdict {
    if low >= required {
        Verdict::Meets
    } else if high < required {
        Verdict::Fails
    } else {
        Verdict::CannotTell
    }
}

/// The compliance of a grid given as its cells' estimates (those that count for Emin)
/// and the surface's own mean estimate, as the module doc says.
pub fn assess(
    cells: &[Estimate],
    mean: &Estimate,
    requirement: &Requirement,
    confidence: Confidence,
) -> Compliance {
    let alpha = 1.0 - confidence.level();
    let k = [requirement.em, requirement.u0]
        .iter()
        .flatten()
        .count()
        .max(1) as f64;
    let level = 1.0 - alpha / k;
    let mf = requirement.maintenance_factor;
    let mut criteria = Vec::new();
    if let Some(em) = requirement.em {
        let z = normal_quantile(level);
        let (m, s) = (mf * mean.mean, mf * mean.std_error);
        let bounds = (m - z * s, m + z * s);
        criteria.push(Criterion {
            name: "Em",
            required: em,
            value: m,
            bounds,
            level,
            verdict: verdict(bounds.0, bounds.1, em),
        });
    }
    if let Some(u) = requirement.u0 {
        let n = cells.len().max(1) as f64;
        let z = normal_quantile(1.0 - alpha / (k * n));
        let (e, around) = (mean.mean, mean.interval(z));
        let emin = cells.iter().map(|c| c.mean).fold(f64::INFINITY, f64::min);
        let low_min = cells
            .iter()
            .map(|c| c.interval(z).low)
            .fold(f64::INFINITY, f64::min);
        let high_min = cells
            .iter()
            .map(|c| c.interval(z).high)
            .fold(f64::INFINITY, f64::min);
        let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { f64::INFINITY };
        let value = ratio(emin, e);
        let low = ratio(low_min, around.high).max(0.0);
        let high = if around.low > 0.0 {
            ratio(high_min, around.low)
        } else {
            f64::INFINITY
        };
        // No cell the surface mostly covers: no Emin, nothing to tell.
        let (low, high) = if cells.is_empty() {
            (0.0, f64::INFINITY)
        } else {
            (low, high)
        };
        criteria.push(Criterion {
            name: "U0",
            required: u,
            value,
            bounds: (low, high),
            level: 1.0 - alpha / (k * n),
            verdict: verdict(low, high, u),
        });
    }
    let all = |v: Verdict| criteria.iter().all(|c| c.verdict == v);
    let verdict = if criteria.iter().any(|c| c.verdict == Verdict::Fails) {
        Verdict::Fails
    } else if all(Verdict::Meets) && !criteria.is_empty() {
        Verdict::Meets
    } else {
        Verdict::CannotTell
    };
    Compliance {
        requirement: requirement.clone(),
        confidence: confidence.level(),
        criteria,
        verdict,
    }
}

impl IlluminanceMap {
    /// The estimates of the cells that count for Emin: those the surface covers at
    /// least half of.
    pub fn emin_cells(&self) -> Vec<Estimate> {
        let full = (self.cell_u * self.cell_v) as f64;
        self.cells
            .iter()
            .flatten()
            .filter(|c| c.area >= 0.5 * full)
            .map(|c| c.estimate)
            .collect()
    }

    /// This grid's compliance with `requirement` at `confidence`.
    pub fn compliance(&self, requirement: &Requirement, confidence: Confidence) -> Compliance {
        assess(&self.emin_cells(), &self.mean, requirement, confidence)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An estimate of `mean` whose two-sided 95 % interval is ± `half`.
    fn est(mean: f64, half: f64) -> Estimate {
        Estimate {
            mean,
            std_error: half / Confidence::DEFAULT.z(),
            samples: 1 << 20,
        }
    }

    fn em_only(em: f64) -> Requirement {
        Requirement {
            task: None,
            em: Some(em),
            u0: None,
            maintenance_factor: 1.0,
        }
    }

    #[test]
    fn em_verdicts_follow_the_interval() {
        let c = Confidence::DEFAULT;
        let cells = [est(520.0, 5.0)];
        let v = |mean: Estimate, req: &Requirement| assess(&cells, &mean, req, c).verdict;
        // True Em 520 lx: ±5 lx meets 500, ±40 lx cannot tell; 470 ± 5 fails.
        assert_eq!(v(est(520.0, 5.0), &em_only(500.0)), Verdict::Meets);
        assert_eq!(v(est(520.0, 40.0), &em_only(500.0)), Verdict::CannotTell);
        assert_eq!(v(est(470.0, 5.0), &em_only(500.0)), Verdict::Fails);
        // A maintenance factor of 0.8 brings 520 lx new to 416 lx maintained: fails.
        let mf = Requirement {
            maintenance_factor: 0.8,
            ..em_only(500.0)
        };
        let r = assess(&cells, &est(520.0, 5.0), &mf, c);
        assert_eq!(r.verdict, Verdict::Fails);
        assert!((r.criteria[0].value - 416.0).abs() < 1e-9);
        assert_eq!(
            r.criteria[0].sentence(0.95),
            "fails Em ≥ 500 lx with 95 % confidence"
        );
    }

    #[test]
    fn uniformity_needs_every_cell_and_counts_them() {
        let c = Confidence::DEFAULT;
        let req = Requirement {
            task: None,
            em: None,
            u0: Some(0.6),
            maintenance_factor: 1.0,
        };
        let mean = est(500.0, 2.0);
        // Every cell at 400 ± 4 lx: U0 = 0.8, surely above 0.6.
        let even = vec![est(400.0, 4.0); 100];
        assert_eq!(assess(&even, &mean, &req, c).verdict, Verdict::Meets);
        // One cell at 250 ± 4 lx: U0 = 0.5, surely below.
        let mut dark = even.clone();
        dark[37] = est(250.0, 4.0);
        let r = assess(&dark, &mean, &req, c);
        assert_eq!(r.verdict, Verdict::Fails);
        assert!((r.criteria[0].value - 0.5).abs() < 1e-12);
        // One cell at 305 ± 10 lx: its plug-in U0 0.61 passes, but a cell picked as the
        // minimum of a hundred cannot be told from 300 at this noise.
        let mut close = even.clone();
        close[3] = est(305.0, 10.0);
        let r = assess(&close, &mean, &req, c);
        assert!(r.criteria[0].value > 0.6);
        assert_eq!(r.verdict, Verdict::CannotTell);
        // The multiplicity correction widens with the number of cells: the same close
        // cell alone (no others to pick it from) is still undecided at ±10, decided at ±2.
        let alone = [est(305.0, 2.0)];
        assert_eq!(assess(&alone, &mean, &req, c).verdict, Verdict::Meets);
        let (lo100, _) = r.criteria[0].bounds;
        let (lo1, _) = assess(&[est(305.0, 10.0)], &mean, &req, c).criteria[0].bounds;
        assert!(lo100 < lo1);
    }

    #[test]
    fn both_criteria_share_the_error_rate() {
        let c = Confidence::DEFAULT;
        let req = Requirement::of_task(task("office").unwrap(), 1.0);
        let r = assess(&vec![est(400.0, 4.0); 10], &est(520.0, 5.0), &req, c);
        assert_eq!(r.criteria.len(), 2);
        assert!((r.criteria[0].level - 0.975).abs() < 1e-12);
        assert!((r.criteria[1].level - (1.0 - 0.05 / 20.0)).abs() < 1e-12);
        assert_eq!(r.verdict, Verdict::Meets);
    }

    #[test]
    fn a_grid_leaves_its_slivers_out_of_emin() {
        use crate::map::MapCell;
        use glam::Vec3;
        // 2 × 1 cells of 1 m²: a full one at 520 ± 5 lx and a sliver (0.1 m² of the
        // surface) whose estimate, 100 lx on few photons, must not decide U0.
        let cell = |c: u32, area: f64, e: Estimate| {
            Some(MapCell {
                index: (c, 0),
                centre: Vec3::new(c as f32 + 0.5, 0.5, 0.0),
                area,
                estimate: e,
                hits: 100,
            })
        };
        let map = IlluminanceMap {
            origin: Vec3::ZERO,
            u: Vec3::X,
            v: Vec3::Y,
            columns: 2,
            rows: 1,
            cell_u: 1.0,
            cell_v: 1.0,
            cells: vec![
                cell(0, 1.0, est(520.0, 5.0)),
                cell(1, 0.1, est(100.0, 60.0)),
            ],
            photons: 1 << 20,
            mean: est(482.0, 5.0),
            u0: est(1.08, 0.02),
            spacing: 1.0,
            spacing_rule: String::new(),
            side: invlight_photon::Side::Both,
            values: invlight_photon::GridValues::CellMeans,
            front_back: (482.0, 0.0),
        };
        assert_eq!(map.emin_cells().len(), 1);
        let office = Requirement::of_task(task("office").unwrap(), 1.0);
        let r = map.compliance(&office, Confidence::DEFAULT);
        // Em: 482 ± 5 lx fails 500; U0 = 520/482 meets 0.6; the grid fails.
        assert_eq!(r.criteria[0].verdict, Verdict::Fails);
        assert_eq!(r.criteria[1].verdict, Verdict::Meets);
        assert_eq!(r.verdict, Verdict::Fails);
        // A grid of slivers alone has no Emin: U0 cannot be told, never met by default.
        let slivers = IlluminanceMap {
            cells: vec![
                cell(0, 0.2, est(520.0, 5.0)),
                cell(1, 0.1, est(100.0, 60.0)),
            ],
            ..map
        };
        let r = slivers.compliance(&office, Confidence::DEFAULT);
        assert_eq!(r.criteria[1].verdict, Verdict::CannotTell);
    }

    #[test]
    fn flags_make_requirements() {
        let r = Requirement::from_flags(Some("corridor"), None, Some(0.5), 0.8)
            .unwrap()
            .unwrap();
        assert_eq!(
            (r.em, r.u0, r.maintenance_factor),
            (Some(100.0), Some(0.5), 0.8)
        );
        assert_eq!(Requirement::from_flags(None, None, None, 1.0), Ok(None));
        assert!(
            Requirement::from_flags(Some("kitchen"), None, None, 1.0)
                .unwrap_err()
                .to_string()
                .contains("office")
        );
        assert!(Requirement::from_flags(None, Some(500.0), None, 1.5).is_err());
    }
}
