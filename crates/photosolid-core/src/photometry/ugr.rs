//! UGR table by the CIE tabular method (CIE 117:1995 §4, CIE 190:2010
//! standard conditions).
//!
//! UGR = 8 log₁₀[(0.25 / L_b) Σ L² ω / p²] (CIE 117 eq. 4.1), evaluated for
//! the standard rooms and reflectances of the CIE 190 table:
//! - rooms X × Y (X across the line of sight, Y along it) from 2H × 2H to
//!   12H × 8H, H the height of the luminaire plane above the seated eye;
//! - a regular array at spacing S = 1.0 H (CIE 190: spacing-to-height ratio
//!   1:1), luminaires at the cell centres; the observer at the middle of one
//!   X wall at eye level, looking horizontally along Y;
//! - crosswise and endwise as CIE 117 eqs. 4.5 and 4.6 define them through
//!   the C angle toward the eye: crosswise C = arctan(T/R), so the C0
//!   direction points along the line of sight (the luminaire axis, C90–C270,
//!   lies across it); endwise C = 90° − arctan(T/R), so C90 points along the
//!   line of sight (T across, R along the line of sight). Until 2026-11 this
//!   module had the two swapped; the CIE 190:2010 example table settled it
//!   (docs/photometry.md, "UGR against CIE 190");
//! - reflectances ceiling / walls / floor 0.7/0.5/0.2, 0.7/0.3/0.2,
//!   0.5/0.5/0.2, 0.5/0.3/0.2, 0.3/0.3/0.2 (effective cavity reflectances).
//!
//! Per luminaire: L = I / A_p and ω = A_p / r², so L²ω = I² / (A_p r²), with I
//! (cd) toward the eye on the bilinear interpolant and A_p the projected
//! luminous area ([`projected_area_m2`]); p the Guth position index
//! ln p = (35.2 − 0.31889τ − 1.22 e^(−2τ/9))·10⁻³ σ + (21 + 0.26667τ − 0.002963τ²)·10⁻⁵ σ²
//! (CIE 117; the same expression as Radiance `src/util/glarendx.c`, `posindex`),
//! σ the angle between the line of sight and the luminaire, τ the angle of
//! the plane through both from the vertical.
//!
//! Background luminance L_b = E_WID / π with E_WID the indirect illuminance on
//! the walls, from a three-surface interreflection (ceiling at the luminaire
//! plane, floor at the eye plane, walls between) with exact form factors: the
//! luminaires' upward flux lands on the ceiling; of the downward flux, the
//! floor receives what the array sends into the floor rectangle (integrated
//! from the distribution on a H/8 grid) and the walls the rest.
//!
//! The table holds for the file's flux: relative photometry at the declared
//! lamp flux Φ (CIE 117 "uncorrected" table for that flux). For another flux
//! Φ' add 8 log₁₀(Φ'/Φ) (L and I scale with the flux, L_b with it too).
//! UGR does not depend on H (every length scales with it), checked in the tests.
//!
//! Luminaires outside CIE 117's field are left out of the glare sum (they
//! still light the room): outside the domain of its Guth Table 4.1, T/R ≤ 3
//! and H/R ≤ 1.9 (the table's axes as transcribed in 123VincentB/eulumdat-ugr,
//! `guth.py`: the first row of the standard array, at R = H/2, is out), or
//! γ > 85° (the eulumdat-ugr notes quoting CIE 117). With this field the CIE
//! 190:2010 example table is met to ±0.22 in every cell (tests/it/photometry.rs). Not modelled: CIE 117's
//! Table 4.1 (the closed form above stands in for it), CIE 190's preset
//! F_GL / F_T background factors (the exact interreflection stands in), the
//! 0.25 H array of catalogue tables, and the correction tables for other spacings.

use glam::DVec3;
use serde::Serialize;

use super::luminance::{projected_area_m2, GridLookup};
use crate::error::{ModelError, Undefined};
use crate::model::frame::unit_angles;
use crate::model::opening::Opening;
use crate::model::Luminaire;

