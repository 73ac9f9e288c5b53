//! Drawing on 8-bit images: rectangles, lines, rings, text in an embedded 5×7 bitmap
//! font, the false-colour scale and its legend. Nothing here needs a font file or a
//! vector library: a legend needs digits, a few letters and a bar.

use image::{Rgb as Px, RgbImage};

/// Glyphs of the embedded font: 7 rows of 5 pixels, the high bit (16) the left column.
/// Drawn after the classic HD44780 5×7 character set.
const GLYPHS: &[(char, [u8; 7])] = &[
    ('0', [14, 17, 19, 21, 25, 17, 14]),
    ('1', [4, 12, 4, 4, 4, 4, 14]),
    ('2', [14, 17, 1, 2, 4, 8, 31]),
    ('3', [31, 2, 4, 2, 1, 17, 14]),
    ('4', [2, 6, 10, 18, 31, 2, 2]),
    ('5', [31, 16, 30, 1, 1, 17, 14]),
    ('6', [6, 8, 16, 30, 17, 17, 14]),
    ('7', [31, 1, 2, 4, 8, 8, 8]),
    ('8', [14, 17, 17, 14, 17, 17, 14]),
    ('9', [14, 17, 17, 15, 1, 2, 12]),
    ('.', [0, 0, 0, 0, 0, 12, 12]),
    (',', [0, 0, 0, 0, 12, 4, 8]),
    (':', [0, 12, 12, 0, 12, 12, 0]),
    ('-', [0, 0, 0, 31, 0, 0, 0]),
    ('+', [0, 4, 4, 31, 4, 4, 0]),
    ('=', [0, 0, 31, 0, 31, 0, 0]),
    ('/', [0, 1, 2, 4, 8, 16, 0]),
    ('(', [2, 4, 8, 8, 8, 4, 2]),
    (')', [8, 4, 2, 2, 2, 4, 8]),
    ('%', [24, 25, 2, 4, 8, 19, 3]),
    ('°', [12, 18, 18, 12, 0, 0, 0]),
    ('θ', [14, 17, 17, 31, 17, 17, 14]),
    ('φ', [4, 14, 21, 21, 21, 14, 4]),
    ('?', [14, 17, 1, 2, 4, 0, 4]),
    ('a', [0, 0, 14, 1, 15, 17, 15]),
    ('b', [16, 16, 22, 25, 17, 17, 30]),
    ('c', [0, 0, 14, 16, 16, 17, 14]),
    ('d', [1, 1, 13, 19, 17, 17, 15]),
    ('e', [0, 0, 14, 17, 31, 16, 14]),
    ('f', [6, 9, 8, 28, 8, 8, 8]),
    ('g', [0, 15, 17, 17, 15, 1, 14]),
    ('h', [16, 16, 22, 25, 17, 17, 17]),
    ('i', [4, 0, 12, 4, 4, 4, 14]),
    ('j', [2, 0, 6, 2, 2, 18, 12]),
    ('k', [16, 16, 18, 20, 24, 20, 18]),
    ('l', [12, 4, 4, 4, 4, 4, 14]),
    ('m', [0, 0, 26, 21, 21, 17, 17]),
    ('n', [0, 0, 22, 25, 17, 17, 17]),
    ('o', [0, 0, 14, 17, 17, 17, 14]),
    ('p', [0, 0, 30, 17, 30, 16, 16]),
    ('q', [0, 0, 13, 19, 15, 1, 1]),
    ('r', [0, 0, 22, 25, 16, 16, 16]),
    ('s', [0, 0, 14, 16, 14, 1, 30]),
    ('t', [8, 8, 28, 8, 8, 9, 6]),
    ('u', [0, 0, 17, 17, 17, 19, 13]),
    ('v', [0, 0, 17, 17, 17, 10, 4]),
    ('w', [0, 0, 17, 17, 21, 21, 10]),
    ('x', [0, 0, 17, 10, 4, 10, 17]),
    ('y', [0, 0, 17, 17, 15, 1, 14]),
    ('z', [0, 0, 31, 2, 4, 8, 31]),
    ('C', [14, 17, 16, 16, 16, 17, 14]),
    ('E', [31, 16, 16, 30, 16, 16, 31]),
    ('I', [14, 4, 4, 4, 4, 4, 14]),
    ('O', [14, 17, 17, 17, 17, 17, 14]),
    ('S', [15, 16, 16, 14, 1, 1, 30]),
    ('U', [17, 17, 17, 17, 17, 17, 14]),
    ('V', [17, 17, 17, 17, 17, 10, 4]),
];

/// The glyph of `c` (`?` for a character the font lacks, blank for a space).
fn glyph(c: char) -> [u8; 7] {
    if c == ' ' {
        return [0; 7];
    }
    GLYPHS
        .iter()
        .find(|g| g.0 == c)
        .or_else(|| GLYPHS.iter().find(|g| g.0 == '?'))
        .map(|g| g.1)
        .unwrap_or([0; 7])
}

