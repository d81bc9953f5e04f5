//! Road-surface reflection: the reduced luminance coefficient
//! r(β, tan ε) = q · cos³ε of a dry road surface, from an r-table.
//!
//! Luminance of a road point lit by one luminaire (CIE 140, EN 13201-3):
//! `L = I(C, γ) · r(β, tan ε) / h²`, where ε (= γ for a level luminaire) is
//! the angle of incidence, h the mounting height over the road and β the
//! angle between the vertical plane observer → point and the vertical plane
//! point → luminaire (β = 0: the luminaire is beyond the point, seen past it).
//!
//! **Interpolation** between table nodes: three-point (quadratic) Lagrange
//! interpolation in tan ε and in β over the three nodes nearest to the query,
//! clamped at 0; it reproduces the table at its nodes. Cells the CIE table
//! leaves blank (large β at large tan ε) take the last tabulated value of
//! their row (constant along β); the lookup counts how often it reads there.
//! Beyond tan ε = 12 (ε > 85.2°) r = 0: light that grazing is not counted.
//! What the standard prescribes for interpolation could not be read from a
//! primary text (`docs/road.md`).

use std::path::Path;

use serde::Serialize;

use super::tables;
use super::RoadError;

/// The CIE standard surface classes shipped with the crate.
pub const CLASSES: [&str; 6] = ["R1", "R2", "R3", "R4", "C1", "C2"];

/// Published Q0 and S1 of the standard tables (CIE 30.2 / CIE 144, as quoted
/// in CIE 140 and EN 13201-3 texts and their implementations; `docs/road.md`).
pub fn published(class: &str) -> Option<(f64, f64)> {
    Some(match class {
        "R1" => (0.10, 0.25),
        "R2" => (0.07, 0.58),
        "R3" => (0.07, 1.11),
        "R4" => (0.08, 1.55),
        "C1" => (0.10, 0.24),
        "C2" => (0.07, 0.97),
        _ => return None,
    })
}

/// An r-table: r × 10⁴ over `tan` (rows) × `beta` (columns, 0–180°).
#[derive(Debug, Clone, PartialEq)]
pub struct RTable {
    /// Class name (`R3`) or the user file's name.
    pub name: String,
    /// tan ε of the rows, increasing from 0.
    pub tan: Vec<f64>,
    /// β of the columns, degrees, increasing from 0 to 180.
    pub beta: Vec<f64>,
    /// r × 10⁴, one row per tan value, blanks filled (see the module docs).
    r: Vec<Vec<f64>>,
    /// Whether each cell was tabulated (not blank) in the source.
    tabulated: Vec<Vec<bool>>,
    /// Multiplier applied to every value (q0 override: wanted / table Q0).
    scale: f64,
}

/// Q0, S1 and S2 of a table (see [`RTable::characteristics`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Characteristics {
    /// Average luminance coefficient Q0, sr⁻¹ (solid-angle mean of q over the tabulated region).
    pub q0: f64,
    /// Specular factor S1 = r(0, 2) / r(0, 0).
    pub s1: f64,
    /// S2 = Q0 / r(0, 0).
    pub s2: f64,
}

impl RTable {
    /// A standard class (`R1`..`R4`, `C1`, `C2`, case-insensitive).
    pub fn standard(class: &str) -> Result<RTable, RoadError> {
        let c = class.trim().to_ascii_uppercase();
        let data: &[[f64; 20]; 29] = match c.as_str() {
            "R1" => &tables::R1,
            "R2" => &tables::R2,
            "R3" => &tables::R3,
            "R4" => &tables::R4,
            "C1" => &tables::C1,
            "C2" => &tables::C2,
            _ => {
                return Err(RoadError::UnknownSurface {
                    surface: class.to_string(),
                })
            }
        };
        let rows = data.iter().map(|r| r.to_vec()).collect();
        RTable::new(&c, tables::TAN.to_vec(), tables::BETA.to_vec(), rows)
    }

