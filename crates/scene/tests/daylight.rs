//! Daylight against what others published and what can be integrated by hand: SPA's
//! worked example and an independent SPA implementation (pvlib) at other places and
//! dates, the sun's path around noon and sunrise, the Kasten–Young air mass, and the CIE
//! skies: each one's horizontal illuminance integrated here over the dome, its shape
//! against the CIE formulas, and its sampling distribution against its density.
//!
//! The skies traced as emitters are checked in the photon crate's tests
//! (`crates/photon/tests/daylight.rs`).

use invlight_scene::Vec3;
use invlight_scene::daylight::{
    Atmosphere, Compass, Date, DaylightError, Site, Sky, SkyKind, SunOptions, SunPosition,
    SunReport, TimeOfDay, relative_air_mass,
};
use invlight_stats::{Pcg32, normal_quantile};
use std::f64::consts::PI;

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

mod sky {
    use super::*;

    /// ∫ over the upper hemisphere of `f(direction) · cos Z dω`, by the midpoint rule
    /// in (Z, azimuth) with `n` × 4n cells, each weighted by its sin Z Jacobian. At
    /// n = 480 its error on the skies here is about 4·10⁻⁶, well under the 5·10⁻⁵ the
    /// tests allow the sky's own, coarser normalisation.
    fn dome_integral(compass: &Compass, n: usize, f: impl Fn(Vec3) -> f64) -> f64 {
        let (dz, da) = (90.0 / n as f64, 360.0 / (4 * n) as f64);
        let mut sum = 0.0;
        for i in 0..n {
            let z = (i as f64 + 0.5) * dz;
            let w = z.to_radians().sin() * z.to_radians().cos() * dz.to_radians() * da.to_radians();
            for j in 0..4 * n {
                let a = (j as f64 + 0.5) * da;
                sum += f(compass.to_sky(z, a)) * w;
            }
        }
        sum
    }

    /// The skies tested, with the compass that names their directions.
    fn skies() -> Vec<(String, Sky, Compass)> {
        let mut out = Vec::new();
        for (up, north) in [(Vec3::Y, 0.0), (Vec3::Z, 30.0)] {
            let c = Compass::new(up, north).unwrap();
            out.push((
                format!("overcast {up}"),
                Sky::cie_overcast(up, 10_000.0).unwrap(),
                c,
            ));
            for (zs, az) in [
                (0.0, 0.0),
                (30.0, 200.0),
                (60.0, 95.0),
                (85.0, 310.0),
                (90.0, 45.0),
            ] {
                let sky = Sky::cie_clear(up, c.to_sky(zs, az), 15_000.0).unwrap();
                out.push((format!("clear {up} sun {zs} {az}"), sky, c));
            }
        }
        out
    }

    #[test]
    fn unobstructed_horizontal_plane_reads_horizontal_lux() {
        for (name, sky, c) in skies() {
            let e = dome_integral(&c, 480, |d| sky.luminance(d) as f64);
            let want = sky.horizontal_illuminance();
            assert!(
                (e - want).abs() < 5e-5 * want,
                "{name}: {e} lx, want {want}"
            );
        }
    }

    /// E_h = 7π/9 · L_z; L(Z) = L_z (1 + 2 cos Z)/3 in every azimuth.
    #[test]
    fn overcast_closed_forms() {
        let sky = Sky::cie_overcast(Vec3::Z, 10_000.0).unwrap();
        assert_eq!(sky.kind(), SkyKind::CieOvercast);
        let lz = 9.0 * 10_000.0 / (7.0 * PI);
        assert!((sky.zenith_luminance() - lz).abs() < 1e-9 * lz);
        let c = Compass::new(Vec3::Z, 0.0).unwrap();
        for z in [0.0f64, 20.0, 45.0, 70.0, 89.99] {
            for a in [0.0, 100.0, 250.0] {
                let l = sky.luminance(c.to_sky(z, a)) as f64;
                let want = lz * (1.0 + 2.0 * z.to_radians().cos()) / 3.0;
                assert!((l - want).abs() < 1e-5 * want, "{z} {a}: {l} {want}");
            }
        }
        assert_eq!(sky.luminance(c.to_sky(90.5, 0.0)), 0.0);
        assert_eq!(sky.luminance(Vec3::NEG_Z), 0.0);
        assert!(sky.sun().is_none());
    }

