//! The road's quantities (EN 13201-2 / -3, CIE 140; `docs/road.md`):
//!
//! - **luminance** at the luminance grid (3 points across each lane, N along
//!   the field) for one observer per lane: eye 1.5 m high, 60 m before the
//!   field, in the lane's centre; `L = Σ MF · I · r(β, tan ε) / h²` over the
//!   luminaires from 5 h before to 12 h beyond the point (h: mounting height);
//! - per observer: L_av (mean over the whole carriageway grid),
//!   U_o = L_min / L_av, U_l = L_min / L_max along the observer lane's centre line;
//! - **TI**: the same lane's observer, eye 1.5 m, line of sight along the road
//!   1° down; it starts 2.75 (h − 1.5) m before the field (where a 20° car
//!   roof uncovers the first luminaire) and moves over the field in steps of
//!   the grid's longitudinal spacing; at each stop
//!   `L_v = 9.86 (1 + (A/66.4)⁴) Σ E_eye / θ²` (A = 23 years, θ in degrees,
//!   1.5° ≤ θ ≤ 60°, luminaires up to 500 m ahead and at most 20° above the
//!   horizontal), `TI = 65 L_v / L_av^0.8` (L_av ≤ 5 cd/m²) or
//!   `95 L_v / L_av^1.05`, initial values (MF = 1); TI is the largest over the stops;
//! - **illuminance** on the EN 13201-3 grid (≤ 1.5 m across, ≥ 3 points),
//!   luminaires within 5 h along the road; E_av, E_min, U_o(E);
//!   hemispherical illuminance `E_hs = Σ MF · I (1 + cos ε) / (4 d²)`;
//! - **R_EI**: mean illuminance on a strip just outside each carriageway edge
//!   over that on the strip just inside, strips min(5 m, width/2) wide; the
//!   smaller of the two sides.
//!
//! Overall: L_av and U_o the smallest over the observers, U_l the smallest,
//! TI the largest.

use glam::DVec3;
use serde::Serialize;

use super::layout::{Placed, Road, TiScreening};
use super::surface::RInterpolation;
use super::RoadError;
use crate::error::{Warning, WarningCode};
use crate::model::IntensityField;
use crate::plan::{Models, REFERENCE};

/// Observer eye height, m.
pub const EYE_HEIGHT_M: f64 = 1.5;
/// Distance of the luminance observer before the field, m.
pub const OBSERVER_DISTANCE_M: f64 = 60.0;
/// Observer age in the veiling-luminance formula, years.
pub const TI_AGE_YEARS: f64 = 23.0;
/// Luminaires up to this far ahead count for TI, m.
pub const TI_RANGE_M: f64 = 500.0;
/// Car-roof screening angle above the horizontal, degrees.
pub const TI_SCREEN_DEG: f64 = 20.0;
/// Line of sight below the horizontal, degrees.
pub const TI_SIGHT_DOWN_DEG: f64 = 1.0;
/// Luminance: luminaires from this many mounting heights before the point …
pub const LUM_BEFORE_H: f64 = 5.0;
/// … to this many beyond it.
pub const LUM_BEYOND_H: f64 = 12.0;
/// Illuminance: luminaires within this many mounting heights along the road.
pub const ILLUM_REACH_H: f64 = 5.0;

/// The veiling-luminance constant 9.86 (1 + (A/66.4)⁴) at A = 23 years (≈ 10.0).
pub fn veiling_constant() -> f64 {
    9.86 * (1.0 + (TI_AGE_YEARS / 66.4).powi(4))
}

/// TI (%) from the veiling luminance and the initial average road luminance.
pub fn threshold_increment(l_v: f64, l_av: f64) -> f64 {
    if l_av <= 5.0 {
        65.0 * l_v / l_av.powf(0.8)
    } else {
        95.0 * l_v / l_av.powf(1.05)
    }
}

/// Calculation options (defaults: the standard's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoadOptions {
    /// Grid refinement factor: every grid count times this (1: the standard grid).
    pub refine: usize,
    /// Distance of the luminance observer before the field, m.
    pub observer_distance_m: f64,
}

impl Default for RoadOptions {
    fn default() -> Self {
        Self {
            refine: 1,
            observer_distance_m: OBSERVER_DISTANCE_M,
        }
    }
}

