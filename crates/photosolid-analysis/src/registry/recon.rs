//! The reconstructions a comparison can build from one distribution.

use std::fmt;
use std::str::FromStr;

use serde::{Serialize, Serializer};

use super::extension::{self, ExtensionId};
use super::owned::{crop, OwnedSampler};
use crate::error::ModelError;
use crate::fit::lobes::{fit_lobes, Lobes};
use crate::fit::{fit, FitOptions, PreparedLights};
use crate::model::{Borrowed, Distribution, IntensityField, Symmetry};
use crate::reconstruct::{
    render, Compact, Filter, LightTexture, Precision, ShField, ShWindow, StoredTexture, TextureSpec,
};
use crate::solid::{grid_solid, measured_solid, Mesh, RadialMesh, SolidGrid, Units};

/// A reconstruction: the measured solid, a filter on the measured grid, the
/// fitted OpenGL lights, or a stored texture read back with a lookup.
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
    /// A texture rendered once and read back as a renderer does ([`StoredTexture`]).
    Texture(TextureSpec),
    /// The same texture sampled by the GPU's texture hardware
    /// (`gpu::realtime::RealtimeTexture`, feature `gpu`, on the process's
    /// adapter; `R16Float` where `R32Float` is not filterable). Written
    /// `FILTER@xK/LOOKUP[+f16][+reduced]+gpu`.
    Gpu(TextureSpec),
    /// A filter on the measured grid cropped to the γ rows between
    /// `gamma_from` and `gamma_to` and, when given, to the C planes from
    /// `c.0` counter-clockwise to `c.1` (degrees; the sector may wrap
    /// through C = 0): what a scene sees of the luminaire ([`crop`]).
    /// Written `FILTER+gamma:FROM-TO[+c:FROM-TO]`.
    Cropped {
        /// The filter.
        filter: Filter,
        /// First kept γ row, degrees.
        gamma_from: f64,
        /// Last kept γ row, degrees.
        gamma_to: f64,
        /// First and last kept C plane, degrees.
        c: Option<(f64, f64)>,
    },
    /// A filter on the measured grid re-stored with a smaller symmetry the
    /// data has. Written `FILTER+isym:N` (N the EULUMDAT code, 0-4).
    Symmetric {
        /// The filter.
        filter: Filter,
        /// The symmetry it is stored with.
        symmetry: Symmetry,
    },
    /// Spherical harmonics of degree `degree` of the Catmull–Rom
    /// reconstruction, Lanczos-windowed, clamped at 0
    /// ([`ShField`]); written `sh:L`, `sh:L+f16` for half-float coefficients,
    /// with `+gpu` evaluated by the GPU in f32 (`gpu::compact`, feature `gpu`).
    Sh {
        /// The degree L (0 to [`MAX_SH_DEGREE`](crate::reconstruct::MAX_SH_DEGREE); to [`MAX_ZONAL_SH_DEGREE`](crate::reconstruct::MAX_ZONAL_SH_DEGREE)
        /// for rotationally symmetric data, whose series is zonal).
        degree: usize,
        /// Coefficients stored as f16 (2 bytes) instead of f32 (4 bytes).
        f16: bool,
        /// Evaluated by the GPU's compute shader instead of the CPU.
        gpu: bool,
    },
    /// A mixture of `count` cosine-power lobes fitted to the measured data
    /// ([`crate::fit::lobes`]); written `lobes:K`, `lobes:K+gpu` evaluated by
    /// the GPU in f32.
    Lobes {
        /// The number of lobes K (1 to [`MAX_LOBES`](crate::fit::lobes::MAX_LOBES)).
        count: usize,
        /// Evaluated by the GPU's compute shader instead of the CPU.
        gpu: bool,
    },
    /// An instance of a representation a caller registered
    /// ([`super::Registry::register`]), written as it spells it.
    Extension {
        /// The registered representation.
        id: ExtensionId,
        /// The instance's parameter (the representation reads and writes it in its names).
        param: u32,
        /// Evaluated by the GPU ([`super::Representation::build_gpu`]), written `NAME+gpu`.
        gpu: bool,
    },
}

