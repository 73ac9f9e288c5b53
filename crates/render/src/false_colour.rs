//! False-colour illuminance pictures (as Radiance's `falsecolor` and DIALux draw them):
//! every visible surface point coloured by its illuminance on a linear scale from 0 to
//! a maximum in lux, with the scale as a legend bar beside the picture.

use crate::draw;
use crate::integrator::IlluminanceImage;
use image::RgbImage;

/// The top of the scale when none is given: the 99th percentile of the illuminances
/// seen, rounded up to a round number, so that a few hot spots (under a lamp) do not
/// squeeze the rest of the picture into the bottom colours.
pub fn auto_max(lux: &[f32]) -> f64 {
    let mut seen: Vec<f32> = lux.iter().copied().filter(|v| v.is_finite()).collect();
    if seen.is_empty() {
        return 1.0;
    }
    let k = ((seen.len() - 1) as f64 * 0.99).round() as usize;
    let (_, v, _) = seen.select_nth_unstable_by(k, f32::total_cmp);
    draw::nice_ceil(*v as f64)
}

/// Text scale of legends for an image `height` pixels tall: 5×7 glyphs doubled from
/// 360 pixels on, so labels stay readable on large pictures.
pub fn text_scale(height: u32) -> u32 {
    (height / 360).clamp(1, 4)
}

/// The picture: each pixel the scale colour of its illuminance, shaded lightly by the
/// angle it is seen at so that shapes stay readable (75 % to 100 % brightness), black
/// where nothing is seen; the legend (from 0 to `max_lux`, in lx) is appended on the
/// right, so the result is wider than the render by [`draw::legend_width`].
pub fn false_colour(image: &IlluminanceImage, max_lux: f64) -> RgbImage {
    let scale = text_scale(image.height);
    let legend = draw::legend_width(scale);
    let mut out = RgbImage::new(image.width + legend, image.height);
    for y in 0..image.height {
        for x in 0..image.width {
            let i = (y * image.width + x) as usize;
            let e = image.lux[i];
            if !e.is_finite() {
                continue;
            }
            let c = draw::scale_colour((e as f64 / max_lux) as f32);
            let shade = 0.75 + 0.25 * image.facing[i].clamp(0.0, 1.0);
            out.put_pixel(x, y, image::Rgb(c.map(|v| (v as f32 * shade + 0.5) as u8)));
        }
    }
    draw::legend(
        &mut out,
        image.width as i32,
        0,
        image.height,
        max_lux,
        "lx",
        scale,
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legend_is_appended_and_colours_follow_the_scale() {
        let (w, h) = (40, 120);
        let lux: Vec<f32> = (0..w * h).map(|i| (i % w) as f32 * 10.0).collect();
        let img = IlluminanceImage {
            width: w,
            height: h,
            lux,
            facing: vec![1.0; (w * h) as usize],
        };
        let max = auto_max(&img.lux);
        // The 99th percentile, 390 lx, rounded up to a round 500.
        assert_eq!(max, 500.0);
        let out = false_colour(&img, max);
        assert_eq!(out.dimensions(), (w + draw::legend_width(1), h));
        assert_eq!(out.get_pixel(0, 5).0, draw::scale_colour(0.0));
        assert_eq!(out.get_pixel(25, 5).0, draw::scale_colour(0.5));
        // The legend bar at its bottom shows the colour of 0 lx, at its top that of max,
        // and its labels are white text on the dark panel.
        let bar_x = w + 4;
        let top = 4 + 7 + 4;
        let bottom = h - 4 - 3;
        assert_eq!(out.get_pixel(bar_x, bottom).0, draw::scale_colour(0.0));
        assert_eq!(out.get_pixel(bar_x, top).0, draw::scale_colour(1.0));
        let white = (w..w + draw::legend_width(1))
            .flat_map(|x| (0..h).map(move |y| (x, y)))
            .filter(|&(x, y)| out.get_pixel(x, y).0 == [255, 255, 255])
            .count();
        assert!(white > 100, "{white} white pixels of labels");
    }
}
