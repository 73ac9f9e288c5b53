//! Luminaires from manufacturers' files given to a scene's lights by name, whatever the
//! scene's format: `--luminaire NAME=FILE` on the command line and
//! `<luminaire light="NAME" file="lamp.ies" multiplier="1"/>` in a problem file. The
//! named point or spot light becomes the [`LightKind::Goniometric`] light of the file's
//! candela table (IES LM-63 or EULUMDAT), where the light is and aimed as it is
//! ([`Scene::set_photometry`]).
//!
//! The file is read as a scene's references are (files.rs): a regular file, within the
//! memory budget. One named on the command line is read wherever it is, relative to
//! the current folder, as the scene file itself is; one named by a problem file is
//! relative to the problem file and must stay in its folder tree unless
//! `--allow-outside-paths`, since a problem file, like a scene file, may come from
//! anyone. An IES `TILT=<file>` is found beside the IES file, under the same rule.

use crate::error::{Diagnostic, LoadError};
use crate::files::Files;
use crate::light::LightKind;
use crate::load::LoadOptions;
use crate::model::Scene;
use crate::photometry::read_photometry_in;
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Arc;

/// A photometric file to give a named light.
#[derive(Debug, Clone, PartialEq)]
pub struct Luminaire {
    /// The point, spot or goniometric light it describes.
    pub light: String,
    /// The IES (`.ies`) or EULUMDAT (`.ldt`) file, as written.
    pub file: PathBuf,
    /// Factor on the file's candela (> 0).
    pub multiplier: f32,
    /// Degrees it is turned about its aim from the orientation its light gives it (its
    /// node's), C0 toward C90 ([`crate::LightKind::turn_about_aim`]); 0 by default.
    pub rotation: f32,
    /// The problem file and line that asked for it; `None` for the command line.
    pub origin: Option<(PathBuf, u32)>,
}

/// A `--luminaire` value that cannot be read; each variant holds the text given.
#[derive(Debug, Clone, PartialEq)]
pub enum LuminaireArgError {
    /// Not a light's name, `=` and a file.
    NotNameEqualsFile(String),
    /// A multiplier after `*` that is not a number > 0.
    BadMultiplier {
        /// The value as given.
        text: String,
        /// The multiplier read.
        multiplier: f32,
    },
}

impl fmt::Display for LuminaireArgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LuminaireArgError::NotNameEqualsFile(s) => write!(
                f,
                "'{s}' is not NAME=FILE: the light's name (`invlight scene` lists them), '=', and its IES or EULUMDAT file, optionally '*' and a multiplier (NAME=FILE*2)"
            ),
            LuminaireArgError::BadMultiplier { text, multiplier } => write!(
                f,
                "'{text}': the multiplier after '*' is {multiplier}, expected a number > 0 (NAME=FILE*2 doubles the file's candela)"
            ),
        }
    }
}

impl std::error::Error for LuminaireArgError {}

/// `NAME=FILE` or `NAME=FILE*M`, the value of `--luminaire`: the multiplier M (> 0,
/// default 1) as a problem file's `<luminaire multiplier>`, so that a lamp of two
/// tubes, or a file in klm, is given on the command line as in a problem. A `*` not
/// followed by a number is part of the file's name.
impl FromStr for Luminaire {
    type Err = LuminaireArgError;

    fn from_str(s: &str) -> Result<Luminaire, LuminaireArgError> {
        match s.split_once('=') {
            Some((light, file)) if !light.trim().is_empty() && !file.trim().is_empty() => {
                let (file, multiplier) = match file.rsplit_once('*') {
                    Some((f, m)) if m.trim().parse::<f32>().is_ok() => {
                        let m: f32 = m.trim().parse().unwrap_or(f32::NAN);
                        if !(m.is_finite() && m > 0.0) {
                            return Err(LuminaireArgError::BadMultiplier {
                                text: s.to_string(),
                                multiplier: m,
                            });
                        }
                        (f, m)
                    }
                    _ => (file, 1.0),
                };
                Ok(Luminaire {
                    light: light.trim().to_string(),
                    file: PathBuf::from(file.trim()),
                    multiplier,
                    rotation: 0.0,
                    origin: None,
                })
            }
            _ => Err(LuminaireArgError::NotNameEqualsFile(s.to_string())),
        }
    }
}

impl Luminaire {
    /// Where it was asked for, for messages: `--luminaire NAME=FILE`, or the
    /// `<luminaire>` element.
    fn asked(&self) -> String {
        match self.origin {
            None if self.multiplier != 1.0 => format!(
                "--luminaire {}={}*{}",
                self.light,
                self.file.display(),
                self.multiplier
            ),
            None => format!("--luminaire {}={}", self.light, self.file.display()),
            Some(_) => "<luminaire>".into(),
        }
    }

