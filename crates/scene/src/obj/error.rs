//! What can be wrong with one statement of an OBJ or MTL file. The reader puts the file
//! and the line in front of it ([`crate::LoadError`]), so each message says only what
//! the statement holds and what was expected there.

use std::fmt;

/// A statement that cannot be read. `statement` is its keyword (`v`, `Kd`, …); tokens
/// are as written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum StatementError {
    /// A token where a number stands that is not a finite number.
    NotANumber { token: String },
    /// Fewer numbers than the statement takes.
    TooFewNumbers {
        statement: &'static str,
        needed: usize,
        found: usize,
    },
    /// A `vt` with no coordinate.
    NoTextureCoordinate,
    /// A face corner whose index is not an integer.
    NotAnIndex { what: &'static str, token: String },
    /// A face corner whose index names no element read so far.
    IndexOutOfRange {
        what: &'static str,
        token: String,
        defined: usize,
    },
    /// A face with fewer than three corners.
    TooFewCorners { found: usize },
    /// A colour given in a space other than RGB (`spectral`, `xyz`).
    UnsupportedColour {
        statement: &'static str,
        space: String,
    },
    /// A colour statement with no value.
    NoColour { statement: &'static str },
    /// A colour statement with two values, or more than three.
    ColourCount { statement: &'static str },
}

impl fmt::Display for StatementError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StatementError::NotANumber { token } => {
                write!(f, "expected a number, found '{token}'")
            }
            StatementError::TooFewNumbers {
                statement,
                needed,
                found,
            } => write!(f, "'{statement}' needs {needed} numbers, found {found}"),
            StatementError::NoTextureCoordinate => f.write_str("'vt' needs at least 1 number"),
            StatementError::NotAnIndex { what, token } => {
                write!(f, "expected a {what} index, found '{token}'")
            }
            StatementError::IndexOutOfRange {
                what,
                token,
                defined,
            } => write!(
                f,
                "{what} index {token} is out of range: {defined} defined so far"
            ),
            StatementError::TooFewCorners { found } => {
                write!(f, "a face needs at least 3 vertices, found {found}")
            }
            StatementError::UnsupportedColour { statement, space } => write!(
                f,
                "'{statement} {space}' colours are not supported; give r g b"
            ),
            StatementError::NoColour { statement } => write!(f, "'{statement}' needs a colour"),
            StatementError::ColourCount { statement } => {
                write!(f, "'{statement}' needs 1 or 3 numbers")
            }
        }
    }
}

impl std::error::Error for StatementError {}

#[cfg(test)]
mod tests {
    use super::StatementError;

    #[test]
    fn messages_say_what_the_statement_needs() {
        let cases = [
            (
                StatementError::NoTextureCoordinate,
                "'vt' needs at least 1 number",
            ),
            (
                StatementError::NotAnIndex {
                    what: "texture coordinate",
                    token: "a".into(),
                },
                "expected a texture coordinate index, found 'a'",
            ),
            (
                StatementError::UnsupportedColour {
                    statement: "Kd",
                    space: "spectral".into(),
                },
                "'Kd spectral' colours are not supported; give r g b",
            ),
            (
                StatementError::NoColour { statement: "Ke" },
                "'Ke' needs a colour",
            ),
        ];
        for (e, message) in cases {
            assert_eq!(e.to_string(), message);
        }
    }
}