/// A grid of values over the field: `values[j][i]` at (`x_m[i]`, `y_m[j]`).
#[derive(Debug, Clone, Serialize)]
pub struct Grid {
    /// x of the columns, m.
    pub x_m: Vec<f64>,
    /// y of the rows, m.
    pub y_m: Vec<f64>,
    /// Values, one row per y.
    pub values: Vec<Vec<f64>>,
}

impl Grid {
    fn mean(&self) -> f64 {
        let n = self.values.iter().map(Vec::len).sum::<usize>();
        if n == 0 {
            return 0.0;
        }
        self.values.iter().flatten().sum::<f64>() / n as f64
    }
    fn min(&self) -> f64 {
        self.values.iter().flatten().copied().fold(f64::INFINITY, f64::min)
    }
}

/// Per observer lane (JSON contract: `lane, l_av_cd_m2, u_o, u_l, ti_pct`).
#[derive(Debug, Clone, Serialize)]
pub struct LaneResult {
    /// 1-based lane number (from y = 0).
    pub lane: usize,
    /// Average luminance seen by this lane's observer, cd/m² (maintained).
    pub l_av_cd_m2: f64,
    /// Overall uniformity L_min / L_av.
    pub u_o: f64,
    /// Longitudinal uniformity along this lane's centre line.
    pub u_l: f64,
    /// Threshold increment, %.
    pub ti_pct: f64,
}

/// The installation (JSON contract: `l_av_cd_m2, u_o, u_l, ti_pct, r_ei,
/// e_av_lux, e_min_lux, u_o_e, e_hs_av_lux`).
#[derive(Debug, Clone, Serialize)]
pub struct Overall {
    /// Smallest L_av over the observers, cd/m².
    pub l_av_cd_m2: f64,
    /// Smallest U_o.
    pub u_o: f64,
    /// Smallest U_l.
    pub u_l: f64,
    /// Largest TI, %.
    pub ti_pct: f64,
    /// Edge illuminance ratio.
    pub r_ei: f64,
    /// Average illuminance of the field, lx.
    pub e_av_lux: f64,
    /// Smallest illuminance of the field, lx.
    pub e_min_lux: f64,
    /// E_min / E_av.
    pub u_o_e: f64,
    /// Average hemispherical illuminance, lx.
    pub e_hs_av_lux: f64,
}

/// Where the observers stood.
#[derive(Debug, Clone, Serialize)]
pub struct Observer {
    /// 1-based lane.
    pub lane: usize,
    /// Luminance observer's eye, m.
    pub luminance_eye_m: [f64; 3],
    /// x of the TI observer's first and last stop, m.
    pub ti_x_m: [f64; 2],
    /// Number of TI stops.
    pub ti_stops: usize,
}

/// Everything `photosolid road` reports.
#[derive(Debug, Clone, Serialize)]
pub struct RoadResult {
    /// The scene file.
    pub scene: String,
    /// The photometric file.
    pub luminaire: String,
    /// Representation used.
    pub representation: String,
    /// Surface table name and its Q0 (sr⁻¹, after any override).
    pub surface: String,
    /// Q0 in use, sr⁻¹.
    pub q0: f64,
    /// Arrangement.
    pub arrangement: &'static str,
    /// The file's C angle pointing across the road from the pole, degrees (`street_side_c_deg`).
    pub street_side_c_deg: f64,
    /// How r was interpolated between the r-table's nodes (`r_interpolation`).
    pub r_interpolation: RInterpolation,
    /// What TI's screening angle was measured from (`ti_screening`).
    pub ti_screening: TiScreening,
    /// Field length (= spacing) and width, m.
    pub field_m: [f64; 2],
    /// Per observer lane.
    pub lanes: Vec<LaneResult>,
    /// The installation.
    pub overall: Overall,
    /// The observers.
    pub observers: Vec<Observer>,
    /// Luminance grid per observer lane, cd/m².
    pub luminance: Vec<Grid>,
    /// Illuminance grid, lx.
    pub illuminance: Grid,
    /// Hemispherical illuminance grid, lx.
    pub hemispherical: Grid,
    /// Recoverable oddities, coded (`{line, code, message}`; codes in docs/warnings.md).
    pub warnings: Vec<Warning>,
}

/// Cell-centre positions of `n` points over [a, a + w].
fn centres(a: f64, w: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| a + w * (i as f64 + 0.5) / n as f64).collect()
}

struct Ctx<'a> {
    road: &'a Road,
    field: &'a dyn IntensityField,
    lums: Vec<Placed>,
    h: f64,
}

