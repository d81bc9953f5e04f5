//! Reconstructions that re-store the measured grid before filtering it:
//! a crop to the directions a scene sees ([`crop`]) and a smaller symmetry
//! the data has, sampled through a texture the field owns ([`OwnedSampler`]).

use glam::DVec3;

use crate::error::ModelError;
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::{Filter, LightTexture};

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

/// `d` with only the γ rows in [from, to] and, when `c` is given, only the
/// C planes of the full circle from `c.0` counter-clockwise to `c.1` (degrees),
/// stored without symmetry.
///
/// # Errors
/// [`ModelError`] when fewer rows or planes than a distribution needs are left.
pub fn crop(d: &Distribution, from: f64, to: f64, c: Option<(f64, f64)>) -> Result<Distribution, ModelError> {
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
