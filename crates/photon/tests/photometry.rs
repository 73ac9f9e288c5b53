//! Goniometric lights (photometric files) against closed forms and numeric
//! integrals of the tables they were given, never against the tracer's own output.
//! Every check is |estimate − exact| < 4 σ of the estimate's own standard error, with
//! fixed seeds, for both estimators (arrivals alone, and arrivals weighted against
//! connections), since the two use the table differently: an arrival carries the
//! photon's power, whose weight I/(Φp) corrects the piecewise-constant density photons
//! are drawn with, and a connection evaluates that weight toward the target.
//!
//! - A Lambertian table (I₀ cos γ, IES and EULUMDAT): a patch below and one off axis
//!   against the closed-form flux of a cosine source onto a rectangle, the total flux
//!   π·I₀ on a large floor.
//! - A table that is one cell, linear in γ: sampling density and intensity differ most.
//! - An asymmetric table turned by the light's frame lights the side its C0 faces.
//! - A disk opening: a Lambertian disk's closed-form illuminance, not a point's.
//! - A linear luminaire in both formats, each by its own convention for the opening's
//!   length, against the area source's integral.
//! - `Scene::set_photometry` on a point lamp over a roof with a hole: a uniform
//!   downward table reaches the floor through the hole alone.
//! - Emission: counts in the table's cells against their share of the flux (χ²),
//!   weighted sums inside cells against the bilinear intensity, each draw's density
//!   against the cell's, Σ 1/(p·N) against the support's solid angle, and the lobe's
//!   density integrating to one.

mod common;

use common::{Z, assert_near, point, rect, rect_solid_angle, roof_with_hole};
use invlight_photon::{Emitters, Estimator, GroupKeys, Sampler, TraceSettings};
use invlight_scene::{
    Light, LightKind, Mat3, Mat4, Material, Opening, PhotometricSystem, Photometry, Scene,
    SurfaceId, Vec3, aimed_frame, read_photometry,
};
use invlight_stats::Estimate;
use invlight_trace::Accel;
use std::f64::consts::PI;
use std::path::PathBuf;
use std::sync::Arc;

