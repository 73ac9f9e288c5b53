//! The colour scale of every false-colour picture and plot: viridis (van der Walt,
//! Smith and Firing, matplotlib 1.5, 2015), perceptually uniform in CAM02-UCS lightness
//! and readable in greyscale and with the common colour-vision deficiencies. The jet
//! rainbow it replaces has bands of sharp hue change (cyan, yellow) that read as edges
//! where the data has none, and its lightness is not monotonic, so a reader ranks its
//! colours wrongly (Borland & Taylor, "Rainbow color map (still) considered harmful",
//! IEEE CG&A 27(2), 2007; Crameri, Shephard & Heron, "The misuse of colour in science
//! communication", Nature Communications 11, 5444, 2020).
//!
//! [`ColourScale`] maps the data's own range onto the whole map: a scale rounded far
//! past the data (as the jet legends were, to the next "nice" number) spends colours on
//! values nothing has.

/// Viridis as 256 sRGB colours, from matplotlib's `_viridis_data` (BIDS/colormap,
/// colormaps.py, CC0), each channel rounded to 8 bits.
#[rustfmt::skip]
const VIRIDIS: [[u8; 3]; 256] = [
    [68, 1, 84], [68, 2, 86], [69, 4, 87], [69, 5, 89], [70, 7, 90], [70, 8, 92], [70, 10, 93], [70, 11, 94],
    [71, 13, 96], [71, 14, 97], [71, 16, 99], [71, 17, 100], [71, 19, 101], [72, 20, 103], [72, 22, 104], [72, 23, 105],
    [72, 24, 106], [72, 26, 108], [72, 27, 109], [72, 28, 110], [72, 29, 111], [72, 31, 112], [72, 32, 113], [72, 33, 115],
    [72, 35, 116], [72, 36, 117], [72, 37, 118], [72, 38, 119], [72, 40, 120], [72, 41, 121], [71, 42, 122], [71, 44, 122],
    [71, 45, 123], [71, 46, 124], [71, 47, 125], [70, 48, 126], [70, 50, 126], [70, 51, 127], [70, 52, 128], [69, 53, 129],
    [69, 55, 129], [69, 56, 130], [68, 57, 131], [68, 58, 131], [68, 59, 132], [67, 61, 132], [67, 62, 133], [66, 63, 133],
    [66, 64, 134], [66, 65, 134], [65, 66, 135], [65, 68, 135], [64, 69, 136], [64, 70, 136], [63, 71, 136], [63, 72, 137],
    [62, 73, 137], [62, 74, 137], [62, 76, 138], [61, 77, 138], [61, 78, 138], [60, 79, 138], [60, 80, 139], [59, 81, 139],
    [59, 82, 139], [58, 83, 139], [58, 84, 140], [57, 85, 140], [57, 86, 140], [56, 88, 140], [56, 89, 140], [55, 90, 140],
    [55, 91, 141], [54, 92, 141], [54, 93, 141], [53, 94, 141], [53, 95, 141], [52, 96, 141], [52, 97, 141], [51, 98, 141],
    [51, 99, 141], [50, 100, 142], [50, 101, 142], [49, 102, 142], [49, 103, 142], [49, 104, 142], [48, 105, 142], [48, 106, 142],
    [47, 107, 142], [47, 108, 142], [46, 109, 142], [46, 110, 142], [46, 111, 142], [45, 112, 142], [45, 113, 142], [44, 113, 142],
    [44, 114, 142], [44, 115, 142], [43, 116, 142], [43, 117, 142], [42, 118, 142], [42, 119, 142], [42, 120, 142], [41, 121, 142],
    [41, 122, 142], [41, 123, 142], [40, 124, 142], [40, 125, 142], [39, 126, 142], [39, 127, 142], [39, 128, 142], [38, 129, 142],
    [38, 130, 142], [38, 130, 142], [37, 131, 142], [37, 132, 142], [37, 133, 142], [36, 134, 142], [36, 135, 142], [35, 136, 142],
    [35, 137, 142], [35, 138, 141], [34, 139, 141], [34, 140, 141], [34, 141, 141], [33, 142, 141], [33, 143, 141], [33, 144, 141],
    [33, 145, 140], [32, 146, 140], [32, 146, 140], [32, 147, 140], [31, 148, 140], [31, 149, 139], [31, 150, 139], [31, 151, 139],
    [31, 152, 139], [31, 153, 138], [31, 154, 138], [30, 155, 138], [30, 156, 137], [30, 157, 137], [31, 158, 137], [31, 159, 136],
    [31, 160, 136], [31, 161, 136], [31, 161, 135], [31, 162, 135], [32, 163, 134], [32, 164, 134], [33, 165, 133], [33, 166, 133],
    [34, 167, 133], [34, 168, 132], [35, 169, 131], [36, 170, 131], [37, 171, 130], [37, 172, 130], [38, 173, 129], [39, 173, 129],
    [40, 174, 128], [41, 175, 127], [42, 176, 127], [44, 177, 126], [45, 178, 125], [46, 179, 124], [47, 180, 124], [49, 181, 123],
    [50, 182, 122], [52, 182, 121], [53, 183, 121], [55, 184, 120], [56, 185, 119], [58, 186, 118], [59, 187, 117], [61, 188, 116],
    [63, 188, 115], [64, 189, 114], [66, 190, 113], [68, 191, 112], [70, 192, 111], [72, 193, 110], [74, 193, 109], [76, 194, 108],
    [78, 195, 107], [80, 196, 106], [82, 197, 105], [84, 197, 104], [86, 198, 103], [88, 199, 101], [90, 200, 100], [92, 200, 99],
    [94, 201, 98], [96, 202, 96], [99, 203, 95], [101, 203, 94], [103, 204, 92], [105, 205, 91], [108, 205, 90], [110, 206, 88],
    [112, 207, 87], [115, 208, 86], [117, 208, 84], [119, 209, 83], [122, 209, 81], [124, 210, 80], [127, 211, 78], [129, 211, 77],
    [132, 212, 75], [134, 213, 73], [137, 213, 72], [139, 214, 70], [142, 214, 69], [144, 215, 67], [147, 215, 65], [149, 216, 64],
    [152, 216, 62], [155, 217, 60], [157, 217, 59], [160, 218, 57], [162, 218, 55], [165, 219, 54], [168, 219, 52], [170, 220, 50],
    [173, 220, 48], [176, 221, 47], [178, 221, 45], [181, 222, 43], [184, 222, 41], [186, 222, 40], [189, 223, 38], [192, 223, 37],
    [194, 223, 35], [197, 224, 33], [200, 224, 32], [202, 225, 31], [205, 225, 29], [208, 225, 28], [210, 226, 27], [213, 226, 26],
    [216, 226, 25], [218, 227, 25], [221, 227, 24], [223, 227, 24], [226, 228, 24], [229, 228, 25], [231, 228, 25], [234, 229, 26],
    [236, 229, 27], [239, 229, 28], [241, 229, 29], [244, 230, 30], [246, 230, 32], [248, 230, 33], [251, 231, 35], [253, 231, 37],];