impl Ctx<'_> {
    /// Initial intensity (cd) of luminaire `l` towards world point `p`.
    fn intensity(&self, l: &Placed, p: DVec3) -> f64 {
        let v = p - l.pose.position;
        let i = self.field.intensity_dir_cd(l.pose.to_local(v));
        if i.is_finite() {
            i.max(0.0)
        } else {
            0.0
        }
    }

    /// Maintained luminance (cd/m²) at road point `p` seen from `eye`; the
    /// count of r lookups that read blank table cells.
    fn luminance(&self, p: DVec3, eye: DVec3, blank: &mut usize) -> f64 {
        let mf = self.road.maintenance_factor;
        let view = DVec3::new(p.x - eye.x, p.y - eye.y, 0.0);
        let mut l = 0.0;
        for lum in &self.lums {
            let q = lum.pose.position;
            let dx = q.x - p.x;
            // along the viewing direction (+x): before = towards the observer
            if dx < -LUM_BEFORE_H * self.h || dx > LUM_BEYOND_H * self.h {
                continue;
            }
            let h = q.z - p.z;
            let to_lum = DVec3::new(q.x - p.x, q.y - p.y, 0.0);
            let rho = to_lum.length();
            let beta = if rho < 1e-9 || view.length() < 1e-9 {
                0.0
            } else {
                (view.dot(to_lum) / (view.length() * rho))
                    .clamp(-1.0, 1.0)
                    .acos()
                    .to_degrees()
            };
            let (r, b) = self.road.surface.lookup_with(self.road.r_interpolation, beta, rho / h);
            if r == 0.0 {
                continue;
            }
            *blank += b as usize;
            l += self.intensity(lum, p) * r / (h * h);
        }
        mf * l
    }

    /// Maintained horizontal and hemispherical illuminance (lx) at road point `p`.
    fn illuminance(&self, p: DVec3) -> (f64, f64) {
        let mf = self.road.maintenance_factor;
        let (mut e, mut ehs) = (0.0, 0.0);
        for lum in &self.lums {
            let q = lum.pose.position;
            if (q.x - p.x).abs() > ILLUM_REACH_H * self.h {
                continue;
            }
            let v = p - q;
            let d2 = v.length_squared();
            if d2 == 0.0 {
                continue;
            }
            let d = d2.sqrt();
            let cos_e = (q.z - p.z) / d;
            if cos_e <= 0.0 {
                continue;
            }
            let i = self.intensity(lum, p);
            e += i * cos_e / d2;
            ehs += i * (1.0 + cos_e) / (4.0 * d2);
        }
        (mf * e, mf * ehs)
    }

    /// Veiling luminance (cd/m², initial) at `eye` looking along +x, 1° down;
    /// counts luminaires skipped for θ < 1.5°.
    fn veiling(&self, eye: DVec3, too_close: &mut usize) -> f64 {
        let (s, c) = crate::model::frame::sin_cos_deg(TI_SIGHT_DOWN_DEG);
        let sight = DVec3::new(c, 0.0, -s);
        let mut sum = 0.0;
        for lum in &self.lums {
            let q = lum.pose.position;
            let v = q - eye;
            if v.x <= 0.0 || v.x > TI_RANGE_M {
                continue;
            }
            let horizontal = (v.x * v.x + v.y * v.y).sqrt();
            if !screening_counts(self.road.ti_screening, v.z.atan2(horizontal).to_degrees()) {
                continue;
            }
            let d = v.length();
            let cos_t = (v.dot(sight) / d).clamp(-1.0, 1.0);
            let theta = cos_t.acos().to_degrees();
            if theta > 60.0 {
                continue;
            }
            if theta < 1.5 {
                *too_close += 1;
                continue;
            }
            let e_eye = self.intensity(lum, eye) * cos_t / (d * d);
            sum += e_eye / (theta * theta);
        }
        veiling_constant() * sum
    }
}

/// Whether TI counts a luminaire at `elevation_deg` above the horizontal
/// under `screening`: at most the screening angle, with 1e-9° to spare so
/// that a luminaire placed on the angle is counted whatever the rounding.
pub fn screening_counts(screening: TiScreening, elevation_deg: f64) -> bool {
    elevation_deg <= screening.max_elevation_deg() + 1e-9
}

