//! Wavefront OBJ scenes with their MTL materials.
//!
//! Names: every face belongs to the current `o` object name and the current `g` group
//! names (a `g` line may list several). Faces sharing the same set of names form one
//! mesh placed by one instance; the instance belongs to the surface of each of its names,
//! so a name covers all its faces however the file interleaves them. Group names stay
//! in effect across an `o` line until the next `g`, as the specification has it. Faces
//! with neither name (before any `o`/`g`, or after a bare `g` with no object) belong to
//! the group `default`, the specification's default group name.
//!
//! Positions are kept as written (`scene.up` = +Y; `--up`/`--scale` are applied by
//! [`crate::load`]). Texture coordinates are flipped to the top-row-first convention of
//! [`crate::Texture::sample`]. Normals are ignored: the tracer takes geometric normals.
//!
//! The parser is hand-rolled over the bytes of the file (no regex, no per-line
//! allocation) because the scenes of the thesis are large: the conference room has
//! 331k triangles (DESIGN.md §6). Statements other than `v vt f o g usemtl mtllib` are
//! ignored, as the format allows (`vn s l p` and vendor extensions). Free-form curves
//! and surfaces and `\` line continuations are not supported.

mod error;
mod mtl;

use error::StatementError;
pub(crate) use mtl::energy_conserving;

use crate::error::LoadError;
use crate::files::{Files, ReadError};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::model::{MaterialId, Scene};
use glam::{Mat4, Vec2, Vec3};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::path::Path;

/// Reflectance of faces with no material (before any `usemtl`, or naming a material no
/// MTL file defines): the usual 80 % grey of modelling tools.
const DEFAULT_REFLECTANCE: f32 = 0.8;

/// Reads an OBJ file and the MTL libraries it names. Its memory is bounded by the file's
/// size (charged to the budget as it is read): every vertex, face and name it builds
/// comes from a line of it.
pub(crate) fn load(path: &Path, files: &Files) -> Result<Scene, LoadError> {
    let bytes = files.read_scene(path)?;
    parse(path, &bytes, files)
}

/// Reads the bytes of an OBJ file; `path` names it in errors and anchors its MTL files.
fn parse(path: &Path, bytes: &[u8], files: &Files) -> Result<Scene, LoadError> {
    let mut parser = Parser::new(path, files);
    for (number, line) in lines(bytes) {
        parser.line = number;
        parser.statement(line).map_err(|fault| match fault {
            Fault::Here(e) => LoadError::at(path, format!("line {number}"), e.to_string()),
            Fault::Library(e) => e,
        })?;
    }
    Ok(parser.finish())
}

/// What went wrong on a line: a fault of the line itself, or of the MTL file it names.
enum Fault {
    Here(StatementError),
    Library(LoadError),
}

impl From<StatementError> for Fault {
    fn from(e: StatementError) -> Self {
        Fault::Here(e)
    }
}

/// The lines of a file with their 1-based numbers, without line terminators.
pub(crate) fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    bytes.split(|&b| b == b'\n').enumerate().map(|(i, line)| {
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        (i + 1, line)
    })
}

/// Whitespace-separated tokens of a line, comments (`#` to the end) removed.
pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    let end = line.iter().position(|&b| b == b'#').unwrap_or(line.len());
    line[..end]
        .split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// A token as text for messages.
pub(crate) fn show(token: &[u8]) -> String {
    String::from_utf8_lossy(token).into_owned()
}

/// Parses a decimal number token.
pub(crate) fn parse_f32(token: &[u8]) -> Result<f32, StatementError> {
    std::str::from_utf8(token)
        .ok()
        .and_then(|s| s.parse::<f32>().ok())
        .filter(|v| v.is_finite())
        .ok_or_else(|| StatementError::NotANumber { token: show(token) })
}

/// Reads `n` numbers from `it`; `statement` names the statement in messages.
pub(crate) fn parse_floats<'a, const N: usize>(
    it: &mut impl Iterator<Item = &'a [u8]>,
    statement: &'static str,
) -> Result<[f32; N], StatementError> {
    let mut out = [0.0; N];
    for (i, slot) in out.iter_mut().enumerate() {
        let token = it.next().ok_or(StatementError::TooFewNumbers {
            statement,
            needed: N,
            found: i,
        })?;
        *slot = parse_f32(token)?;
    }
    Ok(out)
}

