//! The colour variable (`<color>`): a material's K_d with fixed hue and saturation and
//! a free HSV value V (thesis §4.4.3).

use super::{Target, surface_materials};
use crate::problem::VariableSpec;
use crate::space::Domain;
use invlight_scene::{Diagnostic, MaterialId, Scene, known_names};

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

/// A `color` of the materials `spec.id` (or the surface's), of hue and saturation
/// `hs` (degrees, 0–1) and value V from `range`'s first to its second; a base-colour
/// texture is dropped, with a warning.
pub(super) fn variable(
    scene: &mut Scene,
    spec: &VariableSpec,
    (hue, saturation): (f64, f64),
    (min, max): (f64, f64),
    err: &dyn Fn(String) -> Diagnostic,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(Domain, Target), Diagnostic> {
    let materials = colour_materials(scene, &spec.id).ok_or_else(|| {
        err(format!(
            "no material or surface named '{}' in the scene, expected the material (or the surface) whose colour varies",
            spec.id
        ))
        .with_hint(known_names(scene.materials.iter().map(|m| m.name.as_str()), "materials"))
    })?;
    // The problem states the colour (hue, saturation, free value); a
    // base-colour texture would multiply it into another one, and the
    // variable would no longer be the colour the file names.
    for &m in &materials {
        let material = &mut scene.materials[m];
        if material.texture.take().is_some() {
            warnings.push(err(format!(
                "material '{}' has a base-colour texture; the colour variable '{}' replaces it by the uniform colour HSV({hue}°, {saturation}, V)",
                material.name, spec.id
            )));
        }
    }
    Ok((
        Domain::Segment { min, max },
        Target::Colour {
            materials,
            hue,
            saturation,
        },
    ))
}

/// The materials a colour variable named `id` changes: those named `id`, else those of
/// the surface `id`; `None` when there are none.
fn colour_materials(scene: &Scene, id: &str) -> Option<Vec<MaterialId>> {
    let mut materials: Vec<MaterialId> = scene
        .materials
        .iter()
        .enumerate()
        .filter(|(_, m)| m.name == id)
        .map(|(i, _)| MaterialId::from_index(i))
        .collect();
    if materials.is_empty() {
        materials = scene
            .surface(id)
            .map(|s| surface_materials(scene, s))
            .unwrap_or_default();
    }
    (!materials.is_empty()).then_some(materials)
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
