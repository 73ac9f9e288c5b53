//! Files of a few hundred bytes that state huge counts — a bufferless glTF accessor of
//! 178 956 970 VEC3, sparse and index counts, COLLADA `<float_array count>`, OBJ face
//! indices, IES and EULUMDAT table sizes, PNG and JPEG dimensions — each loaded under
//! a counting global allocator: memory must follow what the file holds and what it
//! references, so each is handled (a clear error, or the small scene it really holds)
//! with at most 200 MB allocated at the peak.
//!
//! The allocator also refuses to let the live total pass 1 GiB, so that a regression
//! aborts this test binary ("memory allocation of N bytes failed") instead of taking the
//! machine's memory. The tests share one lock, so each peak is its own. Each case's
//! peak and wall time are printed (`--nocapture`); time is reported, not asserted.

use base64::Engine;
use invlight_scene::{LoadError, LoadOptions, Scene, Vec3, load, parse_ies, parse_ldt};
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// The most a hostile file may take at the peak.
const PEAK_LIMIT: usize = 200 << 20;

/// Past this many live bytes the allocator refuses.
const CAP: usize = 1 << 30;

/// The system allocator, counting the live bytes and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

impl Counting {
    /// Counts `size` more bytes, or refuses them past [`CAP`].
    fn take(size: usize) -> bool {
        let live = LIVE.fetch_add(size, Ordering::Relaxed) + size;
        if live > CAP {
            LIVE.fetch_sub(size, Ordering::Relaxed);
            return false;
        }
        PEAK.fetch_max(live, Ordering::Relaxed);
        true
    }
}

// SAFETY: every call is passed on to `System` unchanged; only the counters are added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !Counting::take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: the caller's layout, as `GlobalAlloc::alloc` requires.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !Counting::take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as in `alloc`.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: `ptr` came from this allocator with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() && !Counting::take(new_size - layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as in `dealloc`, with the caller's new size.
        let out = unsafe { System.realloc(ptr, layout, new_size) };
        if out.is_null() {
            if new_size > layout.size() {
                LIVE.fetch_sub(new_size - layout.size(), Ordering::Relaxed);
            }
        } else if new_size < layout.size() {
            LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
        }
        out
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Held by each test for its whole run, so that the peaks do not mix.
static SERIAL: Mutex<()> = Mutex::new(());

/// Runs `f`, asserts that the bytes it allocated at its peak (above what was live when
/// it started) stay under [`PEAK_LIMIT`], and prints the peak and the wall time.
fn within_limit<T>(case: &str, f: impl FnOnce() -> T) -> T {
    let base = LIVE.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    let start = Instant::now();
    let out = f();
    let seconds = start.elapsed().as_secs_f64();
    let peak = PEAK.load(Ordering::Relaxed).saturating_sub(base);
    eprintln!("{case}: peak {:.2} MB, {seconds:.4} s", peak as f64 / 1e6);
    assert!(
        peak < PEAK_LIMIT,
        "{case}: {peak} bytes at the peak, past {PEAK_LIMIT}"
    );
    out
}

/// A folder of its own for one test's files.
fn folder() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn budget(bytes: u64) -> LoadOptions {
    LoadOptions {
        max_memory: bytes,
        ..LoadOptions::default()
    }
}

/// Loads `path` under the peak limit.
fn load_within(case: &str, path: &Path, options: &LoadOptions) -> Result<Scene, LoadError> {
    within_limit(case, || load(path, options))
}

/// Asserts that `e` is at `location` and says each of `words`.
fn says(e: &LoadError, location: &str, words: &[&str]) {
    assert_eq!(e.location, location, "{e}");
    for w in words {
        assert!(e.message.contains(w), "{w:?} not in: {e}");
    }
}

/// The claimed count of the bufferless POSITION accessors below: 2.1 GB of VEC3.
const CLAIMED: u64 = 178_956_970;

/// The binary buffer of the bufferless quad: its six u16 indices (bytes 0..12), the
/// sparse accessor's three u16 indices (12..18, padded to 20) and its three VEC3 values
/// (20..56), which move vertices 1, 2 and 3 off the origin.
fn quad_buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for i in [0u16, 1, 2, 0, 2, 3, 1, 2, 3, 0] {
        b.extend(i.to_le_bytes());
    }
    for v in [1.0f32, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0] {
        b.extend(v.to_le_bytes());
    }
    b
}

