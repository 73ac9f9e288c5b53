//! Where a scene stands on Earth ([`Site`]) and which of its directions are north and
//! east ([`Compass`]), so that a sun or sky given in the astronomer's horizontal
//! coordinates (zenith angle, azimuth clockwise from north) lands in scene coordinates.
//!
//! The scene's north before any turn (drawn in docs/daylight-compass.svg): −Z when the scene
//! is Y-up (glTF, most OBJ exports: looking down from +Y with −Z up the page, +X is to the
//! right, so east is +X), +Y when it is Z-up (Blender, architectural tools: the same
//! picture looking down from +Z). Both are the "into the screen" axis of the front view
//! in those conventions, and both put east on +X. A model drawn with true north
//! elsewhere gives `north`: the angle, clockwise seen from above, from that default to
//! true north.

use super::DaylightError;
use glam::{DVec3, Vec3};
use serde::Serialize;

/// A place on Earth and the clock kept there.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Site {
    latitude: f64,
    longitude: f64,
    timezone: f64,
    elevation: f64,
    north: f64,
}

fn check(
    what: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    range: &'static str,
) -> Result<f64, DaylightError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(DaylightError::OutOfRange { what, value, range })
    }
}

impl Site {
    /// A site at sea level whose model has its north where the scene's axes put it.
    ///
    /// - `latitude`: geodetic, degrees, positive north, −90 to 90.
    /// - `longitude`: degrees, positive east of Greenwich, −180 to 180 (Montevideo −56.2).
    /// - `timezone`: the clock's offset from UTC in hours, positive east, −18 to 18
    ///   (Montevideo −3, India 5.5); where daylight saving is in force, the offset in
    ///   force (−6 for Mountain Daylight Time).
    pub fn new(latitude: f64, longitude: f64, timezone: f64) -> Result<Site, DaylightError> {
        Ok(Site {
            latitude: check(
                "latitude",
                latitude,
                -90.0,
                90.0,
                "−90 to 90 degrees, positive north",
            )?,
            longitude: check(
                "longitude",
                longitude,
                -180.0,
                180.0,
                "−180 to 180 degrees, positive east of Greenwich",
            )?,
            timezone: check(
                "timezone",
                timezone,
                -18.0,
                18.0,
                "−18 to 18 hours from UTC, positive east",
            )?,
            elevation: 0.0,
            north: 0.0,
        })
    }

    /// The same site `elevation` metres above mean sea level (−500 to 9000: the Dead Sea
    /// shore to above Everest). Elevation moves the observer for SPA's parallax and sets
    /// the default air pressure for refraction.
    pub fn with_elevation(self, elevation: f64) -> Result<Site, DaylightError> {
        Ok(Site {
            elevation: check(
                "elevation",
                elevation,
                -500.0,
                9000.0,
                "−500 to 9000 m above sea level",
            )?,
            ..self
        })
    }

    /// The same site with the model's true north turned `north` degrees clockwise, seen
    /// from above, from the scene's default north (−Z for Y-up, +Y for Z-up). Any finite
    /// angle; it is kept in [0, 360).
    pub fn with_north(self, north: f64) -> Result<Site, DaylightError> {
        let north = check(
            "north",
            north,
            f64::MIN,
            f64::MAX,
            "a finite angle in degrees",
        )?;
        Ok(Site {
            north: north.rem_euclid(360.0),
            ..self
        })
    }

    /// Latitude, degrees, positive north.
    pub fn latitude(&self) -> f64 {
        self.latitude
    }

    /// Longitude, degrees, positive east.
    pub fn longitude(&self) -> f64 {
        self.longitude
    }

    /// Offset of the local clock from UTC, hours, positive east.
    pub fn timezone(&self) -> f64 {
        self.timezone
    }

    /// Height above mean sea level, m.
    pub fn elevation(&self) -> f64 {
        self.elevation
    }

    /// Turn of the model's true north from the scene's default, degrees clockwise from
    /// above, in [0, 360).
    pub fn north(&self) -> f64 {
        self.north
    }

    /// Hours between the clock's zone and the site's own meridian (longitude / 15 −
    /// timezone). Zones follow borders, so one or two hours are common (Madrid ≈ 1.2);
    /// more than three usually means a longitude or a zone written with the wrong sign
    /// (Montevideo at longitude +56.2 with zone −3 gives 6.7), which a caller may warn of.
    pub fn meridian_offset_hours(&self) -> f64 {
        self.longitude / 15.0 - self.timezone
    }

