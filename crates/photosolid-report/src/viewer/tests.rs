//! Tests of the viewer's data: read back with an independent base64 decoder.

use super::*;
use crate::model::IntensityField;

/// An independent RFC 4648 decoder (the `base64` crate, not our encoder run backwards).
fn decode_b64(s: &str) -> Vec<u8> {
    use base64::Engine as _;
    base64::engine::general_purpose::STANDARD
        .decode(s)
        .expect("valid base64")
}

fn u16s(b: &[u8]) -> Vec<u16> {
    b.chunks(2).map(|c| u16::from_le_bytes([c[0], c[1]])).collect()
}

fn i16s(b: &[u8]) -> Vec<i16> {
    b.chunks(2).map(|c| i16::from_le_bytes([c[0], c[1]])).collect()
}

/// A cosine lobe pointing down (I_max 1000 cd at nadir) plus a 100 cd floor.
fn lobe(_c: f64, g: f64) -> f64 {
    100.0 + 900.0 * g.to_radians().cos().max(0.0)
}

#[test]
fn base64_round_trips_every_length() {
    for n in 0..40usize {
        let bytes: Vec<u8> = (0..n).map(|k| (k * 37 + 11) as u8).collect();
        let enc = base64(&bytes);
        assert_eq!(enc.len(), n.div_ceil(3) * 4, "{n}");
        assert_eq!(decode_b64(&enc), bytes, "{n}");
    }
    assert_eq!(base64(b"Man"), "TWFu");
    assert_eq!(base64(b"Ma"), "TWE=");
}

#[test]
fn the_grid_is_the_finest_that_fits_the_budget() {
    for n in 0..30 {
        let (dc, dg) = grid_step(n);
        assert!(STEPS_DEG.contains(&(dc, dg)));
        assert_eq!((360.0 / dc).fract(), 0.0);
        assert_eq!((180.0 / dg).fract(), 0.0);
        let bytes = |dc: f64, dg: f64| (360.0 / dc) as usize * (180.0 / dg + 1.0) as usize * (6 + 2 * (n + 1) + 2 * n);
        let k = STEPS_DEG.iter().position(|&s| s == (dc, dg)).unwrap();
        if k + 1 < STEPS_DEG.len() || bytes(dc, dg) <= MESH_BUDGET_BYTES {
            assert!(bytes(dc, dg) <= MESH_BUDGET_BYTES, "{n} solids at {dc} x {dg}");
        }
        if k > 0 {
            let (fc, fg) = STEPS_DEG[k - 1];
            assert!(bytes(fc, fg) > MESH_BUDGET_BYTES, "{n}: a finer grid fits");
        }
    }
    // One reconstruction gets the finest grid, the default seven (and the reference) a 5 x 2.5 degree one.
    assert_eq!(grid_step(1), (2.0, 2.0));
    assert_eq!(grid_step(7), (5.0, 2.5));
}

