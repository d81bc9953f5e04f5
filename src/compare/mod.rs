//! Compare photometric solids: how wrong is each reconstruction, where, and what does it cost.
//!
//! Between any two of: the measured solid, each filter's reconstruction, the
//! fitted OpenGL lights, another file's distribution (Ashdown 1999, DOMAIN §6):
//! - the **Hausdorff distance** of the photometric solids (symmetric and both
//!   one-sided, with mean and RMS surface distance), certified to within a
//!   tolerance ([`crate::metrics::hausdorff`]): "H = 12.31 cd (+0.05)";
//! - the **radial errors** over a stated direction set
//!   ([`crate::metrics::radial_errors`]); their maximum is the cheap radial
//!   bound of H (max over directions of |I1 − I2| ≥ H, estimated on the set);
//! - the **time per sample** of evaluating the reconstruction.
//!
//! # What is compared with what
//! - One file: each reconstruction of FILE against the reference `against`
//!   of FILE (default: its measured solid).
//! - `vs` OTHER: each reconstruction of FILE (default list starts with FILE's
//!   measured solid) against the reference `against` of OTHER (default:
//!   OTHER's measured solid), FILE optionally aligned first ([`align`]).
//!
//! Solids: the measured solid is [`crate::solid::measured_solid`] (Delaunay
//! of the measured directions); the others are grid solids on
//! [`SolidGrid::refined`]`(d, factor)`. As a field (radial metrics, plots),
//! "measured" is the radial function of the measured solid (exact at the
//! measured directions, linear on its triangles). The radial bound
//! `radial_bound_cd` is max |r_A(ω) − r_B(ω)| over the direction set of the
//! two *meshes'* radial functions (ray cast), so it bounds the meshes'
//! Hausdorff distance up to the set's density.
//!
//! # Normalisation
//! Each distribution is scaled before anything is built: `cd` (none),
//! `peak` (its own I_max = 1) or `klm` (cd/klm, 1000 I / Φ with its own
//! flux). Every length (`*_cd` keys) is in that unit; `units` says which.

pub mod align;
pub mod raycast;
pub mod recon;

use std::str::FromStr;

use serde::Serialize;

pub use align::{best_alignment, Alignment};
pub use raycast::RadialMesh;
pub use recon::{Prepared, Recon, DEFAULT_RECONS};

use crate::error::ModelError;
use crate::metrics::{hausdorff, radial_errors, DirectionSet, Hausdorff, MeshRef, OneSided, ZOTTI_C};
use crate::model::Distribution;
use crate::solid::Mesh;

/// How the distributions are scaled before comparing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Normalize {
    /// Absolute candela.
    #[default]
    Cd,
    /// I_max = 1 (each distribution by its own peak).
    Peak,
    /// cd/klm as in EULUMDAT and lighting practice: candela per 1000 lm of
    /// *lamp* flux (each distribution by its file's declared lamp flux,
    /// [`CompareOptions::lamp_flux_lm`]). Does not apply to absolute photometry.
    Klm,
    /// Equal flux: each distribution divided by its own computed luminaire
    /// flux (x 1000: cd per 1000 lm of luminaire flux).
    Flux,
}

impl Normalize {
    /// The scale factor of `d`, whose file declares the lamp flux
    /// `lamp_flux_lm` (lm; `None` for absolute photometry).
    pub fn factor(self, d: &Distribution, lamp_flux_lm: Option<f64>) -> Result<f64, ModelError> {
        let k = match self {
            Normalize::Cd => 1.0,
            Normalize::Peak => 1.0 / d.max_cd(),
            Normalize::Klm => match lamp_flux_lm {
                Some(lm) => 1000.0 / lm,
                None => {
                    return Err(ModelError::Parameter {
                        name: "normalize",
                        value: "klm".into(),
                        reason: "cd/klm is per 1000 lm of lamp flux, and this file has absolute photometry (no \
                                 lamp flux); use --normalize flux (equal luminaire flux) or peak"
                            .into(),
                    })
                }
            },
            Normalize::Flux => 1000.0 / crate::photometry::flux(d).total_lm,
        };
        if k.is_finite() && k > 0.0 {
            Ok(k)
        } else {
            Err(ModelError::AllZero("normalisation needs a positive peak and flux"))
        }
    }
    /// The unit of lengths after scaling.
    pub fn unit(self) -> &'static str {
        match self {
            Normalize::Cd => "cd",
            Normalize::Peak => "I/I_max",
            Normalize::Klm => "cd/klm",
            Normalize::Flux => "cd/klm of luminaire flux",
        }
    }
}

