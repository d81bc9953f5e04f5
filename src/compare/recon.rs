//! The reconstructions a comparison can build from one distribution.

use std::fmt;
use std::str::FromStr;

use serde::{Serialize, Serializer};

use super::raycast::RadialMesh;
use crate::error::ModelError;
use crate::fit::{fit, FitOptions, FittedLights};
use crate::model::Distribution;
use crate::reconstruct::{Filter, LightTexture};
use crate::solid::{grid_solid, measured_solid, Mesh, SolidGrid, Units};

/// What is compared: the measured solid, one filter's reconstruction, or the fitted OpenGL lights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Recon {
    /// The measured solid (Delaunay of the measured directions, [`measured_solid`]).
    /// As a field (radial metrics, plots) it is that solid's radial function
    /// (ray cast, [`super::raycast::RadialMesh`]): exact at the measured
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
                        crate::reconstruct::FILTER_NAMES
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

/// One distribution with what its reconstructions need: the texture and, when asked for, the fit.
#[derive(Debug)]
pub struct Prepared {
    /// The (normalised, aligned) distribution.
    pub dist: Distribution,
    /// Its light texture.
    pub tex: LightTexture,
    /// The fitted lights, when a `fitted-gl` reconstruction is needed.
    pub model: Option<FittedLights>,
    /// The measured solid.
    pub measured: Mesh,
    /// Its radial function.
    pub measured_rm: RadialMesh,
}

impl Prepared {
    /// Build the texture, and the fit when `with_fit`.
    pub fn new(dist: Distribution, with_fit: bool) -> Result<Self, ModelError> {
        let tex = LightTexture::new(&dist)?;
        let model = if with_fit {
            Some(fit(&dist, &FitOptions::default())?.model().clone())
        } else {
            None
        };
        let measured = measured_solid(&dist, Units::Candela)?;
        let measured_rm = RadialMesh::new(&measured);
        Ok(Self {
            dist,
            tex,
            model,
            measured,
            measured_rm,
        })
    }

    fn model_of(&self) -> Result<&FittedLights, ModelError> {
        self.model
            .as_ref()
            .ok_or(ModelError::AllZero("fitted-gl was not prepared (internal)"))
    }

    /// The intensity (cd, ≥ 0) of reconstruction `r` at (C, γ) in degrees.
    pub fn eval(&self, r: Recon, c_deg: f64, gamma_deg: f64) -> f64 {
        match r {
            Recon::Measured => self.measured_rm.radius_at(c_deg, gamma_deg),
            Recon::Filter(f) => self.tex.sampler(f).cd(c_deg, gamma_deg),
            Recon::FittedGl => self
                .model
                .as_ref()
                .map_or(0.0, |m| m.intensity(c_deg, gamma_deg).max(0.0)),
        }
    }

    /// Evaluate `r` at every (C, γ) of `dirs`.
    pub fn eval_all(&self, r: Recon, dirs: &[(f64, f64)]) -> Vec<f64> {
        use rayon::prelude::*;
        dirs.par_iter().map(|&(c, g)| self.eval(r, c, g)).collect()
    }

    /// The photometric solid of `r` (coordinates in the distribution's unit):
    /// the measured solid, or a grid solid on `SolidGrid::refined(dist, factor)`.
    pub fn solid(&self, r: Recon, factor: usize) -> Result<Mesh, ModelError> {
        match r {
            Recon::Measured => Ok(self.measured.clone()),
            Recon::Filter(f) => grid_solid(
                &self.tex.sampler(f),
                &SolidGrid::refined(&self.dist, factor)?,
                Units::Candela,
            ),
            Recon::FittedGl => {
                let m = self.model_of()?;
                let field = |c: f64, g: f64| m.intensity(c, g).max(0.0);
                grid_solid(&field, &SolidGrid::refined(&self.dist, factor)?, Units::Candela)
            }
        }
    }

    /// Median wall time (ns) per sample of evaluating `r` sequentially at
    /// every direction of `dirs`, over `repeats` runs. `None` for the measured solid.
    pub fn time_per_sample_ns(&self, r: Recon, dirs: &[(f64, f64)], repeats: usize) -> Option<f64> {
        if r == Recon::Measured || dirs.is_empty() {
            return None;
        }
        let mut times: Vec<f64> = (0..repeats.max(1))
            .map(|_| {
                let t0 = std::time::Instant::now();
                let mut acc = 0.0;
                match r {
                    Recon::Filter(f) => {
                        let s = self.tex.sampler(f);
                        for &(c, g) in dirs {
                            acc += s.cd(std::hint::black_box(c), g);
                        }
                    }
                    _ => {
                        let m = self.model.as_ref()?;
                        for &(c, g) in dirs {
                            acc += m.intensity(std::hint::black_box(c), g);
                        }
                    }
                }
                std::hint::black_box(acc);
                Some(t0.elapsed().as_secs_f64())
            })
            .collect::<Option<Vec<f64>>>()?;
        times.sort_by(f64::total_cmp);
        Some(1e9 * times[times.len() / 2] / dirs.len() as f64)
    }
}