#[test]
fn positions_and_errors_decode_to_the_fields() {
    let over = |c: f64, g: f64| lobe(c, g) + 50.0;
    let under = |c: f64, g: f64| lobe(c, g) - 20.0;
    let recons: Vec<(String, &dyn IntensityField)> = vec![("over".into(), &over), ("under".into(), &under)];
    let d = ViewerData::new(&SolidSet {
        reference_label: "truth (test lobe)",
        reference: &lobe,
        recons: &recons,
        i_max: 1000.0,
        note: None,
        error_domain: None,
    });
    assert_eq!((d.c_step_deg, d.gamma_step_deg), grid_step(2));
    assert_eq!(d.solids.len(), 3);
    assert_eq!(d.solids[0].role, "reference");
    let (nc, ng) = (d.nc, d.ng);
    assert_eq!(nc as f64 * d.c_step_deg, 360.0);
    assert_eq!((ng - 1) as f64 * d.gamma_step_deg, 180.0);
    // The largest radius is the over-estimate's peak.
    assert!((d.radius - 1050.0).abs() < 1e-9, "{}", d.radius);
    let tol = d.radius / 65535.0 + d.radius * 3f64.sqrt() / 32767.0;
    let dirs = i16s(&decode_b64(&d.directions));
    assert_eq!(dirs.len(), 3 * nc * ng);
    for (s, f) in d.solids.iter().zip([&lobe as &dyn IntensityField, &over, &under]) {
        let q = u16s(&decode_b64(&s.radius));
        assert_eq!(q.len(), nc * ng);
        for ic in 0..nc {
            for ig in 0..ng {
                let v = ic * ng + ig;
                let p: Vec<f64> = (0..3)
                    .map(|k| f64::from(dirs[3 * v + k]) / 32767.0 * dequantise_u16(q[v], d.radius))
                    .collect();
                let (c, g) = (ic as f64 * d.c_step_deg, ig as f64 * d.gamma_step_deg);
                let want = f.intensity_cd(c, g);
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                assert!((r - want).abs() <= tol, "{} at ({c}, {g}): {r} vs {want}", s.name);
                // The luminaire frame: nadir is -z, C0 is +x, C90 is +y.
                if ig == 0 {
                    assert!(p[2] < -0.99 * want, "nadir {p:?}");
                }
                if ig == ng / 2 && c == 90.0 {
                    assert!(p[1] > 0.99 * want && p[0].abs() <= tol, "C90 {p:?}");
                }
                if ig == ng / 2 && c == 0.0 {
                    assert!(p[0] > 0.99 * want && p[1].abs() <= tol, "C0 {p:?}");
                }
            }
        }
    }
    // Errors in % of I_max: +5 % everywhere for `over`, -2 % for `under`.
    assert!((d.err_max_pct - 5.0).abs() < 1e-9);
    assert_eq!([d.solids[1].scale_pct, d.solids[2].scale_pct], [5.0, 2.0]);
    for (s, want) in d.solids[1..].iter().zip([5.0f64, -2.0]) {
        assert!((s.max_abs_err_pct - want.abs()).abs() < 1e-9);
        for e in i16s(&decode_b64(&s.err)) {
            let pct = f64::from(e) / 32767.0 * d.err_max_pct;
            assert!((pct - want).abs() < 2.0 * d.err_max_pct / 32767.0, "{} {pct}", s.name);
        }
    }
    assert!(d.solids[0].err.is_empty());
}

#[test]
fn colours_are_blue_below_and_red_above_the_reference() {
    let d = ViewerData::new(&SolidSet {
        reference_label: "r",
        reference: &lobe,
        recons: &[],
        i_max: 1000.0,
        note: None,
        error_domain: None,
    });
    let (lo, mid, hi) = (d.lut[0], d.lut[d.lut.len() / 2], d.lut[d.lut.len() - 1]);
    assert!(lo[2] > lo[0] + 50, "negative end is blue: {lo:?}");
    assert!(hi[0] > hi[2] + 50, "positive end is red: {hi:?}");
    assert!(mid.iter().all(|&x| x > 230), "zero is near white: {mid:?}");
    // The heat maps' colour map, so the PNGs and the 3D view agree.
    assert_eq!(hi, ColorMap::RdBu.rgb8(1.0));
    assert_eq!(d.err_max_pct, 0.0);
    assert_eq!(nice_ceiling(0.0), 1.0);
    assert_eq!(nice_ceiling(87.79), 100.0);
    assert_eq!(nice_ceiling(2.96), 5.0);
    assert_eq!(nice_ceiling(0.0123), 0.02);
    assert_eq!(nice_ceiling(2.0), 2.0);
}

#[test]
fn extremes_give_finite_data() {
    let nan = |_c: f64, g: f64| if g > 90.0 { f64::NAN } else { 1e6 };
    let zero = |_c: f64, _g: f64| 0.0;
    let tiny = |_c: f64, _g: f64| 1e-6;
    let recons: Vec<(String, &dyn IntensityField)> = vec![("nan".into(), &nan), ("tiny".into(), &tiny)];
    for i_max in [0.0, f64::NAN, 1e-6] {
        let d = ViewerData::new(&SolidSet {
            reference_label: "all zero",
            reference: &zero,
            recons: &recons,
            i_max,
            note: None,
            error_domain: None,
        });
        for x in [d.i_max, d.radius, d.err_max_pct, d.solids[1].scale_pct] {
            assert!(x.is_finite() && x > 0.0, "{x}");
        }
        let json = serde_json::to_string(&d).unwrap();
        assert!(!json.contains("null") || json.contains("\"note\":null"), "{json:.200}");
    }
}

