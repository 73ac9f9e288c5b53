//! Materials as photon tracing sees them (thesis Algorithm 2.2): a diffuse part K_d, a
//! perfect mirror part K_s, a refracting part with an index of refraction, and emission.

use crate::model::TextureId;
use glam::{Vec2, Vec3};

/// Linear RGB. Photometric when it carries light: its [`crate::luminance`] is the
/// photometric value (cd, lx, cd/m²).
pub type Rgb = Vec3;

/// A surface material.
///
/// The interaction probabilities of Russian roulette (thesis §2.6.1) follow from it:
/// ρ_d = mean(K_d), ρ_s = mean(K_s), and for glass the Fresnel split between reflection
/// and refraction. `K_d + K_s + transmission` is at most 1 per channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name in the source file, for messages and `invlight scene`.
    pub name: String,
    /// Lambertian reflectance K_d (base colour), multiplied by the texture when present.
    pub diffuse: Rgb,
    /// Base-colour texture, modulating `diffuse`.
    pub texture: Option<TextureId>,
    /// Perfect mirror reflectance K_s.
    pub specular: Rgb,
    /// Fraction of light that enters a dielectric (glass), split by Fresnel at the surface.
    pub transmission: f32,
    /// Index of refraction of the dielectric; only meaningful when `transmission > 0`.
    pub ior: f32,
    /// Emitted luminance in cd/m² (Lambertian, from the front face): the mesh is an area
    /// light when this is not zero.
    pub emission: Rgb,
    /// An aperture (ILPSolver: index of refraction < 1): rays pass through every surface
    /// where an object of this material lies, and the object itself is invisible.
    pub hole: bool,
}

impl Material {
    /// A grey-or-coloured Lambertian material.
    pub fn diffuse(name: &str, kd: Rgb) -> Self {
        Material {
            name: name.to_string(),
            diffuse: kd,
            texture: None,
            specular: Vec3::ZERO,
            transmission: 0.0,
            ior: 1.0,
            emission: Vec3::ZERO,
            hole: false,
        }
    }

    /// A perfect mirror with reflectance `ks`.
    pub fn mirror(name: &str, ks: Rgb) -> Self {
        Material {
            specular: ks,
            ..Material::diffuse(name, Vec3::ZERO)
        }
    }

    /// Clear glass with index of refraction `ior`.
    pub fn glass(name: &str, ior: f32) -> Self {
        Material {
            transmission: 1.0,
            ior,
            ..Material::diffuse(name, Vec3::ZERO)
        }
    }

    /// A Lambertian emitter of luminance `luminance` cd/m² (per channel) with black
    /// reflectance.
    pub fn emitter(name: &str, luminance: Rgb) -> Self {
        Material {
            emission: luminance,
            ..Material::diffuse(name, Vec3::ZERO)
        }
    }

    /// The aperture material of holes.
    pub fn hole(name: &str) -> Self {
        Material {
            hole: true,
            ..Material::diffuse(name, Vec3::ZERO)
        }
    }

    /// Whether this material emits light.
    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// A one-word description for listings: `hole`, `emitter`, `glass`, `mirror`,
    /// `diffuse`.
    pub fn kind_name(&self) -> &'static str {
        if self.hole {
            "hole"
        } else if self.is_emissive() {
            "emitter"
        } else if self.transmission > 0.0 {
            "glass"
        } else if self.specular.max_element() > 0.0 {
            "mirror"
        } else {
            "diffuse"
        }
    }
}

/// A base-colour texture in linear RGB, sampled with wrapping (glTF's default).
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major pixels, top row first, linear RGB.
    pub pixels: Vec<Rgb>,
}

impl Texture {
    /// The texel under `uv` (nearest, repeating; v = 0 is the top row as in glTF).
    pub fn sample(&self, uv: Vec2) -> Rgb {
        let u = uv.x - uv.x.floor();
        let v = uv.y - uv.y.floor();
        let x = ((u * self.width as f32) as u32).min(self.width - 1);
        let y = ((v * self.height as f32) as u32).min(self.height - 1);
        self.pixels[(y * self.width + x) as usize]
    }

    /// The mean colour, used where one reflectance stands for the whole texture.
    pub fn mean(&self) -> Rgb {
        self.pixels.iter().copied().sum::<Vec3>() / self.pixels.len().max(1) as f32
    }
}
