//! Declared against computed: what a GLDF container states about a
//! photometry (`DescriptivePhotometry`, see [`GldfDeclared`]) next to what
//! photosolid computes from the intensities, one row per quantity.
//!
//! Every row carries photosolid's value where it computes one: LOR, DLOR,
//! ULOR, DFF and luminous efficacy from the integrated flux, the CIE flux
//! code, the UGR of the standard room (4H x 8H, reflectances 70/50/20,
//! spacing 1H) and the BUG rating from [`crate::photometry::Derived`]; the
//! difference is computed − declared (per number for the flux code).

use serde::Serialize;

use crate::formats::gldf::GldfDeclared;
use crate::InfoReport;

/// One quantity: the container's value, ours, and their difference, as display text.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeclaredRow {
    /// What the row is, e.g. `LOR`.
    pub quantity: &'static str,
    /// The declared value as text (with its unit).
    pub declared: String,
    /// The computed value as text, when photosolid computes it.
    pub computed: Option<String>,
    /// computed − declared as text (percentage points for ratios), when both exist.
    pub difference: Option<String>,
}

/// A ratio row (fractions shown in %; the difference in percentage points).
fn ratio(quantity: &'static str, declared: Option<f64>, computed: Option<f64>) -> Option<DeclaredRow> {
    let d = declared?;
    Some(DeclaredRow {
        quantity,
        declared: format!("{:.2} %", d * 100.0),
        computed: computed.map(|c| format!("{:.2} %", c * 100.0)),
        difference: computed.map(|c| format!("{:+.2} pp", (c - d) * 100.0)),
    })
}

/// The CIE flux code: declared as written, ours from the distribution, and
/// the difference of each of the five numbers when the declared text parses.
fn flux_code_row(g: &GldfDeclared, report: &InfoReport) -> Option<DeclaredRow> {
    let declared = g.cie_flux_code.clone()?;
    let ours = report.derived.cie_flux_code.value();
    let parsed: Vec<f64> = declared.split_whitespace().filter_map(|t| t.parse().ok()).collect();
    let difference = ours.filter(|_| parsed.len() == 5).map(|c| {
        let d: Vec<String> = c.n.iter().zip(&parsed).map(|(o, d)| format!("{:+.0}", o - d)).collect();
        d.join(" ")
    });
    Some(DeclaredRow {
        quantity: "CIE flux code",
        declared,
        computed: ours.map(|c| c.code.clone()),
        difference,
    })
}

/// UGR of the standard room 4H x 8H with reflectances 70/50/20 (the GLDF
/// `UGR-4H8H-70-50-20-LQ` value), crosswise / endwise.
fn ugr_row(g: &GldfDeclared, report: &InfoReport) -> Option<DeclaredRow> {
    let d = g.ugr_4h8h_70_50_20?;
    let ours = report.derived.ugr().and_then(|t| {
        let room = t.rooms_h.iter().position(|r| *r == [4.0, 8.0])?;
        let refl = t.reflectances.iter().position(|r| *r == [0.7, 0.5, 0.2])?;
        Some((t.crosswise[room][refl], t.endwise[room][refl]))
    });
    Some(DeclaredRow {
        quantity: "UGR 4H8H 70/50/20 (crosswise / endwise)",
        declared: format!("{} / {}", d.crosswise, d.endwise),
        computed: ours.map(|(x, y)| format!("{x:.1} / {y:.1}")),
        difference: ours.map(|(x, y)| format!("{:+.1} / {:+.1}", x - d.crosswise, y - d.endwise)),
    })
}

/// The rows for `g` against `report`'s computed values (`input_watts`: the
/// photometric file's declared input power, W, for the efficacy);
/// quantities the container does not declare are left out.
pub fn declared_vs_computed(g: &GldfDeclared, report: &InfoReport, input_watts: Option<f64>) -> Vec<DeclaredRow> {
    let efficacy = input_watts.filter(|w| *w > 0.0).map(|w| report.flux_lm / w);
    let rows = [
        ratio("LOR", g.lor, report.lor),
        ratio("DLOR", g.dlor, report.dlor),
        ratio("ULOR", g.ulor, report.ulor),
        ratio("DFF", g.dff, report.dff),
        g.luminous_efficacy_lm_per_w.map(|d| DeclaredRow {
            quantity: "luminous efficacy",
            declared: format!("{d:.2} lm/W"),
            computed: efficacy.map(|c| format!("{c:.2} lm/W (flux / declared input power)")),
            difference: efficacy.map(|c| format!("{:+.2} lm/W", c - d)),
        }),
        flux_code_row(g, report),
        ugr_row(g, report),
        g.bug_rating.clone().map(|d| {
            let c = report.derived.bug_rating.as_ref().map(|b| &b.rating);
            let same = c.map(|c| d.split_whitespace().collect::<String>() == c.split_whitespace().collect::<String>());
            DeclaredRow {
                quantity: "BUG rating",
                declared: d,
                computed: c.cloned(),
                difference: same.map(|same| if same { "same" } else { "differs" }.into()),
            }
        }),
        g.cut_off_angle_deg.map(|a| DeclaredRow {
            quantity: "cut-off angle",
            declared: format!("{a}°"),
            computed: None,
            difference: None,
        }),
    ];
    rows.into_iter().flatten().collect()
}

