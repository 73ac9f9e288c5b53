//! EULUMDAT files (`.ldt`; the format of A. Stockmar, "EULUMDAT/2", LiTG 1990, which
//! DIALux and Relux exchange): one field per line, decimals with a point or a comma.
//!
//! Lines: 1 company, 2 type indicator Ityp, 3 symmetry indicator Isym (0 none, 1 about
//! the vertical axis, 2 about the C0–C180 plane, 3 about the C90–C270 plane, 4 about
//! both), 4 number of C-planes Mc, 5 their spacing Dc, 6 number of γ angles Ng, 7
//! their spacing Dg, 8 report number, 9 luminaire name, 10 luminaire number, 11 file
//! name, 12 date/user, 13–15 luminaire length (or diameter), width (0: round), height
//! in mm, 16–17 luminous area length (or diameter) and width (0: round) in mm — the
//! lengths along C90–C270, the widths along C0–C180 ([`luminous_area`]), 18–21
//! luminous area heights at C0, C90, C180, C270, 22 downward flux fraction %, 23 light
//! output ratio %, 24 conversion factor of the intensities, 25 tilt during measurement,
//! 26 number n of lamp sets, then per set: number of lamps, lamp type, total luminous
//! flux of the lamps (lm), colour temperature, colour rendering, wattage including
//! ballast (W); then 10 direct ratios, the Mc C angles, the Ng γ angles, and the
//! intensities in cd per 1000 lm of lamp flux, plane by plane, for the planes Isym
//! leaves: all Mc (Isym 0), one (1), Mc/2 + 1 from C0 (2), Mc/2 + 1 from C90 (3),
//! Mc/4 + 1 from C0 (4).
//!
//! The candela table is the intensities × conversion factor × the first lamp set's
//! total flux / 1000 (the first set is the one measured; its flux is the total of its
//! lamps, so the number of lamps is not multiplied in again); its stated flux is that
//! lamp flux × the light output ratio. A blank line where a number stands reads as 0, as
//! exporters leave fields they do not fill (the tilt, the direct ratios) empty.

use super::ies::file_name;
use super::symmetry::{Symmetry, expand_c};
use super::text::{Numbers, increasing, latin1};
use super::{Opening, PhotometricSystem, Photometry, PhotometryFormat, Table};
use crate::error::LoadError;
use std::path::Path;

const FORMAT_HINT: &str =
    "the file does not follow EULUMDAT: export it again from the manufacturer's tool";

/// Reads a EULUMDAT file's bytes; `path` names it in errors.
pub fn parse_ldt(bytes: &[u8], path: &Path) -> Result<Photometry, LoadError> {
    let text = latin1(bytes).replace("\r\n", "\n").replace('\r', "\n");
    let owned: Vec<String> = text.lines().map(|l| l.trim().replace(',', ".")).collect();
    let lines: Vec<&str> = owned.iter().map(String::as_str).collect();
    let mut r = Lines {
        path,
        lines: &lines,
        next: 0,
    };
    let mut header = Header::read(&mut r)?;
    let lamps = Lamps::read(&mut r, &mut header.keywords)?;
    for k in 0..10 {
        r.number(&format!("direct ratio {} of 10", k + 1))?;
    }

    // Angles and intensities, however the lines are broken.
    let first = r.next + 1;
    let mut numbers = Numbers::new(path, &lines[r.next..], first);
    let angles = Angles::read(&r, &mut numbers, &header)?;
    let (symmetry, planes) = angles.measured_planes(&r, &header)?;
    let i_line = numbers.line();
    let raw = numbers.list(planes.len() * header.ng, "an intensity (cd/klm)")?;
    if let Some(k) = raw.iter().position(|&c| c < 0.0) {
        return Err(r.err_at(
            i_line,
            format!("intensity {} is {}; intensities are ≥ 0", k + 1, raw[k]),
        ));
    }
    let mut warnings = Vec::new();
    if numbers.rest() > 0 {
        warnings.push(format!(
            "{} numbers follow the {} intensities that Isym {} and Mc = {} call for, and were ignored",
            numbers.rest(),
            raw.len(),
            header.isym,
            header.mc
        ));
    }
    let h_full = expand_c(planes, symmetry).map_err(|e| {
        r.err_at(angles.c_line, e.to_string())
            .with_hint(FORMAT_HINT)
    })?;
    let scale = header.conversion * lamps.flux / 1000.0;
    let ng = header.ng;
    let raw = &raw;
    let candela: Vec<f64> = h_full
        .iter()
        .flat_map(|&(_, i)| (0..ng).map(move |j| raw[i * ng + j] * scale))
        .collect();
    let table = Table::new(
        PhotometricSystem::C,
        h_full.iter().map(|p| p.0).collect(),
        angles.gammas,
        candela,
    )
    .map_err(|e| {
        r.err_at(i_line, e.to_string())
            .with_hint(format!("checked against Isym on line {}", header.isym_line))
    })?;
    let (opening, shape) = luminous_area(header.length as f32, header.width as f32);
    warnings.extend(shape);
    let mut p = Photometry {
        file: file_name(path),
        source: None,
        format: PhotometryFormat::Eulumdat,
        keywords: header.keywords,
        lamps: lamps.count,
        lumens_per_lamp: (lamps.count > 0).then(|| lamps.flux / lamps.count as f64),
        stated_flux: Some(lamps.flux * header.lor),
        light_output_ratio: Some(header.lor),
        watts: (lamps.watts > 0.0).then_some(lamps.watts),
        ballast_factor: 1.0,
        opening,
        opening_height: header.heights.iter().copied().fold(0.0, f64::max) as f32,
        luminaire: Some((header.luminaire, header.luminaire_height))
            .filter(|(o, _)| *o != Opening::Point),
        tilt: None,
        warnings,
        table,
    };
    p.check_flux();
    Ok(p)
}

