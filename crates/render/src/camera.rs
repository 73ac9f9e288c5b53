//! Perspective views: the scene's camera, or a default three-quarter view of its bounding
//! box when it has none.

use glam::Vec3;
use invlight_scene::{Camera, Scene};
use invlight_trace::Ray;

/// A pinhole camera ready to generate rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Eye position, m.
    pub origin: Vec3,
    /// Unit viewing direction.
    pub forward: Vec3,
    /// Unit right vector of the image plane.
    pub right: Vec3,
    /// Unit up vector of the image plane.
    pub up: Vec3,
    /// tan(yfov/2).
    pub tan_half: f32,
    /// Width / height of the image.
    pub aspect: f32,
}

/// Vertical field of view of the default view, radians (50°, a "normal" lens).
const DEFAULT_YFOV: f32 = 50.0 * std::f32::consts::PI / 180.0;

impl View {
    /// The view of `camera` on an image of `aspect` = width / height.
    pub fn from_camera(camera: &Camera, aspect: f32) -> View {
        let forward = camera.forward.normalize();
        let right = forward.cross(camera.up).normalize();
        View {
            origin: camera.position,
            forward,
            right,
            up: right.cross(forward),
            tan_half: (camera.yfov * 0.5).tan(),
            aspect,
        }
    }

    /// A view of the whole scene from the front, a little to the right and above (with
    /// respect to the scene's up axis), far enough that its bounding sphere fits the
    /// vertical field of view. `None` when the scene is empty.
    pub fn default_for(scene: &Scene, aspect: f32) -> Option<View> {
        let (lo, hi) = scene.bounds()?;
        let centre = (lo + hi) * 0.5;
        let radius = ((hi - lo).length() * 0.5).max(1e-3);
        let up = scene.up.normalize();
        // The front: +Z when Y is up (glTF), −Y when Z is up (Blender's front view).
        let front = if up.z.abs() > 0.9 {
            Vec3::new(0.0, -up.z.signum(), 0.0)
        } else {
            Vec3::Z
        };
        let side = up.cross(front).normalize();
        let from = (front + 0.5 * side + 0.5 * up).normalize();
        let fov = DEFAULT_YFOV.min(2.0 * (aspect * (DEFAULT_YFOV * 0.5).tan()).atan());
        let distance = radius / (fov * 0.5).sin();
        let camera = Camera {
            name: String::new(),
            position: centre + from * distance,
            forward: -from,
            up: (up - from * up.dot(from)).normalize(),
            yfov: DEFAULT_YFOV,
            aspect: Some(aspect),
        };
        Some(View::from_camera(&camera, aspect))
    }

    /// Where the world point `p` appears on a `width` × `height` image, pixels from
    /// the top-left corner: the inverse of [`View::ray`]; `None` behind the camera.
    pub fn pixel(&self, p: Vec3, width: u32, height: u32) -> Option<(f32, f32)> {
        let d = p - self.origin;
        let z = d.dot(self.forward);
        if z <= 1e-6 {
            return None;
        }
        let x = d.dot(self.right) / (z * self.tan_half * self.aspect);
        let y = d.dot(self.up) / (z * self.tan_half);
        Some((
            0.5 * (x + 1.0) * width as f32,
            0.5 * (1.0 - y) * height as f32,
        ))
    }

    /// The ray through the image point (`sx`, `sy`), both in [0, 1], `sy` = 0 at the top.
    #[inline]
    pub fn ray(&self, sx: f32, sy: f32) -> Ray {
        let x = (2.0 * sx - 1.0) * self.tan_half * self.aspect;
        let y = (1.0 - 2.0 * sy) * self.tan_half;
        let dir = (self.forward + self.right * x + self.up * y).normalize();
        Ray::new(self.origin, dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use invlight_scene::{Mat4, Material, Mesh};

    #[test]
    fn camera_rays_span_the_field_of_view() {
        let camera = Camera {
            name: "c".into(),
            position: Vec3::ZERO,
            forward: Vec3::NEG_Z,
            up: Vec3::Y,
            yfov: std::f32::consts::FRAC_PI_2,
            aspect: None,
        };
        let view = View::from_camera(&camera, 2.0);
        assert!((view.ray(0.5, 0.5).dir - Vec3::NEG_Z).length() < 1e-6);
        // tan 45° = 1: the top edge is at 45° up, the right edge at atan 2.
        let top = view.ray(0.5, 0.0).dir;
        assert!((top - Vec3::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6);
        let right = view.ray(1.0, 0.5).dir;
        assert!((right - Vec3::new(2.0, 0.0, -1.0).normalize()).length() < 1e-6);
        // A point on the ray through a pixel projects back onto that pixel.
        let r = view.ray(0.25, 0.75);
        let (x, y) = view.pixel(r.origin + r.dir * 3.0, 200, 100).unwrap();
        assert!((x - 50.0).abs() < 1e-3 && (y - 75.0).abs() < 1e-3);
        assert!(view.pixel(Vec3::new(0.0, 0.0, 1.0), 200, 100).is_none());
    }

    #[test]
    fn default_view_looks_at_the_scene() {
        let mut scene = Scene::default();
        let m = scene.add_material(Material::diffuse("g", Vec3::splat(0.5)));
        let mesh = scene.add_mesh(Mesh::cuboid(Vec3::ZERO, Vec3::ONE, m));
        scene.add_instance("box", mesh, Mat4::IDENTITY);
        let view = View::default_for(&scene, 1.5).unwrap();
        let to_centre = (Vec3::splat(0.5) - view.origin).normalize();
        assert!((view.forward - to_centre).length() < 1e-5);
        assert!(view.up.dot(Vec3::Y) > 0.0);
        assert!(View::default_for(&Scene::default(), 1.0).is_none());
    }
}
