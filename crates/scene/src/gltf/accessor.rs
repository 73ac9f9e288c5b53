//! Accessors (glTF 2.0 spec §3.6.2): typed arrays laid over buffer views, with byte
//! strides, normalised integers (also KHR_mesh_quantization's) and sparse substitution.
//!
//! Every element is copied into a dense array after checking its whole byte range
//! against the view, so a bad offset, stride, count or sparse index is a [`LoadError`]
//! naming the accessor, never a panic (the `gltf` crate's reader `debug_assert`s and
//! computes `count - 1` unchecked, hence this reader).
//!
//! Only the elements a primitive's indices reach are copied: an accessor without a
//! buffer view is zeros (§3.6.2.3, for sparse accessors), so its `count` is a claim no
//! byte of the file backs, and a 4 KB file claiming 178 956 970 VEC3 whose indices use
//! four vertices took 4.2 GB. The claimed count is still what indices and sparse
//! indices are checked against.

use super::Builder;
use crate::error::LoadError;
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, IndexComponentType, Type};
use json::validation::Checked;

/// An accessor's elements packed without stride, and how to read their components.
struct Dense {
    /// The first `reach` elements (all of them when the accessor was read whole).
    bytes: Vec<u8>,
    component: ComponentType,
    normalized: bool,
    /// The accessor's `count`, which may exceed the elements copied.
    count: u64,
}

fn component_size(c: ComponentType) -> usize {
    match c {
        ComponentType::I8 | ComponentType::U8 => 1,
        ComponentType::I16 | ComponentType::U16 => 2,
        ComponentType::U32 | ComponentType::F32 => 4,
    }
}

fn type_name(t: Type) -> &'static str {
    match t {
        Type::Scalar => "SCALAR",
        Type::Vec2 => "VEC2",
        Type::Vec3 => "VEC3",
        Type::Vec4 => "VEC4",
        Type::Mat2 => "MAT2",
        Type::Mat3 => "MAT3",
        Type::Mat4 => "MAT4",
    }
}

/// One component as a float; normalised integers map to [0, 1] or [−1, 1] by the
/// spec's equations (`f = max(c / 127, −1)` for signed bytes and so on).
fn to_f32(c: &[u8], component: ComponentType, normalized: bool) -> f32 {
    let (v, scale) = match component {
        ComponentType::U8 => (c[0] as f32, 255.0),
        ComponentType::I8 => (c[0] as i8 as f32, 127.0),
        ComponentType::U16 => (u16::from_le_bytes([c[0], c[1]]) as f32, 65535.0),
        ComponentType::I16 => (i16::from_le_bytes([c[0], c[1]]) as f32, 32767.0),
        ComponentType::U32 => (
            u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f32,
            u32::MAX as f32,
        ),
        ComponentType::F32 => return f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
    };
    if normalized { (v / scale).max(-1.0) } else { v }
}

/// One unsigned index component.
fn to_u32(c: &[u8], component: ComponentType) -> u32 {
    match component {
        ComponentType::U16 => u16::from_le_bytes([c[0], c[1]]) as u32,
        ComponentType::U32 => u32::from_le_bytes([c[0], c[1], c[2], c[3]]),
        _ => c[0] as u32,
    }
}

