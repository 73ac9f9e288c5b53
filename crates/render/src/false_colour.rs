//! False-colour illuminance pictures (as Radiance's `falsecolor` and DIALux draw them):
//! every visible surface point coloured by its illuminance on the viridis scale
//! ([`crate::ColourScale`]), with the scale as a legend in lux beside the picture.

use crate::chart::{ChartError, colour_bar, draw_on};
use crate::colour_map::ColourScale;
use crate::integrator::IlluminanceImage;
use image::RgbImage;

/// The scale when none is given: from the smallest illuminance seen to the 99th
/// percentile, so that a few hot spots (under a lamp) do not squeeze the rest of the
/// picture into the bottom colours; brighter points take the top colour. `max` (lx),
/// when given, replaces the percentile.
pub fn auto_scale(lux: &[f32], max: Option<f64>) -> ColourScale {
    let mut seen: Vec<f32> = lux.iter().copied().filter(|v| v.is_finite()).collect();
    if seen.is_empty() {
        return ColourScale::new(0.0, max.unwrap_or(1.0));
    }
    let k = ((seen.len() - 1) as f64 * 0.99).round() as usize;
    let (_, p99, _) = seen.select_nth_unstable_by(k, f32::total_cmp);
    let p99 = *p99 as f64;
    let min = seen.iter().copied().fold(f32::INFINITY, f32::min) as f64;
    let top = max.unwrap_or(p99);
    ColourScale::new(min.min(top), top)
}

/// Width of the legend appended to a picture `height` pixels tall, pixels.
pub fn legend_width(height: u32) -> u32 {
    90 * legend_font(height) / 14
}

/// The legend's text size for a picture `height` pixels tall: readable on a 240-pixel
/// thumbnail and in proportion on a large render.
fn legend_font(height: u32) -> u32 {
    (height / 24).clamp(12, 40)
}

/// The picture: each pixel the scale colour of its illuminance, shaded lightly by the
/// angle it is seen at so that shapes stay readable (75 % to 100 % brightness), black
/// where nothing is seen; the legend (lx) is appended on the right, so the result is
/// wider than the render by [`legend_width`].
pub fn false_colour(image: &IlluminanceImage, scale: &ColourScale) -> Result<RgbImage, ChartError> {
    let legend = legend_width(image.height);
    let mut out = RgbImage::from_pixel(image.width + legend, image.height, image::Rgb([255; 3]));
    for y in 0..image.height {
        for x in 0..image.width {
            let i = (y * image.width + x) as usize;
            let e = image.lux[i];
            let c = if e.is_finite() {
                let shade = 0.75 + 0.25 * image.facing[i].clamp(0.0, 1.0);
                scale
                    .colour(e as f64)
                    .map(|v| (v as f32 * shade + 0.5) as u8)
            } else {
                [0; 3]
            };
            out.put_pixel(x, y, image::Rgb(c));
        }
    }
    let font = legend_font(image.height);
    draw_on(&mut out, |root| {
        let (_, bar) = root.split_horizontally(image.width);
        colour_bar(&bar, scale, "lx", font)
    })?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colour_map::viridis;

    #[test]
    fn legend_is_appended_and_colours_follow_the_scale() {
        let (w, h) = (40, 240);
        let lux: Vec<f32> = (0..w * h).map(|i| (i % w) as f32 * 10.0).collect();
        let img = IlluminanceImage {
            width: w,
            height: h,
            lux,
            facing: vec![1.0; (w * h) as usize],
        };
        let scale = auto_scale(&img.lux, None);
        // From the smallest value to the 99th percentile, 390 lx, not rounded beyond.
        assert_eq!((scale.min, scale.max), (0.0, 390.0));
        assert_eq!(auto_scale(&img.lux, Some(200.0)).max, 200.0);
        let out = false_colour(&img, &scale).unwrap();
        assert_eq!(out.dimensions(), (w + legend_width(h), h));
        assert_eq!(out.get_pixel(0, 5).0, viridis(0.0));
        assert_eq!(out.get_pixel(39, 5).0, viridis(1.0));
        // The legend's bar shows the scale's bottom colour low and its top colour high,
        // and its labels put dark text on the white panel.
        let column: Vec<[u8; 3]> = (0..h).map(|y| out.get_pixel(w + 6, y).0).collect();
        assert!(
            column.contains(&viridis(0.0))
                || column.iter().any(|c| c[2] > 70 && c[0] < 75 && c[1] < 10)
        );
        assert!(column.iter().any(|c| c[0] > 240 && c[1] > 220 && c[2] < 60));
        let dark = (w..out.width())
            .flat_map(|x| (0..h).map(move |y| (x, y)))
            .filter(|&(x, y)| out.get_pixel(x, y).0.iter().all(|&v| v < 80))
            .count();
        assert!(dark > 50, "{dark} dark pixels of labels");
    }
}
