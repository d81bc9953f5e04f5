//! Adaptive grid solids: the C and γ angle lists refined where the field
//! needs them, to a stated tolerance, instead of a fixed factor.
//!
//! # Why whole rows and columns (a tensor-product refinement)
//! A quadtree of (C, γ) cells would put fewer vertices where the field is
//! flat in both directions, but cells of different levels meet with
//! T-junctions (cracks) unless a restricted quadtree with transition
//! triangles closes them. Refining whole C columns and γ rows keeps the
//! result a [`SolidGrid`]: [`grid_solid`](super::grid_solid) triangulates
//! it exactly as any other grid, so the mesh is watertight and manifold by
//! construction (the same code, the same topology checks) and no new
//! triangulation can go wrong. The price is that a feature at one C refines
//! its γ rows all around the circle; on photometric data the features are
//! mostly rows (cut-offs, beam edges) and planes, and a rotationally
//! symmetric field needs only as many C planes as the circle's chord error
//! asks for: a field found independent of C (tested on samples,
//! [`crate::metrics::profile::is_c_independent`]) gets evenly spaced planes
//! with `ρ (1 − cos(ΔC/2))` ≤ half the tolerance at the widest ring
//! (ρ = r sin γ); it is tested on one column, and when C needs more,
//! every C interval is halved (the planes stay evenly spaced).
//!
//! # The criterion
//! Each round builds the grid solid's vertices (the same radii, poles and
//! quad splits as [`grid_solid`](super::grid_solid)) and tests points *of the mesh*: the
//! midpoint of every C edge and γ edge, the midpoint of each quad's
//! diagonal and each triangle's centroid. At a mesh point p the distance to
//! the field's solid is at most `| |p| − I(p/|p|) |` (the point I(p/|p|)
//! p/|p| lies on the solid), at most its distance to the solid's point at
//! the test point's own (C, γ) parameters, and at most |p| when the field
//! is zero somewhere (the origin lies on the solid): the smallest of these
//! is an upper bound of how far the mesh is from the field's solid at the
//! tested point (a distance, not a radial difference: on steep flanks,
//! where the surface runs almost along the rays, the radial difference is
//! much larger than the distance and does not bound the Hausdorff distance
//! any better). A γ interval whose γ edge
//! midpoint deviates by more than the tolerance (in any column) is halved,
//! likewise a C interval for its C edges; an interior point splits the
//! longer side of its quad. Rounds repeat until nothing deviates or every
//! offending interval is at the minimum step.
//!
//! Between the tested points the deviation can be larger: for an error
//! that is locally quadratic (a smooth field on small triangles) the
//! largest value on a triangle is at most 4/3 of the largest edge-midpoint
//! value (the sum of the quadratic edge basis functions 4 λ_i λ_j peaks at
//! 4/3, at the centroid), and the centroid itself is tested. The tests
//! (`tests/it/adaptive_solid.rs`) measure the deviation independently, by ray
//! casting ([`super::RadialMesh`]) on dense random directions.
//!
//! Features narrower than the start grid's spacing that leave no trace at
//! any tested point can be missed: start from the data's own knots
//! ([`SolidGrid::knots`]).
//!
//! # Bounded work
//! A jump in the field (a cut-off, a spot's cone, the nearest filter) cannot
//! be met by a continuous mesh: halving an interval across it leaves the
//! deviation where it was. Refined as whole rows and columns, a jump along
//! a tilted curve would otherwise drive every row and column down to the
//! minimum step (7200 x 3600 points at 0.05°). Three bounds stop it, each
//! checked before the next grid is allocated, and each reported
//! ([`AdaptiveGrid::stop`], `reached` false, the deviation actually reached):
//! - an interval whose tested deviation stayed above [`STALL_RATIO`] of its
//!   parent's (and above twice the tolerance) on [`STALLS`] successive
//!   halvings is not halved again (a
//!   smooth field's deviation falls to about 1/4 per halving, a kink's to
//!   1/2, a jump's not at all; a feature narrower than the interval looks
//!   like a jump until the interval is narrower than it): [`Stop::Stalled`];
//! - the point budget [`AdaptiveOptions::max_points`]: [`Stop::PointLimit`];
//! - the resolution of the mesh's `f32` vertices: a tolerance under
//!   [`RESOLUTION_FLOOR`] x I_max is refined only down to that floor:
//!   [`Stop::Resolution`].

