//! MTL material libraries, mapped to the photon tracer's materials (thesis Algorithm
//! 2.2: diffuse K_d, mirror K_s, refraction, emission).
//!
//! The mapping:
//! - `Kd` (+ `map_Kd`, which multiplies it): diffuse reflectance.
//! - `Ke`: emitted luminance in cd/m² (Lambertian, front face): the faces become an
//!   area light.
//! - `Ks` is a mirror only when `illum` asks for ray-traced reflection (3, 5 or 8); under
//!   `illum 2` it is a Phong highlight, which a photon tracer has no use for.
//! - Glass when `illum` asks for refraction (4, 6, 7 or 9): transmission from `Tf`
//!   (mean of its channels) when given, else `1 − d`, else 1; index of refraction `Ni`,
//!   or 1.5 when `Ni` is missing or below 1 (exporters write `Ni 0` as a placeholder).
//!   A dissolve `d` < 1 under any other `illum` is a straight-through transparency
//!   (transmission `1 − d`, index 1).
//!
//! Reflectances are then scaled so that K_d + K_s + transmission ≤ 1 per channel, which
//! Russian roulette needs to be a probability split ([`energy_conserving`]).

use super::{StatementError, lines, parse_f32, parse_floats, show, tokens};
use crate::error::LoadError;
use crate::files::Files;
use crate::image_file::{TextureError, read_texture};
use crate::material::{Material, Rgb, Texture};
use crate::model::TextureId;
use glam::Vec3;
use std::collections::HashMap;
use std::path::Path;

/// One `newmtl` block as written.
struct Record {
    name: String,
    kd: Rgb,
    ks: Rgb,
    ke: Rgb,
    tf: Option<Rgb>,
    d: Option<f32>,
    ni: Option<f32>,
    illum: u32,
    /// The `map_Kd` file and the number of its line.
    map_kd: Option<(String, usize)>,
    /// Line of a `map_Ke` statement.
    map_ke: Option<usize>,
}

impl Record {
    fn new(name: String) -> Self {
        Record {
            name,
            kd: Vec3::splat(super::DEFAULT_REFLECTANCE),
            ks: Vec3::ZERO,
            ke: Vec3::ZERO,
            tf: None,
            d: None,
            ni: None,
            illum: 1,
            map_kd: None,
            map_ke: None,
        }
    }
}

/// Parses an MTL file (`path` names it in errors and anchors texture paths); decoded
/// textures are appended to `textures`. A texture that cannot be read is a warning (the
/// material keeps its colour); one outside the scene's folder or past the memory budget
/// is an error.
pub(super) fn parse(
    bytes: &[u8],
    path: &Path,
    textures: &mut Vec<Texture>,
    files: &Files,
) -> Result<Vec<Material>, LoadError> {
    let mut records: Vec<Record> = Vec::new();
    for (number, line) in lines(bytes) {
        let at = |e: StatementError| LoadError::at(path, format!("line {number}"), e.to_string());
        let mut it = tokens(line);
        let Some(keyword) = it.next() else { continue };
        if keyword == b"newmtl" {
            let name = it.map(show).collect::<Vec<_>>().join(" ");
            records.push(Record::new(name));
            continue;
        }
        let Some(record) = records.last_mut() else {
            continue;
        };
        match keyword {
            b"Kd" => record.kd = rgb(&mut it, "Kd").map_err(at)?,
            b"Ks" => record.ks = rgb(&mut it, "Ks").map_err(at)?,
            b"Ke" => record.ke = rgb(&mut it, "Ke").map_err(at)?,
            b"Tf" => record.tf = Some(rgb(&mut it, "Tf").map_err(at)?),
            b"d" => record.d = Some(scalar(&mut it, "d").map_err(at)?),
            b"Tr" => record.d = Some(1.0 - scalar(&mut it, "Tr").map_err(at)?),
            b"Ni" => record.ni = Some(scalar(&mut it, "Ni").map_err(at)?),
            b"illum" => {
                let value = scalar(&mut it, "illum").map_err(at)?;
                record.illum = value as u32;
            }
            b"map_Kd" => record.map_kd = texture_file(line).map(|f| (f, number)),
            b"map_Ke" => record.map_ke = Some(number),
            _ => {}
        }
    }
    if let Some((r, line)) = records.iter().find_map(|r| {
        r.map_ke
            .filter(|_| r.ke.max_element() > 0.0)
            .map(|l| (r, l))
    }) {
        return Err(LoadError::at(
            path,
            format!("line {line}"),
            format!("material '{}' emits through a texture (map_Ke), which invlight does not read: it would emit Ke uniformly over the whole surface", r.name),
        )
        .with_hint("bake the texture's mean into Ke, or remove Ke if the surface should not emit"));
    }
    let mut decoded: HashMap<String, Option<TextureId>> = HashMap::new();
    let mut materials = Vec::with_capacity(records.len());
    for r in records {
        let mut texture = None;
        if let Some((file, line)) = &r.map_kd {
            texture = match decoded.get(file) {
                Some(&t) => t,
                None => {
                    let loc = format!("line {line}");
                    let written = file.replace('\\', "/");
                    let resolved = files.resolve(path, &loc, file, Path::new(&written))?;
                    let t = match read_texture(&resolved, path, &loc, files) {
                        Ok(t) => {
                            textures.push(t);
                            Some(TextureId::from_index(textures.len() - 1))
                        }
                        Err(TextureError::Refused(e)) => return Err(e),
                        Err(TextureError::Unreadable(e)) => {
                            eprintln!("warning: {e}; material '{}' keeps its Kd colour", r.name);
                            None
                        }
                    };
                    decoded.insert(file.clone(), t);
                    t
                }
            };
        }
        materials.push(material(r, texture));
    }
    Ok(materials)
}

