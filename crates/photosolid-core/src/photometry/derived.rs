//! The derived photometry `info` and `compare` print: CIE flux code, zonal
//! lumens, UGR table, BUG rating and luminance table of one luminaire, and
//! the scalars of two luminaires side by side.
//!
//! JSON keys (additive to the `info` report): `cie_flux_code`,
//! `zonal_lumens`, `ugr_table`, `bug_rating`, `luminance_table`. A quantity
//! that is undefined for a file (no downward light, no luminous area, all-zero
//! data) is `{"undefined": "<reason>"}`, never NaN.
//!
//! The three tables (`ugr_table`, `bug_rating`, `luminance_table`) cost about
//! 50 times the rest of a file's report (BENCHMARKS.md, issue 26), so they are
//! optional: [`Derived::of`] computes everything (`info`), [`Derived::without_tables`]
//! leaves them `None` and out of the JSON (`validate` without `--derived`).

use std::fmt::Write;

use serde::Serialize;

use super::bug::{bug_rating, BugRating};
use super::luminance::{luminance_table, LuminanceTable};
use super::ugr::{ugr_table_at, UgrTable, CATALOGUE_SPACING_H, REFLECTANCES, ROOMS_H};
use super::zonal::{cie_flux_code, zonal_lumens, CieFluxCode, ZonalLumens};
use crate::model::Luminaire;

/// A derived quantity, or why it is undefined for this file.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Derivation<T> {
    /// The value.
    Value(T),
    /// Why there is none.
    Undefined {
        /// The reason, a sentence.
        undefined: String,
    },
}

impl<T> Derivation<T> {
    fn from_result(r: Result<T, crate::ModelError>) -> Self {
        match r {
            Ok(v) => Derivation::Value(v),
            Err(e) => Derivation::Undefined {
                undefined: e.to_string(),
            },
        }
    }
    /// The value, if defined.
    pub fn value(&self) -> Option<&T> {
        match self {
            Derivation::Value(v) => Some(v),
            Derivation::Undefined { .. } => None,
        }
    }
}

/// Derived photometry of one luminaire.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Derived {
    /// CIE flux code N1..N5.
    pub cie_flux_code: Derivation<CieFluxCode>,
    /// Zonal lumen summary.
    pub zonal_lumens: ZonalLumens,
    /// UGR table (CIE 117/190 tabular method); `None` when not asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ugr_table: Option<Derivation<UgrTable>>,
    /// BUG rating (TM-15-11 Addendum A; meaningful for outdoor luminaires); `None` when not asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bug_rating: Option<BugRating>,
    /// Luminance at γ 45-85° in C0 and C90, cd/m²; `None` when not asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub luminance_table: Option<Derivation<LuminanceTable>>,
}

/// Index of the CIE reference room 4H x 8H in [`ROOMS_H`].
fn reference_room() -> usize {
    ROOMS_H.iter().position(|&r| r == (4.0, 8.0)).unwrap_or(0)
}

/// What the derived tables are computed for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DerivedOptions {
    /// Spacing of the UGR table's array, in H ([`CATALOGUE_SPACING_H`] by default).
    pub ugr_spacing_h: f64,
}

impl Default for DerivedOptions {
    fn default() -> Self {
        DerivedOptions {
            ugr_spacing_h: CATALOGUE_SPACING_H,
        }
    }
}

/// One `key value` row of [`Derived::to_text`], the key padded to 34 columns.
fn text_row(o: &mut String, k: &str, v: String) {
    let _ = writeln!(o, "{k:<34} {v}");
}

impl Derived {
    /// Compute everything for `lum` (its untilted distribution) with the default options.
    pub fn of(lum: &Luminaire) -> Self {
        Self::with(lum, &DerivedOptions::default())
    }

    /// Compute everything for `lum` (its untilted distribution) as `options` say.
    pub fn with(lum: &Luminaire, options: &DerivedOptions) -> Self {
        let mut d = Self::without_tables(lum);
        d.add_tables(lum, options);
        d
    }

