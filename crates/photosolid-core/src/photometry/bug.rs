//! BUG rating (Backlight, Uplight, Glare) of outdoor luminaires, IES TM-15-11
//! Addendum A.
//!
//! # Zones (TM-15-11 Luminaire Classification System)
//! Lumens in ten secondary solid angles, by [`zone_flux`] (exact on the
//! bilinear reconstruction, split exactly at every zone boundary):
//! forward FL 0-30°, FM 30-60°, FH 60-80°, FVH 80-90° and the same four
//! back zones BL, BM, BH, BVH; uplight UL 90-100° and UH 100-180° (whole
//! circle). TM-15 puts "forward" at horizontal angles 270°-90° in front of
//! the luminaire, back at 90°-270°. We apply that literally to the file's C
//! (= LM-63 horizontal) angles: forward = C 270-90, the half-space around C0;
//! back = C 90-270. Checked against manufacturers' declared ratings: two
//! LM-63 roadway files (Type II, symmetric about the C0-C180 plane, throw
//! toward C0) rate B2 U0 G2 and B2 U3 G2 as printed in their `[DISTRIBUTION]`
//! keyword only under this convention; with forward = C 0-180 both come out
//! B3 (tests/it/photometry.rs, `declared_bug_ratings_of_manufacturer_files`).
//! A EULUMDAT road luminaire whose street side is C90 (CIE convention) must
//! be turned by 90° before rating; we do not guess the orientation.
//!
//! # Ratings (TM-15-11 Addendum A, Tables; absolute lumens)
//! Each rating is the lowest class whose every zone limit holds:
//!
//! | class | BH, BL | BM | UL, UH | FH | FVH, BVH | BH (glare) |
//! |---|---|---|---|---|---|---|
//! | 0 | 110 | 220 | 0 | 660 | 10 | 110 |
//! | 1 | 500 | 1000 | 10 | 1800 | 250 | 500 |
//! | 2 | 1000 | 2500 | 50 | 5000 | 375 | 1000 |
//! | 3 | 2500 | 5000 | 500 | 7500 | 500 | 2500 |
//! | 4 | 5000 | 8500 | 1000 | 12000 | 750 | 5000 |
//!
//! and class 5 above class 4. A limit of 0 lm (U0) is met only by exactly
//! no uplight: lumens below 1e-9 of the total count as none (rounding).
//!
//! # Where the limits were checked (docs/photometry.md, "BUG limits")
//! The printed addendum was not available. What was checked:
//! - Backlight (BL/BM/BH) and uplight (UL/UH) rows: identical, number for
//!   number, to the independent implementation in holg/eulumdat-rs
//!   (`crates/eulumdat/src/bug_rating.rs`, `BugRating::from_zone_lumens`,
//!   commit c7e8b5d). Its glare rows differ (FH 10/180/600/2000/4000, FVH
//!   10/10/50/200/400, BH tested against the FH limits) and are not used.
//! - The whole chain (zones + all three tables) against the BUG ratings
//!   that manufacturers print in their LM-63 files, `[DISTRIBUTION]` keyword,
//!   computed by their photometric labs (test
//!   `declared_bug_ratings_of_manufacturer_files` in tests/it/photometry.rs).
//! - The glare rows (FVH/BVH, FH, BH) have no second public source here.
//!   These are the asymmetric-distribution (Type I-IV) glare limits; the
//!   addendum's separate glare table for quadrilateral-symmetric (Type V)
//!   distributions could not be found in a public source and is not applied.

use serde::Serialize;

use super::flux::zone_flux;
use crate::model::{Distribution, Front};

/// Lumens in the ten TM-15 secondary solid angles, lm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
#[allow(missing_docs)]
pub struct BugZones {
    pub fl: f64,
    pub fm: f64,
    pub fh: f64,
    pub fvh: f64,
    pub bl: f64,
    pub bm: f64,
    pub bh: f64,
    pub bvh: f64,
    pub ul: f64,
    pub uh: f64,
}

