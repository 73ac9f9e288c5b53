//! IES LM-63 files, every version: 1986 (no header), 1991 (`IESNA91`), 1995
//! (`IESNA:LM-63-1995`), 2002 (`IESNA:LM-63-2002`) and 2019 (`IES:LM-63-2019`).
//!
//! Layout (LM-63-2002 §5): the header line, keyword lines `[KEY] text` (free text in
//! 1986), `TILT=NONE|INCLUDE|<file>` with the tilt data when included, then numbers
//! separated by blanks, commas or line ends: lamps, lumens per lamp (−1: absolute
//! photometry), candela multiplier, the counts of vertical and horizontal angles,
//! photometric type (1 C, 2 B, 3 A), units (1 feet, 2 metres), the luminous opening's
//! width, length and height; ballast factor, a field that was the ballast-lamp
//! photometric factor until 1995 (since "future use", and in 2019 the file generation
//! type), input watts; the vertical angles, the horizontal angles, and the candela
//! values plane by plane (one horizontal angle, all its vertical angles).

use super::symmetry::{Symmetry, expand_b, expand_c};
use super::text::{Numbers, increasing, latin1};
use super::{Opening, PhotometricSystem, Photometry, PhotometryFormat, Table, Tilt};
use crate::error::LoadError;
use crate::files::{Files, ReadError};
use crate::load::LoadOptions;
use std::path::Path;

/// Metres per foot.
const FOOT: f64 = 0.3048;

const FORMAT_HINT: &str = "the file does not follow IES LM-63: export it again from the manufacturer's tool, or check the counts of angles against the values";

/// Reads an IES LM-63 file's bytes; `path` names it in errors and locates a
/// `TILT=<file>`, which is read as a scene's references are (files.rs): from the IES
/// file's folder or below, a regular file, within the default memory budget.
pub fn parse_ies(bytes: &[u8], path: &Path) -> Result<Photometry, LoadError> {
    parse_ies_in(bytes, path, &Files::new(path, &LoadOptions::default()))
}

/// [`parse_ies`] with the references of the load it is part of: a `TILT=<file>` is
/// resolved relative to `path` and must stay where `files` allows (the scene's or the
/// problem file's folder unless `--allow-outside-paths`), charged to its budget.
pub(crate) fn parse_ies_in(
    bytes: &[u8],
    path: &Path,
    files: &Files,
) -> Result<Photometry, LoadError> {
    let text = latin1(bytes).replace("\r\n", "\n").replace('\r', "\n");
    let lines: Vec<&str> = text.lines().collect();
    let (format, start) = version(path, &lines)?;
    let tilt_line = tilt_line(path, &lines)?;
    let keywords = keywords(path, &lines[start..tilt_line], start + 1, format)?;
    let mut numbers = Numbers::new(path, &lines[tilt_line + 1..], tilt_line + 2);
    let tilt = tilt(path, files, lines[tilt_line], tilt_line + 1, &mut numbers)?;
    let fields = Fields::read(path, &mut numbers)?;
    let measured = Measured::read(path, &mut numbers, fields.nv, fields.nh)?;
    let mut warnings = Vec::new();
    if numbers.rest() > 0 {
        warnings.push(format!(
            "{} numbers follow the {} candela values and were ignored: check the counts of angles",
            numbers.rest(),
            measured.candela.len()
        ));
    }
    let table = table(path, format, &fields, &measured)?;
    let (opening, opening_height, shape_warning) = opening(
        fields.width as f32,
        fields.length as f32,
        fields.height as f32,
    );
    warnings.extend(shape_warning);
    let mut p = Photometry {
        file: file_name(path),
        source: None,
        format,
        keywords,
        lamps: fields.lamps as u32,
        lumens_per_lamp: (fields.lumens > 0.0).then_some(fields.lumens),
        stated_flux: None,
        light_output_ratio: None,
        watts: (fields.watts > 0.0).then_some(fields.watts),
        ballast_factor: fields.ballast,
        opening,
        opening_height,
        luminaire: None,
        tilt,
        warnings,
        table,
    };
    p.check_flux();
    Ok(p)
}

