//! `<geometry><mesh>`: sources, `<vertices>` and the primitive lists (`triangles`,
//! `polylist`, `polygons`, `trifans`, `tristrips`) turned into one indexed triangle list
//! whose triangles remember their material symbol.

use super::xml::{Ctx, child, children};
use crate::error::LoadError;
use glam::{Vec2, Vec3};
use roxmltree::Node;
use std::collections::HashMap;
use std::fmt;

/// A geometry in its own space, before materials are bound.
#[derive(Default)]
pub(super) struct Geometry {
    pub positions: Vec<Vec3>,
    /// Parallel to `positions`, or empty when no primitive has texture coordinates.
    pub uvs: Vec<Vec2>,
    pub triangles: Vec<[u32; 3]>,
    /// Material symbol of each primitive list (`""` when it names none).
    pub symbols: Vec<String>,
    /// Index into `symbols` of each triangle.
    pub triangle_symbols: Vec<u16>,
    /// Distinct positions in the order the index lists first reach them: the vertex
    /// order Assimp gives after `JoinIdenticalVertices`, which ILPSolver's problem files
    /// index (`vertexAIndex`…) for `*__Geometry` rectangles.
    pub outline: Vec<Vec3>,
}

/// A `<source>`'s numbers with its accessor's layout.
struct Source {
    data: Vec<f32>,
    stride: usize,
    offset: usize,
    count: usize,
}

impl Source {
    fn get<const N: usize>(&self, i: usize) -> [f32; N] {
        let start = self.offset + i * self.stride;
        let mut out = [0.0; N];
        for (k, v) in out.iter_mut().enumerate() {
            *v = self.data.get(start + k).copied().unwrap_or(0.0);
        }
        out
    }
}

/// One `<input>` of a primitive list.
struct Input<'a> {
    semantic: &'a str,
    offset: usize,
    set: u32,
    source: &'a str,
}

/// Reads a `<geometry>`; geometry kinds other than `<mesh>` (splines, B-reps) give an
/// empty geometry and a warning.
pub(super) fn read(ctx: &Ctx, geometry: Node) -> Result<Geometry, LoadError> {
    let Some(mesh) = child(geometry, "mesh") else {
        ctx.warn(
            geometry,
            "only <mesh> geometries are read; this one is skipped",
        );
        return Ok(Geometry::default());
    };
    let mut reader = MeshReader::new(ctx, mesh)?;
    for prim in mesh.children().filter(|c| c.is_element()) {
        reader.primitive(ctx, prim)?;
    }
    Ok(reader.finish())
}

/// Where a primitive's corners keep their indices in its interleaved `<p>`.
struct Layout<'a> {
    /// Indices per corner.
    stride: usize,
    /// Offset of the position index.
    vertex: usize,
    /// Offset of the texture coordinate index and the URL of its source, when the
    /// primitive or its `<vertices>` has texture coordinates.
    uv: Option<(usize, &'a str)>,
}

/// One `<mesh>` being read: its geometry so far, and what each primitive list's corners
/// are checked against and merged into. The primitives share one vertex list, so a
/// corner seen in an earlier list is not added again.
struct MeshReader<'a, 'input> {
    mesh: Node<'a, 'input>,
    vertices: Node<'a, 'input>,
    /// URL of the `<source>` the positions come from.
    position_source: &'a str,
    /// URL of texture coordinates given in `<vertices>`, used by primitives that give
    /// none of their own.
    vertex_uv_source: Option<&'a str>,
    /// The `<source>`s read so far, by URL.
    sources: HashMap<&'a str, Source>,
    /// Whether each position has been reached by an index yet, for the outline.
    first_seen: Vec<bool>,
    /// Positions in the order the index lists first reach them.
    outline_indices: Vec<u32>,
    /// (position index, texture coordinate index or `u32::MAX`) → mesh vertex.
    remap: HashMap<(u32, u32), u32>,
    out: Geometry,
}

impl<'a, 'input> MeshReader<'a, 'input> {
    /// Reads the mesh's `<vertices>` and its positions: every primitive indexes them.
    fn new(ctx: &Ctx, mesh: Node<'a, 'input>) -> Result<Self, LoadError> {
        let vertices = child(mesh, "vertices")
            .ok_or_else(|| ctx.error(mesh, "a <mesh> needs a <vertices> element"))?;
        let vertex_inputs = inputs(ctx, vertices)?;
        let position_source = vertex_inputs
            .iter()
            .find(|i| i.semantic == "POSITION")
            .ok_or_else(|| ctx.error(vertices, "<vertices> has no POSITION input"))?
            .source;
        let vertex_uv_source = vertex_inputs
            .iter()
            .find(|i| i.semantic == "TEXCOORD")
            .map(|i| i.source);
        let mut sources = HashMap::new();
        load_source(ctx, mesh, position_source, &mut sources)?;
        let position_count = sources[position_source].count;
        Ok(MeshReader {
            mesh,
            vertices,
            position_source,
            vertex_uv_source,
            sources,
            first_seen: vec![false; position_count],
            outline_indices: Vec::new(),
            remap: HashMap::new(),
            out: Geometry::default(),
        })
    }

