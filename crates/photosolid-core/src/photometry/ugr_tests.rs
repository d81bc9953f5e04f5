//! Tests of the UGR table (src/photometry/ugr.rs).

use super::*;
use crate::model::{Dimensions, Distribution, Symmetry};
use std::f64::consts::PI;

/// A rotationally symmetric luminaire with `f(γ)` cd and a square luminous area of side `a` m.
fn luminaire(f: impl Fn(f64) -> f64, a: f64) -> Luminaire {
    let g: Vec<f64> = (0..=180).map(f64::from).collect();
    let cd = g.iter().map(|x| f(x.to_radians())).collect();
    let d = Distribution::new(vec![0.0], g, cd, Symmetry::Rotational).unwrap();
    let mut l = Luminaire::from_distribution(d);
    l.set_luminous_opening(Dimensions {
        length_m: a,
        width_m: a,
        height_m: 0.0,
    });
    l
}

fn lambertian(i0: f64) -> impl Fn(f64) -> f64 {
    move |g: f64| if g <= PI / 2.0 { i0 * g.cos() } else { 0.0 }
}

/// Two aligned unit squares one unit apart see each other with F = 0.1998
/// (Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, Table 13.2 /
/// Fig. 13.4; Howell's catalogue C-11), and F → 1 as the plates grow.
#[test]
fn parallel_plate_view_factor_matches_the_textbook() {
    let f = parallel_rectangles_view_factor(1.0, 1.0, 1.0);
    assert!((f - 0.1998).abs() < 5e-5, "{f}");
    assert!(parallel_rectangles_view_factor(1e4, 1e4, 1.0) > 0.999);
}

/// Interreflection conserves energy: what the surfaces absorb,
/// Σ A_i M_i (1 − ρ_i)/ρ_i, equals what the luminaires emit.
#[test]
fn interreflection_conserves_flux() {
    let (x, y, h) = (8.0, 4.0, 2.0);
    let direct = [300.0, 5000.0, 1200.0];
    let rho = [0.7, 0.2, 0.5];
    let (m, e_wid) = box_interreflection(x, y, h, direct, rho);
    let area = [x * y, x * y, 2.0 * (x + y) * h];
    let absorbed: f64 = (0..3).map(|i| area[i] * m[i] * (1.0 - rho[i]) / rho[i]).sum();
    let emitted: f64 = direct.iter().sum();
    assert!((absorbed - emitted).abs() < 1e-9 * emitted, "{absorbed} vs {emitted}");
    assert!(e_wid > 0.0);
}

/// The Guth index is 1 on the line of sight and grows away from it; at
/// σ = 45° in the horizontal plane (τ = 90°) the closed form gives
/// exp(45·6.496e-3 + 45²·21e-5·…) — checked against the expression of CIE 117.
#[test]
fn position_index_closed_form() {
    assert_eq!(position_index(DVec3::Y), Some(1.0));
    assert_eq!(position_index(-DVec3::Y), None);
    let s = DVec3::new(1.0, 1.0, 0.0).normalize();
    let tau: f64 = 90.0;
    let ln_p = 45.0 * (35.2 - 0.31889 * tau - 1.22 * (-20.0f64).exp()) * 1e-3
        + 45.0 * 45.0 * (21.0 + 0.26667 * tau - 0.002963 * tau * tau) * 1e-5;
    assert!((position_index(s).unwrap() - ln_p.exp()).abs() < 1e-9);
    let higher = position_index(DVec3::new(0.0, 1.0, 1.0).normalize()).unwrap();
    assert!(higher > 1.0);
}