/// The B, U and G classes (0-5) and the zone lumens they come from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BugRating {
    /// Backlight class 0-5.
    pub b: u8,
    /// Uplight class 0-5.
    pub u: u8,
    /// Glare class 0-5.
    pub g: u8,
    /// "B1 U0 G2".
    pub rating: String,
    /// Zone lumens, lm.
    pub zones: BugZones,
    /// Which glare table rated `g`: always the Addendum's asymmetric
    /// (Type I-IV) limits, `"type-i-iv"` (see the module docs).
    pub glare_table: &'static str,
    /// Whether the distribution sends the same lumens forward and back in
    /// every zone pair within 2 % (FL/BL, FM/BM, FH/BH, FVH/BVH), as a
    /// quadrilateral-symmetric (Type V) luminaire does.
    pub quadrilateral_symmetric: bool,
    /// Set for a quadrilateral-symmetric distribution: the Addendum rates
    /// those with their own glare table, which is not applied here.
    pub glare_caveat: Option<String>,
}

/// Backlight limits (lm) per class 0-4: (BH, BM, BL).
const BACKLIGHT: [(f64, f64, f64); 5] = [
    (110.0, 220.0, 110.0),
    (500.0, 1000.0, 500.0),
    (1000.0, 2500.0, 1000.0),
    (2500.0, 5000.0, 2500.0),
    (5000.0, 8500.0, 5000.0),
];
/// Uplight limits (lm) per class 0-4: (UL, UH).
const UPLIGHT: [(f64, f64); 5] = [(0.0, 0.0), (10.0, 10.0), (50.0, 50.0), (500.0, 500.0), (1000.0, 1000.0)];
/// Glare limits (lm) per class 0-4: (FVH, BVH, FH, BH).
const GLARE: [(f64, f64, f64, f64); 5] = [
    (10.0, 10.0, 660.0, 110.0),
    (250.0, 250.0, 1800.0, 500.0),
    (375.0, 375.0, 5000.0, 1000.0),
    (500.0, 500.0, 7500.0, 2500.0),
    (750.0, 750.0, 12000.0, 5000.0),
];

/// The ten zone lumens of `d`, forward being `front` ± 90°.
pub fn bug_zones(d: &Distribution, front: Front) -> BugZones {
    let f = |a: f64, b: f64| zone_flux(d, (a, b), front.forward_c_deg());
    let bk = |a: f64, b: f64| zone_flux(d, (a, b), front.back_c_deg());
    let all = |a: f64, b: f64| zone_flux(d, (a, b), (0.0, 360.0));
    BugZones {
        fl: f(0.0, 30.0),
        fm: f(30.0, 60.0),
        fh: f(60.0, 80.0),
        fvh: f(80.0, 90.0),
        bl: bk(0.0, 30.0),
        bm: bk(30.0, 60.0),
        bh: bk(60.0, 80.0),
        bvh: bk(80.0, 90.0),
        ul: all(90.0, 100.0),
        uh: all(100.0, 180.0),
    }
}

/// Every zone limit of the tables, lm.
fn all_limits() -> impl Iterator<Item = f64> {
    BACKLIGHT
        .iter()
        .flat_map(|&(a, b, c)| [a, b, c])
        .chain(UPLIGHT.iter().flat_map(|&(a, b)| [a, b]))
        .chain(GLARE.iter().flat_map(|&(a, b, c, d)| [a, b, c, d]))
}

/// `lm` with the fewest decimals (0 to 9) at which the printed number sits on
/// the same side of every zone limit as the value the rating compared: a
/// floodlight's 0.34 lm of uplight (U1) prints as "0.3", not "0".
pub fn zone_lumens_text(lm: f64) -> String {
    let same_side = |k: usize| {
        let printed: f64 = format!("{lm:.k$}").parse().unwrap_or(lm);
        all_limits().all(|limit| (printed <= limit) == (lm <= limit))
    };
    match (0..=9).find(|&k| same_side(k)) {
        Some(k) => format!("{lm:.k$}"),
        None => format!("{lm:e}"),
    }
}

