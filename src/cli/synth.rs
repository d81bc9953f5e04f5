//! `photosolid synth KIND [params] -o FILE`: analytic distributions as .ldt or .ies.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use photosolid::jobs::{self, SynthSettings};
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
    /// Print what was written as JSON: `output`, `exact_flux_lm` (where the distribution has one), `warnings`.
    #[arg(long)]
    json: bool,
}

pub fn run(a: SynthArgs) -> anyhow::Result<i32> {
    super::check_output("-o", &a.output)?;
    let name = a
        .kind
        .to_possible_value()
        .map(|v| v.get_name().to_string())
        .unwrap_or_default();
    let kind = Synth::named(&name, a.p, a.cutoff).ok_or_else(|| anyhow::anyhow!("unknown kind {name}"))?;
    let mut grid = GridSpec::uniform(a.c_step, a.gamma_step)?;
    if let Some(c) = a.c_list {
        grid.c = c;
    }
    if let Some(g) = a.gamma_list {
        grid.gamma = g;
    }
    let settings = SynthSettings {
        kind,
        intensity_cd: a.intensity,
        grid,
    };
    let written = jobs::synth(&a.output, &settings).map_err(|e| match e {
        photosolid::Error::Model(_) => anyhow::Error::from(e).context("building the distribution"),
        e => e.into(),
    })?;
    if a.json {
        super::emit(true, &written, "")?;
    }
    match written.exact_flux_lm {
        Some(f) => eprintln!("wrote {} (exact flux {f:.4} lm)", a.output.display()),
        None => eprintln!("wrote {}", a.output.display()),
    }
    Ok(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind the CLI offers is one the library names, under the same word.
    #[test]
    fn every_kind_is_a_library_kind() {
        for kind in Kind::value_variants() {
            let name = kind
                .to_possible_value()
                .map(|v| v.get_name().to_string())
                .unwrap_or_default();
            let synth = Synth::named(&name, 2.0, 60.0).unwrap_or_else(|| panic!("{name}"));
            assert_eq!(synth.name(), name);
        }
        assert_eq!(Kind::value_variants().len(), Synth::NAMES.len());
    }
}
