//! The ranges a scene must lie in to be traced: every number the tracer derives from it
//! (world positions, triangle areas, bounding boxes, luminous fluxes, photon powers and
//! the sums of squares behind the intervals) must stay finite in the `f32` and `f64`
//! that hold it.
//!
//! A file's numbers are checked for finiteness as they are parsed, but finite numbers
//! can still overflow once combined: a vertex at 1e20 m gives a BVH box whose surface
//! area is `inf` (obvhs then indexes out of bounds), a node translated by 3e38 m or a
//! `--scale` of 1e30 does the same in the world, and a 3e38 cd lamp has an `inf` flux,
//! which turned every estimate into NaN. So the scene is checked as a whole, in world
//! space and after `--scale`, against the bounds below, and refused with the name of
//! the thing at fault rather than traced into NaN.

use crate::light::{LightKind, luminance};
use crate::material::Rgb;
use crate::model::{MaterialId, MeshId, Scene};
use glam::{Mat4, Vec3};
use std::f64::consts::PI;
use std::fmt;

/// Largest coordinate magnitude accepted, m in the world and file units in a mesh's own
/// space (whose BVH is built there). 1e9 m is beyond any building or city (the Earth's
/// diameter is 1.3e7 m) and keeps every derived quantity far inside `f32`: a box's
/// surface area is below 6·(2e9)² ≈ 2.4e19 m², a triangle's area below 6e18 m², and the
/// SAH costs obvhs forms from them (area × primitive count) below 1e27. It bounds
/// overflow, not rounding: `f32` keeps 7 digits, so a triangle 1e9 m wide places hits
/// to within metres near its edges (rays near the diagonal of a 2e9 m floor missed it).
pub const MAX_COORDINATE: f32 = 1.0e9;

/// Largest luminous flux, lm, of one light, of one emissive surface and of all of them
/// together (a directional light counts with the flux it sends through the scene's
/// bounding disk, as photon emission sees it). Each photon carries the total flux in
/// `f32` RGB (at most ~14× the luminance for a pure blue light), and the intervals sum
/// squares of per-photon illuminances in `f64`; 1e20 lm, 10¹⁴ stadium floodlights, keeps
/// both with room to spare while a sun of 10⁵ lx over a 10⁷ m wide scene (3e19 lm)
/// still fits.
pub const MAX_FLUX: f64 = 1.0e20;

/// What puts a scene outside the range invlight traces in ([`Scene::validate`]).
#[derive(Debug, Clone, PartialEq)]
pub enum SceneError {
    /// A position (mesh vertex in its own space, world vertex, light, camera or
    /// placement corner) lies beyond [`MAX_COORDINATE`].
    Coordinate {
        /// What holds it: `surface 'Floor'`, `mesh 3`, `light 'Lamp'`, `camera 'View'`.
        place: String,
        /// `in the world` or `in the mesh's own space`.
        space: &'static str,
        /// The offending position (m, or file units in a mesh's space).
        position: Vec3,
    },
    /// An instance transform with a non-finite number.
    Transform {
        /// The surface the instance belongs to.
        place: String,
    },
    /// A light's strength, or a material's colour or emission, is negative or not
    /// finite.
    Colour {
        /// `light 'Lamp'` or `material 'Glass'`.
        place: String,
        /// Which value: `strength`, `emission`, `diffuse colour`, `mirror colour`.
        what: &'static str,
        /// Its value.
        value: Rgb,
    },
    /// A light's direction is zero or not finite, or a spot's cone angles are not
    /// `0 ≤ inner ≤ outer ≤ π/2`.
    Shape {
        /// `light 'Spot'`.
        place: String,
        /// What is wrong.
        message: String,
    },
    /// An emitter's luminous flux exceeds [`MAX_FLUX`].
    Flux {
        /// `light 'Lamp'` or `surface 'Ceiling' (material 'Glow')`.
        place: String,
        /// Its flux, lm (`inf` when it overflows even `f64`).
        flux: f64,
    },
    /// A mesh, instance, surface or material refers to something the scene does not
    /// have.
    Index {
        /// What refers.
        place: String,
        /// To what.
        message: String,
    },
    /// All emitters together exceed [`MAX_FLUX`].
    TotalFlux {
        /// The sum, lm.
        flux: f64,
        /// How many lights and emissive triangles it sums.
        emitters: usize,
    },
    /// A light of positive strength whose flux rounds to zero in `f32` (a spot whose
    /// cone is too narrow): it would emit no photon, silently.
    FluxUnderflow {
        /// `light 'Spot'`.
        place: String,
        /// Its strength (cd, or lx for a sun).
        strength: Rgb,
    },
}