impl FromStr for Normalize {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "cd" => Ok(Normalize::Cd),
            "peak" => Ok(Normalize::Peak),
            "klm" => Ok(Normalize::Klm),
            "flux" => Ok(Normalize::Flux),
            _ => Err(ModelError::Parameter {
                name: "normalize",
                value: s.into(),
                reason: "expected cd, peak, klm (lamp flux) or flux (equal luminaire flux)".into(),
            }),
        }
    }
}

/// The direction set of the radial metrics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Directions {
    /// The measured directions of the reference distribution.
    Measured,
    /// A spherical Fibonacci lattice of N directions.
    Dense(usize),
}

impl Default for Directions {
    fn default() -> Self {
        Directions::Dense(20_000)
    }
}

impl FromStr for Directions {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || ModelError::Parameter {
            name: "directions",
            value: s.into(),
            reason: "expected measured, dense or dense:N (N ≥ 100)".into(),
        };
        match s {
            "measured" => Ok(Directions::Measured),
            "dense" => Ok(Directions::default()),
            _ => match s.strip_prefix("dense:").map(str::parse::<usize>) {
                Some(Ok(n)) if n >= 100 => Ok(Directions::Dense(n)),
                _ => Err(bad()),
            },
        }
    }
}

/// Options of [`compare`].
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// Reconstructions of FILE to compare. Default: [`DEFAULT_RECONS`] (with `vs`, `measured` first).
    pub recons: Vec<Recon>,
    /// The reference (of FILE, or of OTHER with `vs`). Default: measured.
    pub against: Recon,
    /// Scaling. Default: cd.
    pub normalize: Normalize,
    /// Declared lamp flux (lm) of FILE and of OTHER, `None` for absolute
    /// photometry: what [`Normalize::Klm`] divides by. Default: none.
    pub lamp_flux_lm: [Option<f64>; 2],
    /// Direction set of the radial metrics. Default: dense 20000.
    pub directions: Directions,
    /// Hausdorff tolerance as a fraction of the reference I_max. Default: 0.001 (0.1 %).
    pub tolerance: f64,
    /// Refinement factor of the grid solids. Default: 3.
    pub factor: usize,
    /// Search the best C rotation and mirror of FILE onto OTHER (only with `vs`).
    pub align: bool,
    /// Zotti's constant C, fraction of I_max. Default: [`ZOTTI_C`].
    pub zotti_c: f64,
    /// Directions timed per reconstruction. Default: 20000.
    pub timing_samples: usize,
    /// Timing repeats (median). Default: 5.
    pub timing_repeats: usize,
    /// Compute the data of the report's plots. Default: false.
    pub plots: bool,
}

impl Default for CompareOptions {
    fn default() -> Self {
        Self {
            recons: DEFAULT_RECONS.to_vec(),
            against: Recon::Measured,
            normalize: Normalize::Cd,
            lamp_flux_lm: [None, None],
            directions: Directions::default(),
            tolerance: 1e-3,
            factor: 3,
            align: false,
            zotti_c: ZOTTI_C,
            timing_samples: 20_000,
            timing_repeats: 5,
            plots: false,
        }
    }
}

