//! The sun's variables: `directionalLight`, its direction over the hemisphere above the
//! scene, and `sunTime` (invlight), the time of day on a date at the problem's `<site>`,
//! whose sun stands where NREL's SPA puts it ([`SunClock`], docs/daylight.md).

use super::Target;
use crate::problem::{Problem, SunClock, VariableSpec};
use crate::space::{Domain, Hemisphere};
use invlight_scene::{Diagnostic, LightKind, Scene, known_names};

/// A `directionalLight`: the direction of the directional light `spec.id`.
pub(super) fn direction(
    scene: &Scene,
    spec: &VariableSpec,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    let light = scene
        .light(&spec.id)
        .filter(|&l| matches!(scene.lights[l].kind, LightKind::Directional { .. }))
        .ok_or_else(|| {
            err(format!(
                "no directional light named '{}' in the scene",
                spec.id
            ))
            .with_hint(known_names(
                scene
                    .lights
                    .iter()
                    .filter(|l| matches!(l.kind, LightKind::Directional { .. }))
                    .map(|l| l.name.as_str()),
                "directional lights",
            ))
        })?;
    let hemi = Hemisphere::new(scene.up.as_dvec3());
    Ok((Domain::Hemisphere(hemi), Target::Sun { light }))
}

/// A `sunTime` from `from` to `to` minutes after local midnight in steps of `step`: a
/// segment reaching half a step beyond either end, so that each step is a cell's
/// centre. Its sun is put at the range's middle ([`SunClock::place`]).
pub(super) fn time(
    problem: &Problem,
    spec: &VariableSpec,
    scene: &mut Scene,
    from: f64,
    to: f64,
    step: f64,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    if problem.daylight_factor_line().is_some() {
        return Err(err("<sunTime> in a daylight-factor problem: the factor is the overcast sky's light alone, with no sun".into())
            .with_hint("measure the sun's light in a problem of its own (<maximizeRadiance>)"));
    }
    let target =
        Target::SunTime(SunClock::place(problem, spec, scene).map_err(|e| err(e.to_string()))?);
    let half = step / 2.0;
    let domain = Domain::Segment {
        min: from - half,
        max: to + half,
    };
    Ok((domain, target))
}