impl SceneError {
    /// Where in the scene: `surface 'Floor'`, `light 'Lamp'`, …; empty for the scene as
    /// a whole.
    pub fn place(&self) -> &str {
        match self {
            SceneError::Coordinate { place, .. }
            | SceneError::Transform { place }
            | SceneError::Colour { place, .. }
            | SceneError::Shape { place, .. }
            | SceneError::Index { place, .. }
            | SceneError::Flux { place, .. }
            | SceneError::FluxUnderflow { place, .. } => place,
            SceneError::TotalFlux { .. } => "",
        }
    }

    /// How to bring the scene into range.
    pub fn hint(&self) -> String {
        match self {
            SceneError::Coordinate { .. } => format!(
                "invlight traces within ±{MAX_COORDINATE:e} m: check the file's units and \
                 --scale (a CAD export in mm needs --scale 0.001, not 1000)"
            ),
            SceneError::Transform { .. } => "export the node's transform again".into(),
            SceneError::Index { .. } => {
                "a scene built in code must keep its indices within its lists".into()
            }
            SceneError::Colour { .. } => {
                "intensities (cd), illuminances (lx), luminances (cd/m²) and colours are finite and ≥ 0"
                    .into()
            }
            SceneError::Shape { .. } => {
                "a light needs a non-zero direction and 0 ≤ inner ≤ outer ≤ π/2".into()
            }
            SceneError::Flux { .. } | SceneError::TotalFlux { .. } => format!(
                "invlight traces up to {MAX_FLUX:e} lm in all; the brightest real lamps give \
                 ~1e6 lm: check the file's intensity units"
            ),
            SceneError::FluxUnderflow { .. } => {
                "widen the spot's outer cone (or remove the light): so narrow a cone emits nothing"
                    .into()
            }
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Coordinate {
                space, position, ..
            } => {
                let unit = if *space == "in the world" {
                    " m"
                } else {
                    " file units"
                };
                write!(
                    f,
                    "a position {space}, ({}, {}, {}), lies beyond ±{MAX_COORDINATE:e}{unit}",
                    number(position.x),
                    number(position.y),
                    number(position.z)
                )
            }
            SceneError::Transform { .. } => write!(f, "its transform has a non-finite number"),
            SceneError::Colour { what, value, .. } => write!(
                f,
                "its {what} ({}, {}, {}) is negative or not finite",
                value.x, value.y, value.z
            ),
            SceneError::Shape { message, .. } | SceneError::Index { message, .. } => {
                f.write_str(message)
            }
            SceneError::Flux { flux, .. } => write!(
                f,
                "its luminous flux, {flux:.3e} lm, exceeds the {MAX_FLUX:e} lm invlight traces"
            ),
            SceneError::TotalFlux { flux, emitters } => write!(
                f,
                "the {emitters} emitters give {flux:.3e} lm together, more than the \
                 {MAX_FLUX:e} lm invlight traces"
            ),
            SceneError::FluxUnderflow { strength, .. } => write!(
                f,
                "its strength ({}, {}, {}) gives a luminous flux that rounds to 0 lm: it would \
                 emit no photon",
                strength.x, strength.y, strength.z
            ),
        }
    }
}

impl std::error::Error for SceneError {}

/// A coordinate for messages: plain when short, in exponent form when huge or tiny.
fn number(x: f32) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Whether every coordinate of `p` is finite and within [`MAX_COORDINATE`].
fn in_range(p: Vec3) -> bool {
    p.is_finite() && p.abs().max_element() <= MAX_COORDINATE
}

/// Whether a flux is within [`MAX_FLUX`] (NaN is not).
fn within_flux(flux: f64) -> bool {
    flux <= MAX_FLUX
}

/// The luminous flux of `c` (an RGB flux) in `f64`, so that the check itself cannot
/// overflow.
fn luminance64(c: Rgb) -> f64 {
    0.2126 * c.x as f64 + 0.7152 * c.y as f64 + 0.0722 * c.z as f64
}

