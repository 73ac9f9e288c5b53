//! The colour variable's arithmetic: a material's K_d with fixed hue and saturation and
//! a free HSV value V (thesis §4.4.3).

/// The RGB of HSV (hue in degrees, saturation and value in [0, 1]) — the hexcone model
/// (A. R. Smith, "Color gamut transform pairs", SIGGRAPH 1978).
pub fn hsv_to_rgb(hue: f64, saturation: f64, value: f64) -> [f64; 3] {
    let h = hue.rem_euclid(360.0) / 60.0;
    let c = value * saturation;
    let x = c * (1.0 - (h % 2.0 - 1.0).abs());
    let (r, g, b) = match h as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = value - c;
    [r + m, g + m, b + m]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hsv_primaries() {
        assert_eq!(hsv_to_rgb(0.0, 1.0, 1.0), [1.0, 0.0, 0.0]);
        assert_eq!(hsv_to_rgb(240.0, 1.0, 0.5), [0.0, 0.0, 0.5]);
        assert_eq!(hsv_to_rgb(77.0, 0.0, 0.3), [0.3, 0.3, 0.3]);
        let [r, g, b] = hsv_to_rgb(39.0, 0.23, 1.0);
        assert!((r - 1.0).abs() < 1e-12 && (b - 0.77).abs() < 1e-12 && g > b && g < r);
    }
}
