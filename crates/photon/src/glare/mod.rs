//! Discomfort glare at an observer by CIE 117:1995's Unified Glare Rating,
//!
//! UGR = 8·log10( 0.25/Lb · Σ L²·ω/p² ),
//!
//! over every luminaire the eye sees in front of it ([`glare_sources`]: L its luminance
//! toward the eye, ω its solid angle, p Guth's position index, all exact), and Lb the
//! background luminance, the *indirect* illuminance at the eye on the plane facing the
//! view over π (CIE 117 §3; evalglare's "CIE method" background, (Ev − Edir)/π).
//!
//! Lb is traced: a small calculation square at the eye facing the view ([`add_eye`])
//! carries a one-cell grid that counts only light reflected or transmitted at least
//! once ([`GridValues::Indirect`]), so one trace gives the indirect illuminance and its
//! standard error, in the same photons as everything else a search measures. Both parts
//! follow the lights' levels: each luminaire's L scales with its level and Lb is linear
//! in them, so a search reads the UGR of every dimming of one trace from the glare sum
//! of each component ([`crate::Measurement::glare_sum`]) and the indirect grid.
//!
//! UGR falls as Lb rises, so its interval is the UGR at Lb's upper and lower bounds
//! ([`unified_glare_rating`]); a search decides a limit on it with the estimate
//! [`ugr_estimate`] gives (the first-order spread of the same transform, which agrees
//! with those bounds to a fraction of a tenth while Lb is known to a few per cent).

mod sources;

pub use sources::{
    GlareOrigin, GlareSource, glare_sources, light_without_luminous_area, position_index,
};

use crate::{
    Components, Estimator, GridRequest, GridValues, Request, Side, SurfaceGrid, TraceSettings,
};
use glam::{Mat4, Vec3};
use invlight_scene::{Material, Mesh, Scene, SurfaceId};
use invlight_stats::{Confidence, Estimate, Interval};
use invlight_trace::Accel;
use serde::Serialize;
use sources::sight;
use std::fmt;

/// Where the eye is and where it looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observer {
    /// The eye, world metres.
    pub eye: Vec3,
    /// The line of sight (any length but zero).
    pub view: Vec3,
}

/// Why no UGR can be given.
#[derive(Debug, Clone, PartialEq)]
pub enum GlareError {
    /// The line of sight has no length or is not finite.
    NoView,
    /// The line of sight is along the scene's up axis: no vertical plane, no position
    /// index.
    ViewAlongUp,
    /// The eye is not a finite point.
    NoEye,
    /// A luminaire in view has no luminous area to have a luminance.
    NoLuminousArea {
        /// The light's name.
        light: String,
        /// What it is.
        kind: &'static str,
    },
}

impl fmt::Display for GlareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GlareError::NoView => write!(
                f,
                "the view direction has no length, expected DX,DY,DZ along the line of sight"
            ),
            GlareError::ViewAlongUp => write!(
                f,
                "the view looks straight up or down, expected a line of sight with a horizontal part (UGR's position index needs the vertical plane through it)"
            ),
            GlareError::NoEye => write!(f, "the observer is not a finite point"),
            GlareError::NoLuminousArea { light, kind } => write!(
                f,
                "the light '{light}' is in view but is {kind} without a luminous area: UGR needs each luminaire's luminance, its intensity over its luminous area; give it a photometric file with luminous dimensions (IES width and length, EULUMDAT luminous area)"
            ),
        }
    }
}

impl std::error::Error for GlareError {}

/// The Unified Glare Rating at one observer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Ugr {
    /// UGR, when some luminaire is in view (none: no discomfort glare to rate).
    pub ugr: Option<f64>,
    /// Its interval at the run's confidence, from Lb's; the upper end is infinite when
    /// Lb's lower bound is not above 0.
    pub ugr_interval: Option<[f64; 2]>,
    /// The background luminance Lb = E_indirect/π, cd/m².
    pub background_luminance: f64,
    /// Lb's interval, cd/m².
    pub background_interval: [f64; 2],
    /// The illuminance at the eye on the plane facing the view, every bounce, lx.
    pub eye_illuminance: f64,
    /// Its direct part (first hits), lx.
    pub direct_illuminance: f64,
    /// Its indirect part, lx.
    pub indirect_illuminance: f64,
    /// The indirect part's standard error, lx.
    pub indirect_std_error: f64,
    /// The luminaires in view, in the scene's order.
    pub sources: Vec<GlareSource>,
}

