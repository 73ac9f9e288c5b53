//! Scene pieces and closed forms shared by the photon tests (`closed_forms.rs`,
//! `connections.rs`, `photometry.rs`, `intentions.rs`); each test binary uses a part.
#![allow(dead_code)]

use invlight_scene::{Light, LightKind, Mat4, Material, MaterialId, Mesh, Scene, Vec2, Vec3};
use invlight_stats::Estimate;

/// Standard errors an estimate may miss its exact value by: a 4 σ miss has probability
/// 6·10⁻⁵ for an honest interval.
pub const Z: f64 = 4.0;

/// `e` within [`Z`] of its σ of `exact`, and σ below `informative` × exact: an interval
/// that wide would make the first check mean nothing.
pub fn assert_near(e: &Estimate, exact: f64, informative: f64, what: &str) {
    let err = (e.mean - exact).abs();
    assert!(
        err < Z * e.std_error,
        "{what}: estimate {} ± {} lx, exact {exact} lx ({:.1} σ off)",
        e.mean,
        e.std_error,
        err / e.std_error
    );
    assert!(
        e.std_error < informative * exact,
        "{what}: σ {} too large",
        e.std_error
    );
}

/// A point light of `cd` candela, white.
pub fn point(name: &str, position: Vec3, cd: f32) -> Light {
    Light {
        c0: invlight_scene::Vec3::X,
        name: name.into(),
        kind: LightKind::Point {
            position,
            intensity: Vec3::splat(cd),
        },
    }
}

/// A horizontal rectangle [x0,x1]×[y0,y1] at height z, counter-clockwise seen from +z,
/// with texture coordinates (0,0)..(1,1) from corner (x0,y0) to (x1,y1).
pub fn rect(x0: f32, x1: f32, y0: f32, y1: f32, z: f32, m: MaterialId) -> Mesh {
    let mut q = Mesh::quad(
        [
            Vec3::new(x0, y0, z),
            Vec3::new(x1, y0, z),
            Vec3::new(x1, y1, z),
            Vec3::new(x0, y1, z),
        ],
        m,
    );
    q.uvs = vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(0.0, 1.0),
    ];
    q
}

/// Solid angle of the rectangle [0,x]×[0,y] at z = 0 seen from (0,0,h), signed by x·y.
fn corner_solid_angle(x: f64, y: f64, h: f64) -> f64 {
    (x * y / (h * (x * x + y * y + h * h).sqrt())).atan()
}

/// Solid angle of [x0,x1]×[y0,y1] at z = 0 seen from (0,0,h) (corner decomposition).
pub fn rect_solid_angle(x0: f64, x1: f64, y0: f64, y1: f64, h: f64) -> f64 {
    corner_solid_angle(x1, y1, h) - corner_solid_angle(x0, y1, h) - corner_solid_angle(x1, y0, h)
        + corner_solid_angle(x0, y0, h)
}

/// A grey (ρ = 0.5) 10 × 10 m roof at z = 3 with a 1 × 1 m hole over [0,1]×[0,1], and a
/// black floor [−h,h]² at z = 0 ("Roof", "Opening", "Floor"); no light.
pub fn roof_with_hole(h: f32) -> Scene {
    let mut scene = Scene::default();
    let grey = scene.add_material(Material::diffuse("Grey", Vec3::splat(0.5)));
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    let hole = scene.add_material(Material::hole("Hole"));
    let roof = scene.add_mesh(rect(-5.0, 5.0, -5.0, 5.0, 3.0, grey));
    let opening = scene.add_mesh(rect(0.0, 1.0, 0.0, 1.0, 3.0, hole));
    let floor = scene.add_mesh(rect(-h, h, -h, h, 0.0, black));
    scene.add_instance("Roof", roof, Mat4::IDENTITY);
    scene.add_instance("Opening", opening, Mat4::IDENTITY);
    scene.add_instance("Floor", floor, Mat4::IDENTITY);
    scene
}