/// Where the luminance and TI are calculated (module docs).
struct Views {
    /// x of the grid's columns (cell centres over the field), m.
    xs: Vec<f64>,
    /// y of the luminance grid's rows over every lane, m.
    ys: Vec<f64>,
    /// Luminance rows per lane.
    per_lane: usize,
    /// x of the luminance observers' eyes, m.
    eye_x: f64,
    /// x of the TI observer's first stop, m.
    ti_start: f64,
    /// Number of TI stops (the grid's columns).
    ti_stops: usize,
    /// Distance between two TI stops, m.
    ti_step: f64,
}

impl Views {
    /// The grid and stops of `road` at `refine` times the standard's grid
    /// counts, the luminance observers `observer_distance_m` (m) before the field.
    fn new(road: &Road, refine: usize, observer_distance_m: f64) -> Self {
        let (s, h) = (road.spacing_m, road.mounting_height_m);
        let n_along = road.n_along() * refine;
        let per_lane = 3 * refine;
        Views {
            xs: centres(0.0, s, n_along),
            ys: (0..road.lanes)
                .flat_map(|k| centres(k as f64 * road.lane_width_m, road.lane_width_m, per_lane))
                .collect(),
            per_lane,
            eye_x: -observer_distance_m,
            ti_start: -2.75 * (h - EYE_HEIGHT_M).max(0.0),
            ti_stops: n_along,
            ti_step: s / n_along as f64,
        }
    }

    /// The x range (m) of the luminaires any quantity counts: from the
    /// luminance's and the illuminance's reach before the field (and before
    /// the first TI stop) to the TI range beyond the last stop, a spacing
    /// more each way.
    fn luminaire_reach(&self, road: &Road) -> (f64, f64) {
        let (s, h) = (road.spacing_m, road.mounting_height_m);
        let x_from = (self.ti_start - LUM_BEFORE_H * h).min(-ILLUM_REACH_H * h) - s;
        let x_to = s + (TI_RANGE_M + self.ti_step * self.ti_stops as f64).max(LUM_BEYOND_H * h) + s;
        (x_from, x_to)
    }
}

/// What the warnings count: r lookups into blank table cells, luminaires
/// left out of TI.
#[derive(Default)]
struct WarningCounts {
    /// r lookups that read blank table cells.
    blank: usize,
    /// Luminaires within 1.5° of a TI line of sight.
    too_close: usize,
}

/// The illuminance and hemispherical illuminance grids (lx) over the field:
/// columns at `xs` (m), rows across the width `w` (m), `refine` times the standard's.
fn illuminance_grids(ctx: &Ctx<'_>, xs: &[f64], w: f64, refine: usize) -> (Grid, Grid) {
    let ys_e = centres(0.0, w, Road::n_across(w) * refine);
    let mut e_grid = Grid {
        x_m: xs.to_vec(),
        y_m: ys_e.clone(),
        values: Vec::new(),
    };
    let mut ehs_grid = e_grid.clone();
    for &y in &ys_e {
        let (row_e, row_hs): (Vec<f64>, Vec<f64>) = xs.iter().map(|&x| ctx.illuminance(DVec3::new(x, y, 0.0))).unzip();
        e_grid.values.push(row_e);
        ehs_grid.values.push(row_hs);
    }
    (e_grid, ehs_grid)
}

/// R_EI: the smaller over the two edges of the carriageway (width `w`, m) of
/// the mean illuminance on the strip outside over that on the strip inside;
/// 0 when no inside strip is lit.
fn edge_ratio(ctx: &Ctx<'_>, xs: &[f64], w: f64, refine: usize) -> f64 {
    let strip = (w / 2.0).min(5.0);
    let strip_mean = |y0: f64| {
        let ys = centres(y0, strip, Road::n_across(strip) * refine);
        let (mut sum, mut n) = (0.0, 0usize);
        for &y in &ys {
            for &x in xs {
                sum += ctx.illuminance(DVec3::new(x, y, 0.0)).0;
                n += 1;
            }
        }
        sum / n as f64
    };
    let mut r_ei = f64::INFINITY;
    for (outside, inside) in [(-strip, 0.0), (w, w - strip)] {
        let (eo, ei) = (strip_mean(outside), strip_mean(inside));
        if ei > 0.0 {
            r_ei = r_ei.min(eo / ei);
        }
    }
    if !r_ei.is_finite() {
        r_ei = 0.0;
    }
    r_ei
}