use glam::DVec3;
use rayon::prelude::*;

use super::grid::{grid_radii, quad_split, vertex, GridRadii, MAX_GRID_POINTS};
use super::mesh::p64;
use super::{SolidGrid, Units, ZERO_FRACTION};
use crate::error::ModelError;
use crate::model::frame::unit_angles;
use crate::model::{Distribution, IntensityField, Progress, ANGLE_EPS};
use crate::numfmt::PctOfPeak;
use crate::reconstruct::eval_all;

/// How far a grid solid may lie from its field, measured along the radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// Percent of the field's peak intensity on the grid (`PctOfPeak(0.1)`: 0.1 % of I_max), the
    /// one percent type the flags and settings use.
    PercentOfPeak(PctOfPeak),
    /// Candela (absolute).
    Candela(f64),
}

impl Tolerance {
    /// The tolerance in cd for a field whose peak is `peak_cd` (cd).
    pub fn candela(&self, peak_cd: f64) -> f64 {
        match *self {
            Tolerance::PercentOfPeak(p) => p.fraction() * peak_cd,
            Tolerance::Candela(cd) => cd,
        }
    }
}

impl std::fmt::Display for Tolerance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Tolerance::PercentOfPeak(p) => write!(f, "{} % of I_max", p.pct()),
            Tolerance::Candela(cd) => write!(f, "{cd} cd"),
        }
    }
}

/// Default tolerance of the `mesh` command: 0.1 % of I_max.
pub const DEFAULT_TOLERANCE_PCT: f64 = 0.1;

/// Default point budget of an adaptive grid (C x γ points): 2^21, about
/// 4 M triangles (about 100 MB of mesh). Checked before a grid is allocated.
pub const DEFAULT_MAX_POINTS: usize = 1 << 21;

/// A halving that leaves an interval's tested deviation above this fraction
/// of its parent's is a stall (see the module docs: smooth fields fall to
/// about 1/4 per halving, kinks to 1/2, jumps stay).
pub const STALL_RATIO: f64 = 0.75;

/// Successive stalled halvings after which an interval is left as it is.
pub const STALLS: u8 = 2;

/// The smallest tolerance refined for, as a fraction of I_max: 8 units in
/// the last place of the mesh's `f32` coordinates (about 9.5e-7). Below it
/// the tested deviations are rounding of the vertices, not geometry.
pub const RESOLUTION_FLOOR: f64 = 8.0 * f32::EPSILON as f64;

/// What ended an adaptive refinement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stop {
    /// Every tested point is within the tolerance.
    Reached,
    /// Every offending interval is at the minimum step.
    MinStep,
    /// Every offending interval that could still be halved kept its deviation
    /// on the last halving (a jump in the field), or is at the minimum step.
    Stalled,
    /// The next grid would exceed [`AdaptiveOptions::max_points`].
    PointLimit,
    /// The tolerance is below [`RESOLUTION_FLOOR`] x I_max, and the floor is reached.
    Resolution,
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Stop::Reached => "tolerance reached",
            Stop::MinStep => "the minimum step stopped the refinement",
            Stop::Stalled => "halving stopped reducing the deviation (a jump in the field?)",
            Stop::PointLimit => "the point budget stopped the refinement",
            Stop::Resolution => "the tolerance is below the f32 resolution of the mesh's vertices",
        })
    }
}

/// Options of [`adaptive_grid`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveOptions {
    /// Largest radial deviation of the mesh from the field at the tested points.
    pub tolerance: Tolerance,
    /// Intervals are not cut below this step (degrees). Default: 0.05°
    /// (a jump in the field, e.g. the nearest filter's, cannot be met by a
    /// continuous mesh: it is refined down to this step and reported as not reached).
    pub min_step_deg: f64,
    /// Largest number of grid points (C x γ), checked before a grid is
    /// allocated. Default: [`DEFAULT_MAX_POINTS`] (at most [`MAX_GRID_POINTS`]).
    pub max_points: usize,
}

impl Default for AdaptiveOptions {
    fn default() -> Self {
        Self {
            tolerance: Tolerance::PercentOfPeak(PctOfPeak(DEFAULT_TOLERANCE_PCT)),
            min_step_deg: 0.05,
            max_points: DEFAULT_MAX_POINTS,
        }
    }
}

impl AdaptiveOptions {
    /// Options with `tolerance` and the default limits.
    pub fn new(tolerance: Tolerance) -> Self {
        Self {
            tolerance,
            ..Self::default()
        }
    }
}

