//! The glTF 2.0 loader: `.gltf` with embedded (`data:` URI) or external buffers, and
//! `.glb`.
//!
//! What is read (DESIGN.md §1): triangle meshes named by node (else mesh) name, a name
//! covering its node's descendants; world transforms from TRS or matrix hierarchies;
//! metallic-roughness materials as diffuse, mirror, glass, emitter or hole
//! (module `material`); KHR_lights_punctual lights in cd and lx; EXT_lights_ies luminaires
//! from IES profiles (module `ies`); perspective cameras; and
//! `*__Geometry` placement rectangles. Positions are kept as written, +Y up.
//!
//! The JSON schema is `gltf-json`, the document model of the `gltf` crate, but not that
//! crate's importer: its validation indexes `accessors[POSITION]` unchecked, its GLB
//! reader and accessor iterators can panic on truncated or inconsistent files, and its
//! errors do not name the file. So the document is only deserialised (with the JSON path
//! of a bad value), and every index, range and count is checked here as it is used,
//! each failure a [`LoadError`] that names the place (`meshes[2].primitives[0]`).

mod accessor;
mod buffers;
mod glb;
mod ies;
mod material;
mod mesh;
mod nodes;

use crate::error::LoadError;
use crate::files::Files;
use crate::model::{MaterialId, MeshId, Scene, TextureId};
use gltf_json as json;
use std::borrow::Cow;
use std::collections::HashMap;
use std::path::Path;

/// The general hint of a file that breaks the glTF rules.
const VALIDATOR_HINT: &str = "the file breaks the glTF 2.0 rules: check it with the Khronos glTF Validator or export it again";

/// The extensions invlight reads. A file that *requires* any other (mesh compression,
/// texture transforms, other image formats) is refused rather than misread.
const SUPPORTED_REQUIRED: &[&str] = &[
    "EXT_lights_ies",
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_mesh_quantization",
];

/// Reads a glTF 2.0 scene (`.gltf` or `.glb`; the container is told by its magic bytes).
pub(crate) fn load(path: &Path, files: &Files) -> Result<Scene, LoadError> {
    let bytes = files.read_scene(path)?;
    from_bytes(path, &bytes, files)
}

/// Builds the scene from the file's bytes; `path` names it in errors and locates its
/// external files.
fn from_bytes(path: &Path, bytes: &[u8], files: &Files) -> Result<Scene, LoadError> {
    let (json_bytes, bin) = if bytes.starts_with(glb::MAGIC) {
        let g = glb::split(path, bytes)?;
        (g.json, g.bin)
    } else {
        (bytes, None)
    };
    let root = parse(path, json_bytes)?;
    let buffers = buffers::load_buffers(path, &root, bin, files)?;
    let mut builder = Builder {
        path,
        files,
        root: &root,
        buffers,
        scene: Scene::default(),
        meshes: HashMap::new(),
        materials: HashMap::new(),
        default_material: None,
        images: HashMap::new(),
        profiles: HashMap::new(),
    };
    builder.place_nodes()?;
    Ok(builder.scene)
}

/// Deserialises the JSON document and checks its version and required extensions.
fn parse(path: &Path, bytes: &[u8]) -> Result<json::Root, LoadError> {
    let de = &mut serde_json::Deserializer::from_slice(bytes);
    let root: json::Root = serde_path_to_error::deserialize(de).map_err(|e| {
        // A syntax error leaves `.?` for the key it could not read.
        let at = e.path().to_string().trim_end_matches(".?").to_string();
        let inner = e.into_inner();
        let message = if inner.is_syntax() || inner.is_eof() {
            format!("malformed JSON: {inner}")
        } else {
            format!("unexpected value: {inner}")
        };
        LoadError::at(
            path,
            if at == "." || at == "?" {
                String::new()
            } else {
                at
            },
            message,
        )
        .with_hint(VALIDATOR_HINT)
    })?;
    let version = &root.asset.version;
    if version.split('.').next() != Some("2") {
        return Err(LoadError::at(
            path,
            "asset.version",
            format!("glTF version {version}, 2.x expected"),
        )
        .with_hint("invlight reads glTF 2.0; convert older files with an exporter"));
    }
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !SUPPORTED_REQUIRED.contains(&e.as_str()))
    {
        return Err(LoadError::at(
            path,
            "extensionsRequired",
            format!("the file requires {ext}, which invlight does not read"),
        )
        .with_hint("export again without that extension (e.g. without mesh compression)"));
    }
    Ok(root)
}

