//! Triangle meshes in object space.

use crate::model::MaterialId;
use glam::{Mat4, Vec2, Vec3};

/// A triangle mesh in its own (object) space; [`crate::Instance`]s place it in the world.
///
/// Triangles wind counter-clockwise seen from their front face, the side an emissive
/// triangle emits from. Every triangle blocks light from both sides.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Texture coordinates per vertex; empty when the mesh has none.
    pub uvs: Vec<Vec2>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Material of each triangle (parallel to `triangles`).
    pub materials: Vec<MaterialId>,
}

impl Mesh {
    /// A planar quad `a b c d` (counter-clockwise) of one material, as two triangles.
    pub fn quad(corners: [Vec3; 4], material: MaterialId) -> Self {
        Mesh {
            positions: corners.to_vec(),
            uvs: Vec::new(),
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            materials: vec![material; 2],
        }
    }

    /// An axis-aligned box between `min` and `max` with outward-facing triangles.
    pub fn cuboid(min: Vec3, max: Vec3, material: MaterialId) -> Self {
        let p = |x: bool, y: bool, z: bool| {
            Vec3::new(
                if x { max.x } else { min.x },
                if y { max.y } else { min.y },
                if z { max.z } else { min.z },
            )
        };
        let positions: Vec<Vec3> = (0..8)
            .map(|i| p(i & 1 != 0, i & 2 != 0, i & 4 != 0))
            .collect();
        // Faces as counter-clockwise quads seen from outside.
        let faces = [
            [0, 2, 3, 1], // -z
            [4, 5, 7, 6], // +z
            [0, 1, 5, 4], // -y
            [2, 6, 7, 3], // +y
            [0, 4, 6, 2], // -x
            [1, 3, 7, 5], // +x
        ];
        let triangles: Vec<[u32; 3]> = faces
            .iter()
            .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
            .collect();
        Mesh {
            positions,
            uvs: Vec::new(),
            materials: vec![material; triangles.len()],
            triangles,
        }
    }

    /// The three corners of triangle `t` in object space.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Area of triangle `t` after `transform`, m².
    pub fn triangle_area(&self, t: usize, transform: &Mat4) -> f32 {
        let [a, b, c] = self.triangle(t).map(|p| transform.transform_point3(p));
        0.5 * (b - a).cross(c - a).length()
    }

    /// Total area after `transform`, m².
    pub fn area(&self, transform: &Mat4) -> f32 {
        (0..self.triangles.len())
            .map(|t| self.triangle_area(t, transform) as f64)
            .sum::<f64>() as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuboid_faces_point_outward() {
        let m = Mesh::cuboid(Vec3::ZERO, Vec3::ONE, MaterialId::from_index(0));
        let centre = Vec3::splat(0.5);
        for t in 0..m.triangles.len() {
            let [a, b, c] = m.triangle(t);
            let n = (b - a).cross(c - a);
            assert!(n.dot((a + b + c) / 3.0 - centre) > 0.0, "triangle {t}");
        }
        assert!((m.area(&Mat4::IDENTITY) - 6.0).abs() < 1e-6);
    }
}
