//! The reconstructions a comparison can build from one distribution.

use std::fmt;
use std::str::FromStr;

use serde::{Serialize, Serializer};

use super::filter::Filter;
use super::texture::LightTexture;
use crate::error::ModelError;
use crate::fit::{fit, FitOptions, PreparedLights};
use crate::model::{Borrowed, Distribution, IntensityField};
use crate::solid::{grid_solid, measured_solid, Mesh, RadialMesh, SolidGrid, Units};

/// What is compared: the measured solid, one filter's reconstruction, or the fitted OpenGL lights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Recon {
    /// The measured solid (Delaunay of the measured directions, [`measured_solid`]).
    /// As a field (radial metrics, plots) it is that solid's radial function
    /// (ray cast, [`RadialMesh`]): exact at the measured
    /// directions, linear on the Delaunay triangles between them.
    Measured,
    /// A reconstruction filter on the light texture ([`LightTexture::sampler`]).
    Filter(Filter),
    /// The fitted OpenGL lights ([`crate::fit`], name `fitted-gl`).
    FittedGl,
}

/// The default reconstructions of `photosolid compare`.
pub const DEFAULT_RECONS: [Recon; 6] = [
    Recon::Filter(Filter::Bilinear),
    Recon::Filter(Filter::CatmullRom),
    Recon::Filter(Filter::Mitchell {
        b: 1.0 / 3.0,
        c: 1.0 / 3.0,
    }),
    Recon::Filter(Filter::BSpline),
    Recon::Filter(Filter::Pchip),
    Recon::FittedGl,
];

impl fmt::Display for Recon {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Recon::Measured => f.write_str("measured"),
            Recon::Filter(x) => write!(f, "{x}"),
            Recon::FittedGl => f.write_str(crate::fit::RECONSTRUCTION_NAME),
        }
    }
}

impl FromStr for Recon {
    type Err = ModelError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "measured" => Ok(Recon::Measured),
            x if x == crate::fit::RECONSTRUCTION_NAME => Ok(Recon::FittedGl),
            x => x
                .parse::<Filter>()
                .map(Recon::Filter)
                .map_err(|_| ModelError::Parameter {
                    name: "recon",
                    value: x.to_string(),
                    reason: format!(
                        "expected measured, {}, or a filter ({})",
                        crate::fit::RECONSTRUCTION_NAME,
                        super::filter::FILTER_NAMES
                    ),
                }),
        }
    }
}

impl Serialize for Recon {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// One distribution with what its reconstructions need, each reconstruction
/// answered as an [`IntensityField`].
#[derive(Debug)]
pub struct Reconstructions {
    /// The distribution the reconstructions are built from.
    pub dist: Distribution,
    /// Its light texture (every filter samples it).
    pub texture: LightTexture,
    /// The fitted lights, prepared for evaluation, when asked for.
    pub fitted: Option<PreparedLights>,
    /// The measured solid and its radial function, when asked for.
    pub measured: Option<(Mesh, RadialMesh)>,
}

impl Reconstructions {
    /// Build what the reconstructions in `recons` need: the texture always,
    /// the fit for `fitted-gl`, the measured solid for `measured`.
    pub fn new(dist: Distribution, recons: &[Recon]) -> Result<Self, ModelError> {
        let texture = LightTexture::new(&dist)?;
        let fitted = if recons.contains(&Recon::FittedGl) {
            Some(fit(&dist, &FitOptions::default())?.model().prepare())
        } else {
            None
        };
        let measured = if recons.contains(&Recon::Measured) {
            let mesh = measured_solid(&dist, Units::Candela)?;
            let radial = RadialMesh::new(&mesh);
            Some((mesh, radial))
        } else {
            None
        };
        Ok(Self {
            dist,
            texture,
            fitted,
            measured,
        })
    }

    /// Reconstruction `r` as an intensity field (cd).
    ///
    /// # Errors
    /// [`ModelError::Internal`] when `r` was not asked for in [`Reconstructions::new`] (a bug).
    pub fn field(&self, r: Recon) -> Result<Box<dyn IntensityField + '_>, ModelError> {
        let missing = || ModelError::Internal(format!("reconstruction {r} was not prepared"));
        Ok(match r {
            Recon::Measured => Box::new(Borrowed(&self.measured.as_ref().ok_or_else(missing)?.1)),
            Recon::Filter(f) => Box::new(self.texture.sampler(f)),
            Recon::FittedGl => Box::new(Borrowed(self.fitted.as_ref().ok_or_else(missing)?)),
        })
    }

    /// The photometric solid of `r` (coordinates in cd): the measured solid
    /// itself, or the field's grid solid on [`SolidGrid::refined`]`(dist, factor)`.
    pub fn solid(&self, r: Recon, factor: usize) -> Result<Mesh, ModelError> {
        self.solid_in(r, factor, Units::Candela)
    }

    /// [`Reconstructions::solid`] with vertex coordinates in `units`.
    pub fn solid_in(&self, r: Recon, factor: usize, units: Units) -> Result<Mesh, ModelError> {
        match (r, &self.measured) {
            (Recon::Measured, Some((mesh, _))) if units == Units::Candela => Ok(mesh.clone()),
            (Recon::Measured, _) => measured_solid(&self.dist, units),
            _ => grid_solid(&*self.field(r)?, &SolidGrid::refined(&self.dist, factor)?, units),
        }
    }
}

/// Evaluate `field` at every (C, γ) of `dirs` (degrees), in parallel.
pub fn eval_all(field: &dyn IntensityField, dirs: &[(f64, f64)]) -> Vec<f64> {
    use rayon::prelude::*;
    dirs.par_iter().map(|&(c, g)| field.intensity_cd(c, g)).collect()
}