fn data(name: &str) -> Photometry {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry")
        .join(name);
    read_photometry(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// A goniometric light at `position` turned by `frame`.
fn luminaire(photometry: Photometry, position: Vec3, frame: Mat3) -> Light {
    Light {
        c0: invlight_scene::Vec3::X,
        name: "Luminaire".into(),
        kind: LightKind::Goniometric {
            position,
            frame,
            photometry: Arc::new(photometry),
            multiplier: Vec3::ONE,
            tilt: 1.0,
        },
    }
}

/// A scene of black rectangles at z = 0, named, and `light`.
fn black_patches(patches: &[(&str, [f32; 4])], light: Light) -> Scene {
    let mut scene = Scene::default();
    scene.up = Vec3::Z;
    let black = scene.add_material(Material::diffuse("Black", Vec3::ZERO));
    for &(name, [x0, x1, y0, y1]) in patches {
        let m = scene.add_mesh(rect(x0, x1, y0, y1, 0.0, black));
        scene.add_instance(name, m, Mat4::IDENTITY);
    }
    scene.lights.push(light);
    scene
}

/// Both estimators' estimates of the named surfaces, `[arrivals, connected]`.
fn measure(scene: &Scene, names: &[&str], photons: u64, seed: u64) -> Vec<[Estimate; 2]> {
    let accel = Accel::new(scene);
    let ids: Vec<SurfaceId> = names.iter().map(|n| scene.surface(n).unwrap()).collect();
    let settings = TraceSettings {
        photons,
        seed,
        ..TraceSettings::default()
    };
    let runs = [Estimator::ArrivalsOnly, Estimator::Connected]
        .map(|e| invlight_photon::measure(scene, &accel, &ids, &settings, e, None));
    (0..ids.len())
        .map(|i| runs.each_ref().map(|r| r.estimate(i)))
        .collect()
}

/// Both estimates within 4 σ of `exact`, each σ below `informative` × exact.
fn assert_both(both: &[Estimate; 2], exact: f64, informative: [f64; 2], what: &str) {
    for ((e, how), inf) in both.iter().zip(["arrivals", "connected"]).zip(informative) {
        assert_near(e, exact, inf, &format!("{what} ({how})"));
    }
}

/// ∫∫ h²/(x² + y² + h²)² over [0, a] × [0, b]: the flux a source of intensity cos γ at
/// height h sends onto that rectangle (the parallel configuration factor of a
/// differential area to a rectangle, times π).
fn cosine_corner(a: f64, b: f64, h: f64) -> f64 {
    let (p, q) = (a / h, b / h);
    let (sp, sq) = ((1.0 + p * p).sqrt(), (1.0 + q * q).sqrt());
    0.5 * (p / sp * (q / sp).atan() + q / sq * (p / sq).atan()).copysign(a * b)
}

/// Mean illuminance over [x0,x1]×[y0,y1] at z = 0 from I₀ cos γ at (0, 0, h), lx.
fn cosine_rect(i0: f64, [x0, x1, y0, y1]: [f64; 4], h: f64) -> f64 {
    let flux = cosine_corner(x1, y1, h) - cosine_corner(x0, y1, h) - cosine_corner(x1, y0, h)
        + cosine_corner(x0, y0, h);
    i0 * flux / ((x1 - x0) * (y1 - y0))
}

/// The mean over [x0,x1]×[y0,y1] at z = 0 of `e(x, y)`, by the midpoint rule on n × n.
fn mean_over(r: [f64; 4], n: usize, e: impl Fn(f64, f64) -> f64) -> f64 {
    let [x0, x1, y0, y1] = r;
    let (dx, dy) = ((x1 - x0) / n as f64, (y1 - y0) / n as f64);
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            sum += e(x0 + (i as f64 + 0.5) * dx, y0 + (j as f64 + 0.5) * dy);
        }
    }
    sum / (n * n) as f64
}

/// Illuminance at (x, y, 0) from the table `p` at `position` turned by `frame`, with the
/// angles worked out here from the geometry: I(C, γ)·cos θ/d².
fn table_illuminance(p: &Photometry, position: Vec3, frame: Mat3, x: f64, y: f64) -> f64 {
    let d = Vec3::new(x as f32, y as f32, 0.0) - position;
    let r = d.length() as f64;
    let w = d.normalize();
    let (lx, ly, lz) = (
        w.dot(frame.x_axis) as f64,
        w.dot(frame.y_axis) as f64,
        w.dot(frame.z_axis) as f64,
    );
    let gamma = (-lz).clamp(-1.0, 1.0).acos().to_degrees();
    let c = ly.atan2(lx).to_degrees().rem_euclid(360.0);
    p.intensity(c, gamma) * (-d.z as f64 / r) / (r * r)
}

const PATCH_BELOW: [f32; 4] = [-0.1, 0.1, -0.1, 0.1];
const PATCH_SIDE: [f32; 4] = [0.5, 2.0, -0.25, 1.0];

fn f64s(r: [f32; 4]) -> [f64; 4] {
    r.map(|x| x as f64)
}