/// The rows as an indented text table under a title naming the container and photometry.
pub fn to_text(g: &GldfDeclared, rows: &[DeclaredRow]) -> String {
    use std::fmt::Write;
    let mut o = format!(
        "GLDF {} photometry {} ({}): declared vs computed\n",
        g.container.display(),
        g.id,
        g.file
    );
    if rows.is_empty() {
        o.push_str("  (no DescriptivePhotometry values)\n");
    }
    for r in rows {
        let _ = writeln!(
            o,
            "  {:<40} declared {:<18} computed {:<22} {}",
            r.quantity,
            r.declared,
            r.computed.as_deref().unwrap_or("-"),
            r.difference
                .as_deref()
                .map_or(String::new(), |d| format!("difference {d}"))
        );
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A relative IES file (one 1000 lm lamp, rotationally symmetric 100 cd
    /// below the horizontal: 200π lm, LOR = 0.2π; a 0.6 m x 0.6 m opening for
    /// the UGR) against declared values.
    #[test]
    fn rows_put_declared_next_to_computed() {
        let text = "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0.6 0.6 0\n1 1 50\n0 45 90\n0\n100 100 100\n";
        let mut lum = crate::formats::parse(
            text.as_bytes(),
            std::path::Path::new("t.ies"),
            crate::model::Format::Ies,
            &Default::default(),
        )
        .unwrap();
        lum.gldf = Some(GldfDeclared {
            id: "p".into(),
            lor: Some(0.5),
            dff: Some(1.0),
            luminous_efficacy_lm_per_w: Some(10.0),
            bug_rating: Some("B0 U0 G0".into()),
            cie_flux_code: Some("10 20 30 40 50".into()),
            ugr_4h8h_70_50_20: Some(crate::formats::gldf::DeclaredUgr {
                crosswise: 19.0,
                endwise: 20.0,
            }),
            ..GldfDeclared::default()
        });
        let r = InfoReport::of_document(&lum);
        let rows = r.gldf_comparison.as_ref().unwrap();
        let lor = r.lor.unwrap();
        assert!((lor - 0.2 * std::f64::consts::PI).abs() < 1e-3, "{lor}");
        let row = |q: &str| rows.iter().find(|x| x.quantity == q).unwrap();
        assert_eq!(
            row("LOR").computed.as_deref(),
            Some(format!("{:.2} %", lor * 100.0).as_str())
        );
        assert_eq!(
            row("LOR").difference.as_deref(),
            Some(format!("{:+.2} pp", (lor - 0.5) * 100.0).as_str())
        );
        assert_eq!(row("DFF").difference.as_deref(), Some("+0.00 pp"));
        // Efficacy: flux / 50 W declared input power.
        let eff = r.flux_lm / 50.0;
        assert_eq!(
            row("luminous efficacy").difference,
            Some(format!("{:+.2} lm/W", eff - 10.0))
        );
        // The derived photometry fills the flux code, UGR and BUG rows.
        let bug = &r.derived.bug_rating.as_ref().unwrap().rating;
        assert_eq!(row("BUG rating").computed.as_ref(), Some(bug));
        let code = r.derived.cie_flux_code.value().unwrap();
        assert_eq!(row("CIE flux code").computed.as_ref(), Some(&code.code));
        let want: Vec<String> = code
            .n
            .iter()
            .zip([10.0, 20.0, 30.0, 40.0, 50.0])
            .map(|(o, d)| format!("{:+.0}", o - d))
            .collect();
        assert_eq!(row("CIE flux code").difference, Some(want.join(" ")));
        let ugr = row("UGR 4H8H 70/50/20 (crosswise / endwise)");
        let t = r.derived.ugr().unwrap();
        let (i, j) = (
            t.rooms_h.iter().position(|x| *x == [4.0, 8.0]).unwrap(),
            t.reflectances.iter().position(|x| *x == [0.7, 0.5, 0.2]).unwrap(),
        );
        assert_eq!(
            ugr.computed,
            Some(format!("{:.1} / {:.1}", t.crosswise[i][j], t.endwise[i][j]))
        );
        assert!(r.to_text().contains("declared vs computed"));
    }
}
