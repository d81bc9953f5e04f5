//! [`render_on`]: render a texture on the backend chosen with `--backend`
//! ([`Backend`]: a GPU adapter through the installed [`crate::device`], or the CPU).

use crate::device::DeviceRender;
use crate::error::Error;
use crate::reconstruct::{render_with, Backend, LightTexture, RenderOptions, Rendered};

/// A texture rendered by [`render_on`], and where.
#[derive(Debug, Clone)]
pub struct RenderedOn {
    /// The texture (the same texels on every backend, up to f32 rounding).
    pub rendered: Rendered,
    /// Where it was rendered, for the user: `gpu: ADAPTER` or `cpu`.
    pub on: String,
    /// Set when `auto` fell back to the CPU: one line saying why.
    pub notice: Option<&'static str>,
}

/// Render `tex` on `backend`.
///
/// `Auto` uses a GPU adapter when one exists (honouring `WGPU_BACKEND`) and
/// otherwise the CPU, with a [`RenderedOn::notice`]; `Gpu` without an
/// adapter is an error naming the drivers tried. Without an installed GPU
/// device ([`crate::device::install`]; the binary installs wgpu's when built
/// with the `gpu` feature), `Auto` is the CPU and `Gpu` is
/// [`crate::error::GpuError::NotBuilt`].
///
/// # Errors
/// [`GpuError`](crate::error::GpuError) as above; the render's own errors (an invalid factor).
pub fn render_on(backend: Backend, tex: &LightTexture, options: &RenderOptions) -> Result<RenderedOn, Error> {
    let notice = match crate::device::installed() {
        Some(device) => match device.render(backend, tex, options)? {
            DeviceRender::Gpu { rendered, adapter } => {
                return Ok(RenderedOn {
                    rendered,
                    on: format!("gpu: {adapter}"),
                    notice: None,
                })
            }
            DeviceRender::Cpu { notice } => notice,
        },
        None => match backend {
            Backend::Gpu => return Err(crate::error::GpuError::NotBuilt.into()),
            _ => None,
        },
    };
    Ok(RenderedOn {
        rendered: render_with(tex, options)?,
        on: "cpu".to_string(),
        notice,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{GridSpec, Synth};

    /// `cpu` renders exactly what `render_with` does.
    #[test]
    fn cpu_renders_as_render_with() {
        let lum = Synth::Lambertian
            .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
            .unwrap();
        let tex = LightTexture::new(lum.distribution()).unwrap();
        let options = RenderOptions::default();
        let r = render_on(Backend::Cpu, &tex, &options).unwrap();
        assert_eq!((r.on.as_str(), r.notice), ("cpu", None));
        assert_eq!(r.rendered.data, render_with(&tex, &options).unwrap().data);
    }

    /// Without an installed device (none is in the library's unit tests), asking for the GPU is the
    /// typed `NotBuilt` error.
    #[test]
    fn gpu_without_a_device_is_not_built() {
        let lum = Synth::Lambertian
            .build(&GridSpec::uniform(15.0, 5.0).unwrap(), 1000.0)
            .unwrap();
        let tex = LightTexture::new(lum.distribution()).unwrap();
        let e = render_on(Backend::Gpu, &tex, &RenderOptions::default()).unwrap_err();
        assert_eq!(e.downcast_ref(), Some(&crate::error::GpuError::NotBuilt), "{e}");
        assert_eq!(crate::error::ErrorRecord::from(&e).code, "gpu-not-built");
    }
}