    /// The flux code and the zonal lumens only: the UGR, BUG and luminance
    /// tables are `None` (and absent from the JSON).
    pub fn without_tables(lum: &Luminaire) -> Self {
        Derived {
            cie_flux_code: match cie_flux_code(lum) {
                Some(c) => Derivation::Value(c),
                None => Derivation::Undefined {
                    undefined: "no downward flux: the flux code's N1-N3 are fractions of it".into(),
                },
            },
            zonal_lumens: zonal_lumens(lum),
            ugr_table: None,
            bug_rating: None,
            luminance_table: None,
        }
    }

    /// Compute the UGR, BUG and luminance tables of `lum` (the same luminaire).
    pub fn add_tables(&mut self, lum: &Luminaire, options: &DerivedOptions) {
        self.ugr_table = Some(Derivation::from_result(ugr_table_at(lum, options.ugr_spacing_h)));
        self.bug_rating = Some(bug_rating(lum.distribution(), lum.front()));
        self.luminance_table = Some(Derivation::from_result(luminance_table(lum)));
    }

    /// Drop the UGR, BUG and luminance tables.
    pub fn drop_tables(&mut self) {
        self.ugr_table = None;
        self.bug_rating = None;
        self.luminance_table = None;
    }

    /// The UGR table, when computed and defined.
    pub fn ugr(&self) -> Option<&UgrTable> {
        self.ugr_table.as_ref().and_then(Derivation::value)
    }

    /// The luminance table, when computed and defined.
    pub fn luminance(&self) -> Option<&LuminanceTable> {
        self.luminance_table.as_ref().and_then(Derivation::value)
    }

    /// Text block for `info`.
    pub fn to_text(&self) -> String {
        let mut o = String::new();
        self.write_flux_code_and_bug(&mut o);
        self.write_zonal_lumens(&mut o);
        self.write_ugr_table(&mut o);
        self.write_luminance_table(&mut o);
        o
    }

    /// The text's CIE flux code row and, for outdoor luminaires, the BUG rating.
    fn write_flux_code_and_bug(&self, o: &mut String) {
        text_row(
            o,
            "CIE flux code (N1..N5)",
            match &self.cie_flux_code {
                Derivation::Value(c) => format!(
                    "{}{}",
                    c.code,
                    if c.n5_absolute {
                        " (absolute photometry: N5 = 100)"
                    } else {
                        ""
                    }
                ),
                Derivation::Undefined { undefined } => format!("- ({undefined})"),
            },
        );
        if let Some(b) = &self.bug_rating {
            text_row(
                o,
                "BUG rating (TM-15-11, outdoor)",
                format!("{} ({})", b.rating, b.zones.to_text()),
            );
            if let Some(caveat) = &b.glare_caveat {
                text_row(o, "  BUG glare", caveat.clone());
            }
        }
    }

    /// The text's zonal lumens: the summary zones, then the 10° zones on one line.
    fn write_zonal_lumens(&self, o: &mut String) {
        let pct = |v: Option<f64>| v.map_or("-".to_string(), |p| format!("{p:.1} %"));
        let _ = writeln!(o, "zonal lumens (zone: lm, % lamp, % luminaire):");
        for z in &self.zonal_lumens.summary {
            let _ = writeln!(
                o,
                "  {:>3.0}-{:<3.0}  {:>12.2} lm  {:>8}  {:>8}",
                z.from_deg,
                z.to_deg,
                z.lm,
                pct(z.percent_lamp),
                pct(z.percent_luminaire)
            );
        }
        let tens: Vec<String> = self
            .zonal_lumens
            .ten_degree
            .iter()
            .map(|z| format!("{:.0}-{:.0}: {:.1}", z.from_deg, z.to_deg, z.lm))
            .collect();
        let _ = writeln!(o, "  10° zones, lm: {}", tens.join(", "));
    }

