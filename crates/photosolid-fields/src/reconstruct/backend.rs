//! `--backend auto|gpu|cpu`: where a texture is rendered
//! (`photosolid::registry::render_on` is the one function that renders on the
//! chosen backend).
//!
//! The selection lives here, not in `crate::gpu`, so that a build without
//! the `gpu` feature still knows what `gpu` means (an error saying the
//! feature is off) and `auto` (the CPU).

use std::fmt;
use std::str::FromStr;

/// Renderer selection, as given on the command line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Backend {
    /// A GPU adapter (hardware or software) when one exists, else the CPU.
    #[default]
    Auto,
    /// A GPU adapter; an error when none exists.
    Gpu,
    /// The CPU; never touches wgpu.
    Cpu,
}

impl FromStr for Backend {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(Backend::Auto),
            "gpu" => Ok(Backend::Gpu),
            "cpu" => Ok(Backend::Cpu),
            other => Err(format!("unknown backend '{other}' (expected auto, gpu or cpu)")),
        }
    }
}

impl fmt::Display for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Backend::Auto => "auto",
            Backend::Gpu => "gpu",
            Backend::Cpu => "cpu",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spellings of `--backend`.
    #[test]
    fn backends_parse() {
        assert_eq!("auto".parse::<Backend>().unwrap(), Backend::Auto);
        assert_eq!("GPU".parse::<Backend>().unwrap(), Backend::Gpu);
        assert_eq!(" cpu ".parse::<Backend>().unwrap(), Backend::Cpu);
        assert!("cuda".parse::<Backend>().unwrap_err().contains("auto, gpu or cpu"));
        assert_eq!(Backend::default().to_string(), "auto");
    }
}
