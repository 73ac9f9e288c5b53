//! The areas EN 12464-1 judges around a task area, built as calculation surfaces so
//! that one trace measures them all without touching the light:
//!
//! - the **immediate surrounding area**, a band at least 0.5 m wide around the task area
//!   in its plane (EN 12464-1:2021 §5.3.2; 2011 §4.3.2), and the **background area**, a
//!   band at least 3 m wide around that, within the limits of the room (2021 §5.3.3;
//!   2011 §4.3.3): each the frame between two rectangles, clipped to the room's outline;
//! - the **walls** and the **ceiling** (2021 §5.2.4 "illuminance on walls and ceiling";
//!   2011 §4.3.1): the four sides of the room's outline from the floor to the ceiling and
//!   the outline at the ceiling, each a rectangle [`ROOM_SURFACE_OFFSET`] inside the room,
//!   facing into it, so that its front counts the light arriving at the wall or ceiling
//!   and its back the light the wall or ceiling sends back.
//!
//! The room's floor is the highest horizontal level at or below the task area that
//! covers a quarter of the floor's footprint as a `<workplane>` finds it
//! ([`Scene::add_workplane`]), its outline the room's in plan; the ceiling is the lowest
//! such level above the task area, else the top of the scene. Levels count facing
//! either way: a room modelled as a box may face out.

use crate::calculation::{FLOOR_SHARE, Facing, Level, Rectangle, levels, outline, plan_point};
use crate::error::{Diagnostic, LoadError};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::model::{InstanceId, Scene, SurfaceId};
use glam::{DVec2, Mat4, Vec3};
use std::path::Path;

/// The width of the immediate surrounding band, m (EN 12464-1: at least 0.5 m).
pub const SURROUNDING_BAND: f64 = 0.5;

/// The width of the background band, m (EN 12464-1: at least 3 m, within the room).
pub const BACKGROUND_BAND: f64 = 3.0;

/// How far inside the room the walls' and the ceiling's calculation rectangles lie, m:
/// one on the wall itself would be met at the wall's own distance, which of the two a
/// photon reaches first then decided by rounding.
pub const ROOM_SURFACE_OFFSET: f64 = 0.01;

/// Which of EN 12464-1's areas a surface stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AreaKind {
    /// The band around the task area.
    Surrounding,
    /// The band around the immediate surrounding.
    Background,
    /// A wall of the room.
    Wall,
    /// The ceiling.
    Ceiling,
    /// Cylindrical illuminance Ez over the task area at the height of a seated or
    /// standing person's eye ([`Scene::add_cylindrical_area`]).
    Cylindrical,
}

impl AreaKind {
    /// Every kind [`Scene::add_task_areas`] builds, in its order (the cylindrical
    /// illuminance has its own builder, and a task asks it only where the standard
    /// gives an Ēz).
    pub const ALL: [AreaKind; 4] = [
        AreaKind::Surrounding,
        AreaKind::Background,
        AreaKind::Wall,
        AreaKind::Ceiling,
    ];

    /// The grid spacing the area is measured with, m, where EN 12464-1's rule for its
    /// extent would not fit it: the surrounding band gets two cells across its 0.5 m
    /// (the rule, from the band's outer size, gives cells wider than the band, which
    /// then covers none of them by half). `None`: the rule.
    pub fn spacing(self) -> Option<f64> {
        match self {
            AreaKind::Surrounding => Some(0.5 * SURROUNDING_BAND),
            _ => None,
        }
    }

    /// The area in the standard's words.
    pub fn name(self) -> &'static str {
        match self {
            AreaKind::Surrounding => "immediate surrounding",
            AreaKind::Background => "background",
            AreaKind::Wall => "wall",
            AreaKind::Ceiling => "ceiling",
            AreaKind::Cylindrical => "cylindrical illuminance",
        }
    }
}

/// One area built by [`Scene::add_task_areas`].
#[derive(Debug, Clone, PartialEq)]
pub struct TaskArea {
    /// What it stands for.
    pub kind: AreaKind,
    /// The calculation surface built; its front faces where the standard measures.
    pub surface: SurfaceId,
    /// Its name in the scene.
    pub name: String,
    /// Its extent, m: the band's width for the surrounding and background areas,
    /// else the rectangle's two sides.
    pub size: (f64, f64),
}

/// A rectangle in a plan frame: its extents along the frame's two axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Span {
    pub(crate) x: (f64, f64),
    pub(crate) y: (f64, f64),
}

