//! Photometric data of real luminaires: IES LM-63 (`.ies`, module `ies`) and EULUMDAT
//! (`.ldt`, module `ldt`) files read into one [`Photometry`]: the full table of
//! luminous intensities in candela over the sphere after the file's symmetry is
//! expanded and its multipliers applied, with the file's metadata.
//!
//! Coordinates (the luminaire's local frame, as glTF `EXT_lights_ies` maps them,
//! "Coordinate System Mapping"): the photometric zero (both angles 0, where the
//! luminaire is aimed) is local −Z; the photometric horizontal (horizontal angle 0,
//! vertical angle 90°) is local +X, so the X/Z plane is the zero plane and X/Y the
//! horizontal one.
//! - Type C (LM-63-2002 §3 "Horizontal angles": counter-clockwise for type C; EN 13032-1
//!   C-planes): γ from −Z, C about +Z from +X toward +Y, so C0 is +X and C90 is +Y;
//!   d = (sin γ cos C, sin γ sin C, −cos γ), dω = dC·d(1 − cos γ).
//! - Type B (LM-63-2002 §3: planes sharing a horizontal axis; horizontal angles
//!   clockwise): the polar axis is local Y; the vertical angle V turns about it from −Z
//!   toward +X, the horizontal angle H leans out of the zero plane toward −Y;
//!   d = (cos H sin V, −sin H, −cos H cos V), dω = d(sin H)·dV.
//! - Type A is refused: no peer renderer invlight is compared with needs it and
//!   `EXT_lights_ies` makes it optional.
//!
//! Between the measured angles the intensity is bilinear in the two angles, and zero
//! beyond the file's vertical range (a downlight measured to 90° sends nothing upward).
//! [`Photometry::flux`] integrates that interpolation exactly, cell by cell, and the
//! same cell integrals are the masses of the [`PiecewiseConstant2D`] photons are drawn
//! from ([`Photometry::sample`]).
//!
//! The readers are written here: the `eulumdat` crate is AGPL, which this MIT project
//! cannot take, and `lidrs` (MIT) reports errors without the line and reads neither
//! LM-63-1986 nor tilt data.

mod facts;
mod ies;
mod ldt;
mod symmetry;
mod table_error;
mod text;

use crate::error::LoadError;
use crate::files::Files;
use crate::load::LoadOptions;
use glam::{Vec2, Vec3};
use invlight_stats::PiecewiseConstant2D;
use std::path::{Path, PathBuf};

pub use facts::LuminaireFacts;
pub use ies::parse_ies;
pub(crate) use ies::parse_ies_in;
pub use ldt::parse_ldt;
pub use table_error::TableError;

/// Which file format, and which version of it, a photometry was read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhotometryFormat {
    /// IES LM-63-1986: no header line.
    Lm63_1986,
    /// IES LM-63-1991 (`IESNA91`).
    Lm63_1991,
    /// IES LM-63-1995 (`IESNA:LM-63-1995`).
    Lm63_1995,
    /// ANSI/IESNA LM-63-2002 (`IESNA:LM-63-2002`).
    Lm63_2002,
    /// ANSI/IES LM-63-2019 (`IES:LM-63-2019`).
    Lm63_2019,
    /// EULUMDAT (`.ldt`).
    Eulumdat,
    /// A table built in code ([`Photometry::from_table`]).
    Table,
}

impl PhotometryFormat {
    /// The format's usual name.
    pub fn name(self) -> &'static str {
        match self {
            PhotometryFormat::Lm63_1986 => "IES LM-63-1986",
            PhotometryFormat::Lm63_1991 => "IES LM-63-1991",
            PhotometryFormat::Lm63_1995 => "IES LM-63-1995",
            PhotometryFormat::Lm63_2002 => "IES LM-63-2002",
            PhotometryFormat::Lm63_2019 => "IES LM-63-2019",
            PhotometryFormat::Eulumdat => "EULUMDAT",
            PhotometryFormat::Table => "table",
        }
    }
}

/// The goniometric coordinate system of a table (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhotometricSystem {
    /// C-planes about the vertical axis, γ from nadir.
    C,
    /// B-planes about the horizontal axis (floodlights).
    B,
}

/// The luminous opening a luminaire emits from, in metres, lying in the local X/Y plane
/// and facing the photometric zero (−Z). Its sides are named by the C-planes they lie
/// in, not "length" and "width": the two formats lay a luminaire's length along
/// different planes (IES LM-63 along C0–C180, EULUMDAT along C90–C270; the readers'
/// docs give the sources).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Opening {
    /// A point source (dimensions zero).
    Point,
    /// A rectangle `along_c0` × `along_c90`.
    Rectangle {
        /// Its side along C0–C180 (local X), m.
        along_c0: f32,
        /// Its side along C90–C270 (local Y), m.
        along_c90: f32,
    },
    /// A disk of `diameter` m.
    Disk {
        /// Diameter, m.
        diameter: f32,
    },
    /// An ellipse with axes `along_c0` and `along_c90` (LM-63-2019's elliptical
    /// opening).
    Ellipse {
        /// Its axis along C0–C180 (local X), m.
        along_c0: f32,
        /// Its axis along C90–C270 (local Y), m.
        along_c90: f32,
    },
}