    /// A table from its nodes and r × 10⁴ values (0 = blank). Checks the
    /// shape, that the axes increase (tan from 0, β from 0 to 180) and that
    /// the values are finite and not negative, and that row tan = 0 is complete.
    pub fn new(name: &str, tan: Vec<f64>, beta: Vec<f64>, rows: Vec<Vec<f64>>) -> Result<RTable, RoadError> {
        let bad = |reason: String| RoadError::BadTable {
            table: name.to_string(),
            reason,
        };
        let increasing = |v: &[f64]| v.windows(2).all(|w| w[1] > w[0]) && v.iter().all(|x| x.is_finite());
        if tan.len() < 3 || !increasing(&tan) || tan[0] != 0.0 {
            return Err(bad(format!(
                "tan ε: expected at least 3 increasing values from 0, got {tan:?}"
            )));
        }
        if beta.len() < 3 || !increasing(&beta) || beta[0] != 0.0 || beta[beta.len() - 1] != 180.0 {
            return Err(bad(format!(
                "β: expected at least 3 increasing values from 0 to 180 degrees, got {beta:?}"
            )));
        }
        if rows.len() != tan.len() || rows.iter().any(|r| r.len() != beta.len()) {
            return Err(bad(format!(
                "expected {} rows of {} values (tan ε × β)",
                tan.len(),
                beta.len()
            )));
        }
        if let Some(v) = rows.iter().flatten().find(|v| !(v.is_finite() && **v >= 0.0)) {
            return Err(bad(format!("r × 10⁴ = {v}: expected finite values ≥ 0")));
        }
        if rows[0].contains(&0.0) {
            return Err(bad("the row tan ε = 0 must be complete (no blank or 0)".into()));
        }
        let tabulated: Vec<Vec<bool>> = rows.iter().map(|r| r.iter().map(|&v| v > 0.0).collect()).collect();
        let mut r = rows;
        for row in &mut r {
            for j in 1..row.len() {
                if row[j] == 0.0 {
                    row[j] = row[j - 1];
                }
            }
        }
        Ok(RTable {
            name: name.to_string(),
            tan,
            beta,
            r,
            tabulated,
            scale: 1.0,
        })
    }

    /// Read a user table: plain text, `#` comments; the first data line is
    /// `0 β1 β2 … 180` (a corner value, then the β columns in degrees),
    /// each further line `tanε r1 r2 …` with r × 10⁴ (0 or `-` = blank).
    /// Separators: spaces, tabs, commas or semicolons.
    pub fn load(path: &Path) -> Result<RTable, RoadError> {
        let text = std::fs::read_to_string(path).map_err(|e| RoadError::BadTable {
            table: path.display().to_string(),
            reason: e.to_string(),
        })?;
        let name = path.display().to_string();
        let bad = |line: usize, reason: String| RoadError::BadTable {
            table: name.clone(),
            reason: format!("line {line}: {reason}"),
        };
        let mut header: Option<Vec<f64>> = None;
        let (mut tan, mut rows) = (Vec::new(), Vec::new());
        for (k, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let vals: Vec<f64> = line
                .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
                .filter(|t| !t.is_empty())
                .map(|t| if t == "-" { Ok(0.0) } else { t.parse::<f64>() })
                .collect::<Result<_, _>>()
                .map_err(|e| bad(k + 1, format!("`{line}`: {e}")))?;
            match &header {
                None => header = Some(vals[1..].to_vec()),
                Some(h) => {
                    if vals.len() != h.len() + 1 {
                        return Err(bad(
                            k + 1,
                            format!("expected tan ε and {} values, got {} numbers", h.len(), vals.len()),
                        ));
                    }
                    tan.push(vals[0]);
                    rows.push(vals[1..].to_vec());
                }
            }
        }
        let beta = header.ok_or_else(|| bad(0, "empty table".into()))?;
        RTable::new(&name, tan, beta, rows)
    }

    /// The same table scaled so that its Q0 becomes `q0` (sr⁻¹): the usual
    /// way to use a standard table for a surface of another lightness.
    pub fn with_q0(mut self, q0: f64) -> Result<RTable, RoadError> {
        if !(q0.is_finite() && q0 > 0.0 && q0 < 1.0) {
            return Err(RoadError::Invalid {
                key: "q0",
                reason: format!("q0 = {q0}: expected a number in (0, 1) sr⁻¹"),
            });
        }
        let base = published(&self.name)
            .map(|p| p.0)
            .unwrap_or_else(|| self.characteristics().q0);
        self.scale = q0 / base;
        Ok(self)
    }

    /// The multiplier applied by [`RTable::with_q0`] (1 without).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// r × 10⁴ stored at node (row `i`, column `j`), blanks filled, unscaled.
    pub fn node(&self, i: usize, j: usize) -> f64 {
        self.r[i][j]
    }

    /// Whether node (i, j) was tabulated in the source.
    pub fn is_tabulated(&self, i: usize, j: usize) -> bool {
        self.tabulated[i][j]
    }

    /// The largest tan ε tabulated.
    pub fn tan_max(&self) -> f64 {
        self.tan[self.tan.len() - 1]
    }