/// I(γ) = 100 cd·cos γ hanging 2 m over the floor, read from IES and from EULUMDAT:
/// the patch below reads the closed form, within 0.5 % of I₀/h² (E falls as
/// (1 + r²/h²)⁻² across the 0.2 m patch); an off-axis patch the same; a 100 m floor receives π·I₀ less what falls beyond
/// it (h²/(h² + 50²) of a disk, 0.16 %). The table's 1° chords take 2.5·10⁻⁵ of each figure, far inside the errors.
#[test]
fn cosine_table_over_a_floor() {
    let (i0, h) = (100.0, 2.0);
    let below = cosine_rect(i0, f64s(PATCH_BELOW), h);
    assert!((below - i0 / (h * h)).abs() < 5e-3 * i0 / (h * h));
    let side = cosine_rect(i0, f64s(PATCH_SIDE), h);
    let floor = cosine_rect(i0, [-50.0, 50.0, -50.0, 50.0], h) * 1e4;
    assert!(floor < PI * i0 && floor > 0.998 * PI * i0);
    for file in ["cosine.ies", "cosine.ldt"] {
        let light = || luminaire(data(file), Vec3::new(0.0, 0.0, h as f32), Mat3::IDENTITY);
        let scene = black_patches(&[("Below", PATCH_BELOW), ("Side", PATCH_SIDE)], light());
        let e = measure(&scene, &["Below", "Side"], 400_000, 7);
        assert_both(&e[0], below, [0.1, 0.02], &format!("{file}: below"));
        assert_both(&e[1], side, [0.02, 0.02], &format!("{file}: side"));
        let scene = black_patches(&[("Floor", [-50.0, 50.0, -50.0, 50.0])], light());
        let e = measure(&scene, &["Floor"], 100_000, 8);
        for est in e[0] {
            let flux = est.mean * 1e4;
            assert!(
                (flux - floor).abs() < Z * est.std_error * 1e4 + 1e-9 * floor,
                "{file}: {flux} lm on the floor, {floor} expected"
            );
        }
    }
}

/// One cell, I = 1000 cd·γ/90° from nadir to the horizon: photons are drawn uniformly
/// over the hemisphere and carry weights from 0 to π/(2·(π/2 − 1))·… — the case where a
/// connection that took the sampling density for the intensity would be most wrong.
/// Patches below and off axis at 1 m, against a midpoint integral of I·cos θ/d².
#[test]
fn linear_table_where_density_and_intensity_differ() {
    let p = Photometry::from_table(
        PhotometricSystem::C,
        vec![0.0, 360.0],
        vec![0.0, 90.0],
        vec![0.0, 1000.0, 0.0, 1000.0],
    )
    .unwrap();
    let position = Vec3::new(0.0, 0.0, 1.0);
    let below: [f32; 4] = [-1.0, 1.0, -1.0, 1.0];
    let off: [f32; 4] = [1.5, 3.0, -0.5, 0.5];
    let exact = [below, off].map(|r| {
        mean_over(f64s(r), 1000, |x, y| {
            let d2 = x * x + y * y + 1.0;
            let gamma = (x * x + y * y).sqrt().atan();
            1000.0 * gamma / (PI / 2.0) * (1.0 / d2.sqrt()) / d2
        })
    });
    // The table's own interpolation agrees with the formula at an angle.
    assert!((p.intensity(0.0, 30.0) - 1000.0 / 3.0).abs() < 1e-9);
    let scene = black_patches(
        &[("Below", below), ("Off", off)],
        luminaire(p.clone(), position, Mat3::IDENTITY),
    );
    let e = measure(&scene, &["Below", "Off"], 400_000, 11);
    assert_both(&e[0], exact[0], [0.02, 0.02], "linear table: below");
    assert_both(&e[1], exact[1], [0.02, 0.02], "linear table: off axis");
    // A photon's weight is I/(Φ·p): zero at nadir, above one near the horizon.
    let lobe_weight = |gamma: f64| {
        let w = p.direction(0.0, gamma);
        p.pdf_and_weight(w).1 as f64
    };
    let phi = p.flux();
    let pdf = 1.0 / (2.0 * PI);
    assert!(lobe_weight(0.0).abs() < 1e-6);
    assert!((lobe_weight(80.0) - 1000.0 * 80.0 / 90.0 / (phi * pdf)).abs() < 1e-4);
}

