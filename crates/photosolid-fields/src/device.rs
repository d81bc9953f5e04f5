//! The GPU as the layers above see it: a [`GpuDevice`] trait, implemented by
//! the `photosolid-gpu` crate (`photosolid_gpu::Wgpu`) and plugged in at start-up with
//! [`install`]. The registry, the comparisons, the trade table and the shaded-plane report ask
//! [`installed`] for the device instead of naming wgpu, so they hold no
//! `cfg(feature = "gpu")`: without a device, asking for the GPU is
//! [`GpuError::NotBuilt`] and `--backend auto` renders on the CPU.

use std::sync::{Arc, OnceLock};

use glam::DVec3;

use crate::error::GpuError;
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::{Backend, Compact, LightTexture, Lookup, Precision, RenderOptions, Rendered, TextureSpec};

/// Where [`GpuDevice::render`] rendered.
#[derive(Debug)]
pub enum DeviceRender {
    /// On the GPU: the texture and the adapter's name.
    Gpu {
        /// The texture.
        rendered: Rendered,
        /// The adapter, for the user.
        adapter: String,
    },
    /// Not on the GPU (`cpu` asked for, or `auto` without an adapter): the
    /// caller renders on the CPU; `notice` says why `auto` fell back.
    Cpu {
        /// One line for the user when `auto` fell back.
        notice: Option<&'static str>,
    },
}

/// The trade table's GPU columns of a stored texture read by the texture hardware.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureRow {
    /// The adapter.
    pub adapter: String,
    /// The texture format used (`R32Float` or `R16Float`).
    pub texture_format: String,
    /// The adapter's sub-texel weight precision, bits.
    pub subtexel_bits: f64,
    /// Median ns per direction of the dispatch alone.
    pub ns_per_sample_dispatch: f64,
    /// Largest |hardware − exact lookup on the same texels|, fraction of I_max.
    pub vs_exact_max: f64,
}

/// The trade table's GPU columns of a compact representation evaluated by a compute shader.
#[derive(Debug, Clone, PartialEq)]
pub struct CompactRow {
    /// The adapter.
    pub adapter: String,
    /// Median ns per direction of the dispatch alone.
    pub ns_per_sample_dispatch: f64,
    /// Largest |GPU − CPU (f64) evaluation of the same parameters|, cd.
    pub vs_exact_max_cd: f64,
}

/// Which processor a [`Backend`] selects on this machine ([`GpuDevice::select`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Selected {
    /// The GPU, this adapter.
    Gpu {
        /// The adapter's name and driver.
        adapter: String,
    },
    /// The CPU.
    Cpu {
        /// Why `auto` fell back to the CPU (one line for the user); `None` when the CPU was asked for.
        notice: Option<&'static str>,
    },
}

/// Where and how the texture hardware held the texels it read.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureStore {
    /// The adapter whose texture hardware read them.
    pub adapter: String,
    /// The texture format the texels were stored in (`R32Float`, ...).
    pub texture_format: String,
    /// The precision they were stored in: the one asked for, or `F16` where the adapter cannot
    /// filter that format (a CPU lookup of the same texels stores in this one).
    pub precision: Precision,
}

/// Intensities read by the texture hardware ([`GpuDevice::texture_samples`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TextureSamples {
    /// Intensity (cd) in each direction asked for, in order.
    pub cd: Vec<f64>,
    /// Where and how the texels were held.
    pub store: TextureStore,
}

/// What the layers above ask of a GPU.
pub trait GpuDevice: Send + Sync {
    /// Render `tex` with `options` where `backend` says (`auto`: the GPU when
    /// an adapter exists).
    ///
    /// # Errors
    /// [`GpuError`] when `gpu` was asked for and no adapter works, or the render fails.
    fn render(&self, backend: Backend, tex: &LightTexture, options: &RenderOptions) -> Result<DeviceRender, GpuError>;

    /// A rendered texture sampled by the texture hardware with `lookup`
    /// (stored with `reduced` symmetry and `precision`), as a field.
    ///
    /// # Errors
    /// [`GpuError`] when no adapter works or the texture cannot be made.
    fn texture_field(
        &self,
        rendered: &Rendered,
        reduced: Option<Symmetry>,
        precision: Precision,
        lookup: Lookup,
    ) -> Result<Box<dyn IntensityField>, GpuError>;

    /// A spherical-harmonic series or lobe mixture evaluated by a compute shader, as a field.
    ///
    /// # Errors
    /// [`GpuError`] when no adapter works or the pipeline fails.
    fn compact_field(&self, compact: Compact) -> Result<Box<dyn IntensityField>, GpuError>;

    /// The GPU columns of `spec`'s texture of `dist`, timed on `dirs` (`repeats`, median).
    ///
    /// # Errors
    /// [`GpuError`] as [`GpuDevice::texture_field`].
    fn texture_row(
        &self,
        dist: &Distribution,
        spec: TextureSpec,
        dirs: &[DVec3],
        repeats: usize,
    ) -> Result<TextureRow, GpuError>;

    /// The GPU columns of `compact`, timed on `dirs` (`repeats`, median).
    ///
    /// # Errors
    /// [`GpuError`] as [`GpuDevice::compact_field`].
    fn compact_row(&self, compact: Compact, dirs: &[DVec3], repeats: usize) -> Result<CompactRow, GpuError>;

    /// Which processor `backend` selects here: `gpu` without a working adapter is an error,
    /// `auto` then falls back to the CPU with a notice.
    ///
    /// # Errors
    /// [`GpuError`] when `gpu` was asked for and no adapter works.
    fn select(&self, backend: Backend) -> Result<Selected, GpuError>;

    /// `rendered` stored in `precision` and read by the texture hardware's `lookup` in each of
    /// `dirs` (luminaire frame, any length; zero vectors give 0), in one batch. Unlike the
    /// [`GpuDevice::texture_field`]'s per-call lookups, a failure is an error, not zeros.
    ///
    /// # Errors
    /// [`GpuError`] as [`GpuDevice::texture_field`], or when the batch exceeds the device's limits.
    fn texture_samples(
        &self,
        rendered: &Rendered,
        precision: Precision,
        lookup: Lookup,
        dirs: &[DVec3],
    ) -> Result<TextureSamples, GpuError>;
}

static DEVICE: OnceLock<Arc<dyn GpuDevice>> = OnceLock::new();

/// Plug `device` in for the process; `false` when one was installed already
/// (the first stays).
pub fn install(device: Arc<dyn GpuDevice>) -> bool {
    DEVICE.set(device).is_ok()
}

/// The installed device, if any.
pub fn installed() -> Option<&'static dyn GpuDevice> {
    DEVICE.get().map(|d| &**d)
}

/// The installed device, or [`GpuError::NotBuilt`].
///
/// # Errors
/// [`GpuError::NotBuilt`] when none is installed.
pub fn device() -> Result<&'static dyn GpuDevice, GpuError> {
    installed().ok_or(GpuError::NotBuilt)
}