    /// ISO 15469 type 12 worked by hand: the sun at Z_s = 30°, the point at Z = 60° on
    /// the far side (χ = 90°): f(90°) = 1 exactly, φ(60°) = 1 − e^{−0.64} = 0.472708,
    /// f(30°) = 1 + 10(e^{−π/2} − e^{−3π/2}) + 0.45·¾ = 3.326468, φ(0) = 1 − e^{−0.32}
    /// = 0.273851, so L/L_z = 0.472708 / (3.326468 · 0.273851) = 0.518914. The others
    /// computed the same way (sun zenith, point zenith, azimuth from the sun; L/L_z).
    #[test]
    fn clear_sky_against_the_cie_formula() {
        let c = Compass::new(Vec3::Y, 0.0).unwrap();
        for (zs, z, da, want) in [
            (30.0, 60.0, 180.0, 0.518914),
            (30.0, 30.0, 0.0, 3.852460),
            (30.0, 0.0, 0.0, 1.0),
            (60.0, 85.0, 90.0, 2.478986),
            (10.0, 45.0, 45.0, 0.461065),
            (75.0, 75.0, 0.0, 25.880579),
            (75.0, 89.0, 180.0, 4.263263),
            (0.0, 50.0, 0.0, 0.230122),
            (45.0, 20.0, 270.0, 0.963245),
        ] {
            let sun_az = 137.0;
            let sky = Sky::cie_clear(Vec3::Y, c.to_sky(zs, sun_az), 10_000.0).unwrap();
            let got = sky.luminance(c.to_sky(z, sun_az + da)) as f64 / sky.zenith_luminance();
            assert!(
                (got - want).abs() < 2e-6 * want.max(1.0),
                "{zs} {z} {da}: {got} {want}"
            );
        }
    }

    /// The CIE 1973 clear sky as Radiance's skybright.cal writes it (0.91 + 10 e^{−3χ} +
    /// 0.45 cos²χ)(1 − e^{−0.32/cos Z}), normalised at the zenith: the same sky as type
    /// 12 but for 0.91 against 0.91012, so equal to 2·10⁻⁴ everywhere.
    #[test]
    fn clear_sky_is_the_cie_1973_sky() {
        let c = Compass::new(Vec3::Z, 0.0).unwrap();
        let mut rng = Pcg32::new(7, 0);
        for _ in 0..200 {
            let (zs, az_s) = (rng.uniform() as f64 * 90.0, rng.uniform() as f64 * 360.0);
            let to_sun = c.to_sky(zs, az_s).as_dvec3();
            let sky = Sky::cie_clear(Vec3::Z, to_sun.as_vec3(), 10_000.0).unwrap();
            let kittler = |d: glam::DVec3| {
                let cos_chi = d.dot(to_sun).clamp(-1.0, 1.0);
                (0.91 + 10.0 * (-3.0 * cos_chi.acos()).exp() + 0.45 * cos_chi * cos_chi)
                    * (1.0 - (-0.32 / d.z).exp())
            };
            let (z, a) = (rng.uniform() as f64 * 89.9, rng.uniform() as f64 * 360.0);
            let d = c.to_sky(z, a).as_dvec3();
            let want = kittler(d) / kittler(glam::DVec3::Z);
            let got = sky.luminance(d.as_vec3()) as f64 / sky.zenith_luminance();
            assert!(
                (got / want - 1.0).abs() < 2e-4,
                "sun {zs} {az_s}, point {z} {a}: {got} {want}"
            );
        }
    }

    /// Radiance's gensky approximates the clear sky's E_h / L_z by a polynomial in the
    /// solar altitude (`normsc()`, divided by its F2); our integral agrees with that
    /// fit to its 0.2 %.
    #[test]
    fn clear_sky_normalisation_matches_gensky() {
        let c = Compass::new(Vec3::Z, 0.0).unwrap();
        for alt in [5.0f64, 10.0, 20.0, 30.0, 45.0, 60.0, 75.0, 87.0] {
            let a = alt.to_radians();
            let x = (a - PI / 4.0) / (PI / 4.0);
            let normsc = [2.766521, 0.547665, -0.369832, 0.009237, 0.059229]
                .iter()
                .rev()
                .fold(0.0, |acc, k| acc * x + k);
            let f2 = 0.274 * (0.91 + 10.0 * (-3.0 * (PI / 2.0 - a)).exp() + 0.45 * a.sin().powi(2));
            let sky = Sky::cie_clear(Vec3::Z, c.to_sky(90.0 - alt, 0.0), 10_000.0).unwrap();
            let ratio = sky.horizontal_illuminance() / sky.zenith_luminance();
            assert!(
                (ratio / (normsc / f2) - 1.0).abs() < 4e-3,
                "altitude {alt}: {ratio}"
            );
        }
    }

