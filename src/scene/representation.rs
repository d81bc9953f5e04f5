//! The representations of a luminaire's distribution a scene can hold
//! ([`Representation`]) and what builds each as a field ([`Models`]): the
//! candidates of a plan ([`super::plan`]) and the model of every luminaire
//! the illuminance is computed with ([`super::illuminance`]).

use std::fmt;
use std::str::FromStr;

use glam::DVec3;

use super::{Dark, SceneLuminaire};
use crate::error::ModelError;
use crate::fit::{fit, FitOptions};
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::{render, Filter, LightTexture, Precision, StoredTexture, TextureSpec};

/// A representation of a luminaire's distribution.
#[derive(Debug, Clone, PartialEq)]
pub enum Representation {
    /// A filter sampling the native grid (f64).
    Filter(Filter),
    /// A rendered texture as a renderer stores and reads it (f32 or f16,
    /// whole or symmetry-reduced), as in the trade table.
    Texture(TextureSpec),
    /// The fitted OpenGL lights (at most 2).
    Fitted,
    /// The native grid cropped to the γ rows between `gamma_from` and
    /// `gamma_to` and, when given, to the C planes from `c.0` counter-clockwise
    /// to `c.1` (degrees; the sector may wrap through C = 0).
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
    /// The native grid re-stored with a smaller symmetry the data has.
    Symmetric {
        /// The filter.
        filter: Filter,
        /// The symmetry it is stored with.
        symmetry: Symmetry,
    },
}

impl fmt::Display for Representation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Representation::Filter(x) => write!(f, "{x}"),
            Representation::Texture(t) => {
                write!(f, "texture {} x{} / {}", t.filter, t.factor, t.lookup)?;
                if t.precision == Precision::F16 {
                    f.write_str(" +f16")?;
                }
                if t.reduced {
                    f.write_str(" +reduced")?;
                }
                Ok(())
            }
            Representation::Fitted => f.write_str(crate::fit::RECONSTRUCTION_NAME),
            Representation::Cropped {
                filter,
                gamma_from,
                gamma_to,
                c,
            } => {
                write!(f, "{filter}, gamma {gamma_from}-{gamma_to} deg")?;
                if let Some((a, b)) = c {
                    write!(f, ", C {a}-{b} deg")?;
                }
                f.write_str(" only")
            }
            Representation::Symmetric { filter, symmetry } => write!(f, "{filter}, stored {}", symmetry.describe()),
        }
    }
}

impl FromStr for Representation {
    type Err = ModelError;
    /// A filter name, `fitted-gl`, or `texture FILTER xFACTOR / LOOKUP`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        if t == crate::fit::RECONSTRUCTION_NAME {
            return Ok(Representation::Fitted);
        }
        if let Some(rest) = t.strip_prefix("texture ") {
            let bad = || ModelError::Parameter {
                name: "representation",
                value: s.to_string(),
                reason: "expected `texture FILTER xFACTOR / LOOKUP`, e.g. `texture catmull-rom x5 / bilinear`".into(),
            };
            let (left, lookup) = rest.split_once('/').ok_or_else(bad)?;
            let (filter, factor) = left.trim().rsplit_once(' ').ok_or_else(bad)?;
            let factor: u32 = factor
                .trim()
                .strip_prefix('x')
                .and_then(|x| x.parse().ok())
                .ok_or_else(bad)?;
            let mut words = lookup.split_whitespace();
            let mut spec = TextureSpec {
                filter: filter.parse()?,
                factor,
                lookup: words.next().ok_or_else(bad)?.parse()?,
                precision: Precision::F32,
                reduced: false,
            };
            for w in words {
                match w {
                    "+f16" => spec.precision = Precision::F16,
                    "+reduced" => spec.reduced = true,
                    _ => return Err(bad()),
                }
            }
            return Ok(Representation::Texture(spec));
        }
        if t.contains('@') {
            // The trade table's spelling, `FILTER@xK/LOOKUP[+f16][+reduced]`.
            return t.parse().map(Representation::Texture);
        }
        t.parse::<Filter>()
            .map(Representation::Filter)
            .map_err(|_| ModelError::Parameter {
                name: "representation",
                value: s.to_string(),
                reason: format!(
                    "expected a filter ({}), {}, or `texture FILTER xFACTOR / LOOKUP`",
                    crate::reconstruct::FILTER_NAMES,
                    crate::fit::RECONSTRUCTION_NAME
                ),
            })
    }
}

