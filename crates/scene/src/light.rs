//! Punctual and directional lights in photometric units (glTF KHR_lights_punctual),
//! goniometric luminaires from photometric files, and cameras. Area lights are not here:
//! they are the emissive triangles of the meshes.

use crate::material::Rgb;
use crate::photometry::Photometry;
use glam::{Mat3, Vec3};
use std::f32::consts::PI;
use std::sync::Arc;

/// Rec.709 luminance of a linear RGB value: the photometric scalar of a colour
/// (DESIGN.md §1).
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// A named light.
#[derive(Debug, Clone, PartialEq)]
pub struct Light {
    /// Node or light name, as a problem file's `lightInSurface`/`directionalLight` `id`.
    pub name: String,
    /// What kind of light, with its placement and strength.
    pub kind: LightKind,
    /// The world direction a photometric file's C0 plane takes when one is given to
    /// this point or spot light (`<luminaire>`, [`crate::Scene::set_photometry`]): the
    /// node's local +X (glTF, COLLADA), so that a luminaire turned with its node in the
    /// modeller is turned in the scene; +X where the file gives no frame.
    pub c0: Vec3,
}

/// The kinds of non-area light.
#[derive(Debug, Clone, PartialEq)]
pub enum LightKind {
    /// Isotropic point light of intensity `intensity` cd (per channel).
    Point {
        /// World position, m.
        position: Vec3,
        /// Luminous intensity, cd.
        intensity: Rgb,
    },
    /// Spot light: intensity `intensity` cd on its axis, full inside `inner` (half-angle,
    /// radians), falling smoothly to zero at `outer` as glTF recommends.
    Spot {
        /// World position, m.
        position: Vec3,
        /// Unit axis the light shines along.
        direction: Vec3,
        /// Luminous intensity on the axis, cd.
        intensity: Rgb,
        /// Inner cone half-angle, radians.
        inner: f32,
        /// Outer cone half-angle, radians.
        outer: f32,
    },
    /// Sun: parallel light travelling along `direction` with illuminance `illuminance` lx
    /// on a plane perpendicular to it.
    Directional {
        /// Unit vector the light travels along.
        direction: Vec3,
        /// Illuminance on a perpendicular plane, lx.
        illuminance: Rgb,
    },
    /// A luminaire described by a photometric file: intensity `multiplier ×` the table
    /// toward each direction, emitted from a point or from the table's luminous opening
    /// centred on `position` (glTF `EXT_lights_ies`).
    Goniometric {
        /// World position of the photometric centre, m.
        position: Vec3,
        /// Local → world rotation (orthonormal, right-handed): column 0 is the C0 axis
        /// (local +X), column 1 C90 (local +Y), column 2 the axis the luminaire is aimed
        /// away from, so that γ = 0 (local −Z) points along −column 2 (`EXT_lights_ies`
        /// "Coordinate System Mapping"; the photometry module doc).
        frame: Mat3,
        /// The candela table and its metadata.
        photometry: Arc<Photometry>,
        /// RGB factor on the table's candela (glTF `color × multiplier`, a problem
        /// file's `multiplier`, dimming): its luminance scales the flux and the watts.
        multiplier: Rgb,
        /// The IES tilt factor at the current aim ([`tilt_factor`]; 1 without tilt
        /// data), on the candela beside `multiplier`: kept apart so that a new aim
        /// recomputes it ([`LightKind::set_frame`]) and dimming, which sets the
        /// multiplier, leaves it — the lamp's light changes with its tilt, not what it draws.
        tilt: f32,
    },
}

/// The IES tilt factor ([`crate::Tilt`]) of a luminaire aimed along the unit `aim` in
/// a scene whose zenith is `up`: the factor at the angle between the aim and straight
/// down, in degrees (1 without tilt data). That angle is the lamp's tilt for geometry 1
/// (a vertical lamp), and the tilt in the plane the lamp is turned in for geometries 2
/// and 3, as the luminaire is turned about its lamp's perpendicular.
pub fn tilt_factor(photometry: &Photometry, aim: Vec3, up: Vec3) -> f32 {
    photometry.tilt.as_ref().map_or(1.0, |t| {
        let c = aim.normalize().dot(-up.normalize()).clamp(-1.0, 1.0);
        t.factor((c as f64).acos().to_degrees()) as f32
    })
}

