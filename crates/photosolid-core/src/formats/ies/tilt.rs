//! IES tilt tables: `TILT=INCLUDE` inline, `TILT=<file>` from a capped,
//! regular-file-only read next to the photometric file.

use std::path::{Path, PathBuf};

use super::grid::check_or_repair;
use crate::error::{Location, ParseError, Warning, WarningCode};
use crate::formats::scan::{Scanner, Separators};
use crate::formats::text::Source;
use crate::formats::ReadOptions;
use crate::model::TiltTable;

/// Parse a tilt table (`geometry N angles... multipliers...`) from `tokens`.
pub(super) fn read_tilt_table(
    src: &Source<'_>,
    tokens: &mut Scanner<'_>,
    remaining: usize,
    opts: &ReadOptions,
    warnings: &mut Vec<Warning>,
) -> Result<TiltTable, ParseError> {
    let geometry = tokens.integer(src, "tilt lamp-to-luminaire geometry (1, 2 or 3)", 1, 3)? as u8;
    let n_at = tokens.clone();
    let max_pairs = remaining.saturating_sub(2) / 2;
    let n = tokens.integer(src, "number of tilt angle / multiplier pairs", 1, i64::MAX)? as u64;
    if n > max_pairs as u64 {
        let (loc, found) = n_at.nth(0);
        return Err(src.invalid(
            loc,
            format!("a number of tilt pairs that fits the file (at most {max_pairs})"),
            found,
        ));
    }
    let n = n as usize;
    let a_start = tokens.clone();
    let mut angles = Vec::with_capacity(n);
    tokens.numbers_into(src, n, &mut angles, &|i| format!("tilt angle #{} of {n}", i + 1))?;
    let mut multipliers = Vec::with_capacity(n);
    tokens.numbers_into(src, n, &mut multipliers, &|i| {
        format!("tilt multiplier #{} of {n}", i + 1)
    })?;
    let mut m = multipliers;
    check_or_repair(src, &a_start, "tilt", &mut angles, 1, &mut m, true, opts, warnings)?;
    Ok(TiltTable {
        geometry,
        angles,
        multipliers: m,
    })
}

/// Largest tilt file read (bytes). A tilt table is a few hundred numbers;
/// the cap keeps `TILT=` pointing at a huge or endless file from being read.
pub const MAX_TILT_FILE_BYTES: u64 = 1024 * 1024;

/// Resolve `TILT=<file>` next to the photometric file and parse it. The
/// non-standard `TILT=FILE name` form is accepted (warned) when no file is
/// literally called `FILE name`.
pub(super) fn read_tilt_file(
    src: &Source<'_>,
    line: usize,
    value: &str,
    opts: &ReadOptions,
    warnings: &mut Vec<Warning>,
) -> Result<(String, TiltTable), ParseError> {
    let dir = src.path.parent().unwrap_or(Path::new(""));
    let mut name = value.to_string();
    let mut full: PathBuf = dir.join(&name);
    // Byte-wise test: `value` may hold multi-byte characters at any position.
    if !full.is_file() && value.len() > 5 && value.as_bytes()[..4].eq_ignore_ascii_case(b"FILE") {
        // The first four bytes are ASCII, so byte 4 is a character boundary.
        let rest = value[4..].trim_start();
        if !rest.is_empty() && rest.len() < value.len() - 4 {
            warnings.push(Warning::at(
                line,
                WarningCode::TiltFileKeyword,
                format!("non-standard `TILT=FILE {rest}`: read as `TILT={rest}`"),
            ));
            name = rest.to_string();
            full = dir.join(&name);
        }
    }
    let bytes = crate::formats::files::read_capped(&full, MAX_TILT_FILE_BYTES).map_err(|e| {
        src.invalid(
            Location::line(line),
            format!(
                "the tilt file `{}` named by TILT= (a regular file of at most {MAX_TILT_FILE_BYTES} bytes)",
                full.display()
            ),
            format!("it cannot be read: {e}"),
        )
    })?;
    let tsrc = Source::new(&full, &bytes).map_err(|mut e| {
        e.location.line = e.location.line.max(1);
        e
    })?;
    let mut tokens = Scanner::new(tsrc.bytes, 0, 1, Separators::BlanksAndCommas);
    let remaining = tokens.count_remaining();
    let table = read_tilt_table(&tsrc, &mut tokens, remaining, opts, warnings)?;
    let extra = tokens.count_remaining();
    if extra > 0 {
        warnings.push(Warning::new(
            WarningCode::TiltExtraValues,
            format!(
                "{extra} extra token(s) in tilt file `{}` from line {} ignored",
                full.display(),
                tokens.next_line()
            ),
        ));
    }
    Ok((name, table))
}