    /// An error about this request: at the problem file's line, or at the scene file
    /// `scene` for a command-line one.
    fn error(&self, scene: &Path, message: String) -> Diagnostic {
        match &self.origin {
            Some((problem, line)) => Diagnostic::at_line(problem, *line, message),
            None => Diagnostic::at(scene, self.asked(), message),
        }
    }

    /// The photometric file read within `options`.
    fn read(&self, scene: &Path, options: &LoadOptions) -> Result<crate::Photometry, LoadError> {
        let (files, path, relative_to) = match &self.origin {
            None => (
                Files::new(&self.file, options),
                self.file.clone(),
                "a --luminaire file is relative to the current folder".to_string(),
            ),
            Some((problem, line)) => {
                let files = Files::new(problem, options);
                let written = self.file.to_string_lossy();
                let path = files
                    .resolve(problem, "<luminaire>", &written, &self.file)
                    .map_err(|e| Diagnostic {
                        line: Some(*line),
                        ..e
                    })?;
                let dir = problem.parent().unwrap_or(Path::new(""));
                let dir = if dir.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    dir
                };
                let hint = format!(
                    "a <luminaire file> is relative to the problem file's folder, {}",
                    dir.display()
                );
                (files, path, hint)
            }
        };
        if !path.exists() {
            return Err(self
                .error(
                    scene,
                    format!("the photometric file {} does not exist", path.display()),
                )
                .with_hint(relative_to));
        }
        let read = read_photometry_in(&path, &files)?;
        Ok(read.read_from(&self.file.to_string_lossy(), &path))
    }
}

impl Scene {
    /// Gives each named light its luminaire's photometry, in order (a later one for the
    /// same light wins), with `options`' folder rule and memory budget; `scene` is the
    /// scene file, named in errors about a command-line request. A light that is not
    /// a point, spot or goniometric light, a missing file or a bad one is an error
    /// naming where it was asked for; the scene is validated again afterwards (a
    /// multiplier can carry a light's flux out of range).
    pub fn set_luminaires(
        &mut self,
        scene: &Path,
        luminaires: &[Luminaire],
        options: &LoadOptions,
    ) -> Result<(), LoadError> {
        for l in luminaires {
            if !(l.multiplier.is_finite() && l.multiplier > 0.0) {
                return Err(l.error(
                    scene,
                    format!(
                        "the multiplier is {}; a positive factor on the file's candela was expected",
                        l.multiplier
                    ),
                ));
            }
            if let Some(light) = self.light(&l.light)
                && matches!(self.lights[light].kind, LightKind::Directional { .. })
            {
                return Err(l.error(
                    scene,
                    format!(
                        "'{}' is a directional light (a sun); a luminaire file describes a point or spot light",
                        l.light
                    ),
                ));
            }
            let photometry = Arc::new(l.read(scene, options)?);
            self.set_photometry(&l.light, photometry, l.multiplier)
                .map_err(|e| {
                    l.error(scene, e.to_string()).with_hint(
                        "name a point or spot light of the scene: `invlight scene` lists them",
                    )
                })?;
            if let Some(light) = self.light(&l.light) {
                self.lights[light].kind.turn_about_aim(l.rotation);
            }
        }
        self.validate()
            .map_err(|e| LoadError::at(scene, e.place(), e.to_string()).with_hint(e.hint()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn name_equals_file() {
        let l: Luminaire = "Lamp 1 = lamps/down light.ies".parse().unwrap();
        assert_eq!(l.light, "Lamp 1");
        assert_eq!(l.file, PathBuf::from("lamps/down light.ies"));
        assert_eq!((l.multiplier, l.origin), (1.0, None));
        for bad in ["Lamp", "=x.ies", "Lamp=", ""] {
            let e = bad.parse::<Luminaire>().unwrap_err().to_string();
            assert!(e.contains("NAME=FILE"), "{e}");
        }
    }

    #[test]
    fn a_multiplier_follows_a_star() {
        let l: Luminaire = "Lamp1=downlight.ldt*2".parse().unwrap();
        assert_eq!(
            (l.file, l.multiplier),
            (PathBuf::from("downlight.ldt"), 2.0)
        );
        assert_eq!(
            "L=a.ies * 0.5".parse::<Luminaire>().unwrap().multiplier,
            0.5
        );
        // A star not followed by a number is the file's.
        let odd: Luminaire = "L=odd*name.ies".parse().unwrap();
        assert_eq!(
            (odd.file, odd.multiplier),
            (PathBuf::from("odd*name.ies"), 1.0)
        );
        for bad in ["L=a.ies*0", "L=a.ies*-2", "L=a.ies*inf", "L=a.ies*NaN"] {
            let e = bad.parse::<Luminaire>().unwrap_err().to_string();
            assert!(e.contains("a number > 0"), "{bad}: {e}");
        }
    }
}
