//! Byte-level text handling shared by the IES and EULUMDAT readers.
//!
//! Photometric files are ASCII numbers wrapped in text fields of unknown
//! encoding (UTF-8, Latin-1/CP1252, Shift-JIS), with LF, CRLF or CR line ends,
//! an optional UTF-8 BOM, and sometimes a trailing Ctrl-Z or NUL padding.
//! The readers therefore work on bytes: numbers are parsed straight from the
//! byte slices (no `String` per token, no allocation per value) and only text
//! fields are decoded, with the encoding detected once per file.

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
            b'\r' => {
                if bytes.get(i + 1) != Some(&b'\n') {
                    line += 1;
                    start = i + 1;
                }
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

/// A numeric token: its bytes and where it starts.
#[derive(Debug, Clone, Copy)]
pub struct Token<'a> {
    /// The token's bytes (never empty).
    pub bytes: &'a [u8],
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

impl<'a> Token<'a> {
    /// Where the token starts.
    pub fn location(&self) -> Location {
        Location::at(self.line, self.column)
    }
    /// The token as text for messages (lossy, shortened to 40 characters).
    pub fn display(&self) -> String {
        let s = String::from_utf8_lossy(self.bytes);
        if s.chars().count() > 40 {
            format!("`{}...`", s.chars().take(40).collect::<String>())
        } else {
            format!("`{s}`")
        }
    }
}

/// Splits bytes into tokens separated by blanks, commas and line ends,
/// tracking line and column. `;` and `!` start a comment to the end of the
/// line (seen in hand-edited files; never part of a number).
#[derive(Clone)]
pub struct Tokens<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    line_start: usize,
    comma_separates: bool,
}

impl<'a> Tokens<'a> {
    /// Tokens of `bytes[offset..]`, where `offset` starts line `line`.
    /// With `comma_separates` a comma is a separator (IES); otherwise it is
    /// part of the token (EULUMDAT's decimal comma).
    pub fn new(bytes: &'a [u8], offset: usize, line: usize, comma_separates: bool) -> Self {
        Self {
            bytes,
            pos: offset,
            line,
            line_start: offset,
            comma_separates,
        }
    }

    /// Current line (of the next unread byte).
    pub fn line(&self) -> usize {
        self.line
    }

    /// Location of the end of input, for "found end of file" errors.
    pub fn end_location(&self) -> Location {
        Location::line(self.line)
    }

    /// Skip separators; true when a token follows.
    fn skip(&mut self) -> bool {
        let b = self.bytes;
        while self.pos < b.len() {
            match b[self.pos] {
                b'\n' => {
                    self.pos += 1;
                    self.line += 1;
                    self.line_start = self.pos;
                }
                b'\r' => {
                    self.pos += 1;
                    if b.get(self.pos) == Some(&b'\n') {
                        self.pos += 1;
                    }
                    self.line += 1;
                    self.line_start = self.pos;
                }
                b' ' | b'\t' | 0x0B | 0x0C | 0x1A | 0 => self.pos += 1,
                b',' if self.comma_separates => self.pos += 1,
                b';' | b'!' => {
                    while self.pos < b.len() && b[self.pos] != b'\n' && b[self.pos] != b'\r' {
                        self.pos += 1;
                    }
                }
                _ => return true,
            }
        }
        false
    }

