//! Daylight against what others published: SPA's worked example and an independent SPA
//! implementation (pvlib) at other places and dates, the sun's path around noon and
//! sunrise, and the Kasten–Young air mass.

use invlight_scene::Vec3;
use invlight_scene::daylight::{
    Atmosphere, Compass, Date, DaylightError, Site, SunOptions, SunPosition, SunReport, TimeOfDay,
    relative_air_mass,
};

fn sun(site: &Site, date: &str, time: &str, options: &SunOptions) -> SunPosition {
    SunPosition::new(
        site,
        &date.parse().unwrap(),
        &time.parse().unwrap(),
        options,
    )
    .unwrap_or_else(|e| panic!("{date} {time}: {e}"))
}

fn options(delta_t: f64, pressure: f64, temperature: f64) -> SunOptions {
    SunOptions {
        delta_t: Some(delta_t),
        atmosphere: Some(Atmosphere::new(pressure, temperature).unwrap()),
    }
}

mod sun {
    use super::*;

    /// Reda & Andreas (2004), table A5.1: Golden, Colorado, 2003-10-17 12:30:30 at
    /// −7 h, ΔT 67 s, 820 mbar, 11 °C: topocentric zenith 50.11162°, azimuth 194.34024°,
    /// Earth radius vector 0.9965422974 AU.
    #[test]
    fn spa_worked_example() {
        let site = Site::new(39.742476, -105.1786, -7.0)
            .unwrap()
            .with_elevation(1830.14)
            .unwrap();
        let s = sun(&site, "2003-10-17", "12:30:30", &options(67.0, 820.0, 11.0));
        assert!((s.zenith - 50.11162).abs() < 1e-4, "zenith {}", s.zenith);
        assert!(
            (s.azimuth - 194.34024).abs() < 1e-4,
            "azimuth {}",
            s.azimuth
        );
        assert!(
            (s.distance - 0.996_542_297_4).abs() < 1e-8,
            "R {}",
            s.distance
        );
        assert!((s.julian_day - 2_452_930.312_847).abs() < 1e-6);
        assert!(s.zenith_unrefracted > s.zenith, "refraction lifts the sun");
    }

    /// Other places, dates and zones, against pvlib 0.16.1's `spa.solar_position`
    /// (W. Holmgren et al., a separate implementation of the same algorithm), run once
    /// for these inputs with atmos_refract 0.5667: the Southern Hemisphere in both
    /// solstices, a leap day, a sun near the zenith, the midnight sun, a local time
    /// whose UTC date is the day before, a sun near the horizon and a high site.
    #[test]
    fn spa_matches_pvlib() {
        #[rustfmt::skip]
        let cases: [(&str, &str, [f64; 10]); 8] = [
            // date, time, [zone, latitude, longitude, elevation, hPa, °C, ΔT;
            //              zenith, azimuth, zenith without refraction]
            ("2025-12-21", "10:00:00", [-3.0, -34.9, -56.2, 43.0, 1013.25, 15.0, 69.2, 37.085567, 83.197463, 37.098159]),
            ("2026-06-21", "12:00:00", [-3.0, -34.9, -56.2, 43.0, 1013.25, 15.0, 69.3, 59.351492, 12.444891, 59.379484]),
            ("2024-02-29", "08:15:00", [1.0, 59.91, 10.75, 23.0, 1013.25, 15.0, 69.2, 83.884195, 116.816853, 84.022550]),
            ("2030-03-20", "13:07:30", [8.0, 1.35, 103.82, 15.0, 1010.0, 27.0, 71.0, 1.907123, 141.546404, 1.907626]),
            ("2025-06-21", "23:59:59", [0.0, 64.15, -21.94, 20.0, 1013.25, 15.0, 69.2, 90.097350, 339.500997, 90.681054]),
            ("2019-01-01", "00:30:00", [10.0, -33.87, 151.21, 58.0, 1013.25, 15.0, 69.0, 122.561271, 171.308472, 122.561271]),
            ("1995-09-23", "17:30:00", [9.0, 35.68, 139.69, 40.0, 1013.25, 15.0, 61.0, 88.820636, 269.496181, 89.197767]),
            ("2000-01-01", "12:00:00", [-5.0, -0.18, -78.47, 2850.0, 730.0, 12.0, 63.8, 23.213886, 169.880666, 23.219084]),
        ];
        for (date, time, [tz, lat, lon, elev, p, t, dt, zenith, azimuth, geometric]) in cases {
            let site = Site::new(lat, lon, tz)
                .unwrap()
                .with_elevation(elev)
                .unwrap();
            let s = sun(&site, date, time, &options(dt, p, t));
            let what = format!("{date} {time} at {lat}, {lon}");
            assert!(
                (s.zenith - zenith).abs() < 1e-5,
                "{what}: zenith {}",
                s.zenith
            );
            assert!(
                (s.azimuth - azimuth).abs() < 1e-5,
                "{what}: azimuth {}",
                s.azimuth
            );
            assert!((s.zenith_unrefracted - geometric).abs() < 1e-5, "{what}");
        }
    }

