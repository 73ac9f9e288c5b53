//! obj loader (to be written).

use crate::error::LoadError;
use crate::model::Scene;
use std::path::Path;

/// Reads a obj file.
pub(crate) fn load(path: &Path) -> Result<Scene, LoadError> {
    Err(LoadError::new(path, "the obj loader is not written yet"))
}
