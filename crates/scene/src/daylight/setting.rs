//! Daylight put on a scene as a designer states it: a site, the sun at a date and time,
//! a CIE sky by its horizontal illuminance. A problem file's `<site>`, `<sun>` and
//! `<sky>` and the command line's `--site`, `--north`, `--sun` and `--sky` both become a
//! [`Daylight`], which [`Daylight::apply`] turns into the scene's directional light and
//! [`Scene::sky`](crate::Scene::sky).

use super::{Date, DaylightError, Site, Sky, SkyKind, SunOptions, SunPosition, TimeOfDay};
use crate::light::{Light, LightKind};
use crate::model::Scene;
use glam::Vec3;
use std::str::FromStr;
use std::sync::Arc;

/// The name of the directional light [`Daylight::apply`] adds to a scene that has none.
pub const SUN_NAME: &str = "Sun";

/// The horizontal illuminance of the overcast sky a daylight factor is measured under
/// when the scene has none, lx: a typical overcast day (the factor does not depend on
/// it).
pub const DAYLIGHT_FACTOR_LUX: f64 = 10_000.0;

/// The sun at a local date and time, with its illuminance when the user gives one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunAt {
    /// The local date.
    pub date: Date,
    /// The local clock time.
    pub time: TimeOfDay,
    /// Direct normal illuminance, lx; `None` for the clear-sky beam of IES RP-21
    /// ([`SunPosition::clear_sky_direct_normal`]).
    pub illuminance: Option<f64>,
}

impl FromStr for SunAt {
    type Err = DaylightError;

    /// Reads `DATE,TIME` or `DATE,TIME,LUX` (`2025-12-21,10:00`, `2025-12-21,10:00,80000`).
    fn from_str(text: &str) -> Result<SunAt, DaylightError> {
        let parts: Vec<&str> = text.split(',').map(str::trim).collect();
        let (date, time, lux) = match parts[..] {
            [d, t] => (d, t, None),
            [d, t, l] => (d, t, Some(l)),
            _ => {
                return Err(DaylightError::Format {
                    text: text.into(),
                    expected: "DATE,TIME or DATE,TIME,LUX, like 2025-12-21,10:00",
                });
            }
        };
        let illuminance = lux
            .map(|l| match l.parse::<f64>() {
                Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
                _ => Err(DaylightError::OutOfRange {
                    what: "sun illuminance",
                    value: l.parse().unwrap_or(f64::NAN),
                    range: "a finite illuminance ≥ 0 lx (about 100 000 lx for a high clear sun)",
                }),
            })
            .transpose()?;
        Ok(SunAt {
            date: date.parse()?,
            time: time.parse()?,
            illuminance,
        })
    }
}

/// A CIE sky by its model and the illuminance it gives an unobstructed horizontal plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkySpec {
    /// The model.
    pub kind: SkyKind,
    /// `horizontalLux`, lx.
    pub horizontal_lux: f64,
}

impl FromStr for SkySpec {
    type Err = DaylightError;

    /// Reads `KIND:LUX` (`cie-overcast:10000`).
    fn from_str(text: &str) -> Result<SkySpec, DaylightError> {
        let Some((kind, lux)) = text.split_once(':') else {
            return Err(DaylightError::Format {
                text: text.into(),
                expected: "KIND:LUX, like cie-overcast:10000 or cie-clear:15000",
            });
        };
        let horizontal_lux = match lux.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && x > 0.0 => x,
            _ => {
                return Err(DaylightError::Format {
                    text: text.into(),
                    expected: "a positive horizontal illuminance in lx after the colon, like cie-overcast:10000",
                });
            }
        };
        Ok(SkySpec {
            kind: kind.trim().parse()?,
            horizontal_lux,
        })
    }
}

/// The command line's daylight ([`Daylight::flags`]): a [`Daylight`] and the `--north`
/// that turns its site, or the problem's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DaylightFlags {
    /// `--site`, `--sun` and `--sky`.
    pub daylight: Daylight,
    /// `--north`: degrees clockwise seen from above from the scene's default north to
    /// true north ([`Site::with_north`]).
    pub north: Option<f64>,
}

