//! The one error type of every loader: it names the file, the place in it and what was
//! expected, and may carry a hint, so a user can fix the file without reading our code
//! (ripgrep's `WithPath`/`WithLineNumber`, pbrt-v4's `file:line:col`).

use std::fmt;
use std::path::{Path, PathBuf};

/// A scene file could not be read or understood.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadError {
    /// The file at fault.
    pub path: PathBuf,
    /// Where in the file: `line 12`, `<node id="Cube">`, `nodes[3]`; empty when the
    /// whole file is at fault (unreadable, unknown format).
    pub location: String,
    /// What is wrong, phrased as what was expected.
    pub message: String,
    /// How to fix it, when we can tell.
    pub hint: Option<String>,
}

impl LoadError {
    /// An error about the whole file.
    pub fn new(path: &Path, message: impl Into<String>) -> Self {
        LoadError {
            path: path.to_path_buf(),
            location: String::new(),
            message: message.into(),
            hint: None,
        }
    }

    /// An error at a place in the file (a line, an element, a JSON path).
    pub fn at(path: &Path, location: impl Into<String>, message: impl Into<String>) -> Self {
        LoadError {
            location: location.into(),
            ..LoadError::new(path, message)
        }
    }

    /// Adds a hint on how to fix the file.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
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

impl std::error::Error for LoadError {}

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
