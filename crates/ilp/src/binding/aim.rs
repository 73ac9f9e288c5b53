//! `lightAim` (invlight): the aim of a spot or luminaire, within a cone about its
//! authored aim.

use super::Target;
use crate::problem::VariableSpec;
use crate::space::{Domain, Hemisphere};
use glam::{DVec3, Mat3, Quat, Vec3};
use invlight_scene::{Diagnostic, LightId, LightKind, Scene, known_names};

/// A `lightAim` of the spot or luminaire `spec.id` within `max_tilt` degrees of its
/// authored aim.
pub(super) fn variable(
    scene: &Scene,
    spec: &VariableSpec,
    max_tilt: f64,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    let aimed = |k: &LightKind| matches!(k, LightKind::Spot { .. } | LightKind::Goniometric { .. });
    let light = scene
        .light(&spec.id)
        .filter(|&l| aimed(&scene.lights[l].kind))
        .ok_or_else(|| {
            err(format!(
                "no spot or luminaire named '{}' in the scene, expected a light with an aim (a point light sends the same light every way; give it a file with --luminaire or <luminaire> first)",
                spec.id
            ))
            .with_hint(known_names(
                scene
                    .lights
                    .iter()
                    .filter(|l| aimed(&l.kind))
                    .map(|l| l.name.as_str()),
                "spots and luminaires",
            ))
        })?;
    let kind = &scene.lights[light].kind;
    let axis = kind.direction().unwrap_or(-scene.up);
    let frame = match kind {
        LightKind::Goniometric { frame, .. } => *frame,
        _ => Mat3::IDENTITY,
    };
    let cone = Hemisphere::cone(axis.as_dvec3(), max_tilt.to_radians());
    Ok((Domain::Hemisphere(cone), Target::Aim { light, axis, frame }))
}

/// Aims `light` along `d`, turned from its authored aim `axis` (and frame `authored`)
/// by the shortest rotation.
pub(super) fn apply(scene: &mut Scene, light: LightId, axis: Vec3, authored: &Mat3, d: DVec3) {
    // From the authored aim and frame each time, so turns never add up.
    let turn = Quat::from_rotation_arc(axis, d.as_vec3().normalize());
    let up = scene.up;
    match &mut scene.lights[light].kind {
        LightKind::Spot { direction, .. } => *direction = turn * axis,
        kind => kind.set_frame(Mat3::from_quat(turn) * *authored, up),
    }
}
