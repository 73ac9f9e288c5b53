//! glTF metallic-roughness materials mapped onto photon tracing's K_d / K_s /
//! transmission / emission (thesis Algorithm 2.2), with ILPSolver's hole convention.

use super::Builder;
use crate::error::LoadError;
use crate::material::Material;
use crate::model::{MaterialId, TextureId};
use glam::Vec3;
use gltf_json as json;

/// Roughness at or below which a metal is taken for a perfect mirror: photon tracing has
/// only Lambertian and perfectly specular reflection, and a glossy lobe this narrow is
/// closer to the mirror.
const MIRROR_ROUGHNESS: f32 = 0.2;

/// glTF's `ior` default (KHR_materials_ior), that of common glass.
const DEFAULT_IOR: f32 = 1.5;

impl Builder<'_> {
    /// The scene material for glTF `materials[index]`, or for glTF's default material when
    /// the primitive names none; made once and reused.
    pub(super) fn material(
        &mut self,
        index: Option<json::Index<json::Material>>,
        loc: &str,
    ) -> Result<MaterialId, LoadError> {
        let Some(index) = index else {
            if let Some(id) = self.default_material {
                return Ok(id);
            }
            // Spec §3.9.6: baseColorFactor 1, metallic 1, roughness 1 — rough, so diffuse.
            let id = self
                .scene
                .add_material(Material::diffuse("glTF default", Vec3::ONE));
            self.default_material = Some(id);
            return Ok(id);
        };
        let i = index.value();
        if let Some(&id) = self.materials.get(&i) {
            return Ok(id);
        }
        let m = self.root.materials.get(i).ok_or_else(|| {
            self.err(
                &format!("{loc}.material"),
                format!(
                    "material {i} does not exist ({} in the file)",
                    self.root.materials.len()
                ),
            )
        })?;
        let here = format!("materials[{i}]");
        let name = m.name.clone().unwrap_or_else(|| here.clone());
        let pbr = &m.pbr_metallic_roughness;
        let [r, g, b, _] = pbr.base_color_factor.0;
        let base = Vec3::new(r, g, b).clamp(Vec3::ZERO, Vec3::ONE);
        let ext = m.extensions.as_ref();
        let ior = ext.and_then(|e| e.ior.as_ref()).map(|i| i.ior.0);
        let transmission = ext
            .and_then(|e| e.transmission.as_ref())
            .map_or(0.0, |t| t.transmission_factor.0)
            .clamp(0.0, 1.0);
        let strength = ext
            .and_then(|e| e.emissive_strength.as_ref())
            .map_or(1.0, |s| s.emissive_strength.0);
        let emission = Vec3::from_array(m.emissive_factor.0).max(Vec3::ZERO) * strength.max(0.0);
        let factors = [pbr.metallic_factor.0, pbr.roughness_factor.0, r, g, b];
        if !emission.is_finite() || factors.iter().any(|f| !f.is_finite()) {
            return Err(self.err(&here, "a factor is not a finite number"));
        }
        if m.emissive_texture.is_some() && emission.max_element() > 0.0 {
            return Err(self
                .err(
                    &format!("{here}.emissiveTexture"),
                    format!("material '{name}' emits through a texture, which invlight does not read: it would emit emissiveFactor uniformly over the whole surface"),
                )
                .with_hint("bake the texture's mean into emissiveFactor (or split the emitting part into its own material), or set emissiveFactor to 0 if the surface should not emit"));
        }

        let material = if ior.is_some_and(|ior| ior < 1.0) {
            // ILPSolver marks apertures by an index of refraction below 1 (DESIGN.md §2).
            Material::hole(&name)
        } else {
            // The metallic factor blends a metal (mirror when smooth) over the dielectric,
            // whose diffuse part transmission replaces (KHR_materials_transmission).
            let mirror = if pbr.roughness_factor.0 <= MIRROR_ROUGHNESS {
                pbr.metallic_factor.0.clamp(0.0, 1.0)
            } else {
                0.0
            };
            let diffuse = base * (1.0 - mirror) * (1.0 - transmission);
            let texture = match &pbr.base_color_texture {
                Some(info) if diffuse.max_element() > 0.0 => Some(self.texture(
                    info.index,
                    &format!("{here}.pbrMetallicRoughness.baseColorTexture"),
                )?),
                _ => None,
            };
            Material {
                name,
                diffuse,
                texture,
                specular: base * mirror,
                transmission: transmission * (1.0 - mirror),
                ior: ior.unwrap_or(DEFAULT_IOR),
                emission,
                hole: false,
            }
        };
        let id = self.scene.add_material(material);
        self.materials.insert(i, id);
        Ok(id)
    }

    /// The scene texture of glTF `textures[index]`; images shared by several textures are
    /// decoded once.
    fn texture(
        &mut self,
        index: json::Index<json::Texture>,
        loc: &str,
    ) -> Result<TextureId, LoadError> {
        let i = index.value();
        let texture = self.root.textures.get(i).ok_or_else(|| {
            self.err(
                loc,
                format!(
                    "texture {i} does not exist ({} in the file)",
                    self.root.textures.len()
                ),
            )
        })?;
        let image = texture.source;
        if let Some(&id) = self.images.get(&image.value()) {
            return Ok(id);
        }
        let decoded = self.image(image, &format!("textures[{i}].source"))?;
        let id = self.scene.add_texture(decoded);
        self.images.insert(image.value(), id);
        Ok(id)
    }
}