    #[test]
    fn clear_sky_needs_the_sun_up() {
        let c = Compass::new(Vec3::Y, 0.0).unwrap();
        match Sky::cie_clear(Vec3::Y, c.to_sky(95.0, 10.0), 10_000.0) {
            Err(e @ DaylightError::SunBelowHorizon { .. }) => {
                assert!(e.to_string().contains("5.00° below the horizon"), "{e}")
            }
            other => panic!("{other:?}"),
        }
        assert!(Sky::cie_clear(Vec3::Y, c.to_sky(90.0, 10.0), 10_000.0).is_ok());
        assert!(Sky::cie_overcast(Vec3::Y, -1.0).is_err());
        assert!(Sky::cie_overcast(Vec3::ZERO, 1.0).is_err());
        assert_eq!("cie-clear".parse::<SkyKind>().unwrap(), SkyKind::CieClear);
        let e = "cie-sunny".parse::<SkyKind>().unwrap_err().to_string();
        assert!(e.contains("cie-overcast or cie-clear"), "{e}");
    }

    /// ∫ pdf dω over the whole sphere (nothing below the horizon) is 1.
    #[test]
    fn pdf_integrates_to_one() {
        for (name, sky, c) in skies() {
            let upper = dome_integral(&c, 480, |d| {
                let cos = d.dot(c.up()) as f64;
                sky.pdf(d) as f64 / cos
            });
            assert!((upper - 1.0).abs() < 1e-3, "{name}: {upper}");
            let below = c.to_sky(120.0, 33.0);
            assert_eq!(sky.pdf(below), 0.0, "{name}");
        }
    }

    /// A drawn direction's density and luminance are what `pdf` and `luminance` say
    /// of it (a connection's multiple-importance weights need the two to agree), and it
    /// lies above the horizon. That the density is that of the draws is
    /// `histogram_matches_pdf`'s.
    #[test]
    fn sample_pdf_is_pdf() {
        for (name, sky, c) in skies() {
            let mut rng = Pcg32::new(11, 0);
            for _ in 0..20_000 {
                let s = sky.sample(rng.uniform(), rng.uniform());
                assert!((s.to_sky.length() - 1.0).abs() < 1e-5);
                assert!(s.to_sky.dot(c.up()) >= 0.0, "{name}");
                assert!(s.pdf > 0.0, "{name}: {s:?}");
                assert_eq!(s.pdf, sky.pdf(s.to_sky), "{name}");
                assert_eq!(s.luminance, sky.luminance(s.to_sky), "{name}");
            }
            let a = sky.sample(0.25, 0.75);
            assert_eq!(a, sky.sample(0.25, 0.75), "deterministic");
        }
    }

    /// Each drawn direction's L / pdf is the dome's ∫ L dω (the dome emitter's photon
    /// power per m² of its disk): exactly for the overcast sky, whose density is ∝ L;
    /// close to it for the clear sky's table, and on average. And L·cos Z / pdf
    /// estimates E_h.
    #[test]
    fn samples_estimate_the_dome_and_horizontal_illuminance() {
        for (name, sky, c) in skies() {
            let e_h = sky.horizontal_illuminance();
            let dome = sky.dome_luminance();
            let n = 100_000;
            let mut rng = Pcg32::new(3, 1);
            let (mut sum, mut sum_sq, mut h, mut h_sq) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            for _ in 0..n {
                let s = sky.sample(rng.uniform(), rng.uniform());
                let w = s.luminance as f64 / s.pdf as f64;
                if sky.kind() == SkyKind::CieOvercast {
                    assert!((w - dome).abs() < 1e-4 * dome, "{name}: {w}");
                }
                sum += w;
                sum_sq += w * w;
                let wh = w * s.to_sky.dot(c.up()) as f64;
                h += wh;
                h_sq += wh * wh;
            }
            let n = n as f64;
            for (what, sum, sum_sq, want) in [("dome", sum, sum_sq, dome), ("E_h", h, h_sq, e_h)] {
                let mean = sum / n;
                let sd = (sum_sq / n - mean * mean).max(0.0).sqrt();
                assert!(
                    (mean - want).abs() < 4.0 * sd / n.sqrt() + 1e-6 * want,
                    "{name}: {what} {mean}, want {want}"
                );
                if what == "dome" {
                    assert!(sd < 0.1 * dome, "{name}: the table follows L (sd {sd})");
                }
            }
        }
    }