    /// r (sr⁻¹, not × 10⁴) at β (degrees, folded into 0–180) and tan ε ≥ 0;
    /// 0 beyond the table's last tan ε. The flag says whether the value came
    /// (at least partly) from a blank cell of the source table.
    pub fn lookup(&self, beta_deg: f64, tan_eps: f64) -> (f64, bool) {
        self.lookup_with(RInterpolation::Quadratic, beta_deg, tan_eps)
    }

    /// [`RTable::lookup`] with the interpolation between the table's nodes chosen.
    pub fn lookup_with(&self, interpolation: RInterpolation, beta_deg: f64, tan_eps: f64) -> (f64, bool) {
        if !(beta_deg.is_finite() && tan_eps.is_finite()) || tan_eps < 0.0 || tan_eps > self.tan_max() * (1.0 + 1e-12) {
            return (0.0, false);
        }
        let b = beta_deg.abs().rem_euclid(360.0);
        let b = if b > 180.0 { 360.0 - b } else { b };
        let weights = match interpolation {
            RInterpolation::Quadratic => lagrange3,
            RInterpolation::Bilinear => linear2,
        };
        let (it, wt) = weights(&self.tan, tan_eps);
        let (ib, wb) = weights(&self.beta, b);
        let mut v = 0.0;
        let mut blank = false;
        for (a, &w1) in wt.iter().enumerate() {
            for (c, &w2) in wb.iter().enumerate() {
                let w = w1 * w2;
                if w != 0.0 {
                    v += w * self.r[it + a][ib + c];
                    blank |= !self.tabulated[it + a][ib + c];
                }
            }
        }
        (v.max(0.0) * 1e-4 * self.scale, blank)
    }

    /// Q0, S1, S2 of the table (unscaled). Q0 = ∫q dΩ / Ω over the tabulated
    /// cells, with q = r / cos³ε: in t = tan ε, q dΩ = r t dt dβ and
    /// dΩ = t (1 + t²)^(-3/2) dt dβ; each cell whose four nodes are all
    /// tabulated counts, integrated by the trapezoid rule on its corners.
    pub fn characteristics(&self) -> Characteristics {
        let (mut num, mut den) = (0.0, 0.0);
        let w = |t: f64| t / (1.0 + t * t).powf(1.5);
        for i in 0..self.tan.len() - 1 {
            for j in 0..self.beta.len() - 1 {
                let cells = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
                if cells.iter().any(|&(a, b)| !self.tabulated[a][b]) {
                    continue;
                }
                let dt = self.tan[i + 1] - self.tan[i];
                let db = (self.beta[j + 1] - self.beta[j]).to_radians();
                let rt: f64 = cells
                    .iter()
                    .map(|&(a, b)| self.r[a][b] * 1e-4 * self.tan[a])
                    .sum::<f64>()
                    / 4.0;
                num += rt * dt * db;
                den += (w(self.tan[i]) + w(self.tan[i + 1])) / 2.0 * dt * db;
            }
        }
        let q0 = if den > 0.0 { num / den } else { 0.0 };
        let r00 = self.r[0][0] * 1e-4;
        let s1 = match self.tan.iter().position(|&t| (t - 2.0).abs() < 1e-9) {
            Some(i2) => self.r[i2][0] / self.r[0][0],
            None => self.lookup(0.0, 2.0).0 / self.scale / r00,
        };
        Characteristics { q0, s1, s2: q0 / r00 }
    }
}

/// How r is interpolated between the table's nodes (`[road] r_interpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RInterpolation {
    /// Three-point Lagrange (quadratic) in β and in tan ε, as CIE 140 describes (the default).
    #[default]
    Quadratic,
    /// Linear in β and in tan ε between the two enclosing nodes.
    Bilinear,
}

impl RInterpolation {
    /// Parse the `r_interpolation` key.
    pub fn parse(s: &str) -> Result<RInterpolation, RoadError> {
        match s.trim() {
            "quadratic" => Ok(RInterpolation::Quadratic),
            "bilinear" => Ok(RInterpolation::Bilinear),
            other => Err(RoadError::Invalid {
                key: "r_interpolation",
                reason: format!("{other:?}: expected \"quadratic\" or \"bilinear\""),
            }),
        }
    }

    /// The name as written in the scene file.
    pub fn as_str(self) -> &'static str {
        match self {
            RInterpolation::Quadratic => "quadratic",
            RInterpolation::Bilinear => "bilinear",
        }
    }
}