    /// The sun of a day scanned minute by minute, as (minute of the day, position).
    fn day(site: &Site, date: &str) -> Vec<(u32, SunPosition)> {
        let date: Date = date.parse().unwrap();
        (0..24 * 60)
            .map(|m| {
                let t = TimeOfDay::new(m / 60, m % 60, 0.0).unwrap();
                let s = SunPosition::new(site, &date, &t, &SunOptions::default()).unwrap();
                (m, s)
            })
            .collect()
    }

    /// Montevideo at the December solstice: the sun culminates north of the zenith at
    /// |latitude − declination| = |−34.9° + 23.44°| = 11.46° (refraction and parallax
    /// change that by under 0.01°), within the equation of time's ±17 minutes of mean
    /// solar noon (12:00 + (−45° + 56.2°)/15° h = 12:44.8 in UTC−3).
    #[test]
    fn noon_in_montevideo_at_the_december_solstice() {
        let site = Site::new(-34.9, -56.2, -3.0).unwrap();
        let (minute, noon) = day(&site, "2025-12-21")
            .into_iter()
            .min_by(|a, b| a.1.zenith.total_cmp(&b.1.zenith))
            .unwrap();
        assert!((noon.zenith - 11.46).abs() < 0.02, "{}", noon.zenith);
        assert!(
            noon.azimuth.to_radians().cos() > 0.99,
            "north: {}",
            noon.azimuth
        );
        assert!(
            (minute as f64 - (12.0 * 60.0 + 44.8)).abs() < 17.0,
            "{minute}"
        );
        // ΔT was estimated for 2025: around 69 s.
        assert!((noon.delta_t - 69.0).abs() < 3.0, "{}", noon.delta_t);
    }

    /// On the equator at the March equinox the sun rises due east about 06:00 local
    /// mean time (give or take the equation of time's 7.5 minutes and refraction's 2),
    /// sets due west, and the day of its centre lasts 12 h plus the few minutes
    /// refraction adds at both ends.
    #[test]
    fn sunrise_and_sunset_on_the_equator_at_the_equinox() {
        let site = Site::new(0.0, 0.0, 0.0).unwrap();
        let day = day(&site, "2025-03-20");
        let up: Vec<&(u32, SunPosition)> = day.iter().filter(|(_, s)| s.is_up()).collect();
        let (rise, first) = up[0];
        let (set, last) = up[up.len() - 1];
        assert!((5 * 60 + 50..=6 * 60 + 20).contains(rise), "rise {rise}");
        assert!((first.azimuth - 90.0).abs() < 0.5, "{}", first.azimuth);
        assert!((last.azimuth - 270.0).abs() < 0.5, "{}", last.azimuth);
        let length = set - rise;
        assert!(
            (12 * 60..=12 * 60 + 15).contains(&length),
            "day {length} min"
        );
        assert_eq!(up.len() as u32, length + 1, "one daytime");
    }

    #[test]
    fn refuses_what_spa_cannot_compute() {
        let site = Site::new(0.0, 0.0, 0.0).unwrap();
        let t: TimeOfDay = "12:00".parse().unwrap();
        let far: Date = "6001-01-01".parse().unwrap();
        assert!(matches!(
            SunPosition::new(&site, &far, &t, &SunOptions::default()),
            Err(DaylightError::OutOfRange { what: "year", .. })
        ));
        let d: Date = "2000-01-01".parse().unwrap();
        let bad = SunOptions {
            delta_t: Some(f64::NAN),
            atmosphere: None,
        };
        assert!(SunPosition::new(&site, &d, &t, &bad).is_err());
        assert!(Atmosphere::new(0.0, 10.0).is_err() && Atmosphere::new(1000.0, -300.0).is_err());
        // ΔT estimates stop at 3000; an explicit one still works.
        let late: Date = "4000-06-01".parse().unwrap();
        assert!(SunPosition::new(&site, &late, &t, &SunOptions::default()).is_err());
        assert!(SunPosition::new(&site, &late, &t, &options(5000.0, 1013.25, 15.0)).is_ok());
    }

