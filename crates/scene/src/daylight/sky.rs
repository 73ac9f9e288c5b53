//! CIE skies as luminance over the upper hemisphere of a scene, scaled so that an
//! unobstructed horizontal plane receives a given illuminance, and sampled over the dome
//! with the exact density of what is drawn: what a dome emitter needs to send photons
//! in from the sky and what a connection to a target needs to aim at it.
//!
//! **CIE standard overcast sky** (P. Moon, D. E. Spencer, "Illumination from a
//! non-uniform sky", Illuminating Engineering 37, 707–726, 1942; adopted by the CIE in
//! 1955): `L(Z) = L_z · (1 + 2 cos Z) / 3` at zenith angle Z, the same in every azimuth,
//! a third of the zenith's at the horizon. The unobstructed horizontal illuminance is
//! `E_h = ∫ L cos Z dω = 2π L_z/3 · ∫₀¹ (1 + 2μ) μ dμ = 7π/9 · L_z`.
//!
//! **CIE standard clear sky**: type 12 of the CIE standard general sky (ISO 15469:2004 /
//! CIE S 011/E:2003, "Spatial distribution of daylight — CIE standard general sky",
//! eqs. 1–5: "CIE standard clear sky, low luminance turbidity"), with the sun at zenith
//! angle Z_s and χ the angle between the sky point and the sun:
//! `L/L_z = f(χ) φ(Z) / (f(Z_s) φ(0))`,
//! gradation `φ(Z) = 1 + a·exp(b / cos Z)` (φ = 1 at the horizon), indicatrix
//! `f(χ) = 1 + c·(exp(dχ) − exp(dπ/2)) + e·cos²χ`, and a = −1, b = −0.32, c = 10,
//! d = −3, e = 0.45. It is the CIE's 1973 clear sky (CIE Publication 22; R. Kittler
//! 1967) `(0.91 + 10 e^{−3χ} + 0.45 cos²χ)(1 − e^{−0.32/cos Z})` with its 0.91 written
//! exactly as 1 − 10 e^{−3π/2} = 0.91012. The sun itself is not in it: it is the
//! directional light of [`super::SunPosition`]. L_z follows from `E_h` numerically,
//! once, when the sky is built (there is no closed form).
//!
//! **Sampling.** Directions are drawn with a density proportional to L per steradian,
//! the distribution of the light that crosses a disk held across each direction in
//! turn: photons entering a scene through a disk perpendicular to their direction that
//! covers its bounding sphere then all carry the same power, π r² ∫ L dω, whatever the
//! direction (pbrt-v4's `ImageInfiniteLight` does the same for environment maps). A
//! horizontal disk over the scene would favour high skies (density ∝ L·cos Z) but
//! misses the light of low skies, which enters a room through its windows. For the
//! overcast sky the density is analytic, `p(ω) = (1 + 2 cos Z) / (4π)` per steradian,
//! inverted in cos Z in closed form. For the clear sky the dome is mapped to the unit
//! square by (s, t) = (cos Z, azimuth / 2π), Archimedes' equal-area map, whose density is
//! 1 / 2π per steradian, and a piecewise-constant table of L over the square (pbrt-v4's
//! `PiecewiseConstant2D`) carries the rest: `p(ω) = p_table(s, t) / 2π`, exact for what
//! is drawn.

use super::DaylightError;
use glam::{DVec3, Vec3};
use invlight_stats::PiecewiseConstant2D;
use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

/// The CIE sky models.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SkyKind {
    /// The CIE standard overcast sky (Moon & Spencer 1942).
    CieOvercast,
    /// The CIE standard clear sky (ISO 15469 / CIE S 011 type 12).
    CieClear,
}

impl SkyKind {
    /// Every model, in the order the docs list them.
    pub const ALL: [SkyKind; 2] = [SkyKind::CieOvercast, SkyKind::CieClear];

    /// The name a problem file or flag gives: `cie-overcast`, `cie-clear`.
    pub fn name(self) -> &'static str {
        match self {
            SkyKind::CieOvercast => "cie-overcast",
            SkyKind::CieClear => "cie-clear",
        }
    }
}

impl fmt::Display for SkyKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SkyKind {
    type Err = DaylightError;