/// An error about line `line` (1-based) of the file.
fn at(path: &Path, line: usize, message: String) -> LoadError {
    LoadError::at(path, format!("line {line}"), message)
}

/// The version the header line names, and the index of the first line after it;
/// LM-63-1986 has no header. An unknown version is refused rather than guessed at,
/// since the versions lay out their numbers differently.
fn version(path: &Path, lines: &[&str]) -> Result<(PhotometryFormat, usize), LoadError> {
    let first = lines.first().map_or("", |l| l.trim());
    Ok(match first {
        "IESNA91" => (PhotometryFormat::Lm63_1991, 1),
        "IESNA:LM-63-1995" => (PhotometryFormat::Lm63_1995, 1),
        "IESNA:LM-63-2002" => (PhotometryFormat::Lm63_2002, 1),
        "IES:LM-63-2019" => (PhotometryFormat::Lm63_2019, 1),
        s if s.starts_with("IESNA:") || s.starts_with("IES:") => {
            return Err(at(path, 1, format!("unknown IES version '{s}'")).with_hint(
                "invlight reads IESNA91, IESNA:LM-63-1995, IESNA:LM-63-2002 and IES:LM-63-2019 files and headerless LM-63-1986 ones",
            ));
        }
        _ => (PhotometryFormat::Lm63_1986, 0),
    })
}

/// The index of the `TILT` line, which ends the keywords and starts the numbers; a file
/// without one is not an IES file at all.
fn tilt_line(path: &Path, lines: &[&str]) -> Result<usize, LoadError> {
    lines
        .iter()
        .position(|l| l.trim_start().starts_with("TILT"))
        .ok_or_else(|| {
            LoadError::new(path, "no TILT= line: this is not an IES LM-63 file").with_hint(
                "every LM-63 file has a line TILT=NONE, TILT=INCLUDE or TILT=<file> before its numbers",
            )
        })
}

/// The keyword lines `[KEY] text` between the header and the `TILT` line, `lines`
/// starting on line `first`: a `[MORE]` continues the keyword before it, and a line
/// that is not a keyword (all of them in LM-63-1986) is kept as `TEXT`.
fn keywords(
    path: &Path,
    lines: &[&str],
    first: usize,
    format: PhotometryFormat,
) -> Result<Vec<(String, String)>, LoadError> {
    let mut keywords: Vec<(String, String)> = Vec::new();
    for (k, raw) in lines.iter().enumerate() {
        let line = raw.trim();
        if line.is_empty() {
            continue;
        }
        match line.strip_prefix('[').and_then(|l| l.split_once(']')) {
            Some((key, value)) if format != PhotometryFormat::Lm63_1986 => {
                let value = value.trim().to_string();
                match (key, keywords.last_mut()) {
                    ("MORE", Some((_, last))) => {
                        last.push('\n');
                        last.push_str(&value);
                    }
                    ("MORE", None) => {
                        return Err(at(
                            path,
                            first + k,
                            "[MORE] with no keyword before it".into(),
                        ));
                    }
                    _ => keywords.push((key.to_string(), value)),
                }
            }
            _ => keywords.push(("TEXT".into(), line.to_string())),
        }
    }
    Ok(keywords)
}

/// The tilt data the `TILT` line (`line`, numbered `number`) asks for: none, the
/// numbers that follow it, or those of another file.
fn tilt(
    path: &Path,
    files: &Files,
    line: &str,
    number: usize,
    numbers: &mut Numbers<'_>,
) -> Result<Option<Tilt>, LoadError> {
    let spec = line.trim_start()["TILT".len()..].trim_start();
    let Some(spec) = spec.strip_prefix('=').map(str::trim) else {
        return Err(at(path, number, "'TILT' without '='".into())
            .with_hint("write TILT=NONE, TILT=INCLUDE or TILT=<file>"));
    };
    match spec {
        "NONE" => Ok(None),
        "INCLUDE" => read_tilt(numbers).map(Some),
        file => tilt_file(path, files, file, number).map(Some),
    }
}