/// The viridis colour of `t` ∈ [0, 1] (clamped; not-a-number is the bottom), linear
/// between the table's 256 entries.
pub fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * 255.0;
    let i = (x.floor() as usize).min(254);
    let f = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|k| (a[k] as f64 + (b[k] as f64 - a[k] as f64) * f).round() as u8)
}

/// A linear colour scale from `min` (the map's first colour) to `max` (its last).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColourScale {
    /// The value at the bottom of the scale.
    pub min: f64,
    /// The value at its top (greater than `min`).
    pub max: f64,
}

impl ColourScale {
    /// The scale from the smallest to the largest finite value of `values`, widened to a
    /// unit around a single value so that it has a length; [0, 1] when there is none.
    pub fn of(values: impl IntoIterator<Item = f64>) -> ColourScale {
        let (lo, hi) = values
            .into_iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        ColourScale::new(lo, hi)
    }

    /// The scale from `min` to `max`, as [`ColourScale::of`] widens it.
    pub fn new(min: f64, max: f64) -> ColourScale {
        if !(min.is_finite() && max.is_finite()) {
            return ColourScale { min: 0.0, max: 1.0 };
        }
        if max > min {
            return ColourScale { min, max };
        }
        let half = 0.5 * min.abs().max(1e-12);
        ColourScale {
            min: min - half,
            max: min + half,
        }
    }