impl DaylightFlags {
    /// These flags over `base` (a problem file's daylight, or none for a scene file):
    /// each part given replaces `base`'s and the parts not given are `base`'s, so that
    /// `--sun` alone moves a problem's sun at its own `<site>`, and `--north` turns
    /// whichever site there is; with no flag, `base` itself. The result is what a
    /// problem's scene is lit by and its search reads, put on the scene once.
    pub fn over(&self, base: &Daylight) -> Result<Daylight, DaylightError> {
        if self.daylight.is_empty() && self.north.is_none() {
            return Ok(*base);
        }
        let mut daylight = self.daylight.or(base);
        if let Some(north) = self.north {
            let site = daylight.site.ok_or(DaylightError::NorthNeedsSite)?;
            daylight.site = Some(site.with_north(north)?);
        }
        Ok(daylight)
    }

    /// Puts these flags' daylight on a scene file's scene (one without a daylight of its
    /// own); returns its warnings.
    pub fn light(&self, scene: &mut Scene) -> Result<Vec<String>, DaylightError> {
        self.over(&Daylight::default())?.apply(scene)
    }
}

/// Daylight to put on a scene; each part is optional.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Daylight {
    /// Where the scene stands, with its north.
    pub site: Option<Site>,
    /// The sun, which needs the site.
    pub sun: Option<SunAt>,
    /// The sky.
    pub sky: Option<SkySpec>,
}

impl FromStr for Site {
    type Err = DaylightError;

    /// Reads `LAT,LON,TZ` (`-34.9,-56.2,-3`), as the command line's `--site` gives them
    /// and [`Site::new`] takes them.
    fn from_str(text: &str) -> Result<Site, DaylightError> {
        let numbers: Option<Vec<f64>> = text.split(',').map(|x| x.trim().parse().ok()).collect();
        match numbers.as_deref() {
            Some(&[lat, lon, tz]) => Site::new(lat, lon, tz),
            _ => Err(DaylightError::Format {
                text: text.into(),
                expected: "LAT,LON,TZ in degrees and hours, like -34.9,-56.2,-3",
            }),
        }
    }
}

impl Daylight {
    /// The command line's daylight: `--site`, `--north`, `--sun` and `--sky`.
    pub fn flags(
        site: Option<Site>,
        north: Option<f64>,
        sun: Option<SunAt>,
        sky: Option<SkySpec>,
    ) -> DaylightFlags {
        DaylightFlags {
            daylight: Daylight { site, sun, sky },
            north,
        }
    }

    /// Whether it says nothing.
    pub fn is_empty(&self) -> bool {
        self.site.is_none() && self.sun.is_none() && self.sky.is_none()
    }

    /// This daylight with every part it lacks taken from `base` (the command line over
    /// a problem file).
    pub fn or(&self, base: &Daylight) -> Daylight {
        Daylight {
            site: self.site.or(base.site),
            sun: self.sun.or(base.sun),
            sky: self.sky.or(base.sky),
        }
    }

    /// Puts the sun, then the sky, on `scene` ([`Daylight::apply_sun`],
    /// [`Daylight::apply_sky`]); returns what is worth a warning ([`Daylight::warnings`]).
    pub fn apply(&self, scene: &mut Scene) -> Result<Vec<String>, DaylightError> {
        self.apply_sun(scene)?;
        self.apply_sky(scene)?;
        Ok(self.warnings())
    }

