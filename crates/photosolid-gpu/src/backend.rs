//! `--backend auto|gpu|cpu`: which renderer to use ([`Backend`] is
//! `crate::reconstruct::Backend`, known without the `gpu` feature too).

use super::{GpuContext, GpuError};

pub use crate::reconstruct::Backend;

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