#[test]
fn the_fragment_is_self_contained_escaped_and_small() {
    let fields: Vec<Box<dyn Fn(f64, f64) -> f64 + Sync>> = (0..6)
        .map(|k| {
            Box::new(move |c: f64, g: f64| lobe(c, g) * (1.0 + 0.01 * k as f64)) as Box<dyn Fn(f64, f64) -> f64 + Sync>
        })
        .collect();
    let mut recons: Vec<(String, &dyn IntensityField)> = fields
        .iter()
        .enumerate()
        .map(|(k, f)| (format!("r{k}"), f as &dyn IntensityField))
        .collect();
    recons[0].0 = "</script><b>x</b>".into();
    let d = ViewerData::new(&SolidSet {
        reference_label: "truth <lobe> & co",
        reference: &lobe,
        recons: &recons,
        i_max: 1000.0,
        note: None,
        error_domain: None,
    });
    let h = html(&d, "the figures");
    assert_eq!(
        h.matches("</script>").count(),
        2,
        "only the data and code elements close"
    );
    assert!(h.contains("truth &lt;lobe&gt; &amp; co"));
    for bad in ["http://", "https://", "<script src", "<link", "url("] {
        assert!(!h.contains(bad), "{bad}");
    }
    // Seven solids of the default comparison: the fragment stays well under 1 MB.
    assert!(h.len() < 320_000, "{} bytes", h.len());
    assert!(
        h.len() > MESH_BUDGET_BYTES / 2,
        "the meshes are in it: {} bytes",
        h.len()
    );
    // The JSON inside parses back.
    let start = h.find("class=\"psv-data\">").unwrap() + "class=\"psv-data\">".len();
    let end = start + h[start..].find("</script>").unwrap();
    let v: serde_json::Value = serde_json::from_str(&h[start..end]).unwrap();
    assert_eq!(v["solids"][1]["name"], "</script><b>x</b>");
    assert_eq!(v["nc"], 72);
}

/// A cropped representation's error is measured over the directions it keeps, and the
/// legend says so: 0 outside the crop is not an error of the crop.
#[test]
fn a_cropped_recon_is_measured_over_the_directions_it_keeps() {
    use crate::compare::view::ErrorDomain;
    let full = |_c: f64, g: f64| 100.0 + g;
    let cropped = |_c: f64, g: f64| if g <= 44.0 { 100.0 + g } else { 0.0 };
    let recons: Vec<(String, &dyn IntensityField)> = vec![("catmull-rom+gamma:0-44".into(), &cropped)];
    let view = |error_domain| {
        ViewerData::new(&SolidSet {
            reference_label: "full",
            reference: &full,
            recons: &recons,
            i_max: 280.0,
            note: None,
            error_domain,
        })
    };
    let everywhere = view(None);
    assert!(
        everywhere.solids[1].max_abs_err_pct > 50.0,
        "{}",
        everywhere.solids[1].max_abs_err_pct
    );
    assert_eq!(everywhere.legend_quantity, "max |err|");
    let kept = view(Some(ErrorDomain {
        gamma_deg: (0.0, 44.0),
        c_deg: None,
    }));
    assert!(
        kept.solids[1].max_abs_err_pct < 1e-9,
        "{}",
        kept.solids[1].max_abs_err_pct
    );
    assert_eq!(kept.legend_quantity, "max |err| over γ 0–44°");
    let sector = ErrorDomain {
        gamma_deg: (0.0, 90.0),
        c_deg: Some((300.0, 60.0)),
    };
    assert!(sector.contains(0.0, 10.0) && sector.contains(330.0, 10.0) && !sector.contains(180.0, 10.0));
    assert_eq!(sector.to_string(), "γ 0–90°, C 300–60°");
}
