//! EN 12464-1:2021's figures (CEN, "Light and lighting — Lighting of work places —
//! Part 1: Indoor work places"): a few tasks of its schedule of lighting requirements,
//! and what the areas around a task area ([`crate::AreaKind`]) must receive. They sit
//! with the scene, which builds those areas, so that both a problem's `<task>` and
//! `invlight map --task` read one table.
//!
//! - **Immediate surrounding** (2021 §5.3.2, table of the relationship of illuminances;
//!   2011 Table 1): Ēm 500 lx around a task of ≥ 750 lx, 300 around 500, 200 around 300,
//!   150 around 200, and the task's own Ēm at or below 150 lx; U0 ≥ 0.40. A task value
//!   between the table's steps takes the row of the step below it. (Fagerhult, "EN
//!   12464-1: requirements for illuminance and uniformity", fagerhult.com; Trilux's
//!   "Illuminance in the immediate surrounding area" reads the 200 lx row as the task's
//!   own, a disagreement kept here on the side of the 2011 table.)
//! - **Background** (2021 §5.3.3; 2011 §4.3.3): Ēm ≥ ⅓ of the immediate surrounding's
//!   required Ēm, U0 ≥ 0.10, in a band at least 3 m wide (Trilux, "Background
//!   lighting", trilux.com).
//! - **Walls** and **ceiling** (2021 §5.2.4; 2011 §4.3.1): the task's [`Task::walls_em`]
//!   and [`Task::ceiling_em`] (50 and 30 lx where no task is named), U0 ≥ 0.10.

use crate::AreaKind;

/// A task of EN 12464-1:2021's schedule of lighting requirements (its tables by
/// interior area and task), with the required maintained illuminance and uniformity,
/// and the row's other figures where a cited summary of the 2021 edition confirms
/// them ([`Task::source`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Task {
    /// The name `--task` and `<task name>` take.
    pub name: &'static str,
    /// The standard's area and task, in its words.
    pub description: &'static str,
    /// Required maintained average illuminance Ēm, lx.
    pub em: f64,
    /// The 2021 edition's modified Ēm, lx: what the row asks where the task is harder
    /// (small details, low contrast, long duration); `None` where no cited source gives
    /// it.
    pub em_modified: Option<f64>,
    /// Required uniformity U0 = Emin/Ē.
    pub u0: f64,
    /// The unified glare rating limit UGR_L; `None` where no cited source gives it.
    pub ugr_l: Option<f64>,
    /// The minimum colour rendering index Ra; `None` where no cited source gives it.
    pub ra: Option<u32>,
    /// Required maintained cylindrical illuminance Ēz, lx; `None` where no cited
    /// source gives it.
    pub ez: Option<f64>,
    /// Required maintained average illuminance on the walls, lx (U0 ≥ 0.10).
    pub walls_em: f64,
    /// Required maintained average illuminance on the ceiling, lx (U0 ≥ 0.10).
    pub ceiling_em: f64,
    /// Where the figures come from: the published summary of EN 12464-1:2021 that
    /// states them, and which of them it does not.
    pub source: &'static str,
}

/// Glamox's application guide quoting EN 12464-1:2021, conference and meeting rooms.
const GLAMOX_MEETING: &str = "Glamox, \"Lighting requirements in EN 12464-1:2021\", application guide, office: conference and meeting rooms (glamox.com/en-gb/pbs/application-guide/office/conference-and-meeting-rooms): every figure of the row";

/// The same guide, offices' corridors and common areas.
const GLAMOX_CORRIDOR: &str = "Glamox, \"Lighting requirements in EN 12464-1:2021\", application guide, office corridors and common areas (glamox.com/fi/pbs/ratkaisuopas/toimisto/toimistojen-kaytavat-ja-yhteisalueet): every figure of the row; Trilux, \"Corridors, entrance halls, cloakrooms\" (trilux.com, lighting practice) also gives 100 lx";