    /// What this daylight is worth a warning for: a sun below the horizon, which gives
    /// no light, and a site whose clock is far from its meridian (a sign mistaken).
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        if let (Some(sun), Some(site)) = (self.sun, self.site)
            && let Ok(position) =
                SunPosition::new(&site, &sun.date, &sun.time, &SunOptions::default())
            && !position.is_up()
        {
            warnings.push(format!(
                "the sun is {:.1}° below the horizon on {} at {}: it gives no light",
                -position.altitude(),
                sun.date,
                sun.time
            ));
        }
        if let Some(site) = self.site
            && site.meridian_offset_hours().abs() > 3.0
        {
            warnings.push(format!(
                "the site's clock is {:.1} h from its meridian (longitude {} / 15 − zone {}): check the signs (longitude is positive east, the zone positive east of UTC)",
                site.meridian_offset_hours(),
                site.longitude(),
                site.timezone()
            ));
        }
        warnings
    }

    /// Points the scene's sun where it stands at `sun`'s date and time at the site, with
    /// the illuminance given or else IES RP-21's clear-sky beam (0 when the sun is
    /// down). The sun is the scene's only directional light, or the one named
    /// [`SUN_NAME`] among several; a scene with none gets one of that name.
    pub fn apply_sun(&self, scene: &mut Scene) -> Result<(), DaylightError> {
        let Some(sun) = self.sun else {
            return Ok(());
        };
        let site = self.site.ok_or(DaylightError::NeedsSite)?;
        let position = SunPosition::new(&site, &sun.date, &sun.time, &SunOptions::default())?;
        let lux = if position.is_up() {
            sun.illuminance
                .unwrap_or_else(|| position.clear_sky_direct_normal())
        } else {
            0.0
        };
        let direction = position.travel(&site.compass(scene.up)?);
        set_sun(scene, direction, lux)?;
        Ok(())
    }

    /// Puts the sky on the scene, replacing any it has. The clear sky needs the sun's
    /// place: this daylight's sun, else the scene's own directional light.
    pub fn apply_sky(&self, scene: &mut Scene) -> Result<(), DaylightError> {
        let Some(spec) = self.sky else {
            return Ok(());
        };
        let sky = match spec.kind {
            SkyKind::CieOvercast => Sky::cie_overcast(scene.up, spec.horizontal_lux)?,
            SkyKind::CieClear => {
                let to_sun = match sun_light(scene)? {
                    Some(l) => -scene.lights[l].kind.direction().unwrap_or(-scene.up),
                    None => return Err(DaylightError::NeedsSun),
                };
                Sky::cie_clear(scene.up, to_sun, spec.horizontal_lux)?
            }
        };
        scene.sky = Some(Arc::new(sky));
        Ok(())
    }
}

/// The index of the scene's sun: its only directional light, or the one named
/// [`SUN_NAME`] among several.
fn sun_light(scene: &Scene) -> Result<Option<usize>, DaylightError> {
    let suns: Vec<usize> = (0..scene.lights.len())
        .filter(|&l| matches!(scene.lights[l].kind, LightKind::Directional { .. }))
        .collect();
    match suns[..] {
        [] => Ok(None),
        [one] => Ok(Some(one)),
        _ => suns
            .iter()
            .copied()
            .find(|&l| scene.lights[l].name == SUN_NAME)
            .map(Some)
            .ok_or_else(|| {
                DaylightError::SeveralSuns(
                    suns.iter().map(|&l| scene.lights[l].name.clone()).collect(),
                )
            }),
    }
}

/// The sun at every step of a set of days and hours, for the mean of their light: a
/// problem's `<sunTime days objective="mean">`. Illuminance is linear in the light, so
/// the mean over K instants is what K suns give together, each with 1/K of its beam
/// then; one trace measures it, with its interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunSchedule {
    /// The first day.
    pub first: Date,
    /// The last day (included when a whole number of `day_step`s after `first`).
    pub last: Date,
    /// Days from one day to the next (1: every day; 7: one day a week).
    pub day_step: u32,
    /// The first time of each day, minutes after local midnight.
    pub from: f64,
    /// The last time, minutes after local midnight.
    pub to: f64,
    /// Minutes from one time to the next.
    pub step: f64,
}