    /// Adds the triangles of one child of the `<mesh>`; children that are not polygon
    /// lists are skipped, lines with a warning since they have no area to light.
    fn primitive(&mut self, ctx: &Ctx, prim: Node<'a, 'input>) -> Result<(), LoadError> {
        let kind = prim.tag_name().name();
        if !matches!(
            kind,
            "triangles" | "polylist" | "polygons" | "trifans" | "tristrips"
        ) {
            if matches!(kind, "lines" | "linestrips") {
                ctx.warn(prim, "lines have no area; skipped");
            }
            return Ok(());
        }
        let layout = self.layout(ctx, prim)?;
        let symbol_index = self.symbol(ctx, prim)?;
        for IndexList {
            indices,
            sizes,
            shape,
        } in index_lists(ctx, prim, kind)?
        {
            let local = self.corners(ctx, prim, &layout, &indices)?;
            let before = self.out.triangles.len();
            triangulate(&local, &sizes, shape, &mut self.out.triangles)
                .map_err(|e| ctx.error(prim, e.to_string()))?;
            let added = self.out.triangles.len() - before;
            self.out
                .triangle_symbols
                .extend(std::iter::repeat_n(symbol_index, added));
        }
        Ok(())
    }

    /// The primitive's index layout, its texture coordinate source read: its own
    /// lowest `TEXCOORD` set, else the one of `<vertices>` at the position's offset.
    fn layout(&mut self, ctx: &Ctx, prim: Node<'a, 'input>) -> Result<Layout<'a>, LoadError> {
        let prim_inputs = inputs(ctx, prim)?;
        let stride = prim_inputs.iter().map(|i| i.offset + 1).max().unwrap_or(0);
        let vertex = prim_inputs
            .iter()
            .find(|i| i.semantic == "VERTEX")
            .ok_or_else(|| ctx.error(prim, "no VERTEX input"))?;
        if vertex.source.strip_prefix('#') != self.vertices.attribute("id") {
            return Err(ctx.error(
                prim,
                format!(
                    "the VERTEX input '{}' is not this mesh's <vertices>",
                    vertex.source
                ),
            ));
        }
        let uv_input = prim_inputs
            .iter()
            .filter(|i| i.semantic == "TEXCOORD")
            .min_by_key(|i| i.set);
        let uv = match (uv_input, self.vertex_uv_source) {
            (Some(i), _) => Some((i.offset, i.source)),
            (None, Some(s)) => Some((vertex.offset, s)),
            (None, None) => None,
        };
        if let Some((_, s)) = uv {
            load_source(ctx, self.mesh, s, &mut self.sources)?;
        }
        Ok(Layout {
            stride,
            vertex: vertex.offset,
            uv,
        })
    }

    /// The index into `symbols` of the primitive's material symbol, added on first use.
    fn symbol(&mut self, ctx: &Ctx, prim: Node) -> Result<u16, LoadError> {
        let symbol = prim.attribute("material").unwrap_or("").to_string();
        let symbols = &mut self.out.symbols;
        let symbol_index = match symbols.iter().position(|s| *s == symbol) {
            Some(i) => i,
            None => {
                symbols.push(symbol);
                symbols.len() - 1
            }
        };
        u16::try_from(symbol_index)
            .map_err(|_| ctx.error(prim, "more than 65535 material symbols in one mesh"))
    }

    /// The mesh vertex of each corner of one `<p>`, adding the vertices not met
    /// before; indices are checked against their sources here, so that a bad file
    /// is refused rather than read out of bounds.
    fn corners(
        &mut self,
        ctx: &Ctx,
        prim: Node,
        layout: &Layout,
        indices: &[u32],
    ) -> Result<Vec<u32>, LoadError> {
        let stride = layout.stride;
        if !indices.len().is_multiple_of(stride) {
            return Err(ctx.error(
                prim,
                format!(
                    "<p> has {} indices, not a multiple of the {stride} inputs",
                    indices.len()
                ),
            ));
        }
        // Looked up once per list, not per corner.
        let positions = &self.sources[self.position_source];
        let position_count = positions.count;
        let uvs = layout.uv.map(|(o, s)| (o, &self.sources[s]));
        let corners = indices.len() / stride;
        let mut local = Vec::with_capacity(corners);
        for c in 0..corners {
            let p = indices[c * stride + layout.vertex];
            if p as usize >= position_count {
                return Err(ctx.error(
                    prim,
                    format!(
                        "vertex index {p} is out of range: the positions have {position_count}"
                    ),
                ));
            }
            let t = match uvs {
                Some((o, source)) => {
                    let t = indices[c * stride + o];
                    if t as usize >= source.count {
                        return Err(ctx.error(
                            prim,
                            format!(
                                "texture coordinate index {t} is out of range: the source has {}",
                                source.count
                            ),
                        ));
                    }
                    t
                }
                None => u32::MAX,
            };
            if !self.first_seen[p as usize] {
                self.first_seen[p as usize] = true;
                self.outline_indices.push(p);
            }
            let next = self.out.positions.len() as u32;
            let v = *self.remap.entry((p, t)).or_insert(next);
            if v == next {
                let [x, y, z] = positions.get::<3>(p as usize);
                self.out.positions.push(Vec3::new(x, y, z));
                let uv = match uvs {
                    Some((_, source)) => {
                        let [u, v] = source.get::<2>(t as usize);
                        Vec2::new(u, 1.0 - v)
                    }
                    None => Vec2::ZERO,
                };
                self.out.uvs.push(uv);
            }
            local.push(v);
        }
        Ok(local)
    }

    /// The geometry, without texture coordinates when none was given, and with its
    /// outline of distinct positions.
    fn finish(mut self) -> Geometry {
        if self.out.uvs.iter().all(|&uv| uv == Vec2::ZERO) {
            self.out.uvs.clear();
        }
        for p in self.outline_indices {
            let [x, y, z] = self.sources[self.position_source].get::<3>(p as usize);
            let v = Vec3::new(x, y, z);
            if !self.out.outline.contains(&v) {
                self.out.outline.push(v);
            }
        }
        self.out
    }
}