/// The header's fields before the lamp sets (lines 1–25): the text fields as keywords,
/// the table's layout, the luminaire's and its luminous area's dimensions in metres,
/// the light output ratio and the conversion factor.
struct Header {
    keywords: Vec<(String, String)>,
    /// The symmetry indicator Isym and its line, which a table that does not add up
    /// is checked against.
    isym: i64,
    isym_line: usize,
    /// The number of C-planes Mc and of γ angles Ng.
    mc: usize,
    ng: usize,
    /// The luminaire's outline and height.
    luminaire: Opening,
    luminaire_height: f32,
    /// The luminous area's length (or diameter) and width.
    length: f64,
    width: f64,
    /// The luminous area's heights at C0, C90, C180 and C270.
    heights: [f64; 4],
    /// The light output ratio, a fraction.
    lor: f64,
    conversion: f64,
}

impl Header {
    /// Reads lines 1–25, refusing a light output ratio outside 0–100 %.
    fn read(r: &mut Lines<'_>) -> Result<Header, LoadError> {
        let mut keywords = Vec::new();
        keywords.push(("Company".to_string(), r.text()?.to_string()));
        let ityp = r.int("the type indicator Ityp", 0, 3)?;
        keywords.push(("Ityp".into(), ityp.to_string()));
        let isym_line = r.next + 1;
        let isym = r.int("the symmetry indicator Isym", 0, 4)?;
        let mc = r.int("the number of C-planes Mc", 1, 100_000)? as usize;
        r.number("the distance between C-planes Dc")?;
        let ng = r.int("the number of γ angles Ng", 2, 100_000)? as usize;
        r.number("the distance between γ angles Dg")?;
        for key in [
            "ReportNumber",
            "Luminaire",
            "LuminaireNumber",
            "FileName",
            "DateUser",
        ] {
            keywords.push((key.to_string(), r.text()?.to_string()));
        }
        let [l, w, h] = [
            r.number("the luminaire length or diameter (mm)")?,
            r.number("the luminaire width (mm)")?,
            r.number("the luminaire height (mm)")?,
        ]
        .map(|mm| (mm * 1e-3) as f32);
        // The luminaire's outline lies as its luminous area does.
        let luminaire = luminous_area(l, w).0;
        let length = r.number("the luminous area length or diameter (mm)")? * 1e-3;
        let width = r.number("the luminous area width (mm)")? * 1e-3;
        let mut heights = [0.0f64; 4];
        for (h, plane) in heights.iter_mut().zip(["C0", "C90", "C180", "C270"]) {
            *h = r.number(&format!("the luminous area height at {plane} (mm)"))? * 1e-3;
        }
        r.number("the downward flux fraction (%)")?;
        let lor_line = r.next + 1;
        let lor = r.number("the light output ratio (%)")? / 100.0;
        if !(0.0..=1.0).contains(&lor) {
            return Err(r.err_at(
                lor_line,
                format!(
                    "the light output ratio is {}%; 0 to 100 % was expected",
                    lor * 100.0
                ),
            ));
        }
        let conversion = r.number("the conversion factor of the intensities")?;
        r.number("the tilt during measurement")?;
        Ok(Header {
            keywords,
            isym,
            isym_line,
            mc,
            ng,
            luminaire,
            luminaire_height: h,
            length,
            width,
            heights,
            lor,
            conversion,
        })
    }
}