impl Opening {
    /// A point of the opening in local coordinates (z = 0) for two uniform numbers,
    /// uniform by area: the centre for a point source.
    #[inline]
    pub fn point(&self, u1: f32, u2: f32) -> Vec3 {
        let ellipse = |a: f32, b: f32| {
            let r = 0.5 * u1.sqrt();
            let phi = std::f32::consts::TAU * u2;
            Vec3::new(a * r * phi.cos(), b * r * phi.sin(), 0.0)
        };
        match *self {
            Opening::Point => Vec3::ZERO,
            Opening::Rectangle {
                along_c0,
                along_c90,
            } => Vec3::new((u1 - 0.5) * along_c0, (u2 - 0.5) * along_c90, 0.0),
            Opening::Disk { diameter } => ellipse(diameter, diameter),
            Opening::Ellipse {
                along_c0,
                along_c90,
            } => ellipse(along_c0, along_c90),
        }
    }

    /// Area, m² (0 for a point).
    pub fn area(&self) -> f32 {
        use std::f32::consts::FRAC_PI_4;
        match *self {
            Opening::Point => 0.0,
            Opening::Rectangle {
                along_c0,
                along_c90,
            } => along_c0 * along_c90,
            Opening::Disk { diameter } => FRAC_PI_4 * diameter * diameter,
            Opening::Ellipse {
                along_c0,
                along_c90,
            } => FRAC_PI_4 * along_c0 * along_c90,
        }
    }

    /// Its extents along local X (C0–C180) and local Y (C90–C270), m; zeros for a
    /// point.
    pub fn extents(&self) -> [f32; 2] {
        match *self {
            Opening::Point => [0.0; 2],
            Opening::Rectangle {
                along_c0,
                along_c90,
            }
            | Opening::Ellipse {
                along_c0,
                along_c90,
            } => [along_c0, along_c90],
            Opening::Disk { diameter } => [diameter; 2],
        }
    }

    /// The opening in words, in mm, with the axis its length (the longer side) lies
    /// along, named by `axis` from 0 (local X, C0–C180) or 1 (local Y, C90–C270):
    /// "1500 × 60 mm, length along C90–C270".
    pub fn words(&self, axis: impl Fn(usize) -> String) -> String {
        let mm = |m: f32| format!("{:.0}", 1000.0 * m);
        let sides = |[a, b]: [f32; 2]| {
            let (long, short, k) = if b > a { (b, a, 1) } else { (a, b, 0) };
            let size = format!("{} × {} mm", mm(long), mm(short));
            if mm(long) == mm(short) {
                size
            } else {
                format!("{size}, length along {}", axis(k))
            }
        };
        match *self {
            Opening::Point => "a point (no luminous dimensions)".to_string(),
            Opening::Rectangle { .. } => sides(self.extents()),
            Opening::Ellipse { .. } => format!("an ellipse {}", sides(self.extents())),
            Opening::Disk { diameter } => format!("a disk Ø {} mm", mm(diameter)),
        }
    }
}

/// IES tilt data (LM-63-2002 §5.4, `TILT=INCLUDE` or `TILT=<file>`): how the candela
/// values scale with the lamp's tilt away from the orientation it was measured in.
#[derive(Debug, Clone, PartialEq)]
pub struct Tilt {
    /// Lamp-to-luminaire geometry: 1 vertical base-up or base-down lamp, 2 horizontal
    /// lamp along C0–C180 tilted in that plane, 3 horizontal lamp along C90–C270.
    pub geometry: u8,
    /// Tilt angles, degrees, increasing.
    pub angles: Vec<f64>,
    /// Multiplying factors at `angles`.
    pub factors: Vec<f64>,
}

impl Tilt {
    /// The factor at `angle` degrees, linear between the listed angles and held at the
    /// ends (LM-63-2002 §5.4 lists the factors at the angles the lamp may take).
    pub fn factor(&self, angle: f64) -> f64 {
        let n = self.angles.len();
        if n == 0 {
            return 1.0;
        }
        if angle <= self.angles[0] {
            return self.factors[0];
        }
        if angle >= self.angles[n - 1] {
            return self.factors[n - 1];
        }
        let k = self.angles.partition_point(|&a| a <= angle).clamp(1, n - 1);
        let (a0, a1) = (self.angles[k - 1], self.angles[k]);
        let t = (angle - a0) / (a1 - a0);
        self.factors[k - 1] * (1.0 - t) + self.factors[k] * t
    }
}

/// Where a photometric file came from.
#[derive(Debug, Clone, PartialEq)]
pub struct PhotometrySource {
    /// The path as written: on the command line, in a problem file's `<luminaire file>`
    /// or a glTF's `EXT_lights_ies` `uri`.
    pub given: String,
    /// The file read, canonical (absolute, links followed) so that the same file named
    /// from another folder is recognised as the same.
    pub path: PathBuf,
}

