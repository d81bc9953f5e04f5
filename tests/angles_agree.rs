//! Both readers order and de-duplicate angle lists by one rule
//! (`formats::angles`): given the same unsorted list with a near-duplicate,
//! the IES and the EULUMDAT reader refuse it alike without the repair
//! option and, with it, load the same distribution.

use std::path::Path;

use photosolid::model::Format;
use photosolid::ReadOptions;

/// C-planes 0, 90, 90 + 1e-7 (a duplicate within 1e-6), 45, 180, 270 and
/// γ 0, 60, 30, 90, 90 + 5e-7; value = 1000 + 10 × plane index + γ index.
const C: [f64; 6] = [0.0, 90.0, 90.0000001, 45.0, 180.0, 270.0];
const G: [f64; 5] = [0.0, 60.0, 30.0, 90.0, 90.0000005];

fn value(ic: usize, ig: usize) -> f64 {
    1000.0 + 10.0 * ic as f64 + ig as f64
}

fn ies_text() -> String {
    let mut s = String::from("IESNA:LM-63-2002\r\nTILT=NONE\r\n");
    s += &format!("1 -1 1 {} {} 1 2 0 0 0\r\n1 1 0\r\n", G.len(), C.len());
    let join = |v: &[f64]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ");
    s += &format!("{}\r\n{}\r\n", join(&G), join(&C));
    for ic in 0..C.len() {
        let row: Vec<f64> = (0..G.len()).map(|ig| value(ic, ig)).collect();
        s += &format!("{}\r\n", join(&row));
    }
    s
}

fn ldt_text() -> String {
    let mut lines: Vec<String> = vec!["Test".into(), "3".into(), "0".into(), C.len().to_string(), "0".into()];
    lines.extend([G.len().to_string(), "0".into()]);
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
    lines.extend(C.iter().chain(&G).map(|x| x.to_string()));
    for ic in 0..C.len() {
        lines.extend((0..G.len()).map(|ig| value(ic, ig).to_string()));
    }
    lines.join("\r\n") + "\r\n"
}

#[test]
fn ies_and_ldt_readers_agree_on_angle_order_and_duplicates() {
    let strict = ReadOptions::default();
    let repair = ReadOptions {
        repair: true,
        ..ReadOptions::default()
    };
    let (ies, ldt) = (ies_text(), ldt_text());
    let parse = |t: &str, f: Format, o: &ReadOptions| {
        let p = Path::new(if f == Format::Ies { "a.ies" } else { "a.ldt" });
        photosolid::formats::parse(t.as_bytes(), p, f, o)
    };
    let e1 = parse(&ies, Format::Ies, &strict).unwrap_err();
    let e2 = parse(&ldt, Format::Ldt, &strict).unwrap_err();
    assert!(e1.location.line > 0 && e2.location.line > 0, "{e1} / {e2}");
    let a = parse(&ies, Format::Ies, &repair).unwrap();
    let b = parse(&ldt, Format::Ldt, &repair).unwrap();
    assert_eq!(a.distribution().c_angles(), &[0.0, 45.0, 90.0, 180.0, 270.0]);
    assert_eq!(a.distribution().gamma_angles(), &[0.0, 30.0, 60.0, 90.0]);
    assert_eq!(a.distribution().c_angles(), b.distribution().c_angles());
    assert_eq!(a.distribution().gamma_angles(), b.distribution().gamma_angles());
    assert_eq!(a.distribution().intensities(), b.distribution().intensities());
    // The first of the duplicates is kept: C90 is file plane 1, γ 90 is file angle 3.
    assert_eq!(a.distribution().value(2, 3), value(1, 3));
    assert_eq!(a.distribution().value(1, 1), value(3, 2));
}
