//! `<material>` → `<effect>` (profile_COMMON: `phong`, `lambert`, `blinn`, `constant`)
//! mapped to the photon tracer's materials, following ILPSolver's reading of Blender's
//! exports so that its scenes work unchanged (its `Scene::loadSceneMaterials`):
//!
//! 1. `emission` not black → an **emitter**: the colour is the luminance in cd/m²
//!    (DESIGN.md §1). ILPSolver's scenes have no units: `16 16 16` in its Cornell box
//!    is kept as 16 cd/m², so its results scale with that arbitrary number. The diffuse
//!    colour is kept too (ILPSolver's emitters reflect).
//! 2. `index_of_refraction` < 1 → a **hole** (aperture), unless textured (ILPSolver
//!    tests the texture first; ILPSolver's `hole.dae` writes 0.25 with transparency 0).
//! 3. `index_of_refraction` > 1 → **glass** of that index, unless textured. Its transmission is
//!    `1 − opacity` when `transparent`/`transparency` make it see-through, else 1: in
//!    ILPSolver the index alone makes clear glass, and Blender writes an index other
//!    than 1 only for ray-traced transparency.
//! 4. `reflective` × `reflectivity` (1 when absent) → a **mirror** reflectance K_s.
//! 5. `diffuse` colour, or a texture (`sampler2D` → `surface` → `image` `init_from`,
//!    decoded as sRGB) that multiplies white → diffuse K_d.
//!
//! `specular`/`shininess` (Phong highlights) and `ambient` are not read: the tracer's
//! only specular reflection is the perfect mirror of `reflective`.
//!
//! Opacity follows COLLADA 1.4.1 §7 (profile_COMMON transparency): `A_ONE` (default):
//! `transparent.a × transparency`; `RGB_ZERO`: `1 − Y(transparent.rgb) × transparency`;
//! `A_ZERO`: `1 − transparent.a × transparency`; `RGB_ONE`: `Y(transparent.rgb) ×
//! transparency`. A see-through material with index 1 lets light straight through
//! (transmission `1 − opacity`, no refraction). K_d and K_s are scaled so that
//! K_d + K_s + transmission ≤ 1 per channel.

use super::xml::{Ctx, child, children, path};
use crate::error::LoadError;
use crate::image_file::{TextureError, read_texture};
use crate::light::luminance;
use crate::material::{Material, Texture};
use crate::model::TextureId;
use crate::obj::energy_conserving;
use glam::{Vec3, Vec4};
use roxmltree::Node;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Reflectance of surfaces whose material is missing or whose texture cannot be read.
pub(super) const DEFAULT_REFLECTANCE: f32 = 0.8;

/// Decoded texture images by file, `None` for those that failed (warned once).
pub(super) type TextureCache = HashMap<PathBuf, Option<TextureId>>;

/// A `<color>`, or a `<texture>` resolved to an image file (with the location of the
/// `<init_from>` naming it).
enum Value {
    Color(Vec4),
    Image(PathBuf, String),
}