/// Standard rooms (X, Y) in units of H (CIE 190 / CIE 117 table rows).
pub const ROOMS_H: [(f64, f64); 19] = [
    (2.0, 2.0),
    (2.0, 3.0),
    (2.0, 4.0),
    (2.0, 6.0),
    (2.0, 8.0),
    (2.0, 12.0),
    (4.0, 2.0),
    (4.0, 3.0),
    (4.0, 4.0),
    (4.0, 6.0),
    (4.0, 8.0),
    (4.0, 12.0),
    (8.0, 4.0),
    (8.0, 6.0),
    (8.0, 8.0),
    (8.0, 12.0),
    (12.0, 4.0),
    (12.0, 6.0),
    (12.0, 8.0),
];

/// Standard reflectance combinations (ceiling, walls, floor).
pub const REFLECTANCES: [(f64, f64, f64); 5] = [
    (0.7, 0.5, 0.2),
    (0.7, 0.3, 0.2),
    (0.5, 0.5, 0.2),
    (0.5, 0.3, 0.2),
    (0.3, 0.3, 0.2),
];

/// Luminaire spacing of catalogue tables, in H: the spacing-to-height
/// ratio 0.25 at which manufacturers' catalogues, DIALux and Relux publish
/// the table (CIE 117:1995 §4.4) and [`ugr_table`] computes it.
pub const CATALOGUE_SPACING_H: f64 = 0.25;

/// The spacing of CIE 190:2010's own example table, in H (1:1).
pub const CIE_190_EXAMPLE_SPACING_H: f64 = 1.0;

/// Floor integration cells per H at spacings up to [`CATALOGUE_SPACING_H`]
/// (a larger spacing keeps cells of at most H/8).
const CELLS_PER_H: f64 = 8.0;

/// Smallest spacing accepted, in H (a finer array only adds cost: the table
/// converges as the array becomes continuous).
pub const MIN_SPACING_H: f64 = 0.1;

/// The UGR table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UgrTable {
    /// Rooms (X, Y) in H, one per row.
    pub rooms_h: Vec<[f64; 2]>,
    /// Reflectances (ceiling, walls, floor), one per column.
    pub reflectances: Vec<[f64; 3]>,
    /// Crosswise UGR, `[room][reflectance]`.
    pub crosswise: Vec<Vec<f64>>,
    /// Endwise UGR, `[room][reflectance]`.
    pub endwise: Vec<Vec<f64>>,
    /// Luminaire spacing, H.
    pub spacing_h: f64,
    /// The flux the table holds for, lm (the distribution's integrated flux).
    pub flux_lm: f64,
    /// Largest value in the table.
    pub max: f64,
}

/// View of the array: how the luminaire frame sits in the room frame
/// (room +y is the line of sight, +x across it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Luminaire C0 along the line of sight, its C90–C270 axis across it:
    /// the eye sees C = arctan(T/R) (CIE 117 eq. 4.5).
    Crosswise,
    /// Luminaire C90 along the line of sight: the eye sees
    /// C = 90° − arctan(T/R) (CIE 117 eq. 4.6).
    Endwise,
}

impl View {
    /// A room-frame vector in the luminaire frame.
    fn to_luminaire(self, v: DVec3) -> DVec3 {
        match self {
            View::Crosswise => DVec3::new(v.y, -v.x, v.z),
            View::Endwise => v,
        }
    }
}

/// View factor between two aligned, parallel a × b rectangles a distance c
/// apart (Hottel's closed form; Howell's catalogue C-11).
pub fn parallel_rectangles_view_factor(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (x2, y2) = (x * x, y * y);
    let s = ((1.0 + x2) * (1.0 + y2) / (1.0 + x2 + y2)).sqrt().ln()
        + x * (1.0 + y2).sqrt() * (x / (1.0 + y2).sqrt()).atan()
        + y * (1.0 + x2).sqrt() * (y / (1.0 + x2).sqrt()).atan()
        - x * x.atan()
        - y * y.atan();
    2.0 * s / (std::f64::consts::PI * x * y)
}