    /// The text's UGR table (crosswise | endwise per room), when computed.
    fn write_ugr_table(&self, o: &mut String) {
        match &self.ugr_table {
            None => {}
            Some(Derivation::Value(t)) => {
                let _ = writeln!(
                    o,
                    "UGR table (CIE 117/190 tabular, S = {}H, for {:.0} lm; crosswise | endwise):",
                    t.spacing_h, t.flux_lm
                );
                let refl: Vec<String> = t
                    .reflectances
                    .iter()
                    .map(|r| format!("{:.0}/{:.0}/{:.0}", 100.0 * r[0], 100.0 * r[1], 100.0 * r[2]))
                    .collect();
                let _ = writeln!(o, "  {:<9} {} | {}", "X x Y", refl.join(" "), refl.join(" "));
                for (k, room) in t.rooms_h.iter().enumerate() {
                    let cells = |v: &Vec<f64>| v.iter().map(|u| format!("{u:>8.1}")).collect::<Vec<_>>().join(" ");
                    let _ = writeln!(
                        o,
                        "  {:<9} {} | {}",
                        format!("{}H x {}H", room[0], room[1]),
                        cells(&t.crosswise[k]),
                        cells(&t.endwise[k])
                    );
                }
            }
            Some(Derivation::Undefined { undefined }) => text_row(o, "UGR table", format!("- ({undefined})")),
        }
    }

    /// The text's luminance table (C0 and C90 per γ), when computed.
    fn write_luminance_table(&self, o: &mut String) {
        match &self.luminance_table {
            None => {}
            Some(Derivation::Value(t)) => {
                let _ = writeln!(o, "luminance, cd/m² (gamma: C0, C90):");
                for (k, g) in t.gamma_deg.iter().enumerate() {
                    let f = |v: Option<f64>| v.map_or("-".to_string(), |x| crate::numfmt::trimmed(x, 4));
                    let _ = writeln!(o, "  {:>4.0}°  {:>11}  {:>11}", g, f(t.c0_cd_m2[k]), f(t.c90_cd_m2[k]));
                }
            }
            Some(Derivation::Undefined { undefined }) => text_row(o, "luminance table", format!("- ({undefined})")),
        }
    }

    /// The scalars compared side by side: (name, unit, value); the tables' are
    /// `None` when they were not computed.
    pub fn scalars(&self) -> Vec<(String, &'static str, Option<f64>)> {
        let mut v: Vec<(String, &'static str, Option<f64>)> = Vec::new();
        let code = self.cie_flux_code.value();
        for k in 0..5 {
            v.push((format!("CIE flux code N{}", k + 1), "%", code.map(|c| c.n[k])));
        }
        for z in &self.zonal_lumens.summary {
            v.push((
                format!("zonal lumens {:.0}-{:.0}", z.from_deg, z.to_deg),
                "lm",
                Some(z.lm),
            ));
        }
        let r = reference_room();
        let t = self.ugr();
        v.push(("UGR 4Hx8H 70/50/20 crosswise".into(), "", t.map(|t| t.crosswise[r][0])));
        v.push(("UGR 4Hx8H 70/50/20 endwise".into(), "", t.map(|t| t.endwise[r][0])));
        v.push(("UGR table max".into(), "", t.map(|t| t.max)));
        let b = self.bug_rating.as_ref();
        v.push(("BUG B".into(), "class", b.map(|b| f64::from(b.b))));
        v.push(("BUG U".into(), "class", b.map(|b| f64::from(b.u))));
        v.push(("BUG G".into(), "class", b.map(|b| f64::from(b.g))));
        let l = self.luminance();
        let at65 = |plane: u8| {
            l.and_then(|t| {
                let k = t.gamma_deg.iter().position(|&g| g == 65.0)?;
                if plane == 0 {
                    t.c0_cd_m2[k]
                } else {
                    t.c90_cd_m2[k]
                }
            })
        };
        v.push(("luminance C0 gamma 65".into(), "cd/m2", at65(0)));
        v.push(("luminance C90 gamma 65".into(), "cd/m2", at65(90)));
        v.push(("luminance table max".into(), "cd/m2", l.and_then(|t| t.max_cd_m2)));
        debug_assert_eq!(REFLECTANCES[0], (0.7, 0.5, 0.2));
        v
    }
}

/// One scalar of two luminaires.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SideRow {
    /// What it is.
    pub quantity: String,
    /// Its unit ("" for UGR).
    pub unit: &'static str,
    /// Value for FILE.
    pub file: Option<f64>,
    /// Value for OTHER.
    pub other: Option<f64>,
    /// OTHER − FILE, when both are defined.
    pub difference: Option<f64>,
}

