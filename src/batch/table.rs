//! Batch rows as an Arrow table and a Parquet file (cargo feature `parquet`).
//!
//! One column per [`BatchRecord`] field, same name and order (the schema is
//! documented in `docs/batch.md`): strings as `utf8`, counts as `uint32`,
//! quantities as `float64`, `ok` as `bool`, `errors` and `warnings` as
//! `list<utf8>`; null where the record holds `None`. Parquet files are
//! Snappy-compressed, one row group per [`ROW_GROUP`] rows, with the
//! key-value metadata `photosolid.batch.schema` = [`SCHEMA_VERSION`] and
//! `photosolid.batch.holdout` (what the hold-out columns are measured against).

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use arrow_array::builder::{ListBuilder, StringBuilder};
use arrow_array::{Array, ArrayRef, BooleanArray, Float64Array, ListArray, RecordBatch, StringArray, UInt32Array};
use arrow_schema::{Field, Schema};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;

use super::{BatchRecord, HOLDOUT};
use crate::error::{Error, ErrorKind, Location, ParseError, Result};

/// Version of the column set; bumped when a column is added, renamed or retyped.
///
/// 2 (issue 27): `lamp_flux_lm`, `manufacturer`, `catalogue`, `input_watts`, `efficacy_lm_per_w`
/// after `field_angle_c90_deg`; a schema-1 table still reads (those columns null).
/// 3 (issue 30): `smallest_within_1pct` and `compact_ms` at the end (`batch --compact`);
/// an older table reads with them null.
/// 4: `front_c_deg` at the end (the luminaire's front used); an older table reads it null.
pub const SCHEMA_VERSION: &str = "4";

/// Rows per Parquet row group.
pub const ROW_GROUP: usize = 65_536;

fn strings(rows: &[BatchRecord], f: impl Fn(&BatchRecord) -> Option<&str>) -> ArrayRef {
    Arc::new(rows.iter().map(f).collect::<StringArray>())
}

fn floats(rows: &[BatchRecord], f: impl Fn(&BatchRecord) -> Option<f64>) -> ArrayRef {
    Arc::new(rows.iter().map(f).collect::<Float64Array>())
}

fn counts(rows: &[BatchRecord], f: impl Fn(&BatchRecord) -> Option<u32>) -> ArrayRef {
    Arc::new(rows.iter().map(f).collect::<UInt32Array>())
}

fn lists(rows: &[BatchRecord], f: impl Fn(&BatchRecord) -> &[String]) -> ArrayRef {
    let mut b = ListBuilder::new(StringBuilder::new());
    for r in rows {
        for s in f(r) {
            b.values().append_value(s);
        }
        b.append(true);
    }
    Arc::new(b.finish())
}