/// The metrics of one reconstruction against the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReconResult {
    /// The reconstruction (`measured`, a filter name, `fitted-gl`).
    pub name: String,
    /// Symmetric Hausdorff distance H (attained), in `units`.
    pub hausdorff_cd: f64,
    /// Certified gap: H ≤ hausdorff_cd + hausdorff_bound_cd.
    pub hausdorff_bound_cd: f64,
    /// H as % of the reference I_max.
    pub hausdorff_pct: f64,
    /// One-sided h(reconstruction → reference): value, bound, mean, rms, queries.
    pub recon_to_ref: OneSided,
    /// One-sided h(reference → reconstruction).
    pub ref_to_recon: OneSided,
    /// Mean surface distance (mean of the two one-sided area-weighted means).
    pub mean_surface_distance_cd: f64,
    /// RMS surface distance (both directions pooled).
    pub rms_surface_distance_cd: f64,
    /// The radial bound: max |r_recon(ω) − r_ref(ω)| of the two solids (meshes, ray cast) over the direction set (≥ H up to the set's density).
    pub radial_bound_cd: f64,
    /// Largest radial difference of the fields, in `units`.
    pub radial_max_cd: f64,
    /// Largest radial difference of the fields, % of the reference I_max.
    pub radial_max_pct: f64,
    /// Where it is, (C, γ) degrees.
    pub radial_max_at_deg: (f64, f64),
    /// Solid-angle-weighted RMS radial difference, in `units`.
    pub radial_rms_cd: f64,
    /// The same, % of the reference I_max.
    pub radial_rms_pct: f64,
    /// Zotti's relative error (unweighted, constant `zotti_c`).
    pub zotti_err: f64,
    /// Zotti's relative error, solid-angle weighted.
    pub zotti_err_solid_angle: f64,
    /// Flux difference over the direction set, % of the reference flux.
    pub flux_error_pct: f64,
    /// Misplaced-flux fraction, in [0, 2].
    pub misplaced_flux: f64,
    /// Median time (ns) per sample of evaluating the reconstruction (one thread); null for `measured`.
    pub time_per_sample_ns: Option<f64>,
    /// Triangles of the reconstruction's solid.
    pub triangles: usize,
    /// On the speed/accuracy Pareto front (time per sample vs H).
    pub pareto: bool,
}

/// Curves of one pair of half-planes for a polar diagram: points are (signed γ, value).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PolarPlane {
    /// C of the half-plane drawn with negative γ.
    pub left_c: f64,
    /// C of the half-plane drawn with positive γ.
    pub right_c: f64,
    /// `(name, points)` of each reconstruction (and the reference field when it is not the measured data).
    pub curves: Vec<(String, Vec<(f64, f64)>)>,
    /// `(label, points)` of measured data (the reference's; with `vs`, FILE's too).
    pub measured: Vec<(String, Vec<(f64, f64)>)>,
}

/// Signed error of one reconstruction over C x γ, % of I_max: `values[iy * xs.len() + ix]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorMap {
    /// The reconstruction.
    pub name: String,
    /// C angles, degrees.
    pub xs: Vec<f64>,
    /// γ angles, degrees.
    pub ys: Vec<f64>,
    /// (recon − reference) / I_max · 100.
    pub values: Vec<f64>,
}

/// What the report draws.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct PlotData {
    /// C0-C180, C90-C270, and the plane of maximum intensity.
    pub planes: Vec<PolarPlane>,
    /// One per reconstruction.
    pub error_maps: Vec<ErrorMap>,
}

/// The result of [`compare`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// FILE (set by the caller; empty by default).
    pub file: String,
    /// OTHER, with `vs`.
    pub vs: Option<String>,
    /// The reference, e.g. `measured` or `catmull-rom (OTHER)`.
    pub reference: String,
    /// Normalisation.
    pub normalize: Normalize,
    /// Unit of every `*_cd` value.
    pub units: String,
    /// Direction set of the radial metrics, e.g. `fibonacci 20000`.
    pub directions: String,
    /// Its size.
    pub n_directions: usize,
    /// Hausdorff tolerance, fraction of I_max.
    pub tolerance: f64,
    /// The same in `units`.
    pub tolerance_cd: f64,
    /// Grid solid refinement factor.
    pub factor: usize,
    /// Reference I_max, in `units`.
    pub i_max_cd: f64,
    /// Triangles of the reference solid.
    pub reference_triangles: usize,
    /// Zotti's constant C, fraction of I_max.
    pub zotti_c: f64,
    /// The alignment applied to FILE (with `vs` and `align`).
    pub alignment: Option<Alignment>,
    /// One per reconstruction.
    pub results: Vec<ReconResult>,
    /// Plot data (with `plots`), not in the JSON.
    #[serde(skip)]
    pub plots: Option<PlotData>,
}

