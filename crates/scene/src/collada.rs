//! COLLADA 1.4/1.5 scenes (`.dae`), as Blender and ILPSolver's examples write them.
//!
//! Read: `library_geometries` (`<mesh>` with `triangles`, `polylist`, `polygons`,
//! `trifans`, `tristrips`; shared `<input>` offsets; VERTEX and TEXCOORD), the
//! `visual_scene` node tree (`matrix`, `translate`, `rotate`, `scale`, `lookat` in
//! document order), `instance_geometry` with `bind_material`, `instance_node`, effects
//! (see [`effect`]), lights and cameras (see [`light`]), and `<asset>`: `<unit meter>`
//! scales every position to metres; `<up_axis>` only sets [`Scene::up`] — positions are
//! never rotated. Skins, morphs, physics and animation are not read.
//!
//! Names: a node is addressed by its `name`, else its `id`; each `instance_geometry`
//! becomes an instance under that name and is also added to every named ancestor's
//! surface, so a name covers everything under it. Nodes named `*__Geometry` are
//! ILPSolver's placement rectangles: they go to [`Scene::placements`] with their
//! distinct world-space vertices in the order their index lists first reach them (the
//! order ILPSolver saw through Assimp's `JoinIdenticalVertices`, which its problem
//! files' `vertexAIndex`… count in), and are not part of the lit scene.
//!
//! The XML is read with roxmltree, which accepts files missing optional-by-practice
//! elements such as `<created>`; every error names the element and line at fault.

mod effect;
mod geometry;
mod light;
mod xml;

use crate::error::LoadError;
use crate::files::Files;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::model::{MaterialId, MeshId, Placement, Scene, push_distinct};
use geometry::Geometry;
use glam::{Mat4, Quat, Vec3};
use roxmltree::Node;
use std::collections::HashMap;
use std::path::Path;
use xml::{Ctx, child, children};

/// Deepest `<node>`/`<instance_node>` nesting followed; deeper means a reference cycle.
const MAX_DEPTH: usize = 256;

/// Reads a COLLADA file.
pub(crate) fn load(path: &Path, files: &Files) -> Result<Scene, LoadError> {
    let bytes = files.read_scene(path)?;
    // The document tree takes a few times the text: charged once more.
    files.charge(path, "", 2 * bytes.len() as u64, "the XML document tree")?;
    // Some exporters write Latin-1 names; read them with replacement characters rather
    // than refuse the file.
    parse(path, &String::from_utf8_lossy(&bytes), files)
}

/// Reads the text of a COLLADA file; `path` names it in errors and anchors the image
/// files it references.
fn parse(path: &Path, text: &str, files: &Files) -> Result<Scene, LoadError> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, options).map_err(|e| {
        // roxmltree reports the end of the input at its placeholder position 1:1; the
        // place to look at is where the file stops.
        let location = if matches!(e, roxmltree::Error::UnexpectedEndOfStream) {
            format!("line {} (end of file)", text.lines().count().max(1))
        } else {
            let pos = e.pos();
            format!("line {}, column {}", pos.row, pos.col)
        };
        LoadError::at(path, location, format!("malformed XML: {e}"))
            .with_hint("the file looks cut short or has an unclosed element")
    })?;
    let root = doc.root_element();
    if root.tag_name().name() != "COLLADA" {
        return Err(LoadError::at(
            path,
            "line 1",
            format!(
                "expected a <COLLADA> document, found <{}>",
                root.tag_name().name()
            ),
        ));
    }
    let ctx = Ctx::new(path, &doc, files);
    let mut builder = Builder {
        ctx: &ctx,
        scene: Scene::default(),
        geometries: HashMap::new(),
        meshes: HashMap::new(),
        materials: HashMap::new(),
        texture_cache: HashMap::new(),
    };
    let (meter, up) = asset(&ctx, root)?;
    builder.scene.up = up;
    let visual_scene = visual_scene(&ctx, root)?;
    let top = Mat4::from_scale(Vec3::splat(meter));
    let mut names = Vec::new();
    for node in children(visual_scene, "node") {
        builder.node(node, &top, &mut names, None, 0)?;
    }
    Ok(builder.scene)
}

