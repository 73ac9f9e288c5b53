//! The luminaires an eye sees, each with its share of CIE 117's glare sum L²·ω/p²:
//! L its luminance toward the eye (its intensity toward the eye over its luminous area
//! projected on the line of sight), ω the solid angle of that projected area, p Guth's
//! position index. All exact, from the luminaires' candela tables and luminous openings.
//!
//! A luminaire counts when its photometric centre is in front of the eye (less than 90°
//! from the line of sight) and nothing opaque lies between (calculation surfaces do not
//! shade). An emissive surface (a glTF emissive material, a COLLADA or OBJ light panel)
//! is a luminaire of known luminance, summed triangle by triangle. A light without a
//! luminous area — a point or spot light, or a photometric file that gives no luminous
//! dimensions — has no luminance, and UGR is refused rather than guessed. Directional
//! light (the sun) and the sky are not luminaires: their reflected light is in the
//! background, their glare is daylight glare's (DGP).

use super::{GlareError, Observer};
use glam::Vec3;
use invlight_scene::{InstanceId, Light, LightId, LightKind, Opening, Scene, luminance};
use invlight_trace::{Accel, Ray};
use serde::Serialize;

/// One luminaire's share of the glare.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GlareSource {
    /// The light's name.
    pub name: String,
    /// Its luminance toward the eye, cd/m².
    pub luminance: f64,
    /// The solid angle its projected luminous area subtends at the eye, sr.
    pub solid_angle: f64,
    /// Guth's position index p.
    pub position_index: f64,
    /// Its term of the sum, L²·ω/p², cd²/m⁴·sr.
    pub contribution: f64,
    /// Its intensity toward the eye, cd.
    pub intensity: f64,
    /// The distance from the eye to its photometric centre, m.
    pub distance: f64,
    /// The angle between the line of sight and the direction to it, degrees.
    pub off_axis: f64,
    /// The light or emissive instance it is, for the component its level dims.
    #[serde(skip)]
    pub origin: GlareOrigin,
}

/// What a glare source is in the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GlareOrigin {
    /// `scene.lights[i]`.
    Light(LightId),
    /// The emissive triangles of an instance.
    Instance(InstanceId),
}

/// Guth's position index of a source seen along the unit direction `to_source` by an
/// eye looking along the unit `view` with the unit `up` (perpendicular to `view`) as its
/// vertical.
///
/// Above the line of sight, Levin's closed form of Guth's table (IES Lighting
/// Handbook; evalglare's `get_posindex`):
/// p = exp[(35.2 − 0.31889τ − 1.22e^(−2τ/9))·10⁻³·σ + (21 + 0.26667τ − 0.002963τ²)·10⁻⁵·σ²],
/// σ the angle from the line of sight and τ the angle, in the picture plane, between
/// the vertical and the direction to the source, both in degrees. Below it, Iwata's
/// model as evalglare has it: p = 1 + f·R with R = √(tan²φ + tan²θ) (φ, θ the vertical
/// and horizontal angles, R at most 3), f = 0.8 up to R = 0.6 and 1.2 beyond. p is at
/// most 16, where the table ends. On the line of sight p = 1.
pub fn position_index(view: Vec3, up: Vec3, to_source: Vec3) -> f64 {
    let (view, up, d) = (view.as_dvec3(), up.as_dvec3(), to_source.as_dvec3());
    let right = view.cross(up);
    let along = d.dot(view);
    let sigma = along.clamp(-1.0, 1.0).acos().to_degrees();
    let elevation = d.dot(up).clamp(-1.0, 1.0).asin();
    let p = if elevation >= 0.0 {
        let picture = d / along - view;
        let tau = if picture.length() < 1e-12 {
            0.0
        } else {
            picture.angle_between(up).to_degrees()
        };
        ((35.2 - 0.31889 * tau - 1.22 * (-2.0 * tau / 9.0).exp()) / 1000.0 * sigma
            + (21.0 + 0.26667 * tau - 0.002963 * tau * tau) / 100_000.0 * sigma * sigma)
            .exp()
    } else {
        let sideways = d.dot(right).clamp(-1.0, 1.0).asin();
        let r = (elevation.tan().powi(2) + sideways.tan().powi(2)).sqrt();
        let f = if r > 0.6 { 1.2 } else { 0.8 };
        1.0 + f * r.min(3.0)
    };
    p.min(16.0)
}