/// The columns of `rows`: (name, array, nullable), in [`BatchRecord`] field order.
fn columns(rows: &[BatchRecord]) -> Vec<(&'static str, ArrayRef, bool)> {
    vec![
        ("path", strings(rows, |r| Some(&r.path)), false),
        (
            "ok",
            Arc::new(rows.iter().map(|r| Some(r.ok)).collect::<BooleanArray>()),
            false,
        ),
        ("errors", lists(rows, |r| &r.errors), false),
        ("warnings", lists(rows, |r| &r.warnings), false),
        ("format", strings(rows, |r| r.format.as_deref()), true),
        ("version", strings(rows, |r| r.version.as_deref()), true),
        (
            "photometric_type",
            strings(rows, |r| r.photometric_type.as_deref()),
            true,
        ),
        ("symmetry", strings(rows, |r| r.symmetry.as_deref()), true),
        ("n_c", counts(rows, |r| r.n_c), true),
        ("n_c_full", counts(rows, |r| r.n_c_full), true),
        ("n_gamma", counts(rows, |r| r.n_gamma), true),
        ("gamma_min_deg", floats(rows, |r| r.gamma_min_deg), true),
        ("gamma_max_deg", floats(rows, |r| r.gamma_max_deg), true),
        ("max_cd", floats(rows, |r| r.max_cd), true),
        ("flux_lm", floats(rows, |r| r.flux_lm), true),
        ("declared_flux_lm", floats(rows, |r| r.declared_flux_lm), true),
        ("flux_ratio", floats(rows, |r| r.flux_ratio), true),
        ("lor", floats(rows, |r| r.lor), true),
        ("dlor", floats(rows, |r| r.dlor), true),
        ("ulor", floats(rows, |r| r.ulor), true),
        ("beam_angle_deg", floats(rows, |r| r.beam_angle_deg), true),
        ("field_angle_deg", floats(rows, |r| r.field_angle_deg), true),
        ("beam_angle_c90_deg", floats(rows, |r| r.beam_angle_c90_deg), true),
        ("field_angle_c90_deg", floats(rows, |r| r.field_angle_c90_deg), true),
        ("lamp_flux_lm", floats(rows, |r| r.lamp_flux_lm), true),
        ("manufacturer", strings(rows, |r| r.manufacturer.as_deref()), true),
        ("catalogue", strings(rows, |r| r.catalogue.as_deref()), true),
        ("input_watts", floats(rows, |r| r.input_watts), true),
        ("efficacy_lm_per_w", floats(rows, |r| r.efficacy_lm_per_w), true),
        ("best_filter", strings(rows, |r| r.best_filter.as_deref()), true),
        ("best_filter_rms_pct", floats(rows, |r| r.best_filter_rms_pct), true),
        ("best_filter_max_pct", floats(rows, |r| r.best_filter_max_pct), true),
        ("fitted_gl", strings(rows, |r| r.fitted_gl.as_deref()), true),
        ("fitted_gl_error", floats(rows, |r| r.fitted_gl_error), true),
        ("parse_ms", floats(rows, |r| Some(r.parse_ms)), false),
        ("holdout_ms", floats(rows, |r| Some(r.holdout_ms)), false),
        ("fit_ms", floats(rows, |r| Some(r.fit_ms)), false),
        (
            "smallest_within_1pct",
            strings(rows, |r| r.smallest_within_1pct.as_deref()),
            true,
        ),
        ("compact_ms", floats(rows, |r| r.compact_ms), true),
        ("front_c_deg", floats(rows, |r| r.front_c_deg), true),
    ]
}

/// The rows as one Arrow record batch (see the module docs for the types).
///
/// # Errors
/// [`Error::Encode`] if Arrow refuses the arrays (a bug: they are built to the schema).
pub fn record_batch(rows: &[BatchRecord]) -> Result<RecordBatch> {
    let cols = columns(rows);
    let schema = Schema::new(
        cols.iter()
            .map(|(name, a, nullable)| Field::new(*name, a.data_type().clone(), *nullable))
            .collect::<Vec<_>>(),
    );
    RecordBatch::try_new(Arc::new(schema), cols.into_iter().map(|c| c.1).collect()).map_err(|e| Error::Encode {
        format: "Arrow",
        message: format!("batch table: {e}"),
    })
}

/// Write `rows` as Parquet into `out`.
///
/// # Errors
/// [`Error::Encode`] naming the Parquet error (an I/O error of `out` included).
pub fn write_parquet_to<W: Write + Send>(rows: &[BatchRecord], out: W) -> Result<()> {
    let batch = record_batch(rows)?;
    let meta = vec![
        KeyValue::new("photosolid.batch.schema".into(), SCHEMA_VERSION.to_string()),
        KeyValue::new(
            "photosolid.batch.holdout".into(),
            format!(
                "withheld measurements: keep every {} C-plane(s) and every {} gamma row(s), errors in % of I_max",
                HOLDOUT.c_step, HOLDOUT.gamma_step
            ),
        ),
    ];
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_max_row_group_row_count(Some(ROW_GROUP))
        .set_key_value_metadata(Some(meta))
        .build();
    let fail = |e: parquet::errors::ParquetError| Error::Encode {
        format: "Parquet",
        message: e.to_string(),
    };
    let mut w = ArrowWriter::try_new(out, batch.schema(), Some(props)).map_err(fail)?;
    w.write(&batch).map_err(fail)?;
    w.close().map_err(fail)?;
    Ok(())
}

/// The Parquet bytes of `rows` (what [`write_parquet`] writes).
///
/// # Errors
/// As [`write_parquet_to`].
pub fn parquet_bytes(rows: &[BatchRecord]) -> Result<Vec<u8>> {
    let mut buf = Vec::new();
    write_parquet_to(rows, &mut buf)?;
    Ok(buf)
}