/// Exitances (lm/m²) of ceiling, floor and walls of an X × Y × H box (m)
/// receiving `direct` lm (ceiling, floor, walls) with reflectances `rho`,
/// and the indirect illuminance on the walls E_WID (lx).
pub fn box_interreflection(x: f64, y: f64, h: f64, direct: [f64; 3], rho: [f64; 3]) -> ([f64; 3], f64) {
    let (a_cf, a_w) = (x * y, 2.0 * (x + y) * h);
    let f_cf = parallel_rectangles_view_factor(x, y, h);
    let f_cw = 1.0 - f_cf;
    let f_wc = f_cw * a_cf / a_w;
    // Rows: from ceiling, floor, walls to ceiling, floor, walls.
    let f = [[0.0, f_cf, f_cw], [f_cf, 0.0, f_cw], [f_wc, f_wc, 1.0 - 2.0 * f_wc]];
    let area = [a_cf, a_cf, a_w];
    // M_i − ρ_i Σ_j F_ij M_j = ρ_i Φ_i / A_i
    let mut m = [[0.0; 4]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = f64::from(u8::from(i == j)) - rho[i] * f[i][j];
        }
        m[i][3] = rho[i] * direct[i] / area[i];
    }
    let exitance = solve3(m);
    let e_wid = (0..3).map(|j| f[2][j] * exitance[j]).sum();
    (exitance, e_wid)
}

/// Gaussian elimination with partial pivoting on an augmented 3 × 4 matrix.
fn solve3(mut m: [[f64; 4]; 3]) -> [f64; 3] {
    for col in 0..3 {
        let p = (col..3)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .unwrap_or(col);
        m.swap(col, p);
        let piv = m[col][col];
        if piv == 0.0 {
            return [0.0; 3];
        }
        for r in 0..3 {
            if r != col {
                let k = m[r][col] / piv;
                let pivot_row = m[col];
                for (x, p) in m[r].iter_mut().zip(pivot_row).skip(col) {
                    *x -= k * p;
                }
            }
        }
    }
    [m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]]
}

/// Guth position index of a source in direction `s` (unit, room frame) for a
/// line of sight along +y with +z up; None behind the observer.
pub fn position_index(s: DVec3) -> Option<f64> {
    let cos_sigma = s.y;
    if cos_sigma <= 0.0 {
        return None;
    }
    if cos_sigma >= 1.0 {
        return Some(1.0);
    }
    let sigma = cos_sigma.acos().to_degrees();
    let across = (1.0 - cos_sigma * cos_sigma).sqrt();
    let tau = (s.z.abs() / across).min(1.0).acos().to_degrees();
    let ln_p = sigma
        * ((35.2 - 0.31889 * tau - 1.22 * (-2.0 * tau / 9.0).exp()) * 1e-3
            + sigma * (21.0 + 0.26667 * tau - 0.002963 * tau * tau) * 1e-5);
    Some(ln_p.exp())
}

/// Whether a luminaire at (x across, y along the line of sight), in H, lies
/// outside the field CIE 117 evaluates: outside its Guth Table 4.1, whose
/// axes run T/R 0 … 3 and H/R 0 … 1.9 (so the first row of the standard
/// array, at R = H/2, H/R = 2, is out), or γ > 85°.
fn field_cut(x: f64, y: f64) -> bool {
    x.abs() > 3.0 * y || 1.0 > 1.9 * y || (x * x + y * y).sqrt() > 85f64.to_radians().tan()
}

/// Whether `spacing_h` (in H) is a spacing the table can be computed at:
/// 1/n of H (every standard room then holds a whole array in both
/// directions) between [`MIN_SPACING_H`] and 1.
///
/// # Errors
/// [`ModelError::Parameter`] `ugr-spacing`, naming the accepted values.
pub fn check_spacing_h(spacing_h: f64) -> Result<(), ModelError> {
    let per_h = 1.0 / spacing_h;
    let whole = (per_h - per_h.round()).abs() <= 1e-9 * per_h;
    if spacing_h.is_finite() && (MIN_SPACING_H - 1e-12..=1.0 + 1e-12).contains(&spacing_h) && whole {
        return Ok(());
    }
    Err(ModelError::Parameter {
        name: "ugr-spacing",
        value: format!("{} H", crate::error::Num(spacing_h)),
        reason: format!(
            "expected 1/n of H from {MIN_SPACING_H} to 1 (0.25 the catalogue spacing, 0.5, 1.0 as CIE 190's example table), so that every standard room holds a whole array"
        ),
    })
}

/// The regular array of a standard room: `spacing_h` between luminaires (in
/// H), the floor integrated on cells of `cell_h` (in H), an even number of
/// cells per spacing so that every luminaire sits on a cell corner.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Layout {
    spacing_h: f64,
    /// Floor cells per spacing (even).
    cells_per_spacing: i64,
}

