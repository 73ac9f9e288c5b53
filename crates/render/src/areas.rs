//! EN 12464-1's requirements on the areas around a task area and their verdicts: the
//! immediate surrounding, the background, the walls and the ceiling
//! ([`invlight_scene::AreaKind`]; the scene builds them), each judged as a task area is
//! ([`crate::compliance`]) with its own maintained Ēm and U0.
//!
//! The figures are the standard's, from [`invlight_scene::en12464`].
//!
//! The verdicts of several areas are statements made together: with m areas judged,
//! each is made at 1 − α/m (Bonferroni), so that all of them hold jointly at the run's
//! confidence, as the criteria of one grid share its α.

use crate::compliance::{Compliance, Requirement, Verdict};
use crate::map::IlluminanceMap;
use invlight_scene::AreaKind;
use invlight_stats::Confidence;
use serde::{Deserialize, Serialize};

/// What the area `kind` must meet around a task area required to meet `task`: its
/// Ēm and U0 with the task's maintenance factor; `None` for the bands when the task's
/// Ēm is not asked (they are derived from it).
pub fn area_requirement(kind: AreaKind, task: &Requirement) -> Option<Requirement> {
    let (em, u0) = kind.required(task.em, task.task.as_ref())?;
    Some(Requirement {
        task: None,
        em: Some(em),
        u0: Some(u0),
        maintenance_factor: task.maintenance_factor,
    })
}

/// One area's verdict in `invlight map --json` (`areas[]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AreaReport {
    /// The area in the standard's words: `immediate surrounding`, `background`,
    /// `wall`, `ceiling`.
    pub area: String,
    /// The calculation surface measured.
    pub surface: String,
    /// The band's width, or the rectangle's two sides, m.
    pub size: [f64; 2],
    /// Columns and rows of its grid, and the cells' sides, m.
    pub cells: [u32; 2],
    /// ″
    pub cell_size: [f32; 2],
    /// Required maintained Ēm, lx.
    pub required_em: f64,
    /// Required U0.
    pub required_u0: f64,
    /// Maintained Ēm (the maintenance factor × the computed mean), lx.
    pub em: f64,
    /// Its one-sided lower and upper bounds, lx.
    pub em_bounds: [f64; 2],
    /// U0 = Emin/Ē over the cells.
    pub u0: f64,
    /// Its one-sided lower and upper bounds (the upper may be infinite, written null).
    pub u0_bounds: [Option<f64>; 2],
    /// The confidence every bound holds at, 1 − α/(2m) for m areas.
    pub level: f64,
    /// `meets`, `fails` or `cannot tell`.
    pub verdict: String,
}

/// One area measured and judged.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaVerdict {
    /// What it stands for.
    pub kind: AreaKind,
    /// Its calculation surface's name.
    pub surface: String,
    /// The band's width, or the rectangle's sides, m.
    pub size: (f64, f64),
    /// Its map.
    pub map: IlluminanceMap,
    /// Its compliance, at the share of the confidence the module doc gives.
    pub compliance: Compliance,
}

impl AreaVerdict {
    /// The areas `maps` (with their kinds, surface names and sizes) judged around a
    /// task area required to meet `task`, jointly at `confidence`; areas without a
    /// requirement (the bands when no Ēm is asked) are left out.
    pub fn judge(
        maps: Vec<(AreaKind, String, (f64, f64), IlluminanceMap)>,
        task: &Requirement,
        confidence: Confidence,
    ) -> Vec<AreaVerdict> {
        let judged: Vec<_> = maps
            .into_iter()
            .filter_map(|(kind, surface, size, map)| {
                area_requirement(kind, task).map(|r| (kind, surface, size, map, r))
            })
            .collect();
        let m = judged.len().max(1) as f64;
        let share = Confidence::new(1.0 - (1.0 - confidence.level()) / m).unwrap_or(confidence);
        judged
            .into_iter()
            .map(|(kind, surface, size, map, r)| AreaVerdict {
                kind,
                surface,
                size,
                compliance: map.compliance(&r, share),
                map,
            })
            .collect()
    }

    /// The area's name as a report prints it: "wall x = 9.00 m", "immediate surrounding".
    pub fn title(&self) -> String {
        match self.kind {
            AreaKind::Wall => self.surface.clone(),
            kind => kind.name().to_string(),
        }
    }

