//! `lightAim` (invlight): the aim of a spot or luminaire, or of a `<lightGroup>`'s
//! lamps as one, within a cone about its authored aim.

use super::Target;
use super::power::group_lights;
use crate::problem::{LightGroup, VariableSpec};
use crate::space::{Domain, Hemisphere};
use glam::{DVec3, Mat3, Quat, Vec3};
use invlight_scene::{Diagnostic, LightId, LightKind, Scene, known_names};

/// A `lightAim` of the spot or luminaire `spec.id`, or of the lamps of the group of
/// that id, within `max_tilt` degrees of its authored aim (a group's first lamp's).
pub(super) fn variable(
    scene: &Scene,
    spec: &VariableSpec,
    max_tilt: f64,
    groups: &[LightGroup],
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    let aimed = |k: &LightKind| matches!(k, LightKind::Spot { .. } | LightKind::Goniometric { .. });
    let lights = match groups.iter().find(|g| g.id == spec.id) {
        Some(group) => {
            let lights = group_lights(scene, group, err)?;
            if let Some(&l) = lights.iter().find(|&&l| !aimed(&scene.lights[l].kind)) {
                return Err(err(format!(
                    "'{}' of <lightGroup id=\"{}\"> has no aim, expected spots or luminaires (give it a file with --luminaire or <luminaire> first)",
                    scene.lights[l].name, group.id
                )));
            }
            lights
        }
        None => vec![
            scene
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
                })?,
        ],
    };
    let lights: Vec<(LightId, Vec3, Mat3)> = lights
        .into_iter()
        .map(|light| {
            let kind = &scene.lights[light].kind;
            let axis = kind.direction().unwrap_or(-scene.up);
            let frame = match kind {
                LightKind::Goniometric { frame, .. } => *frame,
                _ => Mat3::IDENTITY,
            };
            (light, axis, frame)
        })
        .collect();
    let cone = Hemisphere::cone(lights[0].1.as_dvec3(), max_tilt.to_radians());
    Ok((Domain::Hemisphere(cone), Target::Aim { lights }))
}

/// Aims `lights` along `d`: each turned from its authored aim and frame by the
/// shortest rotation that takes the first one's authored aim onto `d`, so a group
/// turns as one.
pub(super) fn apply(scene: &mut Scene, lights: &[(LightId, Vec3, Mat3)], d: DVec3) {
    let Some(&(_, first, _)) = lights.first() else {
        return;
    };
    // From the authored aims and frames each time, so turns never add up.
    let turn = Quat::from_rotation_arc(first, d.as_vec3().normalize());
    let up = scene.up;
    for &(light, axis, authored) in lights {
        match &mut scene.lights[light].kind {
            LightKind::Spot { direction, .. } => *direction = turn * axis,
            kind => kind.set_frame(Mat3::from_quat(turn) * authored, up),
        }
    }
}