/// The scene under construction, with the document it comes from and what has already
/// been converted (glTF index → scene id), so shared meshes, materials and images are
/// converted once.
struct Builder<'a> {
    /// The file, for errors.
    path: &'a Path,
    /// Its folder tree and the memory budget.
    files: &'a Files,
    /// The parsed document.
    root: &'a json::Root,
    /// `buffers[i]`'s bytes.
    buffers: Vec<Cow<'a, [u8]>>,
    /// The result.
    scene: Scene,
    /// (glTF mesh, mirrored) → scene mesh (`None`: no triangles).
    meshes: HashMap<(usize, bool), Option<MeshId>>,
    /// glTF material → scene material.
    materials: HashMap<usize, MaterialId>,
    /// glTF's default material, made when a primitive has none.
    default_material: Option<MaterialId>,
    /// glTF image → scene texture.
    images: HashMap<usize, TextureId>,
    /// `EXT_lights_ies` profile → its table, shared by the nodes that place it.
    profiles: HashMap<usize, std::sync::Arc<crate::photometry::Photometry>>,
}

impl Builder<'_> {
    /// An error at `location` in this file, with the validator hint.
    fn err(&self, location: &str, message: impl Into<String>) -> LoadError {
        LoadError::at(self.path, location, message).with_hint(VALIDATOR_HINT)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::LoadOptions;
    use serde_json::Value;

    fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Scene, LoadError> {
        super::from_bytes(path, bytes, &Files::new(path, &LoadOptions::default()))
    }

    const GLB: &[u8] = include_bytes!("../../../tests/data/gltf/hierarchy.glb");
    const GLTF: &str = include_str!("../../../tests/data/gltf/hierarchy.gltf");

    /// Bytes of a .glb inverted one at a time — the header, chunk headers and every
    /// binary byte, and every 16th JSON byte (numbers in the JSON get their own test):
    /// each file loads or fails, none panics (the loader's promise; a panic fails the
    /// test).
    #[test]
    fn no_byte_flip_panics() {
        let path = Path::new("mutant.glb");
        let json_end = 20 + u32::from_le_bytes([GLB[12], GLB[13], GLB[14], GLB[15]]) as usize;
        let mut bytes = GLB.to_vec();
        let mut failed = 0;
        for i in (0..bytes.len()).filter(|&i| i < 20 || i >= json_end || i % 16 == 0) {
            bytes[i] ^= 0xFF;
            failed += from_bytes(path, &bytes).is_err() as usize;
            bytes[i] ^= 0xFF;
        }
        assert!(from_bytes(path, &bytes).is_ok());
        assert!(failed > 0);
    }

    /// Every number of the JSON replaced by hostile values (out-of-range indices, huge
    /// counts, offsets past the end, zero): each file loads or fails, none panics.
    #[test]
    fn no_hostile_number_panics() {
        /// JSON pointers (RFC 6901) of every number under `v`.
        fn numbers(v: &Value, at: String, out: &mut Vec<String>) {
            match v {
                Value::Number(_) => out.push(at),
                Value::Array(a) => {
                    for (i, x) in a.iter().enumerate() {
                        numbers(x, format!("{at}/{i}"), out)
                    }
                }
                Value::Object(o) => {
                    for (k, x) in o {
                        numbers(x, format!("{at}/{k}"), out)
                    }
                }
                _ => {}
            }
        }
        let path = Path::new("mutant.gltf");
        let mut doc: Value = serde_json::from_str(GLTF).unwrap();
        let mut pointers = Vec::new();
        numbers(&doc, String::new(), &mut pointers);
        assert!(pointers.len() > 100);
        let hostile = [0.0, 4294967295.0, 1e300];
        for p in &pointers {
            let original = doc.pointer(p).cloned();
            for &h in &hostile {
                *doc.pointer_mut(p).unwrap() = serde_json::json!(h);
                let _ = from_bytes(path, serde_json::to_string(&doc).unwrap().as_bytes());
            }
            *doc.pointer_mut(p).unwrap() = original.unwrap();
        }
        assert!(from_bytes(path, serde_json::to_string(&doc).unwrap().as_bytes()).is_ok());
    }
}