impl BugZones {
    /// The zones as `info` prints them: "BL 1 BM 2 BH 3 BVH 4 / FL ... / UL ... UH ... lm",
    /// each with [`zone_lumens_text`]'s digits.
    pub fn to_text(&self) -> String {
        let t = zone_lumens_text;
        format!(
            "BL {} BM {} BH {} BVH {} / FL {} FM {} FH {} FVH {} / UL {} UH {} lm",
            t(self.bl),
            t(self.bm),
            t(self.bh),
            t(self.bvh),
            t(self.fl),
            t(self.fm),
            t(self.fh),
            t(self.fvh),
            t(self.ul),
            t(self.uh)
        )
    }
}

/// The lowest class whose limits `ok` accepts, 5 when none does.
fn class(ok: impl Fn(usize) -> bool) -> u8 {
    (0..5).find(|&k| ok(k)).unwrap_or(5) as u8
}

/// Rate zone lumens `z` (module docs); `noise_lm` is the level below which
/// lumens count as none for the 0-lm limits. The symmetry fields need the
/// distribution, not only its zones: [`bug_rating`] fills them, so this
/// stays private.
fn rate(z: &BugZones, noise_lm: f64) -> BugRating {
    let le = |x: f64, limit: f64| x <= limit.max(noise_lm);
    let b = class(|k| {
        let (bh, bm, bl) = BACKLIGHT[k];
        le(z.bh, bh) && le(z.bm, bm) && le(z.bl, bl)
    });
    let u = class(|k| le(z.ul, UPLIGHT[k].0) && le(z.uh, UPLIGHT[k].1));
    let g = class(|k| {
        let (fvh, bvh, fh, bh) = GLARE[k];
        le(z.fvh, fvh) && le(z.bvh, bvh) && le(z.fh, fh) && le(z.bh, bh)
    });
    BugRating {
        b,
        u,
        g,
        rating: format!("B{b} U{u} G{g}"),
        zones: *z,
        glare_table: "type-i-iv",
        quadrilateral_symmetric: false,
        glare_caveat: None,
    }
}

/// Whether `d` sends the same lumens (within 2 %) forward and back in each
/// of the four downward BUG bands, and left (front to front + 180) and right
/// (front + 180 to front + 360) in each: the quadrilateral symmetry of a
/// Type V luminaire.
fn is_quadrilateral_symmetric(d: &Distribution, front: Front, z: &BugZones, noise_lm: f64) -> bool {
    let bands = [(0.0, 30.0), (30.0, 60.0), (60.0, 80.0), (80.0, 90.0)];
    let front_back = [(z.fl, z.bl), (z.fm, z.bm), (z.fh, z.bh), (z.fvh, z.bvh)];
    let f0 = front.c_deg;
    let left_right = bands.map(|g| {
        (
            zone_flux(d, g, (f0, f0 + 180.0)),
            zone_flux(d, g, (f0 + 180.0, f0 + 360.0)),
        )
    });
    let same = |(a, b): (f64, f64)| (a - b).abs() <= 0.02 * a.max(b).max(noise_lm);
    let lit = front_back.iter().any(|&(f, b)| f.max(b) > noise_lm);
    lit && front_back.into_iter().chain(left_right).all(same)
}

