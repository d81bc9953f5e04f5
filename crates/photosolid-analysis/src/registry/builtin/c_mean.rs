//! `c-mean`: the luminaire as its mean γ profile, the same in every C-plane.
//!
//! Each γ row of the measured grid is averaged over the full circle of C
//! planes (each plane weighted by the arc it stands for), and the profile is
//! stored as one column read with the Catmull–Rom filter: a rotationally
//! symmetric stand-in, as many values as γ rows. On data the same in every
//! plane it equals the Catmull–Rom filter on the measured grid; for a
//! luminaire whose planes differ its error adds that asymmetry, which the trade table, `plan` and `batch --compact` measure
//! like any other candidate's. On the GPU (`c-mean+gpu`) the profile
//! rendered x5 is read by the texture hardware's bilinear filter.
//!
//! A built-in representation on the open trait: this file and its line in
//! [`super::open`].

use crate::device::GpuDevice;
use crate::error::ModelError;
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::{render, Filter, LightTexture, Lookup, Precision};
use crate::registry::{OwnedSampler, Representation};

/// Its one name.
const NAME: &str = "c-mean";

/// The mean γ profile over C (module docs).
pub(crate) struct CMean;

/// `dist` averaged over C: one plane at C = 0, rotationally symmetric.
fn profile(dist: &Distribution) -> Result<Distribution, ModelError> {
    let full = dist.with_symmetry(Symmetry::None)?;
    let c = full.c_angles_deg();
    let n = c.len();
    // The arc each plane stands for: half the gap to each neighbour, around the circle.
    let weights: Vec<f64> = (0..n)
        .map(|i| match n {
            1 => 1.0,
            _ => {
                let next = if i + 1 < n { c[i + 1] } else { c[0] + 360.0 };
                let prev = if i > 0 { c[i - 1] } else { c[n - 1] - 360.0 };
                (next - prev) / 2.0
            }
        })
        .collect();
    let total: f64 = weights.iter().sum();
    let gamma = full.gamma_angles_deg().to_vec();
    let mean = (0..gamma.len())
        .map(|ig| (0..n).map(|ic| weights[ic] * full.value_cd(ic, ig)).sum::<f64>() / total)
        .collect();
    Distribution::new(vec![0.0], gamma, mean, Symmetry::Rotational)
}

impl Representation for CMean {
    fn parse(&self, name: &str) -> Option<u32> {
        (name == NAME).then_some(0)
    }

    fn name(&self, _: u32) -> String {
        NAME.into()
    }

    fn build(&self, dist: &Distribution, _: u32) -> Result<Box<dyn IntensityField + Send>, ModelError> {
        Ok(Box::new(OwnedSampler {
            texture: LightTexture::new(&profile(dist)?)?,
            filter: Filter::CatmullRom,
            name: NAME.into(),
        }))
    }

    /// A candidate of the jobs that choose the smallest representation good
    /// enough (`tradeoff`, `plan`, `batch --compact`) for a file that stores
    /// more than one plane: on rotationally symmetric data it is the
    /// Catmull–Rom filter under another name. Not one of `compare`'s default
    /// reconstructions of the measured grid.
    fn candidates(&self, job: &super::Job<'_>) -> Vec<u32> {
        match job.declared_symmetry() {
            Some(s) if s != Symmetry::Rotational => vec![0],
            _ => Vec::new(),
        }
    }

    fn defaults(&self) -> Vec<u32> {
        vec![0]
    }

    fn evaluates_on_gpu(&self) -> bool {
        true
    }

    fn build_gpu(
        &self,
        dist: &Distribution,
        _: u32,
        device: &'static dyn GpuDevice,
    ) -> Result<Box<dyn IntensityField>, ModelError> {
        let rendered = render(&LightTexture::new(&profile(dist)?)?, Filter::CatmullRom, 5)?;
        device
            .texture_field(&rendered, None, Precision::F32, Lookup::Bilinear)
            .map_err(|e| ModelError::gpu(format!("{NAME}+gpu"), e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Data the same in every plane is its own mean; a plane-dependent one is
    /// averaged with the arc weights (a cos C term averages out).
    #[test]
    fn the_profile_is_the_arc_weighted_mean() {
        let dist = super::super::tests::cosine_p5();
        let field = CMean.build(&dist, 0).unwrap();
        // The same as the Catmull-Rom filter on the measured grid, which is the same in every plane.
        let measured = LightTexture::new(&dist).unwrap();
        for (c, g) in [(0.0, 0.0), (77.0, 12.5), (200.0, 40.0), (359.0, 89.0), (10.0, 135.0)] {
            let want = measured.sampler(Filter::CatmullRom).cd(c, g);
            assert!((field.intensity_cd(c, g) - want).abs() < 1e-9 * 1000.0, "{c} {g}");
        }
        // I = 100 + 50 cos C on uneven planes 0, 90, 180, 270 and 300: arcs 75, 90, 90, 60, 45.
        let c = vec![0.0, 90.0, 180.0, 270.0, 300.0];
        let gamma = vec![0.0, 90.0, 180.0];
        let cd: Vec<f64> = c
            .iter()
            .flat_map(|a: &f64| [100.0 + 50.0 * a.to_radians().cos(); 3])
            .collect();
        let d = Distribution::new(c, gamma, cd, Symmetry::None).unwrap();
        let p = profile(&d).unwrap();
        let want = (75.0 * 150.0 + 90.0 * 100.0 + 90.0 * 50.0 + 60.0 * 100.0 + 45.0 * 125.0) / 360.0;
        assert!((p.value_cd(0, 1) - want).abs() < 1e-9, "{} vs {want}", p.value_cd(0, 1));
        assert_eq!(p.symmetry(), Symmetry::Rotational);
        assert_eq!(
            field.bytes(),
            LightTexture::new(&profile(&dist).unwrap()).unwrap().bytes()
        );
    }
}