/// A right-handed frame whose −Z is the unit `aim` and whose +X is `reference` made
/// perpendicular to it (or, when `reference` is nearly along `aim`, another axis): the
/// orientation a photometric table takes when only its aiming direction is known.
pub fn aimed_frame(aim: Vec3, reference: Vec3) -> Mat3 {
    let z = -aim.normalize();
    let mut x = reference - z * reference.dot(z);
    if x.length_squared() < 1e-6 * reference.length_squared().max(1e-30) {
        let other = if z.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
        x = other - z * other.dot(z);
    }
    let x = x.normalize();
    Mat3::from_cols(x, z.cross(x), z)
}

impl LightKind {
    /// The factor every one of its intensities (or a sun's illuminance) is: the point
    /// and spot's candela, the sun's lux, the goniometric light's multiplier on its
    /// table. Scaling it scales the light's output and flux alike (dimming).
    pub fn strength_mut(&mut self) -> &mut Rgb {
        match self {
            LightKind::Point { intensity, .. } | LightKind::Spot { intensity, .. } => intensity,
            LightKind::Directional { illuminance, .. } => illuminance,
            LightKind::Goniometric { multiplier, .. } => multiplier,
        }
    }

    /// Position of a point or spot light.
    pub fn position(&self) -> Option<Vec3> {
        match self {
            LightKind::Point { position, .. }
            | LightKind::Spot { position, .. }
            | LightKind::Goniometric { position, .. } => Some(*position),
            LightKind::Directional { .. } => None,
        }
    }

    /// The position of a point, spot or goniometric light, to move it.
    pub fn position_mut(&mut self) -> Option<&mut Vec3> {
        match self {
            LightKind::Point { position, .. }
            | LightKind::Spot { position, .. }
            | LightKind::Goniometric { position, .. } => Some(position),
            LightKind::Directional { .. } => None,
        }
    }

    /// Direction of a spot or directional light, or the aim (γ = 0) of a goniometric one.
    pub fn direction(&self) -> Option<Vec3> {
        match self {
            LightKind::Spot { direction, .. } | LightKind::Directional { direction, .. } => {
                Some(*direction)
            }
            LightKind::Goniometric { frame, .. } => Some(-frame.z_axis),
            LightKind::Point { .. } => None,
        }
    }

    /// The electrical power of a goniometric light whose file gives it, W, in a scene
    /// whose zenith is `up`: the file's input watts (IES LM-63 input watts; EULUMDAT's
    /// wattage including ballast) × the luminance of the light's multiplier without the
    /// IES tilt factor ([`tilt_factor`]), which changes the lamp's light and not what it
    /// draws. A multiplier of 2 is twice the light for twice the power, as two lamps
    /// would be; a light dimmed to a level draws that share. `None` for a file without
    /// watts and for every other kind of light.
    pub fn watts(&self) -> Option<f64> {
        let LightKind::Goniometric {
            photometry,
            multiplier,
            ..
        } = self
        else {
            return None;
        };
        Some(photometry.watts? * luminance(*multiplier) as f64)
    }

    /// Turns a goniometric light to the local → world rotation `to` in a scene whose
    /// zenith is `up`, with the tilt factor of its new aim (LM-63's TILT data are for
    /// the lamp's angle from straight down, which a new aim changes).
    pub fn set_frame(&mut self, to: Mat3, up: Vec3) {
        if let LightKind::Goniometric {
            frame,
            photometry,
            tilt,
            ..
        } = self
        {
            *frame = to;
            *tilt = tilt_factor(photometry, -to.z_axis, up);
        }
    }

    /// Turns a goniometric light by `degrees` about its aim (its local −Z), C0 toward
    /// C90: counter-clockwise seen from above for a luminaire aimed down, as a designer
    /// turns a fitting on its mounting (`<luminaire rotation>`). Other lights are
    /// unchanged.
    pub fn turn_about_aim(&mut self, degrees: f32) {
        if let LightKind::Goniometric { frame, .. } = self {
            *frame *= Mat3::from_rotation_z(degrees.to_radians());
        }
    }

