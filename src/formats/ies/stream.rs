//! The number stream after `TILT=`, read on the fast path.
//!
//! [`Tokens`] tracks line and column for every token; most files never need
//! either, so this scanner only splits bytes (a 256-entry class table, the
//! same separators and comments as [`Tokens`] in comma mode) and counts
//! tokens. When an error needs a position, the `i`-th token is located by
//! re-scanning with [`Tokens`] from the stream start: errors pay, data does not.

use crate::error::{Location, ParseError};
use crate::formats::text::{parse_f64, parse_plain_prefix, Source, Tokens};

const TOKEN: u8 = 0;
const SEP: u8 = 1;
const COMMENT: u8 = 2;

/// Byte classes, matching `Tokens` with `comma_separates = true`.
static CLASS: [u8; 256] = {
    let mut t = [TOKEN; 256];
    let seps = [b' ', b'\t', b'\n', b'\r', 0x0B, 0x0C, 0x1A, 0, b','];
    let mut i = 0;
    while i < seps.len() {
        t[seps[i] as usize] = SEP;
        i += 1;
    }
    t[b';' as usize] = COMMENT;
    t[b'!' as usize] = COMMENT;
    t
};

/// A fast token stream over `bytes[offset..]`, with a [`Tokens`] twin for positions.
#[derive(Clone)]
pub(super) struct Stream<'a> {
    b: &'a [u8],
    pos: usize,
    /// Index of the next token (0-based from the stream start).
    idx: usize,
    start: Tokens<'a>,
}

impl<'a> Stream<'a> {
    /// The stream of `bytes[offset..]`, where `offset` starts line `line`.
    pub fn new(bytes: &'a [u8], offset: usize, line: usize) -> Self {
        Self {
            b: bytes,
            pos: offset,
            idx: 0,
            start: Tokens::new(bytes, offset, line, true),
        }
    }

    /// An upper bound on the tokens left (every token takes a byte and a
    /// separator), computed without scanning: the size check before
    /// allocating needs no exact count.
    pub fn max_remaining(&self) -> usize {
        self.b.len().saturating_sub(self.pos).div_ceil(2)
    }

    /// Index of the next token.
    pub fn index(&self) -> usize {
        self.idx
    }

    /// Move past separators and comments; the position of the next token, if any.
    #[inline(always)]
    fn skip_separators(&mut self) -> Option<usize> {
        let b = self.b;
        let mut p = self.pos;
        loop {
            if p >= b.len() {
                self.pos = p;
                return None;
            }
            match CLASS[b[p] as usize] {
                SEP => p += 1,
                COMMENT => {
                    while p < b.len() && b[p] != b'\n' && b[p] != b'\r' {
                        p += 1;
                    }
                }
                _ => {
                    self.pos = p;
                    return Some(p);
                }
            }
        }
    }

    #[inline]
    fn next_token(&mut self) -> Option<&'a [u8]> {
        let b = self.b;
        let mut p = self.skip_separators()?;
        let s = p;
        while p < b.len() && CLASS[b[p] as usize] == TOKEN {
            p += 1;
        }
        self.pos = p;
        self.idx += 1;
        Some(&b[s..p])
    }

    /// Count the tokens left, without moving.
    pub fn count_remaining(&self) -> usize {
        let mut c = self.clone();
        let mut n = 0;
        while c.next_token().is_some() {
            n += 1;
        }
        n
    }

    /// Location and display text of token `i` (or the end of file).
    pub fn locate(&self, i: usize) -> (Location, String) {
        let mut t = self.start.clone();
        match t.nth(i) {
            Some(tok) => (tok.location(), tok.display()),
            None => (t.end_location(), "end of file".into()),
        }
    }

    /// Line of token `i` (or of the end of file).
    pub fn line_of(&self, i: usize) -> usize {
        self.locate(i).0.line
    }

    /// The next token as a finite number; `what` names it in errors.
    pub fn number(&mut self, src: &Source<'_>, what: &str) -> Result<f64, ParseError> {
        let i = self.idx;
        match self.next_token().and_then(parse_f64) {
            Some(v) => Ok(v),
            None => {
                let (loc, found) = self.locate(i);
                Err(src.invalid(loc, what.to_string(), found))
            }
        }
    }

    /// The next token as an integer in `[min, max]` (`3.0` accepted, as old files write it).
    pub fn integer(&mut self, src: &Source<'_>, what: &str, min: i64, max: i64) -> Result<i64, ParseError> {
        let i = self.idx;
        match self.next_token().and_then(parse_f64) {
            Some(v) if v.fract() == 0.0 && v >= min as f64 && v <= max as f64 => Ok(v as i64),
            _ => {
                let (loc, found) = self.locate(i);
                Err(src.invalid(loc, format!("{what} (integer {min}..={max})"), found))
            }
        }
    }

    /// Append the next `n` numbers to `out` (reserved by the caller), `what(i)` naming the i-th.
    pub fn numbers_into(
        &mut self,
        src: &Source<'_>,
        n: usize,
        out: &mut Vec<f64>,
        what: &dyn Fn(usize) -> String,
    ) -> Result<(), ParseError> {
        for k in 0..n {
            // Fast path: skip separators, then parse the digits in the same
            // pass, accepted when a separator (or the end) follows.
            if let Some(p) = self.skip_separators() {
                if let Some((v, end)) = parse_plain_prefix(self.b, p) {
                    if end == self.b.len() || CLASS[self.b[end] as usize] != TOKEN {
                        out.push(v);
                        self.pos = end;
                        self.idx += 1;
                        continue;
                    }
                }
            }
            let i = self.idx;
            match self.next_token() {
                Some(t) => match parse_f64(t) {
                    Some(v) => out.push(v),
                    None => {
                        let (loc, found) = self.locate(i);
                        return Err(src.invalid(loc, what(k), found));
                    }
                },
                None => {
                    let (loc, found) = self.locate(i);
                    return Err(src.invalid(loc, format!("{} ({k} of {n} values read)", what(k)), found));
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stream_matches_tokens() {
        let b = b"1, 2\r\n3 ; c 9\r4\n\n  5 !x\n,,6\x1a";
        let mut s = Stream::new(b, 0, 1);
        let mut t = Tokens::new(b, 0, 1, true);
        assert_eq!(s.count_remaining(), t.count_remaining());
        while let Some(a) = s.next_token() {
            assert_eq!(a, t.next().unwrap().bytes);
        }
        assert!(t.next().is_none());
        assert_eq!(s.locate(4).0, Location::at(5, 3));
    }
}
