use std::path::Path;

use super::*;

/// Every token of `text` from line 1: its value (if a number) and where it starts.
fn scan_all(text: &[u8], sep: Separators) -> Vec<(Option<f64>, (usize, usize))> {
    let s = Scanner::new(text, 0, 1, sep);
    let mut c = s.clone();
    let mut out = Vec::new();
    while let Some(t) = c.next_token() {
        let loc = s.location(t.offset);
        out.push((parse_number(t.bytes), (loc.line, loc.column.unwrap())));
    }
    out
}

#[test]
fn ies_and_ldt_layouts_give_the_same_numbers_and_locations() {
    // IES style: several numbers a line, blanks, tabs, commas; LF, CRLF and CR
    // line ends; a comment. LDT style: one number a line, a decimal comma.
    // The values stand at the same lines and columns in both texts.
    let ies = b"1, 2.5\t-3\r\n4e1 ; 9 is a comment\r.5,6.\n\n  +7\n0.000001";
    let ldt = b"1  2.5\t-3\r\n4e1 ; 9 is a comment\r.5 6.\n\n  +7\n0,000001";
    let a = scan_all(ies, Separators::BlanksAndCommas);
    let b = scan_all(ldt, Separators::Blanks);
    assert_eq!(a, b);
    let values: Vec<f64> = a.iter().map(|t| t.0.unwrap()).collect();
    assert_eq!(values, [1.0, 2.5, -3.0, 40.0, 0.5, 6.0, 7.0, 1e-6]);
    let at: Vec<(usize, usize)> = a.iter().map(|t| t.1).collect();
    assert_eq!(at, [(1, 1), (1, 4), (1, 8), (2, 1), (3, 1), (3, 4), (5, 3), (6, 1)]);
    // Blank-separated text reads alike under both separator sets, through the fast path too.
    for sep in [Separators::BlanksAndCommas, Separators::Blanks] {
        let mut out = Vec::new();
        Scanner::new(ldt, 0, 1, sep).fill(7, &mut out).unwrap();
        assert_eq!(out, values[..7]);
    }
}

#[test]
fn a_comma_separates_in_ies_and_is_a_decimal_comma_in_ldt() {
    let t = b"1,5 2";
    assert_eq!(
        scan_all(t, Separators::BlanksAndCommas),
        [(Some(1.0), (1, 1)), (Some(5.0), (1, 3)), (Some(2.0), (1, 5))]
    );
    assert_eq!(
        scan_all(t, Separators::Blanks),
        [(Some(1.5), (1, 1)), (Some(2.0), (1, 5))]
    );
}

#[test]
fn shortfalls_name_the_token_or_the_end_alike() {
    let p = Path::new("f.txt");
    for sep in [Separators::BlanksAndCommas, Separators::Blanks] {
        // A stream that starts on line 10 at a line start: locations count from there.
        let text = b"header\n1 2\n3 x4 5";
        let mut s = Scanner::new(text, 7, 10, sep);
        let mut out = Vec::new();
        let e = s.fill(5, &mut out).unwrap_err();
        assert_eq!(out, [1.0, 2.0, 3.0]);
        assert_eq!(
            e,
            Shortfall {
                read: 3,
                location: Location::at(11, 3),
                found: "`x4`".into(),
                at_end: false
            }
        );
        let mut s = Scanner::new(&text[..12], 7, 10, sep);
        let e = s.fill(5, &mut Vec::new()).unwrap_err();
        assert_eq!((e.read, e.location, e.at_end), (3, Location::line(11), true));
        assert_eq!(e.found, "end of file");
        // The worded errors: file, line, column, expected, found.
        let src = Source::new(p, text).unwrap();
        let mut s = Scanner::new(text, 7, 2, sep);
        let e = s
            .numbers_into(&src, 4, &mut Vec::new(), &|i| format!("value #{}", i + 1))
            .unwrap_err();
        assert_eq!(
            (e.location, e.expected.as_str(), e.found.as_str()),
            (Location::at(3, 3), "value #4", "`x4`")
        );
        assert!(e.to_string().starts_with("f.txt:3:3"), "{e}");
        let mut s = Scanner::new(&text[..12], 7, 2, sep);
        let e = s
            .numbers_into(&src, 4, &mut Vec::new(), &|i| format!("value #{}", i + 1))
            .unwrap_err();
        assert_eq!(
            (e.location, e.expected.as_str(), e.found.as_str()),
            (Location::line(3), "value #4 (3 of 4 values read)", "end of file")
        );
        let mut s = Scanner::new(text, 7, 2, sep);
        s.fill(3, &mut Vec::new()).unwrap();
        let e = s.number(&src, "n").unwrap_err();
        assert_eq!((e.location, e.found.as_str()), (Location::at(3, 3), "`x4`"));
        assert_eq!(s.number(&src, "n").unwrap(), 5.0);
        let e = s.number(&src, "n").unwrap_err();
        assert_eq!((e.location, e.found.as_str()), (Location::line(3), "end of file"));
        let e = Scanner::new(text, 7, 2, sep).integer(&src, "count", 2, 9).unwrap_err();
        assert_eq!(
            (e.location, e.expected.as_str()),
            (Location::at(2, 1), "count (integer 2..=9)")
        );
    }
}

#[test]
fn marks_locate_later_tokens_and_count_them() {
    let text = b"1, 2\r\n3 ; c 9\r4\n\n  5 !x\n,,6\x1a";
    let s = Scanner::new(text, 0, 1, Separators::BlanksAndCommas);
    assert_eq!(s.count_remaining(), 6);
    assert!(s.count_remaining() <= s.max_remaining());
    assert_eq!(s.nth(4), (Location::at(5, 3), "`5`".to_string()));
    assert_eq!(s.nth(6), (Location::line(6), "end of file".to_string()));
    let mut m = s.clone();
    m.fill(2, &mut Vec::new()).unwrap();
    assert_eq!(m.next_line(), 2);
    assert_eq!(m.nth(0).0, Location::at(2, 1));
    assert!(m.has_more());
    m.fill(4, &mut Vec::new()).unwrap();
    assert!(!m.has_more());
    // The bound holds for the densest text: one-byte tokens, one separator each.
    for t in [&b"1"[..], b"1 2", b"1 2 3 4", b"12 3"] {
        let s = Scanner::new(t, 0, 1, Separators::Blanks);
        assert!(s.count_remaining() <= s.max_remaining(), "{t:?}");
    }
}

#[test]
fn fast_and_slow_paths_agree_with_std() {
    let toks = [
        "0",
        "12.5",
        "-3.25",
        ".5",
        "5.",
        "1e5",
        "1.5E-3",
        "+7",
        "123456789012345678901",
        "0.30000000000000004",
        "9007199254740993",
        "1e-320",
    ];
    let text = toks.join(" ");
    let mut out = Vec::new();
    Scanner::new(text.as_bytes(), 0, 1, Separators::BlanksAndCommas)
        .fill(toks.len(), &mut out)
        .unwrap();
    let expected: Vec<f64> = toks.iter().map(|t| t.parse().unwrap()).collect();
    assert_eq!(out, expected);
}

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
fn numbers_accept_decimal_commas() {
    assert_eq!(parse_number(b"12,5"), Some(12.5));
    assert_eq!(parse_number(b"-0,25"), Some(-0.25));
    assert_eq!(parse_number(b"1.0"), Some(1.0));
    assert_eq!(parse_number(b"1,2,3"), None);
    assert_eq!(parse_number(b"1.2,3"), None);
    assert_eq!(parse_number(b","), None);
    assert_eq!(parse_number(b"abc"), None);
}