/// CIE 117's flux correction: every intensity × k shifts UGR by exactly
/// 8 log₁₀ k (L and L_b both scale, Σ L²ω/p² as k²); a luminous area × k at
/// the same intensities shifts it by −8 log₁₀ k. And UGR is independent of H.
#[test]
fn scaling_laws_and_height_independence() {
    let base = luminaire(lambertian(1000.0), 0.3);
    let bright = luminaire(lambertian(2000.0), 0.3);
    let big = luminaire(lambertian(1000.0), 0.3 * 2f64.sqrt());
    let t0 = ugr_table(&base).unwrap();
    let t1 = ugr_table(&bright).unwrap();
    let t2 = ugr_table(&big).unwrap();
    let k = 8.0 * 2f64.log10();
    for r in 0..ROOMS_H.len() {
        for c in 0..REFLECTANCES.len() {
            assert!((t1.crosswise[r][c] - t0.crosswise[r][c] - k).abs() < 1e-9);
            assert!((t2.endwise[r][c] - t0.endwise[r][c] + k).abs() < 1e-9);
            // Rotational symmetry and a square area: both views are the same.
            assert!((t0.crosswise[r][c] - t0.endwise[r][c]).abs() < 1e-9);
        }
    }
    for h in [2.0, 2.8, 6.0] {
        let u = ugr_room(
            &base,
            View::Crosswise,
            (4.0, 8.0),
            REFLECTANCES[0],
            h,
            CATALOGUE_SPACING_H,
        )
        .unwrap()
        .unwrap();
        assert!(
            (u - t0.crosswise[10][0]).abs() < 1e-9,
            "H {h}: {u} vs {}",
            t0.crosswise[10][0]
        );
    }
    // Brighter surroundings (higher reflectances) lower the UGR.
    for r in 0..ROOMS_H.len() {
        assert!(t0.crosswise[r][0] < t0.crosswise[r][4]);
    }
}

/// A Lambertian panel's direct flux: the floor receives at most the
/// downward flux and, in the 12H x 8H room, most of it.
#[test]
fn floor_flux_is_bounded_by_the_downward_flux() {
    let l = luminaire(lambertian(1000.0), 0.3);
    let opening = Opening::of_luminaire(&l).unwrap();
    for (spacing, n) in [(CIE_190_EXAMPLE_SPACING_H, 96.0), (CATALOGUE_SPACING_H, 1536.0)] {
        let layout = Layout::new(spacing).unwrap();
        let a = Array::new(GridLookup::new(l.distribution()), &opening, View::Crosswise, layout);
        let (_, floor) = a.room(12.0, 8.0);
        let down = n * PI * 1000.0;
        assert!(
            floor < down && floor > 0.8 * down,
            "spacing {spacing}: {floor} of {down}"
        );
    }
}

