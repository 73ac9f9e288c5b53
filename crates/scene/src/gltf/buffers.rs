//! Where a glTF file's bytes live: buffers and images given as base64 `data:` URIs,
//! as files beside the `.gltf` (relative URIs, percent-encoded), or in the `.glb` BIN
//! chunk; and the buffer views that slice them.

use super::Builder;
use crate::error::LoadError;
use crate::files::{Files, ReadError};
use crate::image_file::{TextureError, decode_texture};
use crate::material::Texture;
use base64::Engine;
use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
use gltf_json as json;
use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// Standard base64 that accepts data with or without `=` padding, as exporters differ.
const BASE64: GeneralPurpose = GeneralPurpose::new(
    &base64::alphabet::STANDARD,
    GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

const EXTERNAL_HINT: &str = "external files are looked up relative to the folder of the \
    .gltf file: keep them beside it, or export a single .glb";

/// What a URI points at.
enum Uri<'u> {
    /// The decoded payload of a `data:` URI.
    Data(Vec<u8>),
    /// A file, relative to the `.gltf`'s folder (or absolute, from a `file:` URI),
    /// %-escapes decoded; [`Files::resolve`] decides whether it may be read.
    File { path: PathBuf, written: &'u str },
}

/// Reads every buffer of the document: `buffers[i]` is the returned vector's item i,
/// cut to its declared `byteLength`.
pub(super) fn load_buffers<'a>(
    path: &Path,
    root: &json::Root,
    bin: Option<&'a [u8]>,
    files: &Files,
) -> Result<Vec<Cow<'a, [u8]>>, LoadError> {
    let mut out = Vec::with_capacity(root.buffers.len());
    for (i, buffer) in root.buffers.iter().enumerate() {
        let loc = format!("buffers[{i}]");
        let data: Cow<'a, [u8]> = match (&buffer.uri, bin) {
            (None, Some(bin)) if i == 0 => Cow::Borrowed(bin),
            (None, _) => {
                return Err(LoadError::at(
                    path,
                    loc,
                    "the buffer has no uri and no .glb BIN chunk",
                )
                .with_hint("only buffers[0] of a .glb may omit its uri"));
            }
            (Some(uri), _) => match parse_uri(path, uri, &loc)? {
                Uri::Data(bytes) => Cow::Owned(bytes),
                Uri::File {
                    path: relative,
                    written,
                } => {
                    let file = files.resolve(path, &loc, written, &relative)?;
                    // At most byteLength bytes: the file may be far longer.
                    match files.read(path, &loc, &file, Some(buffer.byte_length.0)) {
                        Ok(bytes) => Cow::Owned(bytes),
                        Err(e) => return Err(file_error(path, &loc, written, &file, e)),
                    }
                }
            },
        };
        let declared = buffer.byte_length.0;
        if (data.len() as u64) < declared {
            return Err(LoadError::at(
                path,
                loc,
                format!(
                    "byteLength is {declared} but the data has only {} bytes",
                    data.len()
                ),
            )
            .with_hint("the buffer is truncated or belongs to another export: export again"));
        }
        out.push(match data {
            Cow::Borrowed(b) => Cow::Borrowed(&b[..declared as usize]),
            Cow::Owned(mut b) => {
                b.truncate(declared as usize);
                Cow::Owned(b)
            }
        });
    }
    Ok(out)
}

/// The error of an external file that cannot be read: `missing file NAME` when it does
/// not exist.
fn file_error(path: &Path, loc: &str, written: &str, file: &Path, e: ReadError) -> LoadError {
    let message = match e {
        ReadError::Missing => format!("missing file {written} (looked for {})", file.display()),
        ReadError::Io(m) => format!("cannot read {written} ({}): {m}", file.display()),
        ReadError::Budget(e) => return e,
    };
    LoadError::at(path, loc, message).with_hint(EXTERNAL_HINT)
}

