//! From luminances to display pixels: exposure (automatic from the image's log-average
//! luminance, Reinhard et al. 2002, "Photographic Tone Reproduction for Digital
//! Images", eq. 1), a filmic curve (Narkowicz 2015, "ACES Filmic Tone Mapping Curve", a
//! fit of the ACES reference rendering transform) and the sRGB transfer function.

use crate::integrator::Image;
use image::RgbImage;
use invlight_scene::luminance;

/// How bright the image is made before the filmic curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Exposure {
    /// The log-average luminance of the image becomes middle grey (18 %).
    Auto,
    /// This luminance, cd/m², becomes middle grey: the same value keeps a series of
    /// images comparable.
    Luminance(f32),
}

/// A tone mapping: exposure plus a compensation in photographic stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToneMap {
    /// The exposure.
    pub exposure: Exposure,
    /// Stops added to the exposure (+1 doubles the brightness).
    pub compensation: f32,
}

impl Default for ToneMap {
    fn default() -> Self {
        ToneMap {
            exposure: Exposure::Auto,
            compensation: 0.0,
        }
    }
}

/// Middle grey, the key of Reinhard et al.
const KEY: f32 = 0.18;

/// The log-average (geometric mean) luminance of an image's lit pixels, cd/m²; `None`
/// for a black image. Pixels darker than a millionth of the brightest are left out so
/// that black background does not drag the exposure up.
pub fn log_average(image: &Image) -> Option<f32> {
    let max = image
        .pixels
        .iter()
        .map(|&p| luminance(p))
        .fold(0.0f32, f32::max);
    if !(max > 0.0 && max.is_finite()) {
        return None;
    }
    let floor = max * 1e-6;
    let (mut sum, mut n) = (0.0f64, 0u64);
    for &p in &image.pixels {
        let y = luminance(p);
        if y > floor && y.is_finite() {
            sum += (y as f64).ln();
            n += 1;
        }
    }
    (n > 0).then(|| (sum / n as f64).exp() as f32)
}

/// The ACES filmic fit of Narkowicz, input pre-scaled by 0.6 as there.
#[inline]
fn aces(x: f32) -> f32 {
    let x = x * 0.6;
    ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
#[inline]
pub fn srgb_encode(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Tone maps a linear image to 8-bit sRGB.
pub fn tone_map(image: &Image, tone: &ToneMap) -> RgbImage {
    let reference = match tone.exposure {
        Exposure::Auto => log_average(image).unwrap_or(1.0),
        Exposure::Luminance(l) => l,
    };
    let scale = KEY / reference.max(f32::MIN_POSITIVE) * tone.compensation.exp2();
    let mut out = RgbImage::new(image.width, image.height);
    for (px, &c) in out.pixels_mut().zip(&image.pixels) {
        let c = c * scale;
        px.0 = [c.x, c.y, c.z].map(|v| {
            let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
            (srgb_encode(aces(v)) * 255.0 + 0.5) as u8
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn filmic_curve_is_monotone_and_bounded() {
        let mut last = 0.0;
        for i in 0..1000 {
            let y = aces(i as f32 * 0.05);
            assert!(y >= last && y <= 1.0);
            last = y;
        }
        assert_eq!(aces(0.0), 0.0);
    }

    #[test]
    fn auto_exposure_ignores_the_scale_of_the_scene() {
        let image = |k: f32| Image {
            width: 2,
            height: 1,
            pixels: vec![Vec3::splat(k), Vec3::splat(4.0 * k)],
        };
        assert!((log_average(&image(1.0)).unwrap() - 2.0).abs() < 1e-5);
        let tone = ToneMap::default();
        assert_eq!(
            tone_map(&image(1.0), &tone),
            tone_map(&image(1000.0), &tone)
        );
    }
}