/// The tilt data of `TILT=<file>` on line `line`, looked up beside the IES file and
/// read as its other references are; a missing or unreadable one is an error at the
/// `TILT` line, since the table cannot be tilted without it.
fn tilt_file(path: &Path, files: &Files, file: &str, line: usize) -> Result<Tilt, LoadError> {
    let loc = format!("line {line}");
    let tilt_path = files.resolve(path, &loc, file, Path::new(file))?;
    let cannot = |why: String| {
        at(
            path,
            line,
            format!(
                "cannot read the tilt file {file} ({}): {why}",
                tilt_path.display()
            ),
        )
        .with_hint("a TILT=<file> is looked up beside the IES file")
    };
    let bytes = files
        .read(path, &loc, &tilt_path, None)
        .map_err(|e| match e {
            ReadError::Missing => cannot("no such file".into()),
            ReadError::Io(m) => cannot(m),
            ReadError::Budget(e) => e,
        })?;
    let tilt_text = latin1(&bytes);
    let tilt_lines: Vec<&str> = tilt_text.lines().collect();
    read_tilt(&mut Numbers::new(&tilt_path, &tilt_lines, 1))
}

/// The numbers between the tilt data and the angles (LM-63-2002 §5.8–5.10): the lamps,
/// the table's layout and multipliers, and the luminous opening, in metres.
struct Fields {
    lamps: i64,
    /// Lumens per lamp; −1 for absolute photometry.
    lumens: f64,
    multiplier: f64,
    /// Counts of vertical and horizontal angles.
    nv: usize,
    nh: usize,
    system: PhotometricSystem,
    width: f64,
    length: f64,
    height: f64,
    ballast: f64,
    /// The ballast-lamp photometric factor, for files before LM-63-2002.
    lamp_factor: f64,
    watts: f64,
}

impl Fields {
    /// Reads the fields in the file's order, refusing a multiplier or ballast factor
    /// that is not positive and type A photometry.
    fn read(path: &Path, numbers: &mut Numbers<'_>) -> Result<Fields, LoadError> {
        let lamps = numbers.int("the number of lamps", 0, 1_000_000)?;
        let lumens = numbers.f64("the lumens per lamp")?;
        let multiplier_line = numbers.line();
        let multiplier = numbers.f64("the candela multiplier")?;
        if multiplier <= 0.0 {
            return Err(at(
                path,
                multiplier_line,
                format!("the candela multiplier is {multiplier}; a positive number was expected"),
            ));
        }
        let nv = numbers.int("the number of vertical angles", 2, 100_000)? as usize;
        let nh = numbers.int("the number of horizontal angles", 1, 100_000)? as usize;
        let type_line = numbers.line();
        let system = match numbers.int("the photometric type", 1, 3)? {
            1 => PhotometricSystem::C,
            2 => PhotometricSystem::B,
            _ => {
                return Err(at(path, type_line, "type A photometry (photometric type 3) is not supported".into())
                    .with_hint("ask the manufacturer for the type C file (interior luminaires) or type B (floodlights); glTF EXT_lights_ies makes type A optional"));
            }
        };
        let metres = match numbers.int("the units type (1 feet, 2 metres)", 1, 2)? {
            1 => FOOT,
            _ => 1.0,
        };
        let width = numbers.f64("the width of the luminous opening")? * metres;
        let length = numbers.f64("the length of the luminous opening")? * metres;
        let height = numbers.f64("the height of the luminous opening")? * metres;
        let ballast_line = numbers.line();
        let ballast = numbers.f64("the ballast factor")?;
        let lamp_factor =
            numbers.f64("the ballast-lamp photometric factor (future use since 2002)")?;
        let watts = numbers.f64("the input watts")?;
        if ballast <= 0.0 {
            return Err(at(
                path,
                ballast_line,
                format!("the ballast factor is {ballast}; a positive number was expected"),
            ));
        }
        Ok(Fields {
            lamps,
            lumens,
            multiplier,
            nv,
            nh,
            system,
            width,
            length,
            height,
            ballast,
            lamp_factor,
            watts,
        })
    }
}

/// The angles and candela values as the file lists them, each with the line it starts
/// on, for errors.
struct Measured {
    vertical: Vec<f64>,
    v_line: usize,
    horizontal: Vec<f64>,
    h_line: usize,
    /// Plane by plane: `candela[h·nv + v]`.
    candela: Vec<f64>,
    c_line: usize,
}