/// A photometric file read: its intensity table over the whole sphere, in candela after
/// every multiplier the file gives, and what it says about the luminaire.
#[derive(Debug, Clone, PartialEq)]
pub struct Photometry {
    /// The file's name (no folder), for reports.
    pub file: String,
    /// The file as it was asked for and where that was found, when it was read from a
    /// file of its own (not a table given in code, nor a profile inside a glTF): a run
    /// records both, since two files of one name in two folders are two lamps.
    pub source: Option<PhotometrySource>,
    /// What it was read from.
    pub format: PhotometryFormat,
    /// Its keywords in file order: IES `[MANUFAC]`, `[LUMCAT]`… (`[MORE]` joined to the
    /// keyword before), IES-1986 text lines under `TEXT`, EULUMDAT header lines under
    /// their field names (`Company`, `Luminaire`…).
    pub keywords: Vec<(String, String)>,
    /// Number of lamps.
    pub lamps: u32,
    /// Rated flux of each lamp, lm; `None` for absolute photometry (IES lumens −1).
    pub lumens_per_lamp: Option<f64>,
    /// The luminaire's flux the file states, lm, when it states one: EULUMDAT's lamp
    /// flux × light output ratio. An IES file states only its lamps' flux.
    pub stated_flux: Option<f64>,
    /// EULUMDAT light output ratio, 0..1.
    pub light_output_ratio: Option<f64>,
    /// Electrical input watts (IES input watts; EULUMDAT wattage including ballast).
    pub watts: Option<f64>,
    /// IES ballast factor (already applied to the table).
    pub ballast_factor: f64,
    /// The luminous opening.
    pub opening: Opening,
    /// Height of the luminous opening, m: its luminous sides, or a body's height (a
    /// cylinder's, a sphere's); light is emitted from the flat opening, the height
    /// counts in its projected area (its luminance, for glare).
    pub opening_height: f32,
    /// The luminaire's outline in the local X/Y plane (a rectangle, or a disk for a
    /// round one) and its height, m, when the file gives them (EULUMDAT; an IES file
    /// gives only its luminous opening).
    pub luminaire: Option<(Opening, f32)>,
    /// IES tilt data; not applied to the table (it depends on how the luminaire is
    /// installed: [`crate::Scene::set_photometry`] applies it).
    pub tilt: Option<Tilt>,
    /// What is doubtful in the file (e.g. its integrated flux against its stated flux),
    /// one sentence each, for the user to see.
    pub warnings: Vec<String>,
    table: Table,
}

/// The expanded table with its sampling distribution.
///
/// Per photon it costs one draw (`Photometry::sample`) and per connection one look-up
/// (`Photometry::pdf_and_weight`): both fuse the cell search with the interpolation and
/// do their trigonometry in f32 (γ to 10⁻⁷ rad). Measured on batwing.ies (16 × 18
/// cells, 20 M calls, 2026-12-01, shared 2-core EPYC): a draw took 80–115 ns with binary
/// searches in the 2D inversion (perf: 35 % of it), 47 ns with its guide tables; a
/// look-up (two brackets, atan2, acos) 43 ns.
#[derive(Debug, Clone, PartialEq)]
struct Table {
    system: PhotometricSystem,
    /// Horizontal angles, degrees, increasing: type C 0..=360, type B within −90..=90.
    horizontal: Vec<f64>,
    /// Vertical angles, degrees, increasing: type C within 0..=180, type B within
    /// −90..=90.
    vertical: Vec<f64>,
    /// `candela[h·nv + v]`, cd.
    candela: Vec<f64>,
    /// The angles in radians, for the per-photon paths.
    h_rad: Vec<f64>,
    v_rad: Vec<f64>,
    /// 1/(x_i+1 − x_i) of `h_rad` and `v_rad`: a photon's fractions across its cell are
    /// products, not quotients.
    inv_dh: Vec<f64>,
    inv_dv: Vec<f64>,
    /// 1/Φ.
    inv_flux: f64,
    /// Over the sampling coordinates (x, y) of the cells, dω = dx·dy, with the cells'
    /// fluxes as masses; its total is the flux.
    dist: PiecewiseConstant2D,
}

/// A direction drawn from a photometry's table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionSample {
    /// Unit direction in the luminaire's local frame.
    pub dir: Vec3,
    /// Its density per steradian.
    pub pdf: f32,
    /// I(dir) / (Φ·pdf): what a photon drawn here carries relative to the table's mean,
    /// 1 where the piecewise-constant density matches the bilinear intensity.
    pub weight: f32,
}

impl Photometry {
    /// A photometry from a table already expanded over the sphere (type C: horizontal
    /// 0..=360; type B: −90..=90), `candela[h·nv + v]` in cd, with no metadata.
    /// Errors name what is wrong with the table.
    pub fn from_table(
        system: PhotometricSystem,
        horizontal: Vec<f64>,
        vertical: Vec<f64>,
        candela: Vec<f64>,
    ) -> Result<Photometry, TableError> {
        Ok(Photometry {
            file: String::new(),
            source: None,
            format: PhotometryFormat::Table,
            keywords: Vec::new(),
            lamps: 1,
            lumens_per_lamp: None,
            stated_flux: None,
            light_output_ratio: None,
            watts: None,
            ballast_factor: 1.0,
            opening: Opening::Point,
            opening_height: 0.0,
            luminaire: None,
            tilt: None,
            warnings: Vec::new(),
            table: Table::new(system, horizontal, vertical, candela)?,
        })
    }