/// The tracer's material for one record.
fn material(r: Record, texture: Option<TextureId>) -> Material {
    let mirror = matches!(r.illum, 3 | 5 | 8);
    let glass = matches!(r.illum, 4 | 6 | 7 | 9);
    let dissolve = r.d.map(|d| (1.0 - d).clamp(0.0, 1.0));
    let (transmission, ior) = if glass {
        let t = match (r.tf, dissolve) {
            (Some(tf), _) => (tf.x + tf.y + tf.z) / 3.0,
            (None, Some(t)) => t,
            (None, None) => 1.0,
        };
        let ior = r.ni.filter(|&n| n >= 1.0).unwrap_or(1.5);
        (t.clamp(0.0, 1.0), ior)
    } else {
        (dissolve.unwrap_or(0.0), 1.0)
    };
    let specular = if mirror { r.ks } else { Vec3::ZERO };
    let (diffuse, specular) = energy_conserving(r.kd, specular, transmission);
    Material {
        name: r.name,
        diffuse,
        texture,
        specular,
        transmission,
        ior,
        emission: r.ke.max(Vec3::ZERO),
        hole: false,
    }
}

/// Scales K_d and K_s (clamped to be non-negative) so that K_d + K_s + transmission ≤ 1
/// per channel, as Russian roulette needs (thesis Algorithm 2.2: the probabilities of
/// the events must not sum past 1). Reflectances within the bound are left unchanged.
pub(crate) fn energy_conserving(kd: Rgb, ks: Rgb, transmission: f32) -> (Rgb, Rgb) {
    let (kd, ks) = (kd.max(Vec3::ZERO), ks.max(Vec3::ZERO));
    let room = (1.0 - transmission).max(0.0);
    let sum = (kd + ks).max_element();
    if sum > room {
        let s = room / sum;
        (kd * s, ks * s)
    } else {
        (kd, ks)
    }
}

/// The file name of a texture statement (`map_Kd -s 1 1 1 -clamp on tex/a b.png`):
/// options and their arguments (numbers, `on`/`off`) are skipped, and the rest of the
/// line is the name, which may contain spaces.
fn texture_file(line: &[u8]) -> Option<String> {
    let end = line.iter().position(|&b| b == b'#').unwrap_or(line.len());
    let line = &line[..end];
    let mut rest = line.trim_ascii_start();
    // Skip the keyword.
    let skip_token = |s: &[u8]| -> usize {
        s.iter()
            .position(u8::is_ascii_whitespace)
            .unwrap_or(s.len())
    };
    rest = rest[skip_token(rest)..].trim_ascii_start();
    let mut in_option = false;
    while !rest.is_empty() {
        let n = skip_token(rest);
        let token = &rest[..n];
        let is_argument = parse_f32(token).is_ok() || token == b"on" || token == b"off";
        if token == b"-imfchan" || token == b"-type" {
            // Options whose one argument is a word (`-imfchan l`, `-type sphere`).
            rest = rest[n..].trim_ascii_start();
            rest = rest[skip_token(rest)..].trim_ascii_start();
            in_option = false;
            continue;
        }
        if token.starts_with(b"-") && !is_argument {
            in_option = true;
        } else if !(in_option && is_argument) {
            break;
        }
        rest = rest[n..].trim_ascii_start();
    }
    let name = show(rest.trim_ascii_end());
    (!name.is_empty()).then_some(name)
}

