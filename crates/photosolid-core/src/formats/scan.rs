//! The one number scanner of the text readers, and the number parser of every reader.
//!
//! [`Scanner`] splits a stream of numbers (IES LM-63 after `TILT=`, IES tilt
//! files, EULUMDAT from line 27 on) into tokens and parses them; the formats
//! differ only in their [`Separators`]. It tracks a byte offset and nothing
//! else: most files never need a line or a column, so positions are worked
//! out (by counting line ends from the stream's start) only when an error or
//! a warning names one. Errors pay, data does not.
//!
//! [`parse_f64`] and [`parse_number`] are the number syntax of all readers
//! (TM-33 and GLDF numbers too): decimal, optional exponent, finite only.

use crate::error::{Location, ParseError};
use crate::formats::text::{line_col, Source};

/// Which bytes separate two numbers (besides blanks, tabs, line ends, Ctrl-Z and NUL).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Separators {
    /// Commas separate too (IES LM-63 and its tilt files).
    BlanksAndCommas,
    /// A comma belongs to the number: EULUMDAT's decimal comma (`12,5`).
    Blanks,
}

const TOKEN: u8 = 0;
const SEPARATOR: u8 = 1;
/// `;` and `!` start a comment to the end of the line (seen in hand-edited files; never part of a number).
const COMMENT: u8 = 2;

const fn classes(comma_separates: bool) -> [u8; 256] {
    let mut t = [TOKEN; 256];
    let seps = [b' ', b'\t', b'\n', b'\r', 0x0B, 0x0C, 0x1A, 0];
    let mut i = 0;
    while i < seps.len() {
        t[seps[i] as usize] = SEPARATOR;
        i += 1;
    }
    if comma_separates {
        t[b',' as usize] = SEPARATOR;
    }
    t[b';' as usize] = COMMENT;
    t[b'!' as usize] = COMMENT;
    t
}

static WITH_COMMA: [u8; 256] = classes(true);
static WITHOUT_COMMA: [u8; 256] = classes(false);

/// A token: its bytes (never empty) and the offset of its first byte in the scanned bytes.
#[derive(Debug, Clone, Copy)]
pub struct Token<'a> {
    /// The token's bytes.
    pub bytes: &'a [u8],
    /// Byte offset of the token in the bytes given to [`Scanner::new`].
    pub offset: usize,
}

impl Token<'_> {
    /// The token as text for messages: lossy, in backticks, shortened to 40 characters.
    pub fn display(&self) -> String {
        let s = String::from_utf8_lossy(self.bytes);
        if s.chars().count() > 40 {
            format!("`{}...`", s.chars().take(40).collect::<String>())
        } else {
            format!("`{s}`")
        }
    }
}

/// Where a list of numbers stopped short: how many were read, where, and what was found
/// there (the token in backticks, or `end of file`).
#[derive(Debug, Clone, PartialEq)]
pub struct Shortfall {
    /// Numbers read before the failure.
    pub read: usize,
    /// The offending token, or the end of the file (a line only).
    pub location: Location,
    /// The offending token as [`Token::display`] gives it, or `end of file`.
    pub found: String,
    /// Whether the list ran into the end of the file (rather than a token that is no number).
    pub at_end: bool,
}

/// A stream of numbers over `bytes[origin..]`. Cloning it is free: a clone is a
/// mark that later locates the `i`-th token after it ([`Scanner::nth`]).
#[derive(Clone)]
pub struct Scanner<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Where the stream starts (a line start) and that line's 1-based number:
    /// positions are counted from there.
    origin: usize,
    origin_line: usize,
    class: &'static [u8; 256],
}

impl<'a> Scanner<'a> {
    /// The stream of `bytes[origin..]`, where `origin` is the start of line `origin_line` (1-based).
    pub fn new(bytes: &'a [u8], origin: usize, origin_line: usize, separators: Separators) -> Self {
        Self {
            bytes,
            pos: origin.min(bytes.len()),
            origin: origin.min(bytes.len()),
            origin_line,
            class: match separators {
                Separators::BlanksAndCommas => &WITH_COMMA,
                Separators::Blanks => &WITHOUT_COMMA,
            },
        }
    }

    /// The same stream moved on to byte `pos` (at or after the origin, not
    /// inside a token); positions are still counted from the origin.
    pub fn skip_to(mut self, pos: usize) -> Self {
        self.pos = pos.clamp(self.origin, self.bytes.len());
        self
    }