impl Scene {
    /// Checks that the scene lies in the range invlight traces in: every position within
    /// ±[`MAX_COORDINATE`] (mesh vertices in their own space and in the world, lights,
    /// cameras, placements), finite transforms, non-negative finite colours and
    /// strengths, well-formed light directions and cones, and every emitter's luminous
    /// flux and their sum within [`MAX_FLUX`].
    ///
    /// [`crate::load`] calls it after applying `--scale`; a program that builds or moves
    /// a scene in code should call it before tracing.
    ///
    /// Cost: one pass over the mesh vertices and one box per instance; only an instance
    /// whose box leaves the range has its vertices transformed one by one (to report a
    /// real vertex, not a corner of its box), and only emissive triangles are visited per
    /// instance.
    pub fn validate(&self) -> Result<(), SceneError> {
        self.validate_indices()?;
        self.validate_materials()?;
        let mesh_bounds = self.validate_meshes()?;
        self.validate_instances(&mesh_bounds)?;
        self.validate_others()?;
        self.validate_flux()
    }

    fn validate_materials(&self) -> Result<(), SceneError> {
        let bad = |c: Rgb| !c.is_finite() || c.min_element() < 0.0;
        for m in &self.materials {
            for (what, value) in [
                ("emission", m.emission),
                ("diffuse colour", m.diffuse),
                ("mirror colour", m.specular),
            ] {
                if bad(value) {
                    return Err(SceneError::Colour {
                        place: format!("material '{}'", m.name),
                        what,
                        value,
                    });
                }
            }
        }
        Ok(())
    }

