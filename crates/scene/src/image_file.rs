//! Texture images (PNG, JPEG, BMP, TGA) decoded to linear RGB, shared by every loader.

use crate::error::LoadError;
use crate::files::{Files, ReadError};
use crate::material::Texture;
use glam::Vec3;
use std::io::Cursor;
use std::path::Path;

/// Bytes a decoded texture takes per pixel while it is made: the decoder's image (up
/// to 16-bit RGBA, 8 bytes), its 8-bit RGB copy (3) and the linear `f32` texture (12).
const BYTES_PER_PIXEL: u64 = 8 + 3 + 12;

/// Why a texture was not made.
pub(crate) enum TextureError {
    /// It does not fit in the memory budget: the load must stop (a located error).
    Refused(LoadError),
    /// It cannot be read or decoded (an error naming the image): a loader may go on
    /// without the texture.
    Unreadable(LoadError),
}

/// Decodes an encoded image (file bytes) whose colours are sRGB, as base-colour
/// textures are in glTF, OBJ and COLLADA, into a linear texture. `path` names the image
/// in errors; `from` and `loc` name where it is referenced, for a refusal for memory.
///
/// The header is read first: a PNG that declares 13 000 × 13 000 pixels needs 3.9 GB
/// while it is decoded, and is charged to the budget (refused with that figure past
/// it) before the decoder allocates anything; the decoder is held to that figure.
pub(crate) fn decode_texture(
    bytes: &[u8],
    path: &Path,
    from: &Path,
    loc: &str,
    files: &Files,
) -> Result<Texture, TextureError> {
    let unreadable = |e: String| TextureError::Unreadable(LoadError::new(path, e));
    let reader = || {
        image::ImageReader::new(Cursor::new(bytes))
            .with_guessed_format()
            .map_err(|e| unreadable(format!("cannot read the image: {e}")))
    };
    let (w, h) = reader()?
        .into_dimensions()
        .map_err(|e| unreadable(format!("cannot decode the image: {e}")))?;
    let need = w as u64 * h as u64 * BYTES_PER_PIXEL;
    files
        .charge(
            from,
            loc,
            need,
            &format!("the {w} × {h} pixels of {}", path.display()),
        )
        .map_err(TextureError::Refused)?;
    let mut reader = reader()?;
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(need.max(1 << 20));
    reader.limits(limits);
    let img = reader
        .decode()
        .map_err(|e| unreadable(format!("cannot decode the image: {e}")))?
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

/// Reads and decodes an image file (resolved by [`Files::resolve`]); `from` and `loc`
/// name the referrer.
pub(crate) fn read_texture(
    path: &Path,
    from: &Path,
    loc: &str,
    files: &Files,
) -> Result<Texture, TextureError> {
    let bytes = files.read(from, loc, path, None).map_err(|e| match e {
        ReadError::Missing => TextureError::Unreadable(LoadError::new(
            path,
            "cannot read the texture image: no such file",
        )),
        ReadError::Io(m) => TextureError::Unreadable(LoadError::new(
            path,
            format!("cannot read the texture image: {m}"),
        )),
        ReadError::Budget(e) => TextureError::Refused(e),
    })?;
    decode_texture(&bytes, path, from, loc, files)
}

/// The sRGB transfer function inverted (IEC 61966-2-1).
pub(crate) fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}
