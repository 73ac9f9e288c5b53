//! Texture images (PNG, JPEG, BMP, TGA) decoded to linear RGB, shared by every loader.

use crate::error::LoadError;
use crate::material::Texture;
use glam::Vec3;
use std::path::Path;

/// Decodes an encoded image (file bytes) whose colours are sRGB, as base-colour
/// textures are in glTF, OBJ and COLLADA, into a linear texture. `path` names the image
/// in errors.
pub(crate) fn decode_texture(bytes: &[u8], path: &Path) -> Result<Texture, LoadError> {
    let img = image::load_from_memory(bytes)
        .map_err(|e| LoadError::new(path, format!("cannot decode the image: {e}")))?
        .to_rgb8();
    let lut: Vec<f32> = (0..256).map(|i| srgb_to_linear(i as f32 / 255.0)).collect();
    let pixels = img
        .pixels()
        .map(|p| Vec3::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]))
        .collect();
    Ok(Texture {
        width: img.width(),
        height: img.height(),
        pixels,
    })
}

/// Reads and decodes an image file.
pub(crate) fn read_texture(path: &Path) -> Result<Texture, LoadError> {
    let bytes = std::fs::read(path)
        .map_err(|e| LoadError::new(path, format!("cannot read the texture image: {e}")))?;
    decode_texture(&bytes, path)
}

/// The sRGB transfer function inverted (IEC 61966-2-1).
pub(crate) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}