/// The first lamp set, the one the intensities were measured with.
struct Lamps {
    count: u32,
    /// The total luminous flux of its lamps, lm.
    flux: f64,
    watts: f64,
}

impl Lamps {
    /// Reads the number of lamp sets (line 26) and every set, keeping the first; its
    /// type, colour temperature and colour rendering go to `keywords`. Its flux must be
    /// positive, since the intensities are per 1000 lm of it.
    fn read(r: &mut Lines<'_>, keywords: &mut Vec<(String, String)>) -> Result<Lamps, LoadError> {
        let sets = r.int("the number of lamp sets", 1, 100)? as usize;
        let mut first = Lamps {
            count: 0,
            flux: 0.0,
            watts: 0.0,
        };
        for s in 0..sets {
            let n = r.int("the number of lamps", -100_000, 100_000)?;
            let kind = r.text()?.to_string();
            let flux_line = r.next + 1;
            let flux = r.number("the total luminous flux of the lamps (lm)")?;
            let cct = r.text()?.to_string();
            let cri = r.text()?.to_string();
            let w = r.number("the wattage including ballast (W)")?;
            if s == 0 {
                if flux <= 0.0 {
                    return Err(r.err_at(
                        flux_line,
                        format!("the lamps' flux is {flux} lm; a positive flux was expected"),
                    ));
                }
                first = Lamps {
                    count: n.unsigned_abs() as u32,
                    flux,
                    watts: w,
                };
                keywords.push(("LampType".into(), kind));
                keywords.push(("ColourTemperature".into(), cct));
                keywords.push(("ColourRendering".into(), cri));
            }
        }
        Ok(first)
    }
}

/// The C angles and γ angles as listed, with the line the C angles start on.
struct Angles {
    c_angles: Vec<f64>,
    c_line: usize,
    gammas: Vec<f64>,
}

impl Angles {
    /// Reads the Mc C angles and the Ng γ angles, each list increasing and the γ
    /// angles within 0°–180°.
    fn read(
        r: &Lines<'_>,
        numbers: &mut Numbers<'_>,
        header: &Header,
    ) -> Result<Angles, LoadError> {
        let path = r.path;
        let c_line = numbers.line();
        let c_angles = numbers.list(header.mc, "a C angle")?;
        increasing(path, c_line, &c_angles, "C angle")?;
        let g_line = numbers.line();
        let gammas = numbers.list(header.ng, "a γ angle")?;
        increasing(path, g_line, &gammas, "γ angle")?;
        let last = gammas[header.ng - 1];
        if gammas[0] < 0.0 || last > 180.0 {
            return Err(r.err_at(
                g_line,
                format!(
                    "γ angles from {}° to {last}°; they lie within 0° and 180°",
                    gammas[0]
                ),
            ));
        }
        Ok(Angles {
            c_angles,
            c_line,
            gammas,
        })
    }