    fn from_str(s: &str) -> Result<SkyKind, DaylightError> {
        SkyKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| DaylightError::UnknownSky(s.to_string()))
    }
}

/// The gradation and indicatrix parameters a–e of ISO 15469's general sky.
#[derive(Debug, Clone, Copy, PartialEq)]
struct GeneralSky {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    e: f64,
}

/// Type 12, "CIE standard clear sky, low luminance turbidity" (ISO 15469:2004 table 1).
const CIE_CLEAR: GeneralSky = GeneralSky {
    a: -1.0,
    b: -0.32,
    c: 10.0,
    d: -3.0,
    e: 0.45,
};

impl GeneralSky {
    /// φ(Z) of cos Z = `mu` > 0; 1 at the horizon, where exp(b/μ) vanishes for b < 0.
    fn gradation(&self, mu: f64) -> f64 {
        1.0 + self.a * (self.b / mu).exp()
    }

    /// f(χ) of cos χ = `cos_chi`.
    fn indicatrix(&self, cos_chi: f64) -> f64 {
        let chi = cos_chi.clamp(-1.0, 1.0).acos();
        1.0 + self.c * ((self.d * chi).exp() - (self.d * PI / 2.0).exp())
            + self.e * cos_chi * cos_chi
    }
}

/// Rows (in cos Z) and columns (in azimuth) of the clear sky's sampling table: cells of
/// equal solid angle, 10° of zenith angle at the zenith, 0.9° at the horizon, and 2.8° of
/// azimuth, small against the circumsolar peak's e^{−3χ} (χ in radians: 19° to fall by e).
const ROWS: usize = 64;
const COLUMNS: usize = 128;
/// Points per cell side averaged for a cell's weight.
const SUBSAMPLES: usize = 2;
/// Zenith-angle × azimuth cells of the midpoint rule that integrates the clear sky for
/// its normalisation. In (Z, azimuth) the integrand L cos Z sin Z is smooth at the zenith
/// and the horizon alike (in sin² Z it is not, where a sun near the zenith made as many
/// points nearly ten times less accurate); the rule converges as
/// h², to 1.3·10⁻⁵ of E_h at this size for every sun checked against a 3000 × 12 000
/// reference.
const NORMALISATION_GRID: (usize, usize) = (256, 512);

/// A sky over a scene: luminance by direction, its horizontal illuminance and a
/// sampling distribution over the dome with its density.
#[derive(Debug, Clone, PartialEq)]
pub struct Sky {
    frame: Frame,
    model: Model,
    zenith_luminance: f64,
    horizontal_illuminance: f64,
    /// ∫ L dω over the dome, cd/m²·sr = lx.
    dome_luminance: f64,
}

#[derive(Debug, Clone, PartialEq)]
enum Model {
    Overcast,
    Clear(ClearSky, PiecewiseConstant2D),
}

/// The clear sky's sun: unit vector toward it and the denominator f(Z_s)·φ(0).
#[derive(Debug, Clone, Copy, PartialEq)]
struct ClearSky {
    sun: DVec3,
    norm: f64,
}

impl ClearSky {
    /// L / L_z toward unit `d` at cos Z = `mu` > 0.
    fn relative(&self, d: DVec3, mu: f64) -> f64 {
        CIE_CLEAR.indicatrix(d.dot(self.sun)) * CIE_CLEAR.gradation(mu) / self.norm
    }
}

/// The zenith and a tangent frame about it: local (x, y, z) = (·tangent, ·bitangent, ·up).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Frame {
    up: DVec3,
    tangent: DVec3,
    bitangent: DVec3,
}

impl Frame {
    fn new(up: DVec3) -> Frame {
        let (tangent, bitangent) = up.any_orthonormal_pair();
        Frame {
            up,
            tangent,
            bitangent,
        }
    }

    /// The unit vector at cos Z = `mu` and angle `phi` about the zenith.
    fn local(&self, mu: f64, phi: f64) -> DVec3 {
        let sin = (1.0 - mu * mu).max(0.0).sqrt();
        let (sp, cp) = phi.sin_cos();
        sin * (cp * self.tangent + sp * self.bitangent) + mu * self.up
    }

    /// Archimedes' equal-area map: (s, t) = (cos Z, φ / 2π) to a direction.
    fn square_to_direction(&self, s: f64, t: f64) -> DVec3 {
        self.local(s.clamp(0.0, 1.0), 2.0 * PI * t)
    }

