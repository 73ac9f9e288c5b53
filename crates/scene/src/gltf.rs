//! gltf loader (to be written).

use crate::error::LoadError;
use crate::model::Scene;
use std::path::Path;

/// Reads a gltf file.
pub(crate) fn load(path: &Path) -> Result<Scene, LoadError> {
    Err(LoadError::new(path, "the gltf loader is not written yet"))
}