/// A few common tasks of EN 12464-1:2021 (CEN, "Light and lighting — Lighting of work
/// places — Part 1: Indoor work places", schedule of lighting requirements: offices,
/// traffic zones inside buildings, educational premises). Each row names its source;
/// figures no cited summary confirms are marked there, and UGR_L, Ra and Ez are left
/// out (`None`) where none gives them. Check them against your copy of the standard
/// before signing a compliance sheet, and give `--em`/`--u0` (`<task em u0>`) for any
/// other task. The 2021 edition lists the walls' and the ceiling's Ēm per row; where a
/// row's are not confirmed, the 2011 edition's general clause (§4.3.1: 50 lx on walls
/// and 30 lx on ceilings, 75 and 50 lx in offices, education and health care, each
/// with U0 ≥ 0.10; esse-ci.com, "Wall and ceiling illuminance") stands in.
pub const TASKS: &[Task] = &[
    Task {
        name: "office",
        description: "Offices: writing, typing, reading, data processing",
        em: 500.0,
        em_modified: None,
        u0: 0.60,
        ugr_l: None,
        ra: None,
        ez: Some(150.0),
        walls_em: 75.0,
        ceiling_em: 50.0,
        source: "Trilux, \"Lighting of offices and VDU workstations: illuminance\" (trilux.com, lighting practice): Ēm 500 lx; Fagerhult, \"EN 12464-1: requirements for illuminance\" (fagerhult.com, cylindrical illuminance): Ēz ≥ 150 lx in offices; U0 0.60 and the walls' and ceiling's 75/50 lx not confirmed for the 2021 row",
    },
    Task {
        name: "filing",
        description: "Offices: filing, copying",
        em: 300.0,
        em_modified: Some(500.0),
        u0: 0.40,
        ugr_l: None,
        ra: Some(80),
        ez: None,
        walls_em: 75.0,
        ceiling_em: 50.0,
        source: "performanceinlighting.com, \"EN 12464-1 – Lighting of indoor work places\": Ēm 300 (modified 500) lx, U0 0.40, Ra 80; walls and ceiling from the 2011 clause",
    },
    Task {
        name: "meeting",
        description: "Offices: conference and meeting rooms",
        em: 500.0,
        em_modified: Some(1000.0),
        u0: 0.60,
        ugr_l: Some(19.0),
        ra: Some(80),
        ez: Some(150.0),
        walls_em: 150.0,
        ceiling_em: 100.0,
        source: GLAMOX_MEETING,
    },
    Task {
        name: "drawing",
        description: "Offices: technical drawing",
        em: 750.0,
        em_modified: None,
        u0: 0.70,
        ugr_l: None,
        ra: None,
        ez: None,
        walls_em: 75.0,
        ceiling_em: 50.0,
        source: "Trilux, \"Lighting of design and CAD offices\" (trilux.com, lighting practice): 750 lx on drawing boards; U0 0.70 not confirmed; walls and ceiling from the 2011 clause",
    },
    Task {
        name: "corridor",
        description: "Traffic zones inside buildings: corridors and circulation areas",
        em: 100.0,
        em_modified: Some(150.0),
        u0: 0.40,
        ugr_l: Some(28.0),
        ra: Some(40),
        ez: Some(50.0),
        walls_em: 50.0,
        ceiling_em: 30.0,
        source: GLAMOX_CORRIDOR,
    },
    Task {
        name: "classroom",
        description: "Educational premises: classrooms, tutorial rooms",
        em: 500.0,
        em_modified: None,
        u0: 0.60,
        ugr_l: None,
        ra: None,
        ez: Some(150.0),
        walls_em: 75.0,
        ceiling_em: 50.0,
        source: "Trilux, \"Photometric requirements according to EN 12464-1\" (trilux.com, lighting of educational facilities): Ēz 150 lx (U0 ≥ 0.10, at 1.2 m seated), walls 75 lx and ceiling 50 lx; Ēm 500 lx and U0 0.60 not confirmed",
    },
    Task {
        name: "board",
        description: "Educational premises: black, green and white boards",
        em: 500.0,
        em_modified: None,
        u0: 0.70,
        ugr_l: None,
        ra: None,
        ez: None,
        walls_em: 75.0,
        ceiling_em: 50.0,
        source: "Trilux, \"Additional lighting\" (trilux.com, lighting of educational facilities): 500 lx and U0 0.70 on boards; walls and ceiling from the 2011 clause",
    },
];

