//! The EULUMDAT number stream (line 27 on) and its error helpers.

use super::parse_number;
use crate::error::{Location, ParseError};
use crate::formats::text::{line_col, Source};
use crate::model::ANGLE_EPS;

/// The number stream from line 27 on: tokens separated by blanks and line
/// ends, `;` and `!` starting a comment to the end of the line (as
/// [`crate::formats::text::Tokens`] splits them, with the decimal comma kept
/// in the token). It tracks only a byte offset; lines and columns are worked
/// out when an error or warning needs them, which keeps the hot loop lean.
#[derive(Clone)]
pub(super) struct Stream<'a> {
    pub(super) b: &'a [u8],
    pub(super) pos: usize,
}

/// A token of a [`Stream`]: its bytes and byte offset.
pub(super) struct Tok<'a> {
    pub(super) bytes: &'a [u8],
    pub(super) at: usize,
}

#[inline(always)]
pub(super) fn is_separator(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C | 0x1A | 0)
}

impl<'a> Stream<'a> {
    /// The next token parsed in the same pass as the scan, when it is a
    /// plain decimal followed by a separator (the common case); otherwise
    /// `None` with nothing consumed, and the caller takes the token path.
    #[inline(always)]
    pub(super) fn fast_number(&mut self) -> Option<f64> {
        let b = self.b;
        let mut i = self.pos;
        while i < b.len() && is_separator(b[i]) {
            i += 1;
        }
        let (v, end) = crate::formats::text::parse_plain_prefix(b, i)?;
        if end < b.len() && !is_separator(b[end]) {
            return None;
        }
        self.pos = end;
        Some(v)
    }

    #[inline(always)]
    pub(super) fn next(&mut self) -> Option<Tok<'a>> {
        let b = self.b;
        let mut i = self.pos;
        loop {
            match b.get(i) {
                None => {
                    self.pos = i;
                    return None;
                }
                Some(&c) if is_separator(c) => i += 1,
                Some(b';' | b'!') => {
                    while i < b.len() && b[i] != b'\n' && b[i] != b'\r' {
                        i += 1;
                    }
                }
                Some(_) => break,
            }
        }
        let start = i;
        while i < b.len() && !is_separator(b[i]) && b[i] != b';' && b[i] != b'!' {
            i += 1;
        }
        self.pos = i;
        Some(Tok {
            bytes: &b[start..i],
            at: start,
        })
    }

    pub(super) fn location(&self, at: usize) -> Location {
        let (line, col) = line_col(self.b, at);
        Location::at(line, col)
    }

    /// Line of the next token (or of the end of the file).
    pub(super) fn next_line(&self) -> usize {
        let at = self.clone().next().map_or(self.b.len(), |t| t.at);
        line_col(self.b, at).0
    }

    pub(super) fn end_location(&self) -> Location {
        Location::line(line_col(self.b, self.b.len()).0)
    }

    pub(super) fn count_remaining(&self) -> usize {
        let mut c = self.clone();
        let mut n = 0;
        while c.next().is_some() {
            n += 1;
        }
        n
    }
}

/// The next number of the stream (decimal comma allowed).
pub(super) fn number(src: &Source<'_>, toks: &mut Stream<'_>, what: &dyn Fn() -> String) -> Result<f64, ParseError> {
    match toks.next() {
        None => Err(src.invalid(toks.end_location(), what(), "end of file")),
        Some(t) => parse_number(t.bytes).ok_or_else(|| bad(src, toks, &t, what())),
    }
}

pub(super) fn bad(src: &Source<'_>, toks: &Stream<'_>, t: &Tok<'_>, what: String) -> ParseError {
    let s = String::from_utf8_lossy(t.bytes);
    let found = if s.chars().count() > 40 {
        format!("`{}...`", s.chars().take(40).collect::<String>())
    } else {
        format!("`{s}`")
    };
    src.invalid(toks.location(t.at), what, found)
}

/// Where the `i`-th token from `toks` starts.
pub(super) fn nth_location(toks: &Stream<'_>, i: usize) -> Location {
    let mut t = toks.clone();
    for _ in 0..i {
        t.next();
    }
    match t.next() {
        Some(tok) => toks.location(tok.at),
        None => t.end_location(),
    }
}

pub(super) fn check_range(
    src: &Source<'_>,
    v: &[f64],
    toks: &Stream<'_>,
    what: &str,
    hi: f64,
) -> Result<(), ParseError> {
    match v.iter().position(|&a| !(-ANGLE_EPS..=hi + ANGLE_EPS).contains(&a)) {
        None => Ok(()),
        Some(i) => Err(src.invalid(
            nth_location(toks, i),
            format!("{what} angles in [0, {hi}] degrees"),
            format!("{what} angle #{} = {}", i + 1, v[i]),
        )),
    }
}