/// The prefix naming a [`Recon::Lobes`] mixture.
pub const LOBES_PREFIX: &str = "lobes:";

/// The prefix naming a [`Recon::Sh`] series.
pub const SH_PREFIX: &str = "sh:";

/// The suffix naming a [`Recon::Gpu`] texture.
pub const GPU_SUFFIX: &str = "+gpu";

impl fmt::Display for Recon {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Recon::Measured => f.write_str("measured"),
            Recon::Filter(x) => write!(f, "{x}"),
            Recon::FittedGl => f.write_str(crate::fit::RECONSTRUCTION_NAME),
            Recon::Texture(t) => write!(f, "{t}"),
            Recon::Gpu(t) => write!(f, "{t}{GPU_SUFFIX}"),
            Recon::Cropped {
                filter,
                gamma_from,
                gamma_to,
                c,
            } => {
                write!(f, "{filter}+gamma:{gamma_from}-{gamma_to}")?;
                if let Some((a, b)) = c {
                    write!(f, "+c:{a}-{b}")?;
                }
                Ok(())
            }
            Recon::Symmetric { filter, symmetry } => write!(f, "{filter}+isym:{}", symmetry.isym()),
            Recon::Sh { degree, f16, gpu } => write!(
                f,
                "{SH_PREFIX}{degree}{}{}",
                if *f16 { "+f16" } else { "" },
                if *gpu { GPU_SUFFIX } else { "" }
            ),
            Recon::Lobes { count, gpu } => {
                write!(f, "{LOBES_PREFIX}{count}{}", if *gpu { GPU_SUFFIX } else { "" })
            }
            Recon::Extension { id, param, gpu } => f.write_str(&extension::name(*id, *param, *gpu)),
        }
    }
}

impl Recon {
    /// Whether this is the GPU's evaluation of a representation (`…+gpu`):
    /// the same stored data as its CPU twin, evaluated by the GPU.
    pub fn on_gpu(&self) -> bool {
        matches!(
            self,
            Recon::Gpu(_)
                | Recon::Sh { gpu: true, .. }
                | Recon::Lobes { gpu: true, .. }
                | Recon::Extension { gpu: true, .. }
        )
    }
}

impl FromStr for Recon {
    type Err = ModelError;
    /// A built-in reconstruction's name, else the name of an instance of a
    /// representation registered in the process (in any [`super::Registry`]).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        super::builtin::parse(s).or_else(|e| extension::parse(s.trim()).ok_or(e))
    }
}