/// `<asset>`: metres per unit and the up axis.
fn asset(ctx: &Ctx, root: Node) -> Result<(f32, Vec3), LoadError> {
    let Some(asset) = child(root, "asset") else {
        return Ok((1.0, Vec3::Y));
    };
    let meter = match child(asset, "unit").and_then(|u| u.attribute("meter").map(|m| (u, m))) {
        Some((unit, m)) => match m.trim().parse::<f32>() {
            Ok(v) if v > 0.0 && v.is_finite() => v,
            _ => return Err(ctx.error(unit, format!("meter=\"{m}\" is not a positive number"))),
        },
        None => 1.0,
    };
    let up = match child(asset, "up_axis") {
        Some(n) => match n.text().map(str::trim) {
            Some("X_UP") => Vec3::X,
            Some("Y_UP") => Vec3::Y,
            Some("Z_UP") => Vec3::Z,
            other => {
                return Err(ctx.error(
                    n,
                    format!(
                        "expected X_UP, Y_UP or Z_UP, found '{}'",
                        other.unwrap_or("")
                    ),
                ));
            }
        },
        None => Vec3::Y,
    };
    Ok((meter, up))
}

/// The visual scene `<scene><instance_visual_scene>` names, else the first one.
fn visual_scene<'a, 'i>(ctx: &Ctx<'a, 'i>, root: Node<'a, 'i>) -> Result<Node<'a, 'i>, LoadError> {
    if let Some(instance) = xml::path(root, &["scene", "instance_visual_scene"])
        && let Some(url) = instance.attribute("url")
    {
        return ctx.resolve(url, "visual_scene", instance);
    }
    child(root, "library_visual_scenes")
        .and_then(|l| child(l, "visual_scene"))
        .ok_or_else(|| {
            LoadError::new(
                ctx.path,
                "the file has no <visual_scene>: there is nothing to place",
            )
        })
}

/// The node's own transform: its transformation elements composed in document order
/// (COLLADA 1.4.1 §5 "node": each post-multiplies the ones before it).
fn local_transform(ctx: &Ctx, node: Node) -> Result<Mat4, LoadError> {
    let mut m = Mat4::IDENTITY;
    for t in node.children().filter(|c| c.is_element()) {
        let step = match t.tag_name().name() {
            // Row-major in the file; glam is column-major.
            "matrix" => Mat4::from_cols_array(&ctx.floats_n::<16>(t)?).transpose(),
            "translate" => Mat4::from_translation(Vec3::from_array(ctx.floats_n::<3>(t)?)),
            "scale" => Mat4::from_scale(Vec3::from_array(ctx.floats_n::<3>(t)?)),
            "rotate" => {
                let [x, y, z, degrees] = ctx.floats_n::<4>(t)?;
                let axis = Vec3::new(x, y, z);
                if axis.length_squared() == 0.0 {
                    return Err(ctx.error(t, "the rotation axis is zero"));
                }
                Mat4::from_quat(Quat::from_axis_angle(
                    axis.normalize(),
                    degrees.to_radians(),
                ))
            }
            "lookat" => {
                let v = ctx.floats_n::<9>(t)?;
                let eye = Vec3::new(v[0], v[1], v[2]);
                let target = Vec3::new(v[3], v[4], v[5]);
                let up = Vec3::new(v[6], v[7], v[8]);
                // The node's frame: −Z toward the target, +Y toward up, at the eye.
                let f = (target - eye).normalize_or_zero();
                let side = f.cross(up).normalize_or_zero();
                if f == Vec3::ZERO || side == Vec3::ZERO {
                    return Err(ctx.error(t, "eye, target and up do not define a view"));
                }
                Mat4::from_cols(
                    side.extend(0.0),
                    side.cross(f).extend(0.0),
                    (-f).extend(0.0),
                    eye.extend(1.0),
                )
            }
            "skew" => {
                ctx.warn(t, "<skew> is not supported; ignored");
                Mat4::IDENTITY
            }
            _ => continue,
        };
        m *= step;
    }
    Ok(m)
}