    /// The inverse of [`Frame::square_to_direction`] for unit `d` above the horizon.
    fn direction_to_square(&self, d: DVec3) -> (f64, f64) {
        let (x, y) = (d.dot(self.tangent), d.dot(self.bitangent));
        let t = y.atan2(x) / (2.0 * PI);
        (d.dot(self.up).clamp(0.0, 1.0), t.rem_euclid(1.0))
    }
}

/// A direction drawn from a sky's sampling distribution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkySample {
    /// Unit scene vector from the scene toward the sky point; its light travels along
    /// the negative.
    pub to_sky: Vec3,
    /// Density of drawing it, per steradian ([`Sky::pdf`] of `to_sky`).
    pub pdf: f32,
    /// The sky's luminance there, cd/m² ([`Sky::luminance`] of `to_sky`).
    pub luminance: f32,
}

/// A finite non-zero vector, normalised, or an error naming it.
fn direction(v: Vec3, what: &'static str) -> Result<DVec3, DaylightError> {
    let v = v.as_dvec3();
    if !v.is_finite() || v.length_squared() == 0.0 {
        return Err(DaylightError::OutOfRange {
            what,
            value: v.length(),
            range: "a finite non-zero vector",
        });
    }
    Ok(v.normalize())
}

fn check_horizontal_lux(horizontal_lux: f64) -> Result<f64, DaylightError> {
    if horizontal_lux.is_finite() && horizontal_lux >= 0.0 {
        Ok(horizontal_lux)
    } else {
        Err(DaylightError::OutOfRange {
            what: "horizontal illuminance",
            value: horizontal_lux,
            range: "a finite illuminance ≥ 0 lx (10 000 lx is a typical overcast day)",
        })
    }
}

impl Sky {
    /// The CIE standard overcast sky over a scene with zenith `up`, giving an
    /// unobstructed horizontal plane `horizontal_lux` lx: L_z = 9 E_h / (7π).
    pub fn cie_overcast(up: Vec3, horizontal_lux: f64) -> Result<Sky, DaylightError> {
        let horizontal_lux = check_horizontal_lux(horizontal_lux)?;
        Ok(Sky {
            frame: Frame::new(direction(up, "up axis length")?),
            model: Model::Overcast,
            zenith_luminance: 9.0 * horizontal_lux / (7.0 * PI),
            horizontal_illuminance: horizontal_lux,
            // ∫ L_z (1 + 2μ)/3 dω = 2π L_z/3 · ∫₀¹ (1 + 2μ) dμ = 4π L_z/3 = 12/7 E_h.
            dome_luminance: 12.0 / 7.0 * horizontal_lux,
        })
    }

    /// The CIE standard clear sky over a scene with zenith `up`, the sun toward
    /// `to_sun` (at or above the horizon; [`super::SunPosition::to_sky`]), giving an
    /// unobstructed horizontal plane `horizontal_lux` lx. Builds the sampling table and
    /// integrates the luminance once (about 160 000 evaluations: under 10 ms).
    pub fn cie_clear(up: Vec3, to_sun: Vec3, horizontal_lux: f64) -> Result<Sky, DaylightError> {
        let horizontal_lux = check_horizontal_lux(horizontal_lux)?;
        let frame = Frame::new(direction(up, "up axis length")?);
        let sun = direction(to_sun, "sun direction length")?;
        let mu_sun = sun.dot(frame.up);
        if mu_sun < 0.0 {
            return Err(DaylightError::SunBelowHorizon {
                zenith: mu_sun.clamp(-1.0, 1.0).acos().to_degrees(),
            });
        }
        let clear = ClearSky {
            sun,
            norm: CIE_CLEAR.indicatrix(mu_sun) * CIE_CLEAR.gradation(1.0),
        };
        let relative = |d: DVec3| {
            let mu = d.dot(frame.up);
            if mu > 0.0 { clear.relative(d, mu) } else { 0.0 }
        };
        let n = SUBSAMPLES as f64;
        let weights: Vec<f64> = (0..ROWS * COLUMNS)
            .map(|cell| {
                let (i, j) = ((cell / COLUMNS) as f64, (cell % COLUMNS) as f64);
                let mut sum = 0.0;
                for a in 0..SUBSAMPLES {
                    for b in 0..SUBSAMPLES {
                        let s = (i + (a as f64 + 0.5) / n) / ROWS as f64;
                        let t = (j + (b as f64 + 0.5) / n) / COLUMNS as f64;
                        sum += relative(frame.square_to_direction(s, t));
                    }
                }
                sum / (n * n)
            })
            .collect();
        // E_h / L_z = ∫∫ (L/L_z) cos Z sin Z dZ dφ, and ∫ L dω / L_z without the cos Z.
        let (nz, nphi) = NORMALISATION_GRID;
        let (dz, dphi) = (PI / 2.0 / nz as f64, 2.0 * PI / nphi as f64);
        let (mut ratio, mut dome) = (0.0, 0.0);
        for i in 0..nz {
            let z = (i as f64 + 0.5) * dz;
            let ring: f64 = (0..nphi)
                .map(|j| relative(frame.local(z.cos(), (j as f64 + 0.5) * dphi)))
                .sum();
            ratio += ring * z.cos() * z.sin();
            dome += ring * z.sin();
        }
        let zenith_luminance = horizontal_lux / (ratio * dz * dphi);
        Ok(Sky {
            frame,
            model: Model::Clear(clear, square_table(&weights)),
            zenith_luminance,
            horizontal_illuminance: horizontal_lux,
            dome_luminance: zenith_luminance * dome * dz * dphi,
        })
    }

