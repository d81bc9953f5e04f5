//! `photosolid compare FILE [--vs OTHER] [--recon ...] [--against ...] [--normalize cd|peak|klm|flux]
//! [--align] [--directions measured|dense[:N]] [--tolerance PCT%] [--factor K | --solid-tolerance PCT%] [--json] [--report DIR]`.
//!
//! Without `--vs`: each reconstruction of FILE against the truth (`--against
//! truth`, the default for files written by `photosolid synth`, which record
//! their closed form), against FILE's own withheld measurements (`withheld`,
//! k-fold hold-out, the default otherwise), or against another
//! reconstruction of FILE (named as such). With `--vs OTHER` (a denser
//! measurement): against OTHER reconstructed by `--against` (default
//! catmull-rom), FILE first aligned onto OTHER with `--align`.
//! With `--vs`, the derived photometry of both files (flux, LOR, flux code, zonal
//! lumens, UGR, BUG, luminance) is printed side by side above the metrics
//! (JSON key `photometry_side_by_side`).
//! Metrics: see `photosolid::compare`; JSON keys: `photosolid::compare::Comparison`.

use std::path::PathBuf;

use clap::Args;
use photosolid::compare::{Against, Directions, Normalize};
use photosolid::jobs::{self, CompareSettings, Loaded};
use photosolid::registry::Recon;
use photosolid::report::compare_report;

use super::parse::PctOfPeak;
use super::{ReadArgs, ReportArgs};

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// A photometric file: .ies, .ldt, TM-33 .xml, or a GLDF photometry (FILE.gldf#ID; FILE.gldf when it holds one).
    file: PathBuf,
    /// Compare FILE's reconstructions with this file's reference instead of FILE's own.
    #[arg(long)]
    vs: Option<PathBuf>,
    /// Reconstructions of FILE (comma separated): measured, fitted-gl, filters, textures
    /// FILTER@xK/LOOKUP, spherical harmonics sh:L[+f16] (L 0-32; to 128 for data the same
    /// in every C-plane), lobe mixtures lobes:K (K 1-16), the mean γ profile over C c-mean;
    /// +gpu after a texture, sh:L, lobes:K or c-mean: evaluated by the GPU.
    #[arg(long, value_delimiter = ',')]
    recon: Option<Vec<Recon>>,
    /// The reference: truth (the closed form a synth file records), withheld
    /// (k-fold hold-out of FILE's measurements), or a reconstruction (measured,
    /// fitted-gl, a filter) of OTHER with --vs, of FILE without. Default: truth
    /// when FILE records it, else withheld; with --vs, catmull-rom of OTHER.
    #[arg(long)]
    against: Option<Against>,
    /// Folds of the withheld reference (k >= 2).
    /// [default: 2; with another reference, an `ignored-option` warning]
    #[arg(long)]
    folds: Option<usize>,
    /// Units the files are compared in (as `mesh --units`): cd (absolute), peak (I_max = 1), klm
    /// (cd per 1000 lm of the file's lamp flux, as in EULUMDAT; not for absolute photometry), flux
    /// (equal luminaire flux: cd per 1000 lm of the computed flux). `--normalize` is the older name.
    #[arg(long = "units", alias = "normalize", value_name = "UNIT", default_value = "cd")]
    normalize: Normalize,
    /// Search the best C rotation and mirror of FILE onto OTHER (with --vs).
    #[arg(long)]
    align: bool,
    /// Direction set of the radial metrics: measured, dense, dense:N (the radial max is then refined
    /// locally around the set's 32 largest errors).
    /// [default: dense:20000; under the withheld reference, which measures at the withheld
    /// points, a given set is an `ignored-option` warning]
    #[arg(long)]
    directions: Option<Directions>,
    /// Hausdorff tolerance, a percent of I_max with its sign (a bare number is refused).
    #[arg(long, default_value = "0.1%", value_parser = super::parse::pct_of_peak, allow_hyphen_values = true)]
    tolerance: PctOfPeak,
    /// Grid solids on a fixed grid, each measured interval cut into this many steps
    /// (default: adaptive grid solids within --solid-tolerance of their fields).
    #[arg(long, value_parser = super::parse::at_least_one, allow_negative_numbers = true)]
    factor: Option<usize>,
    /// Adaptive grid solids: the largest radial deviation of a solid from its field at the
    /// tested points, a percent of the reference I_max with its sign [default: 0.05%].
    #[arg(long, value_parser = super::parse::pct_of_peak, conflicts_with = "factor", allow_hyphen_values = true)]
    solid_tolerance: Option<PctOfPeak>,
    #[command(flatten)]
    out: ReportArgs,
    #[command(flatten)]
    read: ReadArgs,
}

pub fn run(a: CompareArgs) -> anyhow::Result<i32> {
    a.out.check()?;
    let file = Loaded::load(&a.file, &a.read.options())?;
    let vs = a.vs.as_ref().map(|p| Loaded::load(p, &a.read.options())).transpose()?;
    let settings = CompareSettings {
        recons: a.recon.clone(),
        against: a.against,
        folds: a.folds,
        units: a.normalize,
        align: a.align,
        directions: a.directions,
        tolerance: a.tolerance,
        factor: a.factor,
        solid_tolerance: a.solid_tolerance,
        plots: a.out.report.is_some(),
        // The command line offers the built-in representations.
        registry: photosolid::registry::Registry::builtin(),
    };
    let c = super::with_progress("reconstructions", |progress| {
        jobs::compare(file.named(), vs.as_ref().map(Loaded::named), &settings, progress)
    })?;
    a.out
        .emit(&c, &compare_report::to_text(&c), compare_report::write_report)?;
    Ok(0)
}
