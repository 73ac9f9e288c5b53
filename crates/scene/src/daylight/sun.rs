//! Where the sun is and how bright its beam is on a clear day.
//!
//! **Position**: NREL's Solar Position Algorithm (I. Reda, A. Andreas, "Solar position
//! algorithm for solar radiation applications", Solar Energy 76(5), 577–589, 2004; NREL
//! TP-560-34302, revised 2008): the topocentric zenith angle and azimuth, with
//! atmospheric refraction, to ±0.0003° for years −2000 to 6000. The astronomy (the
//! periodic-term tables of the Earth's heliocentric coordinates, nutation, aberration,
//! parallax) is the `solar-positioning` crate (K. Brunner, MIT), built without its
//! `chrono` feature so that it brings no other crate. We chose it over our own port of
//! `spa.c` because it is that algorithm complete (all tables of the paper's appendix,
//! topocentric angles, refraction from pressure and temperature, ΔT as an input, and
//! Espenak & Meeus' ΔT polynomials for a default), pure Rust and dependency-free; what it
//! lacks for us (validated civil dates and times, time zones, scene directions) is in
//! [`super::time`] and [`super::site`]. The paper's worked example is our test.
//!
//! **Direct normal illuminance** on a clear day: the IES model (IES, "Recommended
//! practice for the calculation of daylight availability", RP-21-84, J. IES 13(4),
//! 381–392, 1984; IES Lighting Handbook, daylighting chapter):
//! `E_dn = E_sc · (1 AU / R)² · exp(−c · m)`, with the solar illuminance constant
//! E_sc = 127.5 klx, the clear-sky extinction coefficient c = 0.21 and the relative
//! optical air mass m. Two refinements of the handbook's shortcuts, both named where
//! they are used: the Earth–Sun distance R is SPA's own (the handbook's
//! 1 + 0.034 cos(2π(J − 2)/365) approximates (1/R)²), and m is Kasten & Young's (1989)
//! instead of 1/sin(altitude), which it matches to 0.3 % above 20° of altitude but, unlike
//! it, stays finite (37.9) at the horizon.

use super::time::{Date, TimeOfDay, julian_day};
use super::{Compass, DaylightError, Site};
use glam::Vec3;
use serde::Serialize;
use solar_positioning::{
    Location, RefractionCorrection, SolarPositions, delta_t, time::JulianDate,
};

/// Solar illuminance constant E_sc of IES RP-21-84: the sun's illuminance at 1 AU
/// outside the atmosphere, lx.
pub const SOLAR_ILLUMINANCE_CONSTANT: f64 = 127_500.0;

/// Luminous extinction coefficient c of a clear sky in IES RP-21-84's `exp(−c·m)`.
pub const CLEAR_SKY_EXTINCTION: f64 = 0.21;

/// The air that bends sunlight near the horizon: SPA's refraction correction (Reda &
/// Andreas 2004, eq. 42, Bennett's formula) scales with P/1010 hPa and 283 K/T.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Atmosphere {
    /// Mean annual local air pressure, hPa (= mbar).
    pub pressure: f64,
    /// Mean annual local air temperature, °C.
    pub temperature: f64,
}

impl Atmosphere {
    /// Air at `pressure` hPa (0 to 2000, exclusive of 0) and `temperature` °C (above
    /// −273, at most 100).
    pub fn new(pressure: f64, temperature: f64) -> Result<Atmosphere, DaylightError> {
        if !(pressure.is_finite() && pressure > 0.0 && pressure <= 2000.0) {
            return Err(DaylightError::OutOfRange {
                what: "pressure",
                value: pressure,
                range: "above 0 and at most 2000 hPa (sea level is about 1013)",
            });
        }
        if !(temperature.is_finite() && temperature > -273.0 && temperature <= 100.0) {
            return Err(DaylightError::OutOfRange {
                what: "temperature",
                value: temperature,
                range: "above −273 and at most 100 °C",
            });
        }
        Ok(Atmosphere {
            pressure,
            temperature,
        })
    }

    /// The ISO standard atmosphere (ISO 2533:1975, troposphere) at `elevation` m:
    /// T = 15 °C − 6.5 K/km · h and P = 1013.25 hPa · (1 − 2.25577·10⁻⁵ h)^5.25588. The
    /// default when a site gives no weather; refraction changes by 1 % per 10 hPa or
    /// 3 K, a few hundredths of a degree at the horizon and far less above it.
    pub fn standard(elevation: f64) -> Atmosphere {
        Atmosphere {
            pressure: 1013.25 * (1.0 - 2.25577e-5 * elevation).powf(5.25588),
            temperature: 15.0 - 0.0065 * elevation,
        }
    }
}

