//! `<sunTime>`: the time of day as a variable (`<sunTime id date from to step>`) or the
//! mean over a schedule of instants (`<sunTime … objective="mean">`), and where the sun
//! of a `sunTime` variable stands at a time (NREL's SPA, docs/daylight.md): what
//! [`super::Problem::load_scene`] shows before a configuration sets the time, and what
//! the binding sets it to.

use super::variables::Conditions;
use super::{Node, Problem, Reader, VariableKind, VariableSpec};
use glam::{DVec3, Vec3};
use invlight_scene::daylight::{
    Compass, Date, Daylight, DaylightError, Site, Sky, SkyKind, SunOptions, SunPosition,
    SunSchedule, TimeOfDay,
};
use invlight_scene::{Diagnostic, LightId, LightKind, Scene};
use std::fmt;
use std::sync::Arc;

impl Reader<'_, '_> {
    /// `<sunTime id days|date from to [step] [dayStep] objective="mean">`: the instants
    /// of [`SunSchedule`], `days="2026-01-01..2026-12-31"` (or one `date`) every
    /// `dayStep` days (default 1), each at the times of [`Reader::sun_time`].
    pub(super) fn sun_schedule(&self, v: Node) -> Result<SunSchedule, Diagnostic> {
        const EXAMPLE: &str = "<sunTime id=\"Sun\" days=\"2026-01-01..2026-12-31\" dayStep=\"7\" from=\"08:00\" to=\"18:00\" step=\"60\" objective=\"mean\"/>";
        self.check_attributes(
            v,
            &[
                "id",
                "days",
                "date",
                "from",
                "to",
                "step",
                "dayStep",
                "objective",
            ],
        );
        let objective = self.required(v, "objective")?;
        if objective != "mean" {
            return Err(self
                .error(
                    v,
                    format!("'objective' of <sunTime> is '{objective}', expected mean"),
                )
                .with_hint(format!("for example {EXAMPLE}")));
        }
        let bad = |e| self.sun_time_error(v, e, EXAMPLE);
        let (first, last): (Date, Date) = match (v.attribute("days"), v.attribute("date")) {
            (Some(days), None) => {
                let (a, b) = days.split_once("..").ok_or_else(|| {
                    self.error(
                        v,
                        format!("'days' of <sunTime> is '{days}', expected FIRST..LAST"),
                    )
                    .with_hint(format!("for example {EXAMPLE}"))
                })?;
                (
                    a.trim().parse().map_err(bad)?,
                    b.trim().parse().map_err(bad)?,
                )
            }
            (None, Some(date)) => {
                let d: Date = date.parse().map_err(bad)?;
                (d, d)
            }
            _ => {
                return Err(self
                    .error(
                        v,
                        "<sunTime objective=\"mean\"> needs 'days' or 'date', not both",
                    )
                    .with_hint(format!("for example {EXAMPLE}")));
            }
        };
        if last < first {
            return Err(self.error(v, format!("'days' of <sunTime> runs from {first} back to {last}, expected the first day first")));
        }
        let day_step = match self.number(v, "dayStep", "a whole number of days")? {
            None => 1,
            Some(0) => {
                return Err(self.error(v, "'dayStep' of <sunTime> is 0, expected at least 1 day"));
            }
            Some(n) => n as u32,
        };
        let (from, to, step) = self.sun_times(v, EXAMPLE)?;
        let schedule = SunSchedule {
            first,
            last,
            day_step,
            from,
            to,
            step,
        };
        let n = schedule.instants().len();
        if n > 20_000 {
            return Err(self.error(v, format!("<sunTime> has {n} instants, expected at most 20 000 (one sun each): take a longer step or dayStep")));
        }
        Ok(schedule)
    }

    /// `<sunTime id date from to [step]>`: the time of day as a variable, on `date`.
    pub(super) fn sun_time(&self, v: Node) -> Result<VariableKind, Diagnostic> {
        const EXAMPLE: &str =
            "<sunTime id=\"Sun\" date=\"2026-12-21\" from=\"08:00\" to=\"18:00\" step=\"10\"/>";
        self.check_attributes(v, &["id", "date", "from", "to", "step"]);
        let date: Date = self
            .required(v, "date")?
            .parse()
            .map_err(|e| self.sun_time_error(v, e, EXAMPLE))?;
        let (from, to, step) = self.sun_times(v, EXAMPLE)?;
        Ok(VariableKind::SunTime {
            date,
            from,
            to,
            step,
        })
    }