/// The line of sight and its vertical, unit vectors, for a scene whose zenith is `up`.
pub(super) fn sight(observer: &Observer, up: Vec3) -> Result<(Vec3, Vec3), GlareError> {
    if !observer.eye.is_finite() {
        return Err(GlareError::NoEye);
    }
    let view = observer.view.normalize_or_zero();
    if view == Vec3::ZERO || !view.is_finite() {
        return Err(GlareError::NoView);
    }
    let vertical = (up - view * up.dot(view)).normalize_or_zero();
    if vertical.length() < 0.5 || view.dot(up).abs() > 0.9999 {
        return Err(GlareError::ViewAlongUp);
    }
    Ok((view, vertical))
}

/// The luminous area of `opening` (raised by `height` at its sides) projected on the
/// plane perpendicular to the unit local direction `w`, m²: its face seen from below
/// (the opening faces local −Z) and its sides, as CIE 117 projects a luminaire.
fn projected_area(opening: &Opening, height: f32, w: Vec3) -> f64 {
    let (w, h) = (w.as_dvec3(), f64::from(height));
    let face = f64::from(opening.area()) * (-w.z).max(0.0);
    // The sides' shadow is the height times the opening's width across the horizontal
    // part of `w`: a·|w_y| + b·|w_x| for a rectangle, √((a·w_y)² + (b·w_x)²) for an
    // ellipse of axes a, b (a disk's d·|w_h|).
    let [a, b] = opening.extents().map(f64::from);
    let sides = match *opening {
        Opening::Point => 0.0,
        Opening::Rectangle { .. } => h * (a * w.y.abs() + b * w.x.abs()),
        Opening::Disk { .. } | Opening::Ellipse { .. } => h * (a * w.y).hypot(b * w.x),
    };
    face + sides
}

/// Whether the segment from `from` to `to` is clear of opaque surfaces (calculation
/// surfaces do not shade), a centimetre short of `to` so that a luminaire set into a
/// ceiling is seen.
fn clear(scene: &Scene, accel: &Accel, from: Vec3, to: Vec3) -> bool {
    let calculation = scene.calculation_instances();
    let (dir, length) = ((to - from).normalize(), (to - from).length());
    let mut start = 0.0f32;
    for _ in 0..64 {
        let mut ray = Ray::new(from + dir * start, dir);
        ray.t_max = length - 0.01 - start;
        if ray.t_max <= 0.0 {
            return true;
        }
        match accel.intersect(&ray) {
            None => return true,
            Some(hit) if calculation.get(hit.instance.index()).copied() == Some(true) => {
                start += hit.t + 1e-4;
            }
            Some(_) => return false,
        }
    }
    false
}

/// The luminaires `observer` sees, each with its luminance, solid angle and position
/// index; refused when one in view has no luminous area.
pub fn glare_sources(
    scene: &Scene,
    accel: &Accel,
    observer: &Observer,
) -> Result<Vec<GlareSource>, GlareError> {
    sources_at(scene, accel, observer, true)
}

/// [`glare_sources`] with the lights in view that have no luminous area left out, for a
/// search that refused them before it started; none when the line of sight is refused.
pub(super) fn seen(scene: &Scene, accel: &Accel, observer: &Observer) -> Vec<GlareSource> {
    sources_at(scene, accel, observer, false).unwrap_or_default()
}

/// The luminaires in view; one without a luminous area is refused when `strict`, else
/// left out.
fn sources_at(
    scene: &Scene,
    accel: &Accel,
    observer: &Observer,
    strict: bool,
) -> Result<Vec<GlareSource>, GlareError> {
    let (view, vertical) = sight(observer, scene.up)?;
    let mut sources = Vec::new();
    for (l, light) in scene.lights.iter().enumerate() {
        let Some(position) = light.kind.position() else {
            continue;
        };
        let offset = position - observer.eye;
        let distance = f64::from(offset.length());
        let to_source = offset.normalize_or_zero();
        if distance <= 0.0 || to_source.dot(view) <= 0.0 {
            continue;
        }
        let intensity = f64::from(luminance(light.kind.intensity_toward(-to_source)));
        if intensity <= 0.0 || !clear(scene, accel, observer.eye, position) {
            continue;
        }
        let area = match &light.kind {
            LightKind::Goniometric {
                frame, photometry, ..
            } if photometry.opening != Opening::Point => {
                let local = frame.transpose() * -to_source;
                projected_area(&photometry.opening, photometry.opening_height, local)
            }
            LightKind::Directional { .. } => continue,
            _ if !strict => continue,
            _ => {
                return Err(light_without_luminous_area_of(light)
                    .expect("a light in view without a luminous area"));
            }
        };
        if area <= 0.0 {
            continue;
        }
        let luminance = intensity / area;
        let solid_angle = area / (distance * distance);
        let p = position_index(view, vertical, to_source);
        sources.push(GlareSource {
            name: light.name.clone(),
            luminance,
            solid_angle,
            position_index: p,
            contribution: luminance * luminance * solid_angle / (p * p),
            intensity,
            distance,
            off_axis: f64::from(to_source.dot(view).clamp(-1.0, 1.0).acos().to_degrees()),
            origin: GlareOrigin::Light(LightId::from_index(l)),
        });
    }
    sources.extend(emissive_sources(scene, accel, observer.eye, view, vertical));
    Ok(sources)
}

