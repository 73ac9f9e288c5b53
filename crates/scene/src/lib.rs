//! The scene model of invlight: named triangle meshes with world transforms, materials,
//! lights and cameras, in photometric units, and the loaders that build it from glTF 2.0,
//! COLLADA and Wavefront OBJ files and read luminaires' photometric files.
//!
//! The core types:
//! - [`Scene`]: everything that is traced: [`Mesh`]es in object space placed by
//!   [`Instance`]s, [`Material`]s, punctual and directional [`Light`]s, [`Camera`]s, the
//!   named [`Surface`]s a user addresses, and the [`Placement`] rectangles of problem files.
//! - [`MeshId`], [`MaterialId`], [`TextureId`], [`InstanceId`], [`SurfaceId`],
//!   [`LightId`]: how the scene's lists refer to one another. Each indexes its own list
//!   and no other (`scene.meshes[scene.instances[id].mesh]`), so an id handed to the
//!   wrong list does not compile; each is a `u32` underneath.
//! - [`Calculation`]: calculation surfaces, which receive light without touching it
//!   (`--calculation-surface NAME`, a problem's `<calculationSurface>`), and the
//!   [`Workplane`]s built over the floor as such ([`Scene::set_calculation`]).
//! - [`load`]: reads a scene file, choosing the format from its extension.
//! - [`daylight`]: sites and their compass, dates and times, the sun's position (NREL
//!   SPA) and clear-sky illuminance, and CIE skies with their sampling distributions
//!   (docs/daylight.md).
//! - [`Photometry`]: a luminaire's candela table from an IES LM-63 or EULUMDAT file
//!   ([`read_photometry`]), which a [`LightKind::Goniometric`] light emits; glTF files
//!   place them by `EXT_lights_ies`, [`Scene::set_photometry`] puts one in place of a
//!   point or spot light, and [`Scene::set_luminaires`] does so from the files a
//!   [`Luminaire`] names (`--luminaire NAME=FILE`, a problem file's `<luminaire>`).
//!
//! Units (DESIGN.md §1): lengths in metres; point and spot intensities in candela,
//! directional illuminance in lux, emission as luminance in cd/m². Colours are linear
//! RGB whose Rec.709 luminance ([`luminance`]) is the photometric quantity, so a white
//! light gives lux.
//!
//! ```
//! use invlight_scene::{Scene, Mesh, Instance, Material, Mat4, Vec3};
//! let mut scene = Scene::default();
//! let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
//! let quad = scene.add_mesh(Mesh::quad(
//!     [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
//!     grey,
//! ));
//! scene.add_instance("Floor", quad, Mat4::IDENTITY);
//! assert_eq!(scene.surface_area(scene.surface("Floor").unwrap()), 1.0);
//! ```
#![deny(missing_docs)]

mod areas;
mod atomic;
mod calculation;
mod collada;
mod cylindrical;
pub mod daylight;
pub mod en12464;
mod error;
mod files;
mod gltf;
mod image_file;
mod light;
mod load;
mod lookup;
mod luminaire;
mod material;
mod mesh;
mod model;
mod obj;
mod photometry;
mod summary;
mod validate;
mod values;
mod walls;
mod world;

pub use areas::{AreaKind, BACKGROUND_BAND, ROOM_SURFACE_OFFSET, SURROUNDING_BAND, TaskArea};
pub use atomic::write_atomically;
pub use calculation::{Calculation, CalculationSurface, Workplane};
pub use cylindrical::{SEATED, SIDES as CYLINDER_SIDES};
pub use error::{Diagnostic, LoadError, PhotometryError};
pub use files::{MemorySizeError, parse_memory_size};
pub use glam::{Mat3, Mat4, Quat, Vec2, Vec3};
pub use light::{Camera, Light, LightKind, aimed_frame, luminance, tilt_factor};
pub use load::{LoadOptions, UnknownUpAxis, UpAxis, load, load_with};
pub use lookup::{known_names, nearest};
pub use luminaire::{Luminaire, LuminaireArgError};
pub use material::{Material, Rgb, Texture};
pub use mesh::Mesh;
pub use model::{
    Instance, InstanceId, LightId, MaterialId, MeshId, PLACEMENT_SUFFIX, Placement, Scene, Surface,
    SurfaceId, TextureId, is_placement_name, placement_name,
};
pub use photometry::{
    DirectionSample, LuminaireFacts, Opening, PhotometricSystem, Photometry, PhotometryFormat,
    PhotometrySource, TableError, Tilt, parse_ies, parse_ldt, read_photometry,
};
pub use summary::{CameraSummary, LightSummary, LuminaireSummary, SceneSummary, SurfaceSummary};
pub use validate::{MAX_COORDINATE, MAX_FLUX, SceneError};
pub use values::{NumberError, finite, positive};
pub use world::WorldTriangle;