/// `s` without a trailing [`GPU_SUFFIX`], and whether it had one.
pub(crate) fn strip_gpu(s: &str) -> (&str, bool) {
    match s.strip_suffix(GPU_SUFFIX) {
        Some(body) => (body, true),
        None => (s, false),
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
    /// The fitted lobe mixtures of 1, 2, … lobes, up to the largest count asked for.
    pub lobes: Vec<Lobes>,
}

impl Reconstructions {
    /// Build what the reconstructions in `recons` need: the texture always,
    /// the fit for `fitted-gl`, the lobe fits for `lobes:K` (one search up to
    /// the largest K), the measured solid for `measured`.
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
        let max_lobes = recons
            .iter()
            .filter_map(|r| match r {
                Recon::Lobes { count, .. } => Some(*count),
                _ => None,
            })
            .max();
        let lobes = match max_lobes {
            Some(k) => fit_lobes(&dist, k)?,
            None => Vec::new(),
        };
        Ok(Self {
            dist,
            texture,
            fitted,
            measured,
            lobes,
        })
    }

    /// Reconstruction `r` as an intensity field (cd). A texture is rendered here.
    ///
    /// # Errors
    /// [`ModelError::Internal`] when `r` was not asked for in [`Reconstructions::new`] (a bug).
    pub fn field(&self, r: Recon) -> Result<Box<dyn IntensityField + '_>, ModelError> {
        if let Some(owned) = self.owned_field(r)? {
            return Ok(owned);
        }
        let missing = || ModelError::Internal(format!("reconstruction {r} was not prepared"));
        Ok(match r {
            Recon::Measured => Box::new(Borrowed(&self.measured.as_ref().ok_or_else(missing)?.1)),
            Recon::Filter(f) => Box::new(self.texture.sampler(f)),
            Recon::FittedGl => Box::new(Borrowed(self.fitted.as_ref().ok_or_else(missing)?)),
            Recon::Gpu(t) => self.gpu_field(r, t)?,
            Recon::Lobes { gpu: true, .. } | Recon::Sh { gpu: true, .. } => self.gpu_compact(r, self.compact(r)?)?,
            Recon::Extension { id, param, gpu: true } => extension::build_gpu(id, param, &self.dist)?,
            // Built by owned_field.
            Recon::Texture(_)
            | Recon::Cropped { .. }
            | Recon::Symmetric { .. }
            | Recon::Lobes { gpu: false, .. }
            | Recon::Sh { gpu: false, .. }
            | Recon::Extension { gpu: false, .. } => return Err(missing()),
        })
    }

    /// The reconstructions whose field owns what it samples (a rendered
    /// texture, a re-stored grid, a series or a mixture), built here at a
    /// cost (a render, a projection): a caller that samples one many times
    /// keeps this value instead of calling [`Reconstructions::field`] again.
    /// `None` for those that borrow from `self` and cost nothing to take
    /// again (`measured`, a filter, `fitted-gl`) and for the GPU's.
    ///
    /// # Errors
    /// As [`Reconstructions::field`].
    pub fn owned_field(&self, r: Recon) -> Result<Option<Box<dyn IntensityField + Send>>, ModelError> {
        Ok(Some(match r {
            Recon::Texture(t) => {
                let rendered = render(&self.texture, t.filter, t.factor)?;
                let reduced = t.reduced.then(|| self.dist.symmetry());
                Box::new(StoredTexture::new(&rendered, reduced, t.precision, t.lookup))
            }
            Recon::Cropped {
                filter,
                gamma_from,
                gamma_to,
                c,
            } => self.owned(r, crop(&self.dist, gamma_from, gamma_to, c)?, filter)?,
            Recon::Symmetric { filter, symmetry } => self.owned(r, self.dist.with_symmetry(symmetry)?, filter)?,
            Recon::Lobes { gpu: false, .. } | Recon::Sh { gpu: false, .. } => Box::new(self.compact(r)?),
            Recon::Extension { id, param, gpu: false } => extension::build(id, param, &self.dist)?,
            _ => return Ok(None),
        }))
    }

    /// The compact representation of `r` (`sh:L`, `lobes:K`, with or without `+gpu`).
    ///
    /// # Errors
    /// [`ModelError::Parameter`] for another reconstruction, [`ModelError::Internal`]
    /// for lobes not fitted in [`Reconstructions::new`] (a bug).
    pub fn compact(&self, r: Recon) -> Result<Compact, ModelError> {
        match r {
            Recon::Lobes { count, .. } => self
                .lobes
                .get(count - 1)
                .cloned()
                .map(Compact::Lobes)
                .ok_or_else(|| ModelError::Internal(format!("reconstruction {r} was not prepared"))),
            Recon::Sh { degree, f16, .. } => {
                let precision = if f16 { Precision::F16 } else { Precision::F32 };
                let source = self.texture.sampler(Filter::CatmullRom);
                Ok(Compact::Sh(ShField::new(
                    &source,
                    degree,
                    ShWindow::Lanczos,
                    precision,
                )?))
            }
            _ => Err(ModelError::Parameter {
                name: "recon",
                value: r.to_string(),
                reason: "not a compact representation (sh:L, lobes:K)".into(),
            }),
        }
    }

    /// A filter on a re-stored grid, sampled through the texture it owns.
    fn owned(&self, r: Recon, d: Distribution, filter: Filter) -> Result<Box<dyn IntensityField + Send>, ModelError> {
        Ok(Box::new(OwnedSampler {
            texture: LightTexture::new(&d)?,
            filter,
            name: r.to_string(),
        }))
    }

    /// A stored texture read by the GPU's texture hardware, on the installed device.
    fn gpu_field(&self, r: Recon, t: TextureSpec) -> Result<Box<dyn IntensityField + '_>, ModelError> {
        let unavailable = |source: crate::error::GpuError| ModelError::gpu(r.to_string(), source);
        let device = crate::device::device().map_err(unavailable)?;
        let rendered = render(&self.texture, t.filter, t.factor)?;
        let reduced = t.reduced.then(|| self.dist.symmetry());
        device
            .texture_field(&rendered, reduced, t.precision, t.lookup)
            .map_err(unavailable)
    }

    /// A spherical-harmonic series or lobe mixture evaluated by the installed GPU device.
    fn gpu_compact(&self, r: Recon, compact: Compact) -> Result<Box<dyn IntensityField + '_>, ModelError> {
        let unavailable = |source: crate::error::GpuError| ModelError::gpu(r.to_string(), source);
        crate::device::device()
            .and_then(|device| device.compact_field(compact))
            .map_err(unavailable)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reconstruct::Lookup;

    /// `+gpu` names a GPU-sampled texture and round-trips; a plain spec stays a CPU texture.
    #[test]
    fn gpu_texture_names() {
        let r: Recon = "catmull-rom@x5/bilinear+f16+gpu".parse().unwrap();
        let Recon::Gpu(t) = r else { panic!("{r:?}") };
        assert_eq!((t.factor, t.lookup, t.precision), (5, Lookup::Bilinear, Precision::F16));
        assert_eq!(r.to_string(), "catmull-rom@x5/bilinear+f16+gpu");
        assert!(matches!(
            "catmull-rom@x5/bilinear".parse::<Recon>().unwrap(),
            Recon::Texture(_)
        ));
        assert!("catmull-rom@x5/bilinear+gpu+f16".parse::<Recon>().is_err());
    }

    /// `sh:L[+f16]+gpu` and `lobes:K+gpu` name the compute shader's
    /// evaluation and round-trip; `+gpu` comes last.
    #[test]
    fn compact_gpu_names() {
        for (name, r) in [
            (
                "sh:16+gpu",
                Recon::Sh {
                    degree: 16,
                    f16: false,
                    gpu: true,
                },
            ),
            (
                "sh:8+f16+gpu",
                Recon::Sh {
                    degree: 8,
                    f16: true,
                    gpu: true,
                },
            ),
            (
                "sh:8+f16",
                Recon::Sh {
                    degree: 8,
                    f16: true,
                    gpu: false,
                },
            ),
            ("lobes:3+gpu", Recon::Lobes { count: 3, gpu: true }),
            ("lobes:3", Recon::Lobes { count: 3, gpu: false }),
        ] {
            assert_eq!(name.parse::<Recon>().unwrap(), r, "{name}");
            assert_eq!(r.to_string(), name);
        }
        for bad in [
            "sh:8+gpu+f16",
            "lobes:3+gpu+gpu",
            "lobes:0+gpu",
            "sh:129+gpu",
            "lobes:+gpu",
        ] {
            assert!(bad.parse::<Recon>().is_err(), "{bad}");
        }
    }

    /// The re-gridded reconstructions round-trip through their names, which
    /// hold no comma (a `--recon a,b` list keeps them whole).
    #[test]
    fn regridded_names_round_trip() {
        for r in [
            Recon::Cropped {
                filter: Filter::CatmullRom,
                gamma_from: 0.0,
                gamma_to: 87.5,
                c: None,
            },
            Recon::Cropped {
                filter: Filter::Mitchell { b: 0.0, c: 0.5 },
                gamma_from: -5.0,
                gamma_to: 90.0,
                c: Some((270.0, 90.0)),
            },
            Recon::Symmetric {
                filter: Filter::Pchip,
                symmetry: Symmetry::C90C270,
            },
        ] {
            let s = r.to_string();
            assert!(!s.contains(','), "{s}");
            assert_eq!(s.parse::<Recon>().unwrap(), r, "{s}");
        }
        for bad in [
            "catmull-rom+isym:7",
            "catmull-rom+gamma:0",
            "catmull-rom+gamma:0-90+isym:2",
            "bilinear+c:0-90",
        ] {
            assert!(bad.parse::<Recon>().is_err(), "{bad}");
        }
    }
}
