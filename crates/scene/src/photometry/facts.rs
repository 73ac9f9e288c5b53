//! The figures of a luminaire's datasheet, computed from its candela table: what a
//! designer checks before choosing a product (flux, watts, efficacy, beam and field
//! angles, the CIE flux code, the luminous opening).
//!
//! Definitions:
//! - beam angle: the full angle, in a plane through the luminaire's axis, between the
//!   two directions where the intensity falls to 50 % of the plane's maximum; field
//!   angle the same at 10 % (IES LM-63 and ANSI C78.379's reflector-lamp definitions,
//!   as datasheets print them for the C0–C180 and C90–C270 planes);
//! - CIE flux code (CIE 52:1982, the British Zonal method's cumulative zones): N1, N2,
//!   N3 the flux within 41.4°, 60° and 75.5° of nadir over the downward flux (the
//!   cones of π/2, π and 3π/2 sr), N4 the downward flux over the luminaire's, N5 the
//!   luminaire's flux over its lamps' (the light output ratio), each in percent;
//! - efficacy: the luminaire's flux over its input watts (EN 13032-4's luminaire
//!   efficacy, lm/W).

use super::{Opening, Photometry};
use glam::Vec3;
use serde::Serialize;

/// The datasheet of one photometric file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LuminaireFacts {
    /// The file's name.
    pub file: String,
    /// Its format and version.
    pub format: String,
    /// The manufacturer (IES `[MANUFAC]`, EULUMDAT's company line).
    pub manufacturer: Option<String>,
    /// The product's name or catalogue number (IES `[LUMINAIRE]`/`[LUMCAT]`,
    /// EULUMDAT's luminaire name and number).
    pub product: Option<String>,
    /// The luminaire's flux, lm: the integral of its candela table.
    pub flux: f64,
    /// The lamps' rated flux, lm, when the file states it (relative photometry).
    pub lamp_flux: Option<f64>,
    /// Input watts, when the file states them.
    pub watts: Option<f64>,
    /// Luminaire efficacy, lm/W.
    pub efficacy: Option<f64>,
    /// The largest intensity, cd.
    pub max_intensity: f64,
    /// Beam angle (50 %) in the C0–C180 and C90–C270 planes, degrees.
    pub beam_angle: [f64; 2],
    /// Field angle (10 %) in the same planes, degrees.
    pub field_angle: [f64; 2],
    /// CIE flux code N1…N5, percent.
    pub cie_flux_code: [f64; 5],
    /// The share of the flux sent downward (below the horizontal), 0..1.
    pub downward_fraction: f64,
    /// The luminous opening in words, with its axes in the luminaire's frame.
    pub opening: String,
    /// The luminous opening's extents along C0–C180 (local X) and C90–C270 (local Y),
    /// m; a disk's diameter twice; zeros for a point.
    pub opening_size: [f64; 2],
    /// The luminous opening's height (its sides), m.
    pub opening_height: f64,
    /// The luminaire's extents along C0–C180 and C90–C270 and its height, m, when the
    /// file gives them.
    pub luminaire_size: Option<[f64; 3]>,
    /// The luminaire in words, as `opening`, when the file gives its size.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub luminaire: Option<String>,
}

/// Steps of the quadratures over the sphere (polar, azimuthal): 0.25° × 1°, where the
/// table's bilinear cells are at most a few degrees wide; the flux code's zones land on
/// the cone boundaries to 0.25°.
const POLAR_STEPS: usize = 720;
const AZIMUTH_STEPS: usize = 360;

impl LuminaireFacts {
    /// The datasheet of `p`.
    pub fn of(p: &Photometry) -> LuminaireFacts {
        let zones = zone_fluxes(p, &[41.4, 60.0, 75.5, 90.0, 180.0]);
        let (down, total) = (zones[3], zones[4]);
        let share = |x: f64| if down > 0.0 { 100.0 * x / down } else { 0.0 };
        let lamp_flux = p.lumens_per_lamp.map(|l| l * f64::from(p.lamps));
        let flux = p.flux();
        let lor = match (p.light_output_ratio, lamp_flux) {
            (Some(lor), _) => 100.0 * lor,
            (None, Some(lamps)) if lamps > 0.0 => 100.0 * flux / lamps,
            _ => 100.0,
        };
        let plane = |c: f64, level: f64| spread(p, c, level);
        LuminaireFacts {
            file: p.file.clone(),
            format: p.format.name().to_string(),
            manufacturer: first_keyword(p, &["MANUFAC", "Company"]),
            product: product(p),
            flux,
            lamp_flux,
            watts: p.watts,
            efficacy: p.watts.filter(|&w| w > 0.0).map(|w| flux / w),
            max_intensity: p.max_intensity(),
            beam_angle: [plane(0.0, 0.5), plane(90.0, 0.5)],
            field_angle: [plane(0.0, 0.1), plane(90.0, 0.1)],
            cie_flux_code: [
                share(zones[0]),
                share(zones[1]),
                share(zones[2]),
                if total > 0.0 {
                    100.0 * down / total
                } else {
                    0.0
                },
                lor,
            ],
            downward_fraction: if total > 0.0 { down / total } else { 0.0 },
            opening: opening_words(&p.opening),
            opening_size: p.opening.extents().map(metres),
            opening_height: metres(p.opening_height),
            luminaire_size: p.luminaire.map(|(o, h)| {
                let [a, b] = o.extents();
                [a, b, h].map(metres)
            }),
            luminaire: p
                .luminaire
                .map(|(o, h)| format!("{}, {:.0} mm high", opening_words(&o), 1000.0 * h)),
        }
    }

