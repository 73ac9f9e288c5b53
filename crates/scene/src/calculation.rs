//! Calculation surfaces: named meshes that receive light without touching it, as the
//! calculation planes of lighting design software (EN 12464-1:2021 §4.4 measures the
//! task area on such a plane; CIE 171:2006's test cases read illuminance on virtual
//! grids). Photons pass through them unchanged (no absorption, reflection or shadow,
//! for the photons' own rays and for the estimator's connections to other surfaces),
//! the renderer does not draw them, and they are tallied on both sides like any
//! measured surface.
//!
//! - `--calculation-surface NAME` and a problem file's `<calculationSurface
//!   surface="NAME"/>` make a surface of the scene one ([`CalculationSurface`]).
//! - `<workplane id="Task" height="0.85" border="0.5" [floor="Floor"]/>` builds one
//!   ([`Workplane`]): a horizontal rectangle `height` metres above the floor, inset by
//!   `border` on every side of the floor's outline, facing up.
//!
//! The floor of a workplane is found as [`Scene::add_workplane`] says: the named surface's
//! largest horizontal level, else the scene's lowest upward-facing horizontal level that
//! covers a quarter of the scene's footprint, else the scene's bounds. Its outline is
//! the smallest rectangle holding that level's triangles in plan (an axis-aligned one
//! when it is as small), so an L-shaped room gets the rectangle around it.

use crate::error::{Diagnostic, LoadError};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::model::{InstanceId, Scene, SurfaceId};
use glam::{DVec2, Mat4, Vec3};
use std::path::{Path, PathBuf};

/// A request to make a surface of the scene a calculation surface.
#[derive(Debug, Clone, PartialEq)]
pub struct CalculationSurface {
    /// The surface's name.
    pub surface: String,
    /// The problem file and line that asked for it; `None` for the command line.
    pub origin: Option<(PathBuf, u32)>,
}

impl CalculationSurface {
    /// The request of `--calculation-surface NAME`.
    pub fn named(surface: &str) -> CalculationSurface {
        CalculationSurface {
            surface: surface.to_string(),
            origin: None,
        }
    }
}

/// A horizontal calculation rectangle over the floor (`<workplane>`).
#[derive(Debug, Clone, PartialEq)]
pub struct Workplane {
    /// The name it is measured by (goals, constraints, `--surface`).
    pub id: String,
    /// Height above the floor, m (> 0; EN 12464-1's desks: 0.75–0.85 m).
    pub height: f32,
    /// Band left out along every side of the floor's outline, m (≥ 0; EN 12464-1
    /// §4.4 leaves 0.5 m along the walls).
    pub border: f32,
    /// The surface it is laid over; `None` finds the floor ([`Scene::add_workplane`]).
    pub floor: Option<String>,
    /// The problem file and line that asked for it.
    pub origin: Option<(PathBuf, u32)>,
}

/// The calculation surfaces a problem or a command asks for: the workplanes to build,
/// then the surfaces to make calculation surfaces.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Calculation {
    /// Surfaces of the scene.
    pub surfaces: Vec<CalculationSurface>,
    /// Rectangles to build.
    pub workplanes: Vec<Workplane>,
}

/// A triangle counts as horizontal when its normal is within about 1.1° of the up axis.
pub(crate) const HORIZONTAL_COS: f32 = 0.9998;

/// The share of the scene's footprint a horizontal level must cover to be taken as the
/// floor when no floor is named.
pub(crate) const FLOOR_SHARE: f64 = 0.25;

/// An error about a request: at its problem file's line, or at the scene file `scene`
/// naming the flag.
pub(crate) fn error(
    origin: &Option<(PathBuf, u32)>,
    scene: &Path,
    flag: String,
    message: String,
) -> Diagnostic {
    match origin {
        Some((problem, line)) => Diagnostic::at_line(problem, *line, message),
        None => Diagnostic::at(scene, flag, message),
    }
}

