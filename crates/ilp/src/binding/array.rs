//! `<lightArray>` (invlight): lamps set out as a regular array on a placement
//! rectangle ([`crate::space::ArrayDomain`]). The first columns × rows lamps fill it
//! row by row, each keeping its authored height off the rectangle's plane (a
//! luminaire authored 5 cm under the ceiling stays 5 cm under it), and the rest are
//! off: they emit nothing, so a trace spends no photons on them, and they draw no
//! power ([`Binding::power`]). A searched orientation turns every lamp about its aim
//! from its frame as loaded, each time a configuration is applied, so that turns never
//! add up. With `continuous="true"` the fittings of each row lie end to end
//! ([`crate::space::Rows`]); what that asks of the lamps (one length, along an edge,
//! a least row that fits) is checked here, at load, with the element's line.

use super::fittings;
use super::placement::{Bounds, find_parallelogram, onto_plane};
use super::{Binding, Target};
use crate::problem::{ArraySpec, FittingSize, VariableSpec};
use crate::space::{ArrayDomain, ArrayShape, Configuration, Domain, Parallelogram, Rows};
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
    /// Where the fittings lie end to end in rows (the domain's, kept here to apply a
    /// shape).
    pub rows: Option<Rows>,
}

impl Lamps {
    /// Where `shape` puts lamp `k` on the rectangle (before its offset off the plane).
    pub fn place(&self, shape: &ArrayShape, k: u32) -> DVec3 {
        let (s, t) = shape.place(k, self.rows.as_ref());
        self.rect.point(s, t)
    }

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
/// rectangle `a.surface`, their fittings sized by `sizes` where it is continuous.
pub(super) fn variable(
    scene: &Scene,
    spec: &VariableSpec,
    a: &ArraySpec,
    sizes: &[FittingSize],
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
    let rows = if a.continuous {
        let ids: Vec<LightId> = lamps.iter().map(|&(l, _, _)| l).collect();
        Some(continuous_rows(scene, spec, a, &rect, &ids, sizes, err)?)
    } else {
        None
    };
    let domain = ArrayDomain {
        rect: rect.clone(),
        columns: a.columns,
        rows: a.rows,
        lamps: lamps.len() as u32,
        turns: a.orientation.is_none(),
        continuous: rows,
    };
    let lamps = Lamps {
        rect,
        lamps,
        frames,
        rows,
    };
    Ok((Domain::Array(domain), Target::Array(lamps)))
}

/// The continuous rows of `<lightArray continuous="true">` over `lamps` on `rect`:
/// every lamp a fitting of one length (its `<luminaire size>` or its file's), lying
/// along one edge of the rectangle, and the least count along the rows (in some
/// orientation, where it is searched) laid end to end no longer than that edge.
fn continuous_rows(
    scene: &Scene,
    spec: &VariableSpec,
    a: &ArraySpec,
    rect: &Parallelogram,
    lamps: &[LightId],
    sizes: &[FittingSize],
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<Rows, Diagnostic> {
    let what = format!("<lightArray id=\"{}\" continuous=\"true\">", spec.id);
    let edges = [rect.e1, rect.e2];
    let mut first: Option<(&str, f64, usize)> = None;
    for &light in lamps {
        let l = &scene.lights[light];
        let Some((length, c90)) = fittings::length(&l.name, &l.kind, sizes) else {
            return Err(err(format!(
                "'{}' has no length, expected every lamp of {what} to be a fitting of known length, laid end to end",
                l.name
            ))
            .with_hint(format!(
                "give it <luminaire light=\"{}\" size=\"L,W\"> (its length along C90 and width, m) or a photometric file with the luminaire's dimensions (EULUMDAT), or leave continuous out",
                l.name
            )));
        };
        let Some(along) = (0..2).find(|&i| c90.dot(edges[i].normalize()).abs() > 1.0 - 1e-6) else {
            return Err(err(format!(
                "'{}' lies across the edges of '{}', expected every lamp of {what} to lie along one of them",
                l.name, a.surface
            ))
            .with_hint("turn the fittings (<luminaire rotation>) so that their length lies along an edge of the rectangle"));
        };
        match first {
            None => first = Some((&l.name, length, along)),
            Some((name, len, _)) if (len - length).abs() > 1e-6 => {
                return Err(err(format!(
                    "'{name}' is {len:.3} m long and '{}' {length:.3} m, expected fittings of one length in {what}",
                    l.name
                ))
                .with_hint("give them one <luminaire size>, or lay out the two kinds in two arrays"));
            }
            Some((name, _, edge)) if edge != along => {
                return Err(err(format!(
                    "'{name}' lies along the {} edge of '{}' and '{}' along the {}, expected every lamp of {what} to lie one way",
                    EDGES[edge], a.surface, l.name, EDGES[along]
                ))
                .with_hint("give them one <luminaire rotation>; orientation=\"search\" turns them all together"));
            }
            Some(_) => {}
        }
    }
    let (_, length, along) = first.expect("an array names at least one lamp");
    let rows = Rows {
        along,
        pitch: edges.map(|e| length / e.length()),
    };
    let orientations = match a.orientation {
        None => vec![Some(0.0), Some(90.0)],
        Some(_) => vec![None],
    };
    let least = [a.columns.0, a.rows.0];
    if orientations.iter().all(|&o| {
        let axis = rows.axis(o);
        f64::from(least[axis]) * rows.pitch[axis] > 1.0 + ROW_SLACK
    }) {
        let axis = rows.axis(orientations[0]);
        let n = least[axis];
        return Err(err(format!(
            "{what} lays at least {n} fittings of {length:.2} m end to end, a row of {:.2} m along the {} edge of '{}', {:.2} m long",
            f64::from(n) * length,
            EDGES[axis],
            a.surface,
            edges[axis].length()
        ))
        .with_hint(format!(
            "lower the least '{}', or turn the fittings (orientation=\"90\" or \"search\"), or use shorter ones",
            ["columns", "rows"][axis]
        )));
    }
    Ok(rows)
}

/// How much longer than its edge a row of fittings may be, as a fraction of it: the
/// rounding of a length that fits exactly.
pub(super) const ROW_SLACK: f64 = 1e-9;

/// The rectangle's edges as a layout names them.
pub(super) const EDGES: [&str; 2] = ["first", "other"];

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
            if let Some(p) = kind.position_mut() {
                *p = (lamps.place(shape, k as u32) + offset).as_vec3();
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