    /// The CIE flux code as datasheets print it: five whole percents.
    pub fn flux_code(&self) -> String {
        self.cie_flux_code
            .iter()
            .map(|n| format!("{:.0}", n))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// A length the file stored in single precision, to the micrometre it can carry.
fn metres(x: f32) -> f64 {
    (f64::from(x) * 1e6).round() / 1e6
}

/// The first of `keys` the file has, trimmed, when not empty.
fn first_keyword(p: &Photometry, keys: &[&str]) -> Option<String> {
    keys.iter()
        .filter_map(|k| p.keyword(k))
        .map(|v| v.split_whitespace().collect::<Vec<_>>().join(" "))
        .find(|v| !v.is_empty())
}

/// The product's name and number, as the file gives them.
fn product(p: &Photometry) -> Option<String> {
    let name = first_keyword(p, &["LUMINAIRE", "Luminaire"]);
    let number = first_keyword(p, &["LUMCAT", "LuminaireNumber"]);
    match (name, number) {
        (Some(n), Some(c)) if n != c => Some(format!("{n} ({c})")),
        (Some(n), _) => Some(n),
        (None, c) => c,
    }
}

/// The opening and its axes in the luminaire's frame (C0 is local +X, C90 local +Y,
/// the photometric zero local −Z: see the module `photometry`).
fn opening_words(o: &Opening) -> String {
    o.words(|k| ["C0–C180 (local X)", "C90–C270 (local Y)"][k].to_string())
}

/// The flux within each polar angle of `limits` (degrees from nadir, increasing), lm:
/// the midpoint rule over the sphere on the steps above.
fn zone_fluxes(p: &Photometry, limits: &[f64]) -> Vec<f64> {
    let dg = std::f64::consts::PI / POLAR_STEPS as f64;
    let dc = std::f64::consts::TAU / AZIMUTH_STEPS as f64;
    let mut out = vec![0.0; limits.len()];
    let mut sum = 0.0;
    let mut zone = 0;
    for i in 0..POLAR_STEPS {
        let g = (i as f64 + 0.5) * dg;
        while zone < limits.len() && g.to_degrees() > limits[zone] {
            out[zone] = sum;
            zone += 1;
        }
        let ring: f64 = (0..AZIMUTH_STEPS)
            .map(|j| p.intensity_toward(toward(g, (j as f64 + 0.5) * dc)))
            .sum();
        sum += ring * g.sin() * dg * dc;
    }
    for o in &mut out[zone..] {
        *o = sum;
    }
    out
}

/// The unit local direction `g` from nadir in the plane of azimuth `c` (radians).
fn toward(g: f64, c: f64) -> Vec3 {
    Vec3::new(
        (g.sin() * c.cos()) as f32,
        (g.sin() * c.sin()) as f32,
        -g.cos() as f32,
    )
}

/// The full angle, degrees, in the vertical plane C`c`–C`c+180` between the outermost
/// directions where the intensity is `level` of the plane's peak: the spread of a
/// batwing's two lobes together, as datasheets give it; 0 for a plane that sends
/// nothing. The plane is walked in 0.1° steps from −180° (over the C`c+180` side) to
/// 180°, and each edge interpolated linearly.
fn spread(p: &Photometry, c: f64, level: f64) -> f64 {
    const STEP: f64 = 0.1;
    let n = (360.0 / STEP) as usize;
    let c = c.to_radians();
    let values: Vec<f64> = (0..=n)
        .map(|k| p.intensity_toward(toward((-180.0 + k as f64 * STEP).to_radians(), c)))
        .collect();
    let max = values.iter().copied().fold(0.0, f64::max);
    if max <= 0.0 {
        return 0.0;
    }
    let edge = max * level;
    let (Some(first), Some(last)) = (
        values.iter().position(|&v| v >= edge),
        values.iter().rposition(|&v| v >= edge),
    ) else {
        return 0.0;
    };
    // Between the sample below the edge and the one at or above it.
    let inside = |k: usize, outer: usize| -> f64 {
        let (a, b) = (values[outer], values[k]);
        let t = if b > a { (edge - a) / (b - a) } else { 1.0 };
        outer as f64 + t * (k as f64 - outer as f64)
    };
    let low = if first == 0 {
        0.0
    } else {
        inside(first, first - 1)
    };
    let high = if last == n {
        n as f64
    } else {
        inside(last, last + 1)
    };
    (high - low) * STEP
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::{PhotometricSystem, Photometry};

    /// A type C table, rotationally symmetric, of intensity `f(γ)` every degree.
    fn rotational(f: impl Fn(f64) -> f64) -> Photometry {
        let vertical: Vec<f64> = (0..=180).map(f64::from).collect();
        let plane: Vec<f64> = vertical.iter().map(|&g| f(g)).collect();
        let candela = [plane.clone(), plane].concat();
        Photometry::from_table(PhotometricSystem::C, vec![0.0, 360.0], vertical, candela).unwrap()
    }

    /// A Lambertian downlight, I = I₀ cos γ: flux π·I₀, beam angle 120° (cos 60° = ½),
    /// field angle 2·acos 0.1, and the flux code of sin²: N1 = sin² 41.4° = 0.438,
    /// N2 = 0.75, N3 = 0.9375 (the zonal cones of π/2, π, 3π/2 sr).
    #[test]
    fn a_lambertian_downlight_has_the_flux_code_and_angles_of_the_cosine() {
        let p = rotational(|g| {
            if g <= 90.0 {
                1000.0 * g.to_radians().cos()
            } else {
                0.0
            }
        });
        let f = LuminaireFacts::of(&p);
        assert!(
            (f.flux / (std::f64::consts::PI * 1000.0) - 1.0).abs() < 2e-3,
            "{}",
            f.flux
        );
        for b in f.beam_angle {
            assert!((b - 120.0).abs() < 0.2, "{b}");
        }
        let field = 2.0 * 0.1f64.acos().to_degrees();
        for b in f.field_angle {
            assert!((b - field).abs() < 0.3, "{b} vs {field}");
        }
        let s2 = |d: f64| 100.0 * d.to_radians().sin().powi(2);
        let code = f.cie_flux_code;
        for (n, expected) in [
            (code[0], s2(41.4)),
            (code[1], s2(60.0)),
            (code[2], s2(75.5)),
        ] {
            assert!((n - expected).abs() < 0.3, "{n} vs {expected}");
        }
        assert!((code[3] - 100.0).abs() < 1e-9 && (f.downward_fraction - 1.0).abs() < 1e-12);
        assert_eq!(f.flux_code(), "44 75 94 100 100");
    }

    /// An isotropic source: half its flux downward (N4 = 50), a spread that never falls
    /// to half (the whole plane, 360°).
    #[test]
    fn an_isotropic_source_sends_half_down_and_has_no_beam_edge() {
        let f = LuminaireFacts::of(&rotational(|_| 100.0));
        assert!(
            (f.cie_flux_code[3] - 50.0).abs() < 0.2,
            "{:?}",
            f.cie_flux_code
        );
        assert!((f.beam_angle[0] - 360.0).abs() < 1e-9);
        assert!((f.flux / (4.0 * std::f64::consts::PI * 100.0) - 1.0).abs() < 2e-3);
    }

    /// A batwing, I = 1000·(0.4 + 0.6·exp(−((γ − 35°)/15°)²)): its peaks at ±35° and
    /// 40 % on the axis, so the beam spans both lobes to their outer 50 % edges, at
    /// 35° + 15°·√ln 6 either side (0.6·e^(−x²) = 0.1), not one lobe's width.
    #[test]
    fn a_batwing_beam_spans_both_lobes() {
        let f = LuminaireFacts::of(&rotational(|g| {
            if g <= 90.0 {
                1000.0 * (0.4 + 0.6 * (-((g - 35.0) / 15.0).powi(2)).exp())
            } else {
                0.0
            }
        }));
        let expected = 2.0 * (35.0 + 15.0 * 6f64.ln().sqrt());
        assert!(
            (f.beam_angle[0] - expected).abs() < 0.1,
            "{:?} vs {expected}",
            f.beam_angle
        );
    }

    /// A narrow spot, I = I₀ for γ ≤ 10° falling linearly to 0 at 20°: the 50 % edge
    /// is at 15°, so the beam is 30°, and the 10 % edge at 19° (field 38°).
    #[test]
    fn a_spot_has_the_beam_of_its_half_intensity_edge() {
        let f = LuminaireFacts::of(&rotational(|g| {
            5000.0 * ((20.0 - g) / 10.0).clamp(0.0, 1.0)
        }));
        assert!((f.beam_angle[0] - 30.0).abs() < 0.05, "{:?}", f.beam_angle);
        assert!(
            (f.field_angle[1] - 38.0).abs() < 0.05,
            "{:?}",
            f.field_angle
        );
        assert_eq!(f.opening, "a point (no luminous dimensions)");
        assert_eq!(f.efficacy, None);
    }
}