/// How the corners of an index list form triangles.
#[derive(Clone, Copy)]
enum Shape {
    /// Consecutive triangles.
    Triangles,
    /// Consecutive polygons of the given sizes, each a fan.
    Polygons,
    /// One fan over all corners.
    Fan,
    /// One strip over all corners, alternating winding.
    Strip,
}

/// One `<p>`: interleaved input indices, and how its corners form triangles.
struct IndexList {
    indices: Vec<u32>,
    /// Corners per polygon, for [`Shape::Polygons`].
    sizes: Vec<u32>,
    shape: Shape,
}

impl IndexList {
    fn new(indices: Vec<u32>, sizes: Vec<u32>, shape: Shape) -> Self {
        IndexList {
            indices,
            sizes,
            shape,
        }
    }
}

/// The index lists of a primitive with their polygon sizes.
fn index_lists(ctx: &Ctx, prim: Node, kind: &str) -> Result<Vec<IndexList>, LoadError> {
    let count = ctx.attr_u32(prim, "count", 0)? as usize;
    let mut out = Vec::new();
    match kind {
        "triangles" => {
            if let Some(p) = child(prim, "p") {
                out.push(IndexList::new(ctx.uints(p)?, Vec::new(), Shape::Triangles));
            }
        }
        "polylist" => {
            let vcount = match child(prim, "vcount") {
                Some(v) => ctx.uints(v)?,
                None if count == 0 => Vec::new(),
                None => return Err(ctx.error(prim, "a <polylist> needs a <vcount>")),
            };
            if vcount.len() != count {
                return Err(ctx.error(
                    prim,
                    format!(
                        "count=\"{count}\" but <vcount> lists {} polygons",
                        vcount.len()
                    ),
                ));
            }
            if let Some(p) = child(prim, "p") {
                out.push(IndexList::new(ctx.uints(p)?, vcount, Shape::Polygons));
            }
        }
        "polygons" => {
            // A polygon with holes (<ph>) keeps its outer boundary.
            let lists =
                children(prim, "p").chain(children(prim, "ph").filter_map(|ph| child(ph, "p")));
            for p in lists {
                out.push(IndexList::new(ctx.uints(p)?, Vec::new(), Shape::Fan));
            }
        }
        "trifans" => {
            for p in children(prim, "p") {
                out.push(IndexList::new(ctx.uints(p)?, Vec::new(), Shape::Fan));
            }
        }
        _ => {
            for p in children(prim, "p") {
                out.push(IndexList::new(ctx.uints(p)?, Vec::new(), Shape::Strip));
            }
        }
    }
    Ok(out)
}

/// A `<p>` whose corners do not make the triangles its primitive declares.
#[derive(Debug, Clone, PartialEq, Eq)]
enum CornerCountError {
    /// A `<polylist>`'s `<vcount>` sizes do not add up to the corners of its `<p>`.
    Sizes { total: u64, corners: usize },
    /// A `<triangles>` list whose corners are not a multiple of 3.
    NotTriangles { corners: usize },
}