/// FxHash (rustc-hash 2's hasher): vertex keys are small integers, so a multiply-rotate
/// hash is enough and several times faster than SipHash on the 1M corners of a large
/// scene. `finish` rotates the well-mixed high bits of the product down into the low
/// bits the table indexes by; without it keys differing only in their high half collide.
#[derive(Default)]
struct FxHasher(u64);

impl Hasher for FxHasher {
    fn finish(&self) -> u64 {
        self.0.rotate_left(26)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

type FxMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// The faces of one set of names, gathered into a mesh of its own.
struct Group {
    /// `o` name first (when any), then the `g` names.
    names: Vec<String>,
    mesh: Mesh,
    /// File vertex (position index, uv index or `u32::MAX`) → mesh vertex.
    remap: FxMap<u64, u32>,
}

/// Parser state: the file's vertex pools, the current names and material, the groups.
struct Parser<'p> {
    path: &'p Path,
    files: &'p Files,
    /// The number of the line being read.
    line: usize,
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    object: Option<String>,
    groups_named: Vec<String>,
    /// Index into `groups` of the current name set, `None` until a face needs it.
    current: Option<usize>,
    groups: Vec<Group>,
    group_index: HashMap<Vec<String>, usize>,
    scene: Scene,
    material_ids: HashMap<String, MaterialId>,
    material: Option<MaterialId>,
    default_material: Option<MaterialId>,
    /// Corners of the face being read: (position, uv or `u32::MAX`).
    face: Vec<(u32, u32)>,
}

impl<'p> Parser<'p> {
    fn new(path: &'p Path, files: &'p Files) -> Self {
        Parser {
            path,
            files,
            line: 0,
            positions: Vec::new(),
            uvs: Vec::new(),
            object: None,
            groups_named: Vec::new(),
            current: None,
            groups: Vec::new(),
            group_index: HashMap::new(),
            scene: Scene::default(),
            material_ids: HashMap::new(),
            material: None,
            default_material: None,
            face: Vec::new(),
        }
    }