impl Measured {
    /// Reads `nv` vertical and `nh` horizontal angles, each list increasing, and their
    /// candela values, none negative.
    fn read(
        path: &Path,
        numbers: &mut Numbers<'_>,
        nv: usize,
        nh: usize,
    ) -> Result<Measured, LoadError> {
        let v_line = numbers.line();
        let vertical = numbers.list(nv, "a vertical angle")?;
        increasing(path, v_line, &vertical, "vertical angle")?;
        let h_line = numbers.line();
        let horizontal = numbers.list(nh, "a horizontal angle")?;
        increasing(path, h_line, &horizontal, "horizontal angle")?;
        let c_line = numbers.line();
        let candela = numbers.list(nh * nv, "a candela value")?;
        if let Some(k) = candela.iter().position(|&c| c < 0.0) {
            return Err(at(
                path,
                c_line,
                format!(
                    "candela value {} is {}; intensities are ≥ 0",
                    k + 1,
                    candela[k]
                ),
            ));
        }
        Ok(Measured {
            vertical,
            v_line,
            horizontal,
            h_line,
            candela,
            c_line,
        })
    }
}

/// The horizontal and vertical angles over the whole sphere, each with the measured
/// angle it copies: type C planes by the symmetry their range declares (the vertical
/// angles as measured), type B by lateral symmetry in both.
type Expanded = (Vec<(f64, usize)>, Vec<(f64, usize)>);

/// The measured angles expanded to the whole sphere ([`Expanded`]); a range no symmetry
/// explains is an error at the line of its angles.
fn expand(path: &Path, system: PhotometricSystem, m: &Measured) -> Result<Expanded, LoadError> {
    let (h_line, v_line) = (m.h_line, m.v_line);
    let (horizontal, vertical) = (&m.horizontal, &m.vertical);
    let (nh, nv) = (horizontal.len(), vertical.len());
    Ok(match system {
        PhotometricSystem::C => {
            let symmetry = Symmetry::of_ies(horizontal[0], horizontal[nh - 1], nh)
                .map_err(|e| at(path, h_line, e.to_string()).with_hint(FORMAT_HINT))?;
            if vertical[0] < 0.0 || vertical[nv - 1] > 180.0 {
                return Err(at(
                    path,
                    v_line,
                    format!(
                        "vertical angles from {}° to {}°: type C angles lie within 0° and 180°",
                        vertical[0],
                        vertical[nv - 1]
                    ),
                ));
            }
            let h = expand_c(horizontal, symmetry).map_err(|e| at(path, h_line, e.to_string()))?;
            (h, (0..nv).map(|k| (vertical[k], k)).collect::<Vec<_>>())
        }
        PhotometricSystem::B => (
            expand_b(horizontal).map_err(|e| at(path, h_line, e.to_string()))?,
            expand_b(vertical).map_err(|e| at(path, v_line, e.to_string()))?,
        ),
    })
}

/// The candela table over the sphere: the measured values copied to the angles the
/// symmetry adds, times the candela multiplier and the ballast factor, and before
/// LM-63-2002 the ballast-lamp factor, which later versions leave for future use.
fn table(
    path: &Path,
    format: PhotometryFormat,
    fields: &Fields,
    m: &Measured,
) -> Result<Table, LoadError> {
    let (h_full, v_full) = expand(path, fields.system, m)?;
    let pre_2002 = matches!(
        format,
        PhotometryFormat::Lm63_1986 | PhotometryFormat::Lm63_1991 | PhotometryFormat::Lm63_1995
    );
    let lamp_factor = if pre_2002 { fields.lamp_factor } else { 1.0 };
    let scale = fields.multiplier * fields.ballast * lamp_factor;
    let (raw, nv) = (&m.candela, m.vertical.len());
    let candela: Vec<f64> = h_full
        .iter()
        .flat_map(|&(_, i)| v_full.iter().map(move |&(_, j)| raw[i * nv + j] * scale))
        .collect();
    Table::new(
        fields.system,
        h_full.iter().map(|p| p.0).collect(),
        v_full.iter().map(|p| p.0).collect(),
        candela,
    )
    .map_err(|e| LoadError::at(path, format!("lines {}–", m.c_line), e.to_string()))
}