/// Parses a buffer or image URI: a base64 `data:` URI, a relative reference to a file
/// beside the `.gltf`, or a `file:` URI (an absolute path, which [`Files::resolve`]
/// refuses unless told otherwise). Other schemes (http, ftp) are refused: a scene must
/// be self-contained.
fn parse_uri<'u>(path: &Path, uri: &'u str, loc: &str) -> Result<Uri<'u>, LoadError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((header, payload)) = rest.split_once(',') else {
            return Err(LoadError::at(
                path,
                loc,
                "the data: URI has no ',' before its payload",
            ));
        };
        if !header.ends_with(";base64") {
            return Err(
                LoadError::at(path, loc, "only base64 data: URIs are supported")
                    .with_hint("glTF requires base64 data URIs (data:...;base64,...)"),
            );
        }
        return BASE64.decode(payload).map(Uri::Data).map_err(|e| {
            LoadError::at(path, loc, format!("the data: URI is not valid base64: {e}"))
        });
    }
    if let Some(rest) = uri.strip_prefix("file://") {
        let decoded = percent_decode(rest)
            .ok_or_else(|| LoadError::at(path, loc, format!("URI {uri} has a bad %-escape")))?;
        return Ok(Uri::File {
            path: PathBuf::from(decoded),
            written: uri,
        });
    }
    let scheme = uri.split_once(':').map(|(s, _)| s);
    if scheme.is_some_and(|s| {
        s.len() > 1
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    }) {
        return Err(
            LoadError::at(path, loc, format!("URI {uri} is not a relative file path"))
                .with_hint(EXTERNAL_HINT),
        );
    }
    let decoded = percent_decode(uri)
        .ok_or_else(|| LoadError::at(path, loc, format!("URI {uri} has a bad %-escape")))?;
    Ok(Uri::File {
        path: PathBuf::from(decoded),
        written: uri,
    })
}

/// Undoes URI %-escapes (RFC 3986 §2.1), so `my%20room.bin` names `my room.bin`.
fn percent_decode(s: &str) -> Option<String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

impl Builder<'_> {
    /// The bytes of `bufferViews[index]` and its byte stride, bounds-checked against its
    /// buffer. `loc` names the referrer for errors.
    pub(super) fn view(
        &self,
        index: json::Index<json::buffer::View>,
        loc: &str,
    ) -> Result<(&[u8], Option<usize>), LoadError> {
        let i = index.value();
        let here = format!("bufferViews[{i}] (from {loc})");
        let view = self.root.buffer_views.get(i).ok_or_else(|| {
            self.err(
                &here,
                format!(
                    "no such buffer view ({} in the file)",
                    self.root.buffer_views.len()
                ),
            )
        })?;
        let b = view.buffer.value();
        let buffer = self.buffers.get(b).ok_or_else(|| {
            self.err(
                &here,
                format!(
                    "buffer {b} does not exist ({} in the file)",
                    self.buffers.len()
                ),
            )
        })?;
        let offset = view.byte_offset.map_or(0, |o| o.0);
        let length = view.byte_length.0;
        let end = offset
            .checked_add(length)
            .filter(|&e| e <= buffer.len() as u64);
        let Some(end) = end else {
            return Err(self.err(
                &here,
                format!(
                    "bytes {offset}..{} lie outside buffers[{b}] of {} bytes",
                    offset.saturating_add(length),
                    buffer.len()
                ),
            ));
        };
        Ok((
            &buffer[offset as usize..end as usize],
            view.byte_stride.map(|s| s.0),
        ))
    }

    /// Decodes `images[index]` (sRGB) into a linear texture, whether it is a file, a data
    /// URI or a buffer view.
    pub(super) fn image(
        &self,
        index: json::Index<json::Image>,
        loc: &str,
    ) -> Result<Texture, LoadError> {
        let i = index.value();
        let here = format!("images[{i}]");
        let image = self.root.images.get(i).ok_or_else(|| {
            self.err(
                loc,
                format!(
                    "image {i} does not exist ({} in the file)",
                    self.root.images.len()
                ),
            )
        })?;
        // Decoding errors are placed at the image; a refusal for memory is already placed.
        let relocate = |e: TextureError, what: &str| match e {
            TextureError::Refused(e) => e,
            TextureError::Unreadable(e) => {
                LoadError::at(self.path, &here, format!("{what}: {}", e.message))
                    .with_hint("invlight decodes PNG, JPEG, BMP and TGA textures")
            }
        };
        let decode =
            |bytes: &[u8], file: &Path| decode_texture(bytes, file, self.path, &here, self.files);
        match (&image.uri, image.buffer_view) {
            (Some(uri), _) => match parse_uri(self.path, uri, &here)? {
                Uri::Data(bytes) => decode(&bytes, self.path).map_err(|e| relocate(e, "data: URI")),
                Uri::File {
                    path: relative,
                    written,
                } => {
                    let file = self.files.resolve(self.path, &here, written, &relative)?;
                    let bytes = self
                        .files
                        .read(self.path, &here, &file, None)
                        .map_err(|e| file_error(self.path, &here, written, &file, e))?;
                    decode(&bytes, &file).map_err(|e| relocate(e, written))
                }
            },
            (None, Some(view)) => {
                let (bytes, _) = self.view(view, &here)?;
                decode(bytes, self.path).map_err(|e| relocate(e, "buffer view"))
            }
            (None, None) => Err(self.err(&here, "the image has neither uri nor bufferView")),
        }
    }
}