impl Span {
    fn of(r: &Rectangle) -> Span {
        Span {
            x: r.along,
            y: r.across,
        }
    }

    pub(crate) fn grown(self, by: f64) -> Span {
        Span {
            x: (self.x.0 - by, self.x.1 + by),
            y: (self.y.0 - by, self.y.1 + by),
        }
    }

    pub(crate) fn clipped(self, to: Span) -> Span {
        Span {
            x: (self.x.0.max(to.x.0), self.x.1.min(to.x.1)),
            y: (self.y.0.max(to.y.0), self.y.1.min(to.y.1)),
        }
    }

    fn area(self) -> f64 {
        (self.x.1 - self.x.0).max(0.0) * (self.y.1 - self.y.0).max(0.0)
    }

    /// The rectangles covering `self` less `inner` (which lies within it): the strips
    /// below and above `inner` across the whole width, and those left and right of it.
    fn frame(self, inner: Span) -> Vec<Span> {
        let strips = [
            Span {
                x: self.x,
                y: (self.y.0, inner.y.0),
            },
            Span {
                x: self.x,
                y: (inner.y.1, self.y.1),
            },
            Span {
                x: (self.x.0, inner.x.0),
                y: inner.y,
            },
            Span {
                x: (inner.x.1, self.x.1),
                y: inner.y,
            },
        ];
        strips.into_iter().filter(|s| s.area() > 1e-9).collect()
    }
}

/// The room around a task area, in a plan frame: what every area built around it is
/// measured from.
pub(crate) struct RoomFrame {
    /// The scene's unit up axis.
    pub(crate) up: Vec3,
    /// The room's outline: its axis `a` is the plan frame's first.
    pub(crate) outline: Rectangle,
    /// The task area's height along up.
    pub(crate) level: f64,
    /// The floor's height.
    pub(crate) floor: f64,
    /// The ceiling's height.
    pub(crate) ceiling: f64,
    /// The room's outline in the plan frame.
    pub(crate) room_span: Span,
    /// The task area in the plan frame, within the room.
    pub(crate) inner: Span,
}

impl Scene {
    /// The room around the task area `task` (a horizontal planar surface): its floor is
    /// the highest level at or below the task area covering a quarter of the scene's
    /// footprint, facing either way (a room's box may face out); its ceiling the lowest
    /// such level above it, else the top of the scene. `scene` is the scene file, named
    /// in errors.
    pub(crate) fn room_frame(&self, scene: &Path, task: SurfaceId) -> Result<RoomFrame, LoadError> {
        let task_name = self.surfaces[task].name.clone();
        let err = |message: String| {
            Diagnostic::at(
                scene,
                format!("the EN 12464-1 areas around '{task_name}'"),
                message,
            )
        };
        let room = self.room(None, &err)?;
        let up = self.up.normalize();
        let tris: Vec<[Vec3; 3]> = self.surfaces[task]
            .instances
            .iter()
            .flat_map(|&i| self.world_triangles(i))
            .map(|t| t.corners)
            .collect();
        let total: f64 = tris
            .iter()
            .map(|c| 0.5 * f64::from((c[1] - c[0]).cross(c[2] - c[0]).length()))
            .sum();
        let task_levels = levels(tris.iter().copied(), up, room.tolerance, Facing::Either);
        let level = match task_levels.as_slice() {
            [level] if level.area >= total * (1.0 - 1e-4) => level,
            _ => {
                return Err(err(format!(
                    "'{task_name}' is not one horizontal plane, expected a task area to lay the surrounding and background bands around"
                ))
                .with_hint("measure a horizontal task area (a <workplane>, or a desk top made a calculation surface), or give --no-areas to judge the task area alone"));
            }
        };
        let calc = self.calculation_instances();
        let room_tris = (0..self.instances.len())
            .filter(|&i| !calc[i])
            .flat_map(|i| self.world_triangles(InstanceId::from_index(i)))
            .map(|t| t.corners);
        let room_levels = levels(room_tris, up, room.tolerance, Facing::Either);
        let footprint = Rectangle::around(&room.level.corners, DVec2::X).area();
        let wide = |l: &&Level| l.area >= FLOOR_SHARE * footprint;
        let floor_level = room_levels
            .iter()
            .filter(wide)
            .rfind(|l| l.height <= level.height + room.tolerance)
            .unwrap_or(&room.level);
        let ceiling = room_levels
            .iter()
            .filter(wide)
            .find(|l| l.height > level.height + room.tolerance)
            .map_or(f64::from(room.top), |l| l.height);
        let outline = outline(&floor_level.corners);
        let room_span = Span::of(&outline);
        let inner = Span::of(&Rectangle::around(&level.corners, outline.a)).clipped(room_span);
        if inner.area() <= 0.0 {
            return Err(err(format!(
                "'{task_name}' lies outside {}'s outline, expected a task area inside the room",
                room.floor_name
            )));
        }
        Ok(RoomFrame {
            up,
            outline,
            level: level.height,
            floor: floor_level.height,
            ceiling,
            room_span,
            inner,
        })
    }