/// Write `rows` to the Parquet file `path`, atomically ([`crate::formats::files::write_atomic_with`]).
///
/// # Errors
/// [`Error::Io`] naming `path`; the file is then untouched.
pub fn write_parquet(path: &Path, rows: &[BatchRecord]) -> Result<()> {
    let bytes = parquet_bytes(rows)?;
    crate::formats::files::write_atomic(path, &bytes)
}

/// A read-back failure: the file is not a batch table.
fn bad(path: &Path, what: String) -> Error {
    Error::Parse(ParseError {
        path: path.to_path_buf(),
        location: Location::default(),
        kind: ErrorKind::Invalid,
        expected: "a photosolid batch table (docs/batch.md)".into(),
        found: what,
    })
}

/// The rows of a Parquet file written by [`write_parquet`] (or any file with the same columns).
///
/// # Errors
/// [`Error::Io`] when it cannot be opened; [`Error::Parse`] when it is not
/// Parquet or a column is missing or of another type.
pub fn read_parquet(path: &Path) -> Result<Vec<BatchRecord>> {
    let file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let reader = ParquetRecordBatchReaderBuilder::try_new(file)
        .and_then(|b| b.build())
        .map_err(|e| bad(path, e.to_string()))?;
    let mut rows = Vec::new();
    for batch in reader {
        let batch = batch.map_err(|e| bad(path, e.to_string()))?;
        rows.extend(rows_in(&batch, path)?);
    }
    Ok(rows)
}

/// Column `name` of `b` as an array of type `T` (`kind` names it, e.g. "Utf8").
fn column_of<'a, T: 'static>(b: &'a RecordBatch, path: &Path, name: &str, kind: &str) -> Result<&'a T> {
    let wrong = |found: String| {
        Error::Parse(ParseError {
            path: path.to_path_buf(),
            location: Location::default(),
            kind: ErrorKind::Invalid,
            expected: format!("a column `{name}` of type {kind} (a photosolid batch table, docs/batch.md)"),
            found,
        })
    };
    let c = b.column_by_name(name).ok_or_else(|| wrong("no such column".into()))?;
    c.as_any()
        .downcast_ref::<T>()
        .ok_or_else(|| wrong(format!("type {}", c.data_type())))
}

/// The rows of one record batch with the batch columns.
///
/// # Errors
/// [`Error::Parse`] (path `<memory>`) naming a column that is missing or of another type.
pub fn rows_of(b: &RecordBatch) -> Result<Vec<BatchRecord>> {
    rows_in(b, Path::new("<memory>"))
}

/// [`rows_of`], the errors naming `path`.
fn rows_in(b: &RecordBatch, path: &Path) -> Result<Vec<BatchRecord>> {
    let v = ColumnValues::read(&Columns { b, path })?;
    Ok((0..b.num_rows()).map(|i| v.record(i)).collect())
}

/// The Float64 columns that every schema has, in the order [`ColumnValues::record`] indexes them.
const FLOAT_COLUMNS: [&str; 19] = [
    "gamma_min_deg",
    "gamma_max_deg",
    "max_cd",
    "flux_lm",
    "declared_flux_lm",
    "flux_ratio",
    "lor",
    "dlor",
    "ulor",
    "beam_angle_deg",
    "field_angle_deg",
    "beam_angle_c90_deg",
    "field_angle_c90_deg",
    "best_filter_rms_pct",
    "best_filter_max_pct",
    "fitted_gl_error",
    "parse_ms",
    "holdout_ms",
    "fit_ms",
];

/// The columns of one record batch, read by name into one value per row
/// (the errors naming `path`).
struct Columns<'a> {
    b: &'a RecordBatch,
    path: &'a Path,
}

