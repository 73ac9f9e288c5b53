//! Which wall of the model each of EN 12464-1's wall areas stands for, so that a
//! verdict names a wall a designer can find: the model's own name for it where one
//! object of the scene makes up most of that wall, seen from the room, and no other
//! wall ("WallNorth"), else
//! its place where it is square to the scene's axes ("wall x = 9.00 m"), else its
//! number.

use crate::model::{InstanceId, Scene};
use glam::Vec3;
use std::collections::HashMap;

/// How far a model's triangle may lie from a calculation wall and still be that wall,
/// m: the calculation rectangle stands [`crate::ROOM_SURFACE_OFFSET`] inside, and
/// a wall's faces may be modelled with some thickness.
const WALL_DEPTH: f32 = 0.1;

/// The share of a calculation wall one object must cover to lend it its name.
const COVER: f64 = 0.5;

/// A wall's plane and extent: its corner, its two unit edges and their lengths, and
/// its unit normal.
struct WallFrame {
    origin: Vec3,
    u: Vec3,
    v: Vec3,
    size: (f32, f32),
    normal: Vec3,
}

impl WallFrame {
    fn of(quad: &[Vec3; 4]) -> WallFrame {
        let (eu, ev) = (quad[1] - quad[0], quad[3] - quad[0]);
        WallFrame {
            origin: quad[0],
            u: eu.normalize(),
            v: ev.normalize(),
            size: (eu.length(), ev.length()),
            normal: eu.cross(ev).normalize(),
        }
    }

    /// How far in front of this wall's plane (into the room) the point `p` lies, when
    /// it lies against the wall: within [`WALL_DEPTH`] of its plane and inside its
    /// extent.
    fn holds(&self, p: Vec3) -> Option<f32> {
        let d = p - self.origin;
        let (s, t, h) = (d.dot(self.u), d.dot(self.v), d.dot(self.normal));
        (h.abs() <= WALL_DEPTH
            && (0.0..=self.size.0).contains(&s)
            && (0.0..=self.size.1).contains(&t))
        .then_some(h)
    }
}

impl Scene {
    /// A name for each of `walls` (calculation rectangles facing into the room, each
    /// `offset` m in front of its wall), as the module doc says.
    pub(crate) fn wall_names(&self, walls: &[[Vec3; 4]], offset: f64) -> Vec<String> {
        let frames: Vec<WallFrame> = walls.iter().map(WallFrame::of).collect();
        let calc = self.calculation_instances();
        // Per wall and object: the area it covers, and that area × its distance in front.
        let mut covered: Vec<HashMap<&str, (f64, f64)>> = vec![HashMap::new(); walls.len()];
        for i in (0..self.instances.len()).filter(|&i| !calc[i]) {
            let name = self.instances[i].name.as_str();
            for t in self.world_triangles(InstanceId::from_index(i)) {
                let area = 0.5 * f64::from(t.cross.length());
                let centroid = (t.corners[0] + t.corners[1] + t.corners[2]) / 3.0;
                let n = t.cross.normalize_or_zero();
                for (w, f) in frames.iter().enumerate() {
                    if n.dot(f.normal).abs() <= 0.99 {
                        continue;
                    }
                    if let Some(h) = f.holds(centroid) {
                        let c = covered[w].entry(name).or_default();
                        *c = (c.0 + area, c.1 + area * f64::from(h));
                    }
                }
            }
        }
        let owner: Vec<Option<&str>> = covered
            .iter()
            .zip(&frames)
            .map(|(c, f)| {
                let wall = f64::from(f.size.0 * f.size.1);
                // Of the objects that make up the wall, the one seen from the room: a
                // board hung on the room's box.
                c.iter()
                    .filter(|&(_, &(a, _))| a >= COVER * wall)
                    .max_by(|a, b| (a.1.1 / a.1.0).total_cmp(&(b.1.1 / b.1.0)))
                    .map(|(&n, _)| n)
            })
            .collect();
        frames
            .iter()
            .enumerate()
            .map(|(w, f)| match owner[w] {
                Some(n) if owner.iter().filter(|&&o| o == Some(n)).count() == 1 => n.to_string(),
                _ => placed(f, offset).unwrap_or_else(|| format!("wall {}", w + 1)),
            })
            .collect()
    }
}