/// Symmetric Hausdorff distance between two solids (f32 positions widened to f64).
pub fn solid_hausdorff(a: &Mesh, b: &Mesh, tolerance: f64) -> Hausdorff {
    let pa: Vec<[f64; 3]> = a.positions().iter().map(|p| p.map(f64::from)).collect();
    let pb: Vec<[f64; 3]> = b.positions().iter().map(|p| p.map(f64::from)).collect();
    hausdorff(
        MeshRef {
            positions: &pa,
            triangles: a.triangles(),
        },
        MeshRef {
            positions: &pb,
            triangles: b.triangles(),
        },
        tolerance,
    )
}

/// The polygon sag of a mesh whose vertices lie on the sphere (`centre`, `radius`):
/// the largest distance between a triangle's plane region and the sphere,
/// `max_t (radius − sqrt(radius² − ρ_t²))` with ρ_t the triangle's circumradius
/// (half the longest edge for degenerate triangles). Each point of the mesh is
/// within it of the sphere and each point of the sphere within it of the
/// mesh (for a closed mesh around the centre), so H(mesh, sphere) ≤ sag.
pub fn sphere_sag(mesh: &Mesh, centre: [f64; 3], radius: f64) -> f64 {
    let p = mesh.positions();
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let norm = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let _ = centre;
    mesh.triangles()
        .iter()
        .map(|t| {
            let v = t.map(|i| p[i as usize].map(f64::from));
            let (a, b, c) = (norm(sub(v[1], v[2])), norm(sub(v[2], v[0])), norm(sub(v[0], v[1])));
            let u = sub(v[1], v[0]);
            let w = sub(v[2], v[0]);
            let cr = [
                u[1] * w[2] - u[2] * w[1],
                u[2] * w[0] - u[0] * w[2],
                u[0] * w[1] - u[1] * w[0],
            ];
            let area2 = norm(cr);
            let longest = a.max(b).max(c);
            let rho = if area2 > 1e-12 * longest * longest {
                a * b * c / (2.0 * area2)
            } else {
                0.5 * longest
            };
            let rho = rho.min(radius);
            radius - (radius * radius - rho * rho).sqrt()
        })
        .fold(0.0, f64::max)
}

