//! Variables that would undo each other, refused before the search: a lamp placed by
//! two of them, or a lamp whose frame two of them set.

use super::Target;
use crate::problem::{VariableKind, VariableSpec};
use invlight_scene::{Diagnostic, LightId, Scene};

/// Refuses a light that two variables place (a `<lightInSurface>` and a
/// `<lightArray>`, or two arrays): each would undo the other.
pub(super) fn placed_once(
    targets: &[Target],
    specs: &[VariableSpec],
    scene: &Scene,
    path: &std::path::Path,
) -> Result<(), Diagnostic> {
    let mut by: Vec<Option<usize>> = vec![None; scene.lights.len()];
    for (i, t) in targets.iter().enumerate() {
        let lights: Vec<LightId> = match t {
            Target::Move(m) => m.lights.iter().map(|&(l, _)| l).collect(),
            Target::Array(a) => a.lamps.iter().map(|&(l, _, _)| l).collect(),
            _ => continue,
        };
        for l in lights {
            if let Some(first) = by[l.index()].replace(i) {
                let (a, b) = (&specs[first], &specs[i]);
                return Err(Diagnostic::at_line(
                    path,
                    b.line,
                    format!(
                        "'{}' is placed by <{} id=\"{}\"> (line {}) and by <{} id=\"{}\">, expected one placement per lamp",
                        scene.lights[l].name,
                        a.kind.name(),
                        a.id,
                        a.line,
                        b.kind.name(),
                        b.id
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Refuses a lamp whose frame two variables would set: an `<objectRotation>` of a
/// lamp of an array that sets its lamps' frames itself (`orientation="search"`, from
/// the frames as loaded at every configuration, which would undo the rotation; a
/// continuous row, whose fittings must lie along its edge), and a `<lightAim>` of a
/// continuous row's lamps, which would tilt them out of line.
pub(super) fn framed_once(
    specs: &[VariableSpec],
    path: &std::path::Path,
) -> Result<(), Diagnostic> {
    for array in specs {
        let VariableKind::LightArray(a) = &array.kind else {
            continue;
        };
        if a.orientation.is_some() && !a.continuous {
            continue;
        }
        let what = if a.continuous {
            "lays its fittings end to end along an edge (continuous=\"true\")"
        } else {
            "sets its lamps' orientation at every configuration (orientation=\"search\")"
        };
        for other in specs {
            let ours = a.lights.contains(&other.id);
            let clash = match other.kind {
                VariableKind::ObjectRotation { .. } => ours,
                VariableKind::LightAim { .. } => a.continuous && (ours || other.id == array.id),
                _ => false,
            };
            if clash {
                return Err(Diagnostic::at_line(
                    path,
                    other.line,
                    format!(
                        "<{} id=\"{}\"> turns a lamp of <lightArray id=\"{}\"> (line {}), which {what}",
                        other.kind.name(),
                        other.id,
                        array.id,
                        array.line
                    ),
                )
                .with_hint("turn the array's fittings with its orientation (0, 90 or search), or take the lamp out of the array"));
            }
        }
    }
    Ok(())
}