    /// A daylight error of `<sunTime>` `v`, with what the element looks like.
    fn sun_time_error(&self, v: Node, e: DaylightError, example: &str) -> Diagnostic {
        self.error(v, format!("<sunTime>: {e}"))
            .with_hint(format!("for example {example}"))
    }

    /// A `<sunTime>`'s `from`, `to` (minutes after local midnight) and `step` (minutes,
    /// 10 by default): whole steps from `from` to `to` within one day.
    fn sun_times(&self, v: Node, example: &str) -> Result<(f64, f64, f64), Diagnostic> {
        let minutes = |attr: &str| -> Result<f64, Diagnostic> {
            let t: TimeOfDay = self
                .required(v, attr)?
                .parse()
                .map_err(|e| self.sun_time_error(v, e, example))?;
            Ok(t.seconds_of_day() / 60.0)
        };
        let (from, to) = (minutes("from")?, minutes("to")?);
        let step = match self.real(v, "step", "minutes")? {
            None => 10.0,
            Some(s) if s > 0.0 && s <= 1440.0 => s,
            Some(s) => {
                return Err(self.error(
                    v,
                    format!("'step' of <sunTime> is {s}, expected minutes in (0, 1440]"),
                ));
            }
        };
        let steps = (to - from) / step;
        if !(from < to && (steps - steps.round()).abs() < 1e-6) {
            return Err(self
                .error(
                    v,
                    format!("<sunTime> runs from {from} to {to} minutes after midnight in steps of {step}, expected from before to and a whole number of steps between them"),
                )
                .with_hint(format!("for example {example}")));
        }
        Ok((from, to, step))
    }

    /// Refuses a `<sunTime>` of `conditions` without a `<site>`, and a mean over a
    /// schedule of suns under a clear sky: a sun by the time of day needs the place it
    /// shines on; a clear sky is drawn about one sun (a `<sunTime>` variable redraws it
    /// about each of its suns, [`SunClock::draw_sky`]).
    pub(super) fn check_sun_times(
        &self,
        conditions: &Conditions,
        daylight: &Daylight,
    ) -> Result<(), Diagnostic> {
        let timed = conditions
            .variables
            .iter()
            .filter(|s| matches!(s.kind, VariableKind::SunTime { .. }))
            .map(|s| s.line);
        let schedule = conditions.sun_schedule.as_ref().map(|s| s.2);
        for line in timed.chain(schedule) {
            let at = |msg: &str| Diagnostic::at_line(self.path, line, msg);
            if daylight.site.is_none() {
                return Err(at("<sunTime> moves the sun over a day at a place, and the problem has no <site>")
                    .with_hint("add <site latitude=\"-34.9\" longitude=\"-56.2\" timezone=\"-3\"/> under <input>"));
            }
            if Some(line) == schedule && daylight.sky.is_some_and(|s| s.kind == SkyKind::CieClear) {
                return Err(at("<sunTime objective=\"mean\"> with a cie-clear <sky> is not supported: the mean over many suns would need a clear sky drawn about each")
                    .with_hint("use the cie-overcast sky, or no sky, or a <sunTime> variable (its clear sky follows its sun)"));
            }
        }
        Ok(())
    }
}

/// Why a `sunTime`'s sun cannot be placed.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum SunTimeError {
    /// The variable of this id is not a `sunTime`.
    NotSunTime(String),
    /// The problem has no `<site>` to put the sun over.
    NoSite,
    /// The light of this id is not a directional light.
    NotDirectional(String),
    /// No light has the id, and the scene's suns have other names.
    OtherSun {
        /// The `sunTime`'s id.
        id: String,
        /// The scene's directional lights.
        suns: Vec<String>,
    },
    /// The site's compass or the sun's position cannot be had.
    Daylight(DaylightError),
}