/// An asymmetric table (light toward C0 only, zero at C180) turned so that C0 faces world
/// +Y: the patch on +Y gets what the table sends there, the one on −Y the little that
/// the C-planes near 180° send; both against a midpoint integral of the table.
#[test]
fn asymmetric_table_lights_the_side_its_frame_turns_it_to() {
    let p = data("asymmetric.ies");
    let position = Vec3::new(0.0, 0.0, 1.5);
    let frame = aimed_frame(Vec3::NEG_Z, Vec3::Y);
    assert!((frame.x_axis - Vec3::Y).length() < 1e-6);
    let north: [f32; 4] = [-0.5, 0.5, 1.0, 2.0];
    let south: [f32; 4] = [-0.5, 0.5, -2.0, -1.0];
    let exact = [north, south].map(|r| {
        mean_over(f64s(r), 600, |x, y| {
            table_illuminance(&p, position, frame, x, y)
        })
    });
    assert!(exact[0] > 10.0 * exact[1], "{exact:?}");
    let scene = black_patches(
        &[("North", north), ("South", south)],
        luminaire(p, position, frame),
    );
    let e = measure(&scene, &["North", "South"], 400_000, 13);
    assert_both(&e[0], exact[0], [0.02, 0.02], "toward C0");
    assert_both(&e[1], exact[1], [0.1, 0.05], "away from C0");
}

/// A Lambertian table (I₀ cos γ) given a disk opening of radius R emits like a Lambertian
/// disk of luminance I₀/(πR²): at height h, E(r) = (I₀/R²)·½·(1 − (h² + r² − R²)/
/// √((h² + r² + R²)² − 4r²R²)) (the configuration factor of a parallel disk), which
/// below the centre is I₀/(h² + R²), not the point source's I₀/h².
#[test]
fn disk_opening_emits_from_its_area() {
    let mut p = data("cosine.ies");
    let (radius, h) = (0.5f64, 0.5f64);
    p.opening = Opening::Disk {
        diameter: 2.0 * radius as f32,
    };
    let i0 = 100.0;
    let disk = |x: f64, y: f64| {
        let r2 = x * x + y * y;
        let (h2, big) = (h * h, radius * radius);
        let f = 0.5 * (1.0 - (h2 + r2 - big) / ((h2 + r2 + big).powi(2) - 4.0 * r2 * big).sqrt());
        i0 / big * f
    };
    let patch: [f32; 4] = [-0.2, 0.2, -0.2, 0.2];
    let exact = mean_over(f64s(patch), 400, disk);
    assert!((disk(0.0, 0.0) - i0 / (h * h + radius * radius)).abs() < 1e-9);
    let scene = black_patches(
        &[("Below", patch)],
        luminaire(p, Vec3::new(0.0, 0.0, h as f32), Mat3::IDENTITY),
    );
    let e = measure(&scene, &["Below"], 400_000, 17);
    assert_both(&e[0], exact, [0.02, 0.02], "disk opening");
    assert!(exact < 0.6 * cosine_rect(i0, f64s(patch), h));
}

/// The mean illuminance over `patch` from `p` at `position` turned by `frame`, its
/// opening's area drawn on an n × n grid of it: the area source's closed integral
/// evaluated by the midpoint rule, from the table's own angles (`table_illuminance`).
fn opening_illuminance(p: &Photometry, position: Vec3, frame: Mat3, patch: [f32; 4]) -> f64 {
    let n = 24;
    let points: Vec<Vec3> = (0..n * n)
        .map(|k| {
            let (u1, u2) = ((k / n) as f32 + 0.5, (k % n) as f32 + 0.5);
            position + frame * p.opening.point(u1 / n as f32, u2 / n as f32)
        })
        .collect();
    mean_over(f64s(patch), 40, |x, y| {
        points
            .iter()
            .map(|&q| table_illuminance(p, q, frame, x, y))
            .sum::<f64>()
            / points.len() as f64
    })
}

