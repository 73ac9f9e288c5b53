//! Which placement variables the search may take as one: identical lamps on one
//! rectangle, whose values swapped light the scene alike
//! ([`crate::Space::with_exchangeable`]).

use super::{Dimmed, Target};
use crate::problem::{VariableKind, VariableSpec};
use glam::Vec3;
use invlight_scene::{LightId, LightKind, Scene};

/// The groups of placement variables that are interchangeable: `lightInSurface`
/// variables of identical lights (the same kind and output, wherever they are) on the
/// same rectangle with the same anchor, each with its `lightPower` variable if it has
/// one (of the same range). Swapping two members' values gives the same lit scene, so
/// the search takes such configurations as one ([`crate::Space::with_exchangeable`]). Each
/// group is a list of members, each member its variables' indices.
pub(super) fn exchangeable(
    scene: &Scene,
    specs: &[VariableSpec],
    targets: &[Target],
) -> Vec<Vec<Vec<usize>>> {
    let power_of = |light: LightId| {
        targets.iter().position(|t| {
            matches!(t, Target::Power { dimmed: Dimmed::Light { light: l, .. }, .. } if *l == light)
        })
    };
    // The group dimming and the group aim a lamp shares with others, if any.
    let shared = |light: LightId| {
        let dimming = targets.iter().position(|t| match t {
            Target::Power {
                dimmed: Dimmed::Group(g),
                ..
            } => g.iter().any(|(l, _)| *l == light),
            _ => false,
        });
        let aim = targets.iter().position(|t| match t {
            Target::Aim { lights } => lights.len() > 1 && lights.iter().any(|(l, ..)| *l == light),
            _ => false,
        });
        (dimming, aim)
    };
    let mut groups: Vec<(usize, Vec<Vec<usize>>)> = Vec::new();
    for (i, (spec, target)) in specs.iter().zip(targets).enumerate() {
        let (VariableKind::LightInSurface(p), Target::Move(m)) = (&spec.kind, target) else {
            continue;
        };
        let [(light, _)] = m.lights[..] else {
            continue;
        };
        // A lamp aimed or turned on its own is not like another: swapping places would
        // swap aims too. Lamps of one group aim alike.
        if targets.iter().any(|t| match t {
            Target::Aim { lights } => lights.len() == 1 && lights[0].0 == light,
            Target::Rotate {
                light: Some((l, _)),
                ..
            } => *l == light,
            _ => false,
        }) {
            continue;
        }
        if !m.instances.is_empty() {
            continue;
        }
        let member = match power_of(light) {
            Some(j) => vec![i, j],
            None => vec![i],
        };
        let alike = |k: usize| {
            let (VariableKind::LightInSurface(q), Target::Move(n)) = (&specs[k].kind, &targets[k])
            else {
                return false;
            };
            let other = n.lights[0].0;
            let range = |j: Option<usize>| j.map(|j| &specs[j].kind);
            q == p
                && same_light(&scene.lights[light].kind, &scene.lights[other].kind)
                && range(power_of(light)) == range(power_of(other))
                && shared(light) == shared(other)
        };
        match groups.iter_mut().find(|(first, _)| alike(*first)) {
            Some((_, members)) => members.push(member),
            None => groups.push((i, vec![member])),
        }
    }
    groups
        .into_iter()
        .map(|(_, members)| members)
        .filter(|members| members.len() > 1)
        .collect()
}

/// Whether two lights are the same lamp (kind, output, aim), wherever they are.
fn same_light(a: &LightKind, b: &LightKind) -> bool {
    let (mut a, mut b) = (a.clone(), b.clone());
    for k in [&mut a, &mut b] {
        if let Some(p) = k.position_mut() {
            *p = Vec3::ZERO;
        }
    }
    a == b
}