/// What SPA needs besides the site and the clock; `Default` estimates both.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SunOptions {
    /// ΔT = TT − UT1, s: how far the Earth's rotation lags atomic time (about 64.5 s
    /// in 2003, 69 s in 2025). `None` estimates it from the year and month with
    /// Espenak & Meeus' polynomials (NASA "Five Millennium Canon of Solar Eclipses",
    /// 2006, as updated in `solar-positioning`), valid for years −500 to 3000. ΔT only
    /// dates the sun's orbital motion (about 1° a day), so a minute's error in it moves
    /// the sun by under 0.001°.
    pub delta_t: Option<f64>,
    /// Air for refraction; `None` is [`Atmosphere::standard`] at the site's elevation.
    pub atmosphere: Option<Atmosphere>,
}

/// The sun seen from a site at a time: SPA's outputs and the inputs it used.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SunPosition {
    /// Topocentric zenith angle of the sun's centre, degrees, corrected for refraction
    /// (where it is seen); SPA's θ of eq. 44.
    pub zenith: f64,
    /// Topocentric azimuth, degrees clockwise from north (east 90°, south 180°), in
    /// [0, 360); SPA's Φ of eq. 46.
    pub azimuth: f64,
    /// The zenith angle without refraction (where the sun geometrically is), degrees.
    pub zenith_unrefracted: f64,
    /// Earth–Sun distance, AU (SPA's R, eq. 12).
    pub distance: f64,
    /// The Julian day (UT) of the instant.
    pub julian_day: f64,
    /// ΔT used, s.
    pub delta_t: f64,
    /// Air used for refraction.
    pub atmosphere: Atmosphere,
}

impl SunPosition {
    /// The sun at `site` when its clocks show `time` on `date`.
    pub fn new(
        site: &Site,
        date: &Date,
        time: &TimeOfDay,
        options: &SunOptions,
    ) -> Result<SunPosition, DaylightError> {
        if !(-2000..=6000).contains(&date.year()) {
            return Err(DaylightError::OutOfRange {
                what: "year",
                value: date.year() as f64,
                range: "−2000 to 6000 (the span SPA is valid for)",
            });
        }
        let delta_t = match options.delta_t {
            Some(dt) if dt.is_finite() && dt.abs() <= 8000.0 => dt,
            Some(dt) => {
                return Err(DaylightError::OutOfRange {
                    what: "ΔT",
                    value: dt,
                    range: "−8000 to 8000 s (about 69 s today)",
                });
            }
            None => {
                let year = date.year() as f64 + (date.month() as f64 - 0.5) / 12.0;
                delta_t::estimate(year).map_err(|_| DaylightError::OutOfRange {
                    what: "year for a ΔT estimate",
                    value: date.year() as f64,
                    range: "−500 to 3000; give ΔT explicitly outside it",
                })?
            }
        };
        let atmosphere = options
            .atmosphere
            .unwrap_or_else(|| Atmosphere::standard(site.elevation()));
        let spa_error = |e: solar_positioning::Error| DaylightError::Spa(e.to_string());
        let jd = julian_day(date, time, site.timezone());
        let prepared = SolarPositions::new()
            .for_time_from_julian(JulianDate::new(jd, delta_t).map_err(spa_error)?)
            .map_err(spa_error)?;
        let location = Location {
            latitude: site.latitude(),
            longitude: site.longitude(),
        };
        let refraction = RefractionCorrection::new(atmosphere.pressure, atmosphere.temperature)
            .map_err(spa_error)?;
        let seen = prepared
            .at(location, site.elevation(), Some(refraction))
            .map_err(spa_error)?;
        let geometric = prepared
            .at(location, site.elevation(), None)
            .map_err(spa_error)?;
        Ok(SunPosition {
            zenith: seen.zenith_angle(),
            azimuth: seen.azimuth(),
            zenith_unrefracted: geometric.zenith_angle(),
            distance: prepared
                .earth_radius_vector()
                .ok_or_else(|| DaylightError::Spa("no Earth–Sun distance".into()))?,
            julian_day: jd,
            delta_t,
            atmosphere,
        })
    }

    /// Apparent altitude of the sun's centre above the horizon, degrees (90° − zenith).
    pub fn altitude(&self) -> f64 {
        90.0 - self.zenith
    }

    /// Whether the sun's centre is seen above the horizon.
    pub fn is_up(&self) -> bool {
        self.zenith < 90.0
    }

