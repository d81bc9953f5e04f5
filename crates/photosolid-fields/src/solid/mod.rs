//! Photometric solids as triangle meshes: the surface { I(d) d : |d| = 1 }.
//!
//! Two builders make one [`Mesh`] type:
//! - [`grid_solid`]: any reconstruction (a filter on the measured data, a
//!   rendered texture, a fitted model), given as an [`IntensityField`](crate::model::IntensityField) and
//!   sampled on a C x γ [`SolidGrid`];
//! - [`measured_solid`]: the measured directions of a [`Distribution`]
//!   alone, no interpolation, triangulated by Delaunay triangulation
//!   (crate `spade`): the "measured" reference of the comparison work.
//!
//! Exports ([`export`]): OBJ, binary PLY, binary STL and binary glTF, written
//! atomically. Quantities: [`Mesh::volume`], [`Mesh::area`]. Invariants:
//! [`Mesh::sanity_check`]; [`check_measured`] is the corpus test in one call.
//!
//! # Frame and units
//! Coordinates are in the luminaire frame (z up, nadir −z, C0 = +x, C90 = +y;
//! docs/domain.md §3.1) and in [`Units`]: candela by default (1 unit of length = 1 cd),
//! or relative to the peak (I_max = 1), or cd/klm (1000 I / Φ). The units are
//! written into every file's metadata.
//!
//! # Zero-intensity regions: topology
//! Where the intensity is zero (hemisphere data, cut-offs, unmeasured γ
//! ranges, all-zero planes) the surface passes through the origin. Every
//! zero-valued sample becomes one **merged origin vertex**
//! ([`Mesh::origin_vertex`]); triangles that collapse (two corners at the
//! origin) are dropped, so no zero-area triangle is left, and the remaining
//! triangles fan around the origin. The result is still a closed, consistently
//! oriented surface (every directed edge matched by its opposite), but the
//! origin may be a **pinch point** where several sheets meet (e.g. a downward
//! and an upward lobe with a dark band between them). Splitting the origin
//! into one copy per sheet gives a union of topological spheres; that is what
//! [`Mesh::sanity_check`] verifies. Its normal is the mean of the adjacent
//! face normals (never NaN). A solid with no zero sample is one sphere with
//! no origin vertex. An all-zero distribution has no solid: the builders
//! return [`ModelError::AllZero`].

//! # Example (what `photosolid mesh` does)
//! `photosolid mesh FILE [--filter F | --measured] [--tolerance 0.1% | --factor K] [--units cd|peak|klm] [--color] -o solid.{obj,ply,stl,glb}`
//! is: load, pick the units, build ([`measured_solid`], or [`grid_solid`]
//! with the filter's sampler as the [`IntensityField`](crate::model::IntensityField) on
//! the [`adaptive`] grid within `--tolerance` % of I_max ([`Refinement::Adaptive`],
//! the default) or on [`SolidGrid::refined`]`(d, factor)` with `--factor`),
//! optionally [`Mesh::colorize`], then [`export::write`] (format from the extension).
//! ```
//! use photosolid_fields::solid::{self, export, ColorMap, SolidGrid, Units};
//! use photosolid_fields::synth::{GridSpec, Synth};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let d = Synth::Lambertian.build(&GridSpec::uniform(15.0, 5.0)?, 1000.0)?.into_distribution();
//! // --measured --units klm --color
//! let mut m = solid::measured_solid(&d, Units::per_kilolumen(&d)?)?;
//! m.colorize(ColorMap::Viridis);
//! let report = m.sanity_check()?;
//! assert_eq!(report.components, 1);
//! // --filter (any sampler; here the analytic kind itself) --factor 5 --units peak
//! let field = |c: f64, g: f64| 1000.0 * Synth::Lambertian.relative(c, g);
//! let g = solid::grid_solid(&field, &SolidGrid::refined(&d, 5)?, Units::Peak)?;
//! let exact = std::f64::consts::PI / 6.0; // a sphere of diameter 1 touching the origin
//! assert!((g.volume() - exact).abs() / exact < 1e-3);
//! let bytes = export::encode(&g, export::MeshFormat::Glb);
//! assert_eq!(&bytes[..4], b"glTF");
//! # Ok(()) }
//! ```

