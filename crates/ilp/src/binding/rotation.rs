//! `objectRotation` (invlight): the turn of an object or luminaire about the normal of
//! the rectangle another variable places it on (the scene's up without one), through
//! its anchor — the box's centre, the light's position.

use super::Target;
use super::find_surface;
use super::placement::{authored, find_parallelogram};
use crate::problem::{Problem, VariableSpec};
use crate::space::Domain;
use glam::{Mat3, Vec3};
use invlight_scene::{Diagnostic, LightId, LightKind, Scene};

/// An `objectRotation` of `spec.id` from `min` to `max` degrees; a whole turn wraps.
pub(super) fn variable(
    problem: &Problem,
    scene: &Scene,
    spec: &VariableSpec,
    min: f64,
    max: f64,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    // The normal of the rectangle another variable places it on, else up.
    let placement = problem
        .variables
        .iter()
        .filter(|w| w.id == spec.id)
        .find_map(|w| w.kind.placement());
    let axis = match placement {
        Some(p) => {
            let r = find_parallelogram(scene, &p.surface, p.vertices, err)?;
            r.e1.cross(r.e2).normalize().as_vec3()
        }
        None => scene.up.normalize(),
    };
    let light = scene
        .light(&spec.id)
        .filter(|&l| !matches!(scene.lights[l].kind, LightKind::Directional { .. }));
    let (instances, light, centre) = match light {
        Some(l) => {
            let kind = scene.lights[l].kind.clone();
            let centre = kind.position().unwrap_or(Vec3::ZERO);
            (Vec::new(), Some((l, kind)), centre)
        }
        None => {
            let s = find_surface(scene, &spec.id, spec, err)?;
            let (instances, centre) = authored(scene, s);
            (instances, None, centre)
        }
    };
    // A whole turn's ends are one orientation: its neighbourhoods wrap.
    let domain = if (max - min - 360.0).abs() < 1e-9 {
        Domain::Turn { min, max }
    } else {
        Domain::Segment { min, max }
    };
    Ok((
        domain,
        Target::Rotate {
            instances,
            light,
            axis,
            centre,
        },
    ))
}

/// Turns `light` by `a` degrees about `axis` from its `authored` kind: a light turns
/// about an axis through itself, so its aim and frame turn.
pub(super) fn turn_light(
    scene: &mut Scene,
    light: LightId,
    authored: &LightKind,
    axis: Vec3,
    a: f64,
) {
    let turn = Mat3::from_axis_angle(axis, a.to_radians() as f32);
    let up = scene.up;
    match (&mut scene.lights[light].kind, authored) {
        (LightKind::Spot { direction, .. }, LightKind::Spot { direction: d0, .. }) => {
            *direction = turn * *d0
        }
        (kind, LightKind::Goniometric { frame: f0, .. }) => {
            kind.set_frame(turn * *f0, up);
        }
        _ => {}
    }
}