impl fmt::Display for CornerCountError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CornerCountError::Sizes { total, corners } => write!(
                f,
                "the polygon sizes add up to {total} corners but <p> has {corners}"
            ),
            CornerCountError::NotTriangles { corners } => write!(
                f,
                "<p> has {corners} corners, not a whole number of triangles"
            ),
        }
    }
}

impl std::error::Error for CornerCountError {}

/// Appends the triangles of `corners` (mesh vertex per corner).
fn triangulate(
    corners: &[u32],
    sizes: &[u32],
    shape: Shape,
    out: &mut Vec<[u32; 3]>,
) -> Result<(), CornerCountError> {
    match shape {
        Shape::Polygons => {
            let total: u64 = sizes.iter().map(|&s| s as u64).sum();
            if total != corners.len() as u64 {
                return Err(CornerCountError::Sizes {
                    total,
                    corners: corners.len(),
                });
            }
            let mut start = 0;
            for &n in sizes {
                let n = n as usize;
                fan(&corners[start..start + n], out);
                start += n;
            }
        }
        Shape::Triangles => {
            if !corners.len().is_multiple_of(3) {
                return Err(CornerCountError::NotTriangles {
                    corners: corners.len(),
                });
            }
            out.extend(corners.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
        }
        Shape::Fan => fan(corners, out),
        Shape::Strip => {
            for i in 2..corners.len() {
                let (a, b, c) = (corners[i - 2], corners[i - 1], corners[i]);
                out.push(if i % 2 == 0 { [a, b, c] } else { [b, a, c] });
            }
        }
    }
    Ok(())
}

/// A polygon as a triangle fan (exact for the convex polygons exporters write).
fn fan(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    for i in 2..polygon.len() {
        out.push([polygon[0], polygon[i - 1], polygon[i]]);
    }
}

/// The `<input>`s of an element.
fn inputs<'a>(ctx: &Ctx, node: Node<'a, '_>) -> Result<Vec<Input<'a>>, LoadError> {
    children(node, "input")
        .map(|i| {
            Ok(Input {
                semantic: i.attribute("semantic").unwrap_or(""),
                offset: ctx.attr_u32(i, "offset", 0)? as usize,
                set: ctx.attr_u32(i, "set", 0)?,
                source: i
                    .attribute("source")
                    .ok_or_else(|| ctx.error(i, "an <input> needs a source"))?,
            })
        })
        .collect()
}

/// Reads the `<source>` a URL names (once).
fn load_source<'a>(
    ctx: &Ctx,
    mesh: Node,
    url: &'a str,
    sources: &mut HashMap<&'a str, Source>,
) -> Result<(), LoadError> {
    if sources.contains_key(url) {
        return Ok(());
    }
    let source = ctx.resolve(url, "source", mesh)?;
    let array = child(source, "float_array")
        .ok_or_else(|| ctx.error(source, "expected a <float_array>"))?;
    let data = ctx.floats(array)?;
    let declared = ctx.attr_u32(array, "count", data.len() as u32)? as usize;
    if declared != data.len() {
        return Err(ctx.error(
            array,
            format!(
                "count=\"{declared}\" but the array holds {} numbers",
                data.len()
            ),
        ));
    }
    let accessor = super::xml::path(source, &["technique_common", "accessor"])
        .ok_or_else(|| ctx.error(source, "expected <technique_common><accessor>"))?;
    let stride = ctx.attr_u32(accessor, "stride", 1)?.max(1) as usize;
    let offset = ctx.attr_u32(accessor, "offset", 0)? as usize;
    let count = ctx.attr_u32(accessor, "count", 0)? as usize;
    let params = children(accessor, "param").count().max(1);
    if count > 0 && offset + (count - 1) * stride + params.min(stride) > data.len() {
        return Err(ctx.error(
            accessor,
            format!(
                "count=\"{count}\" stride=\"{stride}\" needs more than the {} numbers of the array",
                data.len()
            ),
        ));
    }
    sources.insert(
        url,
        Source {
            data,
            stride,
            offset,
            count,
        },
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_counts_that_make_no_triangles_are_refused() {
        let mut out = Vec::new();
        let sizes = triangulate(&[0, 1, 2, 3], &[3, 3], Shape::Polygons, &mut out);
        assert_eq!(
            sizes.unwrap_err().to_string(),
            "the polygon sizes add up to 6 corners but <p> has 4"
        );
        let triangles = triangulate(&[0, 1, 2, 3], &[], Shape::Triangles, &mut out);
        assert_eq!(
            triangles.unwrap_err().to_string(),
            "<p> has 4 corners, not a whole number of triangles"
        );
        triangulate(&[0, 1, 2, 3], &[4], Shape::Polygons, &mut out).unwrap();
        assert_eq!(out, [[0, 1, 2], [0, 2, 3]]);
    }
}