/// A filter over a texture it owns (the cropped and re-stored grids).
#[derive(Debug, Clone)]
pub struct OwnedSampler {
    /// The texture.
    pub texture: LightTexture,
    /// The filter.
    pub filter: Filter,
    /// The name reported.
    pub name: String,
}

impl IntensityField for OwnedSampler {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.texture.sampler(self.filter).cd(c_deg, gamma_deg)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        self.texture.sampler(self.filter).cd_dir(d)
    }
    fn name(&self) -> String {
        self.name.clone()
    }
    fn bytes(&self) -> usize {
        self.texture.bytes()
    }
}

/// What the representations of one luminaire are built from.
pub struct Models<'a> {
    dist: &'a Distribution,
    texture: Option<&'a LightTexture>,
}

impl<'a> Models<'a> {
    /// The models of `lum`; `texture` is its light texture (`None`: all-zero).
    pub fn new(lum: &'a SceneLuminaire, texture: Option<&'a LightTexture>) -> Self {
        Self {
            dist: lum.luminaire.distribution(),
            texture,
        }
    }

    /// Representation `r` as an intensity field (cd); every representation
    /// of an all-zero distribution is [`Dark`].
    pub fn field(&self, r: &Representation) -> Result<Box<dyn IntensityField + 'a>, ModelError> {
        let Some(tex) = self.texture else {
            return Ok(Box::new(Dark));
        };
        let owned = |d: Distribution, filter: Filter| -> Result<Box<dyn IntensityField + 'a>, ModelError> {
            Ok(Box::new(OwnedSampler {
                texture: LightTexture::new(&d)?,
                filter,
                name: r.to_string(),
            }))
        };
        Ok(match r {
            Representation::Filter(f) => Box::new(tex.sampler(*f)),
            Representation::Texture(t) => Box::new(StoredTexture::new(
                &render(tex, t.filter, t.factor)?,
                t.reduced.then(|| self.dist.symmetry()),
                t.precision,
                t.lookup,
            )),
            Representation::Fitted => Box::new(fit(self.dist, &FitOptions::default())?.model().prepare()),
            Representation::Cropped {
                filter,
                gamma_from,
                gamma_to,
                c,
            } => owned(crop(self.dist, *gamma_from, *gamma_to, *c)?, *filter)?,
            Representation::Symmetric { filter, symmetry } => owned(self.dist.with_symmetry(*symmetry)?, *filter)?,
        })
    }
}

/// `d` with only the γ rows in [from, to] and, when `c` is given, only the
/// C planes of the full circle from `c.0` counter-clockwise to `c.1` (degrees),
/// stored without symmetry.
fn crop(d: &Distribution, from: f64, to: f64, c: Option<(f64, f64)>) -> Result<Distribution, ModelError> {
    let g = d.gamma_angles_deg();
    let keep: Vec<usize> = (0..g.len()).filter(|&i| g[i] >= from && g[i] <= to).collect();
    let gamma: Vec<f64> = keep.iter().map(|&i| g[i]).collect();
    let rows = |d: &Distribution, ic: usize| keep.iter().map(|&ig| d.value_cd(ic, ig)).collect::<Vec<f64>>();
    let Some((c0, c1)) = c else {
        let cd = (0..d.n_c()).flat_map(|ic| rows(d, ic)).collect();
        return Distribution::new(d.c_angles_deg().to_vec(), gamma, cd, d.symmetry());
    };
    let full = d.with_symmetry(Symmetry::None)?;
    let eps = crate::model::ANGLE_EPS;
    let inside = |a: f64| {
        if c0 <= c1 {
            a >= c0 - eps && a <= c1 + eps
        } else {
            a >= c0 - eps || a <= c1 + eps
        }
    };
    let planes: Vec<usize> = (0..full.n_c()).filter(|&i| inside(full.c_angles_deg()[i])).collect();
    let angles = planes.iter().map(|&i| full.c_angles_deg()[i]).collect();
    let cd = planes.iter().flat_map(|&ic| rows(&full, ic)).collect();
    Distribution::new(angles, gamma, cd, Symmetry::None)
}