/// Compare the reconstructions of `file` with the reference (see the module docs).
///
/// # Errors
/// All-zero data, unknown grids, a failed fit, or `against` = measured
/// with a distribution whose measured solid cannot be built.
pub fn compare(
    file: &Distribution,
    vs: Option<&Distribution>,
    opts: &CompareOptions,
) -> Result<Comparison, ModelError> {
    let mut a = file.scaled(opts.normalize.factor(file, opts.lamp_flux_lm[0])?)?;
    let b_dist = match vs {
        Some(o) => Some(o.scaled(opts.normalize.factor(o, opts.lamp_flux_lm[1])?)?),
        None => None,
    };
    let mut alignment = None;
    if let (true, Some(b)) = (opts.align, &b_dist) {
        let al = best_alignment(&a, b, 4000)?;
        if al.rotate_deg != 0.0 || al.mirror {
            a = a.reoriented(al.rotate_deg, al.mirror)?;
        }
        alignment = Some(al);
    }
    let needs_fit = |r: Recon| r == Recon::FittedGl;
    let recons: Vec<Recon> = if vs.is_some() {
        opts.recons.clone()
    } else {
        opts.recons.iter().copied().filter(|r| *r != opts.against).collect()
    };
    let pa = Prepared::new(
        a,
        recons.iter().any(|r| needs_fit(*r)) || (vs.is_none() && needs_fit(opts.against)),
    )?;
    let pb = match b_dist {
        Some(b) => Some(Prepared::new(b, needs_fit(opts.against))?),
        None => None,
    };
    let refp = pb.as_ref().unwrap_or(&pa);
    let reference = if vs.is_some() {
        format!("{} (OTHER)", opts.against)
    } else {
        opts.against.to_string()
    };
    let ref_solid = refp.solid(opts.against, opts.factor)?;
    let ref_rm = RadialMesh::new(&ref_solid);
    let i_max = refp.dist.max_cd();
    let tol = opts.tolerance.max(0.0) * i_max;
    let set = match opts.directions {
        Directions::Measured => DirectionSet::measured(&refp.dist),
        Directions::Dense(n) => DirectionSet::fibonacci(n),
    };
    let m = refp.eval_all(opts.against, &set.directions);
    let timing = DirectionSet::fibonacci(opts.timing_samples.max(1)).directions;
    let mut results = Vec::with_capacity(recons.len());
    for &r in &recons {
        let solid = pa.solid(r, opts.factor)?;
        let h = solid_hausdorff(&solid, &ref_solid, tol);
        let av = pa.eval_all(r, &set.directions);
        let rad = radial_errors(&set, &m, &av, i_max, opts.zotti_c);
        let (ab, ba) = (h.a_to_b, h.b_to_a);
        results.push(ReconResult {
            name: r.to_string(),
            hausdorff_cd: h.value,
            hausdorff_bound_cd: h.bound,
            hausdorff_pct: 100.0 * h.value / i_max,
            recon_to_ref: ab,
            ref_to_recon: ba,
            mean_surface_distance_cd: 0.5 * (ab.mean + ba.mean),
            rms_surface_distance_cd: (0.5 * (ab.rms * ab.rms + ba.rms * ba.rms)).sqrt(),
            radial_bound_cd: radial_bound(&RadialMesh::new(&solid), &ref_rm, &set.directions),
            radial_max_cd: rad.max_abs_cd,
            radial_max_pct: rad.max_pct,
            radial_max_at_deg: rad.max_at_deg,
            radial_rms_cd: rad.rms_cd,
            radial_rms_pct: rad.rms_pct,
            zotti_err: rad.zotti_err,
            zotti_err_solid_angle: rad.zotti_err_solid_angle,
            flux_error_pct: rad.flux_error_pct,
            misplaced_flux: rad.misplaced_flux,
            time_per_sample_ns: pa.time_per_sample_ns(r, &timing, opts.timing_repeats),
            triangles: solid.n_triangles(),
            pareto: false,
        });
    }
    mark_pareto(&mut results);
    let plots = if opts.plots {
        Some(plot_data(&pa, refp, vs.is_some(), &recons, opts.against, i_max))
    } else {
        None
    };
    Ok(Comparison {
        file: String::new(),
        vs: None,
        reference,
        normalize: opts.normalize,
        units: opts.normalize.unit().into(),
        directions: set.label.clone(),
        n_directions: set.len(),
        tolerance: opts.tolerance,
        tolerance_cd: tol,
        factor: opts.factor,
        i_max_cd: i_max,
        reference_triangles: ref_solid.n_triangles(),
        zotti_c: opts.zotti_c,
        alignment,
        results,
        plots,
    })
}

/// max over `dirs` of |r_a − r_b|.
fn radial_bound(a: &RadialMesh, b: &RadialMesh, dirs: &[(f64, f64)]) -> f64 {
    use rayon::prelude::*;
    dirs.par_iter()
        .map(|&(c, g)| {
            let w = raycast::direction(c, g);
            (a.radius(w) - b.radius(w)).abs()
        })
        .reduce(|| 0.0, f64::max)
}

