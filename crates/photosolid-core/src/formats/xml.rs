//! The XML helpers shared by the TM-33 reader and the GLDF container
//! reader: decoding, parsing with positions, element lookup, and the errors
//! that name the line, the column and the element.
//!
//! Parsing is `roxmltree` with its defaults: a document type declaration
//! (DTD) is refused, so no entity can expand (no "billion laughs"), and
//! every node keeps its byte range, from which an error gets its line.

use std::path::Path;

use roxmltree::{Document, Node};

use crate::error::{ErrorKind, Location, ParseError};

/// The text of an XML document: UTF-8 (the encoding both TM-33 and GLDF
/// prescribe), a leading byte-order mark dropped.
///
/// # Errors
/// Invalid UTF-8, naming the line of the first bad byte.
pub(crate) fn decode<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str, ParseError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    std::str::from_utf8(bytes).map_err(|e| {
        let at = e.valid_up_to();
        let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
        ParseError {
            path: path.to_path_buf(),
            location: Location::line(line),
            kind: ErrorKind::Invalid,
            expected: "UTF-8 text (XML)".into(),
            found: format!("a byte that is not UTF-8 at offset {at}"),
        }
    })
}

/// Parse `text` as XML; `what` names the document kind for the message.
///
/// # Errors
/// Malformed XML (or a DTD), at the line and column the parser stopped.
pub(crate) fn parse<'a>(text: &'a str, path: &Path, what: &str) -> Result<Document<'a>, ParseError> {
    Document::parse(text).map_err(|e| {
        // The parser gives no position for a document that ends too early
        // (1:1): the end of the text is where it stopped.
        let (location, found) = match e {
            roxmltree::Error::UnclosedRootNode | roxmltree::Error::UnexpectedEndOfStream => {
                let line = 1 + text.bytes().filter(|&b| b == b'\n').count();
                let column = 1 + text.len() - text.rfind('\n').map_or(0, |i| i + 1);
                (
                    Location::at(line, column),
                    format!("{e}: the text ends here (a truncated file?)"),
                )
            }
            _ => {
                let pos = e.pos();
                (Location::at(pos.row as usize, pos.col as usize), e.to_string())
            }
        };
        ParseError {
            path: path.to_path_buf(),
            location,
            kind: ErrorKind::Invalid,
            expected: format!("well-formed XML ({what}) without a DTD"),
            found,
        }
    })
}

/// Line and column where `node` starts.
pub(crate) fn location(node: Node<'_, '_>) -> Location {
    let pos = node.document().text_pos_at(node.range().start);
    Location::at(pos.row as usize, pos.col as usize)
}

/// The element's path from the root, e.g. `IESTM33-22/Emitter/LuminousData`.
pub(crate) fn element_path(node: Node<'_, '_>) -> String {
    let mut names: Vec<&str> = node
        .ancestors()
        .filter(|n| n.is_element())
        .map(|n| n.tag_name().name())
        .collect();
    names.reverse();
    names.join("/")
}

/// An error at `node`: the message names the element by its path.
pub(crate) fn error_at(
    path: &Path,
    node: Node<'_, '_>,
    kind: ErrorKind,
    expected: impl std::fmt::Display,
    found: impl std::fmt::Display,
) -> ParseError {
    ParseError {
        path: path.to_path_buf(),
        location: location(node),
        kind,
        expected: format!("in <{}>: {expected}", element_path(node)),
        found: found.to_string(),
    }
}

/// The first child element of `node` whose local name (namespace ignored) is one of `names`.
pub(crate) fn child<'a, 'i>(node: Node<'a, 'i>, names: &[&str]) -> Option<Node<'a, 'i>> {
    node.children()
        .find(|c| c.is_element() && names.contains(&c.tag_name().name()))
}

/// Every child element of `node` named `name`.
pub(crate) fn children<'a, 'i: 'a>(node: Node<'a, 'i>, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// The trimmed text of the first child element named one of `names`; `None` when absent or empty.
pub(crate) fn child_text<'a>(node: Node<'a, '_>, names: &[&str]) -> Option<&'a str> {
    child(node, names)
        .and_then(|c| c.text())
        .map(str::trim)
        .filter(|t| !t.is_empty())
}

/// The child named one of `names` as a finite number; `None` when absent.
///
/// # Errors
/// Text that is not a finite number, at the child's line.
pub(crate) fn child_number(path: &Path, node: Node<'_, '_>, names: &[&str]) -> Result<Option<f64>, ParseError> {
    let Some(c) = child(node, names) else {
        return Ok(None);
    };
    let text = c.text().map(str::trim).unwrap_or("");
    if text.is_empty() {
        return Ok(None);
    }
    match crate::formats::scan::parse_f64(text.as_bytes()) {
        Some(v) => Ok(Some(v)),
        None => Err(error_at(
            path,
            c,
            ErrorKind::Invalid,
            "a finite number",
            format!("`{text}`"),
        )),
    }
}

/// `s` escaped for XML text and attribute values (`&`, `<`, `>`, `"`, `'`);
/// characters XML 1.0 cannot hold (controls below U+0020 other than tab and
/// line ends, and the noncharacters U+FFFE and U+FFFF) are dropped.
pub(crate) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(ch),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => {}
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escape_round_trips_through_the_parser() {
        let nasty = "a<b & \"c\" 'd' > e\u{1}\u{FFFF}\u{FFFE}";
        let text = format!("<r x=\"{0}\">{0}</r>", escape(nasty));
        let doc = parse(&text, Path::new("t.xml"), "test").unwrap();
        let r = doc.root_element();
        assert_eq!(r.text(), Some("a<b & \"c\" 'd' > e"));
        assert_eq!(r.attribute("x"), Some("a<b & \"c\" 'd' > e"));
    }

    #[test]
    fn errors_carry_line_and_element() {
        let e = parse("<a>\n<b>\n</a>", Path::new("t.xml"), "test").unwrap_err();
        assert_eq!(e.location.line, 3, "{e}");
        let doc = parse("<a>\n <b>x</b></a>", Path::new("t.xml"), "test").unwrap();
        let b = child(doc.root_element(), &["b"]).unwrap();
        let e = child_number(Path::new("t.xml"), doc.root_element(), &["b"]).unwrap_err();
        assert_eq!(location(b).line, 2);
        assert_eq!(e.location.line, 2);
        assert!(e.to_string().contains("<a/b>"), "{e}");
        // A DTD (entity expansion) is refused.
        let bomb = "<!DOCTYPE a [<!ENTITY x \"xx\">]><a>&x;</a>";
        assert!(parse(bomb, Path::new("t.xml"), "test").is_err());
        let e = decode(b"<a>\n\xff</a>", Path::new("t.xml")).unwrap_err();
        assert_eq!(e.location.line, 2);
    }
}