impl Columns<'_> {
    /// The Utf8 column `name`, `None` where null.
    fn strings(&self, name: &str) -> Result<Vec<Option<String>>> {
        let a = column_of::<StringArray>(self.b, self.path, name, "Utf8")?;
        Ok((0..a.len())
            .map(|i| a.is_valid(i).then(|| a.value(i).to_string()))
            .collect())
    }

    /// The Float64 column `name`, `None` where null.
    fn floats(&self, name: &str) -> Result<Vec<Option<f64>>> {
        let a = column_of::<Float64Array>(self.b, self.path, name, "Float64")?;
        Ok((0..a.len()).map(|i| a.is_valid(i).then(|| a.value(i))).collect())
    }

    /// The UInt32 column `name`, `None` where null.
    fn counts(&self, name: &str) -> Result<Vec<Option<u32>>> {
        let a = column_of::<UInt32Array>(self.b, self.path, name, "UInt32")?;
        Ok((0..a.len()).map(|i| a.is_valid(i).then(|| a.value(i))).collect())
    }

    /// The List(Utf8) column `name`, each list without its null items.
    fn lists(&self, name: &str) -> Result<Vec<Vec<String>>> {
        let a = column_of::<ListArray>(self.b, self.path, name, "List(Utf8)")?;
        (0..a.len())
            .map(|i| {
                let v = a.value(i);
                let v = v.as_any().downcast_ref::<StringArray>().ok_or_else(|| {
                    Error::Parse(ParseError {
                        path: self.path.to_path_buf(),
                        location: Location::default(),
                        kind: ErrorKind::Invalid,
                        expected: format!(
                            "a column `{name}` of type List(Utf8) (a photosolid batch table, docs/batch.md)"
                        ),
                        found: format!("a list of {}", v.data_type()),
                    })
                })?;
                Ok((0..v.len())
                    .filter(|&j| v.is_valid(j))
                    .map(|j| v.value(j).to_string())
                    .collect())
            })
            .collect()
    }

    /// [`Columns::floats`] of a column added after schema 1: all null when an
    /// older table lacks it (e.g. `batch --resume` on an older file).
    fn floats_if_present(&self, name: &str) -> Result<Vec<Option<f64>>> {
        match self.b.column_by_name(name) {
            None => Ok(vec![None; self.b.num_rows()]),
            Some(_) => self.floats(name),
        }
    }

    /// [`Columns::strings`] of a column added after schema 1, as [`Columns::floats_if_present`].
    fn strings_if_present(&self, name: &str) -> Result<Vec<Option<String>>> {
        match self.b.column_by_name(name) {
            None => Ok(vec![None; self.b.num_rows()]),
            Some(_) => self.strings(name),
        }
    }
}

/// Every batch column of one record batch, read ([`ColumnValues::read`]).
struct ColumnValues<'a> {
    ok: &'a BooleanArray,
    path: Vec<Option<String>>,
    errors: Vec<Vec<String>>,
    warnings: Vec<Vec<String>>,
    format: Vec<Option<String>>,
    version: Vec<Option<String>>,
    ptype: Vec<Option<String>>,
    symmetry: Vec<Option<String>>,
    n_c: Vec<Option<u32>>,
    n_c_full: Vec<Option<u32>>,
    n_gamma: Vec<Option<u32>>,
    /// The columns of [`FLOAT_COLUMNS`], in its order.
    nums: Vec<Vec<Option<f64>>>,
    best: Vec<Option<String>>,
    gl: Vec<Option<String>>,
    lamp_flux: Vec<Option<f64>>,
    watts: Vec<Option<f64>>,
    efficacy: Vec<Option<f64>>,
    manufacturer: Vec<Option<String>>,
    catalogue: Vec<Option<String>>,
    smallest: Vec<Option<String>>,
    compact_ms: Vec<Option<f64>>,
    front: Vec<Option<f64>>,
}

