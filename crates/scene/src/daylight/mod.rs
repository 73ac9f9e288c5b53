//! Daylight as architects state it: a place and a time instead of a bare direction.
//!
//! - [`Site`] and [`Compass`]: latitude, longitude, the clock's zone and elevation; and
//!   where the scene's north and east lie, so that horizontal coordinates (zenith angle,
//!   azimuth clockwise from north) become scene vectors ([`Compass::to_sky`]).
//! - [`Date`], [`TimeOfDay`]: civil dates and clock times read from `2003-10-17` and
//!   `12:30:30`, refused when no calendar or clock has them.
//! - [`SunPosition`]: NREL's Solar Position Algorithm (Reda & Andreas 2004) for a site
//!   and local time, the direction sunlight travels in the scene, and the clear-sky
//!   direct normal illuminance of IES RP-21-84; [`SunReport`] is all of it, serialisable.
//! - [`Sky`]: the CIE standard overcast and clear skies as luminance over the dome,
//!   scaled to a horizontal illuminance, with a sampling distribution over directions
//!   and its density, for the dome emitter ([`crate::Scene::sky`]).
//! - [`Daylight`]: a site, the sun at a date and time and a sky as a problem file or
//!   the command line gives them, put on a scene by [`Daylight::apply`];
//!   [`daylight_factor_scene`] makes a scene what a daylight factor is measured in.
//!
//! docs/daylight.md states the conventions with a figure, the models and their sources.
//!
//! ```
//! use invlight_scene::daylight::{Date, Site, Sky, SunOptions, SunPosition, TimeOfDay};
//! use invlight_scene::Vec3;
//! // Montevideo, 21 December 2025 at 10:00 local time (UTC−3), a Y-up scene.
//! let site = Site::new(-34.9, -56.2, -3.0)?;
//! let date: Date = "2025-12-21".parse()?;
//! let time: TimeOfDay = "10:00".parse()?;
//! let sun = SunPosition::new(&site, &date, &time, &SunOptions::default())?;
//! assert!(sun.is_up() && sun.azimuth > 45.0 && sun.azimuth < 135.0); // morning: east
//! let compass = site.compass(Vec3::Y)?;
//! let travel = sun.travel(&compass); // what a directional light takes
//! assert!(travel.y < 0.0);
//! let sky = Sky::cie_clear(Vec3::Y, sun.to_sky(&compass), 15_000.0)?;
//! let s = sky.sample(0.3, 0.7);
//! assert!((s.pdf - sky.pdf(s.to_sky)).abs() <= 1e-5 * s.pdf);
//! # Ok::<(), invlight_scene::daylight::DaylightError>(())
//! ```

mod setting;
mod site;
mod sky;
mod sun;
mod time;

pub use setting::{
    DAYLIGHT_FACTOR_LUX, Daylight, DaylightFlags, SUN_NAME, SkySpec, SunAt, SunSchedule,
    daylight_factor_scene, set_sun,
};
pub use site::{Compass, Site};
pub use sky::{Sky, SkyKind, SkySample};
pub use sun::{
    Atmosphere, CLEAR_SKY_EXTINCTION, SOLAR_ILLUMINANCE_CONSTANT, SunOptions, SunPosition,
    SunReport, relative_air_mass,
};
pub use time::{Date, TimeOfDay, is_leap_year, julian_day};

use std::fmt;

/// Why a daylight input was refused. Each message says what was expected, so that the
/// command line and problem-file readers can pass it on as it is.
#[derive(Debug, Clone, PartialEq)]
pub enum DaylightError {
    /// Text that is not a `YYYY-MM-DD` date, or a date no calendar has.
    Date {
        /// The text or date as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// Text that is not an `HH:MM[:SS]` clock time, or a time no clock shows.
    Time {
        /// The text or time as given.
        text: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A number outside the range its quantity can take.
    OutOfRange {
        /// The quantity.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What it may be.
        range: &'static str,
    },
    /// A model that needs the sun above the horizon (the CIE clear sky) was given one
    /// below it.
    SunBelowHorizon {
        /// The sun's zenith angle, degrees (over 90).
        zenith: f64,
    },
    /// A sky name that is not one of [`SkyKind`]'s.
    UnknownSky(String),
    /// The solar position algorithm refused its inputs.
    Spa(String),
    /// Text that is not in the form expected.
    Format {
        /// The text.
        text: String,
        /// The form expected.
        expected: &'static str,
    },
    /// A sun by date and time was given without the site it shines on.
    NeedsSite,
    /// A north was given without a site to turn.
    NorthNeedsSite,
    /// A clear sky was asked for a scene without a sun to place it by.
    NeedsSun,
    /// The scene has several directional lights and none is named [`SUN_NAME`].
    SeveralSuns(Vec<String>),
    /// A daylight factor was asked under a sky that is not the CIE overcast sky.
    NotOvercast(SkyKind),
}

impl fmt::Display for DaylightError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DaylightError::Date { text, problem } => write!(f, "date '{text}': {problem}"),
            DaylightError::Time { text, problem } => write!(f, "time '{text}': {problem}"),
            DaylightError::OutOfRange { what, value, range } => {
                write!(f, "{what} {value} is out of range: expected {range}")
            }
            DaylightError::SunBelowHorizon { zenith } => write!(
                f,
                "the sun is {:.2}° below the horizon; the CIE clear sky needs it above \
                 (use the overcast sky, or a daytime hour)",
                zenith - 90.0
            ),
            DaylightError::UnknownSky(name) => write!(
                f,
                "unknown sky '{name}': expected {}",
                SkyKind::ALL.map(|k| k.name()).join(" or ")
            ),
            DaylightError::Spa(message) => write!(f, "solar position: {message}"),
            DaylightError::Format { text, expected } => write!(f, "'{text}': expected {expected}"),
            DaylightError::NeedsSite => f.write_str(
                "a sun by date and time needs the site it shines on: give a <site> or --site LAT,LON,TZ",
            ),
            DaylightError::NorthNeedsSite => f.write_str(
                "--north turns a site's north, and there is none: give --site LAT,LON,TZ or a problem's <site>",
            ),
            DaylightError::NeedsSun => f.write_str(
                "the CIE clear sky is drawn about the sun, and the scene has none: give a sun by date and time (<sun>, --sun) or a directional light",
            ),
            DaylightError::SeveralSuns(names) => write!(
                f,
                "the scene has {} directional lights ({}) and none is named '{SUN_NAME}': name the one the site's sun replaces '{SUN_NAME}'",
                names.len(),
                names.join(", ")
            ),
            DaylightError::NotOvercast(kind) => write!(
                f,
                "a daylight factor is measured under the CIE overcast sky, and the sky is {kind}: use cie-overcast"
            ),
        }
    }
}

impl std::error::Error for DaylightError {}