/// What [`adaptive_grid`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptiveGrid {
    /// The refined grid.
    pub grid: SolidGrid,
    /// The tolerance asked for, cd.
    pub tolerance_cd: f64,
    /// The largest deviation (cd) at the tested points of the final grid.
    pub tested_deviation_cd: f64,
    /// Whether every tested point is within the tolerance (false when the
    /// minimum step or the point limit stopped the refinement first).
    pub reached: bool,
    /// What ended the refinement ([`Stop::Reached`] exactly when `reached`).
    pub stop: Stop,
    /// Refinement rounds made.
    pub rounds: usize,
}

/// The state a solid can be built in: a grid refined a fixed number of
/// times, or adaptively (the CLI's `--factor N` and `--tolerance PCT`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Refinement {
    /// [`SolidGrid::refined`]: every measured interval cut into this many steps.
    Factor(usize),
    /// [`adaptive_grid`] from [`SolidGrid::knots`].
    Adaptive(AdaptiveOptions),
}

impl Refinement {
    /// The grid of `field`, reconstructed from `d`, under this refinement,
    /// and for an adaptive grid what the refinement found.
    pub fn grid(
        &self,
        field: &dyn IntensityField,
        d: &Distribution,
    ) -> Result<(SolidGrid, Option<AdaptiveGrid>), ModelError> {
        self.grid_with_progress(field, d, &|_, _, _| {})
    }

    /// [`Refinement::grid`], reporting each adaptive round to `progress`
    /// (see [`adaptive_grid_with_progress`]).
    pub fn grid_with_progress(
        &self,
        field: &dyn IntensityField,
        d: &Distribution,
        progress: &Progress<'_>,
    ) -> Result<(SolidGrid, Option<AdaptiveGrid>), ModelError> {
        match self {
            Refinement::Factor(f) => Ok((SolidGrid::refined(d, *f)?, None)),
            Refinement::Adaptive(o) => {
                let a = adaptive_grid_with_progress(field, &SolidGrid::knots(d)?, o, progress)?;
                Ok((a.grid.clone(), Some(a)))
            }
        }
    }

    /// The grid solid of `field` (reconstructed from `d`) in `units`, and
    /// for an adaptive grid what the refinement found.
    pub fn solid(
        &self,
        field: &dyn IntensityField,
        d: &Distribution,
        units: Units,
    ) -> Result<(super::Mesh, Option<AdaptiveGrid>), ModelError> {
        self.solid_with_progress(field, d, units, &|_, _, _| {})
    }

    /// [`Refinement::solid`], reporting each adaptive round to `progress`.
    pub fn solid_with_progress(
        &self,
        field: &dyn IntensityField,
        d: &Distribution,
        units: Units,
        progress: &Progress<'_>,
    ) -> Result<(super::Mesh, Option<AdaptiveGrid>), ModelError> {
        let (grid, found) = self.grid_with_progress(field, d, progress)?;
        Ok((super::grid_solid(field, &grid, units)?, found))
    }

    /// The γ angles (degrees) of the meridian profile of a C-independent
    /// `field` reconstructed from `d`: the refined grid's, or adaptively
    /// halved intervals of the file's γ angles until each segment's midpoint
    /// is within the tolerance of the field (see [`crate::metrics::profile`]).
    /// Returns the angles and, when adaptive, the largest tested deviation (cd).
    pub fn profile_gammas(
        &self,
        field: &dyn IntensityField,
        d: &Distribution,
    ) -> Result<(Vec<f64>, Option<f64>), ModelError> {
        let start = SolidGrid::knots(d)?;
        match self {
            Refinement::Factor(f) => Ok((SolidGrid::refined(d, *f)?.gamma_angles_deg().to_vec(), None)),
            Refinement::Adaptive(o) => {
                let (g, dev) = super::gammas::adaptive_gammas(field, start.gamma_angles_deg(), o);
                Ok((g, Some(dev)))
            }
        }
    }
}