/// Reads a `<material>`.
pub(super) fn read(
    ctx: &Ctx,
    material: Node,
    textures: &mut Vec<Texture>,
    cache: &mut TextureCache,
) -> Result<Material, LoadError> {
    let name = material
        .attribute("name")
        .or(material.attribute("id"))
        .unwrap_or("material");
    let instance = child(material, "instance_effect")
        .ok_or_else(|| ctx.error(material, "a <material> needs an <instance_effect>"))?;
    let url = instance
        .attribute("url")
        .ok_or_else(|| ctx.error(instance, "<instance_effect> needs a url"))?;
    let effect = ctx.resolve(url, "effect", instance)?;
    let Some(profile) = child(effect, "profile_COMMON") else {
        ctx.warn(effect, "only profile_COMMON effects are read; using grey");
        return Ok(Material::diffuse(name, Vec3::splat(DEFAULT_REFLECTANCE)));
    };
    let Some(shading) = child(profile, "technique").and_then(|t| {
        t.children().find(|c| {
            c.is_element()
                && matches!(
                    c.tag_name().name(),
                    "phong" | "lambert" | "blinn" | "constant"
                )
        })
    }) else {
        ctx.warn(
            profile,
            "no phong/lambert/blinn/constant technique; using grey",
        );
        return Ok(Material::diffuse(name, Vec3::splat(DEFAULT_REFLECTANCE)));
    };
    let params: HashMap<&str, Node> = children(profile, "newparam")
        .chain(
            child(profile, "technique")
                .into_iter()
                .flat_map(|t| children(t, "newparam")),
        )
        .filter_map(|p| p.attribute("sid").map(|sid| (sid, p)))
        .collect();
    let value = |tag: &str| -> Result<Option<Value>, LoadError> {
        match child(shading, tag) {
            Some(n) => color_or_texture(ctx, n, &params),
            None => Ok(None),
        }
    };
    let float = |tag: &str| -> Result<Option<f32>, LoadError> {
        match child(shading, tag).and_then(|n| child(n, "float")) {
            Some(f) => Ok(Some(ctx.floats_n::<1>(f)?[0])),
            None => Ok(None),
        }
    };

    let mut m = Material::diffuse(name, Vec3::ZERO);
    match value("diffuse")? {
        Some(Value::Color(c)) => m.diffuse = c.truncate(),
        Some(Value::Image(file, loc)) => {
            m.texture = texture(ctx, &file, &loc, name, textures, cache)?;
            m.diffuse = Vec3::splat(if m.texture.is_some() {
                1.0
            } else {
                DEFAULT_REFLECTANCE
            });
        }
        None => {}
    }
    match value("emission")? {
        Some(Value::Color(c)) => m.emission = c.truncate().max(Vec3::ZERO),
        Some(Value::Image(file, _)) => {
            return Err(ctx
                .error(
                    shading,
                    format!("material '{name}' emits through a texture ({}), which invlight does not read", file.display()),
                )
                .with_hint("give the emitting material an emission colour (its luminance in cd/m²) instead"));
        }
        None => {}
    }
    if let Some(Value::Color(c)) = value("reflective")? {
        m.specular = c.truncate() * float("reflectivity")?.unwrap_or(1.0);
    }
    let ior = float("index_of_refraction")?.unwrap_or(1.0);
    let opacity = opacity(ctx, shading, &params)?;
    // ILPSolver decides emitter, then texture, then the index of refraction: exporters
    // that write `index_of_refraction 0` on textured materials make no holes there.
    let plain = !m.is_emissive() && m.texture.is_none();
    if ior < 1.0 && plain {
        return Ok(Material::hole(name));
    }
    if ior > 1.0 && plain {
        m.ior = ior;
        m.transmission = if opacity < 1.0 { 1.0 - opacity } else { 1.0 };
        m.specular = Vec3::ZERO;
    } else if opacity < 1.0 {
        m.transmission = 1.0 - opacity;
    }
    (m.diffuse, m.specular) = energy_conserving(m.diffuse, m.specular, m.transmission);
    Ok(m)
}

/// The opacity of `transparent`/`transparency` (1 when neither is given).
fn opacity(ctx: &Ctx, shading: Node, params: &HashMap<&str, Node>) -> Result<f32, LoadError> {
    let transparent = child(shading, "transparent");
    let transparency = match child(shading, "transparency").and_then(|n| child(n, "float")) {
        Some(f) => Some(ctx.floats_n::<1>(f)?[0]),
        None => None,
    };
    let Some(t) = transparent else {
        // `transparency` alone scales the default A_ONE white: it is the opacity.
        return Ok(transparency.unwrap_or(1.0).clamp(0.0, 1.0));
    };
    let colour = match color_or_texture(ctx, t, params)? {
        Some(Value::Color(c)) => c,
        // A transparency texture (cut-outs) is beyond a photon tracer's materials.
        _ => return Ok(1.0),
    };
    let f = transparency.unwrap_or(1.0);
    let opacity = match t.attribute("opaque").unwrap_or("A_ONE") {
        "RGB_ZERO" => 1.0 - luminance(colour.truncate()) * f,
        "A_ZERO" => 1.0 - colour.w * f,
        "RGB_ONE" => luminance(colour.truncate()) * f,
        _ => colour.w * f,
    };
    Ok(opacity.clamp(0.0, 1.0))
}

/// A `<color>`, `<texture>` or `<param ref>` inside a shading parameter.
fn color_or_texture(
    ctx: &Ctx,
    node: Node,
    params: &HashMap<&str, Node>,
) -> Result<Option<Value>, LoadError> {
    if let Some(c) = child(node, "color") {
        let v = ctx.floats(c)?;
        return match v.as_slice() {
            [r, g, b] => Ok(Some(Value::Color(Vec4::new(*r, *g, *b, 1.0)))),
            [r, g, b, a] => Ok(Some(Value::Color(Vec4::new(*r, *g, *b, *a)))),
            _ => Err(ctx.error(c, format!("expected 3 or 4 numbers, found {}", v.len()))),
        };
    }
    if let Some(t) = child(node, "texture") {
        let sampler = t.attribute("texture").unwrap_or("");
        return Ok(image_of_sampler(ctx, sampler, params)?.map(|(f, l)| Value::Image(f, l)));
    }
    if let Some(p) = child(node, "param")
        && let Some(np) = p.attribute("ref").and_then(|r| params.get(r))
        && let Some(v) = np
            .children()
            .find(|c| c.is_element() && c.tag_name().name().starts_with("float"))
    {
        let v = ctx.floats(v)?;
        if let [r, g, b, rest @ ..] = v.as_slice() {
            return Ok(Some(Value::Color(Vec4::new(
                *r,
                *g,
                *b,
                rest.first().copied().unwrap_or(1.0),
            ))));
        }
    }
    Ok(None)
}