    /// The unit scene vector toward the sun.
    pub fn to_sky(&self, compass: &Compass) -> Vec3 {
        compass.to_sky(self.zenith, self.azimuth)
    }

    /// The unit scene vector sunlight travels along (from the sun toward the ground),
    /// as [`crate::LightKind::Directional`] takes it.
    pub fn travel(&self, compass: &Compass) -> Vec3 {
        -self.to_sky(compass)
    }

    /// Direct normal illuminance of a clear day, lx: IES RP-21-84 (module doc)
    /// `127.5 klx · (1 AU/R)² · exp(−0.21 · m)` with m the Kasten–Young air mass of the
    /// apparent zenith; 0 when the sun is below the horizon. A mean design value, not a
    /// measurement: the handbook warns that real clear days scatter around it.
    pub fn clear_sky_direct_normal(&self) -> f64 {
        if !self.is_up() {
            return 0.0;
        }
        SOLAR_ILLUMINANCE_CONSTANT / (self.distance * self.distance)
            * (-CLEAR_SKY_EXTINCTION * relative_air_mass(self.zenith)).exp()
    }
}

/// Relative optical air mass at apparent zenith angle `zenith` degrees (F. Kasten,
/// A. T. Young, "Revised optical air mass tables and approximation formula", Applied
/// Optics 28(22), 4735–4738, 1989): `1 / (cos z + 0.50572 · (96.07995° − z)^−1.6364)`.
/// 1 at the zenith, 37.92 at the horizon; infinite (no beam) at and beyond 96.07995°.
pub fn relative_air_mass(zenith: f64) -> f64 {
    if zenith >= 96.07995 {
        return f64::INFINITY;
    }
    1.0 / (zenith.to_radians().cos() + 0.50572 * (96.07995 - zenith).powf(-1.6364))
}

/// What `invlight sun` reports: the sun at a site and time, in the astronomer's angles
/// and as the direction a scene's directional light takes, with the clear-sky beam.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SunReport {
    /// The site asked about.
    pub site: Site,
    /// The local date.
    pub date: Date,
    /// The local clock time.
    pub time: TimeOfDay,
    /// SPA's result.
    pub position: SunPosition,
    /// Apparent altitude, degrees.
    pub altitude: f64,
    /// The scene's up axis the direction is given for.
    pub up: [f32; 3],
    /// Unit scene vector the sunlight travels along.
    pub direction: [f32; 3],
    /// Clear-sky direct normal illuminance, lx ([`SunPosition::clear_sky_direct_normal`]).
    pub direct_normal_illuminance: f64,
}

impl SunReport {
    /// The report for a scene with up axis `up` (true north turned by the site's
    /// `north`).
    pub fn new(
        site: &Site,
        date: &Date,
        time: &TimeOfDay,
        options: &SunOptions,
        up: Vec3,
    ) -> Result<SunReport, DaylightError> {
        let compass = site.compass(up)?;
        let position = SunPosition::new(site, date, time, options)?;
        Ok(SunReport {
            site: *site,
            date: *date,
            time: *time,
            position,
            altitude: position.altitude(),
            up: compass.up().to_array(),
            direction: position.travel(&compass).to_array(),
            direct_normal_illuminance: position.clear_sky_direct_normal(),
        })
    }
}

impl std::fmt::Display for SunReport {
    /// `invlight sun`'s text: the astronomer's angles first, then what a scene takes.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (s, p) = (&self.site, &self.position);
        let [x, y, z] = self.direction;
        writeln!(
            f,
            "site       {}°, {}° (UTC{:+}), {} m; north turned {}°",
            s.latitude(),
            s.longitude(),
            s.timezone(),
            s.elevation(),
            s.north()
        )?;
        writeln!(f, "when       {} {} local time", self.date, self.time)?;
        let refraction = p.zenith_unrefracted - p.zenith;
        writeln!(
            f,
            "zenith     {:.5}° (refraction {refraction:.5}°)",
            p.zenith
        )?;
        writeln!(f, "azimuth    {:.5}° clockwise from north", p.azimuth)?;
        writeln!(f, "altitude   {:.5}°", self.altitude)?;
        let [ux, uy, uz] = self.up;
        writeln!(
            f,
            "direction  ({x:.5}, {y:.5}, {z:.5}): the light's travel in a scene with up ({ux}, {uy}, {uz})"
        )?;
        writeln!(
            f,
            "beam       {:.0} lx direct normal (IES RP-21-84 clear sky)",
            self.direct_normal_illuminance
        )
    }
}