/// The emissive surfaces the eye sees, one source per instance: each of its triangles
/// whose front faces the eye and whose centroid is in front of the eye and unshaded adds
/// L²·ω/p² at its centroid, with ω its area × cos θ / d² (the small-source form CIE 117
/// assumes); the instance's luminance is the solid-angle-weighted mean, its p the one
/// that gives its sum from that luminance and the total ω.
fn emissive_sources(
    scene: &Scene,
    accel: &Accel,
    eye: Vec3,
    view: Vec3,
    vertical: Vec3,
) -> Vec<GlareSource> {
    let calculation = scene.calculation_instances();
    let mut by_instance: Vec<(usize, Term)> = Vec::new();
    for (i, t) in scene.all_world_triangles() {
        let emission = scene.materials[t.material].emission;
        if calculation[i.index()] || emission.max_element() <= 0.0 || t.area() <= 0.0 {
            continue;
        }
        let centroid = (t.corners[0] + t.corners[1] + t.corners[2]) / 3.0;
        let offset = centroid - eye;
        let d = offset.length();
        let to_source = offset / d;
        let cos = -t.normal().dot(to_source);
        if d <= 0.0 || cos <= 0.0 || to_source.dot(view) <= 0.0 {
            continue;
        }
        if !clear(scene, accel, eye, centroid) {
            continue;
        }
        let l = f64::from(luminance(emission));
        let omega = f64::from(t.area() * cos) / f64::from(d * d);
        let p = position_index(view, vertical, to_source);
        let term = Term {
            omega,
            l_omega: l * omega,
            contribution: l * l * omega / (p * p),
            d_omega: f64::from(d) * omega,
            off_omega: f64::from(to_source.dot(view).clamp(-1.0, 1.0).acos().to_degrees()) * omega,
        };
        match by_instance.iter_mut().find(|(k, _)| *k == i.index()) {
            Some((_, sum)) => sum.add(&term),
            None => by_instance.push((i.index(), term)),
        }
    }
    by_instance
        .into_iter()
        .map(|(i, t)| {
            let l = t.l_omega / t.omega;
            GlareSource {
                name: scene.instances[i].name.clone(),
                luminance: l,
                solid_angle: t.omega,
                position_index: (l * l * t.omega / t.contribution).sqrt(),
                contribution: t.contribution,
                intensity: l * t.omega * (t.d_omega / t.omega).powi(2),
                distance: t.d_omega / t.omega,
                off_axis: t.off_omega / t.omega,
                origin: GlareOrigin::Instance(InstanceId::from_index(i)),
            }
        })
        .collect()
}

/// An emissive triangle's sums toward its instance's source.
#[derive(Debug, Clone, Copy)]
struct Term {
    omega: f64,
    l_omega: f64,
    contribution: f64,
    d_omega: f64,
    off_omega: f64,
}

impl Term {
    fn add(&mut self, t: &Term) {
        self.omega += t.omega;
        self.l_omega += t.l_omega;
        self.contribution += t.contribution;
        self.d_omega += t.d_omega;
        self.off_omega += t.off_omega;
    }
}

/// The first light of `scene` that could be in an eye's view and has no luminous area
/// (a point or spot light, a photometric file without luminous dimensions), as the
/// error [`glare_sources`] gives when it is seen: a search that rates glare while it
/// moves lights refuses such a scene before it starts rather than when a light comes
/// into view.
pub fn light_without_luminous_area(scene: &Scene) -> Option<GlareError> {
    scene.lights.iter().find_map(light_without_luminous_area_of)
}