/// The bytes of a file a glTF refers to by `uri` (resolved as buffers and images are)
/// or by buffer view, with the path of the file when it is one: the path errors inside
/// the file name and its own references (an IES `TILT=<file>`) are resolved from.
pub(super) struct Referenced<'b> {
    /// The bytes.
    pub bytes: Cow<'b, [u8]>,
    /// The file they were read from; `None` for a data: URI or a buffer view.
    pub file: Option<PathBuf>,
}

impl Builder<'_> {
    /// The bytes of a `uri` or `bufferView` reference at `loc` (an `EXT_lights_ies`
    /// profile).
    pub(super) fn referenced(
        &self,
        uri: Option<&str>,
        view: Option<json::Index<json::buffer::View>>,
        loc: &str,
    ) -> Result<Referenced<'_>, LoadError> {
        match (uri, view) {
            (Some(uri), _) => match parse_uri(self.path, uri, loc)? {
                Uri::Data(bytes) => Ok(Referenced {
                    bytes: Cow::Owned(bytes),
                    file: None,
                }),
                Uri::File {
                    path: relative,
                    written,
                } => {
                    let file = self.files.resolve(self.path, loc, written, &relative)?;
                    match self.files.read(self.path, loc, &file, None) {
                        Ok(bytes) => Ok(Referenced {
                            bytes: Cow::Owned(bytes),
                            file: Some(file),
                        }),
                        Err(e) => Err(file_error(self.path, loc, written, &file, e)),
                    }
                }
            },
            (None, Some(view)) => Ok(Referenced {
                bytes: Cow::Borrowed(self.view(view, loc)?.0),
                file: None,
            }),
            (None, None) => Err(self.err(loc, "neither uri nor bufferView is given")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_escapes_decode() {
        assert_eq!(
            percent_decode("my%20room.bin").as_deref(),
            Some("my room.bin")
        );
        assert_eq!(percent_decode("a%2"), None);
        assert_eq!(
            percent_decode("plain/x.bin").as_deref(),
            Some("plain/x.bin")
        );
    }

    #[test]
    fn data_uris_with_and_without_padding() {
        let p = Path::new("x.gltf");
        for uri in [
            "data:application/octet-stream;base64,AQID",
            "data:;base64,AQI",
        ] {
            match parse_uri(p, uri, "buffers[0]").unwrap() {
                Uri::Data(b) => assert_eq!(&b[..2], &[1, 2]),
                Uri::File { .. } => panic!("{uri} taken for a file"),
            }
        }
        assert!(parse_uri(p, "data:text/plain,hello", "buffers[0]").is_err());
        assert!(parse_uri(p, "https://example.org/a.bin", "buffers[0]").is_err());
        match parse_uri(p, "file:///etc/host%20name", "buffers[0]").unwrap() {
            Uri::File { path, .. } => assert_eq!(path, PathBuf::from("/etc/host name")),
            Uri::Data(_) => panic!("a file: URI taken for data"),
        }
    }
}
