//! The GPU path's errors ([`GpuError`]).

use super::{Error, LayerError, Layered};

/// Errors of the GPU path. A program without an installed device
/// ([`crate::device::install`]) gets [`GpuError::NotBuilt`] when it asks for the GPU.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GpuError {
    /// No adapter on any of the tried backends.
    #[error(
        "no GPU adapter found (backends tried: {tried}; {detail}); install a Vulkan or GL driver, e.g. Mesa's \
         software drivers (`apt-get install mesa-vulkan-drivers libvulkan1 libegl-mesa0`, see \
         scripts/install-gpu-drivers.sh), or use --backend cpu"
    )]
    NoAdapter {
        /// Backends that were tried.
        tried: String,
        /// wgpu's last message.
        detail: String,
    },
    /// Device creation, a submission or a wait failed.
    #[error("GPU device error: {0}")]
    Device(String),
    /// A shader or pipeline could not be created (a driver that cannot compile it).
    #[error("GPU pipeline error: {0}")]
    Pipeline(String),
    /// A read-back buffer could not be mapped or read.
    #[error("GPU read-back error: {0}")]
    BufferMap(String),
    /// A job is malformed.
    #[error("render job {index}: {reason}")]
    InvalidJob {
        /// Index of the job in the batch.
        index: usize,
        /// What is wrong.
        reason: String,
    },
    /// A single job does not fit the device's limits.
    #[error("render job {index} is too large for this device: {reason}")]
    TooLarge {
        /// Index of the job in the batch.
        index: usize,
        /// Which limit.
        reason: String,
    },
    /// This build has no GPU support (cargo feature `gpu` off).
    #[error(
        "no GPU device: this photosolid was built without GPU support (cargo feature `gpu`), or the program \
         installed none (`photosolid::gpu::install()`)"
    )]
    NotBuilt,
}

impl GpuError {
    /// The stable code of this error in [`super::ErrorRecord::code`] (`gpu-no-adapter`, ...).
    pub fn code(&self) -> &'static str {
        match self {
            GpuError::NoAdapter { .. } => "gpu-no-adapter",
            GpuError::Device(_) => "gpu-device",
            GpuError::Pipeline(_) => "gpu-pipeline",
            GpuError::BufferMap(_) => "gpu-buffer-map",
            GpuError::InvalidJob { .. } => "gpu-invalid-job",
            GpuError::TooLarge { .. } => "gpu-too-large",
            GpuError::NotBuilt => "gpu-not-built",
        }
    }
}

impl LayerError for GpuError {
    fn code(&self) -> &'static str {
        GpuError::code(self)
    }
}

impl From<GpuError> for Error {
    fn from(e: GpuError) -> Self {
        Error::Layer(Layered::new(e))
    }
}