impl SunSchedule {
    /// Every instant: each day from `first` to `last` by `day_step`, each time from
    /// `from` to `to` by `step`.
    pub fn instants(&self) -> Vec<(Date, TimeOfDay)> {
        let times = ((self.to - self.from) / self.step).round() as usize + 1;
        let (a, b) = (self.first.days_since_1970(), self.last.days_since_1970());
        (a..=b)
            .step_by(self.day_step.max(1) as usize)
            .flat_map(|d| {
                (0..times).map(move |k| {
                    let minutes = self.from + k as f64 * self.step;
                    (
                        Date::from_days_since_1970(d),
                        TimeOfDay::from_minutes(minutes),
                    )
                })
            })
            .collect()
    }

    /// Replaces the scene's sun (the directional light `id`, else its only one or the
    /// one named [`SUN_NAME`]) by one directional light per instant the sun is up at
    /// `site`, each with 1/K of its beam (`lux`, or IES RP-21's
    /// clear-sky beam then), K every instant, night ones included: the scene's light is
    /// then the mean over the instants. Returns K and how many had the sun up.
    pub fn apply(
        &self,
        id: &str,
        site: &Site,
        lux: Option<f64>,
        scene: &mut Scene,
    ) -> Result<(usize, usize), DaylightError> {
        let named = (0..scene.lights.len()).find(|&l| {
            scene.lights[l].name == id
                && matches!(scene.lights[l].kind, LightKind::Directional { .. })
        });
        let sun = match named {
            Some(l) => Some(l),
            None => sun_light(scene)?,
        };
        if let Some(l) = sun {
            scene.lights.remove(l);
        }
        let compass = site.compass(scene.up)?;
        let instants = self.instants();
        let k = instants.len();
        let mut up = 0;
        for (date, time) in &instants {
            let sun = SunPosition::new(site, date, time, &SunOptions::default())?;
            if !sun.is_up() {
                continue;
            }
            up += 1;
            let beam = lux.unwrap_or_else(|| sun.clear_sky_direct_normal());
            scene.lights.push(Light {
                c0: glam::Vec3::X,
                name: format!("{SUN_NAME} {date} {time}"),
                kind: LightKind::Directional {
                    direction: sun.travel(&compass),
                    illuminance: Vec3::splat((beam / k as f64) as f32),
                },
            });
        }
        Ok((k, up))
    }
}

/// Sets the scene's sun (its only directional light, or the one named [`SUN_NAME`]
/// among several; added when there is none) to travel along the unit `direction` with
/// `lux` of white light.
pub fn set_sun(scene: &mut Scene, direction: Vec3, lux: f64) -> Result<(), DaylightError> {
    let kind = LightKind::Directional {
        direction,
        illuminance: Vec3::splat(lux as f32),
    };
    match sun_light(scene)? {
        Some(l) => scene.lights[l].kind = kind,
        None => scene.lights.push(Light {
            c0: glam::Vec3::X,
            name: SUN_NAME.into(),
            kind,
        }),
    }
    Ok(())
}