impl SolidGrid {
    /// The start grid of an adaptive refinement: the file's full-circle
    /// planes together with C = 0, 90, 180, 270 (so no gap reaches 180°;
    /// a rotational file starts from those four), and the file's γ angles
    /// with both poles.
    pub fn knots(d: &Distribution) -> Result<Self, ModelError> {
        let mut c: Vec<f64> = d.full_planes().iter().map(|p| p.0).collect();
        for q in [0.0, 90.0, 180.0, 270.0] {
            if c.iter().all(|&x| (x - q).abs() > ANGLE_EPS) {
                c.push(q);
            }
        }
        c.sort_by(f64::total_cmp);
        SolidGrid::new(c, d.gamma_angles_deg().to_vec())
    }
}

/// Where a test point's deviation sends the refinement.
#[derive(Clone, Copy)]
enum Split {
    C(usize),
    Gamma(usize),
}

/// A round's verdict: the largest tested deviation (cd) attributed to each
/// C and γ interval, and over all.
struct Marks {
    c: Vec<f64>,
    gamma: Vec<f64>,
    worst: f64,
}

/// Refine `start` until the grid solid of `field` is within the tolerance
/// at every tested point (see the module docs), or a bound stops it.
///
/// # Errors
/// As [`grid_solid`](super::grid_solid): an all-zero field, NaN samples.
pub fn adaptive_grid(
    field: &dyn IntensityField,
    start: &SolidGrid,
    opts: &AdaptiveOptions,
) -> Result<AdaptiveGrid, ModelError> {
    adaptive_grid_with_progress(field, start, opts, &|_, _, _| {})
}

/// [`adaptive_grid`], calling `progress(points, max_points, what)` after
/// each round (`points`: the grid's C x γ points).
pub fn adaptive_grid_with_progress(
    field: &dyn IntensityField,
    start: &SolidGrid,
    opts: &AdaptiveOptions,
    progress: &Progress<'_>,
) -> Result<AdaptiveGrid, ModelError> {
    let min_step = opts.min_step_deg.max(1e-6);
    let max_points = opts.max_points.clamp(1, MAX_GRID_POINTS);
    // A C-independent field: the C planes follow from the circle's chord error alone.
    let c_fixed = crate::metrics::profile::is_c_independent(field, start.gamma_angles_deg());
    let mut grid = match c_fixed {
        true => rotational_start(field, start, opts, max_points)?,
        false => start.clone(),
    };
    // Each interval's history: its parent's deviation (∞ for the start intervals) and stalls.
    let mut c_parent = vec![History::START; grid.c_angles_deg().len()];
    let mut g_parent = vec![History::START; grid.gamma_angles_deg().len()];
    for round in 1.. {
        let radii = grid_radii(field, &grid, Units::Candela)?;
        let peak = peak_of(&grid, &radii);
        let tolerance_cd = opts.tolerance.candela(peak).max(0.0);
        let refine_cd = tolerance_cd.max(RESOLUTION_FLOOR * peak);
        let marks = test_round(field, &grid, &radii, peak, c_fixed);
        let (c_mark, c_now, c_stalled) = verdicts(&marks.c, &c_parent, refine_cd);
        let (g_mark, g_now, g_stalled) = verdicts(&marks.gamma, &g_parent, refine_cd);
        let (c, c_from, c_cut) = halve(grid.c_angles_deg(), &c_mark, min_step, Some(360.0));
        let (gamma, g_from, g_cut) = halve(grid.gamma_angles_deg(), &g_mark, min_step, None);
        let (nc, ng) = (grid.c_angles_deg().len(), grid.gamma_angles_deg().len());
        progress(
            nc * ng,
            max_points,
            &format!(
                "adaptive solid, round {round}: {nc} C x {ng} gamma, largest tested deviation {:.3e} cd \
                 (tolerance {tolerance_cd:.3e} cd)",
                marks.worst
            ),
        );
        let stop = if marks.worst <= tolerance_cd {
            Some(Stop::Reached)
        } else if marks.worst <= refine_cd {
            Some(Stop::Resolution)
        } else if !c_cut && !g_cut {
            Some(if c_stalled || g_stalled {
                Stop::Stalled
            } else {
                Stop::MinStep
            })
        } else if (c.len() as u128) * (gamma.len() as u128) > max_points as u128 {
            Some(Stop::PointLimit)
        } else {
            None
        };
        if let Some(stop) = stop {
            return Ok(AdaptiveGrid {
                grid,
                tolerance_cd,
                tested_deviation_cd: marks.worst,
                reached: stop == Stop::Reached,
                stop,
                rounds: round,
            });
        }
        c_parent = inherit(&c_from, &c_now, &c_parent);
        g_parent = inherit(&g_from, &g_now, &g_parent);
        grid = SolidGrid::new(c, gamma)?;
    }
    unreachable!("the loop returns: intervals halve down to the minimum step")
}

