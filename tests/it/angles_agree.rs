//! Both readers order and de-duplicate angle lists by one rule
//! (`formats::angles`): given the same angle lists, the IES and the EULUMDAT
//! reader accept or refuse them alike (naming the same angle) without the
//! repair option and, with it, load the same distribution.

use std::path::Path;

use photosolid::formats::Document;
use photosolid::model::Format;
use photosolid::{ParseError, ReadOptions};

/// Value at file plane `ic`, file γ index `ig`: every value tells where it was read from.
fn value(ic: usize, ig: usize) -> f64 {
    1000.0 + 10.0 * ic as f64 + ig as f64
}

fn ies_text(c: &[f64], g: &[f64]) -> String {
    let mut s = String::from("IESNA:LM-63-2002\r\nTILT=NONE\r\n");
    s += &format!("1 -1 1 {} {} 1 2 0 0 0\r\n1 1 0\r\n", g.len(), c.len());
    let join = |v: &[f64]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ");
    s += &format!("{}\r\n{}\r\n", join(g), join(c));
    for ic in 0..c.len() {
        let row: Vec<f64> = (0..g.len()).map(|ig| value(ic, ig)).collect();
        s += &format!("{}\r\n", join(&row));
    }
    s
}

fn ldt_text(c: &[f64], g: &[f64]) -> String {
    let mut lines: Vec<String> = vec!["Test".into(), "3".into(), "0".into(), c.len().to_string(), "0".into()];
    lines.extend([g.len().to_string(), "0".into()]);
    lines.extend(["R", "Lum", "L-1", "t.ldt", "2024"].map(String::from));
    lines.extend(
        [
            "600", "300", "50", "500", "0", "40", "40", "40", "40", "80", "90", "1", "0", "1",
        ]
        .map(String::from),
    );
    // One absolute lamp set of 1000 lm: cd/klm x 1000 / 1000 = cd.
    lines.extend(["-1", "LED", "1000", "3000K", "80", "25"].map(String::from));
    lines.extend((0..10).map(|_| "0.5".to_string()));
    lines.extend(c.iter().chain(g).map(|x| x.to_string()));
    for ic in 0..c.len() {
        lines.extend((0..g.len()).map(|ig| value(ic, ig).to_string()));
    }
    lines.join("\r\n") + "\r\n"
}

/// The IES and the EULUMDAT reading of the same lists.
fn both(c: &[f64], g: &[f64], repair: bool) -> [Result<Document, ParseError>; 2] {
    let o = ReadOptions {
        repair,
        ..ReadOptions::default()
    };
    let ies = photosolid::formats::parse(ies_text(c, g).as_bytes(), Path::new("a.ies"), Format::Ies, &o);
    let ldt = photosolid::formats::parse(ldt_text(c, g).as_bytes(), Path::new("a.ldt"), Format::Ldt, &o);
    [ies, ldt]
}

fn assert_same_grid(a: &Document, b: &Document) {
    assert_eq!(a.distribution().c_angles_deg(), b.distribution().c_angles_deg());
    assert_eq!(a.distribution().gamma_angles_deg(), b.distribution().gamma_angles_deg());
    assert_eq!(a.distribution().intensities_cd(), b.distribution().intensities_cd());
}

#[test]
fn ies_and_ldt_readers_agree_on_angle_order_and_duplicates() {
    // C-planes 0, 90, 90 + 1e-7 (a duplicate within 1e-6), 45, 180, 270 and
    // γ 0, 60, 30, 90, 90 + 5e-7.
    let c = [0.0, 90.0, 90.0000001, 45.0, 180.0, 270.0];
    let g = [0.0, 60.0, 30.0, 90.0, 90.0000005];
    let [e1, e2] = both(&c, &g, false);
    let (e1, e2) = (e1.unwrap_err(), e2.unwrap_err());
    assert!(e1.location.line > 0 && e2.location.line > 0, "{e1} / {e2}");
    let [a, b] = both(&c, &g, true).map(Result::unwrap);
    assert_eq!(a.distribution().c_angles_deg(), &[0.0, 45.0, 90.0, 180.0, 270.0]);
    assert_eq!(a.distribution().gamma_angles_deg(), &[0.0, 30.0, 60.0, 90.0]);
    assert_same_grid(&a, &b);
    // The first of the duplicates is kept: C90 is file plane 1, γ 90 is file angle 3.
    assert_eq!(a.distribution().value_cd(2, 3), value(1, 3));
    assert_eq!(a.distribution().value_cd(1, 1), value(3, 2));
}

#[test]
fn one_disorder_at_a_time_is_named_alike_and_repaired_alike() {
    let c = [0.0, 90.0, 180.0, 270.0];
    let g = [0.0, 30.0, 60.0, 90.0];
    // (C list, γ list, number of the first offending angle, the repaired lists).
    type Case<'a> = (&'a [f64], &'a [f64], usize, &'a [f64], &'a [f64]);
    let cases: [Case; 4] = [
        // A C duplicate within 1e-6: the first is kept.
        (&[0.0, 90.0, 90.0000001, 180.0, 270.0], &g, 3, &c, &g),
        // An unsorted γ list.
        (&c, &[0.0, 60.0, 30.0, 90.0], 3, &c, &g),
        // A γ duplicate at the end of the list.
        (&c, &[0.0, 30.0, 60.0, 90.0, 90.0000005], 5, &c, &g),
        // An unsorted C list with an exact duplicate.
        (&[0.0, 180.0, 90.0, 90.0, 270.0], &g, 3, &c, &g),
    ];
    for (ci, gi, bad, c_fixed, g_fixed) in cases {
        let [e1, e2] = both(ci, gi, false).map(|r| r.unwrap_err().to_string());
        let named = format!("#{bad} = ");
        assert!(e1.contains(&named) && e2.contains(&named), "{named}: {e1} / {e2}");
        let [a, b] = both(ci, gi, true).map(Result::unwrap);
        assert_eq!(a.distribution().c_angles_deg(), c_fixed, "{ci:?}");
        assert_eq!(a.distribution().gamma_angles_deg(), g_fixed, "{gi:?}");
        assert_same_grid(&a, &b);
    }
}

#[test]
fn angles_just_beyond_the_tolerance_are_distinct_for_both() {
    // 2e-6 apart: more than the 1e-6 rule, so both readers keep both planes without repair.
    let c = [0.0, 90.0, 90.000002, 180.0, 270.0];
    let g = [0.0, 30.0, 30.000002, 90.0];
    let [a, b] = both(&c, &g, false).map(Result::unwrap);
    assert_eq!(a.distribution().c_angles_deg(), &c);
    assert_eq!(a.distribution().gamma_angles_deg(), &g);
    assert_same_grid(&a, &b);
}