impl Layout {
    /// The layout at `spacing_h`, which must divide H (every standard room
    /// is a whole number of spacings in both directions) and be at least
    /// [`MIN_SPACING_H`].
    fn new(spacing_h: f64) -> Result<Self, ModelError> {
        check_spacing_h(spacing_h)?;
        let cells = 2 * ((spacing_h * CELLS_PER_H / 2.0).ceil() as i64).max(1);
        Ok(Layout {
            spacing_h,
            cells_per_spacing: cells,
        })
    }

    /// Floor cell size, in H.
    fn cell_h(&self) -> f64 {
        self.spacing_h / self.cells_per_spacing as f64
    }

    /// Luminaires across (X) and along (Y) the line of sight in room X × Y (in H).
    fn counts(&self, x_h: f64, y_h: f64) -> (i64, i64) {
        (
            (x_h / self.spacing_h).round() as i64,
            (y_h / self.spacing_h).round() as i64,
        )
    }
}

/// What the table needs from the luminaire, precomputed per view.
struct Array<'a> {
    look: GridLookup<'a>,
    opening: &'a Opening,
    view: View,
    layout: Layout,
    /// Flux (in units of H² lx … i.e. lm for H = 1) into each floor cell at
    /// offset (m_x, m_y) from a luminaire, as a summed-area table.
    floor_sat: Vec<f64>,
    /// Cells from the luminaire to the edge of the table (12 H).
    half: usize,
}

impl<'a> Array<'a> {
    /// Floor cells span offsets −12H..12H in both directions (the largest room is 12 H).
    fn new(look: GridLookup<'a>, opening: &'a Opening, view: View, layout: Layout) -> Self {
        let cell = layout.cell_h();
        let half = (12.0 / cell).round() as usize;
        let side = 2 * half;
        let mut sat = vec![0.0; (side + 1) * (side + 1)];
        for iy in 0..side {
            let mut row = 0.0;
            for ix in 0..side {
                let dx = (ix as f64 - half as f64 + 0.5) * cell;
                let dy = (iy as f64 - half as f64 + 0.5) * cell;
                let v = DVec3::new(dx, dy, -1.0);
                let r2 = v.length_squared();
                let (c, g) = unit_angles(view.to_luminaire(v / r2.sqrt()));
                // E = I cos γ / r² with cos γ = 1/r (H = 1), times the cell area.
                let flux = look.at(c, g) / (r2 * r2.sqrt()) * cell * cell;
                row += flux;
                sat[(iy + 1) * (side + 1) + ix + 1] = sat[iy * (side + 1) + ix + 1] + row;
            }
        }
        Array {
            look,
            opening,
            view,
            layout,
            floor_sat: sat,
            half,
        }
    }

    /// Sum of floor cells with offsets in [x0, x1) × [y0, y1) (cell indices from −half).
    fn floor_sum(&self, x0: i64, x1: i64, y0: i64, y1: i64) -> f64 {
        let h = self.half as i64;
        let side = 2 * h;
        let w = (side + 1) as usize;
        let idx = |x: i64, y: i64| ((y + h).clamp(0, side) as usize) * w + (x + h).clamp(0, side) as usize;
        self.floor_sat[idx(x1, y1)] - self.floor_sat[idx(x0, y1)] - self.floor_sat[idx(x1, y0)]
            + self.floor_sat[idx(x0, y0)]
    }

    /// (Σ L²ω/p² for H = 1 m, direct flux to the floor for H = 1) in room X × Y (in H).
    fn room(&self, x_h: f64, y_h: f64) -> (f64, f64) {
        let s = self.layout.spacing_h;
        let (nx, ny) = self.layout.counts(x_h, y_h);
        let s_cells = self.layout.cells_per_spacing;
        let (room_x, room_y) = (nx * s_cells, ny * s_cells);
        let (mut glare, mut floor) = (0.0, 0.0);
        for i in 0..nx {
            for j in 0..ny {
                let x = -x_h / 2.0 + (i as f64 + 0.5) * s;
                let y = (j as f64 + 0.5) * s;
                // Floor cells 0..room_x, 0..room_y; the luminaire sits at cell
                // coordinate (i + 0.5)·S·k, so offsets run from −that.
                let (ox, oy) = (i * s_cells + s_cells / 2, j * s_cells + s_cells / 2);
                floor += self.floor_sum(-ox, room_x - ox, -oy, room_y - oy);
                if field_cut(x, y) {
                    continue;
                }
                let to_lum = DVec3::new(x, y, 1.0);
                let r2 = to_lum.length_squared();
                let dir = to_lum / r2.sqrt();
                let Some(p) = position_index(dir) else { continue };
                let emit = self.view.to_luminaire(-dir);
                let (c, g) = unit_angles(emit);
                let a_p = projected_area_m2(self.opening, emit);
                let i_cd = self.look.at(c, g);
                if a_p > 0.0 && i_cd > 0.0 {
                    glare += i_cd * i_cd / (a_p * r2 * p * p);
                }
            }
        }
        (glare, floor)
    }
}