/// Mark the rows no other timed row beats in both time and H.
fn mark_pareto(rows: &mut [ReconResult]) {
    let key: Vec<Option<(f64, f64)>> = rows
        .iter()
        .map(|r| r.time_per_sample_ns.map(|t| (t, r.hausdorff_cd)))
        .collect();
    for (i, r) in rows.iter_mut().enumerate() {
        r.pareto = match key[i] {
            None => false,
            Some((t, h)) => !key
                .iter()
                .flatten()
                .any(|&(t2, h2)| t2 <= t && h2 <= h && (t2 < t || h2 < h)),
        };
    }
}

fn plot_data(pa: &Prepared, refp: &Prepared, vs: bool, recons: &[Recon], against: Recon, i_max: f64) -> PlotData {
    // The plane of maximum intensity of the reference.
    let d = &refp.dist;
    let ng = d.n_gamma();
    let (mut best, mut c_max) = (f64::NEG_INFINITY, 0.0);
    for (c, ic) in d.full_planes() {
        for ig in 0..ng {
            if d.value(ic, ig) > best {
                best = d.value(ic, ig);
                c_max = c;
            }
        }
    }
    let gammas: Vec<f64> = (0..=360).map(|k| k as f64 * 0.5).collect();
    let curve = |p: &Prepared, r: Recon, right: f64, left: f64| -> Vec<(f64, f64)> {
        let mut pts: Vec<(f64, f64)> = gammas.iter().rev().map(|&g| (-g, p.eval(r, left, g))).collect();
        pts.extend(gammas.iter().skip(1).map(|&g| (g, p.eval(r, right, g))));
        pts
    };
    let points = |p: &Prepared, right: f64, left: f64| -> Vec<(f64, f64)> {
        let g = p.dist.gamma_angles();
        let (r, l) = (
            crate::photometry::plane_profile(&p.dist, right),
            crate::photometry::plane_profile(&p.dist, left),
        );
        let mut pts: Vec<(f64, f64)> = g.iter().zip(&l).rev().map(|(&g, &v)| (-g, v)).collect();
        pts.extend(g.iter().zip(&r).filter(|(&g, _)| g > 0.0).map(|(&g, &v)| (g, v)));
        pts
    };
    let pairs = [
        (0.0, 180.0),
        (90.0, 270.0),
        (c_max, crate::model::wrap360(c_max + 180.0)),
    ];
    let planes = pairs
        .iter()
        .map(|&(right, left)| {
            let mut curves: Vec<(String, Vec<(f64, f64)>)> = recons
                .iter()
                .map(|&r| (r.to_string(), curve(pa, r, right, left)))
                .collect();
            if against != Recon::Measured {
                curves.push((format!("{against} (reference)"), curve(refp, against, right, left)));
            }
            let mut measured = vec![(
                if vs {
                    "measured (OTHER)".to_string()
                } else {
                    "measured".to_string()
                },
                points(refp, right, left),
            )];
            if vs {
                measured.push(("measured (FILE)".into(), points(pa, right, left)));
            }
            PolarPlane {
                left_c: left,
                right_c: right,
                curves,
                measured,
            }
        })
        .collect();
    // Cell centres of a 2° x 1° grid: between the knots of the usual
    // measurement grids, where reconstructions differ (at a knot every
    // interpolating filter equals the measurement).
    let xs: Vec<f64> = (0..180).map(|k| 1.0 + k as f64 * 2.0).collect();
    let ys: Vec<f64> = (0..180).map(|k| 0.5 + k as f64).collect();
    let dirs: Vec<(f64, f64)> = ys.iter().flat_map(|&g| xs.iter().map(move |&c| (c, g))).collect();
    let m = refp.eval_all(against, &dirs);
    let error_maps = recons
        .iter()
        .map(|&r| {
            let v = pa.eval_all(r, &dirs);
            ErrorMap {
                name: r.to_string(),
                xs: xs.clone(),
                ys: ys.clone(),
                values: v.iter().zip(&m).map(|(a, b)| 100.0 * (a - b) / i_max).collect(),
            }
        })
        .collect();
    PlotData { planes, error_maps }
}
