//! Property: every luminaire the model accepts survives write -> read in both
//! formats within the writer's documented precision
//! ([`photosolid::formats::roundtrip::check`]), including the cases the
//! fuzzer found: several lamp sets whose text fields look like numbers,
//! angles closer than the writers' decimals, C90-C270 data, and magnitudes
//! at the ends of the model's range. Then the regression inputs found by
//! fuzzing and by the damaged-file corpus, as bytes.

use std::path::Path;

use photosolid::formats::roundtrip::check;
use photosolid::model::{Format, LampSet, MAX_CD, MIN_PEAK_CD};
use photosolid::{Distribution, Luminaire, ReadOptions, Symmetry};
use proptest::prelude::*;

/// Ascending angles from gaps (degrees), scaled to end exactly at `hi` when `span` is set.
fn angles_from(gaps: &[f64], lo: f64, hi: Option<f64>) -> Vec<f64> {
    let mut v = vec![lo];
    for g in gaps {
        v.push(v[v.len() - 1] + g);
    }
    if let Some(hi) = hi {
        let k = (hi - lo) / (v[v.len() - 1] - lo);
        v.iter_mut().for_each(|a| *a = lo + (*a - lo) * k);
        let n = v.len();
        v[n - 1] = hi;
    }
    v
}

fn symmetry() -> impl Strategy<Value = Symmetry> {
    prop_oneof![
        Just(Symmetry::None),
        Just(Symmetry::Rotational),
        Just(Symmetry::C0C180),
        Just(Symmetry::C90C270),
        Just(Symmetry::Quadrant),
    ]
}

/// Text fields that look like numbers as often as like text.
fn field() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(String::new()),
        "[0-9]{1,4}",
        "[A-Za-z ]{1,12}",
        "-?[0-9]{1,3}\\.[0-9]"
    ]
}

fn lamp_set() -> impl Strategy<Value = LampSet> {
    (1.0..8.0f64, field(), 1.0..1e5f64, field(), field(), 0.0..500.0f64).prop_map(
        |(count, lamp_type, flux_lm, color, cri, watts)| LampSet {
            count: count.round(),
            lamp_type,
            flux_lm,
            color,
            cri,
            watts,
        },
    )
}