/// "wall x = 9.00 m": the wall's plane, `offset` behind the calculation rectangle `f`,
/// where it is square to a world axis.
fn placed(f: &WallFrame, offset: f64) -> Option<String> {
    let axis = ["x", "y", "z"]
        .into_iter()
        .zip([Vec3::X, Vec3::Y, Vec3::Z])
        .find(|(_, a)| f.normal.dot(*a).abs() > 0.999)?;
    let at = f.origin.as_dvec3() - f.normal.as_dvec3() * offset;
    let coordinate = at.dot(axis.1.as_dvec3());
    // -0.00 reads as 0.00.
    let coordinate = if coordinate.abs() < 0.005 {
        0.0
    } else {
        coordinate
    };
    Some(format!("wall {} = {coordinate:.2} m", axis.0))
}

#[cfg(test)]
mod tests {
    use crate::{AreaKind, Mat4, Material, Mesh, Scene};
    use glam::Vec3;
    use std::path::Path;

    /// A closed 6 m × 4 m room, 3 m high, Y up, its walls one object, with a 1 m × 1 m
    /// desk area at 0.8 m and, on the wall z = 0, a board of `board` metres wide.
    fn room(board: f32) -> Scene {
        let mut s = Scene::default();
        let grey = s.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
        let room = s.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::new(6.0, 3.0, 4.0), grey));
        s.add_instance("Room", room, Mat4::IDENTITY);
        let quad = |c: [Vec3; 4]| Mesh::quad(c, grey);
        let floor = s.add_mesh(quad([
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 4.0),
            Vec3::new(6.0, 0.0, 4.0),
            Vec3::new(6.0, 0.0, 0.0),
        ]));
        s.add_instance("Floor", floor, Mat4::IDENTITY);
        let board = s.add_mesh(quad([
            Vec3::new(3.0 - board / 2.0, 0.0, 0.02),
            Vec3::new(3.0 + board / 2.0, 0.0, 0.02),
            Vec3::new(3.0 + board / 2.0, 3.0, 0.02),
            Vec3::new(3.0 - board / 2.0, 3.0, 0.02),
        ]));
        s.add_instance("Board", board, Mat4::IDENTITY);
        let desk = s.add_mesh(quad([
            Vec3::new(1.0, 0.8, 1.0),
            Vec3::new(1.0, 0.8, 2.0),
            Vec3::new(2.0, 0.8, 2.0),
            Vec3::new(2.0, 0.8, 1.0),
        ]));
        s.add_instance("Desk", desk, Mat4::IDENTITY);
        let id = s.surface("Desk").unwrap();
        s.make_calculation_surface(id);
        s
    }

    fn walls(s: &mut Scene) -> Vec<String> {
        let desk = s.surface("Desk").unwrap();
        let mut names: Vec<String> = s
            .add_task_areas(Path::new("room.gltf"), desk, &[AreaKind::Wall])
            .unwrap()
            .into_iter()
            .map(|a| a.name)
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_wall_is_named_for_the_object_that_makes_it_else_for_its_place() {
        // The room's box makes up all four walls: each is named by its plane.
        let mut s = room(1.0);
        assert_eq!(
            walls(&mut s),
            [
                "wall x = 0.00 m",
                "wall x = 6.00 m",
                "wall z = 0.00 m",
                "wall z = 4.00 m"
            ]
        );
        // A board across most of the wall z = 0 lends it its name (made unique beside
        // the object's own).
        let mut s = room(5.5);
        let names = walls(&mut s);
        assert!(
            names.contains(&"Board (EN 12464-1)".to_string()),
            "{names:?}"
        );
        assert!(!names.contains(&"wall z = 0.00 m".to_string()), "{names:?}");
        assert!(names.contains(&"wall z = 4.00 m".to_string()), "{names:?}");
    }
}
