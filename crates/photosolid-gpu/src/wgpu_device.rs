//! [`Wgpu`]: this module as the [`crate::device::GpuDevice`] the layers above
//! ask for, and [`install`], which plugs it in.

use std::sync::Arc;

use glam::DVec3;

use super::compact::{compact_row, GpuCompact};
use super::precision::hardware_row;
use super::realtime::{HardwareLookup, RealtimeTexture};
use super::{render_gpu, resolve, GpuContext, GpuError, Resolved};
use crate::device::{CompactRow, DeviceRender, GpuDevice, Selected, TextureRow, TextureSamples, TextureStore};
use crate::model::{Distribution, IntensityField, Symmetry};
use crate::reconstruct::{Backend, Compact, LightTexture, Lookup, Precision, RenderOptions, Rendered, TextureSpec};

/// The headless wgpu device of the process ([`GpuContext::global`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Wgpu;

/// Plug [`Wgpu`] in as the process's GPU device ([`crate::device::install`]):
/// the `photosolid` binary does at start-up; a program that wants GPU
/// renders, `+gpu` reconstructions or the trade table's GPU rows calls it
/// once. `false` when a device was installed already.
pub fn install() -> bool {
    crate::device::install(Arc::new(Wgpu))
}

impl GpuDevice for Wgpu {
    fn render(&self, backend: Backend, tex: &LightTexture, options: &RenderOptions) -> Result<DeviceRender, GpuError> {
        Ok(match resolve(backend)? {
            Resolved::Gpu(ctx) => DeviceRender::Gpu {
                rendered: render_gpu(ctx, tex, options)?,
                adapter: ctx.adapter().to_string(),
            },
            Resolved::Cpu { notice } => DeviceRender::Cpu { notice },
        })
    }

    fn texture_field(
        &self,
        rendered: &Rendered,
        reduced: Option<Symmetry>,
        precision: Precision,
        lookup: Lookup,
    ) -> Result<Box<dyn IntensityField>, GpuError> {
        let ctx = GpuContext::global()?;
        let lookup = HardwareLookup::for_lookup(lookup);
        Ok(Box::new(RealtimeTexture::new(
            ctx, rendered, reduced, precision, lookup,
        )?))
    }

    fn compact_field(&self, compact: Compact) -> Result<Box<dyn IntensityField>, GpuError> {
        Ok(Box::new(GpuCompact::new(GpuContext::global()?, compact)?))
    }

    fn texture_row(
        &self,
        dist: &Distribution,
        spec: TextureSpec,
        dirs: &[DVec3],
        repeats: usize,
    ) -> Result<TextureRow, GpuError> {
        let h = hardware_row(GpuContext::global()?, dist, spec, dirs, repeats)?;
        Ok(TextureRow {
            adapter: h.precision.adapter,
            texture_format: h.texture_format,
            subtexel_bits: h.precision.bits,
            ns_per_sample_dispatch: h.ns_per_sample_dispatch,
            vs_exact_max: h.vs_exact_max,
        })
    }

    fn compact_row(&self, compact: Compact, dirs: &[DVec3], repeats: usize) -> Result<CompactRow, GpuError> {
        let ctx = GpuContext::global()?;
        let h = compact_row(&GpuCompact::new(ctx, compact)?, dirs, repeats)?;
        Ok(CompactRow {
            adapter: ctx.adapter().to_string(),
            ns_per_sample_dispatch: h.ns_per_sample_dispatch,
            vs_exact_max_cd: h.vs_exact_max_cd,
        })
    }

    fn select(&self, backend: Backend) -> Result<Selected, GpuError> {
        Ok(match resolve(backend)? {
            Resolved::Gpu(ctx) => Selected::Gpu {
                adapter: ctx.adapter().to_string(),
            },
            Resolved::Cpu { notice } => Selected::Cpu { notice },
        })
    }

    fn texture_samples(
        &self,
        rendered: &Rendered,
        precision: Precision,
        lookup: Lookup,
        dirs: &[DVec3],
    ) -> Result<TextureSamples, GpuError> {
        let ctx = GpuContext::global()?;
        let texture = RealtimeTexture::new(ctx, rendered, None, precision, HardwareLookup::for_lookup(lookup))?;
        Ok(TextureSamples {
            cd: texture.sample_dirs_cd(dirs)?,
            store: TextureStore {
                adapter: ctx.adapter().to_string(),
                texture_format: format!("{:?}", texture.format()),
                precision: texture.precision(),
            },
        })
    }
}
