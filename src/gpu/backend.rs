//! `--backend auto|gpu|cpu`: which renderer to use.

use std::fmt;
use std::str::FromStr;

use super::{GpuContext, GpuError};

/// Renderer selection, as given on the command line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
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

/// The outcome of [`resolve`].
#[derive(Debug, Clone, Copy)]
pub enum Resolved {
    /// Render on this device.
    Gpu(&'static GpuContext),
    /// Render on the CPU. `notice` is set when `auto` fell back (one line for
    /// the CLI to print), `None` when the CPU was asked for.
    Cpu {
        /// Why `auto` fell back to the CPU.
        notice: Option<&'static str>,
    },
}

impl Resolved {
    /// The GPU context, if the GPU was chosen.
    pub fn gpu(&self) -> Option<&'static GpuContext> {
        match self {
            Resolved::Gpu(c) => Some(c),
            Resolved::Cpu { .. } => None,
        }
    }
}

/// Resolve a [`Backend`] to a renderer. `Cpu` never initialises wgpu; `Auto`
/// and `Gpu` use the process-wide [`GpuContext::global`] (honouring
/// `WGPU_BACKEND`). `Gpu` without an adapter is an error naming the backends
/// and drivers tried; `Auto` then falls back to the CPU with a notice.
pub fn resolve(backend: Backend) -> Result<Resolved, GpuError> {
    static NOTICE: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    match backend {
        Backend::Cpu => Ok(Resolved::Cpu { notice: None }),
        Backend::Gpu => GpuContext::global().map(Resolved::Gpu),
        Backend::Auto => match GpuContext::global() {
            Ok(c) => Ok(Resolved::Gpu(c)),
            Err(e) => {
                let notice = NOTICE.get_or_init(|| format!("note: no usable GPU adapter, rendering on the CPU ({e})"));
                Ok(Resolved::Cpu {
                    notice: Some(notice.as_str()),
                })
            }
        },
    }
}