    /// Move past separators and comments; the offset of the next token, if any.
    #[inline(always)]
    fn skip(&mut self) -> Option<usize> {
        let (b, class) = (self.bytes, self.class);
        let mut p = self.pos;
        loop {
            if p >= b.len() {
                self.pos = p;
                return None;
            }
            match class[b[p] as usize] {
                SEPARATOR => p += 1,
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

    /// The next token.
    #[inline]
    pub fn next_token(&mut self) -> Option<Token<'a>> {
        let (b, class) = (self.bytes, self.class);
        let start = self.skip()?;
        let mut p = start;
        while p < b.len() && class[b[p] as usize] == TOKEN {
            p += 1;
        }
        self.pos = p;
        Some(Token {
            bytes: &b[start..p],
            offset: start,
        })
    }

    /// Whether another token follows.
    pub fn has_more(&self) -> bool {
        self.clone().skip().is_some()
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

    /// An upper bound on the tokens left, without scanning: every token but
    /// the last takes a byte and a separator (the bytes end in a token, as
    /// [`Source`] strips trailing blanks). Size checks before an allocation use it.
    pub fn max_remaining(&self) -> usize {
        (self.bytes.len() - self.pos).div_ceil(2)
    }

    /// Line and column of byte `offset` (at or after the origin).
    pub fn location(&self, offset: usize) -> Location {
        let (line, column) = line_col(&self.bytes[self.origin..], offset - self.origin);
        Location::at(self.origin_line + line - 1, column)
    }

    /// The line of the end of the bytes, for "found end of file" errors.
    pub fn end_location(&self) -> Location {
        Location::line(self.location(self.bytes.len()).line)
    }

    /// Location and display text of `t`.
    pub fn describe(&self, t: &Token<'_>) -> (Location, String) {
        (self.location(t.offset), t.display())
    }

    /// Location and display text of the `i`-th token from here (0 = the
    /// next), or the end-of-file location and `end of file`.
    pub fn nth(&self, i: usize) -> (Location, String) {
        let mut c = self.clone();
        for _ in 0..i {
            if c.next_token().is_none() {
                break;
            }
        }
        match c.next_token() {
            Some(t) => self.describe(&t),
            None => (self.end_location(), "end of file".into()),
        }
    }

    /// Line of the next token (or of the end of the file).
    pub fn next_line(&self) -> usize {
        self.nth(0).0.line
    }

    /// The next token as a finite number; `what` names it in errors.
    pub fn number(&mut self, src: &Source<'_>, what: &str) -> Result<f64, ParseError> {
        match self.next_token() {
            Some(t) => parse_number(t.bytes).ok_or_else(|| {
                let (loc, found) = self.describe(&t);
                src.invalid(loc, what.to_string(), found)
            }),
            None => Err(src.invalid(self.end_location(), what.to_string(), "end of file")),
        }
    }

    /// The next token as an integer in `[min, max]` (`3.0` accepted, as old files write it).
    pub fn integer(&mut self, src: &Source<'_>, what: &str, min: i64, max: i64) -> Result<i64, ParseError> {
        let here = self.clone();
        match self.next_token().and_then(|t| parse_number(t.bytes)) {
            Some(v) if v.fract() == 0.0 && v >= min as f64 && v <= max as f64 => Ok(v as i64),
            _ => {
                let (loc, found) = here.nth(0);
                Err(src.invalid(loc, format!("{what} (integer {min}..={max})"), found))
            }
        }
    }

    /// Append the next `n` numbers to `out` (reserved by the caller); where
    /// they run short, what was found and where. The hot loop of every reader.
    #[inline]
    pub fn fill(&mut self, n: usize, out: &mut Vec<f64>) -> Result<(), Shortfall> {
        for read in 0..n {
            // Fast path: skip separators, then parse the digits in the same
            // pass, accepted when a separator (or the end) follows.
            if let Some(p) = self.skip() {
                if let Some((v, end)) = parse_plain_prefix(self.bytes, p) {
                    if end == self.bytes.len() || self.class[self.bytes[end] as usize] != TOKEN {
                        out.push(v);
                        self.pos = end;
                        continue;
                    }
                }
            }
            match self.next_token() {
                Some(t) => match parse_number(t.bytes) {
                    Some(v) => out.push(v),
                    None => {
                        let (location, found) = self.describe(&t);
                        return Err(Shortfall {
                            read,
                            location,
                            found,
                            at_end: false,
                        });
                    }
                },
                None => {
                    return Err(Shortfall {
                        read,
                        location: self.end_location(),
                        found: "end of file".into(),
                        at_end: true,
                    })
                }
            }
        }
        Ok(())
    }

    /// [`Self::fill`] with the errors worded as `what(i)` for the i-th value
    /// and, at the end of the file, how many of the `n` were read.
    pub fn numbers_into(
        &mut self,
        src: &Source<'_>,
        n: usize,
        out: &mut Vec<f64>,
        what: &dyn Fn(usize) -> String,
    ) -> Result<(), ParseError> {
        self.fill(n, out).map_err(|s| {
            let expected = if s.at_end {
                format!("{} ({} of {n} values read)", what(s.read), s.read)
            } else {
                what(s.read)
            };
            src.invalid(s.location, expected, s.found)
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

/// Parse a number with a decimal point or a decimal comma (`12,5` is 12.5),
/// as EULUMDAT writes them; otherwise as [`parse_f64`]. A token of the
/// IES stream never holds a comma (it separates), so this is the parser of
/// every [`Scanner`].
///
/// No allocation: a comma token is copied to a stack buffer. Non-finite values are refused.
#[inline]
pub fn parse_number(tok: &[u8]) -> Option<f64> {
    if let Some(v) = parse_f64(tok) {
        return Some(v);
    }
    let comma = tok.iter().position(|&b| b == b',')?;
    if tok.len() > 64 || tok[comma + 1..].contains(&b',') || tok.contains(&b'.') {
        return None;
    }
    let mut buf = [0u8; 64];
    buf[..tok.len()].copy_from_slice(tok);
    buf[comma] = b'.';
    parse_f64(&buf[..tok.len()])
}

#[cfg(test)]
mod tests;