    /// Which model.
    pub fn kind(&self) -> SkyKind {
        match self.model {
            Model::Overcast => SkyKind::CieOvercast,
            Model::Clear(..) => SkyKind::CieClear,
        }
    }

    /// The zenith (the scene's up axis), unit.
    pub fn up(&self) -> Vec3 {
        self.frame.up.as_vec3()
    }

    /// Unit vector toward the sun of a clear sky.
    pub fn sun(&self) -> Option<Vec3> {
        match &self.model {
            Model::Overcast => None,
            Model::Clear(clear, _) => Some(clear.sun.as_vec3()),
        }
    }

    /// Luminance at the zenith L_z, cd/m².
    pub fn zenith_luminance(&self) -> f64 {
        self.zenith_luminance
    }

    /// Illuminance the sky gives an unobstructed horizontal plane, lx (the
    /// `horizontalLux` it was built with).
    pub fn horizontal_illuminance(&self) -> f64 {
        self.horizontal_illuminance
    }

    /// The sky's luminance integrated over the dome, ∫ L dω, lx: the illuminance a disk
    /// held across each direction in turn gathers from it, so that π r² times it is the
    /// luminous flux the sky sends into a sphere of radius r.
    pub fn dome_luminance(&self) -> f64 {
        self.dome_luminance
    }

    /// Luminance seen looking along `to_sky` (need not be unit), cd/m²; 0 at and
    /// below the horizon.
    pub fn luminance(&self, to_sky: Vec3) -> f32 {
        let d = to_sky.as_dvec3().normalize_or_zero();
        let mu = d.dot(self.frame.up);
        if mu <= 0.0 {
            return 0.0;
        }
        let relative = match &self.model {
            Model::Overcast => (1.0 + 2.0 * mu) / 3.0,
            Model::Clear(clear, _) => clear.relative(d, mu),
        };
        (self.zenith_luminance * relative) as f32
    }

    /// Density per steradian of [`Sky::sample`] drawing `to_sky` (need not be unit);
    /// 0 at and below the horizon.
    pub fn pdf(&self, to_sky: Vec3) -> f32 {
        let d = to_sky.as_dvec3().normalize_or_zero();
        let mu = d.dot(self.frame.up);
        if mu <= 0.0 {
            return 0.0;
        }
        (match &self.model {
            Model::Overcast => overcast_pdf(mu),
            Model::Clear(_, table) => {
                let (s, t) = self.frame.direction_to_square(d);
                table.pdf(s, t) / (2.0 * PI)
            }
        }) as f32
    }

