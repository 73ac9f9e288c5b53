//! `<lightArray>` (invlight): lamps set out as a regular array on a placement
//! rectangle ([`crate::space::ArrayDomain`]). The first columns × rows lamps fill it
//! row by row, each keeping its authored height off the rectangle's plane (a
//! luminaire authored 5 cm under the ceiling stays 5 cm under it), and the rest are
//! off: they emit nothing, so a trace spends no photons on them, and they draw no
//! power ([`Binding::power`]). A searched orientation turns every lamp about its aim
//! from its frame as loaded, each time a configuration is applied, so that turns never
//! add up.

use super::placement::{Bounds, find_parallelogram, onto_plane};
use super::{Binding, Target};
use crate::problem::{ArraySpec, VariableSpec};
use crate::space::{ArrayDomain, ArrayShape, Configuration, Domain, Parallelogram};
use glam::{DVec3, Mat3};
use invlight_scene::{Diagnostic, LightId, LightKind, Rgb, Scene, known_names};

/// An array's lamps, each with its offset from the rectangle's plane and its authored
/// strength, in the order they fill the array.
#[derive(Debug, Clone)]
pub struct Lamps {
    /// The rectangle (the domain's, kept here to apply a shape).
    pub rect: Parallelogram,
    /// The light, its authored offset along the plane's normal, its authored strength.
    pub lamps: Vec<(LightId, DVec3, Rgb)>,
    /// Each lamp's frame as loaded (its `<luminaire rotation>` included), in `lamps`'
    /// order: what a searched orientation turns; the identity for a lamp without one.
    pub frames: Vec<Mat3>,
}

impl Lamps {
    /// The box every lamp may stand in: the rectangle's corners at each lamp's offset.
    pub fn bounds(&self) -> Option<Bounds> {
        let r = &self.rect;
        let corners = [r.a, r.a + r.e1, r.a + r.e2, r.a + r.e1 + r.e2];
        self.lamps
            .iter()
            .flat_map(|&(_, offset, _)| corners.map(|c| Bounds::point(c + offset)))
            .reduce(Bounds::union)
    }
}

/// A `<lightArray>` over the point, spot or goniometric lights `a.lights` on the
/// rectangle `a.surface`.
pub(super) fn variable(
    scene: &Scene,
    spec: &VariableSpec,
    a: &ArraySpec,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    let rect = find_parallelogram(scene, &a.surface, a.vertices, err)?;
    let (mut lamps, mut frames) = (Vec::new(), Vec::new());
    for name in &a.lights {
        let light = scene.light(name).ok_or_else(|| {
            err(format!(
                "no light named '{name}' in the scene, expected the lamps of <lightArray id=\"{}\">",
                spec.id
            ))
            .with_hint(known_names(
                scene.lights.iter().map(|l| l.name.as_str()),
                "lights",
            ))
        })?;
        let kind = &scene.lights[light].kind;
        let Some(p) = kind.position() else {
            return Err(err(format!(
                "'{name}' is a directional light, expected point, spot or goniometric lamps in <lightArray id=\"{}\">",
                spec.id
            )));
        };
        let p = p.as_dvec3();
        frames.push(match kind {
            LightKind::Goniometric { frame, .. } => *frame,
            _ => Mat3::IDENTITY,
        });
        lamps.push((
            light,
            p - onto_plane(&rect, p),
            *kind.clone().strength_mut(),
        ));
    }
    let domain = ArrayDomain {
        rect: rect.clone(),
        columns: a.columns,
        rows: a.rows,
        lamps: lamps.len() as u32,
        turns: a.orientation.is_none(),
    };
    let lamps = Lamps {
        rect,
        lamps,
        frames,
    };
    Ok((Domain::Array(domain), Target::Array(lamps)))
}

/// Sets the array's lamps out as `shape`: the first columns × rows moved to their
/// places, at their authored strength unless the binding dims them; the rest off. A
/// searched orientation turns every lamp about its aim from its frame as loaded, or,
/// for a lamp a `lightAim` has just aimed, from that aim's frame (the aim sets it from
/// its own authored frame each time, so neither turn adds up).
pub(super) fn apply(scene: &mut Scene, lamps: &Lamps, shape: &ArrayShape, binding: &Binding) {
    let up = scene.up;
    for (k, &(light, offset, authored)) in lamps.lamps.iter().enumerate() {
        let kind = &mut scene.lights[light].kind;
        if let (Some(turn), LightKind::Goniometric { frame, .. }) = (shape.orientation, &kind) {
            let from = if binding.is_aimed(light) {
                *frame
            } else {
                lamps.frames[k]
            };
            kind.set_frame(from * Mat3::from_rotation_z((turn as f32).to_radians()), up);
        }
        if (k as u32) < shape.lamps() {
            let (s, t) = shape.place(k as u32);
            if let Some(p) = kind.position_mut() {
                *p = (lamps.rect.point(s, t) + offset).as_vec3();
            }
            if !binding.is_dimmed(light) {
                *kind.strength_mut() = authored;
            }
        } else {
            *kind.strength_mut() = Rgb::ZERO;
        }
    }
}

impl Binding {
    /// The lamps each `<lightArray>` leaves off at `config`.
    pub(super) fn lamps_off(&self, config: &Configuration) -> Vec<LightId> {
        let mut out = Vec::new();
        for (i, (v, target)) in self.space.variables().iter().zip(&self.targets).enumerate() {
            if let (Domain::Array(a), Target::Array(l)) = (&v.domain, target) {
                let shape = a.shape(self.space.slice(config, i));
                out.extend(
                    l.lamps
                        .iter()
                        .skip(shape.lamps() as usize)
                        .map(|&(light, _, _)| light),
                );
            }
        }
        out
    }

    /// Whether a `lightAim` (its own or its group's) aims `light`.
    fn is_aimed(&self, light: LightId) -> bool {
        self.targets.iter().any(
            |t| matches!(t, Target::Aim { lights } if lights.iter().any(|&(l, _, _)| l == light)),
        )
    }

    /// Whether `light`'s output is set by a `lightPower` (its own or its group's).
    pub(super) fn is_dimmed(&self, light: LightId) -> bool {
        self.component_of(light) != 0
    }

    /// The component `light`'s light is kept apart in: its `lightPower`'s, its group's,
    /// else 0 (the undimmed lights').
    pub(super) fn component_of(&self, light: LightId) -> usize {
        self.targets
            .iter()
            .find_map(|t| match t {
                Target::Power { dimmed, component } if dimmed.holds(light) => Some(*component),
                _ => None,
            })
            .unwrap_or(0)
    }
}