/// The start grid of a C-independent field: `start`'s γ angles and as many
/// evenly spaced C planes as the chord error of the widest ring needs
/// ([`rotational_planes`]), within the point budget `max_points`.
fn rotational_start(
    field: &dyn IntensityField,
    start: &SolidGrid,
    opts: &AdaptiveOptions,
    max_points: usize,
) -> Result<SolidGrid, ModelError> {
    let radii = grid_radii(field, start, Units::Candela)?;
    let peak = peak_of(start, &radii);
    let tol = opts.tolerance.candela(peak).max(RESOLUTION_FLOOR * peak);
    // Within the point budget: the chord test then reports what the planes miss.
    let most = (max_points / start.gamma_angles_deg().len()).max(4);
    SolidGrid::new(
        rotational_planes(start, &radii, tol, most),
        start.gamma_angles_deg().to_vec(),
    )
}

/// The histories of the next round's intervals (`from`: each new interval's
/// old interval and whether it was halved, as [`halve`] returns them): a half
/// remembers its parent's deviation and stalls (`now`, from [`verdicts`]); an
/// interval left whole keeps its history (`parent`).
fn inherit(from: &[(usize, bool)], now: &[History], parent: &[History]) -> Vec<History> {
    from.iter()
        .map(|&(i, cut)| if cut { now[i] } else { parent[i] })
        .collect()
}

/// An interval's refinement history.
#[derive(Clone, Copy)]
struct History {
    /// The tested deviation of the interval it was halved from (cd).
    parent_cd: f64,
    /// Successive halvings that left the deviation where it was.
    stalls: u8,
}

impl History {
    const START: History = History {
        parent_cd: f64::INFINITY,
        stalls: 0,
    };
}

/// Which intervals to halve: those deviating by more than `tol` (cd),
/// unless [`STALLS`] successive halvings each left the deviation above
/// twice the tolerance and between [`STALL_RATIO`] and 1.5 times their
/// parent's (a jump; a deviation far above the parent's is news from the
/// other axis' new points, not a stall).
/// Returns the marks, each interval's history as its halves inherit it, and
/// whether an offending interval was stopped as stalled.
fn verdicts(dev: &[f64], parent: &[History], tol: f64) -> (Vec<bool>, Vec<History>, bool) {
    let mut stalled = false;
    let (marks, now) = dev
        .iter()
        .zip(parent)
        .map(|(&d, h)| {
            // Near the tolerance the tensor product's attribution (a row's largest deviation
            // over columns that change as C is refined) can hover; a jump stands well above it.
            let stuck = d > 2.0 * tol && d > STALL_RATIO * h.parent_cd && d <= 1.5 * h.parent_cd;
            let stalls = if stuck { h.stalls.saturating_add(1) } else { 0 };
            let stop = stalls >= STALLS;
            stalled |= d > tol && stop;
            (d > tol && !stop, History { parent_cd: d, stalls })
        })
        .unzip();
    (marks, now, stalled)
}

/// Evenly spaced C planes (degrees, from 0) for a C-independent field:
/// as many as keep the chord sag of the widest ring, `ρ (1 − cos(ΔC/2))`
/// with ρ = r sin γ, within half the tolerance `tol` (cd), so that the γ
/// refinement has the other half; at least 4 (no gap of 180°), at most `most`.
fn rotational_planes(grid: &SolidGrid, r: &GridRadii, tol: f64, most: usize) -> Vec<f64> {
    let ng = grid.gamma_angles_deg().len();
    let rho = (1..ng - 1)
        .map(|ig| r.radii[ig] * grid.gamma_angles_deg()[ig].to_radians().sin())
        .fold(0.0, f64::max);
    let n = if rho > 0.0 {
        let step = 2.0 * (1.0 - 0.5 * tol / rho).clamp(-1.0, 1.0).acos();
        (std::f64::consts::TAU / step).ceil().min(most as f64) as usize
    } else {
        4
    };
    let n = n.clamp(4, most.max(4));
    (0..n).map(|k| k as f64 * 360.0 / n as f64).collect()
}

/// The largest radius of the grid (cd).
fn peak_of(grid: &SolidGrid, r: &GridRadii) -> f64 {
    let ng = grid.gamma_angles_deg().len();
    r.radii
        .chunks(ng)
        .flat_map(|col| col[1..ng - 1].iter())
        .copied()
        .fold(r.r_nadir.max(r.r_zenith), f64::max)
}

