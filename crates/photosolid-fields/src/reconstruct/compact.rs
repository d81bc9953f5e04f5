//! The compact representations as one type: what a renderer stores in a
//! few hundred bytes instead of a texture, and what the GPU's compute
//! shader evaluates beside the texture lookups (`gpu::compact`).

use glam::DVec3;

use super::{Lobes, ShField};
use crate::model::{IntensityField, Rim};

/// A spherical-harmonic series or a mixture of cosine-power lobes.
#[derive(Debug, Clone, PartialEq)]
pub enum Compact {
    /// A spherical-harmonic series ([`ShField`], `sh:L`).
    Sh(ShField),
    /// A mixture of cosine-power lobes ([`Lobes`], `lobes:K`).
    Lobes(Lobes),
}

impl Compact {
    /// The representation as an intensity field (cd).
    pub fn field(&self) -> &dyn IntensityField {
        match self {
            Compact::Sh(s) => s,
            Compact::Lobes(l) => l,
        }
    }
}

impl IntensityField for Compact {
    fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        self.field().intensity_cd(c_deg, gamma_deg)
    }
    fn intensity_dir_cd(&self, d: DVec3) -> f64 {
        self.field().intensity_dir_cd(d)
    }
    fn name(&self) -> String {
        self.field().name()
    }
    fn form(&self) -> Option<String> {
        self.field().form()
    }
    fn bytes(&self) -> usize {
        self.field().bytes()
    }
    fn is_continuous(&self) -> bool {
        self.field().is_continuous()
    }
    fn rims(&self) -> Option<Vec<Rim>> {
        self.field().rims()
    }
    fn intensity_outside_rim_cd(&self, source: usize, u: DVec3) -> f64 {
        self.field().intensity_outside_rim_cd(source, u)
    }
}
