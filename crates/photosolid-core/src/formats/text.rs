//! Byte-level text handling shared by the IES and EULUMDAT readers.
//!
//! Photometric files are ASCII numbers wrapped in text fields of unknown
//! encoding (UTF-8, Latin-1/CP1252, Shift-JIS), with LF, CRLF or CR line ends,
//! an optional UTF-8 BOM, and sometimes a trailing Ctrl-Z or NUL padding.
//! The readers therefore work on bytes: numbers are scanned and parsed straight
//! from the byte slices ([`crate::formats::scan`]: no `String` per token, no
//! allocation per value) and only text fields are decoded, with the encoding
//! detected once per file.

use std::path::Path;

use crate::error::{ErrorKind, Location, ParseError};

/// Text encoding detected for a file's text fields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// Valid UTF-8 (or plain ASCII).
    Utf8,
    /// Shift-JIS (Japanese manufacturers' files).
    ShiftJis,
    /// Windows-1252, a superset of printable Latin-1; never fails.
    Windows1252,
}

/// A photometric file's bytes prepared for reading: BOM and end-of-file
/// junk stripped, encoding detected, line starts known.
pub struct Source<'a> {
    /// The file name used in error messages.
    pub path: &'a Path,
    /// The content, without BOM and trailing Ctrl-Z/NUL bytes.
    pub bytes: &'a [u8],
    /// Detected encoding of text fields.
    pub encoding: Encoding,
}

impl<'a> Source<'a> {
    /// Prepare `bytes` read from `path`.
    ///
    /// Fails on empty input and on UTF-16 (detected by its BOM or by NUL
    /// bytes in every other position), which no photometric tool writes.
    pub fn new(path: &'a Path, bytes: &'a [u8]) -> Result<Self, ParseError> {
        let mut b = bytes;
        if b.starts_with(&[0xEF, 0xBB, 0xBF]) {
            b = &b[3..];
        }
        if b.starts_with(&[0xFE, 0xFF]) || b.starts_with(&[0xFF, 0xFE]) {
            return Err(ParseError {
                path: path.to_path_buf(),
                location: Location::line(1),
                kind: ErrorKind::Unsupported,
                expected: "an 8-bit text file (ASCII, UTF-8, Latin-1 or Shift-JIS)".into(),
                found: "a UTF-16 byte-order mark; re-save the file as UTF-8".into(),
            });
        }
        // Trailing DOS end-of-file marks, NUL padding and whitespace carry no data.
        while let Some((&last, rest)) = b.split_last() {
            if last == 0x1A || last == 0 || last.is_ascii_whitespace() {
                b = rest;
            } else {
                break;
            }
        }
        if b.is_empty() {
            return Err(ParseError {
                path: path.to_path_buf(),
                location: Location::line(0),
                kind: ErrorKind::Invalid,
                expected: "a photometric file".into(),
                found: if bytes.is_empty() {
                    "an empty file".into()
                } else {
                    format!("{} bytes of padding (NUL, Ctrl-Z or blanks) and no data", bytes.len())
                },
            });
        }
        // `contains` on bytes is a vectorised memchr; locate only on failure.
        if let Some(pos) = b.contains(&0).then(|| b.iter().position(|&c| c == 0)).flatten() {
            let (line, col) = line_col(b, pos);
            return Err(ParseError {
                path: path.to_path_buf(),
                location: Location::at(line, col),
                kind: ErrorKind::Invalid,
                expected: "text".into(),
                found: "a NUL byte (binary data or UTF-16 text)".into(),
            });
        }
        Ok(Self {
            path,
            bytes: b,
            encoding: detect_encoding(b),
        })
    }

    /// Decode a text field with the file's encoding, trimming surrounding blanks.
    pub fn text(&self, raw: &[u8]) -> String {
        decode(raw, self.encoding).trim().to_string()
    }

    /// An `Invalid` error at `loc`.
    pub fn invalid(&self, loc: Location, expected: impl Into<String>, found: impl Into<String>) -> ParseError {
        ParseError {
            path: self.path.to_path_buf(),
            location: loc,
            kind: ErrorKind::Invalid,
            expected: expected.into(),
            found: found.into(),
        }
    }

    /// An `Unsupported` error at `loc`.
    pub fn unsupported(&self, loc: Location, expected: impl Into<String>, found: impl Into<String>) -> ParseError {
        ParseError {
            kind: ErrorKind::Unsupported,
            ..self.invalid(loc, expected, found)
        }
    }

    /// Iterate over the lines (LF, CRLF or CR ends), numbered from 1.
    pub fn lines(&self) -> Lines<'a> {
        Lines {
            bytes: self.bytes,
            pos: 0,
            line: 0,
        }
    }
}