/// The UGR of the sum Σ L²ω/p² over a background luminance `lb`, cd/m²: +∞ over a
/// black background, none without sources.
pub fn ugr_of(sum: f64, lb: f64) -> Option<f64> {
    (sum > 0.0).then(|| {
        if lb > 0.0 {
            8.0 * (0.25 * sum / lb).log10()
        } else {
            f64::INFINITY
        }
    })
}

/// The spread a rating takes while its background is not yet told from black (its
/// indirect illuminance within one standard error of zero): wider than CIE 117's whole
/// scale, so that no limit is decided on it and the search traces on.
const UNTOLD_SPREAD: f64 = 100.0;

/// The UGR of the glare sum `sum` (Σ L²ω/p², cd²/m⁴·sr) over the indirect illuminance
/// at the eye `indirect` (lx, Lb = E/π), as an estimate: its standard error the
/// first-order spread 8/ln 10 · σ_E/E, its mean at least 0. Without a luminaire in view
/// it is 0 (below the scale: no discomfort glare), exactly; over a background not yet
/// told from black its
/// spread is 100, wider than the whole scale, so that no limit is decided on it.
pub fn ugr_estimate(sum: f64, indirect: &Estimate) -> Estimate {
    let samples = indirect.samples;
    if sum <= 0.0 {
        return Estimate {
            mean: 0.0,
            std_error: 0.0,
            samples,
        };
    }
    let e = indirect.mean.max(indirect.std_error);
    if e <= 0.0 {
        return Estimate {
            mean: UNTOLD_SPREAD,
            std_error: UNTOLD_SPREAD,
            samples,
        };
    }
    // Below 0 the formula ranks nothing a designer reads (CIE 117's scale starts at
    // 10): a faint source in view must not rate better than none.
    let mean = ugr_of(sum, e / std::f64::consts::PI)
        .unwrap_or(0.0)
        .max(0.0);
    let std_error = if indirect.mean > indirect.std_error {
        8.0 / std::f64::consts::LN_10 * indirect.std_error / indirect.mean
    } else {
        UNTOLD_SPREAD
    };
    Estimate {
        mean,
        std_error,
        samples,
    }
}

/// The glare sum Σ L²·ω/p² of the luminaires `observer` sees in `scene`, per component
/// of `components` at level 1 (a component dimmed to y contributes y² times its sum, L
/// scaling with y); a light without a luminous area, which [`glare_sources`] refuses,
/// adds nothing here ([`light_without_luminous_area`] refuses it before a search).
pub fn glare_sums(
    scene: &Scene,
    accel: &Accel,
    observer: &Observer,
    components: &Components,
) -> Vec<f64> {
    let mut sums = vec![0.0; components.count()];
    for s in sources::seen(scene, accel, observer) {
        let k = match s.origin {
            GlareOrigin::Light(l) => components.of_light(l),
            GlareOrigin::Instance(i) => components.of_instance(i),
        };
        sums[k] += s.contribution;
    }
    sums
}

/// Half the side of the square that receives the light at the eye, m: small beside a
/// room, large enough for the connected estimator to find it.
const EYE_HALF_SIDE: f32 = 0.1;

/// Adds to `scene` a calculation square named `name` at `observer`'s eye facing the
/// view (its front, the counter-clockwise side, toward what the eye sees), and gives
/// its surface: what [`eye_grid`] lays the background's grid on.
pub fn add_eye(
    scene: &mut Scene,
    observer: &Observer,
    name: &str,
) -> Result<SurfaceId, GlareError> {
    let (view, vertical) = sight(observer, scene.up)?;
    let right = view.cross(vertical);
    let (c, a) = (observer.eye, EYE_HALF_SIDE);
    let material = scene.add_material(Material::diffuse(EYE_MATERIAL, Vec3::ZERO));
    let corners = [
        c - a * right - a * vertical,
        c - a * right + a * vertical,
        c + a * right + a * vertical,
        c + a * right - a * vertical,
    ];
    let mesh = scene.add_mesh(Mesh::quad(corners, material));
    scene.add_instance(name, mesh, Mat4::IDENTITY);
    let s = scene.surface(name).expect("the surface just added");
    scene.make_calculation_surface(s);
    Ok(s)
}

