//! `<light>` and `<camera>` instances placed by their nodes.
//!
//! COLLADA has no photometric units, so the mapping is a convention, chosen so that
//! ILPSolver's and Blender's files keep their numbers: the `<color>` of a point or spot
//! light is its intensity in **candela**, that of a directional light its illuminance in
//! **lux** (a value of 1 is 1 cd or 1 lx). Blender writes colour × energy there
//! (its `<extra><technique profile="blender"><energy>` is already folded in), so its
//! energy is not applied again. Attenuation factors are ignored: light falls off with
//! the inverse square of distance, as it physically does.
//!
//! Spot cones: `falloff_angle` is the **full** cone angle in degrees (Blender's
//! `spotsize`), so the outer half-angle is half of it. Blender's `spotblend` b (its
//! extra technique, also written as `falloff_exponent`) softens the edge over the
//! outer part of the cone the way Blender does, in cosine: `cos inner = cos outer + b ·
//! (1 − cos outer)`. Without it the edge is hard (inner = outer); a `falloff_exponent`
//! from another exporter has no photometric reading and is ignored.
//!
//! Lights shine and cameras look along their node's local −Z, with +Y up (COLLADA 1.4.1
//! §5 `<light>`, `<camera>`). Ambient lights have no direction or position to trace
//! from and are skipped with a warning; orthographic cameras too.

use super::xml::{Ctx, child, path};
use crate::error::LoadError;
use crate::light::{Camera, Light, LightKind};
use glam::{Mat4, Vec3};
use roxmltree::Node;

/// The light of an `<instance_light>` under a node with world transform `world`, or
/// `None` for kinds that are skipped.
pub(super) fn light(
    ctx: &Ctx,
    light: Node,
    name: &str,
    world: &Mat4,
) -> Result<Option<Light>, LoadError> {
    let common = child(light, "technique_common")
        .ok_or_else(|| ctx.error(light, "a <light> needs a <technique_common>"))?;
    let Some(kind) = common.children().find(|c| c.is_element()) else {
        return Err(ctx.error(common, "no light kind (point, spot, directional)"));
    };
    let colour = match child(kind, "color") {
        Some(c) => {
            let v = ctx.floats(c)?;
            match v.as_slice() {
                [r, g, b, ..] => Vec3::new(*r, *g, *b).max(Vec3::ZERO),
                _ => return Err(ctx.error(c, format!("expected 3 numbers, found {}", v.len()))),
            }
        }
        None => Vec3::ONE,
    };
    let position = world.transform_point3(Vec3::ZERO);
    let direction = world
        .transform_vector3(Vec3::NEG_Z)
        .normalize_or(Vec3::NEG_Z);
    let kind = match kind.tag_name().name() {
        "point" => LightKind::Point {
            position,
            intensity: colour,
        },
        "directional" => LightKind::Directional {
            direction,
            illuminance: colour,
        },
        "spot" => {
            let full = match child(kind, "falloff_angle") {
                Some(f) => ctx.floats_n::<1>(f)?[0],
                None => 180.0,
            };
            let outer = (full.clamp(0.0, 360.0) / 2.0).to_radians();
            let blend = match path(light, &["extra", "technique", "spotblend"]) {
                Some(b) => ctx.floats_n::<1>(b)?[0].clamp(0.0, 1.0),
                None => 0.0,
            };
            let cos_outer = outer.cos();
            let inner = (cos_outer + blend * (1.0 - cos_outer))
                .clamp(-1.0, 1.0)
                .acos();
            LightKind::Spot {
                position,
                direction,
                intensity: colour,
                inner,
                outer,
            }
        }
        other => {
            ctx.warn(
                kind,
                &format!("<{other}> lights have no photometric equivalent; skipped"),
            );
            return Ok(None);
        }
    };
    // A photometric file given to this light later takes its C0 from the node's +X.
    let c0 = world.transform_vector3(Vec3::X).normalize_or(Vec3::X);
    Ok(Some(Light {
        c0,
        name: name.to_string(),
        kind,
    }))
}

/// The camera of an `<instance_camera>`, or `None` for orthographic ones.
pub(super) fn camera(
    ctx: &Ctx,
    camera: Node,
    name: &str,
    world: &Mat4,
) -> Result<Option<Camera>, LoadError> {
    let Some(optics) = path(camera, &["optics", "technique_common"]) else {
        return Err(ctx.error(camera, "a <camera> needs <optics><technique_common>"));
    };
    let Some(perspective) = child(optics, "perspective") else {
        ctx.warn(camera, "only perspective cameras are read; skipped");
        return Ok(None);
    };
    let number = |tag: &str| -> Result<Option<f32>, LoadError> {
        match child(perspective, tag) {
            Some(n) => Ok(Some(ctx.floats_n::<1>(n)?[0])),
            None => Ok(None),
        }
    };
    let (xfov, yfov, aspect) = (number("xfov")?, number("yfov")?, number("aspect_ratio")?);
    let half_tan = |deg: f32| (deg.to_radians() / 2.0).tan();
    let (yfov, aspect) = match (xfov, yfov, aspect) {
        (_, Some(y), a) => (
            y.to_radians(),
            a.or(xfov.map(|x| half_tan(x) / half_tan(y))),
        ),
        (Some(x), None, Some(a)) if a > 0.0 => (2.0 * (half_tan(x) / a).atan(), Some(a)),
        (Some(x), None, _) => (x.to_radians(), None),
        (None, None, _) => {
            return Err(ctx.error(perspective, "a perspective camera needs xfov or yfov"));
        }
    };
    if !(yfov > 0.0 && yfov < std::f32::consts::PI) {
        return Err(ctx.error(
            perspective,
            "the field of view must be between 0 and 180 degrees",
        ));
    }
    let forward = world
        .transform_vector3(Vec3::NEG_Z)
        .normalize_or(Vec3::NEG_Z);
    let up = world.transform_vector3(Vec3::Y);
    let up = (up - forward * up.dot(forward)).normalize_or(forward.any_orthonormal_vector());
    Ok(Some(Camera {
        name: name.to_string(),
        position: world.transform_point3(Vec3::ZERO),
        forward,
        up,
        yfov,
        aspect,
    }))
}