/// The JSON of a quad whose POSITION accessor has no buffer view (zeros, spec
/// §3.6.2.3), claims [`CLAIMED`] elements and gets its three non-zero vertices from a
/// sparse substitution; its indices reach vertex 3. `buffer` is the `buffers[0]` entry.
fn quad_json(buffer: &str) -> String {
    format!(
        r#"{{"asset": {{"version": "2.0"}},
        "buffers": [{buffer}],
        "bufferViews": [
            {{"buffer": 0, "byteOffset": 0, "byteLength": 12}},
            {{"buffer": 0, "byteOffset": 12, "byteLength": 6}},
            {{"buffer": 0, "byteOffset": 20, "byteLength": 36}}],
        "accessors": [
            {{"componentType": 5126, "count": {CLAIMED}, "type": "VEC3",
              "sparse": {{"count": 3, "indices": {{"bufferView": 1, "componentType": 5123}},
                         "values": {{"bufferView": 2}}}}}},
            {{"bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
        "nodes": [{{"name": "Quad", "mesh": 0}}],
        "scenes": [{{"nodes": [0]}}]}}"#
    )
}

fn data_uri(bytes: &[u8]) -> String {
    format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// The quad as the file holds it: four vertices, two triangles.
fn assert_quad(scene: &Scene) {
    assert_eq!(scene.meshes.len(), 1);
    let mesh = &scene.meshes[0];
    assert_eq!(
        mesh.positions,
        [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, 1.0), Vec3::Z]
    );
    assert_eq!(mesh.triangles, [[0, 1, 2], [0, 2, 3]]);
}

/// A glTF 2.0 binary container (spec chapter 4) of `json` and `bin`.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().next_multiple_of(4), 0);
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((12 + 8 + json.len() as u32 + 8 + bin.len() as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

/// A bufferless POSITION accessor is materialised only as far as the primitive's
/// indices reach: the 2.1 GB it claims are never allocated, whatever the budget, and
/// the quad the file holds loads (from a `data:` URI and from a `.glb`).
#[test]
fn bufferless_positions_follow_their_indices() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = folder();
    let buffer = quad_buffer();
    let gltf = quad_json(&format!(
        r#"{{"byteLength": {}, "uri": "{}"}}"#,
        buffer.len(),
        data_uri(&buffer)
    ));
    let gltf = write(dir.path(), "quad.gltf", gltf.as_bytes());
    let bin = write(
        dir.path(),
        "quad.glb",
        &glb(
            &quad_json(&format!(r#"{{"byteLength": {}}}"#, buffer.len())),
            &buffer,
        ),
    );
    for (case, path) in [
        ("bufferless quad (.gltf)", &gltf),
        ("bufferless quad (.glb)", &bin),
    ] {
        let scene = load_within(case, path, &LoadOptions::default()).unwrap();
        assert_quad(&scene);
        // Within a budget of 1 MB too: nothing is charged for the claimed count.
        assert_quad(&load(path, &budget(1 << 20)).unwrap());
    }
}

/// Without indices every claimed vertex is referenced, so the budget decides: past
/// `--max-memory` the accessor is refused with its count and the figure, before
/// anything is allocated. The same holds for a bufferless index accessor.
#[test]
fn bufferless_accessors_without_indices_are_refused_past_the_budget() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = folder();
    let path = write(
        dir.path(),
        "no_buffer.gltf",
        format!(
            r#"{{"asset": {{"version": "2.0"}},
            "accessors": [{{"componentType": 5126, "count": {CLAIMED}, "type": "VEC3"}}],
            "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
            "nodes": [{{"name": "Bomb", "mesh": 0}}],
            "scenes": [{{"nodes": [0]}}]}}"#
        )
        .as_bytes(),
    );
    let e = load_within("no buffer, no indices", &path, &budget(100 << 20)).unwrap_err();
    says(
        &e,
        "accessors[0] (from meshes[0].primitives[0].attributes.POSITION)",
        &["178956970 VEC3", "2.1 GB"],
    );
    assert!(e.hint.as_deref().unwrap().contains("--max-memory"), "{e}");

    // Indices of their own that are bufferless: 1e9 zeros claimed.
    let buffer = quad_buffer();
    let json = quad_json(&format!(
        r#"{{"byteLength": {}, "uri": "{}"}}"#,
        buffer.len(),
        data_uri(&buffer)
    ))
    .replace(
        r#"{"bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR"}"#,
        r#"{"componentType": 5125, "count": 1000000000, "type": "SCALAR"}"#,
    );
    assert!(json.contains("1000000000"));
    let path = write(dir.path(), "bufferless_indices.gltf", json.as_bytes());
    let e = load_within("bufferless indices", &path, &budget(100 << 20)).unwrap_err();
    says(
        &e,
        "accessors[1] (from meshes[0].primitives[0].indices)",
        &["1000000000 SCALAR", "4.0 GB"],
    );
}

/// A sparse count is held to the bytes its views hold, and a substitution past the
/// claimed count is refused.
#[test]
fn sparse_counts_are_held_to_their_views() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = folder();
    let buffer = quad_buffer();
    let json = quad_json(&format!(
        r#"{{"byteLength": {}, "uri": "{}"}}"#,
        buffer.len(),
        data_uri(&buffer)
    ));
    let huge = json.replacen(r#""count": 3"#, r#""count": 4294967295"#, 1);
    let path = write(dir.path(), "sparse_count.gltf", huge.as_bytes());
    let e = load_within("sparse count 2³²−1", &path, &LoadOptions::default()).unwrap_err();
    says(
        &e,
        "accessors[0] (from meshes[0].primitives[0].attributes.POSITION)",
        &["sparse.indices: 4294967295 entries overrun their 6-byte buffer view"],
    );
    // The indices reach vertex 3; a claimed count of 3 leaves it out.
    let short = json.replacen(&format!(r#""count": {CLAIMED}"#), r#""count": 3"#, 1);
    let path = write(dir.path(), "short.gltf", short.as_bytes());
    let e = load(&path, &LoadOptions::default()).unwrap_err();
    says(
        &e,
        "accessors[0] (from meshes[0].primitives[0].attributes.POSITION)",
        &["sparse.indices[2] = 3 is not below count 3"],
    );
}

/// The CRC-32 of PNG chunks (ISO 3309, as the PNG specification §5.5 gives it).
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A true 4 × 1 PNG whose header is made to declare `width` × `height` (its CRC
/// recomputed, so only the size is a lie).
fn png_claiming(width: u32, height: u32) -> Vec<u8> {
    let mut png = Vec::new();
    image::RgbImage::new(4, 1)
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    // Signature (8), then the IHDR chunk: length (4), "IHDR" (4), width, height, ….
    assert_eq!(&png[12..16], b"IHDR");
    png[16..20].copy_from_slice(&width.to_be_bytes());
    png[20..24].copy_from_slice(&height.to_be_bytes());
    let crc = crc32(&png[12..29]);
    png[29..33].copy_from_slice(&crc.to_be_bytes());
    png
}

/// A true 8 × 8 JPEG whose frame header (SOF0) is made to declare `width` × `height`.
fn jpeg_claiming(width: u16, height: u16) -> Vec<u8> {
    let mut jpeg = Vec::new();
    image::RgbImage::new(8, 8)
        .write_to(
            &mut std::io::Cursor::new(&mut jpeg),
            image::ImageFormat::Jpeg,
        )
        .unwrap();
    let sof = jpeg.windows(2).position(|w| w == [0xFF, 0xC0]).unwrap();
    // Marker (2), length (2), precision (1), then height and width.
    jpeg[sof + 5..sof + 7].copy_from_slice(&height.to_be_bytes());
    jpeg[sof + 7..sof + 9].copy_from_slice(&width.to_be_bytes());
    jpeg
}

/// A glTF floor whose material's base colour is `image`, embedded as a `data:` URI.
fn textured_floor(image: &[u8], mime: &str) -> String {
    let mut b = Vec::new();
    for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0] {
        b.extend(v.to_le_bytes());
    }
    format!(
        r#"{{"asset": {{"version": "2.0"}},
        "buffers": [{{"byteLength": 36, "uri": "{}"}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}}],
        "images": [{{"uri": "data:{mime};base64,{}"}}],
        "textures": [{{"source": 0}}],
        "materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}}],
        "nodes": [{{"name": "Floor", "mesh": 0}}],
        "scenes": [{{"nodes": [0]}}]}}"#,
        data_uri(&b),
        base64::engine::general_purpose::STANDARD.encode(image)
    )
}