/// The first of the two nodes enclosing `x` and their linear weights (the
/// third weight 0, so the result reads as [`lagrange3`]'s); `x` outside the
/// nodes is clamped to the end node.
fn linear2(nodes: &[f64], x: f64) -> (usize, [f64; 3]) {
    let n = nodes.len();
    let x = x.clamp(nodes[0], nodes[n - 1]);
    let k = nodes.partition_point(|&v| v <= x).saturating_sub(1).min(n - 2);
    let f = (x - nodes[k]) / (nodes[k + 1] - nodes[k]);
    (k, [1.0 - f, f, 0.0])
}

/// The first of the three nodes nearest to `x` and the Lagrange weights of
/// the three; `x` outside the nodes is clamped to the end node.
fn lagrange3(nodes: &[f64], x: f64) -> (usize, [f64; 3]) {
    let n = nodes.len();
    let x = x.clamp(nodes[0], nodes[n - 1]);
    // interval [k, k+1] holding x
    let k = nodes.partition_point(|&v| v <= x).saturating_sub(1).min(n - 2);
    if x == nodes[k] {
        let s = k.saturating_sub(1).min(n - 3);
        let mut w = [0.0; 3];
        w[k - s] = 1.0;
        return (s, w);
    }
    // third node on the side nearer to x
    let s = if k == 0 {
        0
    } else if k + 2 >= n {
        n - 3
    } else if x - nodes[k] < nodes[k + 1] - x {
        k - 1
    } else {
        k
    };
    let (a, b, c) = (nodes[s], nodes[s + 1], nodes[s + 2]);
    let w = [
        (x - b) * (x - c) / ((a - b) * (a - c)),
        (x - a) * (x - c) / ((b - a) * (b - c)),
        (x - a) * (x - b) / ((c - a) * (c - b)),
    ];
    (s, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_standard_table_reproduces_its_nodes() {
        for c in CLASSES {
            let t = RTable::standard(c).unwrap();
            for (i, &tn) in t.tan.iter().enumerate() {
                for (j, &bn) in t.beta.iter().enumerate() {
                    let (v, _) = t.lookup(bn, tn);
                    assert!((v * 1e4 - t.node(i, j)).abs() < 1e-9, "{c} ({tn}, {bn}): {v}");
                }
            }
        }
    }

    /// S1 is a ratio of two table entries and Q0 the solid-angle mean over the
    /// tabulated region: both must round to the published class values
    /// (two decimals: within 0.006 and 0.005). Computed: Q0 R1 0.1040,
    /// R2 0.0709, R3 0.0701, R4 0.0797, C1 0.1020, C2 0.0713.
    #[test]
    fn q0_and_s1_match_the_published_class_values() {
        for c in CLASSES {
            let ch = RTable::standard(c).unwrap().characteristics();
            let (q0, s1) = published(c).unwrap();
            assert!((ch.s1 - s1).abs() <= 0.006, "{c}: S1 {} vs {s1}", ch.s1);
            assert!((ch.q0 - q0).abs() <= 0.005, "{c}: Q0 {} vs {q0}", ch.q0);
            assert!(ch.s2 > 1.0 && ch.s2.is_finite());
        }
    }

    #[test]
    fn lookup_is_smooth_between_nodes_and_zero_beyond() {
        let t = RTable::standard("R3").unwrap();
        let (a, _) = t.lookup(0.0, 1.9);
        let (b, _) = t.lookup(0.0, 2.1);
        assert!(a > b && b > 0.0);
        assert_eq!(t.lookup(0.0, 12.5).0, 0.0);
        assert_eq!(t.lookup(190.0, 1.0).0, t.lookup(170.0, 1.0).0);
        assert!(t.lookup(170.0, 11.0).1, "a blank cell is flagged");
    }

    #[test]
    fn q0_override_scales_every_value() {
        let t = RTable::standard("R3").unwrap().with_q0(0.14).unwrap();
        let base = RTable::standard("R3").unwrap();
        assert!((t.lookup(10.0, 1.0).0 / base.lookup(10.0, 1.0).0 - 2.0).abs() < 1e-12);
        assert!(RTable::standard("R3").unwrap().with_q0(-1.0).is_err());
    }

    #[test]
    fn unknown_class_is_an_error() {
        let e = RTable::standard("R9").unwrap_err();
        assert_eq!(e.code(), "road-unknown-surface");
    }

    #[test]
    fn lagrange_weights_sum_to_one() {
        let n = [0.0, 2.0, 5.0, 10.0, 15.0];
        for x in [0.0, 0.5, 1.9, 2.0, 3.3, 7.0, 14.0, 15.0] {
            let (_, w) = lagrange3(&n, x);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{x}");
        }
    }
}