/// Undefined cases say so instead of printing NaN: upward-only light, no
/// luminous area, all-zero data; a 1e-6 cd luminaire still has a finite table.
#[test]
fn undefined_cases_are_errors() {
    let up = luminaire(|g| if g > PI / 2.0 { 100.0 } else { 0.0 }, 0.3);
    let e = ugr_table(&up).unwrap_err();
    assert_eq!(
        e.to_string(),
        "no downward light: UGR undefined (no glare from the luminaires)"
    );
    assert_eq!(crate::Error::from(e).code(), "undefined");
    let zero = luminaire(|_| 0.0, 0.3);
    assert!(ugr_table(&zero).unwrap_err().to_string().contains("undefined"));
    let point = luminaire(lambertian(1000.0), 0.0);
    let e = ugr_table(&point).unwrap_err();
    assert!(
        matches!(
            e,
            crate::ModelError::Undefined {
                quantity: "UGR",
                why: crate::error::Undefined::NoLuminousArea
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().contains("no luminous area"));
    let dim = ugr_table(&luminaire(lambertian(1e-6), 0.3)).unwrap();
    assert!(dim.max.is_finite());
    let bright = ugr_table(&luminaire(lambertian(1e6), 0.3)).unwrap();
    assert!(bright.max.is_finite());
}

/// A 600 x 600 mm Lambertian panel of 3600 lm (L = 3183 cd/m²): the table
/// must order like every published CIE table does: UGR rises with the room
/// length along the line of sight, and the columns order 70/50 < 50/50 <
/// 70/30 < 50/30 < 30/30 (less reflected light, darker background). Its
/// 4H x 8H 70/50/20 value (21.6 here) lies in the 19-22 band catalogues
/// give for opal panels of this luminance (not a cited table: a plausibility bound).
#[test]
fn lambertian_panel_orders_like_published_tables() {
    let t = ugr_table(&luminaire(lambertian(3600.0 / PI), 0.6)).unwrap();
    for (k, row) in t.crosswise.iter().enumerate() {
        for (a, b) in [(0, 2), (2, 1), (1, 3), (3, 4)] {
            assert!(row[a] < row[b], "room {:?}: {row:?}", t.rooms_h[k]);
        }
    }
    for k in 0..5 {
        // X = 2H rows 0..5: Y = 2, 3, 4, 6, 8, 12 H.
        assert!(t.crosswise[k][0] < t.crosswise[k + 1][0]);
    }
    let r = ROOMS_H.iter().position(|&r| r == (4.0, 8.0)).unwrap();
    assert!((19.0..=23.0).contains(&t.crosswise[r][0]), "{}", t.crosswise[r][0]);
}

/// CIE 117 eqs. 4.5 and 4.6: viewed crosswise, the eye sees the luminaires
/// ahead at C = arctan(T/R), near the C0 plane; endwise at 90° − arctan(T/R),
/// near C90. A luminaire brighter toward C0/C180 than toward C90/C270 (same
/// flux split otherwise) therefore rates higher crosswise, in every room;
/// turned by 90° it rates higher endwise by the same amounts.
#[test]
fn crosswise_sees_the_c0_plane() {
    let make = |phase: f64| {
        let c: Vec<f64> = (0..24).map(|k| f64::from(k) * 15.0).collect();
        let g: Vec<f64> = (0..=180).map(f64::from).collect();
        let cd = c
            .iter()
            .flat_map(|&c| {
                let k = 1.0 + 0.8 * (c + phase).to_radians().cos().powi(2);
                g.iter().map(move |&g: &f64| k * lambertian(1000.0)(g.to_radians()))
            })
            .collect();
        let d = Distribution::new(c, g, cd, Symmetry::None).unwrap();
        let mut l = Luminaire::from_distribution(d);
        l.set_luminous_opening(Dimensions {
            length_m: 0.6,
            width_m: 0.6,
            height_m: 0.0,
        });
        ugr_table(&l).unwrap()
    };
    let (c0, c90) = (make(0.0), make(90.0));
    for (r, room) in ROOMS_H.iter().enumerate() {
        for c in 0..REFLECTANCES.len() {
            assert!(c0.crosswise[r][c] > c0.endwise[r][c] + 0.1, "room {room:?}");
            assert!((c0.crosswise[r][c] - c90.endwise[r][c]).abs() < 1e-6);
            assert!((c0.endwise[r][c] - c90.crosswise[r][c]).abs() < 1e-6);
        }
    }
}

/// CIE 117's field for the tabular method: a luminaire counts while T/R ≤ 3,
/// H/R ≤ 1.9 and γ ≤ 85° (T across, R along the line of sight, in H;
/// tan 85° = 11.43): the first row of the standard array (R = H/2) is out.
#[test]
fn field_cut_at_t_over_r_3_h_over_r_1_9_and_gamma_85() {
    assert!(!field_cut(2.99, 1.0) && field_cut(3.01, 1.0));
    assert!(!field_cut(-2.99, 1.0) && field_cut(-3.01, 1.0));
    assert!(!field_cut(0.0, 11.4) && field_cut(0.0, 11.5));
    assert!(field_cut(8.0, 8.5) && !field_cut(8.0, 8.0));
    assert!(field_cut(0.0, 0.5) && !field_cut(0.0, 0.53) && !field_cut(1.5, 1.5));
}