    /// Each mesh's object-space bounds (`None` when it has no vertex), checked.
    fn validate_meshes(&self) -> Result<Vec<Option<(Vec3, Vec3)>>, SceneError> {
        let mut bounds = Vec::with_capacity(self.meshes.len());
        for (m, mesh) in self.meshes.iter().enumerate() {
            let mut b: Option<(Vec3, Vec3)> = None;
            for &p in &mesh.positions {
                if !in_range(p) {
                    return Err(SceneError::Coordinate {
                        place: self.mesh_user(MeshId::from_index(m)),
                        space: "in the mesh's own space",
                        position: p,
                    });
                }
                b = Some(b.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))));
            }
            bounds.push(b);
        }
        Ok(bounds)
    }

    /// A name for mesh `m` in messages: the first surface that places it.
    fn mesh_user(&self, m: MeshId) -> String {
        match self.instances.iter().find(|i| i.mesh == m) {
            Some(i) => format!("surface '{}'", i.name),
            None => format!("mesh {m}"),
        }
    }

    fn validate_instances(&self, mesh_bounds: &[Option<(Vec3, Vec3)>]) -> Result<(), SceneError> {
        for inst in &self.instances {
            let place = || format!("surface '{}'", inst.name);
            if !inst.transform.is_finite() {
                return Err(SceneError::Transform { place: place() });
            }
            let Some(&Some((lo, hi))) = mesh_bounds.get(inst.mesh.index()) else {
                continue;
            };
            // The world image of the box holds the world image of every vertex.
            if box_corners(lo, hi, &inst.transform).all(in_range) {
                continue;
            }
            let mesh = &self.meshes[inst.mesh];
            if let Some(w) = mesh
                .positions
                .iter()
                .map(|&p| inst.transform.transform_point3(p))
                .find(|&w| !in_range(w))
            {
                return Err(SceneError::Coordinate {
                    place: place(),
                    space: "in the world",
                    position: w,
                });
            }
        }
        Ok(())
    }

    /// Lights, cameras and placements.
    fn validate_others(&self) -> Result<(), SceneError> {
        for light in &self.lights {
            let place = || format!("light '{}'", light.name);
            let (strength, direction) = match light.kind {
                LightKind::Point { intensity, .. } => (intensity, None),
                LightKind::Spot {
                    intensity,
                    direction,
                    inner,
                    outer,
                    ..
                } => {
                    if !(0.0 <= inner && inner <= outer && outer <= std::f32::consts::FRAC_PI_2) {
                        return Err(SceneError::Shape {
                            place: place(),
                            message: format!(
                                "its cone angles are inner {inner}, outer {outer} rad"
                            ),
                        });
                    }
                    (intensity, Some(direction))
                }
                LightKind::Directional {
                    illuminance,
                    direction,
                } => (illuminance, Some(direction)),
                // The frame is checked as a direction through its aim; the table's
                // candela were checked by its reader.
                LightKind::Goniometric {
                    multiplier, frame, ..
                } => (multiplier, Some(-frame.z_axis)),
            };
            if !strength.is_finite() || strength.min_element() < 0.0 {
                return Err(SceneError::Colour {
                    place: place(),
                    what: "strength",
                    value: strength,
                });
            }
            if let Some(d) = direction
                && !(d.is_finite() && d.length_squared() > 0.0)
            {
                return Err(SceneError::Shape {
                    place: place(),
                    message: format!(
                        "its direction ({}, {}, {}) is not a direction",
                        d.x, d.y, d.z
                    ),
                });
            }
            if let Some(p) = light.kind.position()
                && !in_range(p)
            {
                return Err(SceneError::Coordinate {
                    place: place(),
                    space: "in the world",
                    position: p,
                });
            }
        }
        for cam in &self.cameras {
            if !in_range(cam.position) {
                return Err(SceneError::Coordinate {
                    place: format!("camera '{}'", cam.name),
                    space: "in the world",
                    position: cam.position,
                });
            }
        }
        for p in &self.placements {
            if let Some(&v) = p.vertices.iter().find(|&&v| !in_range(v)) {
                return Err(SceneError::Coordinate {
                    place: format!("placement '{}'", p.name),
                    space: "in the world",
                    position: v,
                });
            }
        }
        Ok(())
    }

    /// Every emitter's flux and their sum, in `f64`, as photon emission will weigh them
    /// (`invlight_photon::Emitters`): lights by [`LightKind::flux`], a sun over the
    /// scene's bounding disk, a Lambertian emissive triangle by π·L·A, the sky by its
    /// ∫ L dω over the bounding disk. Runs after the
    /// position checks, so the areas and the bounding disk are finite.
    fn validate_flux(&self) -> Result<(), SceneError> {
        let mut total = 0.0f64;
        let mut emitters = 0usize;
        let radius = self.bounds().map_or(1.0, |(lo, hi)| {
            ((hi.as_dvec3() - lo.as_dvec3()).length() * 0.5).max(1e-3)
        });
        for light in &self.lights {
            let place = || format!("light '{}'", light.name);
            let flux = flux_f64(&light.kind, radius);
            if !within_flux(flux) {
                return Err(SceneError::Flux {
                    place: place(),
                    flux,
                });
            }
            // Below MAX_FLUX the f32 flux photon emission uses cannot overflow (its
            // factors are at most 4π), but it can round to zero.
            let strength = match light.kind {
                LightKind::Point { intensity, .. } | LightKind::Spot { intensity, .. } => intensity,
                LightKind::Directional { illuminance, .. } => illuminance,
                LightKind::Goniometric { multiplier, .. } => multiplier,
            };
            if strength.max_element() > 0.0 && luminance(light.kind.flux()) <= 0.0 {
                return Err(SceneError::FluxUnderflow {
                    place: place(),
                    strength,
                });
            }
            total += flux;
            emitters += 1;
        }
        let emissive: Vec<bool> = self
            .materials
            .iter()
            .map(|m| m.emission.max_element() > 0.0)
            .collect();
        let mesh_emits: Vec<bool> = self
            .meshes
            .iter()
            .map(|m| m.materials.iter().any(|&i| emissive[i.index()]))
            .collect();
        for inst in &self.instances {
            if !mesh_emits[inst.mesh.index()] {
                continue;
            }
            let mesh = &self.meshes[inst.mesh];
            let mut flux = 0.0f64;
            let mut brightest = (0.0f64, MaterialId::from_index(0));
            for (t, &m) in mesh.materials.iter().enumerate() {
                if !emissive[m.index()] {
                    continue;
                }
                let [a, b, c] = mesh
                    .triangle(t)
                    .map(|p| inst.transform.transform_point3(p).as_dvec3());
                let area = 0.5 * (b - a).cross(c - a).length();
                let f = PI * luminance64(self.materials[m].emission) * area;
                flux += f;
                emitters += 1;
                if f > brightest.0 {
                    brightest = (f, m);
                }
            }
            if !within_flux(flux) {
                return Err(SceneError::Flux {
                    place: format!(
                        "surface '{}' (material '{}')",
                        inst.name, self.materials[brightest.1].name
                    ),
                    flux,
                });
            }
            total += flux;
        }
        if let Some(sky) = &self.sky {
            let flux = sky.dome_luminance() * PI * radius * radius;
            if !within_flux(flux) {
                return Err(SceneError::Flux {
                    place: "the sky".into(),
                    flux,
                });
            }
            total += flux;
            emitters += 1;
        }
        if !within_flux(total) {
            return Err(SceneError::TotalFlux {
                flux: total,
                emitters,
            });
        }
        Ok(())
    }

    /// Refuses dangling indices (an instance's mesh, a triangle's vertices or material,
    /// a surface's instances, a material's texture), which a scene built in code can
    /// hold; the loaders never make them.
    fn validate_indices(&self) -> Result<(), SceneError> {
        let dangling = |place: String, message: String| Err(SceneError::Index { place, message });
        for (m, mesh) in self.meshes.iter().enumerate() {
            let place = || self.mesh_user(MeshId::from_index(m));
            if mesh.materials.len() != mesh.triangles.len() {
                return dangling(
                    place(),
                    format!(
                        "{} materials for {} triangles",
                        mesh.materials.len(),
                        mesh.triangles.len()
                    ),
                );
            }
            if !mesh.uvs.is_empty() && mesh.uvs.len() != mesh.positions.len() {
                return dangling(
                    place(),
                    format!(
                        "{} texture coordinates for {} vertices",
                        mesh.uvs.len(),
                        mesh.positions.len()
                    ),
                );
            }
            let n = mesh.positions.len();
            if let Some(t) = mesh
                .triangles
                .iter()
                .position(|t| t.iter().any(|&i| i as usize >= n))
            {
                return dangling(
                    place(),
                    format!("triangle {t} names a vertex past the {n} the mesh has"),
                );
            }
            let k = self.materials.len();
            if let Some(t) = mesh.materials.iter().position(|&i| i.index() >= k) {
                return dangling(
                    place(),
                    format!("triangle {t} names a material past the {k} the scene has"),
                );
            }
        }
        for inst in &self.instances {
            if inst.mesh.index() >= self.meshes.len() {
                return dangling(
                    format!("surface '{}'", inst.name),
                    format!(
                        "it places mesh {}, past the {} the scene has",
                        inst.mesh,
                        self.meshes.len()
                    ),
                );
            }
        }
        for s in &self.surfaces {
            if let Some(&i) = s
                .instances
                .iter()
                .find(|&&i| i.index() >= self.instances.len())
            {
                return dangling(
                    format!("surface '{}'", s.name),
                    format!(
                        "it covers instance {i}, past the {} the scene has",
                        self.instances.len()
                    ),
                );
            }
        }
        for m in &self.materials {
            if let Some(t) = m.texture
                && t.index() >= self.textures.len()
            {
                return dangling(
                    format!("material '{}'", m.name),
                    format!(
                        "it names texture {t}, past the {} the scene has",
                        self.textures.len()
                    ),
                );
            }
        }
        Ok(())
    }
}

