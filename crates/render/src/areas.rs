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

use crate::compliance::{Compliance, Requirement, Verdict, assess};
use crate::map::IlluminanceMap;
use invlight_scene::AreaKind;
use invlight_stats::{Confidence, Estimate};
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

/// The cylindrical illuminance's verdict in `invlight map --json` (`cylindrical`):
/// the mean Ez over the task area and its surrounding at a person's eye height
/// ([`invlight_scene::Scene::add_cylindrical_area`]), judged against the task's Ēz.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CylindricalReport {
    /// The calculation surface measured.
    pub surface: String,
    /// Required maintained Ēz, lx.
    pub required_ez: f64,
    /// Maintained Ēz (the maintenance factor × the computed mean), lx.
    pub ez: f64,
    /// Its one-sided lower and upper bounds, lx.
    pub ez_bounds: [f64; 2],
    /// The confidence every bound holds at, 1 − α/(2m) for m areas judged.
    pub level: f64,
    /// `meets`, `fails` or `cannot tell`.
    pub verdict: String,
}

impl CylindricalReport {
    /// The mean `ez` measured on `surface` judged against `required` maintained lx
    /// with the maintenance factor `mf`, at `share` (the areas' Bonferroni share of
    /// the run's confidence, [`AreaVerdict::judge`]).
    pub fn judge(
        surface: &str,
        ez: &Estimate,
        required: f64,
        mf: f64,
        share: Confidence,
    ) -> CylindricalReport {
        let asked = Requirement {
            task: None,
            em: Some(required),
            u0: None,
            maintenance_factor: mf,
        };
        let c = &assess(&[], ez, &asked, share).criteria[0];
        CylindricalReport {
            surface: surface.into(),
            required_ez: required,
            ez: c.value,
            ez_bounds: [c.bounds.0, c.bounds.1],
            level: c.level,
            verdict: c.verdict.word().into(),
        }
    }
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
    /// task area required to meet `task`, jointly at `confidence` with `others` more
    /// statements made beside them (the cylindrical illuminance's), each at the
    /// returned share of it ([`AreaVerdict::share`]); areas without a requirement (the
    /// bands when no Ēm is asked) are left out.
    pub fn judge(
        maps: Vec<(AreaKind, String, (f64, f64), IlluminanceMap)>,
        task: &Requirement,
        confidence: Confidence,
        others: usize,
    ) -> (Vec<AreaVerdict>, Confidence) {
        let judged: Vec<_> = maps
            .into_iter()
            .filter_map(|(kind, surface, size, map)| {
                area_requirement(kind, task).map(|r| (kind, surface, size, map, r))
            })
            .collect();
        let share = AreaVerdict::share(judged.len() + others, confidence);
        let verdicts = judged
            .into_iter()
            .map(|(kind, surface, size, map, r)| AreaVerdict {
                kind,
                surface,
                size,
                compliance: map.compliance(&r, share),
                map,
            })
            .collect();
        (verdicts, share)
    }

    /// The confidence each of `m` statements made together is made at so that all
    /// hold jointly at `confidence` (Bonferroni: 1 − α/m).
    pub fn share(m: usize, confidence: Confidence) -> Confidence {
        let m = m.max(1) as f64;
        Confidence::new(1.0 - (1.0 - confidence.level()) / m).unwrap_or(confidence)
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
            verdict: c.verdict.word().into(),
        }
    }
}

/// The verdict on a task area (`task`) and the areas around it together: the worst of
/// theirs — it fails if one fails, cannot be told if one cannot, and meets only when
/// every one meets — with the names of the areas that decide it (the task area's as
/// "task area"), so that a summary never says "meets" above an area that fails.
pub fn overall(
    task: Verdict,
    areas: &[AreaReport],
    cylindrical: Option<&CylindricalReport>,
) -> (&'static str, Vec<String>) {
    let verdicts = std::iter::once(("task area".to_string(), task.word()))
        .chain(
            areas
                .iter()
                .map(|a| (a.surface.clone(), a.verdict.as_str())),
        )
        .chain(cylindrical.map(|c| (c.surface.clone(), c.verdict.as_str())));
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
            overall(Verdict::Meets, &areas, None),
            ("fails", vec!["wall 2".to_string()])
        );
        let unsure = [area("wall 1", "cannot tell"), area("wall 2", "meets")];
        assert_eq!(overall(Verdict::Meets, &unsure, None).0, "cannot tell");
        assert_eq!(
            overall(Verdict::Fails, &unsure, None),
            ("fails", vec!["task area".to_string()])
        );
        assert_eq!(overall(Verdict::Meets, &areas[..1], None).0, "meets");
        // The cylindrical illuminance counts as an area does.
        let dark = Estimate {
            mean: 100.0,
            std_error: 1.0,
            samples: 100_000,
        };
        let share = Confidence::new(0.95).unwrap();
        let ez = CylindricalReport::judge("cylindrical illuminance", &dark, 150.0, 0.8, share);
        assert_eq!((ez.ez, ez.verdict.as_str()), (80.0, "fails"));
        assert_eq!(
            overall(Verdict::Meets, &areas[..1], Some(&ez)),
            ("fails", vec!["cylindrical illuminance".to_string()])
        );
        let lit = Estimate {
            mean: 250.0,
            ..dark
        };
        let ez = CylindricalReport::judge("cylindrical illuminance", &lit, 150.0, 0.8, share);
        assert_eq!(ez.verdict, "meets");
        assert!(ez.ez_bounds[0] < 200.0 && ez.ez_bounds[1] > 200.0);
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