/// `angles` with every marked interval halved, unless it is under twice
/// `min_step`; `period` closes the list (C: the last interval wraps to 360).
/// Returns the angles, for each new interval the index of its interval in
/// `angles` and whether that was halved, and whether anything was cut.
fn halve(angles: &[f64], marked: &[bool], min_step: f64, period: Option<f64>) -> (Vec<f64>, Vec<(usize, bool)>, bool) {
    let n = angles.len();
    let mut out = Vec::with_capacity(2 * n);
    let mut from = Vec::with_capacity(2 * n);
    let mut cut = false;
    for i in 0..n {
        out.push(angles[i]);
        from.push((i, false));
        let next = match (i + 1 < n, period) {
            (true, _) => angles[i + 1],
            (false, Some(p)) => angles[0] + p,
            (false, None) => break,
        };
        if marked[i] && next - angles[i] >= 2.0 * min_step {
            let mid = 0.5 * (angles[i] + next);
            // The midpoint of the wrapping interval may equal 360 in floating point.
            if mid < period.unwrap_or(f64::INFINITY) {
                out.push(mid);
                from.push((i, true));
                if let Some(last) = from.len().checked_sub(2) {
                    from[last].1 = true;
                }
                cut = true;
            }
        }
    }
    (out, from, cut)
}

/// A test point of one round: where on the grid solid it lies, the (C, γ)
/// of the grid's parameters it sits at (the direction to test when the
/// point is the origin), and the interval it would split.
type TestPoint = (DVec3, (f64, f64), Split);

/// The grid solid's vertices as `grid_solid` builds them, for placing the
/// test points on its quads.
struct GridVertices<'a> {
    cs: &'a [f64],
    gs: &'a [f64],
    /// (sin, cos) of each C and γ.
    sc: Vec<(f64, f64)>,
    sg: Vec<(f64, f64)>,
    r: &'a GridRadii,
}

impl<'a> GridVertices<'a> {
    /// Vertex ids as grid_solid assigns them, up to renumbering: the origin,
    /// the two poles, and one per inner grid point.
    const ORIGIN: u32 = u32::MAX;

    fn new(grid: &'a SolidGrid, r: &'a GridRadii) -> Self {
        let (cs, gs) = (grid.c_angles_deg(), grid.gamma_angles_deg());
        GridVertices {
            cs,
            gs,
            sc: cs.iter().map(|c| c.to_radians().sin_cos()).collect(),
            sg: gs.iter().map(|g| g.to_radians().sin_cos()).collect(),
            r,
        }
    }

    /// The vertex at grid point (`ic`, `ig`) and its id.
    fn point(&self, ic: usize, ig: usize) -> ([f32; 3], u32) {
        let (r, ng) = (self.r, self.gs.len());
        let rad = if ig == 0 {
            r.r_nadir
        } else if ig == ng - 1 {
            r.r_zenith
        } else {
            r.radii[ic * ng + ig]
        };
        if rad == 0.0 {
            return ([0.0; 3], Self::ORIGIN);
        }
        if ig == 0 || ig == ng - 1 {
            let cg = if ig == 0 { 1.0 } else { -1.0 };
            return (vertex(rad, 0.0, cg, 0.0, 1.0), if ig == 0 { 0 } else { 1 });
        }
        let (sg, sc) = (self.sg[ig], self.sc[ic]);
        (vertex(rad, sg.0, sg.1, sc.0, sc.1), (2 + ic * ng + ig) as u32)
    }

    /// The middle C of interval `ic` (the last one wraps to 360°).
    fn mid_c(&self, ic: usize) -> f64 {
        let cs = self.cs;
        let next = if ic + 1 == cs.len() { cs[0] + 360.0 } else { cs[ic + 1] };
        0.5 * (cs[ic] + next)
    }