/// One 1500 × 60 mm linear luminaire written as IES and as EULUMDAT (cosine-like along
/// its axis, batwing across it; make_photometry.py), each read by its format's
/// convention — IES lays the length along C0, EULUMDAT along C90 — and turned so that
/// its length lies along world X, 0.5 m over a black floor: beyond its end and beside it
/// both read the area source's integral. Read with the length along C0, the EULUMDAT
/// luminaire would lie across X and light beyond its end a third as much.
#[test]
fn a_linear_luminaire_lights_the_same_field_from_either_format() {
    let (ies, ldt) = (data("linear.ies"), data("linear.ldt"));
    let position = Vec3::new(0.0, 0.0, 0.5);
    // EULUMDAT's C90 (local Y) onto world X, its C0 onto −Y.
    let turned = Mat3::from_cols(Vec3::NEG_Y, Vec3::X, Vec3::Z);
    let end: [f32; 4] = [0.7, 1.0, -0.15, 0.15];
    let side: [f32; 4] = [-0.15, 0.15, 0.4, 0.7];
    let exact = [end, side].map(|r| opening_illuminance(&ies, position, Mat3::IDENTITY, r));
    for (k, r) in [end, side].into_iter().enumerate() {
        let own = opening_illuminance(&ldt, position, turned, r);
        assert!(
            (own - exact[k]).abs() < 2e-3 * exact[k],
            "{own} vs {}",
            exact[k]
        );
    }
    let mut along_c0 = ldt.clone();
    along_c0.opening = Opening::Rectangle {
        along_c0: 1.5,
        along_c90: 0.06,
    };
    let wrong = opening_illuminance(&along_c0, position, turned, end);
    assert!(wrong < 0.5 * exact[0], "{wrong} vs {}", exact[0]);
    for (p, frame, file) in [(ies, Mat3::IDENTITY, "IES"), (ldt, turned, "EULUMDAT")] {
        let scene = black_patches(
            &[("End", end), ("Side", side)],
            luminaire(p, position, frame),
        );
        let e = measure(&scene, &["End", "Side"], 400_000, 23);
        assert_both(
            &e[0],
            exact[0],
            [0.02, 0.02],
            &format!("{file}: beyond the end"),
        );
        assert_both(&e[1], exact[1], [0.02, 0.02], &format!("{file}: beside"));
    }
}

/// The table of `Photometry`'s unit tests: C-dependent, zero cells, uneven γ steps.
fn uneven_table() -> Photometry {
    Photometry::from_table(
        PhotometricSystem::C,
        vec![0.0, 90.0, 180.0, 270.0, 360.0],
        vec![0.0, 30.0, 90.0, 180.0],
        vec![
            900.0, 10.0, 0.0, 5.0, 50.0, 400.0, 20.0, 0.0, 700.0, 0.0, 0.0, 0.0, 10.0, 10.0, 10.0,
            10.0, 900.0, 10.0, 0.0, 5.0,
        ],
    )
    .unwrap()
}

/// ∫ of the table's intensity over C ∈ [c0, c1], γ ∈ [g0, g1] (degrees), by the midpoint
/// rule in C and cos γ (so in solid angle), lm.
fn flux_over(p: &Photometry, [c0, c1, g0, g1]: [f64; 4], n: usize) -> f64 {
    let (z0, z1) = (g0.to_radians().cos(), g1.to_radians().cos());
    let dc = (c1 - c0).to_radians() / n as f64;
    let dz = (z0 - z1) / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let c = c0 + (c1 - c0) * (i as f64 + 0.5) / n as f64;
            let g = (z0 - (j as f64 + 0.5) * dz).acos().to_degrees();
            sum += p.intensity(c, g);
        }
    }
    sum * dc * dz
}