fn rgb<'a>(
    it: &mut impl Iterator<Item = &'a [u8]>,
    statement: &'static str,
) -> Result<Rgb, StatementError> {
    let mut it = it.peekable();
    if it.peek() == Some(&&b"spectral"[..]) || it.peek() == Some(&&b"xyz"[..]) {
        return Err(StatementError::UnsupportedColour {
            statement,
            space: show(it.next().unwrap_or_default()),
        });
    }
    let first = parse_f32(it.next().ok_or(StatementError::NoColour { statement })?)?;
    // A single value is a grey, as the MTL specification allows.
    let rest: Result<Vec<f32>, StatementError> = it.take(2).map(parse_f32).collect();
    match rest?.as_slice() {
        [] => Ok(Vec3::splat(first)),
        [g, b] => Ok(Vec3::new(first, *g, *b)),
        _ => Err(StatementError::ColourCount { statement }),
    }
}

fn scalar<'a>(
    it: &mut impl Iterator<Item = &'a [u8]>,
    what: &'static str,
) -> Result<f32, StatementError> {
    let [v] = parse_floats(it, what)?;
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::LoadOptions;

    fn parse(
        bytes: &[u8],
        path: &Path,
        textures: &mut Vec<Texture>,
    ) -> Result<Vec<Material>, LoadError> {
        super::parse(
            bytes,
            path,
            textures,
            &Files::new(path, &LoadOptions::default()),
        )
    }

    fn one(text: &str) -> Material {
        let mut textures = Vec::new();
        let mut m = parse(text.as_bytes(), Path::new("t.mtl"), &mut textures).unwrap();
        assert_eq!(m.len(), 1);
        m.remove(0)
    }

    /// An emission texture is refused, not silently spread evenly over the surface; a
    /// texture on a surface that does not emit is harmless.
    #[test]
    fn emission_textures_are_refused() {
        let mut textures = Vec::new();
        let e = parse(
            b"newmtl lamp\nKe 5 5 5\nmap_Ke glow.png\n",
            Path::new("t.mtl"),
            &mut textures,
        )
        .unwrap_err();
        assert_eq!(e.location, "line 3");
        assert!(
            e.message.contains("map_Ke") && e.message.contains("'lamp'"),
            "{e}"
        );
        assert!(
            parse(
                b"newmtl dark\nmap_Ke glow.png\n",
                Path::new("t.mtl"),
                &mut textures
            )
            .is_ok()
        );
    }

    #[test]
    fn illum_decides_mirror_and_glass() {
        let m = one("newmtl a\nKd 0.2 0.2 0.2\nKs 0.7 0.7 0.7\nillum 2\n");
        assert_eq!(m.kind_name(), "diffuse");
        let m = one("newmtl a\nKd 0.2 0.2 0.2\nKs 0.7 0.7 0.7\nillum 3\n");
        assert_eq!((m.kind_name(), m.specular), ("mirror", Vec3::splat(0.7)));
        let m = one("newmtl a\nKd 0 0 0\nNi 1.33\nTf 0.9 0.9 0.9\nillum 7\n");
        assert_eq!((m.kind_name(), m.ior), ("glass", 1.33));
        assert!((m.transmission - 0.9).abs() < 1e-6);
        let m = one("newmtl a\nKd 0.5 0.5 0.5\nd 0.25\nNi 0\nillum 4\n");
        assert_eq!((m.ior, m.transmission), (1.5, 0.75));
        // K_d is scaled so that K_d + transmission ≤ 1.
        assert!((m.diffuse.x - 0.25).abs() < 1e-6);
    }

    #[test]
    fn emission_and_single_value_colours() {
        let m = one("newmtl light\nKd 0.78\nKe 17 12 4\n");
        assert_eq!(m.emission, Vec3::new(17.0, 12.0, 4.0));
        assert_eq!(m.diffuse, Vec3::splat(0.78));
        assert!(m.is_emissive());
    }

    #[test]
    fn texture_names_follow_their_options() {
        let name = |l: &str| texture_file(l.as_bytes());
        assert_eq!(name("map_Kd tex.png"), Some("tex.png".into()));
        assert_eq!(
            name("map_Kd -s 1 1 1 -clamp on my tex.png # c"),
            Some("my tex.png".into())
        );
        assert_eq!(
            name("map_Kd -bm 0.5 -imfchan l bump.png"),
            Some("bump.png".into())
        );
        assert_eq!(name("map_Kd"), None);
    }

    #[test]
    fn bad_numbers_name_the_line() {
        let mut textures = Vec::new();
        let e = parse(b"newmtl a\n\nKd 1 x 1\n", Path::new("t.mtl"), &mut textures).unwrap_err();
        assert_eq!(e.to_string(), "t.mtl: line 3: expected a number, found 'x'");
    }
}
