//! The IES LM-63 and EULUMDAT readers on the files of tests/data/photometry (written by
//! make_photometry.py there, whose comments give each table's formula and closed-form
//! flux), and on broken files written here; glTF EXT_lights_ies and
//! `Scene::set_photometry`, which put the tables in scenes.

use invlight_scene::{
    Light, LightKind, LoadOptions, Opening, PhotometricSystem, Photometry, PhotometryError,
    PhotometryFormat, Scene, Vec3, aimed_frame, load, parse_ies, parse_ldt, read_photometry,
};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/photometry")
        .join(name)
}

fn read(name: &str) -> Photometry {
    read_photometry(&data(name)).unwrap_or_else(|e| panic!("{e}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// I(γ) = 100 cd·cos γ every degree, as IES and as EULUMDAT: the intensity at nadir is
/// I₀ exactly, the flux π·I₀ within the chords' shortfall (linear interpolation of cos
/// over 1° steps loses about Δ²/12 ≈ 2.5·10⁻⁵ of it), and both files give one table.
#[test]
fn cosine_distribution_in_both_formats() {
    let ies = read("cosine.ies");
    let ldt = read("cosine.ldt");
    assert_eq!(ies.format, PhotometryFormat::Lm63_2002);
    assert_eq!(ldt.format, PhotometryFormat::Eulumdat);
    for p in [&ies, &ldt] {
        assert_eq!(p.system(), PhotometricSystem::C);
        assert!((p.intensity(0.0, 0.0) - 100.0).abs() < 1e-9);
        assert!((p.intensity(77.0, 60.0) - 50.0).abs() < 1e-3);
        assert_eq!(p.intensity(10.0, 120.0), 0.0);
        assert!(rel(p.flux(), 100.0 * PI) < 5e-5, "{}", p.flux());
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }
    assert!(rel(ies.flux(), ldt.flux()) < 1e-9);
    assert_eq!(ldt.stated_flux.map(|f| (f * 1e3).round()), Some(314159.0));
    assert_eq!(ies.lumens_per_lamp, None);
}

/// Every symmetry, IES and EULUMDAT, expands to the table the same distribution has
/// written out over 0..360° (sym-*-full.ies); the IESNA91 quadrant file's ballast
/// factor 0.5 and ballast-lamp factor 2 are both applied.
#[test]
fn each_symmetry_expands_to_the_full_table() {
    for key in ["rotational", "quadrant", "c0", "c90"] {
        let full = read(&format!("sym-{key}-full.ies"));
        let mut others = vec![
            read(&format!("sym-{key}.ies")),
            read(&format!("sym-{key}.ldt")),
        ];
        if key == "c90" {
            others.push(read("sym-c90-full.ldt"));
        }
        for p in &others {
            let what = format!("{} ({key})", p.file);
            if key != "rotational" {
                assert_eq!(p.horizontal(), full.horizontal(), "{what}");
            }
            assert_eq!(p.vertical(), full.vertical(), "{what}");
            let nv = full.vertical().len();
            let mut worst = 0.0f64;
            for (i, &h) in full.horizontal().iter().enumerate() {
                for (j, &v) in full.vertical().iter().enumerate() {
                    worst = worst.max((p.intensity(h, v) - full.candela()[i * nv + j]).abs());
                }
            }
            assert!(worst < 1e-9, "{what}: off by {worst} cd");
        }
    }
    assert_eq!(
        read("sym-rotational.ies").format,
        PhotometryFormat::Lm63_1986
    );
    assert_eq!(
        read("sym-rotational.ies").keyword("TEXT"),
        Some("symmetry test: rotational")
    );
    assert_eq!(read("sym-quadrant.ies").format, PhotometryFormat::Lm63_1991);
    assert_eq!(read("sym-c90.ies").format, PhotometryFormat::Lm63_1995);
}

/// The closed-form fluxes of make_photometry.py's luminaires.
const DOWNLIGHT: f64 = 1700.0;
const BATWING: f64 = 3672.0;
const WALL_WASHER: f64 = 1200.0;
const FLOODLIGHT: f64 = 14000.0;

/// Four manufacturer-style files read with their metadata, and their tables integrate
/// to the closed-form flux of the distribution they sample within 1 % (the bilinear
/// table's chords are all that separates them); an EULUMDAT file's stated flux (lamp
/// flux × LOR) agrees with its table within 1 %, and so do the two files of one
/// luminaire.
#[test]
fn manufacturer_files_read_and_integrate_to_their_flux() {
    let dl = read("downlight.ies");
    assert_eq!(dl.keyword("LUMCAT"), Some("DL150-840-WH"));
    assert_eq!(dl.keyword("MANUFAC"), Some("Lumen & Co."));
    assert_eq!(dl.lumens_per_lamp, Some(2000.0));
    assert_eq!(dl.watts, Some(18.5));
    assert_eq!(dl.opening, Opening::Disk { diameter: 0.15 });
    assert!((dl.intensity(0.0, 0.0) - DOWNLIGHT * 5.0 / (2.0 * PI)).abs() < 1e-3);

    let bw = read("batwing.ies");
    assert_eq!(bw.format, PhotometryFormat::Lm63_2019);
    assert_eq!(bw.keyword("MANUFAC"), Some("Lichtwerk Lüdenscheid GmbH"));
    assert_eq!(
        bw.keyword("LUMINAIRE"),
        Some("Recessed office panel 600 × 600, batwing louvre\nspecular aluminium, UGR < 19")
    );
    assert_eq!((bw.lamps, bw.lumens_per_lamp), (4, Some(1350.0)));
    let Opening::Rectangle {
        along_c0,
        along_c90,
    } = bw.opening
    else {
        panic!("{:?}", bw.opening)
    };
    assert!(
        (along_c0 - 0.6).abs() < 1e-4 && (along_c90 - 0.6).abs() < 1e-4,
        "feet to metres"
    );

    let ww = read("wallwasher.ies");
    assert_eq!(ww.format, PhotometryFormat::Lm63_1995);
    assert_eq!(ww.lumens_per_lamp, None);
    assert!(ww.intensity(0.0, 45.0) > 5.0 * ww.intensity(180.0, 45.0));

    let fl = read("floodlight.ies");
    assert_eq!(fl.system(), PhotometricSystem::B);
    let tilt = fl.tilt.as_ref().expect("TILT=INCLUDE");
    assert_eq!(tilt.geometry, 1);
    assert!((tilt.factor(30.0) - 0.97).abs() < 1e-12);
    assert_eq!(fl.horizontal().first(), Some(&-90.0));

    for (p, exact) in [
        (&dl, DOWNLIGHT),
        (&bw, BATWING),
        (&ww, WALL_WASHER),
        (&fl, FLOODLIGHT),
    ] {
        assert!(rel(p.flux(), exact) < 0.01, "{}: {} lm", p.file, p.flux());
        assert!(p.warnings.is_empty(), "{}: {:?}", p.file, p.warnings);
        if let Some(per_lamp) = p.lumens_per_lamp {
            assert!(p.flux() < per_lamp * p.lamps as f64);
        }
    }
    for (name, ies) in [("downlight", &dl), ("batwing", &bw), ("wallwasher", &ww)] {
        let ldt = read(&format!("{name}.ldt"));
        let stated = ldt.stated_flux.unwrap();
        assert!(
            rel(ldt.flux(), stated) < 0.01,
            "{name}: {} vs {stated}",
            ldt.flux()
        );
        assert!(rel(ies.flux(), ldt.flux()) < 0.01, "{name}");
        assert!(ldt.warnings.is_empty(), "{name}: {:?}", ldt.warnings);
        assert_eq!(ldt.watts, ies.watts);
    }
    let bw_ldt = read("batwing.ldt");
    assert_eq!(
        bw_ldt.luminaire,
        Some((
            Opening::Rectangle {
                along_c0: 0.597,
                along_c90: 0.597
            },
            0.07
        ))
    );
    assert_eq!(
        bw_ldt.keyword("Company"),
        Some("Lichtwerk Lüdenscheid GmbH")
    );
    assert_eq!(bw_ldt.light_output_ratio, Some(0.68));
    assert_eq!(
        bw_ldt.opening,
        Opening::Rectangle {
            along_c0: 0.59,
            along_c90: 0.59
        }
    );
    assert_eq!(
        read("downlight.ldt").opening,
        Opening::Disk { diameter: 0.15 }
    );
}

fn ies_error(text: &str) -> String {
    match parse_ies(text.as_bytes(), Path::new("lamp.ies")) {
        Ok(_) => panic!("read:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn ldt_error(text: &str) -> String {
    match parse_ldt(text.as_bytes(), Path::new("lamp.ldt")) {
        Ok(_) => panic!("read:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const GOOD_IES: &str =
    "IESNA:LM-63-2002\n[TEST] x\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n100 70 0\n";

/// An uplight measured over γ 90–180° sends nothing downward, and its flux is the upper
/// hemisphere's: 100 cd uniform there is 2π·100 lm.
#[test]
fn vertical_angles_from_90_to_180() {
    let text = GOOD_IES
        .replace("0 45 90\n", "90 135 180\n")
        .replace("100 70 0", "100 100 100");
    let p = parse_ies(text.as_bytes(), Path::new("up.ies")).unwrap();
    assert_eq!(p.intensity(0.0, 45.0), 0.0);
    assert_eq!(p.intensity(200.0, 120.0), 100.0);
    assert!(rel(p.flux(), 2.0 * PI * 100.0) < 1e-12);
}

/// Bad files name the file, the line and what was expected.
#[test]
fn bad_ies_files_say_where_and_what() {
    assert!(parse_ies(GOOD_IES.as_bytes(), Path::new("lamp.ies")).is_ok());
    let e = ies_error(&GOOD_IES.replace("100 70 0\n", "100 70\n"));
    assert!(
        e.starts_with("lamp.ies: line 8: the file ends where a candela value was expected"),
        "{e}"
    );
    let e = ies_error(&GOOD_IES.replace("1 1 2 0 0 0", "1 3 2 0 0 0"));
    assert!(
        e.contains("line 4: type A photometry (photometric type 3) is not supported"),
        "{e}"
    );
    let e = ies_error(&GOOD_IES.replace("IESNA:LM-63-2002", "IESNA:LM-63-2031"));
    assert!(
        e.contains("line 1: unknown IES version 'IESNA:LM-63-2031'"),
        "{e}"
    );
    let e = ies_error(&GOOD_IES.replace("TILT=NONE\n", ""));
    assert!(e.contains("no TILT= line"), "{e}");
    let e = ies_error(&GOOD_IES.replace("0 45 90", "0 90 45"));
    assert!(
        e.contains("line 6: vertical angle 3 is 45° after 90°"),
        "{e}"
    );
    let e = ies_error(
        &GOOD_IES
            .replace("1 -1 1 3 1 1 2", "1 -1 1 3 2 1 2")
            .replace("\n0\n100 70 0", "\n0 45\n100 70 0 100 70 0"),
    );
    assert!(
        e.contains(
            "line 7: horizontal angles from 0° to 45°: type C files run 0 to 0, 90, 180 or 360°"
        ),
        "{e}"
    );
    let e = ies_error(&GOOD_IES.replace("1 1 10", "1 x 10"));
    assert!(
        e.contains("line 5: 'x' where the ballast-lamp photometric factor"),
        "{e}"
    );
    let e = ies_error(&GOOD_IES.replace("TILT=NONE", "TILT=lamp.tlt"));
    assert!(
        e.contains("line 3: cannot read the tilt file lamp.tlt"),
        "{e}"
    );
    let e = ies_error(&GOOD_IES.replace("100 70 0", "0 0 0"));
    assert!(e.contains("sends no light"), "{e}");
}

#[test]
fn bad_ldt_files_say_where_and_what() {
    let good = std::fs::read_to_string(data("cosine.ldt")).unwrap();
    assert!(parse_ldt(good.as_bytes(), Path::new("lamp.ldt")).is_ok());
    let lines: Vec<&str> = good.lines().collect();
    let with = |k: usize, s: &str| {
        let mut l = lines.clone();
        l[k] = s;
        l.join("\n")
    };
    let e = ldt_error(&with(2, "7"));
    assert!(
        e.starts_with(
            "lamp.ldt: line 3: the symmetry indicator Isym is 7; a whole number from 0 to 4"
        ),
        "{e}"
    );
    let e = ldt_error(&with(3, "many"));
    assert!(
        e.contains("line 4: 'many' where the number of C-planes Mc (a number) was expected"),
        "{e}"
    );
    let e = ldt_error(&lines[..lines.len() - 3].join("\n"));
    assert!(
        e.contains("the file ends where an intensity (cd/klm) was expected"),
        "{e}"
    );
    // Isym 2 calls for 13 planes of the 24 where Isym 1 had one.
    let e = ldt_error(&with(2, "2"));
    assert!(
        e.contains("the file ends where an intensity (cd/klm) was expected"),
        "{e}"
    );
}

/// A table that integrates to more or less than the file states by over 5 % is read
/// with a warning giving both numbers.
#[test]
fn flux_disagreeing_with_the_file_is_warned_about() {
    let good = std::fs::read_to_string(data("cosine.ldt")).unwrap();
    // Line 23 is the light output ratio, 31.4159 %: claim 40 %.
    let lines: Vec<String> = good
        .lines()
        .enumerate()
        .map(|(k, l)| if k == 22 { "40".into() } else { l.to_string() })
        .collect();
    let p = parse_ldt(lines.join("\n").as_bytes(), Path::new("lamp.ldt")).unwrap();
    assert_eq!(p.warnings.len(), 1, "{:?}", p.warnings);
    assert!(
        p.warnings[0].contains("314.2 lm, the file states 400.0 lm (-21.5 %)"),
        "{}",
        p.warnings[0]
    );
    // An IES table above its lamps' flux: 100 cd·cos γ is 314 lm, the lamp 200 lm.
    let ies = std::fs::read_to_string(data("cosine.ies"))
        .unwrap()
        .replace("1 -1 1 91", "1 200 1 91");
    let p = parse_ies(ies.as_bytes(), Path::new("lamp.ies")).unwrap();
    assert!(
        p.warnings[0].contains("more than the 200.0 lm of its lamps"),
        "{:?}",
        p.warnings
    );
}

/// glTF `EXT_lights_ies`: a profile by uri on a turned, scaled node and one embedded in
/// a buffer view. The node's −Z is the aim and its +X the C0 plane; its scale changes
/// nothing; `color × multiplier` scales the table.
#[test]
fn gltf_ext_lights_ies_places_and_turns_profiles() {
    let scene =
        load(&data("luminaires.gltf"), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.lights.len(), 2);
    let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-5;
    let ww = &scene.lights[scene.light("WallWasher").unwrap()].kind;
    let LightKind::Goniometric {
        position,
        frame,
        photometry,
        multiplier,
        ..
    } = ww
    else {
        panic!("{ww:?}")
    };
    assert!(close(*position, Vec3::new(1.0, 3.0, 0.0)));
    assert!(close(ww.direction().unwrap(), Vec3::NEG_Y), "{frame}");
    assert!(
        close(frame.x_axis, Vec3::NEG_Z),
        "C0 along world −Z: {frame}"
    );
    assert_eq!(*multiplier, Vec3::new(2.0, 1.0, 0.5));
    assert_eq!(photometry.file, "asymmetric.ies");
    // 45° below the horizon toward world −Z is C0: 200·cos 45°; toward +Z, C180: 0.
    let toward_c0 = ww.intensity_toward(Vec3::new(0.0, -1.0, -1.0).normalize());
    let i = 200.0 * std::f32::consts::FRAC_1_SQRT_2;
    let expected = Vec3::new(2.0, 1.0, 0.5) * i;
    assert!((toward_c0 - expected).length() < 1e-5 * i, "{toward_c0}");
    assert_eq!(
        ww.intensity_toward(Vec3::new(0.0, -1.0, 1.0).normalize()),
        Vec3::ZERO
    );
    let flux = ww.flux();
    assert!((flux.x as f64 - 2.0 * photometry.flux()).abs() < 1e-3);

    let embedded = &scene.lights[scene.light("cosine").unwrap()].kind;
    let LightKind::Goniometric { photometry, .. } = embedded else {
        panic!("{embedded:?}")
    };
    assert!(rel(photometry.flux(), 100.0 * PI) < 5e-5);
    assert!(close(
        embedded.intensity_toward(Vec3::NEG_Y),
        Vec3::splat(100.0)
    ));
}

#[test]
fn gltf_profile_errors_name_the_place() {
    let text = std::fs::read_to_string(data("luminaires.gltf")).unwrap();
    let dir = tempdir();
    let write = |name: &str, s: &str| {
        let p = dir.join(name);
        std::fs::write(&p, s).unwrap();
        p
    };
    let missing = write(
        "missing.gltf",
        &text.replace("\"light\": 0", "\"light\": 7"),
    );
    let e = load(&missing, &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("nodes[0].extensions.EXT_lights_ies: light profile 7 does not exist"),
        "{e}"
    );
    let no_file = write("nofile.gltf", &text);
    let e = load(&no_file, &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("extensions.EXT_lights_ies.lights[0]: missing file asymmetric.ies"),
        "{e}"
    );
    let beside = std::fs::read_to_string(data("asymmetric.ies")).unwrap();
    write("asymmetric.ies", &beside);
    let mime = write(
        "mime.gltf",
        &text.replace("application/x-ies-lm-63", "text/plain"),
    );
    let e = load(&mime, &LoadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("lights[1]: a profile in a buffer view needs \"mimeType\""),
        "{e}"
    );
}

/// `TILT=<file>` reads the tilt data from a file beside the IES file.
#[test]
fn tilt_data_from_a_file_beside() {
    let dir = tempdir();
    std::fs::write(dir.join("lamp.tlt"), "3\n3\n0 45 90\n1 0.8 0.5\n").unwrap();
    let ies = dir.join("lamp.ies");
    std::fs::write(&ies, GOOD_IES.replace("TILT=NONE", "TILT=lamp.tlt")).unwrap();
    let p = read_photometry(&ies).unwrap_or_else(|e| panic!("{e}"));
    let tilt = p.tilt.unwrap();
    assert_eq!((tilt.geometry, tilt.angles.len()), (3, 3));
    assert!((tilt.factor(67.5) - 0.65).abs() < 1e-12);
    std::fs::write(dir.join("lamp.tlt"), "4\n").unwrap();
    let e = read_photometry(&ies).unwrap_err().to_string();
    assert!(
        e.contains("lamp.tlt: line 1: the lamp-to-luminaire geometry (1, 2 or 3) is 4"),
        "{e}"
    );
}

/// A `TILT=<file>` is a reference like a scene's: one outside the IES file's folder
/// tree is refused with the line, the way it was written and the flag that allows it;
/// one in a subfolder is read.
#[test]
fn tilt_file_stays_beside() {
    let dir = tempdir();
    std::fs::create_dir(dir.join("lamps")).unwrap();
    std::fs::create_dir(dir.join("lamps/tilt")).unwrap();
    std::fs::write(dir.join("lamp.tlt"), "3\n3\n0 45 90\n1 0.8 0.5\n").unwrap();
    std::fs::copy(dir.join("lamp.tlt"), dir.join("lamps/tilt/lamp.tlt")).unwrap();
    let ies = dir.join("lamps/lamp.ies");
    std::fs::write(&ies, GOOD_IES.replace("TILT=NONE", "TILT=../lamp.tlt")).unwrap();
    let e = read_photometry(&ies).unwrap_err();
    let text = format!("{e} {}", e.hint.as_deref().unwrap_or(""));
    assert!(
        text.contains("line 3")
            && text.contains("../lamp.tlt")
            && text.contains("--allow-outside-paths"),
        "{text}"
    );
    std::fs::write(&ies, GOOD_IES.replace("TILT=NONE", "TILT=tilt/lamp.tlt")).unwrap();
    let p = read_photometry(&ies).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.tilt.unwrap().angles.len(), 3);
}

/// A unique empty folder under the target directory (no tempfile dependency here).
fn tempdir() -> PathBuf {
    use std::sync::atomic::{AtomicU32, Ordering};
    static N: AtomicU32 = AtomicU32::new(0);
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "photometry-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `Scene::set_photometry` turns a point light into the luminaire aimed down (−up) and
/// a spot into one aimed along the spot, applies the IES tilt factor at the aim's angle
/// from straight down, and refuses what it cannot do.
#[test]
fn set_photometry_replaces_point_and_spot_lights() {
    let flood = Arc::new(read("floodlight.ies"));
    let mut scene = Scene::default();
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Lamp".into(),
        kind: LightKind::Point {
            position: Vec3::new(0.0, 3.0, 0.0),
            intensity: Vec3::ONE,
        },
    });
    let aim = Vec3::new(0.5, -(3.0f32.sqrt()) / 2.0, 0.0);
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Spot".into(),
        kind: LightKind::Spot {
            position: Vec3::new(1.0, 3.0, 0.0),
            direction: aim,
            intensity: Vec3::ONE,
            inner: 0.1,
            outer: 0.2,
        },
    });
    scene.lights.push(Light {
        c0: invlight_scene::Vec3::X,
        name: "Sun".into(),
        kind: LightKind::Directional {
            direction: Vec3::NEG_Y,
            illuminance: Vec3::ONE,
        },
    });
    scene.set_photometry("Lamp", flood.clone(), 2.0).unwrap();
    scene.set_photometry("Spot", flood.clone(), 1.0).unwrap();
    let LightKind::Goniometric {
        position,
        frame,
        multiplier,
        ..
    } = &scene.lights[0].kind
    else {
        panic!()
    };
    assert_eq!(*position, Vec3::new(0.0, 3.0, 0.0));
    assert!((-frame.z_axis - Vec3::NEG_Y).length() < 1e-6);
    assert!((frame.x_axis - Vec3::X).length() < 1e-6);
    assert_eq!(*multiplier, Vec3::splat(2.0));
    let LightKind::Goniometric {
        frame,
        multiplier,
        tilt,
        ..
    } = &scene.lights[1].kind
    else {
        panic!()
    };
    assert!((-frame.z_axis - aim).length() < 1e-6);
    // 30° from straight down: the floodlight's tilt factor 0.97, beside the multiplier.
    assert_eq!(*multiplier, Vec3::ONE);
    assert!((tilt - 0.97).abs() < 1e-6, "{tilt}");
    let on_axis = scene.lights[1].kind.intensity_toward(aim);
    // Aimed straight down, the tilt factor is the file's at 0° and the light follows it;
    // the multiplier (what dimming sets, what the watts follow) is unchanged.
    let at_0 = flood.tilt.as_ref().unwrap().factor(0.0) as f32;
    assert!(
        (at_0 - 0.97).abs() > 0.01,
        "the test needs another factor at 0°"
    );
    scene.lights[1]
        .kind
        .set_frame(aimed_frame(Vec3::NEG_Y, Vec3::X), Vec3::Y);
    let LightKind::Goniometric {
        multiplier, tilt, ..
    } = &scene.lights[1].kind
    else {
        panic!()
    };
    assert_eq!((*multiplier, *tilt), (Vec3::ONE, at_0));
    let down = scene.lights[1].kind.intensity_toward(Vec3::NEG_Y);
    assert!(
        (down.x / on_axis.x - at_0 / 0.97).abs() < 1e-5,
        "{down} {on_axis}"
    );
    assert_eq!(
        scene.set_photometry("Sun", flood.clone(), 1.0),
        Err(PhotometryError::NotAtAPoint { name: "Sun".into() })
    );
    let e = scene
        .set_photometry("Lmap", flood.clone(), 1.0)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "no light named 'Lmap'; the scene's lights are Lamp, Spot, Sun"
    );
    assert!(scene.set_photometry("Lamp", flood, -1.0).is_err());
}

/// One linear luminaire written in both formats (make_photometry.py): IES lays its
/// 1500 mm length along C0–C180, EULUMDAT along C90–C270, and in each file that is the
/// plane where it is cosine-like (I = I₀ cos γ at 60°), the batwing across it. The two
/// tables are one distribution turned by 90°, with the same flux; the EULUMDAT
/// luminaire's own 1520 × 80 mm lies the same way as its opening.
#[test]
fn a_linear_luminaires_length_lies_along_its_cosine_like_plane_in_both_formats() {
    let (ies, ldt) = (read("linear.ies"), read("linear.ldt"));
    assert_eq!(
        ies.opening,
        Opening::Rectangle {
            along_c0: 1.5,
            along_c90: 0.06
        }
    );
    assert_eq!(
        ldt.opening,
        Opening::Rectangle {
            along_c0: 0.06,
            along_c90: 1.5
        }
    );
    assert_eq!(
        ldt.luminaire,
        Some((
            Opening::Rectangle {
                along_c0: 0.08,
                along_c90: 1.52
            },
            0.05
        ))
    );
    let i0 = 3000.0 / (PI * 1.375);
    let cosine_like = |p: &Photometry, c: f64| (p.intensity(c, 60.0) - i0 * 0.5).abs() < 1e-3 * i0;
    assert!(cosine_like(&ies, 0.0) && !cosine_like(&ies, 90.0));
    assert!(cosine_like(&ldt, 90.0) && !cosine_like(&ldt, 0.0));
    for c in [0.0, 15.0, 40.0, 90.0, 135.0, 200.0, 300.0] {
        for g in [0.0, 25.0, 60.0, 85.0] {
            let (a, b) = (ies.intensity(c, g), ldt.intensity((c + 90.0) % 360.0, g));
            assert!((a - b).abs() < 1e-3 * i0, "C{c} γ{g}: {a} vs {b}");
        }
    }
    assert!(rel(ies.flux(), ldt.flux()) < 1e-3);
    assert!(rel(ies.flux(), 3000.0) < 0.01, "{}", ies.flux());
    assert!(ies.warnings.is_empty() && ldt.warnings.is_empty());
}

/// LM-63-2019 codes the opening's shape by the signs of its width, length and height;
/// each reads as the flat section invlight emits from, its height kept for its
/// projected area, and a body (cylinder, sphere) is warned of.
#[test]
fn lm63_2019_shapes_by_the_signs_of_their_dimensions() {
    let with = |w: &str, l: &str, h: &str| {
        let text = GOOD_IES
            .replace("IESNA:LM-63-2002", "IES:LM-63-2019")
            .replace("1 1 2 0 0 0\n", &format!("1 1 2 {w} {l} {h}\n"));
        parse_ies(text.as_bytes(), Path::new("shape.ies")).unwrap()
    };
    let rect = |along_c0, along_c90| Opening::Rectangle {
        along_c0,
        along_c90,
    };
    for (w, l, h, opening, height, warning) in [
        ("0", "0", "0", Opening::Point, 0.0, ""),
        ("0.1", "0.5", "0", rect(0.5, 0.1), 0.0, ""),
        ("0.1", "0.5", "0.04", rect(0.5, 0.1), 0.04, ""),
        (
            "-0.2",
            "-0.2",
            "0",
            Opening::Disk { diameter: 0.2 },
            0.0,
            "",
        ),
        (
            "-0.1",
            "-0.3",
            "0",
            Opening::Ellipse {
                along_c0: 0.3,
                along_c90: 0.1,
            },
            0.0,
            "",
        ),
        (
            "-0.2",
            "-0.2",
            "0.3",
            Opening::Disk { diameter: 0.2 },
            0.3,
            "",
        ),
        (
            "-0.2",
            "-0.2",
            "-0.2",
            Opening::Disk { diameter: 0.2 },
            0.2,
            "a sphere",
        ),
        (
            "-0.05",
            "1.2",
            "-0.05",
            rect(1.2, 0.05),
            0.05,
            "1200 mm long along C0–C180",
        ),
        (
            "1.2",
            "-0.05",
            "-0.05",
            rect(0.05, 1.2),
            0.05,
            "1200 mm long along C90–C270",
        ),
        ("-0.2", "0", "-0.2", Opening::Point, 0.2, "from its centre"),
    ] {
        let p = with(w, l, h);
        assert_eq!(p.opening, opening, "{w} {l} {h}");
        assert!((p.opening_height - height).abs() < 1e-6, "{w} {l} {h}");
        match warning {
            "" => assert!(p.warnings.is_empty(), "{w} {l} {h}: {:?}", p.warnings),
            _ => assert!(
                p.warnings.iter().any(|m| m.contains(warning)),
                "{w} {l} {h}: {:?}",
                p.warnings
            ),
        }
    }
}

/// The second number on LM-63's ballast line was the ballast-lamp photometric factor
/// until LM-63-1995 and is "future use" from LM-63-2002 (the file generation type in
/// 2019): the older editions multiply the table by it, the newer do not.
#[test]
fn the_ballast_lamp_factor_applies_before_2002_only() {
    let with = |header: &str| {
        let text = GOOD_IES
            .replace("IESNA:LM-63-2002", header)
            .replace("\n1 1 10\n", "\n1 2 10\n");
        parse_ies(text.as_bytes(), Path::new("factor.ies")).unwrap()
    };
    for (header, factor) in [
        ("IESNA:LM-63-1995", 2.0),
        ("IESNA91", 2.0),
        ("IESNA:LM-63-2002", 1.0),
        ("IES:LM-63-2019", 1.0),
    ] {
        let p = with(header);
        assert_eq!(p.intensity(0.0, 0.0), 100.0 * factor, "{header}");
    }
}

/// A glTF point light's node turned a quarter turn about the vertical turns the
/// photometric file given to it (`<luminaire>`, `--luminaire`): C0 follows the node's
/// local +X instead of staying on world +X, and `rotation` turns it further about its
/// aim.
#[test]
fn a_luminaire_follows_its_nodes_rotation_and_its_own() {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/hostile/lamp_floor.gltf"),
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(data("linear.ldt"), dir.path().join("linear.ldt")).unwrap();
    let c0 = |gltf: &str, rotation: f32| {
        let path = dir.path().join("room.gltf");
        std::fs::write(&path, gltf).unwrap();
        let luminaire = invlight_scene::Luminaire {
            light: "Lamp".into(),
            file: dir.path().join("linear.ldt"),
            multiplier: 1.0,
            rotation,
            origin: None,
        };
        let scene = invlight_scene::load_with(&path, &LoadOptions::default(), &[luminaire])
            .unwrap_or_else(|e| panic!("{e}"));
        match &scene.lights[0].kind {
            LightKind::Goniometric { frame, .. } => {
                // Aimed down (−Y, the file's up being +Y) whichever way it is turned.
                assert!(frame.z_axis.distance(Vec3::Y) < 1e-5, "{frame:?}");
                frame.x_axis
            }
            k => panic!("{k:?}"),
        }
    };
    assert!(c0(&text, 0.0).distance(Vec3::X) < 1e-5);
    // A quarter turn about +Y: local +X goes to −Z.
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let turned = text.replacen(
        "\"translation\"",
        &format!("\"rotation\": [0, {s}, 0, {s}],\n   \"translation\""),
        1,
    );
    assert_ne!(turned, text);
    assert!(c0(&turned, 0.0).distance(Vec3::NEG_Z) < 1e-5);
    // The fitting's own quarter turn, C0 toward C90, does the same from the unturned
    // node, and undoes the node's turn when negative.
    assert!(c0(&text, 90.0).distance(Vec3::NEG_Z) < 1e-5);
    assert!(c0(&turned, -90.0).distance(Vec3::X) < 1e-5);
}