/// Photons of a goniometric light against its table: the counts in each cell follow its
/// share of the flux (χ², 12 cells), the weighted sums in each quarter of a cell follow
/// the bilinear intensity there (4 σ of the weights' own spread), each draw's density
/// is its cell's flux over Φ times the cell's solid angle, Σ 1/(p·N) is the solid angle
/// where the table is not zero, and the lobe's density integrates to one.
#[test]
fn emission_follows_the_table() {
    let p = uneven_table();
    let phi = p.flux();
    let frame = aimed_frame(Vec3::new(0.3, -0.2, -1.0), Vec3::X);
    let mut scene = Scene::default();
    scene
        .lights
        .push(luminaire(p.clone(), Vec3::new(1.0, 2.0, 3.0), frame));
    let emitters = Emitters::new(&scene);
    assert!((emitters.total_flux() - phi).abs() < 1e-3 * phi);
    let (hs, vs) = (p.horizontal().to_vec(), p.vertical().to_vec());
    let (nc, ng) = (hs.len() - 1, vs.len() - 1);
    // Quarter cells: (cell, half in C, half in cos γ).
    let quarter = |c: f64, g: f64| {
        let i = hs.partition_point(|&a| a <= c).clamp(1, nc) - 1;
        let j = vs.partition_point(|&a| a <= g).clamp(1, ng) - 1;
        let hc = (c > 0.5 * (hs[i] + hs[i + 1])) as usize;
        let zm = 0.5 * (vs[j].to_radians().cos() + vs[j + 1].to_radians().cos());
        let hz = (g.to_radians().cos() < zm) as usize;
        ((i * ng + j) * 2 + hc) * 2 + hz
    };
    let bounds = |q: usize| {
        let (cell, hc, hz) = (q / 4, (q / 2) % 2, q % 2);
        let (i, j) = (cell / ng, cell % ng);
        let cm = 0.5 * (hs[i] + hs[i + 1]);
        let (z0, z1) = (vs[j].to_radians().cos(), vs[j + 1].to_radians().cos());
        let gm = (0.5 * (z0 + z1)).acos().to_degrees();
        let c = if hc == 0 {
            [hs[i], cm]
        } else {
            [cm, hs[i + 1]]
        };
        let g = if hz == 0 {
            [vs[j], gm]
        } else {
            [gm, vs[j + 1]]
        };
        [c[0], c[1], g[0], g[1]]
    };
    let nq = nc * ng * 4;
    // Each cell's flux by the midpoint rule, and its density per steradian.
    let cell_flux: Vec<f64> = (0..nc * ng)
        .map(|cell| {
            let (i, j) = (cell / ng, cell % ng);
            flux_over(&p, [hs[i], hs[i + 1], vs[j], vs[j + 1]], 200)
        })
        .collect();
    let cell_pdf: Vec<f64> = (0..nc * ng)
        .map(|cell| {
            let (i, j) = (cell / ng, cell % ng);
            let omega = (hs[i + 1] - hs[i]).to_radians()
                * (vs[j].to_radians().cos() - vs[j + 1].to_radians().cos());
            cell_flux[cell] / (phi * omega)
        })
        .collect();
    let (groups, per) = (4096u64, 64u64);
    let n = (groups * per) as f64;
    let mut counts = vec![0.0f64; nq];
    let mut sums = vec![0.0f64; nq];
    let mut sums2 = vec![0.0f64; nq];
    let (mut inv, mut inv2) = (0.0f64, 0.0f64);
    for g in 0..groups {
        let keys = GroupKeys::new(5, g);
        for i in g * per..(g + 1) * per {
            let s = emitters.sample(&mut Sampler::new(&keys, 5, i));
            let local = frame.transpose() * s.dir;
            let gamma = (-local.z as f64).clamp(-1.0, 1.0).acos().to_degrees();
            let c = (local.y as f64)
                .atan2(local.x as f64)
                .to_degrees()
                .rem_euclid(360.0);
            let q = quarter(c, gamma);
            let pdf = s.lobe.pdf(s.dir) as f64;
            let expected = cell_pdf[q / 4];
            assert!(
                (pdf - expected).abs() < 2e-3 * expected,
                "density {pdf} in cell {} of density {expected}",
                q / 4
            );
            let w = s.power.x as f64 / phi;
            counts[q] += 1.0;
            sums[q] += w;
            sums2[q] += w * w;
            inv += 1.0 / pdf;
            inv2 += 1.0 / (pdf * pdf);
        }
    }
    // χ² of the cells' counts against their flux shares.
    let (mut chi2, mut cells) = (0.0, 0usize);
    for cell in 0..nc * ng {
        let count: f64 = counts[cell * 4..cell * 4 + 4].iter().sum();
        let expected = n * cell_flux[cell] / phi;
        if expected == 0.0 {
            assert_eq!(count, 0.0, "a photon in cell {cell}, which sends nothing");
            continue;
        }
        chi2 += (count - expected).powi(2) / expected;
        cells += 1;
    }
    // Stratified draws spread less than independent ones, so χ² only gets smaller; beyond
    // k + 6√(2k) it has probability below 10⁻⁶ even unstratified.
    let k = (cells - 1) as f64;
    assert!(chi2 < k + 6.0 * (2.0 * k).sqrt(), "χ² = {chi2} for {k} dof");
    // Weighted sums per quarter: Σ w/N estimates ∫_quarter I dω / Φ.
    for q in 0..nq {
        let exact = flux_over(&p, bounds(q), 100) / phi;
        let mean = sums[q] / n;
        let sigma = ((sums2[q] / n - mean * mean) / n).sqrt();
        assert!(
            (mean - exact).abs() < Z * sigma + 1e-6,
            "quarter {q}: {mean} ± {sigma}, table {exact}"
        );
    }
    // Σ 1/(p·N): the solid angle of the cells that send light (a positive corner).
    let mean = inv / n;
    let sigma = ((inv2 / n - mean * mean) / n).sqrt();
    let mut support = 0.0;
    for i in 0..nc {
        for j in 0..ng {
            if cell_flux[i * ng + j] > 0.0 {
                support += (hs[i + 1] - hs[i]).to_radians()
                    * (vs[j].to_radians().cos() - vs[j + 1].to_radians().cos());
            }
        }
    }
    assert!(
        (mean - support).abs() < Z * sigma,
        "Σ 1/(pN) = {mean} ± {sigma}, support {support}"
    );
    // The lobe's density over the sphere (midpoint in cos θ and φ about world Z).
    let s = emitters.sample(&mut Sampler::new(&GroupKeys::new(5, 0), 5, 0));
    let m = 800;
    let mut total = 0.0;
    for a in 0..m {
        for b in 0..m {
            let z = -1.0 + 2.0 * (a as f64 + 0.5) / m as f64;
            let phi_a = 2.0 * PI * (b as f64 + 0.5) / m as f64;
            let r = (1.0 - z * z).sqrt();
            let w = Vec3::new((r * phi_a.cos()) as f32, (r * phi_a.sin()) as f32, z as f32);
            total += s.lobe.pdf(w) as f64;
        }
    }
    let total = total * 4.0 * PI / (m * m) as f64;
    assert!((total - 1.0).abs() < 5e-3, "∫ p dω = {total}");
}