pub mod adaptive;
pub mod colormap;
pub mod export;
mod gammas;
pub mod grid;
pub mod measured;
pub mod mesh;
pub mod radial;
pub mod topology;

pub use adaptive::{
    adaptive_grid, adaptive_grid_with_progress, radial_deviation, surface_distance, AdaptiveGrid, AdaptiveOptions,
    Refinement, Stop, Tolerance,
};
pub use colormap::ColorMap;
pub use grid::{grid_solid, texture_solid, SolidGrid};
pub use measured::{measured_solid, measured_solid_with, MeasuredOptions};
pub use mesh::{Mesh, SanityError, SanityReport, SolidInfo};
pub use radial::RadialMesh;
pub use topology::{topology, MeshTopology, SHEET_SEPARATION};

use crate::error::ModelError;
use crate::model::Distribution;

/// The frame, as written into file metadata.
pub const UNIT_FRAME: &str = "luminaire frame, z up, nadir -z, C0 +x, C90 +y";

/// The spellings of [`Units`] a user chooses from (`--units cd|peak|klm|flux`);
/// [`Units::resolve`] turns one into units for a given distribution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum UnitsName {
    /// cd: 1 unit of length = 1 cd.
    #[default]
    Cd,
    /// I_max = 1.
    Peak,
    /// cd per 1000 lm of the file's lamp flux (as in EULUMDAT; not for absolute photometry).
    Klm,
    /// cd per 1000 lm of the computed luminaire flux: solids of equal flux.
    Flux,
}

impl std::str::FromStr for UnitsName {
    type Err = ModelError;
    /// `cd`, `peak`, `klm` or `flux`, as `--units` writes them.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "cd" => Ok(UnitsName::Cd),
            "peak" => Ok(UnitsName::Peak),
            "klm" => Ok(UnitsName::Klm),
            "flux" => Ok(UnitsName::Flux),
            other => Err(ModelError::Parameter {
                name: "units",
                value: other.to_string(),
                reason: "expected cd, peak, klm or flux".into(),
            }),
        }
    }
}

/// Units of the solid's coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Units {
    /// Candela: 1 unit of length = 1 cd. Default.
    #[default]
    Candela,
    /// Relative: the peak intensity of the solid is 1 (dimensionless).
    Peak,
    /// cd/klm: 1000 I / Φ, with Φ in lm ([`Units::per_kilolumen`] computes it
    /// with [`crate::photometry::flux()`]), so that solids of equal flux compare.
    PerKilolumen {
        /// The flux Φ (lm) the intensities are divided by.
        flux_lm: f64,
    },
}

impl Units {
    /// cd/klm with the flux of `d` from [`crate::photometry::flux()`]; fails for zero flux.
    pub fn per_kilolumen(d: &Distribution) -> Result<Units, ModelError> {
        let flux_lm = crate::photometry::flux(d).total_lm;
        if !(flux_lm.is_finite() && flux_lm > 0.0) {
            return Err(ModelError::AllZero("cd/klm units need a positive flux"));
        }
        Ok(Units::PerKilolumen { flux_lm })
    }