/// Derived scalars of two luminaires side by side, plus the basic ones
/// (flux, LOR, DFF, I_max, beam angles).
pub fn side_by_side(a: &Luminaire, b: &Luminaire) -> Vec<SideRow> {
    let scalars = |l: &Luminaire| {
        let s = super::summary(l);
        let mut v: Vec<(String, &'static str, Option<f64>)> = vec![
            ("flux".into(), "lm", Some(s.flux.total_lm)),
            ("downward flux".into(), "lm", Some(s.flux.downward_lm)),
            ("upward flux".into(), "lm", Some(s.flux.upward_lm)),
            ("LOR".into(), "%", s.lor.map(|x| 100.0 * x)),
            ("DFF".into(), "%", s.dff.map(|x| 100.0 * x)),
            ("max intensity".into(), "cd", Some(s.max_cd)),
            ("IES beam angle C0-C180".into(), "deg", s.beams.ies_beam_deg[0]),
            ("IES beam angle C90-C270".into(), "deg", s.beams.ies_beam_deg[1]),
        ];
        v.extend(Derived::of(l).scalars());
        v
    };
    let (sa, sb) = (scalars(a), scalars(b));
    sa.into_iter()
        .zip(sb)
        .map(|((quantity, unit, file), (_, _, other))| SideRow {
            difference: file.zip(other).map(|(x, y)| y - x).filter(|d| d.is_finite()),
            quantity,
            unit,
            file,
            other,
        })
        .collect()
}

/// Rows as an aligned text table.
pub fn side_by_side_text(rows: &[SideRow], file: &str, other: &str) -> String {
    let mut o = format!(
        "{:<32} {:>14} {:>14} {:>14}\n",
        "photometry (unit)", file, other, "difference"
    );
    for r in rows {
        let f = |v: Option<f64>| side_value(r.unit, v, "-");
        let name = if r.unit.is_empty() {
            r.quantity.clone()
        } else {
            format!("{} ({})", r.quantity, r.unit)
        };
        let _ = writeln!(
            o,
            "{:<32} {:>14} {:>14} {:>14}",
            name,
            f(r.file),
            f(r.other),
            f(r.difference)
        );
    }
    o
}

/// One value of a side-by-side row: classes (BUG) as integers, luminance
/// with 4 significant digits, the rest with 4 decimals; `none` when undefined.
fn side_value(unit: &str, v: Option<f64>, none: &str) -> String {
    v.map_or(none.to_string(), |x| match unit {
        "class" => format!("{x:.0}"),
        "cd/m2" => crate::numfmt::trimmed(x, 4),
        _ => format!("{x:.4}"),
    })
}