    /// The compass of a scene whose up axis is `up` placed at this site.
    pub fn compass(&self, up: Vec3) -> Result<Compass, DaylightError> {
        Compass::new(up, self.north)
    }
}

/// North, east and up of a scene, as unit scene vectors forming a right-handed frame
/// (east × north = up), to turn horizontal coordinates into scene directions and back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Compass {
    up: DVec3,
    north: DVec3,
    east: DVec3,
}

impl Compass {
    /// The compass of a scene with up axis `up` (any non-zero vector) whose true north
    /// is turned `north` degrees clockwise, seen from above, from its default north.
    ///
    /// The default north is −Z projected on the horizontal plane, unless `up` lies
    /// closest to the Z axis (a Z-up scene), where it is +Y projected. For the axes a
    /// loader sets this gives −Z for Y-up and X-up files and +Y for Z-up ones; for a
    /// tilted `up` it is the nearest horizontal direction to that axis.
    pub fn new(up: Vec3, north: f64) -> Result<Compass, DaylightError> {
        let up = up.as_dvec3();
        if !up.is_finite() || up.length_squared() == 0.0 {
            return Err(DaylightError::OutOfRange {
                what: "up axis length",
                value: up.length(),
                range: "a finite non-zero vector",
            });
        }
        check(
            "north",
            north,
            f64::MIN,
            f64::MAX,
            "a finite angle in degrees",
        )?;
        let up = up.normalize();
        let a = up.abs();
        let reference = if a.z > a.x && a.z > a.y {
            DVec3::Y
        } else {
            DVec3::NEG_Z
        };
        let base = (reference - reference.dot(up) * up).normalize();
        // Clockwise seen from above is a negative turn about `up` (right-hand rule).
        let (sin, cos) = (-north.to_radians()).sin_cos();
        let north = (base * cos + up.cross(base) * sin).normalize();
        Ok(Compass {
            up,
            north,
            east: north.cross(up),
        })
    }

    /// Up (the zenith), unit.
    pub fn up(&self) -> Vec3 {
        self.up.as_vec3()
    }

    /// True north along the horizontal, unit.
    pub fn north(&self) -> Vec3 {
        self.north.as_vec3()
    }

    /// East along the horizontal, unit: north turned 90° clockwise seen from above.
    pub fn east(&self) -> Vec3 {
        self.east.as_vec3()
    }

    /// The unit scene vector pointing from the scene toward the point of the sky at
    /// `zenith` degrees from the zenith and `azimuth` degrees clockwise from north
    /// (90° east, 180° south): sin z (cos a · north + sin a · east) + cos z · up. Light
    /// from there travels along its negative.
    pub fn to_sky(&self, zenith: f64, azimuth: f64) -> Vec3 {
        let (sz, cz) = zenith.to_radians().sin_cos();
        let (sa, ca) = azimuth.to_radians().sin_cos();
        (sz * (ca * self.north + sa * self.east) + cz * self.up).as_vec3()
    }

    /// The (zenith, azimuth) of a scene direction pointing toward the sky, degrees; the
    /// azimuth in [0, 360), 0 straight up or down. `direction` need not be unit.
    pub fn angles(&self, direction: Vec3) -> (f64, f64) {
        let d = direction.as_dvec3().normalize();
        let zenith = d.dot(self.up).clamp(-1.0, 1.0).acos().to_degrees();
        let azimuth = d
            .dot(self.east)
            .atan2(d.dot(self.north))
            .to_degrees()
            .rem_euclid(360.0);
        (zenith, if azimuth >= 360.0 { 0.0 } else { azimuth })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-6
    }

    /// The conventions docs/daylight-compass.svg draws, axis by axis.
    #[test]
    fn default_north_and_east_of_each_up_axis() {
        let y = Compass::new(Vec3::Y, 0.0).unwrap();
        assert!(near(y.north(), Vec3::NEG_Z) && near(y.east(), Vec3::X) && near(y.up(), Vec3::Y));
        let z = Compass::new(Vec3::Z, 0.0).unwrap();
        assert!(near(z.north(), Vec3::Y) && near(z.east(), Vec3::X));
        // COLLADA X_UP: right −Y, so east is −Y; north stays −Z.
        let x = Compass::new(Vec3::X, 0.0).unwrap();
        assert!(near(x.north(), Vec3::NEG_Z) && near(x.east(), Vec3::NEG_Y));
        // An unnormalised up is normalised.
        assert_eq!(Compass::new(Vec3::Y * 3.0, 0.0).unwrap(), y);
    }