    /// The test points of column `ic`'s quads: each γ edge's and C edge's
    /// midpoint, the shared diagonal's midpoint and each triangle's centroid.
    fn column_tests(&self, ic: usize) -> Vec<TestPoint> {
        let (cs, gs) = (self.cs, self.gs);
        let (nc, ng) = (cs.len(), gs.len());
        let ic1 = if ic + 1 == nc { 0 } else { ic + 1 };
        let mut out = Vec::with_capacity(6 * ng);
        for ig in 0..ng - 1 {
            let q = [
                self.point(ic, ig),
                self.point(ic1, ig),
                self.point(ic1, ig + 1),
                self.point(ic, ig + 1),
            ];
            let corners = q.map(|x| x.0);
            let ids = q.map(|x| x.1);
            let p = corners.map(|x| p64(&x));
            let gm = 0.5 * (gs[ig] + gs[ig + 1]);
            // γ edge (C_ic, γ_ig)–(C_ic, γ_ig+1).
            out.push((0.5 * (p[0] + p[3]), (cs[ic], gm), Split::Gamma(ig)));
            // C edge (C_ic, γ_ig)–(C_ic+1, γ_ig), not at a pole.
            if ig > 0 {
                out.push((0.5 * (p[0] + p[1]), (self.mid_c(ic), gs[ig]), Split::C(ic)));
            }
            let longer = if p[0].distance(p[1]).max(p[3].distance(p[2])) >= p[0].distance(p[3]).max(p[1].distance(p[2]))
            {
                Split::C(ic)
            } else {
                Split::Gamma(ig)
            };
            let centre = (self.mid_c(ic), gm);
            let tris = quad_split(&corners, &ids);
            if let (Some(a), Some(b)) = (tris[0], tris[1]) {
                // The shared diagonal's midpoint.
                let shared: Vec<usize> = a.iter().copied().filter(|k| b.contains(k)).collect();
                if shared.len() == 2 {
                    out.push((0.5 * (p[shared[0]] + p[shared[1]]), centre, longer));
                }
            }
            for t in tris.into_iter().flatten() {
                out.push(((p[t[0]] + p[t[1]] + p[t[2]]) / 3.0, centre, longer));
            }
        }
        out
    }
}

/// Test every quad of `grid` (see the module docs): the largest deviation
/// per interval. With `c_fixed` (a C-independent field: every column alike)
/// only the first column is tested, and its worst C interval stands for all.
fn test_round(field: &dyn IntensityField, grid: &SolidGrid, r: &GridRadii, peak: f64, c_fixed: bool) -> Marks {
    let (nc, ng) = (grid.c_angles_deg().len(), grid.gamma_angles_deg().len());
    let vertices = GridVertices::new(grid, r);
    let columns = if c_fixed { 1 } else { nc };
    let tests: Vec<TestPoint> = (0..columns)
        .into_par_iter()
        .flat_map_iter(|ic| vertices.column_tests(ic))
        .collect();
    let mut marks = Marks {
        c: vec![0.0; nc],
        gamma: vec![0.0; ng],
        worst: 0.0,
    };
    for ((_, _, split), dev) in tests.iter().zip(deviations(field, &tests, r.any_zero, peak)) {
        marks.worst = marks.worst.max(dev);
        let slot = match *split {
            Split::C(i) => &mut marks.c[i],
            Split::Gamma(i) => &mut marks.gamma[i],
        };
        *slot = slot.max(dev);
    }
    if c_fixed {
        // Every column is alike: refine all of them together, the planes stay evenly spaced.
        let worst_c = marks.c.iter().copied().fold(0.0, f64::max);
        marks.c.fill(worst_c);
    }
    marks
}

/// Each test point's deviation from the field's solid (cd): the radial gap
/// in its own direction, or the distance to the surface point at its
/// parameter midpoint when that is smaller. `any_zero`: the field is zero
/// somewhere (the origin is then a point of its solid); `peak` sets the
/// level below which a value counts as zero.
fn deviations(field: &dyn IntensityField, tests: &[TestPoint], any_zero: bool, peak: f64) -> Vec<f64> {
    // Per point work (an atan2, an acos, a sincos) in parallel: serial, it was a tenth of
    // `compare`'s CPU time on 8.IES while the other cores waited (BENCHMARKS.md).
    let dirs: Vec<(f64, f64)> = tests
        .par_iter()
        .map(|(p, fallback, _)| match p.try_normalize() {
            Some(u) => unit_angles(u),
            None => *fallback,
        })
        .collect();
    let values = eval_all(field, &dirs);
    // The surface point at the parameter midpoint: a second candidate nearest point.
    let params: Vec<(f64, f64)> = tests.iter().map(|t| t.1).collect();
    let at_params = eval_all(field, &params);
    let zero = (f32::MIN_POSITIVE as f64).max(ZERO_FRACTION * peak);
    let clean = |v: f64| if v < zero || v.is_nan() { 0.0 } else { v };
    tests
        .par_iter()
        .zip(values)
        .zip(at_params)
        .map(|(((p, (c, g), _), v), vm)| {
            let v = clean(v);
            let beside = p.distance(clean(vm) * crate::model::frame::direction(*c, *g));
            // Where the field is zero somewhere the origin is a point of its solid, so |p| bounds
            // the distance too: it is the smaller bound on the fans to the origin, whose edges run
            // along rays (a point halfway to a vertex is |p| away along its ray, yet beside the surface).
            match any_zero {
                true => (p.length() - v).abs().min(p.length()),
                false => (p.length() - v).abs(),
            }
            .min(beside)
        })
        .collect()
}

