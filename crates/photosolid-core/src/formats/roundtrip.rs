//! The lossless round-trip property of the writers, as one checkable
//! function: for a loaded luminaire, writing it in either format and reading
//! the text back gives the same distribution within the writer's documented
//! precision. The fuzz targets, the property tests and the damaged-file
//! tests all check it through [`check`].

use std::path::Path;

use crate::error::{Difference, Error};
use crate::formats::{ies, ldt, tm33, Document, ReadOptions};
use crate::model::{Distribution, Format, ANGLE_EPS};

/// Relative tolerance (of the peak |cd|) of the IES writer: 15 significant
/// digits when the header's factors are not 1, exact otherwise.
pub const IES_TOLERANCE: f64 = 1e-12;

/// Relative tolerance (of the peak |cd|) of the EULUMDAT writer: 8
/// significant digits on the values (5e-8 of the peak) and on the flux and
/// CFLI they are scaled by (5e-8 each), plus a reader's move back into the
/// model's range at its ends (as large again, see [`crate::formats::RANGE_SNAP`]).
pub const LDT_TOLERANCE: f64 = 5e-7;

/// Relative tolerance (of the peak |cd|) of the TM-33-23 writer: none; it
/// writes the absolute candela with shortest round-trip decimals and
/// `Multiplier` 1, so the values read back bit for bit.
pub const TM33_TOLERANCE: f64 = 0.0;

/// Write `lum` as IES (LM-63-2002 and 2019), EULUMDAT and TM-33-23, read each text
/// back and compare the distributions: same γ angles (within
/// [`ANGLE_EPS`]), every full-circle plane of `lum` present in the copy,
/// every value within the writer's tolerance × the peak.
///
/// # Errors
/// [`Error::RoundTripRead`] naming the format when the written text does not
/// read back; [`Error::RoundTrip`] with the first [`Difference`] otherwise.
pub fn check(doc: &Document) -> Result<(), Error> {
    let lum = &doc.luminaire;
    let opts = ReadOptions::default();
    let cases = [
        (
            "IES LM-63-2002",
            Format::Ies,
            ies::write(doc, ies::IesWriteVersion::Lm63_2002),
            IES_TOLERANCE,
        ),
        (
            "IES LM-63-2019",
            Format::Ies,
            ies::write(doc, ies::IesWriteVersion::Lm63_2019),
            IES_TOLERANCE,
        ),
        ("EULUMDAT", Format::Ldt, ldt::write(doc), LDT_TOLERANCE),
        ("TM-33-23", Format::Tm33, tm33::write(doc), TM33_TOLERANCE),
    ];
    for (name, format, text, tol) in cases {
        let path = Path::new(match format {
            Format::Ies => "<round-trip>.ies",
            Format::Ldt => "<round-trip>.ldt",
            Format::Tm33 => "<round-trip>.xml",
        });
        let back = crate::formats::parse(text.as_bytes(), path, format, &opts).map_err(|e| Error::RoundTripRead {
            format: name,
            source: Box::new(e.into()),
        })?;
        same_distribution(lum.distribution(), back.luminaire.distribution(), tol).map_err(|difference| {
            Error::RoundTrip {
                format: name,
                difference,
            }
        })?;
    }
    Ok(())
}

/// Whether `back` holds `orig` within `tol` × the peak |cd| of `orig`: same
/// γ angles, and every full-circle plane of `orig` a plane of `back`.
///
/// # Errors
/// The first [`Difference`] found.
pub fn same_distribution(orig: &Distribution, back: &Distribution, tol: f64) -> Result<(), Difference> {
    let (g0, g1) = (orig.gamma_angles_deg(), back.gamma_angles_deg());
    if g0.len() != g1.len() || g0.iter().zip(g1).any(|(a, b)| (a - b).abs() > ANGLE_EPS) {
        return Err(Difference::GammaAngles {
            orig: g0.to_vec(),
            back: g1.to_vec(),
        });
    }
    let peak = orig.intensities_cd().iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let allowed = tol * peak;
    let planes: Vec<(f64, usize)> = if orig.symmetry() == crate::model::Symmetry::Rotational {
        vec![(0.0, 0)]
    } else {
        orig.full_planes()
    };
    for (c, ic) in planes {
        for (ig, &g) in g0.iter().enumerate() {
            let want = orig.value_cd(ic, ig);
            let got = if back.symmetry() == crate::model::Symmetry::Rotational {
                Some(back.value_cd(0, ig))
            } else {
                back.value_at_plane_cd(c, ig)
            };
            match got {
                None => {
                    return Err(Difference::MissingPlane {
                        c,
                        back: back.c_angles_deg().to_vec(),
                    })
                }
                Some(v) if (v - want).abs() > allowed || !v.is_finite() => {
                    return Err(Difference::Value {
                        c,
                        gamma: g,
                        want,
                        got: v,
                        allowed,
                    })
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// Names of the non-finite numbers in a value's `Debug` text (`NaN`, `inf`,
/// `-inf` as whole words); empty when every number is finite. `Debug` is
/// used because it prints NaN and infinity literally, where JSON turns them
/// into `null` like an absent optional value.
pub fn non_finite_in_debug(debug: &str) -> Vec<String> {
    let b = debug.as_bytes();
    let word = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut found = Vec::new();
    for pat in ["NaN", "inf"] {
        let p = pat.as_bytes();
        let mut i = 0;
        while i + p.len() <= b.len() {
            if &b[i..i + p.len()] == p
                && (i == 0 || !word(b[i - 1]))
                && (i + p.len() == b.len() || !word(b[i + p.len()]))
            {
                let from = debug[..i].char_indices().rev().nth(40).map_or(0, |(k, _)| k);
                found.push(debug[from..i + p.len()].to_string());
            }
            i += 1;
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn debug_scan_finds_nan_and_inf_words_only() {
        assert!(non_finite_in_debug("Flux { total_lm: 1.0, info: \"infinite\" }").is_empty());
        assert_eq!(non_finite_in_debug("x: NaN, y: -inf").len(), 2);
    }

    #[test]
    fn every_data_file_round_trips() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
        let mut n = 0;
        let mut files = Vec::new();
        crate::formats::collect_files(&dir, &mut files).unwrap();
        for p in files {
            let doc = crate::formats::load_document(&p).unwrap();
            check(&doc).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            n += 1;
        }
        assert!(n >= 10);
    }
}