    #[test]
    fn north_turns_clockwise_seen_from_above() {
        // Y-up seen from +Y: −Z up the page, +X to the right. A quarter turn clockwise
        // brings north to the right (+X), east down the page (+Z).
        let c = Compass::new(Vec3::Y, 90.0).unwrap();
        assert!(near(c.north(), Vec3::X) && near(c.east(), Vec3::Z));
        let c = Compass::new(Vec3::Z, 90.0).unwrap();
        assert!(near(c.north(), Vec3::X) && near(c.east(), Vec3::NEG_Y));
        let c = Compass::new(Vec3::Z, -45.0).unwrap();
        let s = std::f32::consts::FRAC_1_SQRT_2;
        assert!(near(c.north(), Vec3::new(-s, s, 0.0)));
        assert_eq!(
            Compass::new(Vec3::Z, 360.0 + 30.0).unwrap().north(),
            Compass::new(Vec3::Z, 30.0).unwrap().north()
        );
    }

    #[test]
    fn horizontal_coordinates_to_scene_directions_and_back() {
        let c = Compass::new(Vec3::Y, 0.0).unwrap();
        assert!(near(c.to_sky(0.0, 123.0), Vec3::Y));
        assert!(near(c.to_sky(90.0, 0.0), Vec3::NEG_Z));
        assert!(near(c.to_sky(90.0, 90.0), Vec3::X));
        assert!(near(c.to_sky(90.0, 180.0), Vec3::Z));
        assert!(near(c.to_sky(90.0, 270.0), Vec3::NEG_X));
        // The SPA example's sun (zenith 50.11°, azimuth 194.34°: south-south-west).
        let d = c.to_sky(50.111622, 194.340241);
        let (s, z) = (
            50.111622f64.to_radians().sin(),
            50.111622f64.to_radians().cos(),
        );
        let a = 194.340241f64.to_radians();
        let expected = Vec3::new((s * a.sin()) as f32, z as f32, (-s * a.cos()) as f32);
        assert!(near(d, expected), "{d} {expected}");
        for &(up, north) in &[
            (Vec3::Y, 0.0),
            (Vec3::Z, 37.0),
            (Vec3::new(0.2, 0.1, 1.0), 200.0),
        ] {
            let c = Compass::new(up, north).unwrap();
            for &(zen, az) in &[(10.0, 0.5), (45.0, 90.0), (80.0, 181.0), (135.0, 359.0)] {
                let (z2, a2) = c.angles(c.to_sky(zen, az));
                assert!(
                    (z2 - zen).abs() < 1e-4 && (a2 - az).abs() < 1e-4,
                    "{zen} {az}: {z2} {a2}"
                );
            }
            assert!((c.east().cross(c.north()) - c.up()).length() < 1e-6);
        }
    }

    #[test]
    fn rejects_sites_off_the_globe() {
        assert!(Site::new(-34.9, -56.2, -3.0).is_ok());
        for (lat, lon, tz, what) in [
            (95.0, 0.0, 0.0, "latitude"),
            (0.0, 200.0, 0.0, "longitude"),
            (0.0, 0.0, 19.0, "timezone"),
            (f64::NAN, 0.0, 0.0, "latitude"),
        ] {
            match Site::new(lat, lon, tz) {
                Err(DaylightError::OutOfRange { what: w, .. }) => assert_eq!(w, what),
                other => panic!("{what}: {other:?}"),
            }
        }
        let s = Site::new(39.742476, -105.1786, -7.0).unwrap();
        assert!(s.with_elevation(1830.14).is_ok() && s.with_elevation(1e5).is_err());
        assert_eq!(s.with_north(-90.0).unwrap().north(), 270.0);
        assert!(s.with_north(f64::INFINITY).is_err());
        assert!(Compass::new(Vec3::ZERO, 0.0).is_err());
        assert!(
            (Site::new(-34.9, -56.2, -3.0)
                .unwrap()
                .meridian_offset_hours()
                + 0.747)
                .abs()
                < 1e-3
        );
        assert!(
            Site::new(-34.9, 56.2, -3.0)
                .unwrap()
                .meridian_offset_hours()
                > 6.0
        );
    }
}