    /// The coordinate system of the table.
    pub fn system(&self) -> PhotometricSystem {
        self.table.system
    }

    /// Horizontal angles of the expanded table, degrees.
    pub fn horizontal(&self) -> &[f64] {
        &self.table.horizontal
    }

    /// Vertical angles of the table, degrees.
    pub fn vertical(&self) -> &[f64] {
        &self.table.vertical
    }

    /// The expanded table, `candela()[h·nv + v]`, cd.
    pub fn candela(&self) -> &[f64] {
        &self.table.candela
    }

    /// The largest intensity of the table, cd.
    pub fn max_intensity(&self) -> f64 {
        self.table.candela.iter().copied().fold(0.0, f64::max)
    }

    /// The keyword `key` (e.g. `MANUFAC`, `LUMCAT`), when the file has it.
    pub fn keyword(&self, key: &str) -> Option<&str> {
        self.keywords
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The luminous intensity at horizontal angle `h` and vertical angle `v` (degrees),
    /// cd: bilinear between the table's angles, 0 outside its vertical range.
    pub fn intensity(&self, h: f64, v: f64) -> f64 {
        self.table.intensity(h, v)
    }

    /// The luminous intensity toward the unit direction `dir` of the luminaire's local
    /// frame, cd.
    #[inline]
    pub fn intensity_toward(&self, dir: Vec3) -> f64 {
        let (h, v) = self.table.angles(dir);
        self.table.intensity(h, v)
    }

    /// The luminous flux of the table, lm: the exact integral over the sphere of its
    /// bilinear interpolation (cell by cell, see `Table::cell_flux`).
    pub fn flux(&self) -> f64 {
        self.table.dist.total()
    }

    /// The unit local direction of the angles (`h`, `v`) in degrees.
    pub fn direction(&self, h: f64, v: f64) -> Vec3 {
        self.table.direction(h.to_radians(), v.to_radians())
    }

    /// Draws a direction from the table's piecewise-constant density (each cell's share
    /// of the flux, uniform in solid angle inside the cell), with its density and the
    /// weight I/(Φ·p) that makes a photon drawn there carry the bilinear intensity.
    #[inline]
    pub fn sample(&self, u1: f32, u2: f32) -> DirectionSample {
        let t = &self.table;
        let s = t.dist.sample([u1 as f64, u2 as f64]);
        let (i, j) = s.cell;
        let (dir, fh, fv) = t.in_cell(i, j, s.x, s.y);
        let intensity = t.blend(i, j, fh, fv);
        DirectionSample {
            dir,
            pdf: s.pdf as f32,
            weight: (intensity * t.inv_flux / s.pdf) as f32,
        }
    }

    /// The density per steradian with which [`Photometry::sample`] draws the local unit
    /// direction `dir`, and the weight I/(Φ·p) there (0 where the density is 0).
    #[inline]
    pub fn pdf_and_weight(&self, dir: Vec3) -> (f32, f32) {
        let t = &self.table;
        let (h, v) = t.angles_rad(dir);
        let (Some((i, fh)), Some((j, fv))) = (bracket(&t.h_rad, h), bracket(&t.v_rad, v)) else {
            return (0.0, 0.0);
        };
        let p = t.dist.cell_pdf(i, j);
        if p <= 0.0 {
            return (0.0, 0.0);
        }
        let w = t.blend(i, j, fh, fv) * t.inv_flux / p;
        (p as f32, w as f32)
    }

    /// Checks the table's flux against the flux the file states and records a warning
    /// when they differ by more than 5 %; for an IES file, when the table sends more
    /// than its lamps give.
    fn check_flux(&mut self) {
        let flux = self.flux();
        if let Some(stated) = self.stated_flux {
            if stated > 0.0 && ((flux - stated) / stated).abs() > 0.05 {
                self.warnings.push(format!(
                    "the table integrates to {flux:.1} lm, the file states {stated:.1} lm ({:+.1} %)",
                    100.0 * (flux - stated) / stated
                ));
            }
        } else if let Some(per_lamp) = self.lumens_per_lamp {
            let lamps = per_lamp * self.lamps as f64;
            if lamps > 0.0 && flux > 1.05 * lamps {
                self.warnings.push(format!(
                    "the table integrates to {flux:.1} lm, more than the {lamps:.1} lm of its lamps ({:+.1} %)",
                    100.0 * (flux - lamps) / lamps
                ));
            }
        }
    }
}

impl Photometry {
    /// This photometry as read from `path`, asked for as `given`.
    pub(crate) fn read_from(self, given: &str, path: &Path) -> Photometry {
        let path = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
        Photometry {
            source: Some(PhotometrySource {
                given: given.to_string(),
                path,
            }),
            ..self
        }
    }
}

/// Reads an IES (`.ies`) or EULUMDAT (`.ldt`) file, by extension; a file with another
/// extension is read as IES when it starts like one (`IES`, or a `TILT=` line), else
/// as EULUMDAT. The file is read as a scene file is (a regular file, within the default
/// memory budget), and an IES `TILT=<file>` from its folder or below.
pub fn read_photometry(path: &Path) -> Result<Photometry, LoadError> {
    let files = Files::new(path, &LoadOptions::default());
    let read = read_photometry_in(path, &files)?;
    Ok(read.read_from(&path.to_string_lossy(), path))
}

/// [`read_photometry`] within the references and budget of `files`.
pub(crate) fn read_photometry_in(path: &Path, files: &Files) -> Result<Photometry, LoadError> {
    let bytes = files
        .read_scene(path)
        .map_err(|e| e.with_hint("give the path of an IES LM-63 (.ies) or EULUMDAT (.ldt) file"))?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    match ext.as_deref() {
        Some("ies") => ies::parse_ies_in(&bytes, path, files),
        Some("ldt") => parse_ldt(&bytes, path),
        _ if text::looks_like_ies(&bytes) => ies::parse_ies_in(&bytes, path, files),
        _ => parse_ldt(&bytes, path),
    }
}

impl Table {
    fn new(
        system: PhotometricSystem,
        horizontal: Vec<f64>,
        vertical: Vec<f64>,
        candela: Vec<f64>,
    ) -> Result<Table, TableError> {
        let (lo_h, hi_h, lo_v, hi_v) = match system {
            PhotometricSystem::C => (0.0, 360.0, 0.0, 180.0),
            PhotometricSystem::B => (-90.0, 90.0, -90.0, 90.0),
        };
        let increasing = |a: &[f64]| a.len() >= 2 && a.windows(2).all(|w| w[1] > w[0]);
        if !increasing(&horizontal)
            || horizontal[0] < lo_h
            || horizontal[horizontal.len() - 1] > hi_h
        {
            return Err(TableError::Horizontal { lo: lo_h, hi: hi_h });
        }
        if !increasing(&vertical) || vertical[0] < lo_v || vertical[vertical.len() - 1] > hi_v {
            return Err(TableError::Vertical { lo: lo_v, hi: hi_v });
        }
        if system == PhotometricSystem::C
            && (horizontal[0] != 0.0 || horizontal[horizontal.len() - 1] != 360.0)
        {
            return Err(TableError::NotFullCircle);
        }
        if candela.len() != horizontal.len() * vertical.len() {
            return Err(TableError::Count {
                values: candela.len(),
                horizontal: horizontal.len(),
                vertical: vertical.len(),
            });
        }
        if let Some(k) = candela.iter().position(|c| !(c.is_finite() && *c >= 0.0)) {
            return Err(TableError::Intensity {
                index: k + 1,
                value: candela[k],
            });
        }
        let nv = vertical.len();
        let h_rad: Vec<f64> = horizontal.iter().map(|h| h.to_radians()).collect();
        let v_rad: Vec<f64> = vertical.iter().map(|v| v.to_radians()).collect();
        let inverse = |a: &[f64]| a.windows(2).map(|w| 1.0 / (w[1] - w[0])).collect();
        let mut t = Table {
            system,
            inv_dh: inverse(&h_rad),
            inv_dv: inverse(&v_rad),
            h_rad,
            v_rad,
            horizontal,
            vertical,
            candela,
            inv_flux: 0.0,
            dist: PiecewiseConstant2D::new(vec![0.0, 1.0], vec![0.0, 1.0], &[1.0])
                .expect("a one-cell grid"),
        };
        let xs: Vec<f64> = t
            .horizontal
            .iter()
            .map(|&h| t.to_xy(h.to_radians(), 0.0).0)
            .collect();
        let ys: Vec<f64> = t
            .vertical
            .iter()
            .map(|&v| t.to_xy(0.0, v.to_radians()).1)
            .collect();
        let mut masses = Vec::with_capacity((xs.len() - 1) * (nv - 1));
        for i in 0..xs.len() - 1 {
            for j in 0..nv - 1 {
                masses.push(t.cell_flux(i, j));
            }
        }
        t.dist = PiecewiseConstant2D::new(xs, ys, &masses).map_err(|e| match e {
            invlight_stats::Distribution2DError::Empty => TableError::Dark,
            e => TableError::Distribution(e),
        })?;
        t.inv_flux = 1.0 / t.dist.total();
        Ok(t)
    }