    /// ISO 2533 at sea level and at 1830 m (tables: 1013.25 hPa, 15 °C; 812 hPa, 3.1 °C).
    #[test]
    fn standard_atmosphere() {
        let sea = Atmosphere::standard(0.0);
        assert_eq!((sea.pressure, sea.temperature), (1013.25, 15.0));
        let golden = Atmosphere::standard(1830.14);
        assert!((golden.pressure - 811.9).abs() < 0.5, "{}", golden.pressure);
        assert!((golden.temperature - 3.1).abs() < 0.05);
    }

    /// Kasten & Young's formula as pvlib 0.16.1 computes it (`kastenyoung1989`), and
    /// the 37.92 at the horizon the paper quotes.
    #[test]
    fn air_mass_of_kasten_and_young() {
        for (z, m) in [
            (0.0, 0.99971199),
            (30.0, 1.15399223),
            (60.0, 1.99429285),
            (80.0, 5.58603588),
            (85.0, 10.30579133),
            (89.0, 26.31055507),
            (90.0, 37.91960838),
        ] {
            assert!(
                (relative_air_mass(z) - m).abs() < 1e-7 * m,
                "{z}: {}",
                relative_air_mass(z)
            );
        }
        assert_eq!(relative_air_mass(97.0), f64::INFINITY);
    }

    /// IES RP-21-84 for the SPA example: 127.5 klx / 0.99654² · exp(−0.21 · 1.55701)
    /// = 92 580 lx; none at night.
    #[test]
    fn clear_sky_direct_normal_illuminance() {
        let site = Site::new(39.742476, -105.1786, -7.0)
            .unwrap()
            .with_elevation(1830.14)
            .unwrap();
        let s = sun(&site, "2003-10-17", "12:30:30", &options(67.0, 820.0, 11.0));
        assert!(
            (s.clear_sky_direct_normal() - 92_579.86).abs() < 0.5,
            "{}",
            s.clear_sky_direct_normal()
        );
        let night = sun(&site, "2003-10-17", "23:00:00", &SunOptions::default());
        assert!(!night.is_up() && night.clear_sky_direct_normal() == 0.0);
    }

    /// What `invlight sun --json` prints, for the SPA example in a Y-up and a Z-up scene.
    #[test]
    fn report_serialises_with_scene_direction() {
        let site = Site::new(39.742476, -105.1786, -7.0)
            .unwrap()
            .with_elevation(1830.14)
            .unwrap();
        let (d, t) = ("2003-10-17".parse().unwrap(), "12:30:30".parse().unwrap());
        let opts = options(67.0, 820.0, 11.0);
        for up in [Vec3::Y, Vec3::Z] {
            let r = SunReport::new(&site, &d, &t, &opts, up).unwrap();
            let expected = -Compass::new(up, 0.0).unwrap().to_sky(50.111622, 194.340241);
            assert!((Vec3::from_array(r.direction) - expected).length() < 1e-5);
            // Sunlight goes down, and from the south-south-west toward north-north-east.
            assert!(Vec3::from_array(r.direction).dot(up) < 0.0);
            let json = serde_json::to_value(r).unwrap();
            assert_eq!(json["date"], "2003-10-17");
            assert_eq!(json["time"], "12:30:30");
            assert_eq!(json["site"]["latitude"], 39.742476);
            assert!((json["position"]["zenith"].as_f64().unwrap() - 50.11162).abs() < 1e-4);
            assert!((json["altitude"].as_f64().unwrap() - 39.88838).abs() < 1e-4);
            assert_eq!(json["direction"].as_array().unwrap().len(), 3);
        }
        // A model drawn with north along +X (turned 90°): the sun in the south-south-west
        // now shines from about −X, toward +X.
        let turned = site.with_north(90.0).unwrap();
        let r = SunReport::new(&turned, &d, &t, &opts, Vec3::Y).unwrap();
        assert!(r.direction[0] > 0.6, "{:?}", r.direction);
    }
}
