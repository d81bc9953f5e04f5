//! The lighting classes of EN 13201-2:2015 (Table 1: M1–M6, Table 2: C0–C5,
//! Table 3: P1–P6) and the verdict of a computed road against one of them.
//!
//! Each class is a list of [`Limit`]s on the figures of
//! [`super::quantities::Overall`]; a criterion's name is the `overall` key it
//! reads, so `achieved` is the value the `overall` object holds. Where the
//! standard makes a criterion conditional or leaves one optional, the limit
//! or the class carries the standard's condition as a note, and the output
//! says so (`docs/road.md`, "Lighting classes", gives the sources).

use serde::Serialize;

use super::quantities::Overall;

/// How an achieved value is held against its limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Comparison {
    /// The achieved value must be at least the limit (a minimum).
    #[serde(rename = ">=")]
    AtLeast,
    /// The achieved value must be at most the limit (a maximum).
    #[serde(rename = "<=")]
    AtMost,
}

impl Comparison {
    /// The symbol as the JSON and the text write it.
    pub fn symbol(self) -> &'static str {
        match self {
            Comparison::AtLeast => ">=",
            Comparison::AtMost => "<=",
        }
    }

    /// The signed distance of `achieved` from `required`: positive when it passes.
    pub fn margin(self, achieved: f64, required: f64) -> f64 {
        match self {
            Comparison::AtLeast => achieved - required,
            Comparison::AtMost => required - achieved,
        }
    }
}

/// Which figures a class family is judged on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Family {
    /// M classes: road luminance (motorised traffic), Table 1.
    M,
    /// C classes: illuminance of conflict areas, Table 2.
    C,
    /// P classes: illuminance for pedestrians and low-speed traffic, Table 3.
    P,
}

/// One limit of a class.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// The [`Overall`] key it reads (`l_av_cd_m2`, `u_o`, ...).
    pub name: &'static str,
    /// The limit, in `unit`.
    pub required: f64,
    /// Minimum or maximum.
    pub comparison: Comparison,
    /// Unit of the value (`cd/m²`, `lx`, `%`, or empty for a ratio).
    pub unit: &'static str,
    /// The standard's condition on this criterion, if it has one.
    pub condition: Option<&'static str>,
}

/// A lighting class of EN 13201-2:2015.
#[derive(Debug, Clone, PartialEq)]
pub struct LightingClass {
    /// `M3`, `C2`, `P4`, ...
    pub name: &'static str,
    /// Its family.
    pub family: Family,
    /// Its limits, every one counted in the verdict.
    pub limits: Vec<Limit>,
    /// What the standard adds that this calculation does not assess (optional criteria).
    pub not_assessed: Vec<&'static str>,
}

/// Where the tables come from (printed with every verdict).
pub const SOURCE: &str = "EN 13201-2:2015, Tables 1 (M), 2 (C) and 3 (P)";

/// TI is conditional in Table 1 (footnote).
const TI_CONDITION: &str =
    "EN 13201-2 Table 1 (footnote, wording as recalled): an increase of 5 percentage points in TI may be \
     permitted where low-luminance light sources are used; the verdict holds the table's value";
/// R_EI is conditional in Table 1 (footnote).
const REI_CONDITION: &str = "EN 13201-2 Table 1 (footnote, wording as recalled): applies only where no traffic \
                             areas with their own requirements adjoin the carriageway; counted in the verdict";
/// Table 1's wet-road uniformity is optional.
const WET_NOTE: &str = "U_ow (overall uniformity of the wet road) is an optional criterion of Table 1, for roads \
                        wet a substantial part of the hours of darkness: not assessed (dry r-tables only)";
/// Table 3's facial-recognition criteria are an additional, optional requirement.
const FACE_NOTE: &str = "E_v,min and E_sc,min (vertical and semi-cylindrical illuminance) are Table 3's \
                         additional requirement where facial recognition is necessary: not assessed";
/// Table 3's cap on the average illuminance (footnote), recalled but not found in a public copy.
const P_CAP_NOTE: &str = "a footnote of Table 3 is recalled as capping the maintained average illuminance at \
                          1.5 times the class's minimum (for uniformity); no public copy confirms it, so it is \
                          not counted";

