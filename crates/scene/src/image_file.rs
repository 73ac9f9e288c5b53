//! Texture images (PNG, JPEG, BMP, TGA) decoded to linear RGB, shared by every loader.

use crate::error::LoadError;
use crate::files::{Files, ReadError};
use crate::material::Texture;
use glam::Vec3;
use image::ImageDecoder;
use std::io::Cursor;
use std::path::Path;

/// Bytes a decoded texture takes per pixel while it is made: the decoder's image (up
/// to 16-bit RGBA, 8 bytes), its 8-bit RGB copy (3) and the linear `f32` texture (12).
const BYTES_PER_PIXEL: u64 = 8 + 3 + 12;

/// Most bytes of pixel rows a PNG's zlib stream can inflate to per byte of it: deflate
/// (RFC 1951 §3.2.5) codes a 258-byte match, its longest, in no fewer than 2 bits (a
/// 1-bit length code and a 1-bit distance code), 1032:1.
const PNG_MOST_INFLATION: u64 = 1032;

/// Most pixels a baseline or progressive JPEG can code per byte: every 8 × 8 block of
/// its full-resolution component codes at least a DC difference, a Huffman code of 1 to
/// 16 bits (ITU-T T.81 §F.1.2.1, §G.1.2.1), so a byte covers at most 8 blocks of 64.
const JPEG_MOST_PIXELS_PER_BYTE: u64 = 512;

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
/// The header is read first. A PNG or JPEG whose header declares more pixels than its
/// bytes can code (a PNG of under 1 kB claiming 16 000 × 16 000, for which the decoder allocated
/// its 768 MB canvas before finding the data short) is unreadable, with both figures;
/// otherwise a PNG that declares 13 000 × 13 000 pixels needs 3.9 GB while it is
/// decoded, and is charged to the budget (refused with that figure past it) before the
/// decoder allocates anything; the decoder is held to that figure.
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
    let header = reader()?;
    let format = header.format();
    let decoder = header
        .into_decoder()
        .map_err(|e| unreadable(format!("cannot decode the image: {e}")))?;
    let (w, h) = decoder.dimensions();
    let bits = decoder.original_color_type().bits_per_pixel() as u64;
    if let Some(most) = most_coded(format, bytes.len() as u64, bits)
        && w as u64 * h as u64 > most
    {
        return Err(unreadable(format!(
            "its header declares {w} × {h} pixels, but its {} can hold at most {most} \
             pixels: the file is cut short or its header is wrong",
            crate::files::show_bytes(bytes.len() as u64)
        )));
    }
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

/// The most pixels of `bits` bits an encoded image of `len` bytes in `format` can
/// hold, for the formats whose coding bounds it (PNG, JPEG); `None` for the others,
/// which only the budget bounds.
fn most_coded(format: Option<image::ImageFormat>, len: u64, bits: u64) -> Option<u64> {
    match format? {
        image::ImageFormat::Png => Some(len * PNG_MOST_INFLATION * 8 / bits.max(1)),
        image::ImageFormat::Jpeg => Some(len * JPEG_MOST_PIXELS_PER_BYTE),
        _ => None,
    }
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