    /// Where `value` falls on the scale, 0 at `min` and 1 at `max` (not clamped).
    pub fn fraction(&self, value: f64) -> f64 {
        (value - self.min) / (self.max - self.min)
    }

    /// The colour of `value`; values outside the scale take its end colours.
    pub fn colour(&self, value: f64) -> [u8; 3] {
        viridis(self.fraction(value))
    }

    /// Round values inside the scale for its labels: about `count` steps of 1, 2 or 5
    /// times a power of ten (Heckbert, "Nice numbers for graph labels", Graphics Gems,
    /// 1990), never outside [min, max].
    pub fn ticks(&self, count: usize) -> Vec<f64> {
        nice_ticks(self.min, self.max, count)
    }
}

/// Round values in [lo, hi], about `count` of them, as [`ColourScale::ticks`].
pub fn nice_ticks(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return vec![lo];
    }
    let raw = span / count.max(1) as f64;
    let p = 10f64.powf(raw.log10().floor());
    // Heckbert's rounding of the raw step to 1, 2, 5 or 10 times a power of ten.
    let f = raw / p;
    let m = match f {
        f if f < 1.5 => 1.0,
        f if f < 3.0 => 2.0,
        f if f < 7.0 => 5.0,
        _ => 10.0,
    };
    let step = m * p;
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    // i·m divided by an exact power of ten rounds once, so 0.6 is 0.6, not 3 × 0.2.
    let value = |i: i64| {
        if p < 1.0 {
            i as f64 * m / (1.0 / p).round()
        } else {
            i as f64 * step
        }
    };
    (first..=last).map(value).collect()
}

/// A tick value as a label with the decimals its step needs (at most 4), without "-0".
pub fn tick_label(value: f64, step: f64) -> String {
    let decimals = (0..4)
        .find(|&d| {
            let k = step.abs() * 10f64.powi(d);
            (k - k.round()).abs() < 1e-6 * k.max(1.0)
        })
        .unwrap_or(4) as usize;
    let s = format!("{value:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_runs_dark_purple_to_yellow_and_lightens_throughout() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        assert_eq!(viridis(-1.0), viridis(0.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        // Rec. 709 luma rises monotonically: the property jet lacks.
        let luma = |c: [u8; 3]| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64;
        let mut last = -1.0;
        for i in 0..=100 {
            let l = luma(viridis(i as f64 / 100.0));
            assert!(l > last, "luma falls at {i} %");
            last = l;
        }
    }

    #[test]
    fn the_scale_spans_the_data_and_its_ticks_stay_inside() {
        let s = ColourScale::of([212.0, 530.5, f64::NAN, 377.0]);
        assert_eq!((s.min, s.max), (212.0, 530.5));
        assert_eq!(s.colour(212.0), viridis(0.0));
        assert_eq!(s.colour(530.5), viridis(1.0));
        assert_eq!(s.ticks(5), vec![250.0, 300.0, 350.0, 400.0, 450.0, 500.0]);
        assert_eq!(nice_ticks(0.0, 1.0, 5), vec![0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
        let one = ColourScale::of([40.0]);
        assert!(one.min < 40.0 && one.max > 40.0);
        assert_eq!(tick_label(0.25, 0.05), "0.25");
        assert_eq!(tick_label(1500.0, 500.0), "1500");
        assert_eq!(tick_label(-0.0001, 0.1), "0.0");
    }
}