    /// A direction toward the sky for uniform `u1`, `u2` in [0, 1), drawn with density
    /// ∝ L per steradian, with its density and luminance. Both are those [`Sky::pdf`] and
    /// [`Sky::luminance`] give the returned vector, so that they agree exactly even where
    /// rounding to `f32` moves a direction across the edge of a table cell (a sliver of
    /// the dome some 10⁻⁷ wide, where the density is that of the neighbouring cell).
    pub fn sample(&self, u1: f32, u2: f32) -> SkySample {
        let d = self.sample_direction(u1 as f64, u2 as f64);
        debug_assert!(d.is_finite() && d.dot(self.frame.up) >= 0.0);
        let to_sky = d.as_vec3();
        SkySample {
            to_sky,
            pdf: self.pdf(to_sky),
            luminance: self.luminance(to_sky),
        }
    }

    /// The unit direction drawn for (u1, u2): by inverting the overcast sky's CDF in
    /// cos Z (azimuth uniform), or through the table and Archimedes' map.
    fn sample_direction(&self, u1: f64, u2: f64) -> DVec3 {
        match &self.model {
            Model::Overcast => self.frame.local(overcast_cos_zenith(u1), 2.0 * PI * u2),
            Model::Clear(_, table) => {
                let d = table.sample([u1, u2]);
                self.frame.square_to_direction(d.x, d.y)
            }
        }
    }
}

/// The overcast sky's sampling density per steradian, (1 + 2μ)/(4π): L over ∫ L dω.
fn overcast_pdf(mu: f64) -> f64 {
    (1.0 + 2.0 * mu) / (4.0 * PI)
}

/// The cos Z at which the overcast sky's CDF over cos Z, F(μ) = (μ + μ²)/2 (the density
/// above integrated over azimuth and from the horizon), reaches `u`: the root of the
/// quadratic, written as 2u / (1/2 + √(1/4 + 2u)) so that it keeps its digits near 0.
fn overcast_cos_zenith(u: f64) -> f64 {
    let u = u.clamp(0.0, 1.0);
    (2.0 * u / (0.5 + (0.25 + 2.0 * u).sqrt())).clamp(0.0, 1.0)
}

/// The clear sky's table over Archimedes' square: `weights` row by row (row i of
/// [`ROWS`] in s, column j of [`COLUMNS`] in t), every cell of the same area, so a
/// cell's mass is its weight.
fn square_table(weights: &[f64]) -> PiecewiseConstant2D {
    let axis = |n: usize| (0..=n).map(|k| k as f64 / n as f64).collect::<Vec<_>>();
    PiecewiseConstant2D::new(axis(ROWS), axis(COLUMNS), weights)
        .expect("the clear sky's weights are positive and finite")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overcast_inversion_reaches_its_cdf() {
        for k in 0..=1000 {
            let u = k as f64 / 1000.0;
            let mu = overcast_cos_zenith(u);
            let f = (mu + mu * mu) / 2.0;
            assert!((f - u).abs() < 1e-12, "{u}: F({mu}) = {f}");
        }
        assert_eq!(overcast_cos_zenith(0.0), 0.0);
        assert_eq!(overcast_cos_zenith(1.0), 1.0);
    }

    /// Archimedes' map and its inverse undo each other, and what the table draws has the
    /// density it reports at the point drawn (in f64, where no rounding moves a point
    /// across a cell edge).
    #[test]
    fn square_map_round_trips_and_table_density_is_the_drawn_one() {
        let sky = Sky::cie_clear(Vec3::new(0.3, 1.0, -0.2), Vec3::new(1.0, 0.4, 0.0), 1.0).unwrap();
        let Model::Clear(_, table) = &sky.model else {
            unreachable!()
        };
        for i in 0..97 {
            for j in 0..101 {
                let (u1, u2) = ((i as f64 + 0.31) / 97.0, (j as f64 + 0.77) / 101.0);
                let d = table.sample([u1, u2]);
                let (s, t, p) = (d.x, d.y, d.pdf);
                let (s2, t2) = sky
                    .frame
                    .direction_to_square(sky.frame.square_to_direction(s, t));
                assert!(
                    (s2 - s).abs() < 1e-12 && (t2 - t).abs() < 1e-12,
                    "{s} {t}: {s2} {t2}"
                );
                assert_eq!(p, table.pdf(s, t));
                let d = sky.sample_direction(u1, u2);
                assert!((sky.pdf(d.as_vec3()) as f64 - p / (2.0 * PI)).abs() < 1e-5 * p);
            }
        }
    }
}