/// A point lamp 1 m over a roof with a 1 × 1 m hole, made by `Scene::set_photometry` a
/// luminaire of 100 cd in every downward direction (aimed at −up): the floor 3 m below
/// the roof gets 100 cd × the hole's solid angle, spread over its 36 m² (the beam
/// through the hole lands inside it). Photons and connection rays must both pass the
/// hole and nowhere else.
#[test]
fn luminaire_set_on_a_point_lamp_shines_through_a_hole() {
    let mut scene = roof_with_hole(3.0);
    scene.up = Vec3::Z;
    scene
        .lights
        .push(point("Lamp", Vec3::new(0.5, 0.5, 4.0), 1.0));
    let uniform = Photometry::from_table(
        PhotometricSystem::C,
        vec![0.0, 360.0],
        vec![0.0, 90.0],
        vec![100.0; 4],
    )
    .unwrap();
    scene
        .set_photometry("Lamp", Arc::new(uniform), 1.0)
        .unwrap();
    let omega = rect_solid_angle(-0.5, 0.5, -0.5, 0.5, 1.0);
    let e = measure(&scene, &["Floor"], 400_000, 19);
    assert_both(
        &e[0],
        100.0 * omega / 36.0,
        [0.02, 0.02],
        "through the hole",
    );
}
