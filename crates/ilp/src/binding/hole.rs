//! Holes (thesis §4.1, fig. 4.2): a `holeInSurface` object becomes an aperture through
//! which rays pass, by giving its instances a copy of their mesh whose every triangle
//! is of a hole material (the tracer makes the object's box a volume where every
//! surface is transparent).

use super::placement::{Bounds, authored, placed};
use super::{Target, find_surface};
use crate::problem::{PlacementSpec, VariableSpec};
use crate::space::{Domain, Parallelogram};
use invlight_scene::{Diagnostic, Material, Scene, SurfaceId};

/// Refuses a hole that covers its whole placement rectangle wherever it goes: it would
/// remove the wall it is cut in (and everything else in its box) for every candidate,
/// which no one means. `bounds` is the hole object's box.
pub fn check_size(
    rect: &Parallelogram,
    bounds: &Bounds,
    id: &str,
    wall: &str,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(), Diagnostic> {
    let u = rect.e1.normalize();
    let v = rect.e1.cross(rect.e2).cross(rect.e1).normalize();
    let extent = |axis: glam::DVec3| {
        let corners = (0..8).map(|k| {
            let pick = |bit: usize, lo: f64, hi: f64| if k & bit == 0 { lo } else { hi };
            glam::DVec3::new(
                pick(1, bounds.lo.x, bounds.hi.x),
                pick(2, bounds.lo.y, bounds.hi.y),
                pick(4, bounds.lo.z, bounds.hi.z),
            )
            .dot(axis)
        });
        let (lo, hi) = corners.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
        hi - lo
    };
    let (wu, wv) = (rect.e1.length(), rect.e2.dot(v).abs());
    let (hu, hv) = (extent(u), extent(v));
    if hu >= wu && hv >= wv {
        return Err(err(format!(
            "the hole '{id}' ({hu:.3} m × {hv:.3} m) is as large as its placement '{wall}' ({wu:.3} m × {wv:.3} m) or larger: wherever it goes it removes the whole of it"
        ))
        .with_hint("make the hole smaller than the wall it is cut in, or the placement larger"));
    }
    Ok(())
}

/// Gives a surface's instances a copy of their mesh whose every triangle is a hole.
pub fn make_hole(scene: &mut Scene, s: SurfaceId, id: &str) {
    let mut hole = None;
    for i in scene.surfaces[s].instances.clone() {
        let mesh = scene.instances[i].mesh;
        if scene.meshes[mesh]
            .materials
            .iter()
            .all(|&m| scene.materials[m].hole)
        {
            continue;
        }
        let h = *hole
            .get_or_insert_with(|| scene.add_material(Material::hole(&format!("{id} (hole)"))));
        let mut copy = scene.meshes[mesh].clone();
        copy.materials.iter_mut().for_each(|m| *m = h);
        scene.instances[i].mesh = scene.add_mesh(copy);
    }
}

/// A `holeInSurface`: the object `spec.id` placed on `p` as for an `objectInSurface`,
/// made a hole, and refused if it would cover its whole rectangle.
pub(super) fn placement(
    scene: &mut Scene,
    spec: &VariableSpec,
    p: &PlacementSpec,
    err: &dyn Fn(String) -> Diagnostic,
    warnings: &mut Vec<Diagnostic>,
) -> Result<(Domain, Target), Diagnostic> {
    let s = find_surface(scene, &spec.id, spec, err)?;
    let bound = placed(scene, spec, p, Some(s), None, err, warnings)?;
    if let (Domain::Parallelogram(rect), Target::Move(m)) = &bound {
        check_size(rect, &m.bounds, &spec.id, &p.surface, err)?;
    }
    make_hole(scene, s, &spec.id);
    Ok(bound)
}

/// A `holeSize`: the object `spec.id`, made a hole, scaled about its authored centre
/// from `min` to `max` times its authored size.
pub(super) fn size(
    scene: &mut Scene,
    spec: &VariableSpec,
    min: f64,
    max: f64,
    err: &dyn Fn(String) -> Diagnostic,
) -> Result<(Domain, Target), Diagnostic> {
    let s = find_surface(scene, &spec.id, spec, err)?;
    make_hole(scene, s, &spec.id);
    let (instances, centre) = authored(scene, s);
    Ok((
        Domain::Segment { min, max },
        Target::Scale { instances, centre },
    ))
}