    /// The next token without consuming it.
    pub fn peek(&mut self) -> Option<Token<'a>> {
        let save = (self.pos, self.line, self.line_start);
        let t = self.next();
        (self.pos, self.line, self.line_start) = save;
        t
    }

    /// Parse the next token as a finite number; `what` names the expected value.
    pub fn number(&mut self, src: &Source<'_>, what: &str) -> Result<f64, ParseError> {
        match self.next() {
            None => Err(src.invalid(self.end_location(), what.to_string(), "end of file")),
            Some(t) => parse_f64(t.bytes).ok_or_else(|| src.invalid(t.location(), what.to_string(), t.display())),
        }
    }

    /// Parse the next token as an integer (a number with zero fraction, as
    /// old files write `3.0`) within `[min, max]`.
    pub fn integer(&mut self, src: &Source<'_>, what: &str, min: i64, max: i64) -> Result<i64, ParseError> {
        let t = match self.next() {
            None => return Err(src.invalid(self.end_location(), what.to_string(), "end of file")),
            Some(t) => t,
        };
        let expected = || format!("{what} (integer {min}..={max})");
        let v = parse_f64(t.bytes).ok_or_else(|| src.invalid(t.location(), expected(), t.display()))?;
        if v.fract() != 0.0 || v < min as f64 || v > max as f64 {
            return Err(src.invalid(t.location(), expected(), t.display()));
        }
        Ok(v as i64)
    }

    /// Fill `out` with the next `n` numbers, `what(i)` naming the i-th for errors.
    pub fn numbers_into(
        &mut self,
        src: &Source<'_>,
        n: usize,
        out: &mut Vec<f64>,
        what: &dyn Fn(usize) -> String,
    ) -> Result<(), ParseError> {
        out.reserve(n);
        for i in 0..n {
            match self.next() {
                None => {
                    return Err(src.invalid(
                        self.end_location(),
                        format!("{} ({} of {n} values read)", what(i), i),
                        "end of file",
                    ))
                }
                Some(t) => match parse_f64(t.bytes) {
                    Some(v) => out.push(v),
                    None => return Err(src.invalid(t.location(), what(i), t.display())),
                },
            }
        }
        Ok(())
    }

    /// Count the remaining tokens (used to size-check headers and to warn
    /// about trailing values) without allocating.
    pub fn count_remaining(&self) -> usize {
        let mut c = self.clone();
        let mut n = 0;
        while c.next().is_some() {
            n += 1;
        }
        n
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = Token<'a>;
    fn next(&mut self) -> Option<Token<'a>> {
        if !self.skip() {
            return None;
        }
        let b = self.bytes;
        let start = self.pos;
        while self.pos < b.len() {
            match b[self.pos] {
                b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C | 0x1A | 0 | b';' | b'!' => break,
                b',' if self.comma_separates => break,
                _ => self.pos += 1,
            }
        }
        Some(Token {
            bytes: &b[start..self.pos],
            line: self.line,
            column: start - self.line_start + 1,
        })
    }
}

/// Exact powers of ten representable in f64 (Clinger's fast path).
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// Parse a plain decimal (`-12.5`, `.5`, `5.`: no exponent) starting at
/// `b[start]`, when it takes Clinger's exact fast path (at most 19 digits,
/// mantissa below 2^53, at most 22 fraction digits). Returns the value and
/// the index after the last byte read. The caller checks that a separator
/// (or the end) follows; anything else (an exponent, junk, a long number)
/// returns `None` or stops early, and the caller falls back to [`parse_f64`]
/// on the whole token. Both give the same, correctly rounded value.
#[inline(always)]
pub fn parse_plain_prefix(b: &[u8], start: usize) -> Option<(f64, usize)> {
    let d = scan_decimal(b, start);
    if d.digits == 0 || d.digits > 19 || d.mant > (1u64 << 53) || d.frac > 22 {
        return None;
    }
    let v = d.mant as f64 / POW10[d.frac];
    Some((if d.neg { -v } else { v }, d.end))
}

/// The sign, digits and fraction of a decimal at `b[start..]`, read once.
struct Decimal {
    neg: bool,
    /// The digits as an integer (wrapping past 19 digits; callers check `digits`).
    mant: u64,
    /// Digits before and after the point.
    digits: usize,
    /// Digits after the point.
    frac: usize,
    /// Index after the last byte read.
    end: usize,
}

#[inline(always)]
fn scan_decimal(b: &[u8], start: usize) -> Decimal {
    let mut i = start;
    let n = b.len();
    let neg = i < n && b[i] == b'-';
    if i < n && (b[i] == b'-' || b[i] == b'+') {
        i += 1;
    }
    let mut mant: u64 = 0;
    let mut digits_loop = |i: &mut usize| {
        let s = *i;
        while *i < n {
            let d = b[*i].wrapping_sub(b'0');
            if d > 9 {
                break;
            }
            mant = mant.wrapping_mul(10).wrapping_add(d as u64);
            *i += 1;
        }
        *i - s
    };
    let int = digits_loop(&mut i);
    let mut frac = 0;
    if i < n && b[i] == b'.' {
        i += 1;
        frac = digits_loop(&mut i);
    }
    Decimal {
        neg,
        mant,
        digits: int + frac,
        frac,
        end: i,
    }
}