/// The eight corners of the box from `lo` to `hi`.
pub(crate) fn box_corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// Two unit vectors across `up` with `e1 × e2 = up`: Z and X for a Y-up scene, X and Y
/// for a Z-up one, so that rooms along the axes get plan axes along them.
pub(crate) fn plan_axes(up: Vec3) -> (Vec3, Vec3) {
    let up = up.normalize();
    let seed = if up.y.abs() > 0.9 { Vec3::Z } else { Vec3::X };
    let e1 = (seed - up * seed.dot(up)).normalize();
    (e1, up.cross(e1))
}

/// The world point at `(x, y)` in the plan frame whose first axis is `a` (the second
/// `a` turned by +90°, both in [`plan_axes`]' plane), `height` along `up`.
pub(crate) fn plan_point(up: Vec3, a: DVec2, x: f64, y: f64, height: f64) -> Vec3 {
    let up = up.normalize();
    let (e1, e2) = plan_axes(up);
    let p = a * x + a.perp() * y;
    (e1.as_dvec3() * p.x + e2.as_dvec3() * p.y + up.as_dvec3() * height).as_vec3()
}

/// A horizontal level: its height along up, area, and its triangles' corners in plan.
pub(crate) struct Level {
    pub(crate) height: f64,
    pub(crate) area: f64,
    pub(crate) corners: Vec<DVec2>,
}

/// Which way the horizontal triangles [`levels`] keeps face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Facing {
    /// Their front faces up: a floor.
    Up,
    /// Either way.
    Either,
}

/// The room found by [`Scene::room`].
pub(crate) struct Room {
    /// The floor level.
    pub(crate) level: Level,
    /// The floor as messages name it.
    pub(crate) floor_name: String,
    /// The highest point of the scene along up.
    pub(crate) top: f32,
    /// Heights within this are one level, m.
    pub(crate) tolerance: f64,
}

/// The horizontal triangles `tris` (corners, world) grouped by height: levels within
/// `tolerance` of one another, lowest first, of those whose front faces as `facing` asks.
pub(crate) fn levels(
    tris: impl Iterator<Item = [Vec3; 3]>,
    up: Vec3,
    tolerance: f64,
    facing: Facing,
) -> Vec<Level> {
    let (e1, e2) = plan_axes(up);
    let mut flat: Vec<(f64, f64, [DVec2; 3])> = tris
        .filter_map(|c| {
            let cross = (c[1] - c[0]).cross(c[2] - c[0]);
            let area = 0.5 * cross.length();
            let cos = cross.normalize_or_zero().dot(up);
            let horizontal = match facing {
                Facing::Up => cos >= HORIZONTAL_COS,
                Facing::Either => cos.abs() >= HORIZONTAL_COS,
            };
            (area > 0.0 && horizontal).then(|| {
                let h = c.iter().map(|p| f64::from(p.dot(up))).sum::<f64>() / 3.0;
                let plan = c.map(|p| DVec2::new(p.dot(e1).into(), p.dot(e2).into()));
                (h, f64::from(area), plan)
            })
        })
        .collect();
    flat.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<Level> = Vec::new();
    for (h, area, plan) in flat {
        match out.last_mut() {
            Some(l) if h - l.height <= tolerance => {
                l.area += area;
                l.corners.extend(plan);
            }
            _ => out.push(Level {
                height: h,
                area,
                corners: plan.to_vec(),
            }),
        }
    }
    out
}

/// A rectangle in plan: its unit axis `a` (the other axis is `a` turned by +90°) and
/// its extents along each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rectangle {
    pub(crate) a: DVec2,
    pub(crate) along: (f64, f64),
    pub(crate) across: (f64, f64),
}

impl Rectangle {
    pub(crate) fn area(&self) -> f64 {
        (self.along.1 - self.along.0) * (self.across.1 - self.across.0)
    }