/// A light's luminous flux in `f64`, so that the check itself cannot overflow: as
/// [`LightKind::flux`] for point and spot lights, and a sun's illuminance over the disk
/// of radius `radius` that photon emission sends it through.
fn flux_f64(kind: &LightKind, radius: f64) -> f64 {
    match *kind {
        LightKind::Point { intensity, .. } => 4.0 * PI * luminance64(intensity),
        LightKind::Spot {
            intensity,
            inner,
            outer,
            ..
        } => {
            let (inner, outer) = (inner as f64, (outer as f64).max(inner as f64));
            // 1 − cos θ = 2 sin²(θ/2), exact for narrow cones.
            let flat = 2.0 * (inner / 2.0).sin().powi(2);
            let ring = inner.cos() - outer.cos();
            2.0 * PI * luminance64(intensity) * (flat + ring / 3.0)
        }
        LightKind::Directional { illuminance, .. } => {
            luminance64(illuminance) * PI * radius * radius
        }
        LightKind::Goniometric {
            ref photometry,
            multiplier,
            tilt,
            ..
        } => photometry.flux() * luminance64(multiplier) * f64::from(tilt),
    }
}

/// The eight corners of the box `lo..hi` under `m`.
fn box_corners(lo: Vec3, hi: Vec3, m: &Mat4) -> impl Iterator<Item = Vec3> + '_ {
    (0..8).map(move |i| {
        m.transform_point3(Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        ))
    })
}
