//! The one error type of every file invlight reads (scene files, problem files, later
//! photometric files): it names the file, the place in it and what was expected, and may
//! carry a hint, so a user can fix the file without reading our code (ripgrep's
//! `WithPath`/`WithLineNumber`, pbrt-v4's `file:line:col`). Warnings have the same shape.

use std::fmt;
use std::path::{Path, PathBuf};

/// A message about a file: an error, or a warning the reader carries along.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// The file at fault.
    pub path: PathBuf,
    /// 1-based line, when the message is about a line of a text file.
    pub line: Option<u32>,
    /// Where in the file otherwise: `<node id="Cube">`, `nodes[3]`, `light 'Sun'`; empty
    /// when the line says it or the whole file is at fault (unreadable, unknown format).
    pub location: String,
    /// What is wrong, phrased as what was expected.
    pub message: String,
    /// How to fix it, when we can tell.
    pub hint: Option<String>,
}

/// A scene file could not be read or understood.
pub type LoadError = Diagnostic;

impl Diagnostic {
    /// A message about the whole file.
    pub fn new(path: &Path, message: impl Into<String>) -> Self {
        Diagnostic {
            path: path.to_path_buf(),
            line: None,
            location: String::new(),
            message: message.into(),
            hint: None,
        }
    }

    /// A message about a place in the file (an element, a JSON path, a named thing).
    pub fn at(path: &Path, location: impl Into<String>, message: impl Into<String>) -> Self {
        Diagnostic {
            location: location.into(),
            ..Diagnostic::new(path, message)
        }
    }

    /// A message about line `line` of a text file.
    pub fn at_line(path: &Path, line: u32, message: impl Into<String>) -> Self {
        Diagnostic {
            line: Some(line),
            ..Diagnostic::new(path, message)
        }
    }

    /// Adds a hint on how to fix the file.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if !self.location.is_empty() {
            write!(f, ": {}", self.location)?;
        }
        write!(f, ": {}", self.message)?;
        if let Some(hint) = &self.hint {
            write!(f, "\n  hint: {hint}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostic {}

/// A light could not be given a photometric file ([`crate::Scene::set_photometry`]).
#[derive(Debug, Clone, PartialEq)]
pub enum PhotometryError {
    /// No light has that name.
    NoSuchLight {
        /// The name asked for.
        name: String,
        /// The lights the scene has.
        lights: Vec<String>,
    },
    /// The light is directional: a photometric file describes a luminaire at a point.
    NotAtAPoint {
        /// The light's name.
        name: String,
    },
    /// The multiplier is negative or not finite.
    BadMultiplier {
        /// What was given.
        multiplier: f32,
    },
}

impl fmt::Display for PhotometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PhotometryError::NoSuchLight { name, lights } if lights.is_empty() => {
                write!(
                    f,
                    "no light named '{name}': the scene has no point, spot or directional light"
                )
            }
            PhotometryError::NoSuchLight { name, lights } => write!(
                f,
                "no light named '{name}'; the scene's lights are {}",
                lights.join(", ")
            ),
            PhotometryError::NotAtAPoint { name } => write!(
                f,
                "'{name}' is a directional light; a photometric file replaces a point or spot light"
            ),
            PhotometryError::BadMultiplier { multiplier } => {
                write!(f, "the multiplier {multiplier} must be a finite number ≥ 0")
            }
        }
    }
}

impl std::error::Error for PhotometryError {}