/// 1-based line and column of byte offset `pos`.
pub fn line_col(bytes: &[u8], pos: usize) -> (usize, usize) {
    let mut line = 1;
    let mut start = 0;
    let mut i = 0;
    while i < pos {
        match bytes[i] {
            b'\n' => {
                line += 1;
                start = i + 1;
            }
            b'\r' if bytes.get(i + 1) != Some(&b'\n') => {
                line += 1;
                start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    (line, pos - start + 1)
}

fn detect_encoding(b: &[u8]) -> Encoding {
    if b.is_ascii() || std::str::from_utf8(b).is_ok() {
        return Encoding::Utf8;
    }
    // Shift-JIS text has high bytes in pairs (lead 0x81-0x9F/0xE0-0xFC, trail
    // mostly >= 0x80 for kana and kanji); Latin-1 text has isolated high
    // bytes between ASCII letters. Choose Shift-JIS only when it decodes
    // cleanly and most high bytes come in high pairs.
    let (_, _, had_errors) = encoding_rs::SHIFT_JIS.decode(b);
    if !had_errors {
        let mut pairs = 0usize;
        let mut singles = 0usize;
        let mut i = 0;
        while i < b.len() {
            let c = b[i];
            if c >= 0x80 {
                if i + 1 < b.len() && b[i + 1] >= 0x80 {
                    pairs += 1;
                    i += 2;
                    continue;
                }
                singles += 1;
            }
            i += 1;
        }
        if pairs > 0 && pairs >= singles {
            return Encoding::ShiftJis;
        }
    }
    Encoding::Windows1252
}

/// Decode `raw` text bytes with `enc`; never fails (invalid bytes become U+FFFD).
pub fn decode(raw: &[u8], enc: Encoding) -> std::borrow::Cow<'_, str> {
    match enc {
        Encoding::Utf8 => String::from_utf8_lossy(raw),
        Encoding::ShiftJis => encoding_rs::SHIFT_JIS.decode(raw).0,
        Encoding::Windows1252 => encoding_rs::WINDOWS_1252.decode(raw).0,
    }
}

/// Lines of a [`Source`], each with its 1-based number and its byte offset.
#[derive(Clone)]
pub struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

/// One line: number, offset of its first byte, content without the line end.
#[derive(Debug, Clone, Copy)]
pub struct Line<'a> {
    /// 1-based line number.
    pub number: usize,
    /// Byte offset of the line's start in the source.
    pub offset: usize,
    /// Content without the line terminator.
    pub bytes: &'a [u8],
}

impl<'a> Lines<'a> {
    /// Byte offset of the next unread line.
    pub fn offset(&self) -> usize {
        self.pos
    }
    /// Number of the last line returned (0 before the first).
    pub fn line_number(&self) -> usize {
        self.line
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Line<'a>;
    fn next(&mut self) -> Option<Line<'a>> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let start = self.pos;
        let rest = &self.bytes[start..];
        let end = rest
            .iter()
            .position(|&c| c == b'\n' || c == b'\r')
            .map_or(self.bytes.len(), |p| start + p);
        let mut next = end;
        if next < self.bytes.len() {
            if self.bytes[next] == b'\r' && self.bytes.get(next + 1) == Some(&b'\n') {
                next += 2;
            } else {
                next += 1;
            }
        }
        self.pos = next;
        self.line += 1;
        Some(Line {
            number: self.line,
            offset: start,
            bytes: &self.bytes[start..end],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_handle_all_endings() {
        let p = Path::new("x");
        let src = Source::new(p, b"a\r\nb\rc\nd").unwrap();
        let l: Vec<_> = src.lines().map(|l| (l.number, l.bytes.to_vec())).collect();
        assert_eq!(
            l,
            vec![
                (1, b"a".to_vec()),
                (2, b"b".to_vec()),
                (3, b"c".to_vec()),
                (4, b"d".to_vec())
            ]
        );
    }

    #[test]
    fn source_strips_bom_ctrl_z_and_rejects_utf16() {
        let p = Path::new("x");
        assert_eq!(Source::new(p, b"\xEF\xBB\xBFab\x1A\x1A").unwrap().bytes, b"ab");
        assert!(Source::new(p, b"\xFE\xFF\x001").is_err());
        assert!(Source::new(p, b"").is_err());
        assert!(Source::new(p, b"\0\0\0").is_err());
        assert_eq!(Source::new(p, b"caf\xE9 1").unwrap().encoding, Encoding::Windows1252);
    }
}