/// An image whose header declares more pixels than its bytes can encode is refused as
/// unreadable, naming both figures, before the decoder allocates its canvas; one that
/// could hold them is still held to the budget.
#[test]
fn images_are_held_to_what_their_bytes_can_encode() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = folder();
    let png = write(
        dir.path(),
        "png.gltf",
        textured_floor(&png_claiming(16_000, 16_000), "image/png").as_bytes(),
    );
    let e = load_within("PNG claiming 16000²", &png, &LoadOptions::default()).unwrap_err();
    says(&e, "images[0]", &["16000 × 16000", "can hold at most"]);
    let jpeg = write(
        dir.path(),
        "jpeg.gltf",
        textured_floor(&jpeg_claiming(16_000, 16_000), "image/jpeg").as_bytes(),
    );
    let e = load_within("JPEG claiming 16000²", &jpeg, &LoadOptions::default()).unwrap_err();
    says(&e, "images[0]", &["16000 × 16000", "can hold at most"]);

    // A 4 × 1 PNG that says so decodes, and a budget below its pixels refuses it.
    let honest = write(
        dir.path(),
        "honest.gltf",
        textured_floor(&png_claiming(4, 1), "image/png").as_bytes(),
    );
    let scene = load(&honest, &LoadOptions::default()).unwrap();
    assert_eq!((scene.textures[0].width, scene.textures[0].height), (4, 1));
    let small = std::fs::metadata(&honest).unwrap().len() + 100;
    let e = load(&honest, &budget(small)).unwrap_err();
    says(&e, "images[0]", &["the 4 × 1 pixels"]);
}