/// The tilt data: lamp-to-luminaire geometry, the number of pairs, the angles and the
/// factors (LM-63-2002 §5.4–5.7).
fn read_tilt(numbers: &mut Numbers<'_>) -> Result<Tilt, LoadError> {
    let geometry = numbers.int("the lamp-to-luminaire geometry (1, 2 or 3)", 1, 3)? as u8;
    let n = numbers.int("the number of tilt angles", 0, 100_000)? as usize;
    let line = numbers.line();
    let angles = numbers.list(n, "a tilt angle")?;
    increasing(numbers.path(), line, &angles, "tilt angle")?;
    let factors = numbers.list(n, "a tilt multiplying factor")?;
    Ok(Tilt {
        geometry,
        angles,
        factors,
    })
}

/// The luminous opening of an IES file from its width, length and height, m, with the
/// height its sides or body count with, and a warning when invlight models it
/// approximately.
///
/// LM-63-2002 §5.11 lays the length along the 0°–180° photometric plane and the width
/// along 90°–270° (Radiance's `ies2rad` places them so, and a linear luminaire's
/// cosine-like, along-the-lamp plane is 0° in IES files): here `along_c0` is the
/// length. Zero width and length are a point; both positive a rectangle, a positive
/// height its luminous sides. LM-63-2019 codes other shapes by negative dimensions:
/// width and length negative an ellipse (a disk when equal) and with a height a
/// vertical cylinder (positive: its base and luminous sides, as a rectangle's) or a
/// spheroid (negative); one of them positive with a negative height a horizontal
/// cylinder, its positive dimension its length. A spheroid or horizontal cylinder
/// emits from its horizontal section, its height counted in its projected area, and is
/// warned of; shapes with a zero dimension (vertical circles) emit from their centre.
pub(super) fn opening(width: f32, length: f32, height: f32) -> (Opening, f32, Option<String>) {
    let mm = |m: f32| format!("{:.0}", 1000.0 * m.abs());
    let body = |shape: String| {
        Some(format!(
            "the luminous opening is {shape} (LM-63-2019): it emits from its horizontal section, its height counted in its projected area"
        ))
    };
    let (w, l, h) = (width, length, height);
    if w == 0.0 && l == 0.0 {
        (Opening::Point, h.abs(), None)
    } else if w > 0.0 && l > 0.0 && h >= 0.0 {
        let rectangle = Opening::Rectangle {
            along_c0: l,
            along_c90: w,
        };
        (rectangle, h, None)
    } else if w < 0.0 && l < 0.0 {
        let section = if (w - l).abs() <= 1e-3 * w.abs() {
            Opening::Disk { diameter: -w }
        } else {
            Opening::Ellipse {
                along_c0: -l,
                along_c90: -w,
            }
        };
        // A vertical cylinder (a positive height) is its base and its sides, as a
        // rectangle with luminous sides.
        let shape =
            (h < 0.0).then(|| format!("a sphere or spheroid {} × {} × {} mm", mm(l), mm(w), mm(h)));
        let shape = shape.and_then(body);
        (section, h.abs(), shape)
    } else if h < 0.0 && w != 0.0 && l != 0.0 && (w < 0.0) != (l < 0.0) {
        // One of width and length is negative: a horizontal cylinder along the other.
        let (long, along) = if l > 0.0 {
            (l, "C0–C180")
        } else {
            (w, "C90–C270")
        };
        let section = Opening::Rectangle {
            along_c0: l.abs(),
            along_c90: w.abs(),
        };
        let shape = format!(
            "a horizontal cylinder {} mm long along {along}, Ø {} mm",
            mm(long),
            mm(h)
        );
        (section, h.abs(), body(shape))
    } else {
        (
            Opening::Point,
            h.abs(),
            Some(format!(
                "the luminous opening (width {width} m, length {length} m, height {height} m) is not one invlight models: it emits from its centre"
            )),
        )
    }
}

/// The file name of `path`, for reports.
pub(super) fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}
