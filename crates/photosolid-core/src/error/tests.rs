//! Tests of the error types: codes, their documentation, messages.

use super::*;

/// One error of every variant (the match below fails to compile when a
/// variant is added without a sample here).
fn every_error() -> Vec<Error> {
    let parse = |kind| ParseError {
        path: "f.ies".into(),
        location: Location::at(3, 4),
        kind,
        expected: "a number".into(),
        found: "`x`".into(),
    };
    let model = |m: ModelError| Error::Model(m);
    let all = vec![
        Error::Parse(parse(ErrorKind::Invalid)),
        Error::Parse(parse(ErrorKind::Unsupported)),
        Error::io("f.ies", std::io::Error::other("gone")),
        model(ModelError::Angles {
            axis: "C",
            reason: "unsorted".into(),
        }),
        model(ModelError::Intensities("NaN".into())),
        model(ModelError::Mesh("index past the vertices".into())),
        model(ModelError::AllZero("normalising")),
        model(ModelError::Internal("bug".into())),
        model(ModelError::Parameter {
            name: "factor",
            value: "0".into(),
            reason: "expected >= 1".into(),
        }),
        model(ModelError::Undefined {
            quantity: "UGR",
            why: Undefined::NoLuminousArea,
        }),
        model(ModelError::Opening("signs".into())),
        model(ModelError::Gpu {
            recon: "bilinear@x2+gpu".into(),
            source: Layered::new(Upper),
        }),
        Error::Encode {
            format: "PNG",
            message: "full".into(),
        },
        Error::UnknownExtension {
            path: "x.txt".into(),
            what: "output format",
            accepted: &[".ies"],
        },
        Error::NothingChecked("no files".into()),
        Error::Option {
            option: "--range".into(),
            message: "empty".into(),
        },
        Error::Layer(Layered::new(Upper)),
        Error::RoundTrip {
            format: "EULUMDAT",
            difference: Difference::MissingPlane {
                c: 90.0,
                back: vec![0.0],
            },
        },
    ];
    for e in &all {
        // Exhaustive on purpose: a new variant must get a sample above.
        match e {
            Error::Parse(_)
            | Error::Io { .. }
            | Error::Model(_)
            | Error::Encode { .. }
            | Error::UnknownExtension { .. }
            | Error::NothingChecked(_)
            | Error::Option { .. }
            | Error::Layer(_)
            | Error::RoundTrip { .. }
            | Error::RoundTripRead { .. } => {}
        }
    }
    all
}

/// An error of a layer above, as those crates define theirs: a code from the table, a line.
#[derive(Debug, thiserror::Error)]
#[error("upper.toml:7: the upper layer failed")]
struct Upper;

impl LayerError for Upper {
    fn code(&self) -> &'static str {
        "scene-invalid"
    }
    fn location(&self) -> Option<Location> {
        Some(Location::line(7))
    }
}

/// Every code this crate's errors give is in [`ERROR_CODES`] (that every code there is given by
/// some error of some crate is `tests/it/typed_errors.rs`'s to check), and the documentation of
/// [`ErrorRecord::code`] lists exactly the table's codes (it once listed `unsupported-operation`,
/// which no error had).
#[test]
fn error_codes_are_documented_and_exist() {
    use std::collections::BTreeSet;
    let table: BTreeSet<&str> = ERROR_CODES.iter().map(|(c, _)| *c).collect();
    assert_eq!(table.len(), ERROR_CODES.len(), "a code is listed twice");
    let given: BTreeSet<&str> = every_error().iter().map(Error::code).collect();
    assert!(
        given.is_subset(&table),
        "codes given by errors but not in ERROR_CODES: {:?}",
        given.difference(&table)
    );
    // The doc comment of `ErrorRecord::code`: every `code` in backticks.
    let src = include_str!("../error.rs");
    let start = src
        .find("    /// Stable code ([`ERROR_CODES`]):")
        .expect("the doc of ErrorRecord::code");
    let doc: String = src[start..]
        .lines()
        .take_while(|l| l.trim_start().starts_with("///"))
        .collect::<Vec<_>>()
        .join("\n");
    let documented: BTreeSet<&str> = doc
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|w| w.chars().all(|c| c.is_ascii_lowercase() || c == '-'))
        .collect();
    assert_eq!(
        documented, table,
        "codes documented on ErrorRecord::code vs ERROR_CODES"
    );
    // The record carries the error's code and location.
    let rec = ErrorRecord::from(&every_error()[0]);
    assert_eq!((rec.line, rec.column, rec.code), (Some(3), Some(4), "invalid"));
    // A layer's error keeps its code, line, message and type through Error.
    let upper = Error::Layer(Layered::new(Upper));
    let rec = ErrorRecord::from(&upper);
    assert_eq!((rec.line, rec.code), (Some(7), "scene-invalid"));
    assert_eq!(upper.to_string(), "upper.toml:7: the upper layer failed");
    assert!(upper.downcast_ref::<Upper>().is_some());
    assert!(Error::NothingChecked("x".into()).downcast_ref::<Upper>().is_none());
}

#[test]
fn numbers_print_short_and_read_back() {
    let cases = [
        (1e-200, "1e-200"),
        (-1e-200, "-1e-200"),
        (1e300, "1e300"),
        (4e-320, "4e-320"),
        (1.2345678901234568e29, "1.2345678901234568e29"),
        (0.0001, "0.0001"),
        (0.00009, "9e-5"),
        (123.25, "123.25"),
        (1e15, "1000000000000000"),
        (1e16, "1e16"),
        (0.0, "0"),
        (f64::NAN, "NaN"),
        (f64::NEG_INFINITY, "-inf"),
    ];
    for (x, want) in cases {
        let s = Num(x).to_string();
        assert_eq!(s, want);
        if x.is_finite() {
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s} reads back");
        }
    }
    assert_eq!(Nums(&[0.0, 1e-300, 90.0]).to_string(), "[0, 1e-300, 90]");
}

/// docs/warnings.md lists every warning code exactly once, and nothing else, and each
/// code's JSON spelling is its `as_str`.
#[test]
fn every_warning_code_is_documented() {
    let doc = include_str!("../../../../docs/warnings.md");
    let rows: Vec<&str> = doc
        .lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .filter_map(|l| l.split('`').next())
        .collect();
    let mut codes: Vec<&str> = WarningCode::ALL.iter().map(|c| c.as_str()).collect();
    for c in WarningCode::ALL {
        assert_eq!(serde_json::to_value(c).unwrap(), c.as_str(), "{c:?}");
    }
    let mut listed = rows.clone();
    listed.sort_unstable();
    codes.sort_unstable();
    assert_eq!(listed, codes, "docs/warnings.md rows vs WarningCode::ALL");
}