/// COLLADA: a `<float_array count>` or an accessor count past the numbers present is
/// an error at that element.
#[test]
fn collada_counts_are_held_to_the_numbers_present() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = folder();
    let dae = |array_count: &str, accessor_count: &str| {
        format!(
            r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries>
    <geometry id="Tri-mesh" name="Tri">
      <mesh>
        <source id="Tri-positions">
          <float_array id="Tri-array" count="{array_count}">0 0 0 1 0 0 0 0 1</float_array>
          <technique_common>
            <accessor source="#Tri-array" count="{accessor_count}" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="Tri-vertices"><input semantic="POSITION" source="#Tri-positions"/></vertices>
        <triangles count="1"><input semantic="VERTEX" source="#Tri-vertices" offset="0"/><p>0 1 2</p></triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="Scene">
      <node id="Tri" name="Tri"><instance_geometry url="#Tri-mesh"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#Scene"/></scene>
</COLLADA>
"##
        )
    };
    let path = write(dir.path(), "ok.dae", dae("9", "3").as_bytes());
    assert_eq!(
        load(&path, &LoadOptions::default()).unwrap().meshes.len(),
        1
    );

    let path = write(dir.path(), "array.dae", dae("4000000000", "3").as_bytes());
    let e = load_within(
        "COLLADA float_array count 4e9",
        &path,
        &LoadOptions::default(),
    )
    .unwrap_err();
    says(
        &e,
        "line 7: <float_array id=\"Tri-array\">",
        &["count=\"4000000000\" but the array holds 9 numbers"],
    );
    let path = write(
        dir.path(),
        "accessor.dae",
        dae("9", "1000000000").as_bytes(),
    );
    let e = load_within("COLLADA accessor count 1e9", &path, &LoadOptions::default()).unwrap_err();
    says(
        &e,
        "line 9: <accessor> in <source id=\"Tri-positions\">",
        &["count=\"1000000000\"", "9 numbers"],
    );
}

/// OBJ: a face index past the vertices read so far is an error at its line.
#[test]
fn obj_indices_are_held_to_the_vertices_present() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let dir = folder();
    let path = write(
        dir.path(),
        "far.obj",
        b"o Tri\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 4000000000\n",
    );
    let e = load_within("OBJ face index 4e9", &path, &LoadOptions::default()).unwrap_err();
    says(&e, "line 5", &["4000000000"]);
}

/// IES and EULUMDAT: the largest tables their counts allow (10¹⁰ candela values) over
/// a handful of numbers are errors where the numbers run out.
#[test]
fn photometric_counts_are_held_to_the_numbers_present() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let ies = "IESNA:LM-63-2002\n[TEST] huge counts\nTILT=NONE\n\
        1 -1 1 100000 100000 1 2 0 0 0\n1 1 0\n0 90\n0\n100 50\n";
    let e = within_limit("IES 100000 × 100000 angles", || {
        parse_ies(ies.as_bytes(), Path::new("huge.ies"))
    })
    .unwrap_err();
    says(
        &e,
        "line 8",
        &["the file ends where a vertical angle was expected"],
    );

    let mut ldt: Vec<String> = [
        "huge counts",
        "1",
        "0",
        "100000",
        "0.0036",
        "100000",
        "0.0018",
        "R",
        "L",
        "N",
        "huge.ldt",
        "d",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
        "100",
        "100",
        "1",
        "0",
        "1",
        "1",
        "lamp",
        "1000",
        "3000",
        "80",
        "10",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    ldt.extend((0..10).map(|_| "0".to_string()));
    ldt.extend(["0", "90", "180", "270"].map(String::from));
    let ldt = ldt.join("\n") + "\n";
    let e = within_limit("LDT 100000 × 100000 angles", || {
        parse_ldt(ldt.as_bytes(), Path::new("huge.ldt"))
    })
    .unwrap_err();
    says(
        &e,
        "line 46",
        &["the file ends where a C angle was expected"],
    );
}