prop_compose! {
    fn luminaire()(
        sym in symmetry(),
        n_c in 2usize..9,
        n_g in 1usize..12,
        // Gaps between angles: down to 2e-6 degrees, closer than the writers' 9 decimals round.
        tiny in prop::bool::ANY,
        seed in prop::collection::vec(0.0..1.0f64, 200),
        magnitude in prop_oneof![Just(MIN_PEAK_CD), Just(1e-6), Just(1.0), Just(1e3), Just(1e6), Just(MAX_CD)],
        sets in prop::collection::vec(lamp_set(), 1..4),
        relative in prop::bool::ANY,
    ) -> Luminaire {
        let gap = |i: usize| if tiny && i.is_multiple_of(3) { 2e-6 + seed[i] * 1e-6 } else { 0.5 + seed[i] * 10.0 };
        let g_gaps: Vec<f64> = (0..n_g - 1).map(gap).collect();
        let gamma = angles_from(&g_gaps, seed[50] * 10.0, None);
        let gamma: Vec<f64> = if gamma[gamma.len() - 1] > 180.0 { angles_from(&g_gaps, 0.0, Some(180.0)) } else { gamma };
        let (lo, hi) = sym.stored_range();
        // C90-C270 needs a plane between its two mirror planes.
        let n_c = if sym == Symmetry::C90C270 { n_c.max(3) } else { n_c };
        let c_gaps: Vec<f64> = (0..n_c - 1).map(|i| gap(i + 20)).collect();
        let c = match sym {
            Symmetry::Rotational => vec![0.0],
            Symmetry::None => {
                let v = angles_from(&c_gaps, 0.0, None);
                if v[v.len() - 1] >= 359.0 { angles_from(&c_gaps, 0.0, Some(350.0)) } else { v }
            }
            _ => angles_from(&c_gaps, lo, Some(hi)),
        };
        let cd: Vec<f64> = (0..c.len() * gamma.len()).map(|i| magnitude * seed[(i * 7 + 3) % 200]).collect();
        let mut cd = cd;
        cd[0] = magnitude; // the peak is the magnitude
        let d = Distribution::new(c, gamma, cd, sym).expect("a valid distribution");
        let mut lum = Luminaire::from_distribution(d);
        lum.set_lamp_sets(sets).unwrap();
        if relative {
            let flux = lum.lamp_sets()[0].flux_lm;
            lum.declared_mut().absolute = false;
            lum.declared_mut().lamp_flux_lm = Some(flux);
        }
        lum
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn written_files_read_back_the_same(lum in luminaire()) {
        let lum = photosolid::formats::Document::bare(lum);
        check(&lum).map_err(|e| TestCaseError::fail(e.to_string()))?;
        // Lamp sets come back in their own layout, whatever their text fields hold.
        let text = photosolid::formats::ldt::write(&lum);
        let back = photosolid::formats::ldt::read(text.as_bytes(), Path::new("p.ldt"), &ReadOptions::default()).unwrap();
        prop_assert_eq!(back.lamp_sets().len(), lum.lamp_sets().len());
        for (a, b) in back.lamp_sets().iter().zip(lum.lamp_sets()).skip(1) {
            // Text fields are read trimmed.
            prop_assert_eq!(a.lamp_type.trim(), b.lamp_type.trim());
            prop_assert!((a.flux_lm - b.flux_lm).abs() <= 1e-7 * b.flux_lm);
        }
    }
}

/// Parse `bytes`; a load must round-trip (the fuzz targets' check).
fn loads_and_round_trips(bytes: &[u8], format: Format) {
    let path = Path::new("/nonexistent/regression").with_extension(match format {
        Format::Ies => "ies",
        Format::Ldt => "ldt",
        Format::Tm33 => "xml",
    });
    if let Ok(lum) = photosolid::formats::parse(bytes, &path, format, &ReadOptions::default()) {
        check(&lum).unwrap();
        let s = format!("{:?}", photosolid::photometry::summary(&lum));
        assert!(
            photosolid::formats::roundtrip::non_finite_in_debug(&s).is_empty(),
            "{s}"
        );
    }
}

#[test]
fn huge_candela_values_are_refused_not_overflowed() {
    // Finite but near f64::MAX: the flux used to overflow to inf.
    let ies = b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n1e308 1e308\n";
    let e = photosolid::formats::parse(ies, Path::new("h.ies"), Format::Ies, &ReadOptions::default()).unwrap_err();
    assert_eq!(e.location.line, 7, "{e}");
    assert!(e.found.contains("exceeds"), "{e}");
    // Multiplier x ballast factor that underflows: refused at the ballast line, not written as NaN later.
    let ies = b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1e-200 2 1 1 2 0 0 0\n1e-200 1 0\n0 90\n0\n100 10\n";
    let e = photosolid::formats::parse(ies, Path::new("u.ies"), Format::Ies, &ReadOptions::default()).unwrap_err();
    assert_eq!(e.location.line, 4, "{e}");
    // A subnormal peak (the fit used to divide by it): round-off, read as zero with a warning.
    let ies = b"IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 90\n0\n4.9e-324 0\n";
    let l = photosolid::formats::parse(ies, Path::new("s.ies"), Format::Ies, &ReadOptions::default()).unwrap();
    assert_eq!(l.distribution().max_cd(), 0.0);
    assert!(
        l.warnings().iter().any(|w| w.code == "range-snapped"),
        "{:?}",
        l.warnings()
    );
    let fit = photosolid::fit::fit(l.distribution(), &Default::default());
    assert!(fit.is_err(), "an all-zero distribution has nothing to fit");
    // Scaling (the TILT path) that would leave the range is refused; scaling to round-off gives zero.
    let d = Distribution::new(vec![0.0], vec![0.0, 90.0], vec![1e9, 1.0], Symmetry::Rotational).unwrap();
    assert!(d.scaled(1e4).is_err());
    assert_eq!(d.scaled(1e-30).unwrap().max_cd(), 0.0);
    assert_eq!(d.scaled(1e-9).unwrap().max_cd(), 1.0);
}

#[test]
fn close_angles_and_mirror_only_c90_c270_are_refused_by_the_model() {
    // Angles closer than 1e-6 degree collapse in any writer: the model refuses them.
    assert!(Distribution::new(vec![0.0], vec![0.0, 1e-9, 90.0], vec![1.0; 3], Symmetry::Rotational).is_err());
    // C90-C270 with the planes 90 and 270 only: the IES reader refused it, the LDT reader loaded it.
    assert!(Distribution::new(vec![90.0, 270.0], vec![0.0, 90.0], vec![1.0; 4], Symmetry::C90C270).is_err());
    let ldt = [
        "m", "1", "3", "2", "180", "2", "90", "", "", "", "", "", "0", "0", "0", "0", "0", "0", "0", "0", "0", "100",
        "100", "1", "0", "1", "-1", "LED", "1000", "", "", "10", "0", "0", "0", "0", "0", "0", "0", "0", "0", "0",
        "90", "270", "0", "90", "100", "10", "50", "5",
    ]
    .join("\r\n");
    let e = photosolid::formats::parse(ldt.as_bytes(), Path::new("m.ldt"), Format::Ldt, &ReadOptions::default())
        .unwrap_err();
    assert!(e.found.contains("C90-C270"), "{e}");
    assert!(e.location.line >= 1);
}

#[test]
fn two_lamp_sets_with_numeric_text_fields_keep_their_layout() {
    // Field groups whose type and colour fields are numbers used to be read as blocks (100 cd -> 0.20 cd).
    let mut lum = Luminaire::from_distribution(
        Distribution::new(vec![0.0], vec![0.0, 90.0], vec![100.0, 10.0], Symmetry::Rotational).unwrap(),
    );
    let set = |t: &str, f: f64, cri: &str| LampSet {
        count: 1.0,
        lamp_type: t.into(),
        flux_lm: f,
        color: "830".into(),
        cri: cri.into(),
        watts: 10.0,
    };
    // Read as blocks, set 1 would have type "2", flux "1" lm ... and one text field ("1B")
    // where field groups have none: the old text tie-break chose blocks.
    lum.set_lamp_sets(vec![set("1", 1000.0, "80"), set("2", 500.0, "1B")])
        .unwrap();
    lum.declared_mut().absolute = false;
    lum.declared_mut().lamp_flux_lm = Some(1000.0);
    let lum = photosolid::formats::Document::bare(lum);
    check(&lum).unwrap();
    let text = photosolid::formats::ldt::write(&lum);
    let back = photosolid::formats::parse(
        text.as_bytes(),
        Path::new("l.ldt"),
        Format::Ldt,
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(back.lamp_sets()[1].cri, "1B");
    assert_eq!(back.distribution().plane_cd(0), &[100.0, 10.0]);
    loads_and_round_trips(text.as_bytes(), Format::Ldt);
}