/// Horizontal advance of one character at `scale`, pixels.
pub fn char_width(scale: u32) -> u32 {
    6 * scale
}

/// Width of `text` at `scale`, pixels.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * char_width(scale)
}

/// Height of a line of text at `scale`, pixels (the glyph, without spacing).
pub fn text_height(scale: u32) -> u32 {
    7 * scale
}

/// Writes `text` with its top-left corner at (x, y), each font pixel a `scale`×`scale`
/// block; whatever falls outside the image is clipped.
pub fn text(img: &mut RgbImage, x: i32, y: i32, text: &str, scale: u32, colour: [u8; 3]) {
    for (i, c) in text.chars().enumerate() {
        let g = glyph(c);
        let x0 = x + (i as u32 * char_width(scale)) as i32;
        for (row, bits) in g.iter().enumerate() {
            for col in 0..5 {
                if bits & (16 >> col) != 0 {
                    fill_rect(
                        img,
                        x0 + (col * scale) as i32,
                        y + (row as u32 * scale) as i32,
                        scale,
                        scale,
                        colour,
                    );
                }
            }
        }
    }
}

/// Fills a `w`×`h` rectangle at (x, y), clipped to the image.
pub fn fill_rect(img: &mut RgbImage, x: i32, y: i32, w: u32, h: u32, colour: [u8; 3]) {
    let x0 = x.max(0) as u32;
    let y0 = y.max(0) as u32;
    let x1 = ((x + w as i32).max(0) as u32).min(img.width());
    let y1 = ((y + h as i32).max(0) as u32).min(img.height());
    for yy in y0..y1 {
        for xx in x0..x1 {
            img.put_pixel(xx, yy, Px(colour));
        }
    }
}

/// Outlines a `w`×`h` rectangle at (x, y) one pixel wide.
pub fn stroke_rect(img: &mut RgbImage, x: i32, y: i32, w: u32, h: u32, colour: [u8; 3]) {
    fill_rect(img, x, y, w, 1, colour);
    fill_rect(img, x, y + h as i32 - 1, w, 1, colour);
    fill_rect(img, x, y, 1, h, colour);
    fill_rect(img, x + w as i32 - 1, y, 1, h, colour);
}

#[inline]
fn plot(img: &mut RgbImage, x: i32, y: i32, colour: [u8; 3]) {
    if x >= 0 && y >= 0 && (x as u32) < img.width() && (y as u32) < img.height() {
        img.put_pixel(x as u32, y as u32, Px(colour));
    }
}

/// A line from (x0, y0) to (x1, y1), `width` pixels wide (Bresenham, with a square pen).
pub fn line(
    img: &mut RgbImage,
    (x0, y0): (i32, i32),
    (x1, y1): (i32, i32),
    width: u32,
    colour: [u8; 3],
) {
    let (dx, dy) = ((x1 - x0).abs(), -(y1 - y0).abs());
    let (sx, sy) = (if x0 < x1 { 1 } else { -1 }, if y0 < y1 { 1 } else { -1 });
    let (mut x, mut y, mut err) = (x0, y0, dx + dy);
    let half = width as i32 / 2;
    loop {
        fill_rect(img, x - half, y - half, width.max(1), width.max(1), colour);
        if x == x1 && y == y1 {
            break;
        }
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
    }
}

/// A ring of radius `r` around (cx, cy), `width` pixels thick.
pub fn ring(img: &mut RgbImage, cx: i32, cy: i32, r: i32, width: i32, colour: [u8; 3]) {
    let (inner, outer) = ((r - width).max(0), r);
    for y in -outer..=outer {
        for x in -outer..=outer {
            let d2 = x * x + y * y;
            if d2 <= outer * outer && d2 >= inner * inner {
                plot(img, cx + x, cy + y, colour);
            }
        }
    }
}

/// A filled disc of radius `r` around (cx, cy).
pub fn disc(img: &mut RgbImage, cx: i32, cy: i32, r: i32, colour: [u8; 3]) {
    ring(img, cx, cy, r, r + 1, colour);
}

/// Stops of the false-colour scale, from 0 to 1: dark blue, blue, cyan, green, yellow,
/// red, dark red — the rainbow of Radiance's `falsecolor` and DIALux, kept because
/// lighting designers read it at a glance.
const SCALE: [(f32, [f32; 3]); 7] = [
    (0.0, [0.0, 0.0, 0.45]),
    (0.15, [0.0, 0.1, 1.0]),
    (0.35, [0.0, 0.9, 1.0]),
    (0.5, [0.1, 0.85, 0.1]),
    (0.65, [1.0, 0.95, 0.0]),
    (0.85, [1.0, 0.1, 0.0]),
    (1.0, [0.5, 0.0, 0.0]),
];

/// The colour of `t` ∈ [0, 1] on the false-colour scale (clamped outside).
pub fn scale_colour(t: f32) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let i = SCALE
        .iter()
        .position(|s| s.0 >= t)
        .unwrap_or(SCALE.len() - 1)
        .max(1);
    let (t0, c0) = SCALE[i - 1];
    let (t1, c1) = SCALE[i];
    let f = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
    [0, 1, 2].map(|k| ((c0[k] + (c1[k] - c0[k]) * f) * 255.0 + 0.5) as u8)
}

