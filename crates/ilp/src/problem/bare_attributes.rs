//! ILPSolver's problem files as the thesis prints them (appendix D) write
//! `maxIterations=1000` without quotes, which is not XML. This pass quotes such values
//! before the XML parser sees them, warning about each, and leaves comments, processing
//! instructions, CDATA and text alone.

use invlight_scene::Diagnostic;
use std::path::Path;

/// Quotes attribute values written without quotes (`maxIterations=1000`, as printed in
/// the thesis' appendix D), warning about each. Comments, processing instructions,
/// CDATA and text are left alone.
pub(super) fn quote_bare_attributes(
    text: &str,
    path: &Path,
    warnings: &mut Vec<Diagnostic>,
) -> String {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len() + 16);
    let mut i = 0;
    let mut line = 1u32;
    let mut in_tag = false;
    let mut quote: Option<u8> = None;
    while i < bytes.len() {
        let c = bytes[i];
        if !in_tag {
            if text[i..].starts_with("<!--")
                || text[i..].starts_with("<?")
                || text[i..].starts_with("<![CDATA[")
            {
                let end = if text[i..].starts_with("<!--") {
                    "-->"
                } else if text[i..].starts_with("<?") {
                    "?>"
                } else {
                    "]]>"
                };
                let stop = text[i..]
                    .find(end)
                    .map(|k| i + k + end.len())
                    .unwrap_or(bytes.len());
                line += text[i..stop].matches('\n').count() as u32;
                out.push_str(&text[i..stop]);
                i = stop;
                continue;
            }
            if c == b'<' {
                in_tag = true;
            }
        } else if let Some(q) = quote {
            if c == q {
                quote = None;
            }
        } else if c == b'"' || c == b'\'' {
            quote = Some(c);
        } else if c == b'>' {
            in_tag = false;
        } else if c == b'=' {
            let mut j = i + 1;
            while j < bytes.len() && (bytes[j] == b' ' || bytes[j] == b'\t') {
                j += 1;
            }
            if j < bytes.len() && bytes[j] != b'"' && bytes[j] != b'\'' {
                let mut k = j;
                while k < bytes.len()
                    && !bytes[k].is_ascii_whitespace()
                    && bytes[k] != b'>'
                    && !(bytes[k] == b'/' && bytes.get(k + 1) == Some(&b'>'))
                {
                    k += 1;
                }
                let value = &text[j..k];
                warnings.push(
                    Diagnostic::at_line(
                        path,
                        line,
                        format!("attribute value {value} is not quoted; read as \"{value}\""),
                    )
                    .with_hint("XML wants attribute values in quotes"),
                );
                out.push_str("=\"");
                out.push_str(value);
                out.push('"');
                i = k;
                continue;
            }
        }
        if c == b'\n' {
            line += 1;
        }
        let ch_len = text[i..].chars().next().map_or(1, char::len_utf8);
        out.push_str(&text[i..i + ch_len]);
        i += ch_len;
    }
    out
}