    /// Builds EN 12464-1's areas around the task area `task` (a horizontal planar
    /// surface) as calculation surfaces, as the module doc says: the immediate
    /// surrounding and the background (left out where the room leaves no room for
    /// them), the four walls and the ceiling, those of `kinds` only. `scene` is the
    /// scene file, named in errors.
    pub fn add_task_areas(
        &mut self,
        scene: &Path,
        task: SurfaceId,
        kinds: &[AreaKind],
    ) -> Result<Vec<TaskArea>, LoadError> {
        let RoomFrame {
            up,
            outline,
            level,
            floor,
            ceiling,
            room_span,
            inner,
        } = self.room_frame(scene, task)?;
        let mut areas = Vec::new();
        let surrounding = inner.grown(SURROUNDING_BAND).clipped(room_span);
        let background = surrounding.grown(BACKGROUND_BAND).clipped(room_span);
        for (kind, outer, within, band) in [
            (AreaKind::Surrounding, surrounding, inner, SURROUNDING_BAND),
            (
                AreaKind::Background,
                background,
                surrounding,
                BACKGROUND_BAND,
            ),
        ] {
            let strips = outer.frame(within);
            if strips.is_empty() || !kinds.contains(&kind) {
                continue;
            }
            let quads = strips
                .iter()
                .map(|s| {
                    [
                        (s.x.0, s.y.0),
                        (s.x.1, s.y.0),
                        (s.x.1, s.y.1),
                        (s.x.0, s.y.1),
                    ]
                    .map(|(x, y)| plan_point(up, outline.a, x, y, level))
                })
                .collect();
            let surface = self.add_area(kind.name(), quads);
            areas.push(self.area(kind, surface, (band, band)));
        }

        let e = ROOM_SURFACE_OFFSET;
        let inside = room_span.grown(-e);
        let at = |x: f64, y: f64, h: f64| plan_point(up, outline.a, x, y, h);
        areas.extend(self.room_areas(inside, (floor + e, ceiling - e), at, kinds));
        Ok(areas)
    }

    /// The four walls and the ceiling of the room `inside` (in plan) from height `f` to
    /// `c`, those of `kinds`, as calculation rectangles facing into it; `at` puts a plan
    /// point at a height in the world.
    fn room_areas(
        &mut self,
        inside: Span,
        (f, c): (f64, f64),
        at: impl Fn(f64, f64, f64) -> Vec3,
        kinds: &[AreaKind],
    ) -> Vec<TaskArea> {
        let (x, y) = (inside.x, inside.y);
        let mut areas = Vec::new();
        // Each wall as (its two ends in plan), then the room's centre to face.
        let walls = [
            ((x.0, y.0), (x.1, y.0)),
            ((x.1, y.0), (x.1, y.1)),
            ((x.1, y.1), (x.0, y.1)),
            ((x.0, y.1), (x.0, y.0)),
        ];
        let centre = at(0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1), 0.5 * (f + c));
        let walls = if kinds.contains(&AreaKind::Wall) {
            &walls[..]
        } else {
            &[]
        };
        let quads: Vec<[Vec3; 4]> = walls
            .iter()
            .map(|&(p, q)| {
                let quad = [
                    at(p.0, p.1, f),
                    at(q.0, q.1, f),
                    at(q.0, q.1, c),
                    at(p.0, p.1, c),
                ];
                facing(quad, centre)
            })
            .collect();
        let names = self.wall_names(&quads, ROOM_SURFACE_OFFSET);
        for ((&(p, q), quad), name) in walls.iter().zip(quads).zip(names) {
            let surface = self.add_area(&name, vec![quad]);
            let length = ((q.0 - p.0).powi(2) + (q.1 - p.1).powi(2)).sqrt();
            areas.push(self.area(AreaKind::Wall, surface, (length, c - f)));
        }
        if kinds.contains(&AreaKind::Ceiling) {
            let quad = [(x.0, y.0), (x.1, y.0), (x.1, y.1), (x.0, y.1)].map(|(x, y)| at(x, y, c));
            let surface = self.add_area("ceiling", vec![facing(quad, centre)]);
            areas.push(self.area(AreaKind::Ceiling, surface, (x.1 - x.0, y.1 - y.0)));
        }
        areas
    }

    /// Adds a calculation surface of `quads` named `name`, or `name (EN 12464-1)` when
    /// the scene has a surface called `name`.
    pub(crate) fn add_area(&mut self, name: &str, quads: Vec<[Vec3; 4]>) -> SurfaceId {
        let mut unique = name.to_string();
        let mut n = 1;
        while self.surface(&unique).is_some() || self.placement(&unique).is_some() {
            unique = if n == 1 {
                format!("{name} (EN 12464-1)")
            } else {
                format!("{name} (EN 12464-1, {n})")
            };
            n += 1;
        }
        let material = self.add_material(Material::diffuse(
            &format!("{unique} (calculation)"),
            Vec3::ZERO,
        ));
        for quad in quads {
            let mesh = self.add_mesh(Mesh::quad(quad, material));
            self.add_instance(&unique, mesh, Mat4::IDENTITY);
        }
        let s = self.surface(&unique).expect("the surface just added");
        self.make_calculation_surface(s);
        s
    }

    pub(crate) fn area(&self, kind: AreaKind, surface: SurfaceId, size: (f64, f64)) -> TaskArea {
        TaskArea {
            kind,
            surface,
            name: self.surfaces[surface].name.clone(),
            size,
        }
    }
}

