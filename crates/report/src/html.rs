//! One self-contained HTML page: pictures embedded as `data:` URIs, plots as inline
//! SVG, the style in the page, no script — so it opens from a file in any browser with
//! no network, and prints to A4 (`@page`, figures kept whole across pages).

use base64::Engine;
use std::fmt::Write;

/// The page's style: readable on screen, A4 in print.
const STYLE: &str = r#"
@page { size: A4; margin: 14mm 12mm; }
* { box-sizing: border-box; }
body { font-family: "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; color: #1a1a1a;
  max-width: 186mm; margin: 0 auto; padding: 10px; line-height: 1.4; font-size: 11pt; }
h1 { font-size: 20pt; margin: 0 0 4px; }
h2 { font-size: 14pt; margin: 22px 0 8px; border-bottom: 2px solid #3b528b; padding-bottom: 2px; }
p.sub { color: #555; margin: 0 0 12px; }
.answer { border: 2px solid #21918c; border-radius: 6px; padding: 8px 12px; background: #f3fbfa; }
.answer p { margin: 4px 0; }
.meets { color: #1a7f37; font-weight: bold; } .fails { color: #b42318; font-weight: bold; }
.cannot { color: #9a6700; font-weight: bold; }
table { border-collapse: collapse; width: 100%; font-size: 9pt; margin: 6px 0; }
th, td { border: 1px solid #ccc; padding: 2px 5px; text-align: right; }
th { background: #eef0f6; } td.l, th.l { text-align: left; }
figure { margin: 10px 0; break-inside: avoid; page-break-inside: avoid; }
figure img, figure svg { width: 100%; height: auto; display: block; border: 1px solid #ddd; }
figcaption { font-size: 9pt; color: #333; margin-top: 3px; }
.gallery { display: grid; grid-template-columns: 1fr 1fr; gap: 8px; }
dl { display: grid; grid-template-columns: max-content 1fr; gap: 2px 12px; margin: 6px 0; }
dt { font-weight: bold; } dd { margin: 0; }
svg text { font-family: "DejaVu Sans", Arial, sans-serif; }
@media print { h2 { break-after: avoid; } .gallery { grid-template-columns: 1fr 1fr; } }
"#;

/// `text` with `&`, `<`, `>` and `"` escaped.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

/// A PNG file's bytes as an `<img>` with a `data:` URI.
pub fn img_png(bytes: &[u8], alt: &str) -> String {
    format!(
        r#"<img alt="{}" src="data:image/png;base64,{}">"#,
        escape(alt),
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// A figure: `content` (an `<img>` or inline SVG) with its caption.
pub fn figure(content: &str, caption: &str) -> String {
    format!("<figure>{content}<figcaption>{caption}</figcaption></figure>\n")
}

/// A table with a header row; cells are HTML, the first column left-aligned.
pub fn table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut out = String::from("<table><tr>");
    for (i, h) in header.iter().enumerate() {
        let class = if i == 0 { " class=\"l\"" } else { "" };
        let _ = write!(out, "<th{class}>{}</th>", escape(h));
    }
    out.push_str("</tr>\n");
    for row in rows {
        out.push_str("<tr>");
        for (i, cell) in row.iter().enumerate() {
            let class = if i == 0 { " class=\"l\"" } else { "" };
            let _ = write!(out, "<td{class}>{cell}</td>");
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</table>\n");
    out
}

/// A page being written: a title and sections.
pub struct Page {
    title: String,
    body: String,
}

impl Page {
    /// A page titled `title` with `subtitle` under it.
    pub fn new(title: &str, subtitle: &str) -> Page {
        Page {
            title: title.to_string(),
            body: format!(
                "<h1>{}</h1>\n<p class=\"sub\">{}</p>\n",
                escape(title),
                escape(subtitle)
            ),
        }
    }

    /// Adds a section headed `heading` holding `html`.
    pub fn section(&mut self, heading: &str, html: &str) {
        let _ = write!(self.body, "<h2>{}</h2>\n{html}\n", escape(heading));
    }

    /// The document.
    pub fn finish(&self) -> String {
        format!(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{}</body>\n</html>\n",
            escape(&self.title),
            self.body
        )
    }
}

/// Every reference of `html` that a browser would fetch from outside the page: a `src`
/// or `href` that is not a `data:` URI or a fragment, a CSS `url(` that is not `data:`,
/// an `@import`. A report must have none (it is read offline and sent by mail).
pub fn external_references(html: &str) -> Vec<String> {
    let mut out = Vec::new();
    let lower = html.to_ascii_lowercase();
    for attr in ["src=\"", "href=\"", "src='", "href='", "url("] {
        let mut from = 0;
        while let Some(i) = lower[from..].find(attr) {
            let start = from + i + attr.len();
            let rest = lower[start..].trim_start_matches(['"', '\'', ' ']);
            if !(rest.starts_with("data:") || rest.starts_with('#')) {
                out.push(html[start..(start + 60).min(html.len())].to_string());
            }
            from = start;
        }
    }
    if lower.contains("@import") {
        out.push("@import".into());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pages_are_escaped_and_reference_nothing_outside() {
        let mut page = Page::new("a <b> & \"c\"", "sub");
        page.section("S", &table(&["x", "y"], &[vec!["1".into(), "2".into()]]));
        page.section("P", &img_png(&[137, 80, 78, 71], "pixel"));
        let html = page.finish();
        assert!(html.contains("<title>a &lt;b&gt; &amp; &quot;c&quot;</title>"));
        assert!(html.contains("src=\"data:image/png;base64,"));
        assert!(
            external_references(&html).is_empty(),
            "{:?}",
            external_references(&html)
        );
        let bad =
            "<img src=\"http://x/y.png\"><link href='style.css'><style>@import 'a.css';</style>";
        assert_eq!(external_references(bad).len(), 3);
    }
}