impl Builder<'_> {
    /// The accessor `index`, which must be of type `want`, as floats (`n` components
    /// per element, element-major) with its claimed `count`. Only the first `reach`
    /// elements are read when given (a primitive's largest index + 1), all `count`
    /// otherwise. `loc` names the referrer, e.g.
    /// `meshes[0].primitives[1].attributes.POSITION`.
    pub(super) fn read_floats(
        &self,
        index: json::Index<json::Accessor>,
        want: Type,
        loc: &str,
        reach: Option<u64>,
    ) -> Result<(Vec<f32>, u64), LoadError> {
        let dense = self.dense(index, want, loc, reach)?;
        let size = component_size(dense.component);
        let floats = (dense.bytes.len() / size * size_of::<f32>()) as u64;
        self.files.charge(
            self.path,
            &format!("accessors[{}] (from {loc})", index.value()),
            floats,
            "its components as floats",
        )?;
        let floats = dense
            .bytes
            .chunks_exact(size)
            .map(|c| to_f32(c, dense.component, dense.normalized))
            .collect();
        Ok((floats, dense.count))
    }

    /// The index accessor `index`: SCALAR of unsigned byte, short or int.
    pub(super) fn read_indices(
        &self,
        index: json::Index<json::Accessor>,
        loc: &str,
    ) -> Result<Vec<u32>, LoadError> {
        let dense = self.dense(index, Type::Scalar, loc, None)?;
        if !matches!(
            dense.component,
            ComponentType::U8 | ComponentType::U16 | ComponentType::U32
        ) {
            return Err(self.err(
                &format!("accessors[{}] (from {loc})", index.value()),
                "indices must be unsigned byte, short or int (componentType 5121, 5123, 5125)",
            ));
        }
        let size = component_size(dense.component);
        Ok(dense
            .bytes
            .chunks_exact(size)
            .map(|c| to_u32(c, dense.component))
            .collect())
    }

    /// Copies the accessor's first `reach` elements (all when `None`) densely, applying
    /// its sparse substitution; the whole claimed range is checked against the view.
    fn dense(
        &self,
        index: json::Index<json::Accessor>,
        want: Type,
        loc: &str,
        reach: Option<u64>,
    ) -> Result<Dense, LoadError> {
        let i = index.value();
        let here = format!("accessors[{i}] (from {loc})");
        let acc = self.root.accessors.get(i).ok_or_else(|| {
            self.err(
                loc,
                format!(
                    "accessor {i} does not exist ({} in the file)",
                    self.root.accessors.len()
                ),
            )
        })?;
        let Checked::Valid(GenericComponentType(component)) = acc.component_type else {
            return Err(self.err(&here, "componentType is not a glTF component type"));
        };
        let Checked::Valid(ty) = acc.type_ else {
            return Err(self.err(&here, "type is not a glTF accessor type"));
        };
        if ty != want {
            return Err(self.err(
                &here,
                format!(
                    "type {} where {} is expected",
                    type_name(ty),
                    type_name(want)
                ),
            ));
        }
        let element = (ty.multiplicity() * component_size(component)) as u64;
        let count = acc.count.0;
        let copied = reach.map_or(count, |r| r.min(count));
        // Charged before anything is allocated: without indices to bound it, a
        // bufferless accessor's claim is refused past the budget with its figure.
        let total = copied
            .checked_mul(element)
            .ok_or_else(|| self.err(&here, format!("count {count} is too large")))?;
        let what = if copied == count {
            format!("its {count} {} elements", type_name(ty))
        } else {
            format!(
                "the {copied} of its {count} {} elements that indices reach",
                type_name(ty)
            )
        };
        self.files.charge(self.path, &here, total, &what)?;
        // The strided source, checked whole before anything is allocated.
        let source = match acc.buffer_view {
            Some(view) => {
                let (data, stride) = self.view(view, &here)?;
                let stride = stride.map_or(element, |s| s as u64);
                if stride < element {
                    return Err(self.err(
                        &here,
                        format!("byteStride {stride} is less than the {element}-byte element"),
                    ));
                }
                let offset = acc.byte_offset.map_or(0, |o| o.0);
                let end = count
                    .checked_sub(1)
                    .map_or(Some(0), |last| {
                        last.checked_mul(stride)
                            .and_then(|x| x.checked_add(offset))
                            .and_then(|x| x.checked_add(element))
                    })
                    .filter(|&e| e <= data.len() as u64);
                if end.is_none() {
                    return Err(self.err(
                        &here,
                        format!(
                            "{count} elements of {element} bytes every {stride} from byte {offset} overrun its {}-byte buffer view",
                            data.len()
                        ),
                    ));
                }
                Some((data, offset as usize, stride as usize))
            }
            None => None,
        };
        let mut bytes = vec![0u8; total as usize];
        if let Some((data, offset, stride)) = source {
            let element = element as usize;
            for (k, out) in bytes.chunks_exact_mut(element).enumerate() {
                let at = offset + k * stride;
                out.copy_from_slice(&data[at..at + element]);
            }
        }
        if let Some(sparse) = &acc.sparse {
            self.substitute(sparse, &mut bytes, element as usize, count, &here)?;
        }
        Ok(Dense {
            bytes,
            component,
            normalized: acc.normalized,
            count,
        })
    }

    /// Replaces the elements a sparse accessor lists (spec §3.6.2.3), each index
    /// checked against the claimed `count`; those past the copied `bytes` are not read.
    fn substitute(
        &self,
        sparse: &json::accessor::sparse::Sparse,
        bytes: &mut [u8],
        element: usize,
        count: u64,
        here: &str,
    ) -> Result<(), LoadError> {
        let n = sparse.count.0;
        let Checked::Valid(IndexComponentType(component)) = sparse.indices.component_type else {
            return Err(self.err(
                here,
                "sparse.indices.componentType is not unsigned byte, short or int",
            ));
        };
        let isize = component_size(component) as u64;
        let slice = |view, offset: u64, size: u64, what: &str| -> Result<&[u8], LoadError> {
            let (data, _) = self.view(view, &format!("{here}.sparse.{what}"))?;
            let end = n.checked_mul(size).and_then(|x| x.checked_add(offset));
            match end.filter(|&e| e <= data.len() as u64) {
                Some(end) => Ok(&data[offset as usize..end as usize]),
                None => Err(self.err(
                    here,
                    format!(
                        "sparse.{what}: {n} entries overrun their {}-byte buffer view",
                        data.len()
                    ),
                )),
            }
        };
        let indices = slice(
            sparse.indices.buffer_view,
            sparse.indices.byte_offset.0,
            isize,
            "indices",
        )?;
        let values = slice(
            sparse.values.buffer_view,
            sparse.values.byte_offset.0,
            element as u64,
            "values",
        )?;
        for (k, value) in values.chunks_exact(element).enumerate() {
            let target = to_u32(&indices[k * isize as usize..], component) as u64;
            if target >= count {
                return Err(self.err(
                    here,
                    format!("sparse.indices[{k}] = {target} is not below count {count}"),
                ));
            }
            let at = target as usize * element;
            if let Some(out) = bytes.get_mut(at..at + element) {
                out.copy_from_slice(value);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::error::LoadError;
    use crate::files::Files;
    use crate::load::LoadOptions;
    use crate::model::Scene;
    use base64::Engine;
    use glam::{Vec2, Vec3};
    use std::path::Path;

    /// Three vertices interleaved (f32 position + normalised u16 uv, stride 16), a
    /// sparse substitution of vertex 2, and u8 positions (KHR_mesh_quantization).
    fn buffer() -> Vec<u8> {
        let mut b = Vec::new();
        let uv: [[u16; 2]; 3] = [[0, 65535], [65535, 65535], [32768, 0]];
        for (k, p) in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
            .iter()
            .enumerate()
        {
            p.iter().for_each(|x| b.extend(x.to_le_bytes()));
            uv[k].iter().for_each(|x| b.extend(x.to_le_bytes()));
        }
        b.extend([2, 0, 0, 0]); // sparse index (u8) at 48, padded
        [5.0f32, 5.0, 5.0]
            .iter()
            .for_each(|x| b.extend(x.to_le_bytes())); // at 52
        for p in [[1u8, 2, 3], [4, 5, 6], [7, 8, 9]] {
            b.extend(p);
            b.push(0); // each element 4-byte aligned, stride 4
        }
        b
    }

    fn document(edit: impl Fn(&str) -> String) -> Result<Scene, LoadError> {
        let data = base64::engine::general_purpose::STANDARD.encode(buffer());
        let json = format!(
            r#"{{"asset": {{"version": "2.0"}},
            "buffers": [{{"byteLength": 76, "uri": "data:application/octet-stream;base64,{data}"}}],
            "bufferViews": [
                {{"buffer": 0, "byteOffset": 0, "byteLength": 48, "byteStride": 16}},
                {{"buffer": 0, "byteOffset": 48, "byteLength": 1}},
                {{"buffer": 0, "byteOffset": 52, "byteLength": 12}},
                {{"buffer": 0, "byteOffset": 64, "byteLength": 12, "byteStride": 4}}],
            "accessors": [
                {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]}},
                {{"bufferView": 0, "byteOffset": 12, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"}},
                {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [5,5,5],
                  "sparse": {{"count": 1, "indices": {{"bufferView": 1, "componentType": 5121}}, "values": {{"bufferView": 2}}}}}},
                {{"bufferView": 3, "componentType": 5121, "count": 3, "type": "VEC3", "min": [1,2,3], "max": [7,8,9]}}],
            "meshes": [{{"primitives": [
                {{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}}},
                {{"attributes": {{"POSITION": 2}}}},
                {{"attributes": {{"POSITION": 3}}}}]}}],
            "nodes": [{{"name": "A", "mesh": 0}}],
            "scenes": [{{"nodes": [0]}}]}}"#
        );
        let path = Path::new("t.gltf");
        super::super::from_bytes(
            path,
            edit(&json).as_bytes(),
            &Files::new(path, &LoadOptions::default()),
        )
    }

    #[test]
    fn strides_normalisation_sparse_and_quantisation() {
        let s = document(|j| j.to_string()).unwrap();
        let m = &s.meshes[0];
        let v = |x, y, z| Vec3::new(x, y, z);
        assert_eq!(
            m.positions,
            [
                v(0.0, 0.0, 0.0),
                v(1.0, 0.0, 0.0),
                v(0.0, 1.0, 0.0),
                v(0.0, 0.0, 0.0),
                v(1.0, 0.0, 0.0),
                v(5.0, 5.0, 5.0),
                v(1.0, 2.0, 3.0),
                v(4.0, 5.0, 6.0),
                v(7.0, 8.0, 9.0),
            ]
        );
        // u16 normalised: c / 65535; vertices of primitives without uvs get (0, 0).
        let mut uvs = vec![
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(32768.0 / 65535.0, 0.0),
        ];
        uvs.resize(9, Vec2::ZERO);
        assert_eq!(m.uvs, uvs);
        assert_eq!(m.triangles, [[0, 1, 2], [3, 4, 5], [6, 7, 8]]);
    }

    #[test]
    fn inconsistent_accessors_are_located_errors() {
        let cases = [
            (
                r#""byteStride": 16}"#,
                r#""byteStride": 8}"#,
                "byteStride 8 is less than the 12-byte element",
            ),
            (
                r#""count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]"#,
                r#""count": 4, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]"#,
                "overrun",
            ),
            (
                r#""count": 1, "indices""#,
                r#""count": 2, "indices""#,
                "sparse.indices: 2 entries overrun",
            ),
            (
                r#""count": 3, "type": "VEC3", "min": [0,0,0], "max": [5,5,5]"#,
                r#""count": 2, "type": "VEC3", "min": [0,0,0], "max": [5,5,5]"#,
                "sparse.indices[0] = 2 is not below count 2",
            ),
            (
                r#""byteOffset": 64, "byteLength": 12"#,
                r#""byteOffset": 68, "byteLength": 12"#,
                "lie outside buffers[0]",
            ),
            (
                r#""POSITION": 3}"#,
                r#""POSITION": 1}"#,
                "type VEC2 where VEC3 is expected",
            ),
        ];
        for (from, to, expected) in cases {
            let e = document(|j| {
                assert!(j.contains(from), "{from}");
                j.replacen(from, to, 1)
            })
            .unwrap_err();
            assert!(
                e.location.starts_with("accessors[") || e.location.starts_with("bufferViews["),
                "{e}"
            );
            assert!(e.message.contains(expected), "{e}");
        }
    }
}
