//! The public paths that code outside the crate relies on (benchmarks, the
//! Python bindings, users): ARCHITECTURE.md, "Public API". Each is named here
//! with its signature, so a move that breaks one (a module moved down the
//! layers without its re-export) fails this build, not a user's.

use std::path::Path;

use photosolid::formats::{parse, sniff, Document};
use photosolid::model::{Distribution, Format, Luminaire};
use photosolid::photometry::{flux, Flux};
use photosolid::reconstruct::{Filter, LightTexture, Sampler};
use photosolid::{ParseError, ReadOptions};

/// The paths with their signatures, and one file read through them.
#[test]
fn the_public_paths_read_a_file_and_sample_it() {
    let _: fn(&[u8]) -> Format = sniff;
    let _: fn(&[u8], &Path, Format, &ReadOptions) -> Result<Document, ParseError> = parse;
    let _: fn(&Luminaire) -> &Distribution = Luminaire::distribution;
    let _: fn(&Distribution) -> Flux = flux;
    let _: for<'t> fn(&'t LightTexture, Filter) -> Sampler<'t> = LightTexture::sampler;
    let _: fn(&Sampler<'static>, f64, f64) -> f64 = Sampler::cd;
    let _: photosolid::formats::ReadOptions = ReadOptions::default();

    let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/data/lambertian.ldt"));
    let bytes = std::fs::read(path).unwrap();
    let format = sniff(&bytes);
    assert_eq!(format, Format::Ldt);
    let doc: Document = parse(&bytes, path, format, &ReadOptions::default()).unwrap();
    let lum: &Luminaire = &doc.luminaire;
    let d = lum.distribution();
    assert!(flux(d).total_lm > 0.0);
    let tex = LightTexture::new(d).unwrap();
    // Catmull-Rom interpolates: the measured value at (C0, γ0) comes back.
    let (c0, g0) = (d.c_angles_deg()[0], d.gamma_angles_deg()[0]);
    let at = tex.sampler(Filter::CatmullRom).cd(c0, g0);
    assert!((at - d.value_cd(0, 0)).abs() <= 1e-9 * d.value_cd(0, 0), "{at}");
}