impl<'a> ColumnValues<'a> {
    /// Every batch column of `c`; the first one missing or of another type (in
    /// this order) is the [`Error::Parse`].
    fn read(c: &Columns<'a>) -> Result<Self> {
        let ok = column_of::<BooleanArray>(c.b, c.path, "ok", "Boolean")?;
        let (path, errors, warnings) = (c.strings("path")?, c.lists("errors")?, c.lists("warnings")?);
        let (format, version, ptype, symmetry) = (
            c.strings("format")?,
            c.strings("version")?,
            c.strings("photometric_type")?,
            c.strings("symmetry")?,
        );
        let (n_c, n_c_full, n_gamma) = (c.counts("n_c")?, c.counts("n_c_full")?, c.counts("n_gamma")?);
        let nums: Vec<Vec<Option<f64>>> = FLOAT_COLUMNS.iter().map(|n| c.floats(n)).collect::<Result<_>>()?;
        let (best, gl) = (c.strings("best_filter")?, c.strings("fitted_gl")?);
        let (lamp_flux, watts, efficacy) = (
            c.floats_if_present("lamp_flux_lm")?,
            c.floats_if_present("input_watts")?,
            c.floats_if_present("efficacy_lm_per_w")?,
        );
        let (manufacturer, catalogue) = (
            c.strings_if_present("manufacturer")?,
            c.strings_if_present("catalogue")?,
        );
        let (smallest, compact_ms) = (
            c.strings_if_present("smallest_within_1pct")?,
            c.floats_if_present("compact_ms")?,
        );
        let front = c.floats_if_present("front_c_deg")?;
        Ok(Self {
            ok,
            path,
            errors,
            warnings,
            format,
            version,
            ptype,
            symmetry,
            n_c,
            n_c_full,
            n_gamma,
            nums,
            best,
            gl,
            lamp_flux,
            watts,
            efficacy,
            manufacturer,
            catalogue,
            smallest,
            compact_ms,
            front,
        })
    }

    /// Row `i` (a missing path reads as empty, a null `ok` as false, null timings as 0 ms).
    fn record(&self, i: usize) -> BatchRecord {
        let x = |k: usize| self.nums[k][i];
        BatchRecord {
            path: self.path[i].clone().unwrap_or_default(),
            ok: self.ok.is_valid(i) && self.ok.value(i),
            errors: self.errors[i].clone(),
            warnings: self.warnings[i].clone(),
            format: self.format[i].clone(),
            version: self.version[i].clone(),
            photometric_type: self.ptype[i].clone(),
            symmetry: self.symmetry[i].clone(),
            n_c: self.n_c[i],
            n_c_full: self.n_c_full[i],
            n_gamma: self.n_gamma[i],
            gamma_min_deg: x(0),
            gamma_max_deg: x(1),
            max_cd: x(2),
            flux_lm: x(3),
            declared_flux_lm: x(4),
            flux_ratio: x(5),
            lor: x(6),
            dlor: x(7),
            ulor: x(8),
            beam_angle_deg: x(9),
            field_angle_deg: x(10),
            beam_angle_c90_deg: x(11),
            field_angle_c90_deg: x(12),
            lamp_flux_lm: self.lamp_flux[i],
            manufacturer: self.manufacturer[i].clone(),
            catalogue: self.catalogue[i].clone(),
            input_watts: self.watts[i],
            efficacy_lm_per_w: self.efficacy[i],
            best_filter: self.best[i].clone(),
            best_filter_rms_pct: x(13),
            best_filter_max_pct: x(14),
            fitted_gl: self.gl[i].clone(),
            fitted_gl_error: x(15),
            parse_ms: x(16).unwrap_or(0.0),
            holdout_ms: x(17).unwrap_or(0.0),
            fit_ms: x(18).unwrap_or(0.0),
            smallest_within_1pct: self.smallest[i].clone(),
            compact_ms: self.compact_ms[i],
            front_c_deg: self.front[i],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows written as Parquet read back equal, nulls and lists included; a non-Parquet file is a parse error.
    #[test]
    fn parquet_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let grid = crate::synth::GridSpec::uniform(15.0, 5.0).unwrap();
        let lum = crate::synth::Synth::Lambertian.build(&grid, 50.0).unwrap();
        let good = dir.path().join("l.ies");
        crate::save(&lum.clone().into(), &good, &Default::default()).unwrap();
        let bad_file = dir.path().join("bad.ldt");
        std::fs::write(&bad_file, "not a file\n").unwrap();
        let rows = super::super::run(&[good, bad_file.clone()], &Default::default(), &|_, _, _| {});
        assert!(rows[0].ok && !rows[1].ok);
        let out = dir.path().join("t.parquet");
        write_parquet(&out, &rows).unwrap();
        assert_eq!(read_parquet(&out).unwrap(), rows);
        let err = read_parquet(&bad_file).unwrap_err();
        assert!(err.to_string().contains("bad.ldt"), "{err}");
    }
}