/// The smallest "nice" number (1, 2, 2.5 or 5 times a power of ten) ≥ `x` > 0, so a scale
/// ends on a round value.
pub fn nice_ceil(x: f64) -> f64 {
    if !(x > 0.0 && x.is_finite()) {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|&v| v >= x * (1.0 - 1e-9))
        .unwrap_or(10.0 * p)
}

/// Tick values for an axis from `lo` to `hi`: about `count` round steps.
pub fn ticks(lo: f64, hi: f64, count: u32) -> Vec<f64> {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return vec![lo];
    }
    let step = nice_ceil(span / count.max(1) as f64);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// A value as a short label with as many decimals as the tick step needs (at most 4).
pub fn label(value: f64, step: f64) -> String {
    let decimals = (0..4)
        .find(|&d| {
            let k = step * 10f64.powi(d);
            (k - k.round()).abs() < 1e-6 * k.abs().max(1.0)
        })
        .unwrap_or(4) as usize;
    let s = format!("{value:.decimals$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// Width of the legend panel (bar and labels) drawn beside pictures, pixels, at text
/// `scale`.
pub fn legend_width(scale: u32) -> u32 {
    24 * scale + text_width("00000", scale) + 6 * scale
}

/// Draws a vertical colour bar from 0 (bottom) to `max` (top) with labelled ticks and
/// `unit` above it, into the rectangle at (x, y) of height `h` on a dark background.
pub fn legend(img: &mut RgbImage, x: i32, y: i32, h: u32, max: f64, unit: &str, scale: u32) {
    let w = legend_width(scale);
    fill_rect(img, x, y, w, h, [24, 24, 24]);
    let pad = (4 * scale) as i32;
    let top = y + pad + text_height(scale) as i32 + pad;
    let bottom = y + h as i32 - pad - (text_height(scale) / 2) as i32;
    let bar_x = x + pad;
    let bar_w = 10 * scale;
    text(img, bar_x, y + pad, unit, scale, [255, 255, 255]);
    let span = (bottom - top).max(1);
    for row in top..=bottom {
        let t = (bottom - row) as f32 / span as f32;
        fill_rect(img, bar_x, row, bar_w, 1, scale_colour(t));
    }
    let ticks = ticks(0.0, max, 5);
    let step = if ticks.len() > 1 {
        ticks[1] - ticks[0]
    } else {
        max
    };
    for v in ticks {
        let row = bottom - ((v / max) * span as f64).round() as i32;
        fill_rect(
            img,
            bar_x + bar_w as i32,
            row,
            2 * scale,
            scale,
            [255, 255, 255],
        );
        // A clear gap after the tick, so that it does not read as a minus sign.
        text(
            img,
            bar_x + (bar_w + 6 * scale) as i32,
            row - (text_height(scale) / 2) as i32,
            &label(v, step),
            scale,
            [255, 255, 255],
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_numbers_and_ticks() {
        assert_eq!(nice_ceil(0.7), 1.0);
        assert_eq!(nice_ceil(1.2), 2.0);
        assert_eq!(nice_ceil(2.1), 2.5);
        assert_eq!(nice_ceil(430.0), 500.0);
        assert_eq!(
            ticks(0.0, 500.0, 5),
            vec![0.0, 100.0, 200.0, 300.0, 400.0, 500.0]
        );
        assert_eq!(label(0.25, 0.25), "0.25");
        assert_eq!(label(1500.0, 500.0), "1500");
        assert_eq!(label(0.5, 0.1), "0.5");
    }

    #[test]
    fn scale_runs_from_blue_to_red() {
        let lo = scale_colour(0.0);
        let mid = scale_colour(0.5);
        let hi = scale_colour(0.9);
        assert!(lo[2] > lo[0] && lo[2] > lo[1]);
        assert!(mid[1] > mid[0] && mid[1] > mid[2]);
        assert!(hi[0] > hi[1] && hi[0] > hi[2]);
        assert_eq!(scale_colour(2.0), scale_colour(1.0));
    }

    #[test]
    fn text_draws_the_glyph_bits() {
        let mut img = RgbImage::new(12, 7);
        text(&mut img, 0, 0, "1l", 1, [255, 255, 255]);
        // '1' row 0 is 00100: only column 2 lit; 'l' row 6 is 01110 from x = 6.
        let lit = |x, y| img.get_pixel(x, y).0 == [255, 255, 255];
        assert!(lit(2, 0) && !lit(1, 0) && !lit(3, 0));
        assert!(!lit(6, 6) && lit(7, 6) && lit(9, 6) && !lit(10, 6));
        // Every glyph has at most 5 columns and the characters are distinct.
        for (c, g) in GLYPHS {
            assert!(g.iter().all(|&r| r < 32), "{c}");
            assert_eq!(GLYPHS.iter().filter(|o| o.0 == *c).count(), 1, "{c}");
        }
    }
}