/// The refusal `light` earns in view when it has no luminous area.
fn light_without_luminous_area_of(light: &Light) -> Option<GlareError> {
    match &light.kind {
        LightKind::Goniometric { photometry, .. } if photometry.opening == Opening::Point => {
            Some(no_area(&light.name, "a photometric file"))
        }
        LightKind::Point { .. } => Some(no_area(&light.name, "a point light")),
        LightKind::Spot { .. } => Some(no_area(&light.name, "a spot light")),
        _ => None,
    }
}

fn no_area(light: &str, kind: &'static str) -> GlareError {
    GlareError::NoLuminousArea {
        light: light.to_string(),
        kind,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const VIEW: Vec3 = Vec3::X;
    const UP: Vec3 = Vec3::Z;

    fn toward(elevation: f32, azimuth: f32) -> Vec3 {
        let (e, a) = (elevation.to_radians(), azimuth.to_radians());
        Vec3::new(e.cos() * a.cos(), -e.cos() * a.sin(), e.sin())
    }

    #[test]
    fn position_index_is_one_on_the_line_of_sight_and_grows_away_from_it() {
        assert!((position_index(VIEW, UP, VIEW) - 1.0).abs() < 1e-12);
        let mut last = 1.0;
        for e in [10.0, 20.0, 30.0, 45.0, 60.0] {
            let p = position_index(VIEW, UP, toward(e, 0.0));
            assert!(p > last, "{e}°: {p} after {last}");
            last = p;
        }
        for e in [5.0, 30.0, 70.0] {
            let (l, r) = (toward(e, 25.0), toward(e, -25.0));
            let (pl, pr) = (position_index(VIEW, UP, l), position_index(VIEW, UP, r));
            assert!((pl - pr).abs() < 1e-9, "left {pl} right {pr}");
        }
        assert_eq!(position_index(VIEW, UP, toward(89.0, 80.0)), 16.0);
    }

    #[test]
    fn position_index_straight_above_follows_guths_closed_form() {
        // τ = 0: p = exp((35.2 − 1.22)·10⁻³·σ + 21·10⁻⁵·σ²).
        for sigma in [10.0f64, 30.0, 45.0] {
            let want = ((35.2 - 1.22) / 1000.0 * sigma + 21.0 / 100_000.0 * sigma * sigma).exp();
            let got = position_index(VIEW, UP, toward(sigma as f32, 0.0));
            assert!(
                (got - want).abs() < 1e-4 * want,
                "σ {sigma}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn position_index_below_the_line_of_sight_is_iwatas() {
        // 20° straight below: R = tan 20° = 0.364 ≤ 0.6, p = 1 + 0.8 R.
        let got = position_index(VIEW, UP, toward(-20.0, 0.0));
        let want = 1.0 + 0.8 * 20f64.to_radians().tan();
        assert!((got - want).abs() < 1e-5, "{got} vs {want}");
    }

    #[test]
    fn a_panel_seen_from_below_projects_its_face_and_from_the_side_its_edge() {
        let panel = Opening::Rectangle {
            along_c0: 0.6,
            along_c90: 0.3,
        };
        let below = projected_area(&panel, 0.05, -Vec3::Z);
        assert!((below - 0.18).abs() < 1e-6);
        let along_x = projected_area(&panel, 0.05, Vec3::X);
        assert!((along_x - 0.05 * 0.3).abs() < 1e-6);
        let flat = projected_area(&panel, 0.0, Vec3::Y);
        assert_eq!(flat, 0.0);
        // An ellipse of the panel's axes: π/4 of its face; from the side its height
        // times the axis across the view.
        let ellipse = Opening::Ellipse {
            along_c0: 0.6,
            along_c90: 0.3,
        };
        let below = projected_area(&ellipse, 0.05, -Vec3::Z);
        assert!((below - 0.18 * std::f64::consts::FRAC_PI_4).abs() < 1e-6);
        for (w, across) in [(Vec3::X, 0.3), (Vec3::Y, 0.6)] {
            assert!((projected_area(&ellipse, 0.05, w) - 0.05 * across).abs() < 1e-6);
        }
    }

    #[test]
    fn a_view_along_up_or_of_no_length_is_refused() {
        let eye = Vec3::new(0.0, 0.0, 1.2);
        let up = |view| sight(&Observer { eye, view }, UP);
        assert_eq!(up(Vec3::Z), Err(GlareError::ViewAlongUp));
        assert_eq!(up(Vec3::ZERO), Err(GlareError::NoView));
        assert!(up(Vec3::new(1.0, 0.0, -0.2)).is_ok());
    }
}