    /// The sampling coordinates (x, y) of the angles (radians), in which dω = dx·dy.
    #[inline]
    fn to_xy(&self, h: f64, v: f64) -> (f64, f64) {
        match self.system {
            PhotometricSystem::C => (h, 1.0 - v.cos()),
            PhotometricSystem::B => (h.sin(), v),
        }
    }

    /// The unit local direction of sampling coordinates (x, y) inside cell (i, j), with
    /// their fractions across the cell in the two angles (for [`Table::blend`]). Type C
    /// needs one acos (γ, for its fraction) and a sincos (C); type B one asin and a
    /// sincos.
    #[inline]
    fn in_cell(&self, i: usize, j: usize, x: f64, y: f64) -> (Vec3, f64, f64) {
        let (d, h, v) = match self.system {
            PhotometricSystem::C => {
                let cos_g = (1.0 - y as f32).clamp(-1.0, 1.0);
                let sin_g = (1.0 - cos_g * cos_g).max(0.0).sqrt();
                let (sin_c, cos_c) = (x as f32).sin_cos();
                (
                    Vec3::new(sin_g * cos_c, sin_g * sin_c, -cos_g),
                    x,
                    cos_g.acos() as f64,
                )
            }
            PhotometricSystem::B => {
                let sin_h = (x as f32).clamp(-1.0, 1.0);
                let cos_h = (1.0 - sin_h * sin_h).max(0.0).sqrt();
                let (sin_v, cos_v) = (y as f32).sin_cos();
                (
                    Vec3::new(cos_h * sin_v, -sin_h, -cos_h * cos_v),
                    sin_h.asin() as f64,
                    y,
                )
            }
        };
        let fh = ((h - self.h_rad[i]) * self.inv_dh[i]).clamp(0.0, 1.0);
        let fv = ((v - self.v_rad[j]) * self.inv_dv[j]).clamp(0.0, 1.0);
        (d, fh, fv)
    }