/// Walks the node tree, building meshes per (geometry, bound materials) once.
struct Builder<'c, 'a, 'i> {
    ctx: &'c Ctx<'a, 'i>,
    scene: Scene,
    geometries: HashMap<&'a str, Geometry>,
    meshes: HashMap<(&'a str, Vec<MaterialId>), MeshId>,
    /// Scene material of each COLLADA material id (`""`: the default grey).
    materials: HashMap<String, MaterialId>,
    texture_cache: effect::TextureCache,
}

impl<'a, 'i> Builder<'_, 'a, 'i> {
    /// Places a node and its subtree. `names` are the named ancestors; `placement` the
    /// placement rectangle being collected when inside a `*__Geometry` node.
    fn node(
        &mut self,
        node: Node<'a, 'i>,
        parent: &Mat4,
        names: &mut Vec<String>,
        placement: Option<usize>,
        depth: usize,
    ) -> Result<(), LoadError> {
        let ctx = self.ctx;
        if depth > MAX_DEPTH {
            return Err(ctx.error(
                node,
                format!("nodes nest deeper than {MAX_DEPTH}: an <instance_node> cycle?"),
            ));
        }
        let world = *parent * local_transform(ctx, node)?;
        let name = node.attribute("name").or(node.attribute("id"));
        let placement = match (placement, name) {
            (None, Some(n)) if crate::model::is_placement_name(n) => {
                self.scene.placements.push(Placement {
                    name: n.to_string(),
                    vertices: Vec::new(),
                });
                Some(self.scene.placements.len() - 1)
            }
            (p, _) => p,
        };
        if let Some(n) = name {
            names.push(n.to_string());
        }
        let result = self.contents(node, &world, names, placement, depth);
        if name.is_some() {
            names.pop();
        }
        result
    }

    /// The instances and child nodes of a node.
    fn contents(
        &mut self,
        node: Node<'a, 'i>,
        world: &Mat4,
        names: &mut Vec<String>,
        placement: Option<usize>,
        depth: usize,
    ) -> Result<(), LoadError> {
        let ctx = self.ctx;
        let own_name = node.attribute("name").or(node.attribute("id"));
        for item in node.children().filter(|c| c.is_element()) {
            let url = || {
                item.attribute("url")
                    .ok_or_else(|| ctx.error(item, "this instance needs a url"))
            };
            match item.tag_name().name() {
                "node" => self.node(item, world, names, placement, depth + 1)?,
                "instance_node" => {
                    let target = ctx.resolve(url()?, "node", item)?;
                    self.node(target, world, names, placement, depth + 1)?;
                }
                "instance_geometry" => {
                    let geometry = ctx.resolve(url()?, "geometry", item)?;
                    self.instance_geometry(item, geometry, world, names, own_name, placement)?;
                }
                "instance_light" => {
                    let light = ctx.resolve(url()?, "light", item)?;
                    let name = own_name.or(light.attribute("name")).unwrap_or("light");
                    if let Some(l) = light::light(ctx, light, name, world)? {
                        self.scene.lights.push(l);
                    }
                }
                "instance_camera" => {
                    let camera = ctx.resolve(url()?, "camera", item)?;
                    let name = own_name.or(camera.attribute("name")).unwrap_or("camera");
                    if let Some(c) = light::camera(ctx, camera, name, world)? {
                        self.scene.cameras.push(c);
                    }
                }
                "instance_controller" => {
                    ctx.warn(item, "skinned and morphed meshes are not read; skipped")
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Places one `<instance_geometry>`, or adds its vertices to a placement rectangle.
    fn instance_geometry(
        &mut self,
        item: Node<'a, 'i>,
        geometry: Node<'a, 'i>,
        world: &Mat4,
        names: &[String],
        own_name: Option<&str>,
        placement: Option<usize>,
    ) -> Result<(), LoadError> {
        let ctx = self.ctx;
        let id = geometry.attribute("id").unwrap_or("");
        if !self.geometries.contains_key(id) {
            let g = geometry::read(ctx, geometry)?;
            self.geometries.insert(id, g);
        }
        let g = &self.geometries[id];
        if let Some(p) = placement {
            let vertices = &mut self.scene.placements[p].vertices;
            push_distinct(
                vertices,
                g.outline.iter().map(|v| world.transform_point3(*v)),
            );
            return Ok(());
        }
        if g.triangles.is_empty() {
            return Ok(());
        }
        // Material symbol → material id, from <bind_material>.
        let bindings: HashMap<&str, &str> = xml::path(item, &["bind_material", "technique_common"])
            .into_iter()
            .flat_map(|t| children(t, "instance_material"))
            .filter_map(|m| Some((m.attribute("symbol")?, m.attribute("target")?)))
            .collect();
        let symbols = g.symbols.clone();
        let mut ids = Vec::with_capacity(symbols.len());
        for symbol in &symbols {
            let target = match bindings.get(symbol.as_str()) {
                Some(t) => t.strip_prefix('#').unwrap_or(t).to_string(),
                // Unbound symbols: some exporters use the material id itself.
                None if !symbol.is_empty() => {
                    if ctx
                        .by_id(symbol)
                        .is_none_or(|n| n.tag_name().name() != "material")
                    {
                        ctx.warn(
                            item,
                            &format!("material symbol '{symbol}' is not bound; using grey"),
                        );
                        String::new()
                    } else {
                        symbol.clone()
                    }
                }
                None => String::new(),
            };
            ids.push(self.material(&target, item)?);
        }
        let key = (id, ids.clone());
        let mesh = match self.meshes.get(&key) {
            Some(&m) => m,
            None => {
                let g = &self.geometries[id];
                let mesh = Mesh {
                    positions: g.positions.clone(),
                    uvs: g.uvs.clone(),
                    triangles: g.triangles.clone(),
                    materials: g
                        .triangle_symbols
                        .iter()
                        .map(|&s| ids[s as usize])
                        .collect(),
                };
                let m = self.scene.add_mesh(mesh);
                self.meshes.insert(key, m);
                m
            }
        };
        let name = own_name
            .or(geometry.attribute("name"))
            .unwrap_or(id)
            .to_string();
        let instance = self.scene.add_instance(&name, mesh, *world);
        for ancestor in names {
            self.scene.add_to_surface(ancestor, instance);
        }
        Ok(())
    }

    /// The scene material of a COLLADA material id (`""`: default grey), read once.
    fn material(&mut self, id: &str, from: Node) -> Result<MaterialId, LoadError> {
        if let Some(&m) = self.materials.get(id) {
            return Ok(m);
        }
        let material = if id.is_empty() {
            Material::diffuse("default", Vec3::splat(effect::DEFAULT_REFLECTANCE))
        } else {
            let node = self.ctx.resolve(id, "material", from)?;
            effect::read(
                self.ctx,
                node,
                &mut self.scene.textures,
                &mut self.texture_cache,
            )?
        };
        let m = self.scene.add_material(material);
        self.materials.insert(id.to_string(), m);
        Ok(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hostile edits of a file that uses most of the reader (number lists, indices,
    /// counts, references, transforms, lights) give errors, never a panic.
    #[test]
    fn no_panic_under_byte_edits() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/collada/textured/scene.dae");
        let text = std::fs::read_to_string(&path).unwrap();
        let body = text.find("<library_effects>").unwrap();
        let mut bytes = text.clone().into_bytes();
        let mut errors = 0;
        // Every fifth byte, with edits taking turns, keeps the test quick in debug.
        let edits = [b'-', b'9', b'#', b' ', b'<'];
        for (k, i) in (body..bytes.len()).step_by(5).enumerate() {
            let original = bytes[i];
            bytes[i] = edits[k % edits.len()];
            let edited = String::from_utf8_lossy(&bytes);
            let files = Files::new(&path, &crate::load::LoadOptions::default());
            errors += usize::from(parse(&path, &edited, &files).is_err());
            bytes[i] = original;
        }
        assert!(errors > 0);
    }
}
