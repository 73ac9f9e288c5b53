//! The text of photometric files: Latin-1 bytes (LM-63-2019 §5.2; EULUMDAT files come
//! from Windows tools in the same code page), lines, and numbers read with the line
//! they stand on so that an error can point at it.

use crate::error::LoadError;
use std::path::Path;

/// Decodes ISO 8859-1: every byte is the code point of the same value, so no file fails
/// to decode and a `°` or `ü` in a keyword survives.
pub(crate) fn latin1(bytes: &[u8]) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    bytes.iter().map(|&b| b as char).collect()
}

/// Whether the bytes start like an IES file: a header line, or a `TILT=` line near the
/// top (LM-63-1986 has no header).
pub(crate) fn looks_like_ies(bytes: &[u8]) -> bool {
    let text = latin1(&bytes[..bytes.len().min(4096)]);
    let first = text.lines().next().unwrap_or("").trim_start();
    first.starts_with("IES") || text.lines().any(|l| l.trim_start().starts_with("TILT"))
}

/// The whitespace- and comma-separated numbers of some lines, each with its 1-based
/// line number, read on demand.
pub(crate) struct Numbers<'a> {
    path: &'a Path,
    tokens: Vec<(&'a str, usize)>,
    next: usize,
    /// Line number of the end of the data, for "the file ends" errors.
    end_line: usize,
}

impl<'a> Numbers<'a> {
    /// The tokens of `lines`, numbered from `first_line`.
    pub(crate) fn new(path: &'a Path, lines: &[&'a str], first_line: usize) -> Numbers<'a> {
        let mut tokens = Vec::new();
        for (k, line) in lines.iter().enumerate() {
            for t in line.split(|c: char| c.is_whitespace() || c == ',') {
                if !t.is_empty() {
                    tokens.push((t, first_line + k));
                }
            }
        }
        Numbers {
            path,
            tokens,
            next: 0,
            end_line: first_line + lines.len().saturating_sub(1),
        }
    }

    /// The file the numbers are read from.
    pub(crate) fn path(&self) -> &'a Path {
        self.path
    }

    /// The line of the next token (or of the end).
    pub(crate) fn line(&self) -> usize {
        self.tokens.get(self.next).map_or(self.end_line, |t| t.1)
    }

    /// The next number, described as `what` in errors.
    pub(crate) fn f64(&mut self, what: &str) -> Result<f64, LoadError> {
        let Some(&(t, line)) = self.tokens.get(self.next) else {
            return Err(LoadError::at(
                self.path,
                format!("line {}", self.end_line),
                format!("the file ends where {what} was expected"),
            )
            .with_hint("the file is truncated, or a count earlier in it is too large"));
        };
        self.next += 1;
        match t.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(LoadError::at(
                self.path,
                format!("line {line}"),
                format!("'{t}' where {what} (a number) was expected"),
            )),
        }
    }

    /// The next number as a whole count in `lo..=hi`.
    pub(crate) fn int(&mut self, what: &str, lo: i64, hi: i64) -> Result<i64, LoadError> {
        let line = self.line();
        let x = self.f64(what)?;
        if x.fract() != 0.0 || x < lo as f64 || x > hi as f64 {
            return Err(LoadError::at(
                self.path,
                format!("line {line}"),
                format!("{what} is {x}; a whole number from {lo} to {hi} was expected"),
            ));
        }
        Ok(x as i64)
    }

    /// `n` numbers.
    pub(crate) fn list(&mut self, n: usize, what: &str) -> Result<Vec<f64>, LoadError> {
        (0..n).map(|_| self.f64(what)).collect()
    }

    /// Tokens left after the data.
    pub(crate) fn rest(&self) -> usize {
        self.tokens.len() - self.next
    }
}

/// Checks that `angles` (read from the line `line`) increase; `what` names them.
pub(crate) fn increasing(
    path: &Path,
    line: usize,
    angles: &[f64],
    what: &str,
) -> Result<(), LoadError> {
    if let Some(k) = angles.windows(2).position(|w| w[1] <= w[0]) {
        return Err(LoadError::at(
            path,
            format!("line {line}"),
            format!(
                "{what} {} is {}° after {}°: the angles must increase",
                k + 2,
                angles[k + 1],
                angles[k]
            ),
        ));
    }
    Ok(())
}
