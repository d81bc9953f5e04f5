use super::*;

/// The in-range shortcut of `wrap360` gives the bits of the general rule
/// (`rem_euclid`, then the seam) everywhere: in range, at both ends, just
/// below the seam's band, negative, past 360, signed zeros, NaN and ±∞.
#[test]
fn wrap360_shortcut_is_the_general_rule() {
    let general = |c: f64| {
        let w = c.rem_euclid(360.0);
        if w >= 360.0 - ANGLE_EPS {
            0.0
        } else {
            w
        }
    };
    let edge = 360.0 - ANGLE_EPS;
    let mut xs = vec![
        0.0,
        -0.0,
        360.0,
        -360.0,
        720.5,
        -1e-300,
        1e-300,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    xs.extend([edge, edge.next_down(), edge.next_up(), 359.999_999, 180.0, 1e9, -1e9]);
    xs.extend((-2000..=2000).map(|k| k as f64 * 0.37));
    for c in xs {
        assert_eq!(wrap360(c).to_bits(), general(c).to_bits(), "{c}");
    }
}

/// The vectorised passes agree with the plain loops on every length
/// around the lane count, with the odd value anywhere (chunks and tail):
/// NaN, ±∞, beyond the bound, a round-off peak, negative values.
#[test]
fn vectorised_peak_and_range_agree_with_plain_loops() {
    for n in 1..40 {
        for at in 0..n {
            for odd in [f64::NAN, f64::INFINITY, -f64::INFINITY, 2e12, -3e12, 5e-10, -7.5, 1e12] {
                let mut cd: Vec<f64> = (0..n).map(|k| ((k * 37) % 11) as f64 * 0.25 - 1.0).collect();
                cd[at] = odd;
                let plain_ok = cd.iter().all(|v| v.is_finite() && v.abs() <= MAX_CD);
                let (ok, peak) = abs_peak_in_range(&cd);
                assert_eq!(ok, plain_ok, "n {n} at {at} value {odd}");
                if plain_ok {
                    let want = cd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    assert_eq!(peak.to_bits(), want.to_bits(), "n {n} at {at} value {odd}");
                    let want_max = cd.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
                    assert_eq!(max_of(&cd).to_bits(), want_max.to_bits());
                }
                // The error path still names the offending value.
                if !plain_ok {
                    assert_eq!(check_intensities(&cd).map_err(|e| e.0), Err(at));
                }
            }
        }
    }
    let tiny = vec![0.0, 5e-10, -4e-10];
    assert_eq!(check_intensities(&tiny).map_err(|e| e.0), Err(1));
}

fn quadrant() -> Distribution {
    // planes 0, 30, 90 (non-uniform) x gamma 0, 45, 90
    Distribution::new(
        vec![0.0, 30.0, 90.0],
        vec![0.0, 45.0, 90.0],
        vec![10.0, 8.0, 1.0, 10.0, 7.0, 2.0, 10.0, 6.0, 3.0],
        Symmetry::Quadrant,
    )
    .unwrap()
}

#[test]
fn fold_maps_into_stored_range() {
    for c in [
        -720.0, -1.0, 0.0, 45.0, 89.9, 90.0, 135.0, 180.0, 200.0, 270.0, 300.0, 359.999, 360.0, 1e6,
    ] {
        for s in [Symmetry::None, Symmetry::C0C180, Symmetry::C90C270, Symmetry::Quadrant] {
            let f = s.fold(c);
            let (lo, hi) = s.stored_range();
            assert!(f >= lo && f <= hi + 1e-9, "{s:?} {c} -> {f}");
        }
    }
    assert_eq!(Symmetry::C90C270.fold(10.0), 170.0);
    assert_eq!(Symmetry::C90C270.fold(300.0), 240.0);
    assert_eq!(Symmetry::Quadrant.fold(200.0), 20.0);
    assert_eq!(Symmetry::Quadrant.fold(330.0), 30.0);
}

#[test]
fn expansion_reproduces_stored_values_on_nonuniform_grid() {
    let d = quadrant();
    let full = d.expand(1);
    let c = full.c_angles_deg();
    assert_eq!(c, &[0.0, 30.0, 90.0, 150.0, 180.0, 210.0, 270.0, 330.0]);
    for (k, &a) in c.iter().enumerate() {
        let ic = d.find_plane(Symmetry::Quadrant.fold(a)).unwrap();
        assert_eq!(full.plane_cd(k), d.plane_cd(ic));
    }
    assert_eq!(full.detect_symmetry(1e-9), Symmetry::Quadrant);
    let back = full.with_symmetry(Symmetry::Quadrant).unwrap();
    assert_eq!(back, d);
}

#[test]
fn c90c270_round_trip() {
    let d = Distribution::new(
        vec![90.0, 180.0, 270.0],
        vec![0.0, 90.0],
        vec![5.0, 1.0, 5.0, 2.0, 5.0, 3.0],
        Symmetry::C90C270,
    )
    .unwrap();
    let full = d.expand(1);
    assert_eq!(full.c_angles_deg(), &[0.0, 90.0, 180.0, 270.0]);
    assert_eq!(full.plane_cd(0), d.plane_cd(1)); // C0 = C180
    assert_eq!(full.detect_symmetry(1e-9), Symmetry::C90C270);
    assert_eq!(full.with_symmetry(Symmetry::C90C270).unwrap(), d);
}

#[test]
fn reorientation_rotates_and_mirrors() {
    let lum = crate::synth::Synth::Roadway
        .build(&crate::synth::GridSpec::uniform(10.0, 10.0).unwrap(), 100.0)
        .unwrap();
    let d = lum.distribution();
    let r = d.reoriented(90.0, false).unwrap();
    // The C90-C270 mirror becomes a C0-C180 mirror after a 90° turn.
    assert_eq!(r.symmetry(), Symmetry::C0C180);
    let full = d.expand(1);
    for (k, &c) in full.c_angles_deg().iter().enumerate() {
        assert_eq!(r.value_at_plane_cd(c + 90.0, 3), Some(full.value_cd(k, 3)));
    }
    let m = d.reoriented(0.0, true).unwrap();
    assert_eq!(m.value_at_plane_cd(300.0, 5), d.expand(1).value_at_plane_cd(60.0, 5));
    assert_eq!(
        d.reoriented(360.0, false).unwrap(),
        d.with_symmetry(Symmetry::C90C270).unwrap()
    );
}

#[test]
fn rejects_bad_grids() {
    assert!(Distribution::new(vec![0.0], vec![10.0, 5.0], vec![1.0, 1.0], Symmetry::Rotational).is_err());
    assert!(Distribution::new(vec![0.0], vec![0.0, 0.0], vec![1.0, 1.0], Symmetry::Rotational).is_err());
    assert!(Distribution::new(vec![0.0], vec![0.0, 190.0], vec![1.0, 1.0], Symmetry::Rotational).is_err());
    assert!(Distribution::new(vec![0.0], vec![0.0, 90.0], vec![1.0, f64::NAN], Symmetry::Rotational).is_err());
    assert!(Distribution::new(vec![0.0, 360.0], vec![0.0], vec![1.0, 1.0], Symmetry::None).is_err());
    assert!(Distribution::new(vec![0.0, 80.0], vec![0.0], vec![1.0, 1.0], Symmetry::Quadrant).is_err());
    assert!(Distribution::new(vec![0.0], vec![0.0], vec![1.0, 1.0], Symmetry::Rotational).is_err());
}

#[test]
fn pole_average_is_weighted_by_circle_share() {
    let d = Distribution::new(
        vec![0.0, 90.0, 180.0, 270.0],
        vec![0.0, 90.0],
        vec![1.0, 0.0, 2.0, 0.0, 3.0, 0.0, 4.0, 0.0],
        Symmetry::None,
    )
    .unwrap();
    assert_eq!(d.pole_spread_cd(), (3.0, 0.0));
    let a = d.with_averaged_poles();
    for ic in 0..4 {
        assert!((a.value_cd(ic, 0) - 2.5).abs() < 1e-12);
    }
}
