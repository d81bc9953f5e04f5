//! `photosolid synth KIND [params] -o FILE`: analytic distributions as .ldt or .ies.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, ValueEnum};
use photosolid::synth::{GridSpec, Synth};

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Kind {
    Isotropic,
    Lambertian,
    CosinePower,
    Spot,
    Batwing,
    Roadway,
}

#[derive(Args, Debug)]
pub struct SynthArgs {
    /// Distribution kind.
    kind: Kind,
    /// Exponent p (cosine-power, spot).
    #[arg(long, default_value_t = 1.0, value_parser = super::parse::non_negative)]
    p: f64,
    /// Cut-off angle in degrees (spot), in (0, 90].
    #[arg(long, default_value_t = 90.0, value_parser = super::parse::positive)]
    cutoff: f64,
    /// Peak intensity, cd.
    #[arg(long, default_value_t = 1000.0, value_parser = super::parse::positive)]
    intensity: f64,
    /// C step of a uniform grid, degrees.
    #[arg(long, default_value_t = 15.0, value_parser = super::parse::positive)]
    c_step: f64,
    /// Gamma step of a uniform grid, degrees.
    #[arg(long, default_value_t = 5.0, value_parser = super::parse::positive)]
    gamma_step: f64,
    /// Explicit C angles (comma separated, degrees); overrides --c-step.
    #[arg(long, value_delimiter = ',')]
    c_list: Option<Vec<f64>>,
    /// Explicit gamma angles (comma separated, degrees); overrides --gamma-step.
    #[arg(long, value_delimiter = ',')]
    gamma_list: Option<Vec<f64>>,
    /// Output file (.ldt or .ies).
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(a: SynthArgs) -> anyhow::Result<i32> {
    super::check_output("-o", &a.output)?;
    let kind = match a.kind {
        Kind::Isotropic => Synth::Isotropic,
        Kind::Lambertian => Synth::Lambertian,
        Kind::CosinePower => Synth::CosinePower { p: a.p },
        Kind::Spot => Synth::Spot {
            p: a.p,
            cutoff_deg: a.cutoff,
        },
        Kind::Batwing => Synth::Batwing,
        Kind::Roadway => Synth::Roadway,
    };
    let mut grid = GridSpec::uniform(a.c_step, a.gamma_step)?;
    if let Some(c) = a.c_list {
        grid.c = c;
    }
    if let Some(g) = a.gamma_list {
        grid.gamma = g;
    }
    // The roadway's street side goes where the output format's readers take its front.
    let format = photosolid::model::Format::from_extension(&a.output).unwrap_or(photosolid::model::Format::Ldt);
    let lum = kind
        .build_for(format, &grid, a.intensity)
        .context("building the distribution")?;
    photosolid::save(&lum.clone().into(), &a.output, &Default::default())?;
    if let Some(f) = kind.exact_flux(a.intensity) {
        eprintln!("wrote {} (exact flux {f:.4} lm)", a.output.display());
    } else {
        eprintln!("wrote {}", a.output.display());
    }
    Ok(0)
}
