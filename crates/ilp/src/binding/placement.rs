//! Placement variables (thesis §4.4.1): the parallelogram an object, light or hole is
//! placed on, and the object's anchor — the point of it a user means by "where it is".
//!
//! ILPSolver moves an object by P − A (P the placement point, A the rectangle's first
//! vertex), so P is where vertex A goes and the object keeps its authored offset from
//! A: an object authored at the rectangle's centre is searched over a rectangle shifted
//! by half a diagonal. The anchor (a light's position; an object's bounding-box centre
//! projected on the rectangle's plane) is what results report as the object's place,
//! beside P, and with `anchor="centre"` what P stands for.

use super::{Moved, Target, find_surface, surface_materials};
use crate::problem::{Anchor, PlacementSpec, VariableSpec};
use crate::space::{Domain, Parallelogram};
use glam::{DVec3, Mat4, Vec3};
use invlight_scene::{Diagnostic, InstanceId, LightId, LightKind, Scene, SurfaceId, known_names};

/// An axis-aligned box in world space, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Lowest corner.
    pub lo: DVec3,
    /// Highest corner.
    pub hi: DVec3,
}

impl Bounds {
    /// The box of one point.
    pub fn point(p: DVec3) -> Bounds {
        Bounds { lo: p, hi: p }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Bounds) -> Bounds {
        Bounds {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    /// The centre.
    pub fn centre(&self) -> DVec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Whether `other` lies inside this box grown by `slack` on every side.
    pub fn holds(&self, other: &Bounds, slack: f64) -> bool {
        (other.lo - self.lo).min_element() >= -slack && (self.hi - other.hi).min_element() >= -slack
    }

    /// The box moved by `d`.
    pub fn shifted(&self, d: DVec3) -> Bounds {
        Bounds {
            lo: self.lo + d,
            hi: self.hi + d,
        }
    }
}

/// The world bounds of some instances, `None` when they have no vertices.
pub fn instance_bounds(scene: &Scene, instances: &[InstanceId]) -> Option<Bounds> {
    let mut out: Option<Bounds> = None;
    for &i in instances {
        let inst = &scene.instances[i];
        for &p in &scene.meshes[inst.mesh].positions {
            let b = Bounds::point(inst.transform.transform_point3(p).as_dvec3());
            out = Some(out.map_or(b, |o| o.union(b)));
        }
    }
    out
}

/// A surface's instances with their authored transforms, and the centre of their world
/// bounds (the origin when they have no vertices): what a scaling or a turn about the
/// surface's centre starts from.
pub fn authored(scene: &Scene, surface: SurfaceId) -> (Vec<(InstanceId, Mat4)>, Vec3) {
    let ids = &scene.surfaces[surface].instances;
    let centre =
        instance_bounds(scene, ids).map_or(Vec3::ZERO, |b| (0.5 * (b.lo + b.hi)).as_vec3());
    let instances = ids
        .iter()
        .map(|&i| (i, scene.instances[i].transform))
        .collect();
    (instances, centre)
}

/// The point `p` projected along the parallelogram's normal onto its plane.
pub fn onto_plane(rect: &Parallelogram, p: DVec3) -> DVec3 {
    let n = rect.e1.cross(rect.e2).normalize();
    p - (p - rect.a).dot(n) * n
}

/// The placement rectangle `name` with vertex indices A, B, C, D: a `*__Geometry`
/// placement, else a surface with four distinct vertices, else `name__Geometry`.
/// `message` makes a located error.
pub fn find_parallelogram(
    scene: &Scene,
    name: &str,
    idx: [usize; 4],
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<Parallelogram, Diagnostic> {
    let vertices: Vec<Vec3> = if let Some(p) = scene.placement(name) {
        p.vertices.clone()
    } else if let Some(s) = scene.surface(name) {
        let mut v: Vec<Vec3> = Vec::new();
        for &i in &scene.surfaces[s].instances {
            let inst = &scene.instances[i];
            for &p in &scene.meshes[inst.mesh].positions {
                let w = inst.transform.transform_point3(p);
                if !v.contains(&w) {
                    v.push(w);
                }
                if v.len() > 4 {
                    break;
                }
            }
        }
        v
    } else if let Some(p) = scene.placement(&invlight_scene::placement_name(name)) {
        p.vertices.clone()
    } else {
        return Err(err(format!(
            "no placement rectangle or surface named '{name}' in the scene"
        ))
        .with_hint(invlight_scene::known_names(
            scene.placements.iter().map(|p| p.name.as_str()),
            "placement rectangles",
        )));
    };
    if vertices.len() != 4 {
        return Err(err(format!(
            "placement '{name}' has {} distinct vertices, expected a planar quad (4)",
            if vertices.len() > 4 {
                "more than 4".to_string()
            } else {
                vertices.len().to_string()
            }
        )));
    }
    if let Some(&bad) = idx.iter().find(|&&i| i >= 4) {
        return Err(err(format!(
            "vertex index {bad} on '{name}', expected 0–3 (it has 4 vertices)"
        )));
    }
    let mut sorted = idx;
    sorted.sort();
    if sorted != [0, 1, 2, 3] {
        return Err(err(format!(
            "vertex indices {idx:?} on '{name}', expected each of 0, 1, 2, 3 once"
        )));
    }
    let v = |k: usize| vertices[idx[k]].as_dvec3();
    Parallelogram::from_corners(v(0), [v(1), v(2), v(3)])
        .map_err(|e| err(format!("placement '{name}' is not a planar quad: {e}")))
}

/// An `objectInSurface`: the instances of the surface `spec.id` placed on `p`.
pub(super) fn object(
    scene: &Scene,
    spec: &VariableSpec,
    p: &PlacementSpec,
    err: &dyn Fn(String) -> Diagnostic,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(Domain, Target), Diagnostic> {
    let s = find_surface(scene, &spec.id, spec, err)?;
    placed(scene, spec, p, Some(s), None, err, warnings)
}

/// A `lightInSurface`: the point, spot or goniometric light `spec.id`, else the
/// emissive object of that name (with a warning when it emits nothing), placed on `p`.
pub(super) fn light(
    scene: &Scene,
    spec: &VariableSpec,
    p: &PlacementSpec,
    err: &dyn Fn(String) -> Diagnostic,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(Domain, Target), Diagnostic> {
    Ok(match scene.light(&spec.id) {
        Some(l) => {
            if matches!(scene.lights[l].kind, LightKind::Directional { .. }) {
                return Err(err(format!(
                    "'{}' is a directional light, expected a point, spot or goniometric light or an emissive object (use <directionalLight> for a sun)",
                    spec.id
                )));
            }
            placed(scene, spec, p, None, Some(l), err, warnings)?
        }
        None => {
            let s = scene.surface(&spec.id).ok_or_else(|| {
                err(format!(
                    "no light or surface named '{}' in the scene, expected a point, spot or goniometric light or an emissive object",
                    spec.id
                ))
                .with_hint(known_names(scene.lights.iter().map(|l| l.name.as_str()), "lights"))
            })?;
            if !surface_materials(scene, s)
                .iter()
                .any(|&m| scene.materials[m].is_emissive())
            {
                warnings.push(err(format!(
                    "'{}' emits no light; moving it only moves its shadow",
                    spec.id
                )));
            }
            placed(scene, spec, p, Some(s), None, err, warnings)?
        }
    })
}

/// The domain and target of a placement variable moving the instances of `surface` or
/// the light `light`, with a warning when ILPSolver's rule would search it away from
/// where it was authored.
pub(super) fn placed(
    scene: &Scene,
    spec: &VariableSpec,
    p: &PlacementSpec,
    surface: Option<SurfaceId>,
    light: Option<LightId>,
    err: &dyn Fn(String) -> Diagnostic,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(Domain, Target), Diagnostic> {
    let rect = find_parallelogram(scene, &p.surface, p.vertices, err)?;
    let instances: Vec<(InstanceId, Mat4)> = surface
        .map(|s| {
            scene.surfaces[s]
                .instances
                .iter()
                .map(|&i| (i, scene.instances[i].transform))
                .collect()
        })
        .unwrap_or_default();
    let lights: Vec<(LightId, Vec3)> = light
        .and_then(|l| scene.lights[l].kind.position().map(|p| (l, p)))
        .into_iter()
        .collect();
    let ids: Vec<InstanceId> = instances.iter().map(|&(i, _)| i).collect();
    let mut bounds = instance_bounds(scene, &ids);
    for &(_, pos) in &lights {
        let b = Bounds::point(pos.as_dvec3());
        bounds = Some(bounds.map_or(b, |o| o.union(b)));
    }
    let bounds = bounds.ok_or_else(|| err(format!("'{}' has no geometry to place", spec.id)))?;
    let anchor = match lights.first() {
        Some(&(_, pos)) => pos.as_dvec3(),
        None => onto_plane(&rect, bounds.centre()),
    };
    let reference = match p.anchor {
        Anchor::VertexA => {
            let offset = anchor - rect.a;
            if offset.length() > 1e-3 * rect.diagonal().max(1.0) {
                warnings.push(
                    err(format!(
                        "'{}' is authored at ({:.3}, {:.3}, {:.3}), {:.3} m from vertex A of '{}': by ILPSolver's rule it moves by P − A, so it is searched over that rectangle shifted by ({:.3}, {:.3}, {:.3}) m, and P is not where it is",
                        spec.id,
                        anchor.x,
                        anchor.y,
                        anchor.z,
                        offset.length(),
                        p.surface,
                        offset.x,
                        offset.y,
                        offset.z
                    ))
                    .with_hint(format!(
                        "add anchor=\"centre\" to <{}> to put {} itself on the rectangle; results give both P and its anchor",
                        spec.kind.name(),
                        if lights.is_empty() { "the object's centre" } else { "the light" }
                    )),
                );
            }
            rect.a
        }
        Anchor::Centre => anchor,
    };
    Ok((
        Domain::Parallelogram(rect),
        Target::Move(Moved {
            instances,
            lights,
            reference,
            anchor,
            bounds,
        }),
    ))
}