/// Parse a decimal number (`12`, `-3.5`, `.5`, `5.`, `1e-3`, `+2E+04`).
///
/// Returns `None` for anything else, including `inf` and `NaN`: no
/// non-finite value ever enters the model. Plain decimals with at most 15
/// significant digits and a small exponent take Clinger's fast path
/// (mantissa and power of ten both exact in f64, so one correctly rounded
/// operation); everything else falls back to the standard library's
/// correctly rounded parser. Both give the same, correctly rounded result.
#[inline]
pub fn parse_f64(s: &[u8]) -> Option<f64> {
    s.first()?;
    let Decimal {
        neg,
        mant,
        digits,
        frac,
        end,
    } = scan_decimal(s, 0);
    let (n, mut i, frac_digits) = (s.len(), end, frac);
    if digits == 0 {
        return None;
    }
    let mut exp: i64 = 0;
    if i < n {
        if s[i] != b'e' && s[i] != b'E' {
            return None;
        }
        i += 1;
        let eneg = match s.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let estart = i;
        while i < n && s[i].is_ascii_digit() {
            exp = (exp * 10 + (s[i] - b'0') as i64).min(1 << 20);
            i += 1;
        }
        if i == estart || i != n {
            return None;
        }
        if eneg {
            exp = -exp;
        }
    }
    let e10 = exp - frac_digits as i64;
    // Clinger's fast path: at most 19 digits cannot overflow u64; a mantissa
    // below 2^53 and a power of ten up to 1e22 are exact in f64, so one
    // multiplication or division rounds correctly.
    if digits <= 19 && mant <= (1u64 << 53) && (-22..=22).contains(&e10) {
        let m = mant as f64;
        let v = if e10 >= 0 {
            m * POW10[e10 as usize]
        } else {
            m / POW10[(-e10) as usize]
        };
        return Some(if neg { -v } else { v });
    }
    // Slow path: the validated token is ASCII, so from_utf8 cannot fail.
    let v: f64 = std::str::from_utf8(s).ok()?.parse().ok()?;
    v.is_finite().then_some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_f64_matches_std() {
        for s in [
            "0",
            "1",
            "-1",
            "12.5",
            ".5",
            "5.",
            "-0.0",
            "1e3",
            "1E-3",
            "+2e+04",
            "123456789012345",
            "1234567890123456789",
            "0.1",
            "0.30000000000000004",
            "3.14159265358979323846",
            "1e308",
            "2.2250738585072014e-308",
            "000001.5000",
        ] {
            let expected: f64 = s.parse().unwrap();
            assert_eq!(parse_f64(s.as_bytes()), Some(expected), "{s}");
        }
        for s in [
            "", "-", ".", "e5", "1e", "1.2.3", "inf", "NaN", "1e999", "abc", "1,5", "--1", "1e+",
        ] {
            assert_eq!(parse_f64(s.as_bytes()), None, "{s}");
        }
    }

    #[test]
    fn plain_prefix_agrees_with_std() {
        for s in [
            "0",
            "12.5",
            "-3.25",
            ".5",
            "5.",
            "123456.789",
            "9007199254740992",
            "0.000001",
            "+7",
        ] {
            let (v, end) = parse_plain_prefix(s.as_bytes(), 0).unwrap();
            assert_eq!(end, s.len());
            assert_eq!(v, s.parse::<f64>().unwrap(), "{s}");
        }
        // An exponent stops the prefix early; the caller falls back.
        assert_eq!(parse_plain_prefix(b"1e5", 0), Some((1.0, 1)));
        assert_eq!(parse_plain_prefix(b"-", 0), None);
        assert_eq!(parse_plain_prefix(b"99999999999999999999", 0), None);
    }

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
    fn tokens_track_lines_and_comments() {
        let b = b"1, 2\r\n3 ; c\r4\n\n  5";
        let t: Vec<_> = Tokens::new(b, 0, 1, true)
            .map(|t| (t.line, t.column, t.bytes.to_vec()))
            .collect();
        assert_eq!(
            t,
            vec![
                (1, 1, b"1".to_vec()),
                (1, 4, b"2".to_vec()),
                (2, 1, b"3".to_vec()),
                (3, 1, b"4".to_vec()),
                (5, 3, b"5".to_vec())
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