    /// Interprets one line.
    fn statement(&mut self, line: &[u8]) -> Result<(), Fault> {
        let mut it = tokens(line);
        let Some(keyword) = it.next() else {
            return Ok(());
        };
        match keyword {
            b"v" => {
                let [x, y, z] = parse_floats(&mut it, "v")?;
                self.positions.push(Vec3::new(x, y, z));
            }
            b"vt" => {
                let u = parse_f32(it.next().ok_or(StatementError::NoTextureCoordinate)?)?;
                let v = it.next().map(parse_f32).transpose()?.unwrap_or(0.0);
                self.uvs.push(Vec2::new(u, 1.0 - v));
            }
            b"f" => self.face_statement(it)?,
            b"o" => {
                self.object = rest_of_line(line, keyword);
                self.current = None;
            }
            b"g" => {
                self.groups_named = it.map(show).collect();
                self.current = None;
            }
            b"usemtl" => {
                let name = rest_of_line(line, keyword).unwrap_or_default();
                self.material = Some(self.material_named(&name));
            }
            b"mtllib" => {
                let names: Vec<String> = it.map(show).collect();
                for name in names {
                    self.read_library(&name).map_err(Fault::Library)?;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// `f v1 v2 v3 …` with `v`, `v/vt`, `v//vn` or `v/vt/vn` corners, triangulated as a
    /// fan (exact for the convex polygons modelling tools write).
    fn face_statement<'a>(
        &mut self,
        it: impl Iterator<Item = &'a [u8]>,
    ) -> Result<(), StatementError> {
        self.face.clear();
        for token in it {
            let mut parts = token.split(|&b| b == b'/');
            let v = parts.next().unwrap_or_default();
            let vt = parts.next().filter(|t| !t.is_empty());
            let p = resolve_index(v, self.positions.len(), "vertex")?;
            let t = match vt {
                Some(vt) => resolve_index(vt, self.uvs.len(), "texture coordinate")?,
                None => u32::MAX,
            };
            self.face.push((p, t));
        }
        if self.face.len() < 3 {
            return Err(StatementError::TooFewCorners {
                found: self.face.len(),
            });
        }
        let material = match self.material {
            Some(m) => m,
            None => self.default_material(),
        };
        let g = match self.current {
            Some(g) => g,
            None => self.enter_group(),
        };
        let group = &mut self.groups[g];
        let mut local = [0u32; 3];
        let first = group.vertex(self.face[0], &self.positions, &self.uvs);
        local[0] = first;
        local[2] = group.vertex(self.face[1], &self.positions, &self.uvs);
        for &corner in &self.face[2..] {
            local[1] = local[2];
            local[2] = group.vertex(corner, &self.positions, &self.uvs);
            group.mesh.triangles.push(local);
            group.mesh.materials.push(material);
        }
        Ok(())
    }

    /// The group of the current names, created on its first face.
    fn enter_group(&mut self) -> usize {
        let mut names: Vec<String> = self.object.iter().cloned().collect();
        for g in &self.groups_named {
            if !names.contains(g) {
                names.push(g.clone());
            }
        }
        if names.is_empty() {
            names.push("default".to_string());
        }
        let g = match self.group_index.get(&names) {
            Some(&g) => g,
            None => {
                self.groups.push(Group {
                    names: names.clone(),
                    mesh: Mesh::default(),
                    remap: FxMap::default(),
                });
                self.group_index.insert(names, self.groups.len() - 1);
                self.groups.len() - 1
            }
        };
        self.current = Some(g);
        g
    }

    fn default_material(&mut self) -> MaterialId {
        *self.default_material.get_or_insert_with(|| {
            self.scene.add_material(Material::diffuse(
                "default",
                Vec3::splat(DEFAULT_REFLECTANCE),
            ))
        })
    }

    /// The material `usemtl name` selects; an undefined name gets a grey material of
    /// that name and a warning, as other readers do.
    fn material_named(&mut self, name: &str) -> MaterialId {
        if let Some(&id) = self.material_ids.get(name) {
            return id;
        }
        eprintln!(
            "warning: {}: material '{name}' is not defined by any mtllib; using {} % grey",
            self.path.display(),
            DEFAULT_REFLECTANCE * 100.0
        );
        let id = self
            .scene
            .add_material(Material::diffuse(name, Vec3::splat(DEFAULT_REFLECTANCE)));
        self.material_ids.insert(name.to_string(), id);
        id
    }

    /// Reads an MTL library beside the OBJ file; a missing or unreadable one is only a
    /// warning, since the geometry is still usable (its faces become grey), but one
    /// outside the scene's folder or past the memory budget is an error.
    fn read_library(&mut self, name: &str) -> Result<(), LoadError> {
        let loc = format!("line {}", self.line);
        let mtl_path = self.files.resolve(self.path, &loc, name, Path::new(name))?;
        let bytes = match self.files.read(self.path, &loc, &mtl_path, None) {
            Ok(bytes) => bytes,
            Err(ReadError::Budget(e)) => return Err(e),
            Err(e) => {
                let why = match e {
                    ReadError::Io(m) => m,
                    _ => "no such file".to_string(),
                };
                eprintln!(
                    "warning: {}: cannot read the material library {}: {why}; its materials will be grey",
                    self.path.display(),
                    mtl_path.display()
                );
                return Ok(());
            }
        };
        let materials = mtl::parse(&bytes, &mtl_path, &mut self.scene.textures, self.files)?;
        for material in materials {
            let name = material.name.clone();
            let id = self.scene.add_material(material);
            self.material_ids.entry(name).or_insert(id);
        }
        Ok(())
    }

    /// Builds the scene: one mesh and one instance per name set.
    fn finish(mut self) -> Scene {
        for group in self.groups {
            let mut mesh = group.mesh;
            if mesh.uvs.iter().all(|&uv| uv == Vec2::ZERO) {
                mesh.uvs.clear();
            }
            let id = self.scene.add_mesh(mesh);
            let instance = self.scene.add_instance(&group.names[0], id, Mat4::IDENTITY);
            for name in &group.names[1..] {
                self.scene.add_to_surface(name, instance);
            }
        }
        self.scene.up = Vec3::Y;
        self.scene
    }
}

impl Group {
    /// The mesh vertex of a file corner, added on first use.
    fn vertex(&mut self, (p, t): (u32, u32), positions: &[Vec3], uvs: &[Vec2]) -> u32 {
        let key = (t as u64) << 32 | p as u64;
        let mesh = &mut self.mesh;
        *self.remap.entry(key).or_insert_with(|| {
            mesh.positions.push(positions[p as usize]);
            mesh.uvs.push(if t == u32::MAX {
                Vec2::ZERO
            } else {
                uvs[t as usize]
            });
            (mesh.positions.len() - 1) as u32
        })
    }
}

/// The text after the keyword, trimmed (names may contain spaces).
fn rest_of_line(line: &[u8], keyword: &[u8]) -> Option<String> {
    let end = line.iter().position(|&b| b == b'#').unwrap_or(line.len());
    let start = line
        .windows(keyword.len())
        .position(|w| w == keyword)
        .map_or(0, |i| i + keyword.len());
    let name = show(line[start..end].trim_ascii());
    (!name.is_empty()).then_some(name)
}

/// An OBJ index: 1-based, or negative counting back from the last element read.
fn resolve_index(token: &[u8], len: usize, what: &'static str) -> Result<u32, StatementError> {
    let (negative, digits) = match token.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, token),
    };
    if digits.is_empty() || digits.len() > 10 || !digits.iter().all(u8::is_ascii_digit) {
        return Err(StatementError::NotAnIndex {
            what,
            token: show(token),
        });
    }
    let n = digits.iter().fold(0u64, |n, &d| n * 10 + (d - b'0') as u64);
    let index = if negative {
        (len as u64).checked_sub(n).filter(|_| n > 0)
    } else {
        n.checked_sub(1)
    };
    match index {
        Some(i) if i < len as u64 => Ok(i as u32),
        _ => Err(StatementError::IndexOutOfRange {
            what,
            token: show(token),
            defined: len,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::LoadOptions;

    fn parse(path: &Path, bytes: &[u8]) -> Result<Scene, LoadError> {
        super::parse(path, bytes, &Files::new(path, &LoadOptions::default()))
    }

    #[test]
    fn indices_resolve_absolute_and_relative() {
        assert_eq!(resolve_index(b"1", 4, "vertex"), Ok(0));
        assert_eq!(resolve_index(b"4", 4, "vertex"), Ok(3));
        assert_eq!(resolve_index(b"-1", 4, "vertex"), Ok(3));
        assert_eq!(resolve_index(b"-4", 4, "vertex"), Ok(0));
        assert!(resolve_index(b"0", 4, "vertex").is_err());
        assert!(resolve_index(b"5", 4, "vertex").is_err());
        assert!(resolve_index(b"-5", 4, "vertex").is_err());
        assert!(resolve_index(b"-0", 4, "vertex").is_err());
        assert!(resolve_index(b"1.5", 4, "vertex").is_err());
        assert!(resolve_index(b"99999999999999999999", 4, "vertex").is_err());
    }

    /// Hostile edits of a file using every statement read (with its MTL and texture)
    /// give errors, never a panic.
    #[test]
    fn no_panic_under_byte_edits() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/obj/names.obj");
        let mut bytes = std::fs::read(&path).unwrap();
        let mut errors = 0;
        for i in 0..bytes.len() {
            let original = bytes[i];
            for b in [b'-', b'0', b'/', b' ', b'\n'] {
                bytes[i] = b;
                errors += usize::from(parse(&path, &bytes).is_err());
            }
            bytes[i] = original;
        }
        assert!(errors > 0);
    }

    /// Every prefix of a real file loads or gives an error naming it; none panics.
    #[test]
    fn truncations_never_panic() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/obj/CornellBox-Original.obj");
        let bytes = std::fs::read(&path).unwrap();
        for len in 0..bytes.len() {
            if let Err(e) = parse(&path, &bytes[..len]) {
                assert_eq!(e.path, path);
                assert!(e.location.starts_with("line "), "{e}");
            }
        }
    }

    #[test]
    fn rest_of_line_keeps_inner_spaces() {
        assert_eq!(
            rest_of_line(b"usemtl  my mat  # c", b"usemtl"),
            Some("my mat".to_string())
        );
        assert_eq!(rest_of_line(b"o", b"o"), None);
    }
}