/// The image file a `<texture texture="…">` reaches: sampler2D → surface → image
/// (COLLADA 1.4), sampler2D → instance_image (1.5), or an image id directly (some
/// exporters), with the location of its `<init_from>`. `None` (with a warning) when the
/// chain is broken; an error when the file lies outside the scene's folder tree.
fn image_of_sampler(
    ctx: &Ctx,
    sampler: &str,
    params: &HashMap<&str, Node>,
) -> Result<Option<(PathBuf, String)>, LoadError> {
    let mut image_id = sampler.to_string();
    if let Some(s2d) = params.get(sampler).and_then(|p| child(*p, "sampler2D")) {
        if let Some(url) = child(s2d, "instance_image").and_then(|i| i.attribute("url")) {
            image_id = url.to_string();
        } else if let Some(surface_sid) = child(s2d, "source").and_then(|s| s.text()) {
            let init = params
                .get(surface_sid.trim())
                .and_then(|p| path(*p, &["surface", "init_from"]))
                .and_then(|i| i.text());
            match init {
                Some(id) => image_id = id.trim().to_string(),
                None => {
                    ctx.warn(
                        s2d,
                        &format!("surface '{surface_sid}' has no init_from; no texture"),
                    );
                    return Ok(None);
                }
            }
        }
    }
    let image = ctx
        .by_id(&image_id)
        .filter(|n| n.tag_name().name() == "image");
    let Some(image) = image else {
        eprintln!(
            "warning: {}: texture '{sampler}' reaches no <image> ('{image_id}'); no texture",
            ctx.path.display()
        );
        return Ok(None);
    };
    let Some(init) = child(image, "init_from") else {
        return Ok(None);
    };
    let Some(uri) = child(init, "ref").and_then(|r| r.text()).or(init.text()) else {
        return Ok(None);
    };
    let uri = uri.trim();
    let loc = ctx.location(init);
    let file = ctx.files.resolve(ctx.path, &loc, uri, &uri_to_path(uri))?;
    Ok(Some((file, loc)))
}

/// A file URI or relative reference as a path: `file://` dropped, `%XX` decoded.
fn uri_to_path(uri: &str) -> PathBuf {
    let uri = uri
        .strip_prefix("file:///")
        .map(|rest| {
            // `file:///C:/x` is a Windows drive path; `file:///x` an absolute Unix one.
            if rest.as_bytes().get(1) == Some(&b':') {
                rest.to_string()
            } else {
                format!("/{rest}")
            }
        })
        .or_else(|| uri.strip_prefix("file://").map(str::to_string))
        .unwrap_or_else(|| uri.to_string());
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && let (Some(h), Some(l)) = (
                bytes.get(i + 1).and_then(|&b| hex(b)),
                bytes.get(i + 2).and_then(|&b| hex(b)),
            )
        {
            out.push((h * 16 + l) as u8);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    PathBuf::from(String::from_utf8_lossy(&out).replace('\\', "/"))
}

/// The texture index of an image file, decoding it on first use; `None` (with a
/// warning) when it cannot be read, an error when it does not fit in the memory budget.
fn texture(
    ctx: &Ctx,
    file: &Path,
    loc: &str,
    material: &str,
    textures: &mut Vec<Texture>,
    cache: &mut TextureCache,
) -> Result<Option<TextureId>, LoadError> {
    if let Some(&t) = cache.get(file) {
        return Ok(t);
    }
    let t = match read_texture(file, ctx.path, loc, ctx.files) {
        Ok(t) => {
            textures.push(t);
            Some(TextureId::from_index(textures.len() - 1))
        }
        Err(TextureError::Refused(e)) => return Err(e),
        Err(TextureError::Unreadable(e)) => {
            eprintln!("warning: {e}; material '{material}' is grey instead");
            None
        }
    };
    cache.insert(file.to_path_buf(), t);
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_become_paths() {
        assert_eq!(uri_to_path("tex/a%20b.png"), PathBuf::from("tex/a b.png"));
        assert_eq!(
            uri_to_path("file:///home/x.png"),
            PathBuf::from("/home/x.png")
        );
        assert_eq!(uri_to_path("file:///C:/x.png"), PathBuf::from("C:/x.png"));
        assert_eq!(uri_to_path("..\\t.jpg"), PathBuf::from("../t.jpg"));
        assert_eq!(uri_to_path("100%.png"), PathBuf::from("100%.png"));
    }
}
