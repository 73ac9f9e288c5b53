//! Loading a scene file: the format is chosen by extension, then the units are applied.

use crate::error::LoadError;
use crate::files::Files;
use crate::model::Scene;
use glam::{Mat4, Vec3};
use std::path::Path;

/// The up axis a file was authored with, when the file does not say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UpAxis {
    /// +Y up (glTF, most OBJ exports).
    Y,
    /// +Z up (Blender, most architectural tools).
    Z,
}

impl UpAxis {
    /// The axis as a unit vector.
    pub fn vector(self) -> Vec3 {
        match self {
            UpAxis::Y => Vec3::Y,
            UpAxis::Z => Vec3::Z,
        }
    }
}

/// An `--up` value other than `y` or `z`: the text given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownUpAxis(pub String);

impl std::fmt::Display for UnknownUpAxis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "'{}': expected y or z", self.0)
    }
}

impl std::error::Error for UnknownUpAxis {}

impl std::str::FromStr for UpAxis {
    type Err = UnknownUpAxis;

    /// `y` or `z`, as `--up` gives it.
    fn from_str(s: &str) -> Result<UpAxis, UnknownUpAxis> {
        match s {
            "y" | "Y" => Ok(UpAxis::Y),
            "z" | "Z" => Ok(UpAxis::Z),
            _ => Err(UnknownUpAxis(s.to_string())),
        }
    }
}

/// How to read a file authored in other units or axes, and how far to trust it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadOptions {
    /// Metres per file unit, applied after the file's own unit (COLLADA `<unit meter>`).
    pub scale: f32,
    /// Up axis, overriding what the file says (glTF: Y; COLLADA: `<up_axis>`; OBJ: Y).
    pub up: Option<UpAxis>,
    /// Bytes the load may allocate from the sizes the file declares (the file itself,
    /// buffers, accessors, decoded textures); a file that asks for more is refused with
    /// the figure before anything is allocated. Default: half of the machine's memory
    /// (on Linux the smaller of `MemTotal` and the control group's `memory.max`; 4 GiB
    /// where neither can be read).
    pub max_memory: u64,
    /// Lets the file reference files anywhere (absolute paths, `..` out of its folder,
    /// links that lead out). Off by default: a scene file may come from anyone, and only
    /// files in its own folder tree are read. Device files and pipes are refused either
    /// way.
    pub allow_outside_paths: bool,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            scale: 1.0,
            up: None,
            max_memory: crate::files::default_max_memory(),
            allow_outside_paths: false,
        }
    }
}

/// [`load`], then gives the named lights their photometric files
/// ([`Scene::set_luminaires`]; `--luminaire NAME=FILE`, a problem's `<luminaire>`).
pub fn load_with(
    path: &Path,
    options: &LoadOptions,
    luminaires: &[crate::Luminaire],
) -> Result<Scene, LoadError> {
    let mut scene = load(path, options)?;
    scene.set_luminaires(path, luminaires, options)?;
    Ok(scene)
}

/// Reads a glTF (`.gltf`, `.glb`), COLLADA (`.dae`) or Wavefront (`.obj`) scene.
pub fn load(path: &Path, options: &LoadOptions) -> Result<Scene, LoadError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .unwrap_or_default();
    if path.is_dir() {
        return Err(LoadError::new(path, "is a folder, not a scene file")
            .with_hint("name the .gltf, .glb, .dae or .obj file inside it"));
    }
    if !path.is_file() {
        return Err(LoadError::new(path, "no such file")
            .with_hint("check the path; relative paths are taken from the current directory"));
    }
    let files = Files::new(path, options);
    let mut scene = match ext.as_str() {
        "gltf" | "glb" => crate::gltf::load(path, &files)?,
        "dae" => crate::collada::load(path, &files)?,
        "obj" => crate::obj::load(path, &files)?,
        _ => {
            return Err(LoadError::new(
                path,
                format!("unknown scene format '.{ext}'"),
            )
            .with_hint("invlight reads glTF 2.0 (.gltf, .glb), COLLADA (.dae) and Wavefront OBJ (.obj)"));
        }
    };
    if let Some(up) = options.up {
        scene.up = up.vector();
    }
    if options.scale != 1.0 {
        scale_scene(&mut scene, options.scale);
    }
    // After the scale: `--scale 1e30` must not carry a valid file out of range.
    scene
        .validate()
        .map_err(|e| LoadError::at(path, e.place(), e.to_string()).with_hint(e.hint()))?;
    Ok(scene)
}

/// Scales the whole scene about the origin: positions and lengths by `s`; point, spot
/// and goniometric intensities are kept, and so is a luminous opening's size, in
/// metres already (a lamp stays the same lamp in another unit system).
pub(crate) fn scale_scene(scene: &mut Scene, s: f32) {
    let m = Mat4::from_scale(Vec3::splat(s));
    for inst in &mut scene.instances {
        inst.transform = m * inst.transform;
    }
    for light in &mut scene.lights {
        if let Some(position) = light.kind.position_mut() {
            *position *= s;
        }
    }
    for cam in &mut scene.cameras {
        cam.position *= s;
    }
    for p in &mut scene.placements {
        for v in &mut p.vertices {
            *v *= s;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::UpAxis;

    #[test]
    fn up_axes_are_y_or_z() {
        assert_eq!("Z".parse::<UpAxis>(), Ok(UpAxis::Z));
        assert_eq!(
            "x".parse::<UpAxis>().unwrap_err().to_string(),
            "'x': expected y or z"
        );
    }
}