/// BUG rating of `d` (absolute candela: the limits are absolute lumens),
/// its forward half centred on `front` ([`crate::model::front`]).
pub fn bug_rating(d: &Distribution, front: Front) -> BugRating {
    let z = bug_zones(d, front);
    let total = z.fl + z.fm + z.fh + z.fvh + z.bl + z.bm + z.bh + z.bvh + z.ul + z.uh;
    let noise_lm = 1e-9 * total.abs();
    let mut r = rate(&z, noise_lm);
    r.quadrilateral_symmetric = is_quadrilateral_symmetric(d, front, &z, noise_lm);
    r.glare_caveat = r.quadrilateral_symmetric.then(|| {
        "quadrilateral-symmetric (Type V) distribution rated with the Type I-IV glare limits: TM-15-11 Addendum A's \
         Type V glare table is not applied (no public source), so G may be higher than it gives"
            .to_string()
    });
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Symmetry;
    use std::f64::consts::PI;

    /// The LM-63 front: forward = C 270-90.
    fn c0() -> Front {
        Front::convention(crate::model::Format::Ies)
    }

    fn iso(cd: f64, to: f64) -> Distribution {
        let g: Vec<f64> = (0..=18).map(|i| to * i as f64 / 18.0).collect();
        let v = vec![cd; g.len()];
        Distribution::new(vec![0.0], g, v, Symmetry::Rotational).unwrap()
    }

    /// Closed form: an isotropic source of I cd puts π I (cos a − cos b) lm in
    /// each half-circle zone and 2π I (cos a − cos b) in each uplight ring.
    #[test]
    fn isotropic_zones_are_closed_form() {
        let z = bug_zones(&iso(1000.0, 180.0), c0());
        let half = |a: f64, b: f64| PI * 1000.0 * (a.to_radians().cos() - b.to_radians().cos());
        for (got, want) in [
            (z.fl, half(0.0, 30.0)),
            (z.bm, half(30.0, 60.0)),
            (z.fh, half(60.0, 80.0)),
            (z.bvh, half(80.0, 90.0)),
            (z.ul, 2.0 * half(90.0, 100.0)),
            (z.uh, 2.0 * half(100.0, 180.0)),
        ] {
            assert!((got - want).abs() < 1e-9 * want, "{got} vs {want}");
        }
    }

    /// Class boundaries of Addendum A: a value at a limit is in the class, just
    /// above it the next; 0 lm uplight is U0, any measurable uplight is not.
    #[test]
    fn limits_are_inclusive_and_ordered() {
        let mut z = BugZones {
            bh: 110.0,
            bm: 220.0,
            bl: 110.0,
            ..Default::default()
        };
        let r = rate(&z, 0.0);
        assert_eq!((r.b, r.u, r.g), (0, 0, 0));
        z.bm = 220.1;
        assert_eq!(rate(&z, 0.0).b, 1);
        z.fh = 12000.0;
        assert_eq!(rate(&z, 0.0).g, 4);
        z.fvh = 751.0;
        assert_eq!(rate(&z, 0.0).g, 5);
        z.ul = 0.5;
        assert_eq!(rate(&z, 0.0).u, 1);
        z.uh = 1000.5;
        let r = rate(&z, 0.0);
        assert_eq!(r.u, 5);
        assert_eq!(r.rating, format!("B1 U5 G5"));
    }

    /// Every limit row, restated from the table in the module docs (TM-15-11
    /// Addendum A; B and U rows as in eulumdat-rs c7e8b5d): a zone exactly at
    /// the class-k limit rates k, 0.01 lm above it rates k + 1, with every
    /// other zone at 0 lm. A typo in one constant fails its own row.
    #[test]
    fn every_limit_row_matches_the_cited_table() {
        type Set = fn(&mut BugZones, f64);
        type Pick = fn(&BugRating) -> u8;
        let b: Pick = |r| r.b;
        let u: Pick = |r| r.u;
        let g: Pick = |r| r.g;
        let rows: [(&str, Set, Pick, [f64; 5]); 10] = [
            ("B/BL", |z, x| z.bl = x, b, [110.0, 500.0, 1000.0, 2500.0, 5000.0]),
            ("B/BM", |z, x| z.bm = x, b, [220.0, 1000.0, 2500.0, 5000.0, 8500.0]),
            ("B/BH", |z, x| z.bh = x, b, [110.0, 500.0, 1000.0, 2500.0, 5000.0]),
            ("U/UL", |z, x| z.ul = x, u, [0.0, 10.0, 50.0, 500.0, 1000.0]),
            ("U/UH", |z, x| z.uh = x, u, [0.0, 10.0, 50.0, 500.0, 1000.0]),
            ("G/FVH", |z, x| z.fvh = x, g, [10.0, 250.0, 375.0, 500.0, 750.0]),
            ("G/BVH", |z, x| z.bvh = x, g, [10.0, 250.0, 375.0, 500.0, 750.0]),
            ("G/FH", |z, x| z.fh = x, g, [660.0, 1800.0, 5000.0, 7500.0, 12000.0]),
            ("G/BH", |z, x| z.bh = x, g, [110.0, 500.0, 1000.0, 2500.0, 5000.0]),
            // Zones that no rating reads: any amount leaves B, U, G at 0.
            (
                "none",
                |z, x| {
                    z.fl = x;
                    z.fm = x;
                },
                |r| r.b.max(r.u).max(r.g),
                [1e9; 5],
            ),
        ];
        for (name, set, pick, limits) in rows {
            for (k, &limit) in limits.iter().enumerate() {
                let mut z = BugZones::default();
                set(&mut z, limit);
                let at = pick(&rate(&z, 0.0));
                set(&mut z, limit + 0.01);
                let above = pick(&rate(&z, 0.0));
                if name == "none" {
                    assert_eq!((at, above), (0, 0), "{name}");
                } else {
                    assert_eq!((at, above), (k as u8, k as u8 + 1), "{name} limit {limit}");
                }
            }
        }
    }

    /// Zone lumens print with the digits their class needs: 0.34 lm of
    /// uplight (U1, above U0's 0) is not rounded to 0, 110.3 lm of backlight
    /// (above B0's 110) is not rounded to 110.
    #[test]
    fn zone_lumens_print_on_the_side_of_their_limits() {
        assert_eq!(zone_lumens_text(0.34), "0.3");
        assert_eq!(zone_lumens_text(0.0), "0");
        assert_eq!(zone_lumens_text(110.3), "110.3");
        assert_eq!(zone_lumens_text(110.0), "110");
        assert_eq!(zone_lumens_text(1234.4), "1234");
        assert_eq!(zone_lumens_text(0.004), "0.004");
        let z = BugZones {
            ul: 0.34,
            ..BugZones::default()
        };
        assert!(z.to_text().contains("UL 0.3 UH 0 lm"), "{}", z.to_text());
    }

    /// A 1 cd isotropic lower-hemisphere source: every zone far below the
    /// class-0 limits except FVH/BVH (π·0.1736 = 0.545 lm ≤ 10): B0 U0 G0.
    /// At 1000 cd: BVH = 545 lm puts G at 4 (≤ 750), BM = 1150 lm puts B at 2
    /// (≤ 2500 and BH = 1160 lm > 1000 makes it B3), no uplight U0.
    #[test]
    fn isotropic_ratings() {
        assert_eq!(bug_rating(&iso(1.0, 90.0), c0()).rating, "B0 U0 G0");
        let r = bug_rating(&iso(1000.0, 90.0), c0());
        let bh = PI * 1000.0 * (60f64.to_radians().cos() - 80f64.to_radians().cos());
        assert!((r.zones.bh - bh).abs() < 1e-9 * bh);
        assert!(bh > 1000.0 && bh <= 2500.0);
        assert_eq!(r.rating, "B3 U0 G4");
        // All-zero data: nothing anywhere.
        assert_eq!(bug_rating(&iso(0.0, 180.0), c0()).rating, "B0 U0 G0");
    }

    /// A rotationally symmetric lamp is quadrilateral symmetric and says that
    /// its G comes from the Type I-IV table; a forward-throw one does not.
    #[test]
    fn type_v_distributions_carry_the_glare_caveat() {
        let grid = crate::synth::GridSpec::uniform(5.0, 2.5).unwrap();
        let round = crate::synth::Synth::Lambertian.build(&grid, 10_000.0).unwrap();
        let r = bug_rating(round.distribution(), c0());
        assert!(r.quadrilateral_symmetric, "{r:?}");
        assert!(r.glare_caveat.as_deref().unwrap().contains("Type V"), "{r:?}");
        assert_eq!(r.glare_table, "type-i-iv");
        let road = crate::synth::Synth::Roadway.build(&grid, 10_000.0).unwrap();
        let r = bug_rating(road.distribution(), road.front());
        assert!(!r.quadrilateral_symmetric && r.glare_caveat.is_none(), "{:?}", r.zones);
        let dark = Distribution::new(
            vec![0.0],
            vec![0.0, 90.0, 180.0],
            vec![0.0; 3],
            crate::model::Symmetry::Rotational,
        )
        .unwrap();
        assert!(
            !bug_rating(&dark, c0()).quadrilateral_symmetric,
            "no light is no symmetry"
        );
    }
}