    /// The symmetry Isym declares and the C-planes it leaves measured, which must run
    /// over the range the symmetry mirrors (C0–C180, C90–C270 or C0–C90): a file whose
    /// Mc angles do not is refused rather than mirrored wrongly.
    fn measured_planes(
        &self,
        r: &Lines<'_>,
        header: &Header,
    ) -> Result<(Symmetry, &[f64]), LoadError> {
        let (isym, mc, c_angles) = (header.isym, header.mc, &self.c_angles);
        let (symmetry, planes): (Symmetry, &[f64]) = match isym {
            0 => (Symmetry::None, c_angles),
            1 => (Symmetry::Rotational, &c_angles[..1]),
            2 => (Symmetry::AboutC0, &c_angles[..(mc / 2 + 1).min(mc)]),
            3 => (
                Symmetry::AboutC90,
                &c_angles[(mc / 4).min(mc - 1)..(3 * mc / 4 + 1).min(mc)],
            ),
            _ => (Symmetry::Quadrant, &c_angles[..(mc / 4 + 1).min(mc)]),
        };
        let expected_range = match symmetry {
            Symmetry::AboutC0 => Some((0.0, 180.0)),
            Symmetry::AboutC90 => Some((90.0, 270.0)),
            Symmetry::Quadrant => Some((0.0, 90.0)),
            _ => None,
        };
        if let Some((lo, hi)) = expected_range {
            let (a, b) = (planes[0], planes[planes.len() - 1]);
            if (a - lo).abs() > 1e-6 || (b - hi).abs() > 1e-6 {
                return Err(r
                    .err_at(self.c_line, format!("Isym {isym} needs the C-planes from {lo}° to {hi}° among the Mc = {mc} angles, which give {a}° to {b}°"))
                    .with_hint(FORMAT_HINT));
            }
        }
        Ok((symmetry, planes))
    }
}

/// The header's lines, one field each.
struct Lines<'a> {
    path: &'a Path,
    lines: &'a [&'a str],
    next: usize,
}

impl Lines<'_> {
    fn err_at(&self, line: usize, message: String) -> LoadError {
        LoadError::at(self.path, format!("line {line}"), message)
    }

    fn text(&mut self) -> Result<&str, LoadError> {
        let Some(line) = self.lines.get(self.next) else {
            return Err(LoadError::at(
                self.path,
                format!("line {}", self.next + 1),
                "the file ends inside its header",
            )
            .with_hint(FORMAT_HINT));
        };
        self.next += 1;
        Ok(line)
    }

    fn number(&mut self, what: &str) -> Result<f64, LoadError> {
        let line = self.next + 1;
        let t = self.text()?.to_string();
        match t.split_whitespace().next().map(str::parse::<f64>) {
            Some(Ok(x)) if x.is_finite() => Ok(x),
            None => Ok(0.0),
            _ => Err(self
                .err_at(line, format!("'{t}' where {what} (a number) was expected"))
                .with_hint(FORMAT_HINT)),
        }
    }

    fn int(&mut self, what: &str, lo: i64, hi: i64) -> Result<i64, LoadError> {
        let line = self.next + 1;
        let x = self.number(what)?;
        if x.fract() != 0.0 || x < lo as f64 || x > hi as f64 {
            return Err(self
                .err_at(
                    line,
                    format!("{what} is {x}; a whole number from {lo} to {hi} was expected"),
                )
                .with_hint(FORMAT_HINT));
        }
        Ok(x as i64)
    }
}

/// The luminous area of an EULUMDAT file from its length (or diameter) and width, m: a
/// disk when the width is 0, else a rectangle whose length lies along C90–C270.
///
/// EULUMDAT's C0–C180 plane is the one across a linear luminaire and C90–C270 the one
/// along it (DIALux's support article on the luminous intensity distribution names the
/// C0/C180 plane transverse to the luminaire axis and C90/C270 along it), the opposite
/// of IES LM-63, which lays the length along 0°–180°. Manufacturers' files agree: a
/// linear luminaire's batwing (across-the-lamp) curve is its C0 plane and its
/// cosine-like (along-the-lamp) curve its C90 plane, and an exit sign that shines toward
/// C0 and C180 can only have its 232 mm length along C90.
fn luminous_area(length: f32, width: f32) -> (Opening, Option<String>) {
    if length == 0.0 && width == 0.0 {
        (Opening::Point, None)
    } else if width == 0.0 && length > 0.0 {
        (Opening::Disk { diameter: length }, None)
    } else if length > 0.0 && width > 0.0 {
        let rectangle = Opening::Rectangle {
            along_c0: width,
            along_c90: length,
        };
        (rectangle, None)
    } else {
        (
            Opening::Point,
            Some(format!(
                "the luminous area (length {length} m, width {width} m) is not a rectangle or a disk: it emits from its centre"
            )),
        )
    }
}