/// M classes: L_av (cd/m²), U_o, U_l, TI (%), R_EI.
const M_TABLE: [(&str, [f64; 5]); 6] = [
    ("M1", [2.0, 0.40, 0.70, 10.0, 0.35]),
    ("M2", [1.5, 0.40, 0.70, 10.0, 0.35]),
    ("M3", [1.0, 0.40, 0.60, 15.0, 0.30]),
    ("M4", [0.75, 0.40, 0.60, 15.0, 0.30]),
    ("M5", [0.50, 0.35, 0.40, 15.0, 0.30]),
    ("M6", [0.30, 0.35, 0.40, 20.0, 0.30]),
];
/// C classes: E_av (lx), U_o of the illuminance.
const C_TABLE: [(&str, [f64; 2]); 6] = [
    ("C0", [50.0, 0.40]),
    ("C1", [30.0, 0.40]),
    ("C2", [20.0, 0.40]),
    ("C3", [15.0, 0.40]),
    ("C4", [10.0, 0.40]),
    ("C5", [7.5, 0.40]),
];
/// P classes: E_av (lx), E_min (lx).
const P_TABLE: [(&str, [f64; 2]); 6] = [
    ("P1", [15.0, 3.0]),
    ("P2", [10.0, 2.0]),
    ("P3", [7.5, 1.5]),
    ("P4", [5.0, 1.0]),
    ("P5", [3.0, 0.6]),
    ("P6", [2.0, 0.4]),
];

fn limit(name: &'static str, required: f64, comparison: Comparison, unit: &'static str) -> Limit {
    Limit {
        name,
        required,
        comparison,
        unit,
        condition: None,
    }
}

/// Every class name, in the standard's order.
pub fn class_names() -> Vec<&'static str> {
    M_TABLE
        .iter()
        .map(|r| r.0)
        .chain(C_TABLE.iter().map(|r| r.0))
        .chain(P_TABLE.iter().map(|r| r.0))
        .collect()
}

/// The class named `name` (case-insensitive), or `None`.
pub fn lighting_class(name: &str) -> Option<LightingClass> {
    let name = name.trim().to_ascii_uppercase();
    use Comparison::{AtLeast, AtMost};
    if let Some((n, [l, uo, ul, ti, rei])) = M_TABLE.iter().find(|r| r.0 == name) {
        return Some(LightingClass {
            name: n,
            family: Family::M,
            limits: vec![
                limit("l_av_cd_m2", *l, AtLeast, "cd/m²"),
                limit("u_o", *uo, AtLeast, ""),
                limit("u_l", *ul, AtLeast, ""),
                Limit {
                    condition: Some(TI_CONDITION),
                    ..limit("ti_pct", *ti, AtMost, "%")
                },
                Limit {
                    condition: Some(REI_CONDITION),
                    ..limit("r_ei", *rei, AtLeast, "")
                },
            ],
            not_assessed: vec![WET_NOTE],
        });
    }
    if let Some((n, [e, uo])) = C_TABLE.iter().find(|r| r.0 == name) {
        return Some(LightingClass {
            name: n,
            family: Family::C,
            limits: vec![limit("e_av_lux", *e, AtLeast, "lx"), limit("u_o_e", *uo, AtLeast, "")],
            not_assessed: Vec::new(),
        });
    }
    if let Some((n, [e, emin])) = P_TABLE.iter().find(|r| r.0 == name) {
        return Some(LightingClass {
            name: n,
            family: Family::P,
            limits: vec![
                limit("e_av_lux", *e, AtLeast, "lx"),
                limit("e_min_lux", *emin, AtLeast, "lx"),
            ],
            not_assessed: vec![FACE_NOTE, P_CAP_NOTE],
        });
    }
    None
}

/// The value of the [`Overall`] key `name` (a name [`lighting_class`] uses).
pub fn achieved(overall: &Overall, name: &str) -> f64 {
    match name {
        "l_av_cd_m2" => overall.l_av_cd_m2,
        "u_o" => overall.u_o,
        "u_l" => overall.u_l,
        "ti_pct" => overall.ti_pct,
        "r_ei" => overall.r_ei,
        "e_av_lux" => overall.e_av_lux,
        "e_min_lux" => overall.e_min_lux,
        "u_o_e" => overall.u_o_e,
        "e_hs_av_lux" => overall.e_hs_av_lux,
        _ => f64::NAN,
    }
}

