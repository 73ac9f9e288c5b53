//! What every part of the COLLADA reader needs from the XML tree: element lookup by
//! local name and by `#id` URL, number lists, and error locations (`line 12: <polylist>
//! in <geometry id="Cone-mesh">`).

use crate::error::LoadError;
use crate::files::Files;
use roxmltree::{Document, Node};
use std::collections::HashMap;
use std::path::Path;

/// The parsed document with its id index, and the file it came from.
pub(super) struct Ctx<'a, 'input> {
    pub path: &'a Path,
    /// The scene's folder tree and memory budget.
    pub files: &'a Files,
    pub doc: &'a Document<'input>,
    ids: HashMap<&'a str, Node<'a, 'input>>,
}

impl<'a, 'input> Ctx<'a, 'input> {
    pub fn new(path: &'a Path, doc: &'a Document<'input>, files: &'a Files) -> Self {
        let ids = doc
            .descendants()
            .filter(|n| n.is_element())
            .filter_map(|n| n.attribute("id").map(|id| (id, n)))
            .collect();
        Ctx {
            path,
            files,
            doc,
            ids,
        }
    }

    /// The element a URL (`#id`) points to, expected to be a `<tag>`; `from` is the
    /// referring element, named in errors.
    pub fn resolve(&self, url: &str, tag: &str, from: Node) -> Result<Node<'a, 'input>, LoadError> {
        let id = url.strip_prefix('#').unwrap_or(url);
        match self.ids.get(id) {
            Some(n) if n.tag_name().name() == tag => Ok(*n),
            Some(n) => Err(self.error(
                from,
                format!(
                    "'{url}' names a <{}>, expected a <{tag}>",
                    n.tag_name().name()
                ),
            )),
            None => Err(self.error(from, format!("no <{tag}> has the id '{id}'"))),
        }
    }

    /// The element with this id, whatever its tag.
    pub fn by_id(&self, id: &str) -> Option<Node<'a, 'input>> {
        self.ids.get(id.strip_prefix('#').unwrap_or(id)).copied()
    }

    /// An error located at an element.
    pub fn error(&self, node: Node, message: impl Into<String>) -> LoadError {
        LoadError::at(self.path, self.location(node), message)
    }

    /// `line N: <tag id="…">`, with the enclosing element that has an id when the
    /// element itself has none.
    pub fn location(&self, node: Node) -> String {
        let pos = self.doc.text_pos_at(node.range().start);
        let mut s = format!("line {}: {}", pos.row, describe(node));
        if node.attribute("id").is_none()
            && let Some(owner) = node
                .ancestors()
                .skip(1)
                .find(|a| a.attribute("id").is_some())
        {
            s.push_str(" in ");
            s.push_str(&describe(owner));
        }
        s
    }

    /// Warns on stderr about an element that is read past.
    pub fn warn(&self, node: Node, message: &str) {
        eprintln!(
            "warning: {}: {}: {message}",
            self.path.display(),
            self.location(node)
        );
    }

    /// The numbers of an element's text.
    pub fn floats(&self, node: Node) -> Result<Vec<f32>, LoadError> {
        let text = node.text().unwrap_or("");
        let mut out = Vec::with_capacity(text.len() / 8);
        for token in text.split_ascii_whitespace() {
            match token.parse::<f32>() {
                Ok(v) if v.is_finite() => out.push(v),
                _ => {
                    return Err(self.error(node, format!("expected a number, found '{token}'")));
                }
            }
        }
        Ok(out)
    }

    /// The non-negative integers of an element's text (index lists, counts).
    pub fn uints(&self, node: Node) -> Result<Vec<u32>, LoadError> {
        let text = node.text().unwrap_or("");
        let mut out = Vec::with_capacity(text.len() / 3);
        for token in text.split_ascii_whitespace() {
            match token.parse::<u32>() {
                Ok(v) => out.push(v),
                Err(_) => {
                    return Err(self.error(
                        node,
                        format!("expected a non-negative integer, found '{token}'"),
                    ));
                }
            }
        }
        Ok(out)
    }

    /// Exactly `N` numbers.
    pub fn floats_n<const N: usize>(&self, node: Node) -> Result<[f32; N], LoadError> {
        let v = self.floats(node)?;
        <[f32; N]>::try_from(v.as_slice())
            .map_err(|_| self.error(node, format!("expected {N} numbers, found {}", v.len())))
    }

    /// A numeric attribute, `default` when absent.
    pub fn attr_u32(&self, node: Node, name: &str, default: u32) -> Result<u32, LoadError> {
        match node.attribute(name) {
            None => Ok(default),
            Some(s) => s.trim().parse().map_err(|_| {
                self.error(
                    node,
                    format!("attribute {name}=\"{s}\" is not a non-negative integer"),
                )
            }),
        }
    }
}

/// `<tag id="…">` (or `name`, or bare).
pub(super) fn describe(node: Node) -> String {
    let tag = node.tag_name().name();
    match (node.attribute("id"), node.attribute("name")) {
        (Some(id), _) => format!("<{tag} id=\"{id}\">"),
        (None, Some(name)) => format!("<{tag} name=\"{name}\">"),
        (None, None) => format!("<{tag}>"),
    }
}

/// The first child element called `name`.
pub(super) fn child<'a, 'input>(node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
    node.children()
        .find(|c| c.is_element() && c.tag_name().name() == name)
}

/// The child elements called `name`.
pub(super) fn children<'a, 'input: 'a>(
    node: Node<'a, 'input>,
    name: &'a str,
) -> impl Iterator<Item = Node<'a, 'input>> + 'a {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// The element at the end of a path of child names.
pub(super) fn path<'a, 'input>(node: Node<'a, 'input>, names: &[&str]) -> Option<Node<'a, 'input>> {
    names.iter().try_fold(node, |n, name| child(n, name))
}
