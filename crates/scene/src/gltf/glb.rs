//! The binary glTF container (`.glb`, glTF 2.0 spec chapter 4): a 12-byte header, a JSON
//! chunk, then an optional BIN chunk that is the first buffer.
//!
//! Written here rather than taken from the `gltf` crate because its `Glb::from_slice`
//! subtracts the header size from the declared length unchecked, which panics on a
//! truncated or hostile file; every length here is checked against the bytes present.

use crate::error::LoadError;
use std::path::Path;

/// `glTF` in ASCII, the first four bytes of every `.glb`.
pub(super) const MAGIC: &[u8; 4] = b"glTF";
const JSON_CHUNK: u32 = 0x4E4F_534A;
const BIN_CHUNK: u32 = 0x004E_4942;

/// The two chunks invlight reads, borrowed from the file's bytes.
pub(super) struct Glb<'a> {
    /// The glTF JSON document.
    pub json: &'a [u8],
    /// The binary buffer (`buffers[0]` when its `uri` is absent).
    pub bin: Option<&'a [u8]>,
}

/// Splits a `.glb` file into its JSON and BIN chunks. Unknown chunk types are skipped,
/// as the spec requires.
pub(super) fn split<'a>(path: &Path, bytes: &'a [u8]) -> Result<Glb<'a>, LoadError> {
    let truncated = |location: &str, message: String| {
        LoadError::at(path, location, message)
            .with_hint("the .glb file is cut short: copy or export it again")
    };
    if bytes.len() < 12 {
        return Err(truncated(
            "GLB header",
            format!("12 bytes expected, the file has {}", bytes.len()),
        ));
    }
    let word =
        |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let version = word(4);
    if version != 2 {
        return Err(LoadError::at(
            path,
            "GLB header",
            format!("container version {version}, 2 expected"),
        )
        .with_hint("invlight reads glTF 2.0; convert glTF 1.0 files with an exporter"));
    }
    let length = word(8) as usize;
    if length > bytes.len() {
        return Err(truncated(
            "GLB header",
            format!(
                "the header says {length} bytes, the file has {}",
                bytes.len()
            ),
        ));
    }
    let mut json = None;
    let mut bin = None;
    let mut at = 12;
    let mut chunk = 0;
    while at < length {
        let name = |kind: Option<u32>| match kind {
            Some(JSON_CHUNK) => format!("GLB chunk {chunk} (JSON)"),
            Some(BIN_CHUNK) => format!("GLB chunk {chunk} (BIN)"),
            _ => format!("GLB chunk {chunk}"),
        };
        if length - at < 8 {
            return Err(truncated(
                &name(None),
                format!(
                    "an 8-byte chunk header expected, {} bytes remain",
                    length - at
                ),
            ));
        }
        let (size, kind) = (word(at) as usize, word(at + 4));
        let start = at + 8;
        if size > length - start {
            return Err(truncated(
                &name(Some(kind)),
                format!(
                    "the chunk says {size} bytes, {} remain in the file",
                    length - start
                ),
            ));
        }
        let data = &bytes[start..start + size];
        match kind {
            JSON_CHUNK if chunk == 0 => json = Some(data),
            BIN_CHUNK if chunk == 1 => bin = Some(data),
            _ if chunk == 0 => {
                return Err(
                    LoadError::at(path, name(Some(kind)), "the first chunk must be JSON")
                        .with_hint("the file is not a valid .glb: export it again"),
                );
            }
            _ => {}
        }
        at = start + size;
        chunk += 1;
    }
    match json {
        Some(json) => Ok(Glb { json, bin }),
        None => Err(truncated(
            "GLB chunk 0 (JSON)",
            "the JSON chunk is missing".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
        let mut chunks = Vec::new();
        chunks.extend((json.len() as u32).to_le_bytes());
        chunks.extend(JSON_CHUNK.to_le_bytes());
        chunks.extend(json);
        if let Some(bin) = bin {
            chunks.extend((bin.len() as u32).to_le_bytes());
            chunks.extend(BIN_CHUNK.to_le_bytes());
            chunks.extend(bin);
        }
        let mut out = MAGIC.to_vec();
        out.extend(2u32.to_le_bytes());
        out.extend((12 + chunks.len() as u32).to_le_bytes());
        out.extend(chunks);
        out
    }

    #[test]
    fn splits_json_and_bin() {
        let bytes = glb(b"{}  ", Some(&[1, 2, 3, 4]));
        let g = split(Path::new("a.glb"), &bytes).unwrap();
        assert_eq!(g.json, b"{}  ");
        assert_eq!(g.bin, Some(&[1u8, 2, 3, 4][..]));
    }

    #[test]
    fn every_truncation_is_an_error() {
        let bytes = glb(b"{}  ", Some(&[1, 2, 3, 4]));
        for cut in 0..bytes.len() {
            let mut short = bytes[..cut].to_vec();
            // A consistent header that still overruns its chunks, and the raw cut.
            let e = split(Path::new("a.glb"), &short).err();
            assert!(e.is_some(), "cut at {cut} accepted");
            if cut >= 12 {
                short[8..12].copy_from_slice(&(cut as u32).to_le_bytes());
                if let Err(e) = split(Path::new("a.glb"), &short) {
                    assert!(e.location.starts_with("GLB chunk"), "{e}");
                } else {
                    // Cutting exactly between the chunks leaves a valid JSON-only file.
                    assert_eq!(cut, 12 + 8 + 4);
                }
            }
        }
    }
}