    /// The dome's ∫ L dω against the midpoint rule here: 12/7 E_h for the overcast sky.
    #[test]
    fn dome_luminance_is_the_integral_of_luminance() {
        for (name, sky, c) in skies() {
            let e = dome_integral(&c, 480, |d| sky.luminance(d) as f64 / d.dot(c.up()) as f64);
            let want = sky.dome_luminance();
            assert!((e - want).abs() < 5e-5 * want, "{name}: {e}, want {want}");
        }
        let overcast = Sky::cie_overcast(Vec3::Y, 7_000.0).unwrap();
        assert!((overcast.dome_luminance() - 12_000.0).abs() < 1e-9);
    }

    /// Pearson's χ² of 200 000 draws in 10 (cos Z) × 24 (azimuth) bins of the compass
    /// frame, against counts from integrating `pdf` over each bin (pbrt-v4 and Mitsuba's
    /// chi2 tests); bins expecting under 5 draws are pooled. Fails at p < 10⁻⁴.
    #[test]
    fn histogram_matches_pdf() {
        const MU: usize = 10;
        const AZ: usize = 24;
        const SUB: usize = 24;
        for (name, sky, c) in skies() {
            let mut expected = vec![0.0f64; MU * AZ];
            for i in 0..MU * SUB {
                let mu = (i as f64 + 0.5) / (MU * SUB) as f64;
                for j in 0..AZ * SUB {
                    let a = (j as f64 + 0.5) / (AZ * SUB) as f64 * 360.0;
                    let d = c.to_sky(mu.acos().to_degrees(), a);
                    // dω = dμ dφ
                    let w = sky.pdf(d) as f64 * (2.0 * PI) / ((MU * SUB * AZ * SUB) as f64);
                    expected[(i / SUB) * AZ + j / SUB] += w;
                }
            }
            let n = 200_000usize;
            let mut observed = vec![0u32; MU * AZ];
            let mut rng = Pcg32::new(5, 2);
            for _ in 0..n {
                let s = sky.sample(rng.uniform(), rng.uniform());
                let (z, a) = c.angles(s.to_sky);
                let mu = z.to_radians().cos().clamp(0.0, 1.0 - 1e-12);
                observed[(mu * MU as f64) as usize * AZ
                    + ((a / 360.0 * AZ as f64) as usize).min(AZ - 1)] += 1;
            }
            let (mut chi2, mut dof) = (0.0, 0usize);
            let (mut pooled_e, mut pooled_o) = (0.0, 0.0);
            for (e, &o) in expected.iter().zip(&observed) {
                let e = e * n as f64;
                if e < 5.0 {
                    pooled_e += e;
                    pooled_o += o as f64;
                } else {
                    chi2 += (o as f64 - e).powi(2) / e;
                    dof += 1;
                }
            }
            if pooled_e > 0.0 {
                chi2 += (pooled_o - pooled_e).powi(2) / pooled_e;
                dof += 1;
            }
            let k = (dof - 1) as f64;
            // Wilson–Hilferty: χ²_k quantile ≈ k (1 − 2/9k + z √(2/9k))³.
            let z = normal_quantile(1.0 - 1e-4);
            let limit = k * (1.0 - 2.0 / (9.0 * k) + z * (2.0 / (9.0 * k)).sqrt()).powi(3);
            assert!(
                chi2 < limit,
                "{name}: χ² {chi2:.1} over {k} degrees of freedom (limit {limit:.1})"
            );
        }
    }
}