/// Makes `scene` what a daylight factor is measured in (CIE S 011's overcast sky, no
/// other light): its own overcast sky, or one of [`DAYLIGHT_FACTOR_LUX`] when it has
/// none; every light and emission off. Returns the sky's horizontal illuminance, the
/// factor's E_unobstructed.
pub fn daylight_factor_scene(scene: &mut Scene) -> Result<f64, DaylightError> {
    let sky = match scene.sky.take() {
        Some(sky) if sky.kind() == SkyKind::CieOvercast => sky,
        Some(sky) => return Err(DaylightError::NotOvercast(sky.kind())),
        None => Arc::new(Sky::cie_overcast(scene.up, DAYLIGHT_FACTOR_LUX)?),
    };
    let lux = sky.horizontal_illuminance();
    scene.sky = Some(sky);
    scene.lights.clear();
    for m in &mut scene.materials {
        m.emission = Vec3::ZERO;
    }
    Ok(lux)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_parse_and_mistakes_say_what_was_expected() {
        let sun: SunAt = "2025-12-21,10:00".parse().unwrap();
        assert_eq!(
            (sun.date.day(), sun.time.hour(), sun.illuminance),
            (21, 10, None)
        );
        let sun: SunAt = "2025-12-21, 10:00, 80000".parse().unwrap();
        assert_eq!(sun.illuminance, Some(80_000.0));
        let e = "2025-12-21".parse::<SunAt>().unwrap_err().to_string();
        assert!(e.contains("DATE,TIME"), "{e}");
        let e = "2025-12-21,10:00,-5"
            .parse::<SunAt>()
            .unwrap_err()
            .to_string();
        assert!(e.contains("sun illuminance"), "{e}");
        let sky: SkySpec = "cie-clear:15000".parse().unwrap();
        assert_eq!(
            (sky.kind, sky.horizontal_lux),
            (SkyKind::CieClear, 15_000.0)
        );
        for (text, what) in [
            ("cie-overcast", "KIND:LUX"),
            ("cie-overcast:0", "positive"),
            ("cie-sunny:5", "cie-overcast or cie-clear"),
        ] {
            let e = text.parse::<SkySpec>().unwrap_err().to_string();
            assert!(e.contains(what), "{text}: {e}");
        }
        let site: Site = "-34.9, -56.2, -3".parse().unwrap();
        assert_eq!(site, Site::new(-34.9, -56.2, -3.0).unwrap());
        assert!("-34.9,-56.2".parse::<Site>().is_err());
        assert!("-94,0,0".parse::<Site>().is_err());
    }

    /// The command line's parts replace a problem's and take the rest from it: `--sun`
    /// alone shines at the problem's site; no flag leaves the problem's daylight as it is.
    #[test]
    fn flags_go_over_a_problems_daylight() {
        let base = Daylight {
            site: Some(Site::new(-34.9, -56.2, -3.0).unwrap()),
            sun: Some("2025-12-21,10:00".parse().unwrap()),
            sky: None,
        };
        let none = Daylight::flags(None, None, None, None);
        assert_eq!(none.over(&base), Ok(base));
        let travel = |daylight: Daylight| {
            let mut scene = Scene::default();
            daylight.apply(&mut scene).unwrap();
            match scene.lights[..] {
                [
                    Light {
                        kind: LightKind::Directional { direction, .. },
                        ..
                    },
                ] => direction,
                _ => panic!("{:?}", scene.lights),
            }
        };
        let afternoon =
            Daylight::flags(None, None, Some("2025-12-21,16:00".parse().unwrap()), None);
        assert_eq!(afternoon.over(&base).unwrap().site, base.site);
        // The afternoon sun stands in the west (−X of a Y-up scene): its light travels east.
        let east = travel(afternoon.over(&base).unwrap());
        assert!(east.x > 0.5, "{east}");
        // North turned 90° clockwise onto +X puts east on +Z and west on −Z: the light
        // travels +Z, each vector turned with the compass.
        let turned = DaylightFlags {
            north: Some(90.0),
            ..afternoon
        };
        let d = travel(turned.over(&base).unwrap());
        assert!(
            (d - Vec3::new(-east.z, east.y, east.x)).length() < 1e-5,
            "{d} {east}"
        );
        let e = afternoon
            .over(&Daylight::default())
            .unwrap()
            .apply(&mut Scene::default());
        assert_eq!(e, Err(DaylightError::NeedsSite));
        let north_alone = Daylight::flags(None, Some(10.0), None, None);
        let e = north_alone.over(&Daylight::default()).unwrap_err();
        assert!(e.to_string().contains("--site"), "{e}");
        let bad = Daylight::flags(base.site, Some(f64::NAN), None, None);
        assert!(bad.over(&Daylight::default()).is_err());
    }

    /// A sun is added to a scene without one, set on its only directional light, and
    /// needs a site; the clear sky takes the sun's place.
    #[test]
    fn apply_sets_the_sun_and_the_sky() {
        let mut scene = Scene::default();
        let site = Site::new(-34.9, -56.2, -3.0).unwrap();
        let sun: SunAt = "2025-12-21,10:00".parse().unwrap();
        let daylight = Daylight {
            site: None,
            sun: Some(sun),
            sky: None,
        };
        assert_eq!(daylight.apply(&mut scene), Err(DaylightError::NeedsSite));
        let clear = Some("cie-clear:15000".parse().unwrap());
        let e = Daylight {
            sky: clear,
            ..Daylight::default()
        }
        .apply(&mut scene);
        assert_eq!(e, Err(DaylightError::NeedsSun));
        let daylight = Daylight {
            site: Some(site),
            sun: Some(sun),
            sky: clear,
        };
        assert!(daylight.apply(&mut scene).unwrap().is_empty());
        assert_eq!(scene.lights.len(), 1);
        assert_eq!(scene.lights[0].name, SUN_NAME);
        let LightKind::Directional {
            direction,
            illuminance,
        } = scene.lights[0].kind
        else {
            panic!("{:?}", scene.lights[0]);
        };
        // The morning sun stands in the east (+X of a Y-up scene): its light travels west.
        assert!(direction.x < -0.5 && direction.y < 0.0, "{direction}");
        assert!(illuminance.x > 90_000.0, "{illuminance}");
        let sky = scene.sky.as_ref().unwrap();
        assert!((sky.sun().unwrap() + direction).length() < 1e-5);
        // Again: the same light is set, no second one is added.
        daylight.apply(&mut scene).unwrap();
        assert_eq!(scene.lights.len(), 1);
        // At night the sun gives nothing, with a warning.
        let night = Daylight {
            sun: Some("2025-12-21,23:00".parse().unwrap()),
            sky: None,
            ..daylight
        };
        let warnings = night.apply(&mut scene).unwrap();
        assert!(warnings[0].contains("below the horizon"), "{warnings:?}");
        assert_eq!(scene.lights[0].kind.flux(), Vec3::ZERO);
    }

    /// One day a week over four weeks, three hours a day; the suns carry 1/K of the beam
    /// and the night's instants none.
    #[test]
    fn a_schedule_is_the_mean_of_its_suns() {
        let s = SunSchedule {
            first: "2026-03-02".parse().unwrap(),
            last: "2026-03-23".parse().unwrap(),
            day_step: 7,
            from: 5.0 * 60.0,
            to: 7.0 * 60.0,
            step: 60.0,
        };
        let instants = s.instants();
        assert_eq!(instants.len(), 12);
        assert_eq!(instants[3].0.to_string(), "2026-03-09");
        assert_eq!(instants[3].1.to_string(), "05:00:00");
        assert_eq!(instants[11].1.to_string(), "07:00:00");
        let mut scene = Scene::default();
        set_sun(&mut scene, -Vec3::Y, 1.0).unwrap();
        // On the equator at 05:00 the sun is down, at 06:00 (about) rising, at 07:00 up.
        let site = Site::new(0.0, 0.0, 0.0).unwrap();
        let (k, up) = s.apply(SUN_NAME, &site, Some(1200.0), &mut scene).unwrap();
        assert_eq!(k, 12);
        assert_eq!(scene.lights.len(), up);
        assert!((4..=8).contains(&up), "{up}");
        for l in &scene.lights {
            let LightKind::Directional { illuminance, .. } = l.kind else {
                panic!("{l:?}");
            };
            assert_eq!(illuminance, Vec3::splat(100.0), "{l:?}");
        }
    }

    #[test]
    fn daylight_factor_scene_keeps_the_overcast_sky_alone() {
        let mut scene = Scene::default();
        set_sun(&mut scene, -Vec3::Y, 1000.0).unwrap();
        assert_eq!(daylight_factor_scene(&mut scene), Ok(DAYLIGHT_FACTOR_LUX));
        assert!(scene.lights.is_empty());
        assert_eq!(scene.sky.as_ref().unwrap().kind(), SkyKind::CieOvercast);
        scene.sky = Some(Arc::new(Sky::cie_clear(Vec3::Y, Vec3::Y, 5.0).unwrap()));
        assert_eq!(
            daylight_factor_scene(&mut scene),
            Err(DaylightError::NotOvercast(SkyKind::CieClear))
        );
    }
}
