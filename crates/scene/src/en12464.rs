//! EN 12464-1:2021's figures (CEN, "Light and lighting — Lighting of work places —
//! Part 1: Indoor work places"): a few tasks of its schedule of lighting requirements,
//! and what the areas around a task area ([`crate::AreaKind`]) must receive. They sit
//! with the scene, which builds those areas, so that both a problem's `<task>` and
//! `invlight map --task` read one table.
//!
//! - **Immediate surrounding** (2021 §5.3.2, table of the relationship of illuminances;
//!   2011 Table 1): Ēm 500 lx around a task of ≥ 750 lx, 300 around 500, 200 around 300,
//!   150 around 200, and the task's own Ēm at or below 150 lx; U0 ≥ 0.40. A task value
//!   between the table's steps takes the row of the step below it.
//! - **Background** (2021 §5.3.3; 2011 §4.3.3): Ēm ≥ ⅓ of the immediate surrounding's
//!   required Ēm, U0 ≥ 0.10.
//! - **Walls** and **ceiling** (2021 §5.2.4; 2011 §4.3.1): the task's [`Task::walls_em`]
//!   and [`Task::ceiling_em`] (50 and 30 lx where no task is named), U0 ≥ 0.10.

use crate::AreaKind;

/// A task of EN 12464-1:2021's schedule of lighting requirements (its clause 5 tables,
/// by interior area and task), with the required maintained illuminance and uniformity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Task {
    /// The name `--task` takes.
    pub name: &'static str,
    /// The standard's area and task, in its words.
    pub description: &'static str,
    /// Required maintained average illuminance Ēm, lx.
    pub em: f64,
    /// Required uniformity U0 = Emin/Ē.
    pub u0: f64,
    /// Required maintained average illuminance on the walls, lx (U0 ≥ 0.10): 75 lx
    /// where the standard asks for bright rooms (offices, education), else 50 lx.
    pub walls_em: f64,
    /// Required maintained average illuminance on the ceiling, lx (U0 ≥ 0.10): 50 lx
    /// in those rooms, else 30 lx.
    pub ceiling_em: f64,
}

/// A few common tasks of EN 12464-1:2021 (CEN, "Light and lighting — Lighting of work
/// places — Part 1: Indoor work places", schedule of lighting requirements: offices,
/// traffic zones inside buildings, educational premises). The values are the required
/// Ēm and U0 as the standard tabulates them; check them against your copy before
/// relying on them, and give `--em`/`--u0` for any other task. The walls' and the
/// ceiling's values are those of its clause on the illuminance of walls and ceilings
/// (2021 §5.2.4; 2011 §4.3.1): Ēm ≥ 50 lx on walls and 30 lx on ceilings, 75 lx and
/// 50 lx in offices, education and health care, each with U0 ≥ 0.10.
pub const TASKS: &[Task] = &[
    Task {
        name: "office",
        description: "Offices: writing, typing, reading, data processing",
        em: 500.0,
        u0: 0.60,
        walls_em: 75.0,
        ceiling_em: 50.0,
    },
    Task {
        name: "filing",
        description: "Offices: filing, copying",
        em: 300.0,
        u0: 0.40,
        walls_em: 75.0,
        ceiling_em: 50.0,
    },
    Task {
        name: "meeting",
        description: "Offices: conference and meeting rooms",
        em: 500.0,
        u0: 0.60,
        walls_em: 75.0,
        ceiling_em: 50.0,
    },
    Task {
        name: "drawing",
        description: "Offices: technical drawing",
        em: 750.0,
        u0: 0.70,
        walls_em: 75.0,
        ceiling_em: 50.0,
    },
    Task {
        name: "corridor",
        description: "Traffic zones inside buildings: corridors and circulation areas",
        em: 100.0,
        u0: 0.40,
        walls_em: 50.0,
        ceiling_em: 30.0,
    },
    Task {
        name: "classroom",
        description: "Educational premises: classrooms, tutorial rooms",
        em: 500.0,
        u0: 0.60,
        walls_em: 75.0,
        ceiling_em: 50.0,
    },
    Task {
        name: "board",
        description: "Educational premises: black, green and white boards",
        em: 500.0,
        u0: 0.70,
        walls_em: 75.0,
        ceiling_em: 50.0,
    },
];

/// The task called `name`.
pub fn task(name: &str) -> Option<&'static Task> {
    TASKS.iter().find(|t| t.name == name)
}

/// U0 required on the immediate surrounding.
pub const SURROUNDING_U0: f64 = 0.40;

/// U0 required on the background, the walls and the ceiling.
pub const ROOM_U0: f64 = 0.10;

/// Required Ēm on the immediate surrounding of a task area lit to `task_em`, lx.
pub fn surrounding_em(task_em: f64) -> f64 {
    const TABLE: [(f64, f64); 4] = [
        (750.0, 500.0),
        (500.0, 300.0),
        (300.0, 200.0),
        (200.0, 150.0),
    ];
    TABLE
        .iter()
        .find(|&&(task, _)| task_em >= task)
        .map_or(task_em, |&(_, around)| around.min(task_em))
}

impl AreaKind {
    /// What this area must receive, as (maintained Ēm in lx, U0), around a task area
    /// required to receive `task_em` (the bands are derived from it, so without one they
    /// ask nothing) of the named `task`, if any (the walls and the ceiling read its
    /// figures, else the standard's general 50 and 30 lx).
    pub fn required(self, task_em: Option<f64>, task: Option<&Task>) -> Option<(f64, f64)> {
        Some(match self {
            AreaKind::Surrounding => (surrounding_em(task_em?), SURROUNDING_U0),
            AreaKind::Background => (surrounding_em(task_em?) / 3.0, ROOM_U0),
            AreaKind::Wall => (task.map_or(50.0, |t| t.walls_em), ROOM_U0),
            AreaKind::Ceiling => (task.map_or(30.0, |t| t.ceiling_em), ROOM_U0),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_surrounding_takes_the_row_of_the_step_at_or_below_the_task() {
        for (task, around) in [
            (1000.0, 500.0),
            (750.0, 500.0),
            (600.0, 300.0),
            (400.0, 200.0),
            (500.0, 300.0),
            (300.0, 200.0),
            (200.0, 150.0),
            (150.0, 150.0),
            (100.0, 100.0),
        ] {
            assert_eq!(surrounding_em(task), around, "{task} lx");
        }
    }
}
