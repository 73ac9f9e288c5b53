//! glTF meshes (spec §3.7.2) as scene meshes: every triangle primitive of a glTF mesh in
//! one [`Mesh`], with a material per triangle.

use super::Builder;
use crate::error::LoadError;
use crate::mesh::Mesh;
use crate::model::MeshId;
use glam::{Vec2, Vec3};
use gltf_json as json;
use json::accessor::Type;
use json::mesh::{Mode, Semantic};
use json::validation::Checked;

/// How a primitive's vertex list forms triangles, or `None` for points and lines, which
/// bound no area and so receive no light.
fn triangulate(mode: Mode, indices: &[u32]) -> Option<Vec<[u32; 3]>> {
    let n = indices.len();
    let v = |i: usize| indices[i];
    let tris: Vec<[u32; 3]> = match mode {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        // Spec §3.7.2: p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2−i%2)}} keeps one winding.
        Mode::TriangleStrip => (0..n.saturating_sub(2))
            .map(|i| [v(i), v(i + 1 + i % 2), v(i + 2 - i % 2)])
            .collect(),
        // Spec §3.7.2: p_i = {v_{i+1}, v_{i+2}, v_0}.
        Mode::TriangleFan => (0..n.saturating_sub(2))
            .map(|i| [v(i + 1), v(i + 2), v(0)])
            .collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => return None,
    };
    // Strips restart with repeated indices; such triangles have no area.
    Some(
        tris.into_iter()
            .filter(|[a, b, c]| a != b && b != c && a != c)
            .collect(),
    )
}

impl Builder<'_> {
    /// The scene mesh of glTF `meshes[index]`, built on first use and shared by every
    /// node that instances it; `None` when it has no triangles.
    ///
    /// `mirrored` (a world transform of negative determinant) gives a copy wound the
    /// other way: glTF takes a mirrored node's clockwise faces as front (spec §3.7.2),
    /// while a scene mesh's front is counter-clockwise after any transform.
    pub(super) fn mesh(
        &mut self,
        index: json::Index<json::Mesh>,
        mirrored: bool,
        loc: &str,
    ) -> Result<Option<MeshId>, LoadError> {
        let m = index.value();
        if let Some(&id) = self.meshes.get(&(m, mirrored)) {
            return Ok(id);
        }
        let gltf_mesh = self.root.meshes.get(m).ok_or_else(|| {
            self.err(
                loc,
                format!(
                    "mesh {m} does not exist ({} in the file)",
                    self.root.meshes.len()
                ),
            )
        })?;
        let mut mesh = Mesh::default();
        let mut has_uvs = false;
        for (p, prim) in gltf_mesh.primitives.iter().enumerate() {
            let here = format!("meshes[{m}].primitives[{p}]");
            let Checked::Valid(mode) = prim.mode else {
                return Err(self.err(&here, "mode is not a glTF primitive mode (0–6)"));
            };
            // Indices first: the vertices are read only as far as they reach.
            let indices = match prim.indices {
                Some(acc) => Some(self.read_indices(acc, &format!("{here}.indices"))?),
                None => None,
            };
            let reach = indices
                .as_ref()
                .map(|i| i.iter().max().map_or(0, |&m| m as u64 + 1));
            let (positions, claimed) = self.positions(prim, &here, reach)?;
            let base = mesh.positions.len() as u32;
            let count = positions.len();
            let indices = match indices {
                Some(indices) => indices,
                None => (0..count as u32).collect(),
            };
            if let Some((k, &bad)) = indices
                .iter()
                .enumerate()
                .find(|(_, i)| **i as u64 >= claimed)
            {
                return Err(self.err(
                    &format!("{here}.indices"),
                    format!("index {k} is {bad}, but the primitive has {claimed} vertices"),
                ));
            }
            let Some(triangles) = triangulate(mode, &indices) else {
                continue;
            };
            // The set the base-colour texture reads (its `texCoord`, usually 0).
            let set = prim
                .material
                .and_then(|m| self.root.materials.get(m.value()))
                .and_then(|m| m.pbr_metallic_roughness.base_color_texture.as_ref())
                .map_or(0, |t| t.tex_coord);
            let uvs = match prim
                .attributes
                .get(&Checked::Valid(Semantic::TexCoords(set)))
            {
                Some(&acc) => {
                    let at = format!("{here}.attributes.TEXCOORD_{set}");
                    let (uvs, uv_count) = self.read_floats(acc, Type::Vec2, &at, reach)?;
                    if uv_count != claimed {
                        return Err(self.err(
                            &at,
                            format!("{uv_count} texture coordinates for {claimed} vertices"),
                        ));
                    }
                    Some(uvs)
                }
                None => None,
            };
            let material = self.material(prim.material, &here)?;
            // Texture coordinates are per mesh: pad the vertices of primitives without.
            if let Some(uvs) = uvs {
                if !has_uvs {
                    mesh.uvs = vec![Vec2::ZERO; mesh.positions.len()];
                    has_uvs = true;
                }
                mesh.uvs
                    .extend(uvs.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])));
            } else if has_uvs {
                mesh.uvs.extend(std::iter::repeat_n(Vec2::ZERO, count));
            }
            if mesh.positions.is_empty() {
                mesh.positions = positions;
            } else {
                mesh.positions.extend(positions);
            }
            mesh.materials
                .extend(std::iter::repeat_n(material, triangles.len()));
            mesh.triangles
                .extend(triangles.iter().map(|t| t.map(|i| i + base)));
        }
        if mirrored {
            mesh.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        }
        let id = (!mesh.triangles.is_empty()).then(|| self.scene.add_mesh(mesh));
        self.meshes.insert((m, mirrored), id);
        Ok(id)
    }

    /// The POSITION attribute of a primitive, finite numbers required: the first
    /// `reach` vertices (all when `None`) and the count the accessor claims.
    pub(super) fn positions(
        &self,
        prim: &json::mesh::Primitive,
        here: &str,
        reach: Option<u64>,
    ) -> Result<(Vec<Vec3>, u64), LoadError> {
        let loc = format!("{here}.attributes.POSITION");
        let Some(&acc) = prim.attributes.get(&Checked::Valid(Semantic::Positions)) else {
            return Err(self.err(here, "the primitive has no POSITION attribute"));
        };
        let (floats, claimed) = self.read_floats(acc, Type::Vec3, &loc, reach)?;
        if floats.iter().any(|f| !f.is_finite()) {
            return Err(self.err(&loc, "a position is not a finite number"));
        }
        let positions = floats
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect();
        Ok((positions, claimed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_the_winding() {
        let idx = [0, 1, 2, 3, 4];
        assert_eq!(
            triangulate(Mode::TriangleStrip, &idx).unwrap(),
            vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            triangulate(Mode::TriangleFan, &idx).unwrap(),
            vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        assert_eq!(triangulate(Mode::Lines, &idx), None);
        // A strip restart (repeated index) yields no zero-area triangle.
        assert_eq!(
            triangulate(Mode::TriangleStrip, &[0, 1, 1, 2])
                .unwrap()
                .len(),
            0
        );
    }
}