/// The largest distance (cd) from the field's solid to `mesh`, sampled at
/// `n` random directions (seeded): the solid's points `I(ω) ω` and their
/// exact distances to the mesh's triangles (a BVH). The independent check
/// of an adaptive solid in the sense that matters for Hausdorff distances
/// (h(solid → mesh)).
pub fn surface_distance(field: &dyn IntensityField, mesh: &super::Mesh, n: usize, seed: u64) -> f64 {
    let dirs = crate::metrics::random_directions(n, seed);
    let angles: Vec<(f64, f64)> = dirs.iter().map(|&u| unit_angles(u)).collect();
    let values = eval_all(field, &angles);
    let scale = mesh.info().units_per_cd;
    let points: Vec<DVec3> = dirs
        .iter()
        .zip(&values)
        .map(|(&u, &v)| v.max(0.0) * scale * u)
        .collect();
    let bvh = crate::metrics::Bvh::build_owned(mesh.positions_f64(), mesh.triangles());
    crate::metrics::hausdorff::distances(&points, &bvh)
        .into_iter()
        .fold(0.0, f64::max)
        / scale
}

/// The largest radial deviation (cd) of `mesh` from `field` over `n`
/// random directions (seeded), by ray casting into the mesh
/// ([`super::RadialMesh`]): the independent check of an adaptive solid.
pub fn radial_deviation(field: &dyn IntensityField, mesh: &super::Mesh, n: usize, seed: u64) -> f64 {
    let rm = super::RadialMesh::new(mesh);
    let dirs = crate::metrics::random_directions(n, seed);
    let angles: Vec<(f64, f64)> = dirs.iter().map(|&u| unit_angles(u)).collect();
    let values = eval_all(field, &angles);
    let scale = mesh.info().units_per_cd;
    dirs.par_iter()
        .zip(values.par_iter())
        .map(|(&u, &v)| (rm.radius(u) - v * scale).abs())
        .reduce(|| 0.0, f64::max)
        / scale
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halving_wraps_c_and_stops_at_the_minimum_step() {
        let (c, from, cut) = halve(
            &[0.0, 90.0, 180.0, 270.0],
            &[false, true, false, true],
            1.0,
            Some(360.0),
        );
        assert!(cut);
        assert_eq!(c, vec![0.0, 90.0, 135.0, 180.0, 270.0, 315.0]);
        assert_eq!(
            from,
            vec![(0, false), (1, true), (1, true), (2, false), (3, true), (3, true)]
        );
        let (g, _, cut) = halve(&[0.0, 1.5, 180.0], &[true, false], 1.0, None);
        assert!(!cut);
        assert_eq!(g, vec![0.0, 1.5, 180.0]);
    }

    #[test]
    fn a_sphere_needs_the_chord_error_planes() {
        // Isotropic 1000 cd: only C (and γ) chords deviate; r (1 − cos(Δ/2)) ≤ 1 cd needs Δ ≤ 5.1°.
        let field = |_c: f64, _g: f64| 1000.0;
        let start = SolidGrid::new(vec![0.0, 90.0, 180.0, 270.0], vec![0.0, 90.0, 180.0]).unwrap();
        let a = adaptive_grid(&field, &start, &AdaptiveOptions::new(Tolerance::Candela(1.0))).unwrap();
        assert!(a.reached, "{a:?}");
        let widest = 2.0 * (1.0 - 1.0 / 1000.0f64).acos().to_degrees();
        let step = 360.0 / a.grid.c_angles_deg().len() as f64;
        assert!(step <= widest && step > widest / 2.0, "{step} vs {widest}");
    }
}