    /// Short name: `cd`, `peak` or `cd/klm` (the CLI's `--units` spellings are `cd`, `peak`, `klm`).
    pub fn name(&self) -> &'static str {
        match self {
            Units::Candela => "cd",
            Units::Peak => "peak",
            Units::PerKilolumen { .. } => "cd/klm",
        }
    }

    /// The units `name` means for `d`, whose file declares the lamp flux
    /// `lamp_flux_lm` (lm; `None` for absolute photometry).
    ///
    /// # Errors
    /// [`ModelError::Parameter`] for `klm` without a positive lamp flux;
    /// [`ModelError::AllZero`] for `flux` of a zero distribution.
    pub fn resolve(name: UnitsName, d: &Distribution, lamp_flux_lm: Option<f64>) -> Result<Units, ModelError> {
        match name {
            UnitsName::Cd => Ok(Units::Candela),
            UnitsName::Peak => Ok(Units::Peak),
            UnitsName::Klm => match lamp_flux_lm {
                Some(flux_lm) if flux_lm.is_finite() && flux_lm > 0.0 => Ok(Units::PerKilolumen { flux_lm }),
                _ => Err(ModelError::Parameter {
                    name: "units",
                    value: "klm".into(),
                    reason: "cd/klm is per 1000 lm of lamp flux, and this file has absolute photometry (no lamp \
                             flux); use --units flux (equal luminaire flux) or peak"
                        .into(),
                }),
            },
            UnitsName::Flux => Units::per_kilolumen(d),
        }
    }

    /// Human description for metadata.
    pub fn describe(&self) -> String {
        match self {
            Units::Candela => "cd (1 unit of length = 1 cd)".into(),
            Units::Peak => "relative to the peak (I_max = 1)".into(),
            Units::PerKilolumen { flux_lm } => {
                format!("cd/klm (1000 I / flux, flux = {flux_lm} lm)")
            }
        }
    }

    /// Units per cd for a solid whose peak is `peak_cd` (cd, positive).
    pub fn units_per_cd(&self, peak_cd: f64) -> Result<f64, ModelError> {
        let bad = |value: f64, reason: &str| ModelError::Parameter {
            name: "units",
            value: value.to_string(),
            reason: reason.into(),
        };
        match *self {
            Units::Candela => Ok(1.0),
            Units::Peak if peak_cd.is_finite() && peak_cd > 0.0 => Ok(1.0 / peak_cd),
            Units::Peak => Err(ModelError::AllZero("peak-relative units need a positive peak")),
            Units::PerKilolumen { flux_lm } if flux_lm.is_finite() && flux_lm > 0.0 => Ok(1000.0 / flux_lm),
            Units::PerKilolumen { flux_lm } => Err(bad(flux_lm, "cd/klm needs a positive, finite flux in lm")),
        }
    }
}

/// What [`check_measured`] can fail with.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    /// The solid could not be built (e.g. all-zero data).
    #[error(transparent)]
    Build(#[from] ModelError),
    /// The solid was built but breaks an invariant: a bug.
    #[error(transparent)]
    Sanity(#[from] SanityError),
}

/// The corpus check in one call: build the measured solid of `d` in cd,
/// with normals, and run [`Mesh::sanity_check`] on it. All-zero data gives
/// `Err(CheckError::Build(ModelError::AllZero(..)))`, which a corpus loop
/// may accept; a `Sanity` error is always a bug.
pub fn check_measured(d: &Distribution) -> Result<SanityReport, CheckError> {
    let mesh = measured_solid(d, Units::Candela)?;
    Ok(mesh.sanity_check()?)
}

pub use crate::model::ZERO_FRACTION;

/// Scaled intensity → the radius stored: NaN and too-large values are
/// refused; negative values, values below the smallest normal f32 (they
/// would collapse onto the origin in the file) and values below [`ZERO_FRACTION`] (1e-9) of the
/// peak (round-off of a zero, e.g. I0 cos 90° = 6e-17 I0) are zero, i.e. the
/// merged origin vertex. `peak` is the peak in the same units.
#[inline]
pub(crate) fn stored_radius(v_units: f64, peak: f64) -> Result<f64, ModelError> {
    if v_units.is_nan() {
        return Err(ModelError::Intensities("an intensity is NaN".into()));
    }
    // Below 1e-9 of the peak a value is rounding noise (cubic weights summing
    // to zero on zero data give about 1e-11 of I_max): such values would make
    // spurious sheets through the origin, so they count as zero.
    if v_units < (f32::MIN_POSITIVE as f64).max(ZERO_FRACTION * peak) {
        return Ok(0.0);
    }
    // Leave headroom so that products of coordinates stay finite in f32 readers.
    if v_units > 1e18 {
        return Err(ModelError::Intensities(format!(
            "intensity {v_units} (in output units) is too large for f32 coordinates"
        )));
    }
    Ok(v_units)
}