    /// The angles (radians) of a unit local direction.
    #[inline]
    fn angles_rad(&self, dir: Vec3) -> (f64, f64) {
        let (x, y, z) = (dir.x as f64, dir.y as f64, dir.z as f64);
        match self.system {
            PhotometricSystem::C => {
                let c = y.atan2(x);
                let c = if c < 0.0 {
                    c + std::f64::consts::TAU
                } else {
                    c
                };
                (c, (-z).clamp(-1.0, 1.0).acos())
            }
            PhotometricSystem::B => ((-y).clamp(-1.0, 1.0).asin(), x.atan2(-z)),
        }
    }

    /// The bilinear intensity inside cell (i, j) at fractions `fh`, `fv` across it.
    #[inline]
    fn blend(&self, i: usize, j: usize, fh: f64, fv: f64) -> f64 {
        let nv = self.vertical.len();
        let c = |a: usize, b: usize| self.candela[a * nv + b];
        (1.0 - fh) * ((1.0 - fv) * c(i, j) + fv * c(i, j + 1))
            + fh * ((1.0 - fv) * c(i + 1, j) + fv * c(i + 1, j + 1))
    }

    /// The unit local direction of the angles (radians).
    #[inline]
    fn direction(&self, h: f64, v: f64) -> Vec3 {
        let d = match self.system {
            PhotometricSystem::C => {
                let s = v.sin();
                [s * h.cos(), s * h.sin(), -v.cos()]
            }
            PhotometricSystem::B => {
                let c = h.cos();
                [c * v.sin(), -h.sin(), -c * v.cos()]
            }
        };
        Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32)
    }

    /// The angles (degrees) of a unit local direction.
    #[inline]
    fn angles(&self, dir: Vec3) -> (f64, f64) {
        let (x, y, z) = (dir.x as f64, dir.y as f64, dir.z as f64);
        match self.system {
            PhotometricSystem::C => {
                let c = y.atan2(x).to_degrees();
                let c = if c < 0.0 { c + 360.0 } else { c };
                let gamma = Vec2::new(dir.x, dir.y).length() as f64;
                (c, gamma.atan2(-z).to_degrees())
            }
            PhotometricSystem::B => {
                let h = (-y).atan2((x * x + z * z).sqrt()).to_degrees();
                (h, x.atan2(-z).to_degrees())
            }
        }
    }

    /// Bilinear intensity at (`h`, `v`) degrees; 0 outside the table.
    #[inline]
    fn intensity(&self, h: f64, v: f64) -> f64 {
        match (bracket(&self.horizontal, h), bracket(&self.vertical, v)) {
            (Some((i, fh)), Some((j, fv))) => self.blend(i, j, fh, fv),
            _ => 0.0,
        }
    }

    /// The flux of cell (i, j), lm: ∫ of the bilinear intensity over the cell's solid
    /// angle. With s, t the cell's fractions in the two angles, a bilinear function
    /// integrates against a Jacobian that depends on one angle alone as the corners'
    /// weights times ∫(1 − s) = ∫ s = Δ/2 along the flat angle and the moments
    /// ∫(1 − t)·J, ∫t·J along the curved one:
    /// - type C, J = sin γ over [γ₀, γ₁]: ∫t sin γ = −cos γ₁ + (sin γ₁ − sin γ₀)/Δγ and
    ///   ∫(1 − t) sin γ = cos γ₀ − (sin γ₁ − sin γ₀)/Δγ;
    /// - type B, J = cos H over [H₀, H₁]: ∫t cos H = sin H₁ + (cos H₁ − cos H₀)/ΔH and
    ///   ∫(1 − t) cos H = −sin H₀ − (cos H₁ − cos H₀)/ΔH.
    fn cell_flux(&self, i: usize, j: usize) -> f64 {
        let nv = self.vertical.len();
        let c = |a: usize, b: usize| self.candela[a * nv + b];
        let (h0, h1) = (
            self.horizontal[i].to_radians(),
            self.horizontal[i + 1].to_radians(),
        );
        let (v0, v1) = (
            self.vertical[j].to_radians(),
            self.vertical[j + 1].to_radians(),
        );
        match self.system {
            PhotometricSystem::C => {
                let d = v1 - v0;
                let ds = (v1.sin() - v0.sin()) / d;
                let (m0, m1) = (v0.cos() - ds, -v1.cos() + ds);
                0.5 * (h1 - h0)
                    * ((c(i, j) + c(i + 1, j)) * m0 + (c(i, j + 1) + c(i + 1, j + 1)) * m1)
            }
            PhotometricSystem::B => {
                let d = h1 - h0;
                let dc = (h1.cos() - h0.cos()) / d;
                let (m0, m1) = (-h0.sin() - dc, h1.sin() + dc);
                0.5 * (v1 - v0)
                    * ((c(i, j) + c(i, j + 1)) * m0 + (c(i + 1, j) + c(i + 1, j + 1)) * m1)
            }
        }
    }
}