/// UGR for one room, view and reflectance set at luminaire height `h_m`
/// above the eye, luminaires `spacing_h` (in H) apart. None when no
/// luminaire sends light toward the observer or the background is dark.
pub fn ugr_room(
    lum: &Luminaire,
    view: View,
    room_h: (f64, f64),
    rho: (f64, f64, f64),
    h_m: f64,
    spacing_h: f64,
) -> Result<Option<f64>, ModelError> {
    let rooms = Rooms::new(lum, spacing_h)?;
    Ok(one(&rooms.array(view), &rooms.flux, room_h, rho, h_m))
}

/// The set-up every standard room of one luminaire shares: its luminous
/// opening, the array layout and its flux (one place, so the table, one
/// room and one background cannot drift apart).
struct Rooms<'a> {
    lum: &'a Luminaire,
    opening: Opening,
    layout: Layout,
    flux: super::Flux,
}

impl<'a> Rooms<'a> {
    /// # Errors
    /// [`ModelError::Parameter`] when `spacing_h` is not 1/n of H (checked first);
    /// [`ModelError::Opening`] when the luminous opening cannot be built.
    fn new(lum: &'a Luminaire, spacing_h: f64) -> Result<Self, ModelError> {
        let layout = Layout::new(spacing_h)?;
        let opening = Opening::of_luminaire(lum)?;
        Ok(Rooms {
            lum,
            opening,
            layout,
            flux: super::flux::flux(lum.distribution()),
        })
    }

    /// The array of luminaires seen in `view`.
    fn array(&self, view: View) -> Array<'_> {
        Array::new(
            GridLookup::new(self.lum.distribution()),
            &self.opening,
            view,
            self.layout,
        )
    }
}

/// The background of one standard room: where each luminaire's flux lands
/// first and the indirect wall illuminance that sets L_b = E_WID / π.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Background {
    /// Direct flux of one luminaire (mean over the array) onto the floor
    /// (the reference plane at eye level), lm: CIE 190's Φ_zL at this flux.
    pub floor_lm: f64,
    /// Direct flux of one luminaire onto the walls, lm (the rest of its downward flux).
    pub walls_lm: f64,
    /// Direct flux of one luminaire onto the ceiling, lm (its upward flux).
    pub ceiling_lm: f64,
    /// Indirect illuminance on the walls, E_WID, lx.
    pub e_wid_lx: f64,
}

/// The [`Background`] of room `room_h` (X, Y in H) for `view` with
/// reflectances `rho` (ceiling, walls, floor) at luminaire height `h_m`
/// above the eye, luminaires `spacing_h` (in H) apart.
///
/// # Errors
/// [`ModelError::Opening`] when the luminous opening cannot be built from
/// the file's dimensions; [`ModelError::Parameter`] when the spacing is not 1/n of H.
pub fn background(
    lum: &Luminaire,
    view: View,
    room_h: (f64, f64),
    rho: (f64, f64, f64),
    h_m: f64,
    spacing_h: f64,
) -> Result<Background, ModelError> {
    let rooms = Rooms::new(lum, spacing_h)?;
    let (_, floor) = rooms.array(view).room(room_h.0, room_h.1);
    Ok(room_background(&rooms.flux, rooms.layout, room_h, floor, rho, h_m))
}