/// EN 12464-1:2021's grid spacing (§5.4 / Annex A; EN 12464-1:2011 §4.4): p = 0.2 ·
/// 5^log10(d) m, d the longer side of the area, or the shorter when the longer is at
/// least twice it, and p at most 10 m. The grid then has ⌈d/p⌉ points along d, the other
/// side spaced alike. Tabulated: 1 m → 0.20 m, 5 m → 0.60 m, 10 m → 1 m, 100 m → 5 m.
pub fn en12464_spacing(longer: f64, shorter: f64) -> f64 {
    let (d, _) = en12464_side(longer, shorter);
    (0.2 * 5f64.powf(d.log10())).min(10.0)
}

/// The side d that [`en12464_spacing`] is reckoned from, and whether it is the
/// shorter side (the longer being at least twice it).
fn en12464_side(a: f64, b: f64) -> (f64, bool) {
    let (longer, shorter) = (a.max(b), a.min(b));
    // "2 or more", read with the rounding of coordinates in metres: a 1.6 m × 0.8 m
    // desk whose sides come out as 1.5999999 and 0.8000001 is 2:1.
    if longer >= 2.0 * shorter * (1.0 - 1e-6) {
        (shorter, true)
    } else {
        (longer, false)
    }
}

/// [`en12464_spacing`] of an `a` × `b` m area as a reader checks it: "EN 12464-1's grid
/// rule: p = 0.2 × 5^log10(d) = 0.79 m, d = 7.20 m (the longer side)".
pub fn en12464_rule(a: f64, b: f64) -> String {
    let (d, shorter) = en12464_side(a, b);
    let side = if shorter {
        "the shorter side, the longer being at least twice it"
    } else {
        "the longer side"
    };
    let p = en12464_spacing(a, b);
    let capped = if p < 0.2 * 5f64.powf(d.log10()) {
        ", at most 10 m"
    } else {
        ""
    };
    format!(
        "EN 12464-1's grid rule: p = 0.2 × 5^log10(d) = {p:.2} m{capped}, d = {d:.2} m ({side})"
    )
}

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
    /// figures, else the standard's general 50 and 30 lx). The cylindrical illuminance
    /// asks its Ēz alone ([`Task::ez`]), not an Ēm and a U0: `None`.
    pub fn required(self, task_em: Option<f64>, task: Option<&Task>) -> Option<(f64, f64)> {
        Some(match self {
            AreaKind::Surrounding => (surrounding_em(task_em?), SURROUNDING_U0),
            AreaKind::Background => (surrounding_em(task_em?) / 3.0, ROOM_U0),
            AreaKind::Wall => (task.map_or(50.0, |t| t.walls_em), ROOM_U0),
            AreaKind::Ceiling => (task.map_or(30.0, |t| t.ceiling_em), ROOM_U0),
            AreaKind::Cylindrical => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows as the cited summaries of EN 12464-1:2021 state them.
    #[test]
    fn rows_match_their_cited_sources() {
        let meeting = task("meeting").unwrap();
        assert_eq!(
            (
                meeting.em,
                meeting.em_modified,
                meeting.u0,
                meeting.ugr_l,
                meeting.ra,
                meeting.ez
            ),
            (500.0, Some(1000.0), 0.60, Some(19.0), Some(80), Some(150.0))
        );
        assert_eq!((meeting.walls_em, meeting.ceiling_em), (150.0, 100.0));
        let corridor = task("corridor").unwrap();
        assert_eq!(
            (
                corridor.em,
                corridor.em_modified,
                corridor.u0,
                corridor.ugr_l,
                corridor.ra
            ),
            (100.0, Some(150.0), 0.40, Some(28.0), Some(40))
        );
        assert_eq!(
            (corridor.ez, corridor.walls_em, corridor.ceiling_em),
            (Some(50.0), 50.0, 30.0)
        );
        let filing = task("filing").unwrap();
        assert_eq!(
            (filing.em, filing.em_modified, filing.u0, filing.ra),
            (300.0, Some(500.0), 0.40, Some(80))
        );
        assert_eq!(task("drawing").unwrap().em, 750.0);
        let board = task("board").unwrap();
        assert_eq!((board.em, board.u0), (500.0, 0.70));
        assert_eq!(task("classroom").unwrap().ez, Some(150.0));
        // Every row names where its figures come from.
        assert!(TASKS.iter().all(|t| t.source.contains('"')));
    }

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
