//! A solve's configuration applied to its problem's scene: `RESULT#K`, member K of the
//! ISOC in a `result.json` (counted from 1 in its order, as `isoc-01.png` … are), for
//! `render`, `measure` and `map` to look at what a solve found.

use crate::binding::Binding;
use crate::output::ResultFile;
use crate::problem::Problem;
use invlight_scene::{Diagnostic, Scene};
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// `RESULT#K`, or `RESULT` for member 1 (the highest mean).
#[derive(Debug, Clone, PartialEq)]
pub struct MemberRef {
    /// The `result.json`.
    pub file: PathBuf,
    /// K, from 1.
    pub number: usize,
}

/// Why a `RESULT#K` names no member: K, as written, is not a number from 1.
#[derive(Debug, Clone, PartialEq)]
pub struct MemberNumberError(pub String);

impl std::fmt::Display for MemberNumberError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "'{}' is not an ISOC member number (they count from 1, as isoc-01.png, isoc-02.png, …)",
            self.0
        )
    }
}

impl std::error::Error for MemberNumberError {}

impl FromStr for MemberRef {
    type Err = MemberNumberError;

    fn from_str(s: &str) -> Result<MemberRef, MemberNumberError> {
        match s.rsplit_once('#') {
            Some((f, k)) => match k.parse::<usize>() {
                Ok(number) if number >= 1 => Ok(MemberRef {
                    file: PathBuf::from(f),
                    number,
                }),
                _ => Err(MemberNumberError(k.into())),
            },
            None => Ok(MemberRef {
                file: PathBuf::from(s),
                number: 1,
            }),
        }
    }
}

impl MemberRef {
    /// Applies the member to `scene`, the scene of `problem` as loaded: it is bound to
    /// the problem (holes cut) and moved as the member says.
    pub fn apply(&self, problem: &Problem, scene: &mut Scene) -> Result<(), Diagnostic> {
        let binding = Binding::new(problem, scene)?;
        let result = ResultFile::read(&self.file)?;
        let config = result
            .configuration(&binding, self.number)
            .map_err(|e| Diagnostic::new(&self.file, e.to_string()))?;
        binding.apply(scene, &config);
        Ok(())
    }
}

/// The scene `path` names, read the same way by `render`, `measure` and `map`: a scene
/// file, loaded by `file`; or a problem file (`.xml`), whose scene `problem` loads, with
/// member `config` (`RESULT#K`) of one of its solves applied. `config` with a scene
/// file is refused: only a problem binds the variables a configuration sets.
pub fn configured_scene<E: From<Diagnostic>>(
    path: &Path,
    config: Option<&str>,
    file: impl FnOnce() -> Result<Scene, E>,
    problem: impl FnOnce(&mut Problem) -> Result<Scene, E>,
) -> Result<Scene, E> {
    let xml = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"));
    if !xml {
        return match config {
            Some(_) => Err(Diagnostic::new(
                path,
                "--config applies a solve's configuration to the scene of its problem file; this is not a problem file (.xml)",
            )
            .into()),
            None => file(),
        };
    }
    let mut read = Problem::read(path)?;
    let mut scene = problem(&mut read)?;
    if let Some(config) = config {
        let member: MemberRef = config
            .parse()
            .map_err(|e| Diagnostic::new(path, format!("--config {config}: {e}")))?;
        member.apply(&read, &mut scene)?;
    }
    Ok(scene)
}