/// The interval of increasing `a` holding `x` and the fraction across it, `None`
/// outside `a`'s range.
#[inline]
fn bracket(a: &[f64], x: f64) -> Option<(usize, f64)> {
    let n = a.len();
    if !(x >= a[0] && x <= a[n - 1]) {
        return None;
    }
    let k = a.partition_point(|&b| b <= x).clamp(1, n - 1);
    let t = (x - a[k - 1]) / (a[k] - a[k - 1]);
    Some((k - 1, t.clamp(0.0, 1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// I(γ) = 100·cos γ on γ ∈ [0, 90°] every `step` degrees, rotationally symmetric.
    fn cosine(step: f64) -> Photometry {
        let v: Vec<f64> = (0..=(90.0 / step) as usize)
            .map(|k| k as f64 * step)
            .collect();
        let row: Vec<f64> = v.iter().map(|g| 100.0 * g.to_radians().cos()).collect();
        let candela = [row.clone(), row].concat();
        Photometry::from_table(PhotometricSystem::C, vec![0.0, 360.0], v, candela).unwrap()
    }

    #[test]
    fn flux_is_the_exact_integral_of_the_interpolation() {
        // Linear in γ between two angles: I = 100·γ/(π/2) on [0, π/2], so
        // Φ = 2π·∫ I sin γ dγ = 2π·100/(π/2)·[sin γ − γ cos γ]₀^{π/2} = 400.
        let p = Photometry::from_table(
            PhotometricSystem::C,
            vec![0.0, 360.0],
            vec![0.0, 90.0],
            vec![0.0, 100.0, 0.0, 100.0],
        )
        .unwrap();
        assert!((p.flux() - 400.0).abs() < 1e-9, "{}", p.flux());
        // A cos γ table converges on π·I₀ as its steps shrink (chords under the curve).
        let fine = cosine(0.5).flux();
        assert!((fine - 100.0 * PI).abs() < 1e-4 * 100.0 * PI, "{fine}");
        assert!(cosine(5.0).flux() < fine);
    }

    #[test]
    fn type_b_flux_matches_a_numeric_integral() {
        let h = vec![-90.0, -30.0, 0.0, 45.0, 90.0];
        let v = vec![-90.0, -20.0, 0.0, 10.0, 90.0];
        let candela: Vec<f64> = (0..25).map(|k| ((k * 37) % 11) as f64 * 10.0).collect();
        let p = Photometry::from_table(PhotometricSystem::B, h, v, candela).unwrap();
        // Midpoint rule over the sphere in (cos γ, φ) of the intensity toward each
        // direction: independent of the cell formula and of the angle mapping.
        let n = 1000;
        let mut sum = 0.0;
        for a in 0..n {
            for b in 0..n {
                let z = -1.0 + 2.0 * (a as f64 + 0.5) / n as f64;
                let phi = 2.0 * PI * (b as f64 + 0.5) / n as f64;
                let r = (1.0 - z * z).sqrt();
                let d = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                sum += p.intensity_toward(d);
            }
        }
        let numeric = sum * 4.0 * PI / (n * n) as f64;
        assert!(
            (p.flux() - numeric).abs() < 2e-3 * numeric,
            "{} vs {numeric}",
            p.flux()
        );
    }

    #[test]
    fn directions_and_angles_agree() {
        let c = cosine(10.0);
        assert!((c.direction(0.0, 0.0) - Vec3::NEG_Z).length() < 1e-6);
        assert!((c.direction(0.0, 90.0) - Vec3::X).length() < 1e-6);
        assert!((c.direction(90.0, 90.0) - Vec3::Y).length() < 1e-6);
        let b = Photometry::from_table(
            PhotometricSystem::B,
            vec![-90.0, 90.0],
            vec![-90.0, 90.0],
            vec![1.0; 4],
        )
        .unwrap();
        assert!((b.direction(0.0, 0.0) - Vec3::NEG_Z).length() < 1e-6);
        assert!((b.direction(0.0, 90.0) - Vec3::X).length() < 1e-6);
        assert!((b.direction(90.0, 0.0) - Vec3::NEG_Y).length() < 1e-6);
        for (p, (h, v)) in [
            (&c, (123.0, 37.0)),
            (&c, (300.0, 170.0)),
            (&b, (-40.0, 65.0)),
        ] {
            let (h2, v2) = p.table.angles(p.direction(h, v));
            assert!((h2 - h).abs() < 1e-3 && (v2 - v).abs() < 1e-3, "{h2} {v2}");
        }
    }

    /// For a type C and a type B table: every draw's density and weight are what
    /// `pdf_and_weight` gives at the direction drawn, the mean weight is 1
    /// (E[I/(Φp)] = ∫I dω/Φ), and the weighted mean direction E[r·ω] is the table's
    /// ∫I·ω dω/Φ, integrated over the sphere through `intensity_toward` (the angle
    /// mapping the draws do not use); each within 4 σ of the draws' own spread.
    #[test]
    fn sampling_density_and_weights() {
        let c = Photometry::from_table(
            PhotometricSystem::C,
            vec![0.0, 90.0, 180.0, 270.0, 360.0],
            vec![0.0, 30.0, 90.0, 180.0],
            vec![
                900.0, 10.0, 0.0, 5.0, 50.0, 400.0, 20.0, 0.0, 700.0, 0.0, 0.0, 0.0, 10.0, 10.0,
                10.0, 10.0, 900.0, 10.0, 0.0, 5.0,
            ],
        )
        .unwrap();
        let b = Photometry::from_table(
            PhotometricSystem::B,
            vec![-90.0, -20.0, 0.0, 40.0, 90.0],
            vec![-90.0, -10.0, 30.0, 90.0],
            vec![
                0.0, 5.0, 10.0, 0.0, 50.0, 300.0, 80.0, 5.0, 100.0, 900.0, 200.0, 20.0, 20.0,
                400.0, 600.0, 0.0, 0.0, 0.0, 30.0, 0.0,
            ],
        )
        .unwrap();
        for p in [c, b] {
            let m = 800;
            let mut first = Vec3::ZERO.as_dvec3();
            for a in 0..m {
                for k in 0..m {
                    let z = -1.0 + 2.0 * (a as f64 + 0.5) / m as f64;
                    let phi = 2.0 * PI * (k as f64 + 0.5) / m as f64;
                    let r = (1.0 - z * z).sqrt();
                    let w = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32);
                    first += w.as_dvec3() * p.intensity_toward(w);
                }
            }
            let first = first * (4.0 * PI / (m * m) as f64 / p.flux());
            let mut rng = invlight_stats::SplitMix64::new(3);
            let n = 200_000;
            let (mut s, mut s2) = (0.0f64, 0.0f64);
            let (mut v, mut v2) = (Vec3::ZERO.as_dvec3(), Vec3::ZERO.as_dvec3());
            for _ in 0..n {
                let d = p.sample(rng.next_f64() as f32, rng.next_f64() as f32);
                let (pdf, w) = p.pdf_and_weight(d.dir);
                assert!((pdf - d.pdf).abs() <= 1e-4 * d.pdf, "{pdf} vs {}", d.pdf);
                assert!(
                    (w - d.weight).abs() <= 1e-3 * d.weight.max(1e-3),
                    "{w} vs {}",
                    d.weight
                );
                let (wt, dir) = (d.weight as f64, d.dir.as_dvec3());
                s += wt;
                s2 += wt * wt;
                v += dir * wt;
                v2 += dir * dir * wt * wt;
            }
            let nf = n as f64;
            let mean = s / nf;
            let sigma = ((s2 / nf - mean * mean) / nf).sqrt();
            assert!((mean - 1.0).abs() < 4.0 * sigma, "{mean} ± {sigma}");
            let (mean, sigma) = (v / nf, ((v2 / nf - (v / nf) * (v / nf)) / nf).sqrt());
            // The sphere's midpoint rule adds its own 10⁻³ or so.
            let off = (mean - first).abs();
            assert!(
                off.cmple(sigma * 4.0 + 2e-3).all(),
                "{:?}: E[r·ω] = {mean} ± {sigma}, table {first}",
                p.system()
            );
        }
    }

    #[test]
    fn tilt_factors_interpolate() {
        let t = Tilt {
            geometry: 1,
            angles: vec![0.0, 30.0, 90.0],
            factors: vec![1.0, 0.9, 0.6],
        };
        assert_eq!(t.factor(-5.0), 1.0);
        assert!((t.factor(15.0) - 0.95).abs() < 1e-12);
        assert!((t.factor(60.0) - 0.75).abs() < 1e-12);
        assert_eq!(t.factor(120.0), 0.6);
    }

    #[test]
    fn bad_tables_are_refused() {
        let e = |h: Vec<f64>, v: Vec<f64>, c: Vec<f64>| {
            Photometry::from_table(PhotometricSystem::C, h, v, c)
                .unwrap_err()
                .to_string()
        };
        assert!(e(vec![0.0, 180.0], vec![0.0, 90.0], vec![1.0; 4]).contains("0..360"));
        assert!(e(vec![0.0, 360.0], vec![0.0, 90.0], vec![1.0; 3]).contains("3 candela"));
        assert!(e(vec![0.0, 360.0], vec![0.0, 90.0], vec![1.0, -1.0, 1.0, 1.0]).contains("≥ 0"));
        assert!(e(vec![0.0, 360.0], vec![0.0, 90.0], vec![0.0; 4]).contains("no light"));
    }
}
