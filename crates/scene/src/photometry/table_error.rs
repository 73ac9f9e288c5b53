//! Why a candela table cannot be a [`super::Photometry`]: what
//! [`super::Photometry::from_table`] refuses, and what a file's table is checked
//! against once its symmetry is expanded (the readers put the file and line in front).

use invlight_stats::Distribution2DError;
use std::fmt;

/// A table that is not a luminaire's intensities over the sphere.
#[derive(Debug, Clone, PartialEq)]
pub enum TableError {
    /// Horizontal angles fewer than two, not increasing, or outside `lo..hi` degrees.
    Horizontal {
        /// The smallest angle the system allows.
        lo: f64,
        /// The largest angle the system allows.
        hi: f64,
    },
    /// Vertical angles fewer than two, not increasing, or outside `lo..hi` degrees.
    Vertical {
        /// The smallest angle the system allows.
        lo: f64,
        /// The largest angle the system allows.
        hi: f64,
    },
    /// A type C table whose horizontal angles do not run from 0 to 360°.
    NotFullCircle,
    /// As many candela values as the angles call for were not given.
    Count {
        /// The values given.
        values: usize,
        /// The horizontal angles.
        horizontal: usize,
        /// The vertical angles.
        vertical: usize,
    },
    /// A candela value that is negative or not finite.
    Intensity {
        /// Its 1-based position in the table.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Every intensity is zero.
    Dark,
    /// The cells' fluxes do not make a distribution to draw photons from.
    Distribution(Distribution2DError),
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableError::Horizontal { lo, hi } => write!(
                f,
                "the horizontal angles must be at least two, increasing, within {lo}..{hi}°"
            ),
            TableError::Vertical { lo, hi } => write!(
                f,
                "the vertical angles must be at least two, increasing, within {lo}..{hi}°"
            ),
            TableError::NotFullCircle => {
                f.write_str("a type C table must cover the horizontal angles 0..360°")
            }
            TableError::Count {
                values,
                horizontal,
                vertical,
            } => write!(
                f,
                "{values} candela values for {horizontal} × {vertical} angles"
            ),
            TableError::Intensity { index, value } => write!(
                f,
                "candela value {index} is {value}: intensities are finite and ≥ 0"
            ),
            TableError::Dark => {
                f.write_str("every intensity is zero: the luminaire sends no light")
            }
            TableError::Distribution(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for TableError {}