/// The material of every eye square, by which [`is_eye_of`] knows one.
const EYE_MATERIAL: &str = "eye (glare)";

/// Whether surface `s` of `scene` is the eye square [`add_eye`] added for `observer`: a
/// calculation surface of two triangles of the eye's material, centred on the eye and
/// facing the view. A scene bound to a problem twice keeps its eyes; any other surface
/// of an observer's name is not one.
pub fn is_eye_of(scene: &Scene, s: SurfaceId, observer: &Observer) -> bool {
    let Ok((view, _)) = sight(observer, scene.up) else {
        return false;
    };
    let surface = &scene.surfaces[s];
    if !scene.is_calculation_surface(s) || surface.instances.len() != 1 {
        return false;
    }
    let triangles: Vec<_> = scene.world_triangles(surface.instances[0]).collect();
    let centre = triangles
        .iter()
        .flat_map(|t| t.corners)
        .fold(Vec3::ZERO, |a, p| a + p)
        / (3 * triangles.len().max(1)) as f32;
    triangles.len() == 2
        && triangles.iter().all(|t| {
            scene.materials[t.material].name == EYE_MATERIAL && t.normal().dot(view) > 0.999
        })
        && centre.distance(observer.eye) < 1e-4
}

/// The one-cell grid of the eye square `eye` ([`add_eye`]) that reads the background:
/// its front's indirect light.
pub fn eye_grid(scene: &Scene, eye: SurfaceId, target: usize) -> GridRequest {
    GridRequest {
        target,
        side: Side::Front,
        grid: SurfaceGrid::new(scene, eye, 4.0 * EYE_HALF_SIDE)
            .expect("an eye square is planar and larger than nothing"),
        values: GridValues::Indirect,
    }
}

/// The UGR at `observer`: its sources exact, its background traced with `settings` in
/// one trace of the scene with an eye square, its interval at `confidence` from Lb's.
pub fn unified_glare_rating(
    scene: &Scene,
    accel: &Accel,
    observer: &Observer,
    settings: &TraceSettings,
    confidence: Confidence,
) -> Result<Ugr, GlareError> {
    let sources = glare_sources(scene, accel, observer)?;
    let mut with_eye = scene.clone();
    let eye = add_eye(&mut with_eye, observer, "invlight eye")?;
    let accel = Accel::with_movable(&with_eye, &[]);
    let components = Components::one(&with_eye);
    let targets = [eye];
    let request = Request {
        grids: vec![eye_grid(&with_eye, eye, 0)],
        ..Request::means(&targets, &components, Estimator::Connected)
    };
    let m = crate::measure_with(&with_eye, &accel, &request, settings, None);
    let all = m.estimate_of(0, Side::Front, &[1.0]);
    let indirect = m.grids[0].average(&[1.0]);
    let sum: f64 = sources.iter().map(|s| s.contribution).sum();
    let pi = std::f64::consts::PI;
    let lb = indirect.mean.max(0.0) / pi;
    let Interval { low, high } = indirect.interval(confidence.z());
    let (lb_low, lb_high) = (low.max(0.0) / pi, high.max(0.0) / pi);
    let ugr = ugr_of(sum, lb);
    let ugr_interval = ugr.map(|_| {
        [
            ugr_of(sum, lb_high).unwrap_or(f64::NEG_INFINITY),
            ugr_of(sum, lb_low).unwrap_or(f64::INFINITY),
        ]
    });
    Ok(Ugr {
        ugr,
        ugr_interval,
        background_luminance: lb,
        background_interval: [lb_low, lb_high],
        eye_illuminance: all.mean,
        direct_illuminance: all.mean - indirect.mean,
        indirect_illuminance: indirect.mean,
        indirect_std_error: indirect.std_error,
        sources,
    })
}