/// The observers of lane `k` (0-based): the luminance grid they see
/// (cd/m²), its L_av, U_o and U_l, and TI over the stops.
fn observe_lane(ctx: &Ctx<'_>, v: &Views, k: usize, counts: &mut WarningCounts) -> (LaneResult, Observer, Grid) {
    let road = ctx.road;
    let y_obs = (k as f64 + 0.5) * road.lane_width_m;
    let eye = DVec3::new(v.eye_x, y_obs, EYE_HEIGHT_M);
    let mut grid = Grid {
        x_m: v.xs.clone(),
        y_m: v.ys.clone(),
        values: Vec::new(),
    };
    for &y in &v.ys {
        grid.values.push(
            v.xs.iter()
                .map(|&x| ctx.luminance(DVec3::new(x, y, 0.0), eye, &mut counts.blank))
                .collect(),
        );
    }
    let l_av = grid.mean();
    let l_min = grid.min();
    // centre line of lane k: the middle row of its points
    let centre = &grid.values[k * v.per_lane + v.per_lane / 2];
    let c_max = centre.iter().copied().fold(0.0, f64::max);
    let c_min = centre.iter().copied().fold(f64::INFINITY, f64::min);
    let u_o = if l_av > 0.0 { l_min / l_av } else { 0.0 };
    let u_l = if c_max > 0.0 { c_min / c_max } else { 0.0 };
    // TI: initial values (MF = 1)
    let ti = max_ti(ctx, v, y_obs, l_av / road.maintenance_factor, &mut counts.too_close);
    let observer = Observer {
        lane: k + 1,
        luminance_eye_m: eye.to_array(),
        ti_x_m: [v.ti_start, v.ti_start + (v.ti_stops - 1) as f64 * v.ti_step],
        ti_stops: v.ti_stops,
    };
    let result = LaneResult {
        lane: k + 1,
        l_av_cd_m2: l_av,
        u_o,
        u_l,
        ti_pct: ti,
    };
    (result, observer, grid)
}

/// The largest TI (%) over the stops of the observer at `y_obs` (m), with
/// the initial average luminance `l_init` (cd/m²; 0 when it is not positive).
fn max_ti(ctx: &Ctx<'_>, v: &Views, y_obs: f64, l_init: f64, too_close: &mut usize) -> f64 {
    let mut ti: f64 = 0.0;
    for m in 0..v.ti_stops {
        let eye = DVec3::new(v.ti_start + m as f64 * v.ti_step, y_obs, EYE_HEIGHT_M);
        let l_v = ctx.veiling(eye, too_close);
        if l_init > 0.0 {
            ti = ti.max(threshold_increment(l_v, l_init));
        }
    }
    ti
}

/// The warnings of a calculation: an observer that sees no luminance, and
/// the `counts` of blank r-table cells read and of luminaires left out of TI.
fn road_warnings(lanes: &[LaneResult], counts: &WarningCounts) -> Vec<Warning> {
    let mut warnings = Vec::new();
    if lanes.iter().any(|l| l.l_av_cd_m2 <= 0.0) {
        warnings.push(Warning::new(
            WarningCode::ObserverSeesNothing,
            "an observer sees no luminance on the field (L_av = 0): its U_o, U_l are 0 and its TI is not defined (0)",
        ));
    }
    let blank = counts.blank;
    if blank > 0 {
        warnings.push(Warning::new(
            WarningCode::RTableBlankCells,
            format!(
                "{blank} r-table look-ups read cells the CIE table leaves blank (filled with the last tabulated \
                 value of their row)"
            ),
        ));
    }
    let too_close = counts.too_close;
    if too_close > 0 {
        warnings.push(Warning::new(
            WarningCode::TiLuminairesLeftOut,
            format!(
                "{too_close} luminaire positions within 1.5 degrees of the line of sight were left out of TI (the \
                 formula holds from 1.5 to 60 degrees)"
            ),
        ));
    }
    warnings
}

