//! The job of `mesh`: a reconstruction's photometric solid, on a fixed grid,
//! an adaptive grid within a tolerance, or a rendered texture.

use crate::error::Result;
use crate::model::Progress;
use crate::numfmt::PctOfPeak;
use crate::registry::{Recon, Reconstructions};
use crate::solid::adaptive::{AdaptiveGrid, DEFAULT_TOLERANCE_PCT};
use crate::solid::{texture_solid, AdaptiveOptions, ColorMap, Mesh, Refinement, Tolerance, Units, UnitsName};

use super::option_error;
use super::Named;

/// The options of `mesh` (the CLI's flags; defaults are the CLI's).
#[derive(Clone, Debug, PartialEq)]
pub struct MeshSettings {
    /// `--filter F` (a filter or `fitted-gl`), or `measured` for `--measured`.
    pub recon: Recon,
    /// `--texture`: the solid of the filter's rendered float texture (a filter only).
    pub texture: bool,
    /// `--factor`: a fixed grid, each measured interval cut into this many steps
    /// (with `texture`: the render factor, default 5). None: the adaptive grid.
    pub factor: Option<usize>,
    /// `--tolerance`: the adaptive grid's largest radial deviation, a percent of
    /// I_max (None: 0.1%); excluded by `factor` and `texture`.
    pub tolerance: Option<PctOfPeak>,
    /// `--units`: cd, peak, klm or flux.
    pub units: UnitsName,
    /// `--color`: per-vertex viridis colour of intensity.
    pub color: bool,
}

impl Default for MeshSettings {
    fn default() -> Self {
        Self {
            recon: Recon::Filter(crate::reconstruct::Filter::CatmullRom),
            texture: false,
            factor: None,
            tolerance: None,
            units: UnitsName::Cd,
            color: false,
        }
    }
}

impl MeshSettings {
    /// The adaptive grid's tolerance, % of I_max.
    pub fn tolerance_pct(&self) -> f64 {
        self.tolerance.map_or(DEFAULT_TOLERANCE_PCT, PctOfPeak::pct)
    }

    fn check(&self) -> Result<()> {
        if self.tolerance.is_some() && (self.factor.is_some() || self.texture) {
            return Err(option_error(
                "--tolerance",
                "cannot be used with --factor or --texture (a fixed grid)",
            ));
        }
        if self.texture && !matches!(self.recon, Recon::Filter(_)) {
            return Err(option_error("--texture", format!("needs a filter, not {}", self.recon)));
        }
        Ok(())
    }
}

/// A built solid and how it was built.
#[derive(Debug)]
pub struct BuiltSolid {
    /// The solid, its source named after the file.
    pub mesh: Mesh,
    /// The adaptive grid it was built on, when it was.
    pub adaptive: Option<AdaptiveGrid>,
    /// The units of its coordinates.
    pub units: Units,
}

/// `photosolid mesh FILE`: the solid the settings ask for (not yet written).
pub fn mesh(file: Named<'_>, settings: &MeshSettings, progress: &Progress<'_>) -> Result<BuiltSolid> {
    settings.check()?;
    let d = file.document.distribution();
    let units = Units::resolve(settings.units, d, file.document.declared().lamp_flux_lm)?;
    let recon = settings.recon;
    let (mut mesh, adaptive) = match recon {
        Recon::Filter(f) if settings.texture => {
            let factor = u32::try_from(settings.factor.unwrap_or(5)).unwrap_or(u32::MAX);
            (texture_solid(d, f, factor, units)?, None)
        }
        Recon::Measured => (
            Reconstructions::new(d.clone(), &[recon])?.solid_in(recon, 1, units)?,
            None,
        ),
        _ => {
            let recs = Reconstructions::new(d.clone(), &[recon])?;
            match settings.factor {
                Some(factor) => (recs.solid_in(recon, factor, units)?, None),
                None => {
                    let tolerance =
                        Tolerance::PercentOfPeak(settings.tolerance.unwrap_or(PctOfPeak(DEFAULT_TOLERANCE_PCT)));
                    let field = recs.field(recon)?;
                    Refinement::Adaptive(AdaptiveOptions::new(tolerance))
                        .solid_with_progress(&*field, d, units, progress)?
                }
            }
        }
    };
    mesh.info_mut().source = file.name.to_string();
    if settings.color {
        mesh.colorize(ColorMap::Viridis);
    }
    Ok(BuiltSolid { mesh, adaptive, units })
}
