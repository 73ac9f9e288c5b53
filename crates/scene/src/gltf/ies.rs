//! glTF `EXT_lights_ies` (KhronosGroup/glTF `extensions/2.0/Vendor/EXT_lights_ies`):
//! IES LM-63 light profiles listed at the root (`lights`, each a `uri` or a
//! `bufferView` with `mimeType` `application/x-ies-lm-63`) and placed by nodes
//! (`light`, `multiplier`, `color`). The node's transform places and turns the profile:
//! its photometric zero along the node's local −Z, the horizontal angle 0 along local +X
//! ("Coordinate System Mapping"); the node's scale changes nothing ("The light's
//! intensity is unaffected by the node's global scale").
//!
//! `gltf-json` has no schema for the extension, so it is read from the JSON it keeps
//! for unknown extensions, with every field checked here.

use super::Builder;
use crate::error::LoadError;
use crate::light::{Light, LightKind, tilt_factor};
use crate::photometry::{Photometry, parse_ies_in};
use glam::{Mat3, Mat4, Vec3};
use gltf_json as json;
use serde_json::Value;
use std::path::Path;
use std::sync::Arc;

/// The extension's name, the key of its JSON.
pub(super) const EXT: &str = "EXT_lights_ies";

/// The media type a profile in a buffer view must declare.
const MIME: &str = "application/x-ies-lm-63";

const HINT: &str = "see the EXT_lights_ies specification: a node has {\"light\": index, \"multiplier\": ≥ 0, \"color\": [r, g, b]}, the root lists {\"uri\"} or {\"bufferView\", \"mimeType\": \"application/x-ies-lm-63\"} profiles";

impl Builder<'_> {
    /// The `EXT_lights_ies` object of node `i`, when it has one.
    pub(super) fn ies_extension(&self, i: usize) -> Option<&Value> {
        self.root.nodes[i]
            .extensions
            .as_ref()
            .and_then(|e| e.others.get(EXT))
    }

    /// Places the profile node `i` refers to by `ext` with the node's world transform.
    pub(super) fn ies_light(
        &mut self,
        i: usize,
        ext: &Value,
        world: Mat4,
    ) -> Result<(), LoadError> {
        let here = format!("nodes[{i}].extensions.{EXT}");
        let err = |m: String| LoadError::at(self.path, &here, m).with_hint(HINT);
        let index = ext
            .get("light")
            .and_then(Value::as_u64)
            .ok_or_else(|| err("'light' must be the index of a light profile".into()))?
            as usize;
        let multiplier = match ext.get("multiplier") {
            None => 1.0,
            Some(m) => m
                .as_f64()
                .filter(|m| m.is_finite() && *m >= 0.0)
                .ok_or_else(|| err(format!("'multiplier' is {m}; a number ≥ 0 was expected")))?,
        } as f32;
        let color = match ext.get("color") {
            None => Vec3::ONE,
            Some(c) => {
                let v: Option<Vec<f64>> = c
                    .as_array()
                    .filter(|a| a.len() == 3)
                    .and_then(|a| a.iter().map(Value::as_f64).collect());
                let v = v
                    .filter(|v| v.iter().all(|x| x.is_finite()))
                    .ok_or_else(|| err(format!("'color' is {c}; three numbers were expected")))?;
                // The spec clamps the colour to [0, 1].
                Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32).clamp(Vec3::ZERO, Vec3::ONE)
            }
        };
        let photometry = self.ies_profile(index, &here)?;
        let position = world.transform_point3(Vec3::ZERO);
        let Some(frame) = rotation(world) else {
            return Err(self.err(
                &format!("nodes[{i}]"),
                "the transform collapses the light's axes",
            ));
        };
        let tilt = tilt_factor(&photometry, -frame.z_axis, Vec3::Y);
        let name = self.root.nodes[i]
            .name
            .clone()
            .or_else(|| {
                self.profile_json(index)
                    .and_then(|p| p.get("name")?.as_str().map(String::from))
            })
            .unwrap_or_else(|| format!("{EXT}.lights[{index}]"));
        self.scene.lights.push(Light {
            c0: glam::Vec3::X,
            name,
            kind: LightKind::Goniometric {
                position,
                frame,
                photometry,
                multiplier: color * multiplier,
                tilt,
            },
        });
        Ok(())
    }

    /// The JSON of root profile `index`.
    fn profile_json(&self, index: usize) -> Option<&Value> {
        self.root
            .extensions
            .as_ref()?
            .others
            .get(EXT)?
            .get("lights")?
            .as_array()?
            .get(index)
    }

    /// Root profile `index`, read once however many nodes place it.
    fn ies_profile(&mut self, index: usize, from: &str) -> Result<Arc<Photometry>, LoadError> {
        if let Some(p) = self.profiles.get(&index) {
            return Ok(p.clone());
        }
        let here = format!("extensions.{EXT}.lights[{index}]");
        let Some(profile) = self.profile_json(index) else {
            return Err(LoadError::at(
                self.path,
                from,
                format!("light profile {index} does not exist in extensions.{EXT}.lights"),
            )
            .with_hint(HINT));
        };
        let err = |m: String| LoadError::at(self.path, &here, m).with_hint(HINT);
        let uri = match profile.get("uri") {
            None => None,
            Some(u) => Some(
                u.as_str()
                    .ok_or_else(|| err(format!("'uri' is {u}, not a string")))?,
            ),
        };
        let view = match profile.get("bufferView") {
            None => None,
            Some(v) => {
                let v = v
                    .as_u64()
                    .ok_or_else(|| err(format!("'bufferView' is {v}, not an index")))?;
                let mime = profile.get("mimeType").and_then(Value::as_str);
                if uri.is_none() && mime != Some(MIME) {
                    return Err(err(format!(
                        "a profile in a buffer view needs \"mimeType\": \"{MIME}\""
                    )));
                }
                Some(json::Index::new(v as u32))
            }
        };
        let referenced = self.referenced(uri, view, &here)?;
        let photometry = match &referenced.file {
            Some(file) => parse_ies_in(&referenced.bytes, file, self.files)?
                .read_from(uri.unwrap_or_default(), file),
            None => {
                // Embedded: errors point into the glTF, a TILT=<file> beside it.
                let beside = self
                    .path
                    .parent()
                    .unwrap_or(Path::new(""))
                    .join("embedded.ies");
                parse_ies_in(&referenced.bytes, &beside, self.files).map_err(|e| LoadError {
                    path: self.path.to_path_buf(),
                    location: if e.location.is_empty() {
                        here.clone()
                    } else {
                        format!("{here}, {}", e.location)
                    },
                    ..e
                })?
            }
        };
        let photometry = Arc::new(photometry);
        self.profiles.insert(index, photometry.clone());
        Ok(photometry)
    }
}

/// The rotation of `world` without its scale: the node's local axes, normalised and made
/// orthogonal from −Z (the aim) outward, keeping the transform's handedness.
fn rotation(world: Mat4) -> Option<Mat3> {
    let m = Mat3::from_mat4(world);
    let z = m.z_axis.normalize_or_zero();
    let x = (m.x_axis - z * m.x_axis.dot(z)).normalize_or_zero();
    if z == Vec3::ZERO || x == Vec3::ZERO {
        return None;
    }
    let y = z.cross(x);
    let y = if m.determinant() < 0.0 { -y } else { y };
    Some(Mat3::from_cols(x, y, z))
}