    /// The rectangle of `points` with its sides along `a` and `a` turned by 90°.
    pub(crate) fn around(points: &[DVec2], a: DVec2) -> Rectangle {
        let b = a.perp();
        let mut r = Rectangle {
            a,
            along: (f64::INFINITY, f64::NEG_INFINITY),
            across: (f64::INFINITY, f64::NEG_INFINITY),
        };
        for p in points {
            let (x, y) = (p.dot(a), p.dot(b));
            r.along = (r.along.0.min(x), r.along.1.max(x));
            r.across = (r.across.0.min(y), r.across.1.max(y));
        }
        r
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain; A. M.
/// Andrew, "Another efficient algorithm for convex hulls in two dimensions", 1979).
fn hull(mut points: Vec<DVec2>) -> Vec<DVec2> {
    points.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let turn = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut h: Vec<DVec2> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = h.len();
        let ordered: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in ordered {
            while h.len() >= start + 2 && turn(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// The smallest rectangle holding `points`: some side of it lies along an edge of
/// their convex hull (H. Freeman and R. Shapira, "Determining the minimum-area encasing
/// rectangle for an arbitrary closed curve", CACM 18(7), 1975). The axis-aligned one is
/// kept unless another is smaller by more than rounding, so a room along the axes gets
/// a workplane along them.
pub(crate) fn outline(points: &[DVec2]) -> Rectangle {
    let mut best = Rectangle::around(points, DVec2::X);
    let h = hull(points.to_vec());
    for (i, &p) in h.iter().enumerate() {
        let edge = h[(i + 1) % h.len()] - p;
        if edge.length_squared() > 0.0 {
            let r = Rectangle::around(points, edge.normalize());
            if r.area() < best.area() * (1.0 - 1e-9) {
                best = r;
            }
        }
    }
    best
}

impl Scene {
    /// The surfaces that are calculation surfaces, in the order they became so.
    pub fn calculation_surfaces(&self) -> &[SurfaceId] {
        &self.calculation
    }

    /// Whether surface `s` is a calculation surface.
    pub fn is_calculation_surface(&self, s: SurfaceId) -> bool {
        self.calculation.contains(&s)
    }

    /// Makes surface `s` a calculation surface: every instance under it lets photons
    /// through and receives them.
    pub fn make_calculation_surface(&mut self, s: SurfaceId) {
        if !self.calculation.contains(&s) {
            self.calculation.push(s);
        }
    }

    /// For each instance, whether it belongs to a calculation surface (then the tracer
    /// leaves it out of every occlusion test and counts the photons crossing it).
    pub fn calculation_instances(&self) -> Vec<bool> {
        let mut v = vec![false; self.instances.len()];
        for &s in &self.calculation {
            for &i in &self.surfaces[s].instances {
                if let Some(f) = v.get_mut(i.index()) {
                    *f = true;
                }
            }
        }
        v
    }

    /// Builds the workplanes of `calculation`, then makes its surfaces calculation
    /// surfaces; `scene` is the scene file, named in errors about a command-line
    /// request.
    pub fn set_calculation(
        &mut self,
        scene: &Path,
        calculation: &Calculation,
    ) -> Result<(), LoadError> {
        for w in &calculation.workplanes {
            self.add_workplane(scene, w)?;
        }
        for c in &calculation.surfaces {
            let flag = format!("--calculation-surface {}", c.surface);
            let Some(s) = self.surface(&c.surface) else {
                let hint = if self.placement(&c.surface).is_some() {
                    format!(
                        "'{}' is a placement rectangle (*__Geometry), which is not part of the scene; a <workplane> builds a calculation rectangle over the floor",
                        c.surface
                    )
                } else {
                    crate::known_names(self.surfaces.iter().map(|s| s.name.as_str()), "surfaces")
                };
                return Err(error(
                    &c.origin,
                    scene,
                    flag,
                    format!(
                        "no surface named '{}', expected the surface to make a calculation surface",
                        c.surface
                    ),
                )
                .with_hint(hint));
            };
            if self.surface_area(s) <= 0.0 {
                return Err(error(
                    &c.origin,
                    scene,
                    flag,
                    format!(
                        "the surface '{}' has no area (its triangles are degenerate), expected a surface to measure",
                        c.surface
                    ),
                ));
            }
            self.make_calculation_surface(s);
        }
        Ok(())
    }

    /// Builds the workplane `w`: a rectangle of two triangles facing up (its front, the
    /// counter-clockwise side, along [`Scene::up`]), `w.height` above the floor and
    /// `w.border` inside the floor's outline on every side, under the surface `w.id`,
    /// made a calculation surface.
    ///
    /// The floor: with `w.floor`, that surface's horizontal triangles (facing up, or
    /// either way when none faces up) at the height holding most of their area;
    /// without, the lowest height at which upward-facing horizontal triangles of the
    /// scene (calculation surfaces left out) cover a quarter of the footprint of its
    /// bounds, and failing that the bottom of its bounds with their footprint. The
    /// outline is the smallest rectangle around that height's triangles in plan.
    pub fn add_workplane(&mut self, scene: &Path, w: &Workplane) -> Result<SurfaceId, LoadError> {
        let err =
            |message: String| error(&w.origin, scene, format!("workplane '{}'", w.id), message);
        if w.id.trim().is_empty() {
            return Err(err(
                "the workplane has an empty id, expected the name to measure it by".into(),
            ));
        }
        if self.surface(&w.id).is_some() || self.placement(&w.id).is_some() {
            return Err(err(format!(
                "the scene already has a surface named '{}', expected a new name for the workplane",
                w.id
            ))
            .with_hint("give the workplane another id, or make the existing surface a calculation surface with <calculationSurface>"));
        }
        if !(w.height.is_finite() && w.height > 0.0) {
            return Err(err(format!(
                "its height is {} m, expected a positive height above the floor (e.g. 0.85)",
                w.height
            )));
        }
        if !(w.border.is_finite() && w.border >= 0.0) {
            return Err(err(format!(
                "its border is {} m, expected a band of zero or more metres along the walls (e.g. 0.5)",
                w.border
            )));
        }
        let Room {
            level,
            floor_name,
            top,
            ..
        } = self.room(w.floor.as_deref(), &err)?;
        let r = outline(&level.corners);
        let (b, length, width) = (
            f64::from(w.border),
            r.along.1 - r.along.0,
            r.across.1 - r.across.0,
        );
        if length <= 2.0 * b || width <= 2.0 * b {
            return Err(err(format!(
                "a border of {} m on each side leaves nothing of {floor_name}'s {:.3} m × {:.3} m outline",
                w.border, length, width
            ))
            .with_hint(format!(
                "give a border under {:.3} m (half the shorter side)",
                0.5 * length.min(width)
            )));
        }
        let height = level.height + f64::from(w.height);
        if height >= f64::from(top) {
            return Err(err(format!(
                "{} m above {floor_name} (at {:.3} m) is {height:.3} m, at or above the top of the scene ({top:.3} m)",
                w.height, level.height
            ))
            .with_hint("give the height above the floor in metres (e.g. 0.85), or name the floor with floor=\"…\""));
        }
        let up = self.up;
        let at = |x: f64, y: f64| plan_point(up, r.a, x, y, height);
        let (x0, x1) = (r.along.0 + b, r.along.1 - b);
        let (y0, y1) = (r.across.0 + b, r.across.1 - b);
        let material = self.add_material(Material::diffuse(
            &format!("{} (workplane)", w.id),
            Vec3::ZERO,
        ));
        let mesh = self.add_mesh(Mesh::quad(
            [at(x0, y0), at(x1, y0), at(x1, y1), at(x0, y1)],
            material,
        ));
        self.add_instance(&w.id, mesh, Mat4::IDENTITY);
        let s = self.surface(&w.id).expect("the surface just added");
        self.make_calculation_surface(s);
        Ok(s)
    }

    /// The room a workplane or a task's areas are laid in: the floor level (with
    /// `floor`, that surface's horizontal triangles facing up, or either way when none
    /// faces up, at the height holding most of their area; without, the lowest height
    /// at which upward-facing horizontal triangles of the scene, calculation surfaces
    /// left out, cover a quarter of the footprint of its bounds, and failing that the
    /// bottom of its bounds with their footprint), and the scene's extent along up.
    pub(crate) fn room(
        &self,
        floor: Option<&str>,
        err: &dyn Fn(String) -> Diagnostic,
    ) -> Result<Room, Diagnostic> {
        let Some((lo, hi)) = self.bounds() else {
            return Err(err(
                "the scene is empty, expected a room to lay it in".into()
            ));
        };
        let up = self.up.normalize();
        let (e1, e2) = plan_axes(up);
        let box_corners = box_corners(lo, hi);
        let (bottom, top) = box_corners
            .iter()
            .map(|p| p.dot(up))
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(b, t), h| {
                (b.min(h), t.max(h))
            });
        let tolerance = 1e-3f64.max(1e-4 * f64::from((hi - lo).length()));
        let calc = self.calculation_instances();
        let (level, floor_name) = match floor {
            Some(name) => {
                let Some(s) = self.surface(name) else {
                    return Err(err(format!(
                        "no surface named '{name}', expected the floor to lay the workplane over"
                    ))
                    .with_hint(crate::known_names(
                        self.surfaces.iter().map(|s| s.name.as_str()),
                        "surfaces",
                    )));
                };
                let tris = || {
                    self.surfaces[s]
                        .instances
                        .iter()
                        .flat_map(|&i| self.world_triangles(i))
                        .map(|t| t.corners)
                };
                let mut found = levels(tris(), up, tolerance, Facing::Up);
                if found.is_empty() {
                    found = levels(tris(), up, tolerance, Facing::Either);
                }
                let best = found
                    .into_iter()
                    .reduce(|a, b| if b.area > a.area { b } else { a });
                let Some(best) = best else {
                    return Err(err(format!(
                        "the floor '{name}' has no horizontal triangles, expected a floor level across the scene's up axis ({})",
                        axis_name(up)
                    ))
                    .with_hint("name the floor surface (`invlight scene` lists them) or check --up"));
                };
                (best, name.to_string())
            }
            None => {
                let box_corners: Vec<DVec2> = box_corners
                    .iter()
                    .map(|p| DVec2::new(p.dot(e1).into(), p.dot(e2).into()))
                    .collect();
                let footprint = Rectangle::around(&box_corners, DVec2::X).area();
                let tris = (0..self.instances.len())
                    .filter(|&i| !calc[i])
                    .flat_map(|i| self.world_triangles(InstanceId::from_index(i)))
                    .map(|t| t.corners);
                let found = levels(tris, up, tolerance, Facing::Up)
                    .into_iter()
                    .find(|l| l.area >= FLOOR_SHARE * footprint);
                match found {
                    Some(l) => (l, "the lowest floor".to_string()),
                    None => {
                        let level = Level {
                            height: bottom.into(),
                            area: footprint,
                            corners: box_corners,
                        };
                        (level, "the scene's bounds".to_string())
                    }
                }
            }
        };
        Ok(Room {
            level,
            floor_name,
            top,
            tolerance,
        })
    }

    /// A warning for measuring surface `s` when it cannot receive light as it is and is
    /// not a calculation surface: every triangle a hole (photons pass through it
    /// without arriving: it reads 0 lx), or every triangle fully transparent (absorbs
    /// and reflects nothing: it is traced as glass, which bends or partly reflects the
    /// light and hides what lies behind it from the estimator's connections).
    pub fn reception_warning(&self, s: SurfaceId) -> Option<String> {
        if self.is_calculation_surface(s) {
            return None;
        }
        let surface = &self.surfaces[s];
        let mut materials = surface.instances.iter().flat_map(|&i| {
            self.meshes[self.instances[i].mesh]
                .materials
                .iter()
                .copied()
        });
        let first = materials.next()?;
        let all = |f: &dyn Fn(&Material) -> bool| {
            f(&self.materials[first]) && materials.clone().all(|m| f(&self.materials[m]))
        };
        let name = &surface.name;
        let material = &self.materials[first].name;
        let suggestion = format!(
            "to measure there without touching the light, make it a calculation surface (<calculationSurface surface=\"{name}\"/> in the problem's <scene>, or --calculation-surface {name}), or build one with <workplane>"
        );
        if all(&|m: &Material| m.hole) {
            return Some(format!(
                "'{name}' is a hole (material '{material}'): photons pass through it without arriving, so it reads 0 lx; {suggestion}"
            ));
        }
        let clear = |m: &Material| {
            !m.hole
                && m.transmission >= 1.0
                && m.diffuse.max_element() <= 0.0
                && m.specular.max_element() <= 0.0
                && !m.is_emissive()
        };
        if all(&clear) {
            let m = &self.materials[first];
            let effect = if m.ior == 1.0 {
                "each photon still stops at it, and it hides what lies behind it from the estimator's connections".to_string()
            } else {
                format!(
                    "it bends and partly reflects the light crossing it as glass of index {}",
                    m.ior
                )
            };
            return Some(format!(
                "'{name}' absorbs and reflects nothing (material '{material}' is fully transparent): photons are counted on it, but {effect}; {suggestion}"
            ));
        }
        None
    }
}

/// `+Y`, `+Z` or the vector, for messages.
fn axis_name(up: Vec3) -> String {
    if up == Vec3::Y {
        "+Y".into()
    } else if up == Vec3::Z {
        "+Z".into()
    } else {
        format!("{up}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed 4 m × 3 m room, 2.5 m high, Y up, its floor of two triangles facing up,
    /// a 1 m table top at 0.75 m.
    fn room() -> Scene {
        let mut s = Scene::default();
        let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let room = s.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(4.0, 2.5, 3.0), grey));
        s.add_instance("Room", room, Mat4::IDENTITY);
        let floor = s.add_mesh(Mesh::quad(
            [
                Vec3::ZERO,
                Vec3::new(0.0, 0.0, 3.0),
                Vec3::new(4.0, 0.0, 3.0),
                Vec3::new(4.0, 0.0, 0.0),
            ],
            grey,
        ));
        s.add_instance("Floor", floor, Mat4::IDENTITY);
        let table = s.add_mesh(Mesh::cuboid(
            Vec3::new(1.0, 0.7, 1.0),
            Vec3::new(2.0, 0.75, 2.0),
            grey,
        ));
        s.add_instance("Table", table, Mat4::IDENTITY);
        s
    }

    fn plane(id: &str, height: f32, border: f32, floor: Option<&str>) -> Workplane {
        Workplane {
            id: id.into(),
            height,
            border,
            floor: floor.map(String::from),
            origin: None,
        }
    }

    /// The world corners of surface `s`'s one instance and its front normal.
    fn corners(scene: &Scene, s: SurfaceId) -> (Vec<Vec3>, Vec3) {
        let i = scene.surfaces[s].instances[0];
        let t: Vec<_> = scene.world_triangles(i).collect();
        let mut v: Vec<Vec3> = t.iter().flat_map(|t| t.corners).collect();
        v.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.z.total_cmp(&b.z)));
        v.dedup();
        (v, t[0].normal())
    }

    #[test]
    fn a_workplane_lies_over_the_floor_inside_its_border() {
        for floor in [None, Some("Floor")] {
            let mut s = room();
            let id = s
                .add_workplane(Path::new("room.gltf"), &plane("Task", 0.85, 0.5, floor))
                .unwrap();
            assert!(s.is_calculation_surface(id));
            let (v, n) = corners(&s, id);
            let expect = [
                Vec3::new(0.5, 0.85, 0.5),
                Vec3::new(0.5, 0.85, 2.5),
                Vec3::new(3.5, 0.85, 0.5),
                Vec3::new(3.5, 0.85, 2.5),
            ];
            assert_eq!(v.len(), 4, "{v:?}");
            for (got, want) in v.iter().zip(expect) {
                assert!(got.distance(want) < 1e-5, "{floor:?}: {got} vs {want}");
            }
            assert!(n.distance(Vec3::Y) < 1e-6, "faces up: {n}");
            assert!((s.surface_area(id) - 6.0).abs() < 1e-4);
            let calc = s.calculation_instances();
            assert_eq!(calc, [false, false, false, true]);
        }
    }

    /// A Z-up floor turned by 30° about the vertical: the workplane follows its sides.
    #[test]
    fn a_turned_floor_gets_a_turned_workplane() {
        let mut s = Scene::default();
        s.up = Vec3::Z;
        let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let floor = s.add_mesh(Mesh::quad(
            [
                Vec3::ZERO,
                Vec3::new(6.0, 0.0, 0.0),
                Vec3::new(6.0, 2.0, 0.0),
                Vec3::new(0.0, 2.0, 0.0),
            ],
            grey,
        ));
        let turn = Mat4::from_translation(Vec3::new(10.0, -3.0, 1.0))
            * Mat4::from_rotation_z(30f32.to_radians());
        s.add_instance("Slab", floor, turn);
        let roof = s.add_mesh(Mesh::quad(
            [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            grey,
        ));
        s.add_instance(
            "Marker",
            roof,
            Mat4::from_translation(Vec3::new(10.0, -3.0, 4.0)),
        );
        let id = s
            .add_workplane(Path::new("site.obj"), &plane("Desk", 0.8, 0.25, None))
            .unwrap();
        assert!((s.surface_area(id) - 5.5 * 1.5).abs() < 1e-3);
        let i = s.surfaces[id].instances[0];
        for t in s.world_triangles(i) {
            assert!(t.normal().distance(Vec3::Z) < 1e-6);
            for p in t.corners {
                assert!((p.z - 1.8).abs() < 1e-5);
                // Back in the slab's frame, inside it by the border.
                let local = turn.inverse().transform_point3(p);
                let inside =
                    |x: f32, lo: f32, hi: f32| (x - lo).abs() < 1e-4 || (x - hi).abs() < 1e-4;
                assert!(
                    inside(local.x, 0.25, 5.75) && inside(local.y, 0.25, 1.75),
                    "{local}"
                );
            }
        }
    }

    #[test]
    fn bad_workplanes_are_refused_with_the_reason() {
        let p = Path::new("room.gltf");
        let mut s = room();
        let e = s
            .add_workplane(p, &plane("Task", 0.85, 1.5, None))
            .unwrap_err();
        assert!(e.message.contains("leaves nothing"), "{e}");
        assert!(e.hint.as_ref().unwrap().contains("under 1.500 m"), "{e}");
        let e = s
            .add_workplane(p, &plane("Floor", 0.85, 0.5, None))
            .unwrap_err();
        assert!(
            e.message.contains("already has a surface named 'Floor'"),
            "{e}"
        );
        let e = s
            .add_workplane(p, &plane("Task", 3.0, 0.5, None))
            .unwrap_err();
        assert!(e.message.contains("above the top of the scene"), "{e}");
        let e = s
            .add_workplane(p, &plane("Task", 0.0, 0.5, None))
            .unwrap_err();
        assert!(e.message.contains("positive height"), "{e}");
        let e = s
            .add_workplane(p, &plane("Task", 0.8, 0.5, Some("Flor")))
            .unwrap_err();
        assert!(e.message.contains("no surface named 'Flor'"), "{e}");
        // Nothing half-built was left behind.
        assert_eq!(s.surfaces.len(), 3);
        assert!(s.calculation_surfaces().is_empty());
    }

    #[test]
    fn surfaces_that_cannot_receive_are_warned_of() {
        let mut s = room();
        let hole = s.add_material(Material::hole("Opening"));
        let clear = s.add_material(Material::glass("Clear", 1.0));
        let quad = |m| Mesh::quad([Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y], m);
        let (h, c) = (s.add_mesh(quad(hole)), s.add_mesh(quad(clear)));
        s.add_instance("Window", h, Mat4::IDENTITY);
        s.add_instance("Sheet", c, Mat4::IDENTITY);
        let window = s.surface("Window").unwrap();
        let w = s.reception_warning(window).unwrap();
        assert!(
            w.contains("reads 0 lx") && w.contains("<calculationSurface surface=\"Window\"/>"),
            "{w}"
        );
        let w = s.reception_warning(s.surface("Sheet").unwrap()).unwrap();
        assert!(w.contains("absorbs and reflects nothing"), "{w}");
        assert_eq!(s.reception_warning(s.surface("Floor").unwrap()), None);
        let calc = Calculation {
            surfaces: vec![CalculationSurface::named("Window")],
            workplanes: Vec::new(),
        };
        s.set_calculation(Path::new("room.gltf"), &calc).unwrap();
        assert_eq!(s.reception_warning(window), None);
        let bad = Calculation {
            surfaces: vec![CalculationSurface::named("Windw")],
            workplanes: Vec::new(),
        };
        let e = s.set_calculation(Path::new("room.gltf"), &bad).unwrap_err();
        assert!(e.location.contains("--calculation-surface Windw"), "{e}");
    }
}