    /// `point`, `spot`, `directional` or `goniometric`.
    pub fn name(&self) -> &'static str {
        match self {
            LightKind::Point { .. } => "point",
            LightKind::Spot { .. } => "spot",
            LightKind::Directional { .. } => "directional",
            LightKind::Goniometric { .. } => "goniometric",
        }
    }

    /// The RGB intensity, cd, that a point, spot or goniometric light sends along the
    /// unit world direction `w` (zero for a directional light, which has none).
    #[inline]
    pub fn intensity_toward(&self, w: Vec3) -> Rgb {
        match self {
            LightKind::Point { intensity, .. } => *intensity,
            LightKind::Spot {
                direction,
                intensity,
                inner,
                outer,
                ..
            } => *intensity * LightKind::spot_falloff(w.dot(direction.normalize()), *inner, *outer),
            LightKind::Goniometric {
                frame,
                photometry,
                multiplier,
                tilt,
                ..
            } => *multiplier * (*tilt * photometry.intensity_toward(frame.transpose() * w) as f32),
            LightKind::Directional { .. } => Vec3::ZERO,
        }
    }

    /// Fraction of the axis intensity a spot light sends at `cos_theta` from its axis
    /// (glTF's recommended smooth falloff: linear in cos between the cones, squared).
    pub fn spot_falloff(cos_theta: f32, inner: f32, outer: f32) -> f32 {
        let (ci, co) = (inner.cos(), outer.cos());
        if cos_theta >= ci {
            1.0
        } else if cos_theta <= co {
            0.0
        } else {
            let t = (cos_theta - co) / (ci - co).max(1e-12);
            t * t
        }
    }

    /// Emitted luminous flux in lm for point, spot and goniometric lights (RGB; for the
    /// last, the multiplier times the integral of its table, [`Photometry::flux`]). A directional light
    /// has no flux of its own; it is `illuminance × area` of whatever it falls on, so this
    /// returns its illuminance.
    ///
    /// Spot: ∫ I·f(θ) dω = 2π·I·(1 − cos inner) for the flat part and the falloff ring
    /// integrated in closed form: with c = cos θ, t = (c − c_o)/(c_i − c_o),
    /// ∫_{c_o}^{c_i} t² dc = (c_i − c_o)/3.
    pub fn flux(&self) -> Rgb {
        match self {
            LightKind::Point { intensity, .. } => *intensity * (4.0 * PI),
            LightKind::Spot {
                intensity,
                inner,
                outer,
                ..
            } => {
                // 1 − cos θ as 2 sin²(θ/2): in f32, 1 − cos θ is 0 below θ ≈ 3e-4 rad,
                // which gave a narrow spot no flux at all. The ring has the same trouble
                // (c_i − c_o = 2 sin((θ_o+θ_i)/2) sin((θ_o−θ_i)/2)).
                let flat = 2.0 * (inner * 0.5).sin().powi(2);
                let outer = outer.max(*inner);
                let ring = 2.0 * ((outer + inner) * 0.5).sin() * ((outer - inner) * 0.5).sin();
                *intensity * (2.0 * PI * (flat + ring / 3.0))
            }
            LightKind::Directional { illuminance, .. } => *illuminance,
            LightKind::Goniometric {
                photometry,
                multiplier,
                tilt,
                ..
            } => *multiplier * (*tilt * photometry.flux() as f32),
        }
    }
}

/// A perspective camera.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    /// Node or camera name.
    pub name: String,
    /// Eye position, m.
    pub position: Vec3,
    /// Unit viewing direction.
    pub forward: Vec3,
    /// Unit up vector, perpendicular to `forward`.
    pub up: Vec3,
    /// Vertical field of view, radians.
    pub yfov: f32,
    /// Width / height, when the file sets it.
    pub aspect: Option<f32>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A spot of a 1e-4 rad cone keeps its flux I·π·θ² (in f32, 1 − cos θ is 0 there).
    #[test]
    fn narrow_spot_keeps_its_flux() {
        let theta = 1e-4f32;
        let kind = LightKind::Spot {
            position: Vec3::ZERO,
            direction: Vec3::Z,
            intensity: Vec3::ONE,
            inner: theta,
            outer: theta,
        };
        let expected = PI * theta * theta;
        assert!(
            (kind.flux().x - expected).abs() < 1e-4 * expected,
            "{}",
            kind.flux().x
        );
    }

    #[test]
    fn spot_flux_matches_numeric_integral() {
        let (inner, outer) = (0.3f32, 0.7f32);
        let kind = LightKind::Spot {
            position: Vec3::ZERO,
            direction: Vec3::Z,
            intensity: Vec3::ONE,
            inner,
            outer,
        };
        let n = 200_000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let c = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            sum += LightKind::spot_falloff(c as f32, inner, outer) as f64 * 2.0 / n as f64;
        }
        let numeric = 2.0 * std::f64::consts::PI * sum;
        assert!((kind.flux().x as f64 - numeric).abs() < 1e-4 * numeric);
    }
}
