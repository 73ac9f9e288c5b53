//! Holes (apertures): ILPSolver's convention (thesis §4.1, fig. 4.2). An object whose
//! material is a hole is not drawn; its object-space bounding box, carried to the world
//! by its instance transform, is a volume inside which every surface is transparent, so a
//! hole rectangle lying in a roof cuts a window in the roof.

use glam::{Mat3A, Mat4, Vec3, Vec3A};

/// Half-thickness given to a flat (zero-extent) direction of a hole's box, relative to
/// the scene's bounding-box diagonal: a hole rectangle modelled in the plane of a wall
/// must cut the wall despite rounding (10⁻⁴ of a 40 m atrium is 4 mm).
pub const HOLE_THICKNESS: f32 = 1.0e-4;

/// An oriented box (a parallelepiped under a sheared transform) in world space.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HoleVolume {
    centre: Vec3A,
    /// World → box coordinates, in which the box is [-1, 1]³.
    to_unit: Mat3A,
}

impl HoleVolume {
    /// The world image under `transform` of the object-space box `lo..hi`, flat
    /// directions thickened to `thickness` either side.
    pub fn new(lo: Vec3, hi: Vec3, transform: &Mat4, thickness: f32) -> Option<Self> {
        let centre = transform.transform_point3((lo + hi) * 0.5);
        let half = (hi - lo) * 0.5;
        let axes: [Vec3; 3] =
            std::array::from_fn(|i| transform.transform_vector3(Vec3::AXES[i] * half[i]));
        // Directions: the transformed axes where they have length, completed to a basis
        // by cross products (one flat direction) or any perpendiculars (two or three).
        let long: Vec<usize> = (0..3).filter(|&i| axes[i].length() > thickness).collect();
        let mut dirs: [Vec3; 3] = std::array::from_fn(|i| axes[i].normalize_or_zero());
        match long.as_slice() {
            [_, _, _] => {}
            [a, b] => {
                let flat = 3 - a - b;
                dirs[flat] = axes[*a].cross(axes[*b]).normalize_or_zero();
            }
            [a] => {
                let (p, q) = dirs[*a].any_orthonormal_pair();
                let mut others = (0..3).filter(|i| i != a);
                dirs[others.next()?] = p;
                dirs[others.next()?] = q;
            }
            _ => dirs = [Vec3::X, Vec3::Y, Vec3::Z],
        }
        let cols: [Vec3; 3] = std::array::from_fn(|i| dirs[i] * axes[i].length().max(thickness));
        let m = Mat3A::from_cols(cols[0].into(), cols[1].into(), cols[2].into());
        if m.determinant().abs() <= f32::MIN_POSITIVE {
            return None;
        }
        Some(HoleVolume {
            centre: centre.into(),
            to_unit: m.inverse(),
        })
    }

    /// Whether `p` lies inside (boundary included).
    #[inline(always)]
    pub fn contains(&self, p: Vec3A) -> bool {
        (self.to_unit * (p - self.centre)).abs().max_element() <= 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_rectangle_becomes_a_thin_slab() {
        // A unit square in the xy plane, rotated into the xz plane and moved up.
        let t = Mat4::from_translation(Vec3::new(0.0, 3.0, 0.0))
            * Mat4::from_rotation_x(std::f32::consts::FRAC_PI_2);
        let h = HoleVolume::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), &t, 0.01).unwrap();
        // Rotating xy by +90° about x maps y to z.
        assert!(h.contains(Vec3A::new(0.5, 3.0, 0.5)));
        assert!(h.contains(Vec3A::new(0.5, 3.009, 0.5)));
        assert!(!h.contains(Vec3A::new(0.5, 3.011, 0.5)));
        assert!(!h.contains(Vec3A::new(1.01, 3.0, 0.5)));
        assert!(!h.contains(Vec3A::new(0.5, 3.0, -0.01)));
    }
}