    /// Its `--json` form.
    pub fn report(&self) -> AreaReport {
        let c = &self.compliance;
        let em = &c.criteria[0];
        let u0 = &c.criteria[1];
        let finite = |x: f64| x.is_finite().then_some(x);
        AreaReport {
            area: self.kind.name().into(),
            surface: self.surface.clone(),
            size: [self.size.0, self.size.1],
            cells: [self.map.columns, self.map.rows],
            cell_size: [self.map.cell_u, self.map.cell_v],
            required_em: em.required,
            required_u0: u0.required,
            em: em.value,
            em_bounds: [em.bounds.0, em.bounds.1],
            u0: u0.value,
            u0_bounds: [finite(u0.bounds.0), finite(u0.bounds.1)],
            level: u0.level.min(em.level),
            verdict: match c.verdict {
                Verdict::Meets => "meets",
                Verdict::Fails => "fails",
                Verdict::CannotTell => "cannot tell",
            }
            .into(),
        }
    }
}

/// The verdict on a task area (`task`) and the areas around it together: the worst of
/// theirs — it fails if one fails, cannot be told if one cannot, and meets only when
/// every one meets — with the names of the areas that decide it (the task area's as
/// "task area"), so that a summary never says "meets" above an area that fails.
pub fn overall(task: Verdict, areas: &[AreaReport]) -> (&'static str, Vec<String>) {
    let name = |v: Verdict| match v {
        Verdict::Meets => "meets",
        Verdict::Fails => "fails",
        Verdict::CannotTell => "cannot tell",
    };
    let verdicts = std::iter::once(("task area".to_string(), name(task))).chain(
        areas
            .iter()
            .map(|a| (a.surface.clone(), a.verdict.as_str())),
    );
    let all: Vec<(String, &str)> = verdicts.collect();
    let worst = ["fails", "cannot tell"]
        .into_iter()
        .find(|w| all.iter().any(|(_, v)| v == w))
        .unwrap_or("meets");
    let deciding = all
        .iter()
        .filter(|(_, v)| *v == worst)
        .map(|(n, _)| n.clone())
        .collect();
    (worst, deciding)
}

#[cfg(test)]
mod tests {
    use super::*;
    use invlight_scene::en12464::task;

    /// The summary's verdict is the worst: one failing area fails the whole, whatever
    /// the task area's own verdict, and it names the area.
    #[test]
    fn the_overall_verdict_is_the_worst_areas() {
        let area = |surface: &str, verdict: &str| AreaReport {
            area: "wall".into(),
            surface: surface.into(),
            size: [1.0, 1.0],
            cells: [1, 1],
            cell_size: [1.0, 1.0],
            required_em: 75.0,
            required_u0: 0.1,
            em: 80.0,
            em_bounds: [79.0, 81.0],
            u0: 0.5,
            u0_bounds: [Some(0.4), Some(0.6)],
            level: 0.95,
            verdict: verdict.into(),
        };
        let areas = [area("wall 1", "meets"), area("wall 2", "fails")];
        assert_eq!(
            overall(Verdict::Meets, &areas),
            ("fails", vec!["wall 2".to_string()])
        );
        let unsure = [area("wall 1", "cannot tell"), area("wall 2", "meets")];
        assert_eq!(overall(Verdict::Meets, &unsure).0, "cannot tell");
        assert_eq!(
            overall(Verdict::Fails, &unsure),
            ("fails", vec!["task area".to_string()])
        );
        assert_eq!(overall(Verdict::Meets, &areas[..1]).0, "meets");
    }

    #[test]
    fn an_office_asks_its_areas_what_the_standard_does() {
        let office = Requirement::of_task(task("office").unwrap(), 0.8);
        let ask = |k| {
            let r = area_requirement(k, &office).unwrap();
            (r.em.unwrap(), r.u0.unwrap(), r.maintenance_factor)
        };
        assert_eq!(ask(AreaKind::Surrounding), (300.0, 0.40, 0.8));
        assert_eq!(ask(AreaKind::Background), (100.0, 0.10, 0.8));
        assert_eq!(ask(AreaKind::Wall), (75.0, 0.10, 0.8));
        assert_eq!(ask(AreaKind::Ceiling), (50.0, 0.10, 0.8));
        let corridor = Requirement::of_task(task("corridor").unwrap(), 1.0);
        let r = area_requirement(AreaKind::Wall, &corridor).unwrap();
        assert_eq!(r.em, Some(50.0));
        // Only a uniformity asked: no Ēm for the bands to follow; walls still judged.
        let u0_only = Requirement {
            task: None,
            em: None,
            u0: Some(0.6),
            maintenance_factor: 1.0,
        };
        assert!(area_requirement(AreaKind::Surrounding, &u0_only).is_none());
        assert_eq!(
            area_requirement(AreaKind::Ceiling, &u0_only).unwrap().em,
            Some(30.0)
        );
    }
}