/// [`Background`] from the array's direct floor flux (`floor`, all luminaires, lm).
fn room_background(
    f: &super::Flux,
    layout: Layout,
    (x_h, y_h): (f64, f64),
    floor: f64,
    (rc, rw, rf): (f64, f64, f64),
    h_m: f64,
) -> Background {
    let (nx, ny) = layout.counts(x_h, y_h);
    let n = (nx * ny) as f64;
    let direct = [n * f.upward_lm, floor, (n * f.downward_lm - floor).max(0.0)];
    let (_, e_wid) = box_interreflection(x_h * h_m, y_h * h_m, h_m, direct, [rc, rf, rw]);
    Background {
        floor_lm: direct[1] / n,
        walls_lm: direct[2] / n,
        ceiling_lm: direct[0] / n,
        e_wid_lx: e_wid,
    }
}

fn one(array: &Array, f: &super::Flux, room_h: (f64, f64), rho: (f64, f64, f64), h_m: f64) -> Option<f64> {
    let (glare_1m, floor) = array.room(room_h.0, room_h.1);
    ugr_of(array.layout, f, room_h, (glare_1m, floor), rho, h_m)
}

/// UGR from a room's glare sum (for H = 1 m) and direct floor flux ([`Array::room`]).
fn ugr_of(
    layout: Layout,
    f: &super::Flux,
    (x_h, y_h): (f64, f64),
    (glare_1m, floor): (f64, f64),
    rho: (f64, f64, f64),
    h_m: f64,
) -> Option<f64> {
    let lb = room_background(f, layout, (x_h, y_h), floor, rho, h_m).e_wid_lx / std::f64::consts::PI;
    // Σ I²/(A_p r² p²) scales as 1/H² (r ∝ H).
    let glare = glare_1m / (h_m * h_m);
    (glare > 0.0 && lb > 0.0)
        .then(|| 8.0 * (0.25 * glare / lb).log10())
        .filter(|u| u.is_finite())
}

/// The catalogue table of `lum` (luminaires [`CATALOGUE_SPACING_H`] apart),
/// or the reason it is undefined (no luminous area, no downward light).
///
/// # Errors
/// As [`ugr_table_at`].
pub fn ugr_table(lum: &Luminaire) -> Result<UgrTable, ModelError> {
    ugr_table_at(lum, CATALOGUE_SPACING_H)
}

/// The table of `lum` with luminaires `spacing_h` (in H, 1/n of H) apart.
///
/// # Errors
/// [`ModelError::Undefined`] for a point source, a luminaire without
/// downward light or one that sends none toward the observer of a room; [`ModelError::Opening`] when the declared opening is not
/// one this crate models; [`ModelError::Parameter`] for a spacing that is not 1/n of H.
pub fn ugr_table_at(lum: &Luminaire, spacing_h: f64) -> Result<UgrTable, ModelError> {
    let rooms = Rooms::new(lum, spacing_h)?;
    let (layout, f) = (rooms.layout, &rooms.flux);
    let undefined = |why| ModelError::Undefined { quantity: "UGR", why };
    if rooms.opening.is_point() {
        return Err(undefined(Undefined::NoLuminousArea));
    }
    if f.downward_lm.is_nan() || f.downward_lm <= 0.0 {
        return Err(undefined(Undefined::NoDownwardLight));
    }
    let mut tables = Vec::new();
    for view in [View::Crosswise, View::Endwise] {
        let array = rooms.array(view);
        let mut rows = Vec::new();
        for &room in &ROOMS_H {
            let mut row = Vec::new();
            // The array's sums do not depend on the reflectances: once per room.
            let sums = array.room(room.0, room.1);
            for &rho in &REFLECTANCES {
                match ugr_of(layout, f, room, sums, rho, 1.0) {
                    Some(u) => row.push(u),
                    None => return Err(undefined(Undefined::NoLightTowardObserver { room_h: room })),
                }
            }
            rows.push(row);
        }
        tables.push(rows);
    }
    let endwise = tables.pop().unwrap_or_default();
    let crosswise = tables.pop().unwrap_or_default();
    let max = crosswise
        .iter()
        .chain(&endwise)
        .flatten()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    Ok(UgrTable {
        rooms_h: ROOMS_H.iter().map(|&(x, y)| [x, y]).collect(),
        reflectances: REFLECTANCES.iter().map(|&(a, b, c)| [a, b, c]).collect(),
        crosswise,
        endwise,
        spacing_h,
        flux_lm: f.total_lm,
        max,
    })
}

#[cfg(test)]
#[path = "ugr_tests.rs"]
mod tests;