/// Rows as a Markdown table.
pub fn side_by_side_markdown(rows: &[SideRow], file: &str, other: &str) -> String {
    let mut o = format!("| quantity | unit | {file} | {other} | difference |\n|---|---|---:|---:|---:|\n");
    for r in rows {
        let f = |v: Option<f64>| side_value(r.unit, v, "–");
        let _ = writeln!(
            o,
            "| {} | {} | {} | {} | {} |",
            r.quantity,
            r.unit,
            f(r.file),
            f(r.other),
            f(r.difference)
        );
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Distribution, Symmetry};

    /// A file compared with itself differs by 0 everywhere; with a copy at
    /// twice the intensities, flux differences equal the flux and the
    /// flux-code shares do not change.
    #[test]
    fn side_by_side_differences() {
        let g: Vec<f64> = (0..=18).map(|k| 5.0 * k as f64).collect();
        let cd: Vec<f64> = g.iter().map(|x: &f64| 100.0 * x.to_radians().cos()).collect();
        let d = Distribution::new(vec![0.0], g, cd, Symmetry::Rotational).unwrap();
        let a = Luminaire::from_distribution(d.clone());
        let b = Luminaire::from_distribution(d.scaled(2.0).unwrap());
        for r in side_by_side(&a, &a) {
            assert!(r.difference.is_none_or(|x| x == 0.0), "{r:?}");
        }
        let rows = side_by_side(&a, &b);
        let get = |q: &str| rows.iter().find(|r| r.quantity == q).unwrap().clone();
        let fl = get("flux");
        assert!((fl.difference.unwrap() - fl.file.unwrap()).abs() < 1e-9);
        assert!(get("CIE flux code N1").difference.unwrap().abs() < 1e-9);
        // No luminous area: UGR and luminance are undefined on both sides, no difference.
        let u = get("UGR table max");
        assert_eq!((u.file, u.other, u.difference), (None, None, None));
        let text = side_by_side_text(&rows, "a.ies", "b.ies");
        assert!(text.contains("flux (lm)") && !text.contains("NaN"));
        assert!(side_by_side_markdown(&rows, "a", "b").starts_with("| quantity |"));
    }

    /// Extremes: all-zero data, a single γ sample, a single plane with two
    /// samples, upward-only light, 1e-6 and 1e6 cd, with and without a
    /// luminous area: every number printed is finite, undefined parts say why.
    #[test]
    fn extremes_give_finite_numbers_or_reasons() {
        let cases: Vec<(Vec<f64>, Vec<f64>)> = vec![
            (vec![0.0, 45.0, 90.0, 180.0], vec![0.0; 4]),
            (vec![0.0], vec![500.0]),
            (vec![0.0, 90.0], vec![1e6, 0.0]),
            (vec![90.0, 135.0, 180.0], vec![1e6, 1e6, 1e6]),
            (vec![0.0, 30.0, 60.0, 90.0], vec![1e-6; 4]),
            (vec![0.0, 30.0, 60.0, 90.0], vec![1e6; 4]),
        ];
        for (g, cd) in cases {
            for area in [0.0, 0.5] {
                let d = Distribution::new(vec![0.0], g.clone(), cd.clone(), Symmetry::Rotational).unwrap();
                let mut lum = Luminaire::from_distribution(d);
                lum.set_luminous_opening(crate::model::Dimensions {
                    length_m: area,
                    width_m: area,
                    ..lum.luminous_opening()
                });
                let der = Derived::of(&lum);
                let text = der.to_text();
                assert!(!text.contains("NaN") && !text.contains("inf"), "{g:?} {cd:?}:\n{text}");
                for (name, _, v) in der.scalars() {
                    assert!(v.is_none_or(f64::is_finite), "{name} = {v:?} for {g:?} {cd:?}");
                }
                for z in der.zonal_lumens.ten_degree.iter().chain(&der.zonal_lumens.summary) {
                    assert!(z.lm.is_finite());
                }
                if let Some(t) = der.ugr() {
                    assert!(t.crosswise.iter().chain(&t.endwise).flatten().all(|u| u.is_finite()));
                }
                let down = crate::photometry::flux(lum.distribution()).downward_lm;
                if down <= 0.0 || area == 0.0 {
                    assert!(
                        matches!(der.ugr_table, Some(Derivation::Undefined { .. })),
                        "{g:?} {cd:?}"
                    );
                }
            }
        }
    }
}