/// `quad` wound so that its front faces the point `towards`.
fn facing(quad: [Vec3; 4], towards: Vec3) -> [Vec3; 4] {
    let normal = (quad[1] - quad[0]).cross(quad[2] - quad[0]);
    if normal.dot(towards - quad[0]) >= 0.0 {
        quad
    } else {
        [quad[0], quad[3], quad[2], quad[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed 6 m × 4 m room, 3 m high, Y up, a floor and a 1 m × 1 m desk area at
    /// 0.8 m whose corner lies 1 m from two walls.
    fn office() -> (Scene, SurfaceId) {
        let mut s = Scene::default();
        let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let room = s.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(6.0, 3.0, 4.0), grey));
        s.add_instance("Room", room, Mat4::IDENTITY);
        let floor = s.add_mesh(Mesh::quad(
            [
                Vec3::ZERO,
                Vec3::new(0.0, 0.0, 4.0),
                Vec3::new(6.0, 0.0, 4.0),
                Vec3::new(6.0, 0.0, 0.0),
            ],
            grey,
        ));
        s.add_instance("Floor", floor, Mat4::IDENTITY);
        let desk = s.add_mesh(Mesh::quad(
            [
                Vec3::new(1.0, 0.8, 1.0),
                Vec3::new(1.0, 0.8, 2.0),
                Vec3::new(2.0, 0.8, 2.0),
                Vec3::new(2.0, 0.8, 1.0),
            ],
            grey,
        ));
        s.add_instance("Desk", desk, Mat4::IDENTITY);
        let id = s.surface("Desk").unwrap();
        s.make_calculation_surface(id);
        (s, id)
    }

    fn triangles(s: &Scene, id: SurfaceId) -> Vec<[Vec3; 3]> {
        s.surfaces[id]
            .instances
            .iter()
            .flat_map(|&i| s.world_triangles(i))
            .map(|t| t.corners)
            .collect()
    }

    #[test]
    fn the_bands_frame_the_task_area_within_the_room() {
        let (mut s, desk) = office();
        let areas = s
            .add_task_areas(Path::new("office.gltf"), desk, &AreaKind::ALL)
            .unwrap();
        let kinds: Vec<_> = areas.iter().map(|a| a.kind).collect();
        use AreaKind::*;
        assert_eq!(
            kinds,
            [Surrounding, Background, Wall, Wall, Wall, Wall, Ceiling]
        );
        // The surrounding: (2 m)² less the desk's 1 m²; the background: 3 m around
        // that square, which reaches three walls and stops 0.5 m short of the far one
        // (4 m × 5.5 m), less the square.
        let want = [3.0, 18.0];
        for (a, want) in areas.iter().zip(want) {
            assert!(s.is_calculation_surface(a.surface));
            let area = f64::from(s.surface_area(a.surface));
            assert!((area - want).abs() < 1e-4, "{}: {area} m²", a.name);
            for t in triangles(&s, a.surface) {
                let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
                assert!(n.dot(Vec3::Y) > 0.9999, "{} faces up", a.name);
                assert!(t.iter().all(|p| (p.y - 0.8).abs() < 1e-6));
                // No band covers the desk.
                let m = (t[0] + t[1] + t[2]) / 3.0;
                assert!(!(1.0..2.0).contains(&m.x) || !(1.0..2.0).contains(&m.z));
            }
        }
    }

    #[test]
    fn the_walls_and_ceiling_face_into_the_room_just_inside_it() {
        let (mut s, desk) = office();
        let areas = s
            .add_task_areas(Path::new("office.gltf"), desk, &AreaKind::ALL)
            .unwrap();
        let centre = Vec3::new(3.0, 1.5, 2.0);
        let e = ROOM_SURFACE_OFFSET as f32;
        let mut sum = 0.0;
        for a in areas.iter().filter(|a| a.kind == AreaKind::Wall) {
            sum += a.size.0;
            assert!((a.size.1 - (3.0 - 2.0 * ROOM_SURFACE_OFFSET)).abs() < 1e-9);
            for t in triangles(&s, a.surface) {
                let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
                assert!(n.y.abs() < 1e-6, "{} is vertical", a.name);
                assert!(n.dot(centre - t[0]) > 0.0, "{} faces in", a.name);
                let p = t[0];
                let from_wall = [p.x, 6.0 - p.x, p.z, 4.0 - p.z]
                    .into_iter()
                    .fold(f32::INFINITY, f32::min);
                assert!((from_wall - e).abs() < 1e-5, "{}: {p}", a.name);
            }
        }
        assert!((sum - 2.0 * (6.0 + 4.0 - 4.0 * ROOM_SURFACE_OFFSET)).abs() < 1e-6);
        let ceiling = areas.last().unwrap();
        for t in triangles(&s, ceiling.surface) {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
            assert!(n.dot(Vec3::NEG_Y) > 0.9999);
            assert!(t.iter().all(|p| (p.y - (3.0 - e)).abs() < 1e-5));
        }
    }

    #[test]
    fn only_the_kinds_asked_are_built() {
        let (mut s, desk) = office();
        let before = s.surfaces.len();
        let kinds = [AreaKind::Surrounding, AreaKind::Ceiling];
        let areas = s
            .add_task_areas(Path::new("office.gltf"), desk, &kinds)
            .unwrap();
        let built: Vec<AreaKind> = areas.iter().map(|a| a.kind).collect();
        assert_eq!(built, kinds);
        assert_eq!(s.surfaces.len(), before + 2);
        assert!(s.surface("wall 1").is_none() && s.surface("background").is_none());
    }

    #[test]
    fn a_task_area_filling_the_room_has_no_bands_and_names_stay_unique() {
        let (mut s, _) = office();
        let floor = s.surface("Floor").unwrap();
        let grey = s.add_material(Material::diffuse("White", Vec3::ONE));
        let mesh = s.add_mesh(Mesh::quad([Vec3::ZERO; 4], grey));
        s.add_instance("ceiling", mesh, Mat4::IDENTITY);
        let areas = s
            .add_task_areas(Path::new("office.gltf"), floor, &AreaKind::ALL)
            .unwrap();
        assert!(areas.iter().all(|a| a.kind != AreaKind::Surrounding));
        assert!(areas.iter().all(|a| a.kind != AreaKind::Background));
        assert_eq!(areas.last().unwrap().name, "ceiling (EN 12464-1)");
    }

    #[test]
    fn a_task_area_that_is_not_horizontal_is_refused_with_a_hint() {
        let (mut s, _) = office();
        let grey = s.add_material(Material::diffuse("Board", Vec3::ONE));
        let board = s.add_mesh(Mesh::quad(
            [
                Vec3::new(0.0, 1.0, 1.0),
                Vec3::new(0.0, 1.0, 3.0),
                Vec3::new(0.0, 2.0, 3.0),
                Vec3::new(0.0, 2.0, 1.0),
            ],
            grey,
        ));
        s.add_instance("Board", board, Mat4::IDENTITY);
        let id = s.surface("Board").unwrap();
        let e = s
            .add_task_areas(Path::new("office.gltf"), id, &AreaKind::ALL)
            .unwrap_err();
        let text = e.to_string();
        assert!(text.contains("not one horizontal plane"), "{text}");
        assert!(text.contains("--no-areas"), "{text}");
    }
}
