//! Ray casting against an [`invlight_scene::Scene`] for photon tracing and rendering.
//!
//! [`Accel`] keeps one compressed 8-wide BVH per mesh in object space (bottom level,
//! built once) and one over the instances' world bounds (top level), so moving an
//! object, a lamp or a hole rebuilds only the top level ([`Accel::update_instances`]),
//! as OptiX transform nodes did for the thesis' ILPSolver (DESIGN.md §7). The trees are
//! built by the `obvhs` crate (PLOC, Meister & Bittner 2018, into Ylitie et al.'s
//! CWBVH, 2017); traversal and the watertight triangle test (Woop et al. 2013), eight
//! triangles of a leaf at a time with AVX2, are here.
//!
//! - [`Accel::with_movable`] bakes every instance the caller will not move into one
//!   world-space BVH and keeps only the movable ones as instances: many overlapping
//!   static instances otherwise cost a third of the ray rate (BENCHMARKS.md, "Ray casting").
//!   Rays walk the baked tree first and the movable instances' small top level after it,
//!   so they pay for a movable object only where they reach its box before the static
//!   hit (BENCHMARKS.md, "Engine speed").
//! - [`Accel::with_preset`] chooses the builder's effort among obvhs's presets
//!   ([`BuildPreset`]); the others build obvhs's medium preset, and traversal gives the
//!   same hits on every tree.
//! - [`Accel::interaction`] reads the hit surface from the scene's own meshes, which the
//!   structure does not copy.
//! - Every triangle blocks from both sides; [`Interaction::normal`] still tells the front
//!   (counter-clockwise) side, which emitters emit from.
//! - Holes (thesis §4.1, fig. 4.2): instances of hole materials are not traced; each
//!   makes its world-space box a volume in which every surface is transparent.
//! - Calculation surfaces ([`invlight_scene::Scene::calculation_surfaces`]) are in no
//!   tree: every ray passes them, and [`Accel::crossings`] lists where a ray crossed
//!   them before its hit, so photons can be counted there without being stopped.
//! - Rays leaving a surface come from [`Interaction::spawn`] / [`Interaction::spawn_to`],
//!   which offset the origin (Wächter & Binder 2019) so they never re-hit it.
//! - [`Accel`] is `Send + Sync`; tracing allocates nothing.
//!
//! ```
//! use invlight_scene::{Scene, Mesh, Material, Mat4, Vec3};
//! use invlight_trace::{Accel, Ray};
//! let mut scene = Scene::default();
//! let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
//! let quad = scene.add_mesh(Mesh::quad(
//!     [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
//!     grey,
//! ));
//! scene.add_instance("Floor", quad, Mat4::from_translation(Vec3::new(0.0, 0.0, -2.0)));
//! let accel = Accel::new(&scene);
//! let ray = Ray::new(Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z);
//! let hit = accel.intersect(&ray).unwrap();
//! assert!((hit.t - 3.0).abs() < 1e-6);
//! let surface = accel.interaction(&scene, &ray, &hit);
//! assert_eq!(surface.normal, Vec3::Z);
//! assert!(!accel.occluded(&surface.spawn(Vec3::Z)));
//! ```
#![deny(missing_docs)]

mod accel;
mod holes;
mod ray;
mod triangle;
mod wide;

pub use accel::{
    Accel, AccelStats, BUILD_BYTES_PER_TRIANGLE, BYTES_PER_INSTANCE, BuildPreset, crossing_slack,
};
pub use holes::HOLE_THICKNESS;
pub use ray::{Hit, Interaction, OFFSET_SCALE, Ray, SHADOW_EPSILON, offset_point};