impl fmt::Display for SunTimeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SunTimeError::NotSunTime(id) => write!(f, "'{id}' is not a sunTime"),
            SunTimeError::NoSite => write!(f, "<sunTime> needs the problem's <site>"),
            SunTimeError::NotDirectional(id) => write!(
                f,
                "'{id}' is not a directional light, expected the sun a <sunTime> moves"
            ),
            SunTimeError::OtherSun { id, suns } => write!(
                f,
                "no directional light named '{id}', and the scene's sun is {}: give its name as the <sunTime>'s id",
                suns.join(", ")
            ),
            SunTimeError::Daylight(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SunTimeError {}

impl From<DaylightError> for SunTimeError {
    fn from(e: DaylightError) -> SunTimeError {
        SunTimeError::Daylight(e)
    }
}

/// The sun of a `sunTime` variable: the directional light it sets, standing where the
/// sun stands at a time of `date` at `site` (SPA), with `lux` or else the clear-sky
/// beam of IES RP-21 then.
#[derive(Debug, Clone)]
pub(crate) struct SunClock {
    /// The directional light.
    pub(crate) light: LightId,
    site: Site,
    date: Date,
    compass: Compass,
    lux: Option<f64>,
    /// The horizontal illuminance of the problem's CIE clear sky, lx, which is drawn
    /// again about each sun the clock sets (the sky's luminance follows the sun: CIE S
    /// 011 / ISO 15469's indicatrix and gradation are functions of the angle to it).
    clear_sky: Option<f64>,
}

impl SunClock {
    /// Puts the sun of `sunTime` `spec` where it stands at the middle of its range (the
    /// directional light `spec.id`, added to a scene without any): what the problem's
    /// scene shows before a configuration sets the time.
    pub(crate) fn place(
        problem: &Problem,
        spec: &VariableSpec,
        scene: &mut Scene,
    ) -> Result<SunClock, SunTimeError> {
        let VariableKind::SunTime { date, from, to, .. } = &spec.kind else {
            return Err(SunTimeError::NotSunTime(spec.id.clone()));
        };
        let site = problem.daylight.site.ok_or(SunTimeError::NoSite)?;
        let compass = site.compass(scene.up)?;
        let light = sun_time_light(scene, &spec.id)?;
        let clock = SunClock {
            light,
            site,
            date: *date,
            compass,
            lux: problem.daylight.sun.and_then(|s| s.illuminance),
            clear_sky: problem
                .daylight
                .sky
                .filter(|s| s.kind == SkyKind::CieClear)
                .map(|s| s.horizontal_lux),
        };
        let (d, lux) = clock.at((from + to) / 2.0)?;
        scene.lights[light].kind = LightKind::Directional {
            direction: d.as_vec3(),
            illuminance: Vec3::splat(lux as f32),
        };
        clock.draw_sky(scene, d);
        Ok(clock)
    }

    /// Whether the clock draws the scene's sky (a CIE clear sky about its sun).
    pub(crate) fn draws_sky(&self) -> bool {
        self.clear_sky.is_some()
    }

    /// Draws the problem's clear sky about the sun whose light travels along `travel`,
    /// when the problem has one: with the sun below the horizon the CIE clear sky is not
    /// defined and, as the sun's beam is then 0, the scene has no sky.
    pub(crate) fn draw_sky(&self, scene: &mut Scene, travel: DVec3) {
        if let Some(lux) = self.clear_sky {
            scene.sky = Sky::cie_clear(scene.up, -travel.as_vec3(), lux)
                .ok()
                .map(Arc::new);
        }
    }

    /// Where the sun stands `minutes` after local midnight (to the second, held within
    /// the day): the direction its light travels and its direct normal illuminance, lx
    /// (the problem's `<sun illuminance>`, else IES RP-21's clear-sky beam; 0 below the
    /// horizon).
    pub(crate) fn at(&self, minutes: f64) -> Result<(DVec3, f64), DaylightError> {
        let time = TimeOfDay::from_minutes(minutes);
        let sun = SunPosition::new(&self.site, &self.date, &time, &SunOptions::default())?;
        let beam = match (sun.is_up(), self.lux) {
            (false, _) => 0.0,
            (true, Some(l)) => l,
            (true, None) => sun.clear_sky_direct_normal(),
        };
        Ok((sun.travel(&self.compass).as_dvec3(), beam))
    }
}

/// The directional light a `sunTime` of id `id` sets: the one of that name, else one of
/// that name added to a scene without any.
fn sun_time_light(scene: &mut Scene, id: &str) -> Result<LightId, SunTimeError> {
    let directional = |k: &LightKind| matches!(k, LightKind::Directional { .. });
    if let Some(l) = scene.light(id) {
        return match directional(&scene.lights[l].kind) {
            true => Ok(l),
            false => Err(SunTimeError::NotDirectional(id.into())),
        };
    }
    let suns: Vec<String> = scene
        .lights
        .iter()
        .filter(|l| directional(&l.kind))
        .map(|l| l.name.clone())
        .collect();
    if !suns.is_empty() {
        return Err(SunTimeError::OtherSun {
            id: id.into(),
            suns,
        });
    }
    scene.lights.push(invlight_scene::Light {
        c0: invlight_scene::Vec3::X,
        name: id.into(),
        kind: LightKind::Directional {
            direction: -scene.up,
            illuminance: Vec3::ZERO,
        },
    });
    Ok(LightId::from_index(scene.lights.len() - 1))
}