/// One criterion of a verdict (JSON contract: `name, required, comparison,
/// achieved, unit, pass`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Criterion {
    /// The `overall` key the criterion reads.
    pub name: &'static str,
    /// The class's limit, in `unit`.
    pub required: f64,
    /// `>=` (a minimum) or `<=` (a maximum).
    pub comparison: Comparison,
    /// The value the `overall` object holds, in `unit`.
    pub achieved: f64,
    /// Unit (`cd/m²`, `lx`, `%`, or empty for a ratio).
    pub unit: &'static str,
    /// Whether `achieved` meets `required`.
    pub pass: bool,
    /// The signed distance to the limit, in `unit`: positive when it passes.
    pub margin: f64,
    /// The standard's condition on this criterion, when it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub condition: Option<&'static str>,
}

/// A road's verdict against a class (JSON keys `class`, `criteria`, `pass`,
/// `class_notes`, `class_source`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClassVerdict {
    /// The class's name.
    pub class: &'static str,
    /// Every criterion of the class.
    pub criteria: Vec<Criterion>,
    /// Whether every criterion passes.
    pub pass: bool,
    /// What the standard adds that was not assessed.
    pub class_notes: Vec<&'static str>,
    /// The table the limits come from.
    pub class_source: &'static str,
}

impl LightingClass {
    /// The verdict of the figures `overall` against this class.
    pub fn verdict(&self, overall: &Overall) -> ClassVerdict {
        let criteria: Vec<Criterion> = self
            .limits
            .iter()
            .map(|l| {
                let a = achieved(overall, l.name);
                let margin = l.comparison.margin(a, l.required);
                Criterion {
                    name: l.name,
                    required: l.required,
                    comparison: l.comparison,
                    achieved: a,
                    unit: l.unit,
                    pass: margin >= 0.0,
                    margin,
                    condition: l.condition,
                }
            })
            .collect();
        ClassVerdict {
            class: self.name,
            pass: criteria.iter().all(|c| c.pass),
            criteria,
            class_notes: self.not_assessed.clone(),
            class_source: SOURCE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn overall(l: f64, uo: f64, ul: f64, ti: f64, rei: f64) -> Overall {
        Overall {
            l_av_cd_m2: l,
            u_o: uo,
            u_l: ul,
            ti_pct: ti,
            r_ei: rei,
            e_av_lux: 12.0,
            e_min_lux: 5.0,
            u_o_e: 5.0 / 12.0,
            e_hs_av_lux: 6.0,
        }
    }

    #[test]
    fn every_class_is_found_and_has_its_families_criteria() {
        let names = class_names();
        assert_eq!(names.len(), 18);
        for n in names {
            let c = lighting_class(&n.to_lowercase()).unwrap();
            let expected = match c.family {
                Family::M => 5,
                Family::C => 2,
                Family::P => 2,
            };
            assert_eq!(c.limits.len(), expected, "{n}");
        }
        assert!(lighting_class("M7").is_none());
        assert!(lighting_class("").is_none());
    }

    #[test]
    fn a_verdict_passes_on_the_limits_and_fails_just_beyond() {
        let m3 = lighting_class("M3").unwrap();
        let on = m3.verdict(&overall(1.0, 0.40, 0.60, 15.0, 0.30));
        assert!(on.pass, "{on:?}");
        assert!(on.criteria.iter().all(|c| c.margin.abs() < 1e-12));
        let ti_high = m3.verdict(&overall(1.0, 0.40, 0.60, 15.000001, 0.30));
        assert!(!ti_high.pass);
        let failing: Vec<_> = ti_high.criteria.iter().filter(|c| !c.pass).map(|c| c.name).collect();
        assert_eq!(failing, ["ti_pct"]);
        let dim = m3.verdict(&overall(0.999, 0.5, 0.7, 5.0, 0.5));
        assert!(!dim.pass);
        assert!((dim.criteria[0].margin + 0.001).abs() < 1e-12);
    }

    #[test]
    fn p_classes_hold_the_minimum_at_a_fifth_of_the_average() {
        for n in ["P1", "P2", "P3", "P4", "P5", "P6"] {
            let c = lighting_class(n).unwrap();
            assert!((c.limits[1].required / c.limits[0].required - 0.2).abs() < 1e-12, "{n}");
        }
    }
}