/// A UGR as tables print it: to a tenth, "< 10" below CIE 117's scale (10, the
/// threshold of discomfort, to 30; the formula's lower values mean nothing more than
/// "no discomfort"), an infinite upper bound as ∞.
pub fn rating(x: f64) -> String {
    if x < 10.0 {
        "< 10".into()
    } else if x.is_finite() {
        format!("{x:.1}")
    } else {
        "∞".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rating_below_cie_117s_scale_reads_below_10() {
        assert_eq!(rating(-6.1), "< 10");
        assert_eq!(rating(f64::NEG_INFINITY), "< 10");
        assert_eq!(rating(9.96), "< 10");
        assert_eq!(rating(19.04), "19.0");
        assert_eq!(rating(f64::INFINITY), "∞");
    }

    #[test]
    fn ugr_of_scales_by_eight_log_k_when_everything_is_dimmed_by_k() {
        let (sum, lb) = (3.0e5, 40.0);
        for k in [0.5, 2.0, 10.0] {
            // L scales by k, so L²ω/p² by k²; Lb by k.
            let shift = ugr_of(sum * k * k, lb * k).unwrap() - ugr_of(sum, lb).unwrap();
            assert!((shift - 8.0 * f64::log10(k)).abs() < 1e-12);
        }
        assert_eq!(ugr_of(0.0, 10.0), None);
        assert_eq!(ugr_of(1.0, 0.0), Some(f64::INFINITY));
    }

    #[test]
    fn a_ugr_estimate_spreads_as_its_interval_from_the_backgrounds_bounds() {
        let indirect = Estimate {
            mean: 120.0,
            std_error: 3.0,
            samples: 1_000_000,
        };
        let sum = 4.0e6;
        let e = ugr_estimate(sum, &indirect);
        let pi = std::f64::consts::PI;
        assert!((e.mean - ugr_of(sum, 120.0 / pi).unwrap()).abs() < 1e-12);
        // The bounds from Lb's ±zσ and the estimate's ±zσ agree to a few hundredths.
        let z = 1.96;
        let high = ugr_of(sum, (120.0 - z * 3.0) / pi).unwrap();
        let low = ugr_of(sum, (120.0 + z * 3.0) / pi).unwrap();
        assert!(
            (e.mean + z * e.std_error - high).abs() < 0.01,
            "{e:?} {high}"
        );
        assert!((e.mean - z * e.std_error - low).abs() < 0.01, "{e:?} {low}");
    }

    #[test]
    fn a_faint_source_in_view_rates_no_better_than_none() {
        let bright_background = Estimate {
            mean: 5_000.0,
            std_error: 10.0,
            samples: 10,
        };
        // 0.25·Σ/Lb < 1: the formula alone would read below 0.
        assert!(ugr_of(100.0, 5_000.0 / std::f64::consts::PI).unwrap() < 0.0);
        assert_eq!(ugr_estimate(100.0, &bright_background).mean, 0.0);
    }

    #[test]
    fn an_eye_square_is_known_as_its_observers_and_no_other_surface_is() {
        let mut scene = Scene::default();
        scene.up = Vec3::Z;
        let observer = Observer {
            eye: Vec3::new(1.0, 2.0, 1.2),
            view: Vec3::Y,
        };
        let s = add_eye(&mut scene, &observer, "pupil").unwrap();
        assert!(is_eye_of(&scene, s, &observer));
        let elsewhere = Observer {
            eye: Vec3::new(1.0, 3.0, 1.2),
            ..observer
        };
        assert!(!is_eye_of(&scene, s, &elsewhere));
        let other_way = Observer {
            view: Vec3::X,
            ..observer
        };
        assert!(!is_eye_of(&scene, s, &other_way));
        let m = scene.add_material(Material::diffuse("desk", Vec3::splat(0.5)));
        let quad = [
            Vec3::new(0.9, 2.0, 1.1),
            Vec3::new(1.1, 2.0, 1.1),
            Vec3::new(1.1, 2.0, 1.3),
            Vec3::new(0.9, 2.0, 1.3),
        ];
        let mesh = scene.add_mesh(Mesh::quad(quad, m));
        scene.add_instance("desk", mesh, Mat4::IDENTITY);
        let desk = scene.surface("desk").unwrap();
        scene.make_calculation_surface(desk);
        assert!(!is_eye_of(&scene, desk, &observer));
    }

    #[test]
    fn no_luminaire_in_view_rates_zero_and_a_black_background_is_undecided() {
        let some = Estimate {
            mean: 50.0,
            std_error: 1.0,
            samples: 10,
        };
        assert_eq!(ugr_estimate(0.0, &some).mean, 0.0);
        assert_eq!(ugr_estimate(0.0, &some).std_error, 0.0);
        let black = Estimate {
            mean: 0.0,
            std_error: 0.5,
            samples: 10,
        };
        let e = ugr_estimate(1e6, &black);
        assert!(e.std_error >= UNTOLD_SPREAD, "{e:?}");
    }
}