/// `street-side-mismatch`: the luminaire's downward light leans more than
/// 45° away from the street side it is installed with
/// ([`crate::photometry::throw`]).
fn street_side_mismatch(road: &Road) -> Option<Warning> {
    let s = road.street_side_c_deg;
    crate::photometry::throw::leans_away_from(road.luminaire.distribution(), s).map(|t| {
        Warning::new(
            WarningCode::StreetSideMismatch,
            format!(
                "the luminaire's downward light leans towards C{:.0} ({:.0} % of its downward flux), {:.0} degrees \
                 from the street side C{} it is installed with: if C{:.0} is its street side, set \
                 street_side_c_deg = {:.0} in [road]",
                t.azimuth_c_deg,
                100.0 * t.fraction,
                crate::model::front::c_separation_deg(t.azimuth_c_deg, s),
                crate::error::Num(s),
                t.azimuth_c_deg,
                t.azimuth_c_deg
            ),
        )
    })
}

/// The installation's figures from the lanes', R_EI, the field's average
/// and smallest illuminance and its average hemispherical illuminance (lx).
fn overall_figures(lanes: &[LaneResult], r_ei: f64, e_av: f64, e_min: f64, e_hs_av: f64) -> Overall {
    let fmin = |f: fn(&LaneResult) -> f64| lanes.iter().map(f).fold(f64::INFINITY, f64::min);
    Overall {
        l_av_cd_m2: fmin(|l| l.l_av_cd_m2),
        u_o: fmin(|l| l.u_o),
        u_l: fmin(|l| l.u_l),
        ti_pct: lanes.iter().map(|l| l.ti_pct).fold(0.0, f64::max),
        r_ei,
        e_av_lux: e_av,
        e_min_lux: e_min,
        u_o_e: if e_av > 0.0 { e_min / e_av } else { 0.0 },
        e_hs_av_lux: e_hs_av,
    }
}

/// Compute the road (see the module docs).
pub fn evaluate(road: &Road, options: &RoadOptions) -> Result<RoadResult, RoadError> {
    let s = road.spacing_m;
    let w = road.width_m();
    let h = road.mounting_height_m;
    if !(options.observer_distance_m > 0.0 && options.observer_distance_m.is_finite()) {
        return Err(RoadError::ObserverInField {
            x_m: -options.observer_distance_m,
            length_m: s,
        });
    }
    let refine = options.refine.max(1);
    let template = road.scene_luminaire("road luminaire", road.luminaires(0.0, 0.0)[0].pose);
    let luminaire_err = |e: crate::ModelError| RoadError::Luminaire {
        file: road.file.clone(),
        message: e.to_string(),
    };
    let rep = road.representation.unwrap_or(REFERENCE);
    let models = Models::new(&template, &[rep]).map_err(luminaire_err)?;
    let field = models.field(&rep).map_err(luminaire_err)?;
    let views = Views::new(road, refine, options.observer_distance_m);
    let (x_from, x_to) = views.luminaire_reach(road);
    let ctx = Ctx {
        road,
        field: &*field,
        lums: road.luminaires(x_from, x_to),
        h,
    };
    let (e_grid, ehs_grid) = illuminance_grids(&ctx, &views.xs, w, refine);
    let e_av = e_grid.mean();
    let e_min = e_grid.min();
    let r_ei = edge_ratio(&ctx, &views.xs, w, refine);
    // Luminance per observer lane.
    let mut counts = WarningCounts::default();
    let (mut lanes, mut grids, mut observers) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..road.lanes {
        let (lane, observer, grid) = observe_lane(&ctx, &views, k, &mut counts);
        observers.push(observer);
        lanes.push(lane);
        grids.push(grid);
    }
    if lanes.iter().all(|l| l.l_av_cd_m2 <= 0.0) && e_av <= 0.0 {
        return Err(RoadError::NothingInView);
    }
    let mut warnings = road_warnings(&lanes, &counts);
    warnings.extend(street_side_mismatch(road));
    let overall = overall_figures(&lanes, r_ei, e_av, e_min, ehs_grid.mean());
    let ch = road.surface.characteristics();
    Ok(RoadResult {
        scene: road.path.as_ref().map(|p| p.display().to_string()).unwrap_or_default(),
        luminaire: road.file.display().to_string(),
        representation: field.name(),
        surface: road.surface.name.clone(),
        q0: super::surface::published(&road.surface.name).map_or(ch.q0, |p| p.0) * road.surface.scale(),
        arrangement: road.arrangement.as_str(),
        street_side_c_deg: road.street_side_c_deg,
        r_interpolation: road.r_interpolation,
        ti_screening: road.ti_screening,
        field_m: [s, w],
        lanes,
        overall,
        observers,
        luminance: grids,
        illuminance: e_grid,
        hemispherical: ehs_grid,
        warnings,
    })
}
