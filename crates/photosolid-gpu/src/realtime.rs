//! The real-time path of Wallner 2008 (§4–5): a light distribution
//! texture in a float texture, sampled by the hardware for a batch of
//! directions, and the accuracy that costs.
//!
//! A [`RealtimeTexture`] uploads the texels of a
//! [`crate::reconstruct::StoredTexture`] (a render of the LDT,
//! I / I_max, whole or only its symmetry's C sector) as an `R32Float`
//! texture when the adapter can filter it (`FLOAT32_FILTERABLE`), else as
//! `R16Float` (values rounded to f16); a quantised or BC6H store as
//! `R16Unorm`, `R8Unorm` or `Bc6hRgbUfloat` (its blocks padded to whole
//! 4 × 4, a padding the shader never reads: it applies the address modes
//! itself), with a sampler, and evaluates a
//! [`HardwareLookup`] in a compute shader (`realtime.wgsl`: Wallner's (2008)
//! texture-coordinate mapping, equations 1–3, `textureSampleLevel`).
//!
//! [`RealtimeTexture::exact`] is the CPU twin: the same texel data (after
//! the same f16 rounding) read with the exact filter
//! ([`Lookup::Bilinear`] / [`Lookup::CatmullRom`] in f64), so the difference
//! of the two is the cost of hardware filtering alone (fixed-point
//! sub-texel weights, f32 coordinates), measured per adapter with
//! [`super::precision::subtexel_precision`].

use std::time::Duration;

use glam::DVec3;

use super::batch::direction_data;
pub use super::batch::LookupBatch;
use super::{GpuContext, GpuError};
use crate::model::{frame, IntensityField, Symmetry};
use crate::reconstruct::{Lookup, Precision, Rendered, StoredTexture};

/// How the hardware reads the texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum HardwareLookup {
    /// One fetch with a nearest sampler (`GL_NEAREST`).
    Nearest,
    /// One fetch with the hardware's bilinear filter (`GL_LINEAR`).
    Linear,
    /// Catmull–Rom from 9 bilinear fetches (3 per axis: the outer texels at
    /// their centres, the middle pair merged; Sigg & Hadwiger's linear-fetch
    /// trick adapted to an interpolating kernel, see `realtime.wgsl`).
    CatmullRomLinearFetch,
}

impl HardwareLookup {
    /// Every hardware lookup.
    pub const ALL: [HardwareLookup; 3] = [
        HardwareLookup::Nearest,
        HardwareLookup::Linear,
        HardwareLookup::CatmullRomLinearFetch,
    ];

    /// The exact CPU lookup this one approximates.
    pub fn exact(self) -> Lookup {
        match self {
            HardwareLookup::Nearest => Lookup::Nearest,
            HardwareLookup::Linear => Lookup::Bilinear,
            HardwareLookup::CatmullRomLinearFetch => Lookup::CatmullRom,
        }
    }

    /// The hardware lookup for an exact one.
    pub fn for_lookup(lookup: Lookup) -> Self {
        match lookup {
            Lookup::Nearest => HardwareLookup::Nearest,
            Lookup::Bilinear => HardwareLookup::Linear,
            Lookup::CatmullRom => HardwareLookup::CatmullRomLinearFetch,
        }
    }

    /// Texture fetches per sample.
    pub fn fetches(self) -> usize {
        match self {
            HardwareLookup::CatmullRomLinearFetch => 9,
            _ => 1,
        }
    }

    fn mode(self) -> u32 {
        match self {
            HardwareLookup::Nearest => 0,
            HardwareLookup::Linear => 1,
            HardwareLookup::CatmullRomLinearFetch => 2,
        }
    }
}

/// The probe mode of the shader: raw (u, v) coordinates, one linear fetch.
pub(crate) const MODE_PROBE: u32 = 3;

/// Wallner's (2008) texture coordinates (s, t) of direction `d` in the luminaire
/// frame, literally as its equations 1–3 (f64): `s = arccos(n₀·d)/π`,
/// `φ = arccos(r₀·p)` with p the unit projection of d onto the (r₀, u₀)
/// plane, `t = φ/2π` when `u₀·d > 0`, else `1 − φ/2π`; n₀ = −z, r₀ = +x,
/// u₀ = +y. Dimensionless, s ∈ [0, 1], t ∈ [0, 1]; `None` for a zero or
/// non-finite vector. At the poles (p = 0) φ is taken as 0. The shader
/// evaluates the same angles in atan2 form (see `realtime.wgsl`).
pub fn seed_texture_coords(d: DVec3) -> Option<(f64, f64)> {
    let len = d.length();
    if !(len.is_finite() && len > 0.0) {
        return None;
    }
    let d = d / len;
    let (n0, r0, u0) = (DVec3::NEG_Z, DVec3::X, DVec3::Y);
    let s = n0.dot(d).clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
    let p = d.dot(r0) * r0 + d.dot(u0) * u0;
    let phi = if p.length() > 0.0 {
        r0.dot(p / p.length()).clamp(-1.0, 1.0).acos()
    } else {
        0.0
    };
    let w = 0.5 * phi / std::f64::consts::PI;
    let t = if u0.dot(d) <= 0.0 { 1.0 - w } else { w };
    Some((s, t))
}

/// The real-time pipeline and its bind group layout (one per device).
pub(crate) struct Pipelines {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl Pipelines {
    /// The pipeline of `ctx`, built on first use; a validation error (a
    /// driver that cannot compile the shader) is returned, not raised.
    fn of(ctx: &GpuContext) -> Result<&Pipelines, GpuError> {
        super::batch::built_once(&ctx.realtime, ctx, "real-time lookup", Pipelines::new)
    }

    fn new(ctx: &GpuContext) -> Self {
        let d = &ctx.device;
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        };
        let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("realtime"),
            entries: &[
                entry(
                    0,
                    wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                ),
                // One sampler per texture: GL pairs each texture with one sampler.
                entry(1, wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)),
                super::batch::buffer_entry(2, wgpu::BufferBindingType::Storage { read_only: true }),
                super::batch::buffer_entry(3, wgpu::BufferBindingType::Storage { read_only: false }),
                super::batch::buffer_entry(4, wgpu::BufferBindingType::Uniform),
            ],
        });
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("realtime"),
            source: wgpu::ShaderSource::Wgsl(include_str!("realtime.wgsl").into()),
        });
        let pl = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("realtime"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("realtime"),
            layout: Some(&pl),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Pipelines { layout, pipeline }
    }
}

/// A stored texture on the device, with its samplers, read with a [`HardwareLookup`].
pub struct RealtimeTexture<'a> {
    ctx: &'a GpuContext,
    view: wgpu::TextureView,
    /// Linear, or nearest for [`HardwareLookup::Nearest`].
    sampler: wgpu::Sampler,
    format: wgpu::TextureFormat,
    lookup: HardwareLookup,
    /// Shader parameters after `n`, `mode`, `dispatch_x`: fold code, then sizes.
    fold: u32,
    /// The device texture's (width, height), texels: the stored texels, padded
    /// to whole 4 × 4 blocks for BC6H.
    texture_size: (usize, usize),
    exact: StoredTexture,
}

impl std::fmt::Debug for RealtimeTexture<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RealtimeTexture")
            .field("adapter", self.ctx.adapter())
            .field("format", &self.format)
            .field("lookup", &self.lookup)
            .finish_non_exhaustive()
    }
}

/// The texture format and the bytes to upload for `exact`'s texels: f32,
/// f16, or the normalised integers of the largest texel (already on their
/// steps in `exact`).
///
/// # Errors
/// [`GpuError::InvalidJob`] for a BC6H texture without its blocks (the
/// encoder not built in; [`RealtimeTexture::new`] stores such a row in f16).
fn upload_texels(exact: &StoredTexture) -> Result<(wgpu::TextureFormat, Vec<u8>), GpuError> {
    Ok(match exact.precision() {
        Precision::F32 => (
            wgpu::TextureFormat::R32Float,
            bytemuck::cast_slice(exact.texels()).to_vec(),
        ),
        Precision::F16 => {
            let v: Vec<u16> = exact
                .texels()
                .iter()
                .map(|&x| half::f16::from_f32(x).to_bits())
                .collect();
            (wgpu::TextureFormat::R16Float, bytemuck::cast_slice(&v).to_vec())
        }
        // The stored texels are already on the format's steps of the largest texel.
        Precision::U16 => {
            let scale = exact.unorm_scale();
            let v: Vec<u16> = exact
                .texels()
                .iter()
                .map(|&x| unorm(x, scale, 65_535.0) as u16)
                .collect();
            (wgpu::TextureFormat::R16Unorm, bytemuck::cast_slice(&v).to_vec())
        }
        Precision::Bc6h => match exact.bc6h_blocks() {
            Some(blocks) => (wgpu::TextureFormat::Bc6hRgbUfloat, blocks.to_vec()),
            None => {
                return Err(GpuError::InvalidJob {
                    index: 0,
                    reason: "a BC6H texture without its blocks".into(),
                })
            }
        },
        Precision::U8 => {
            let scale = exact.unorm_scale();
            let v: Vec<u8> = exact.texels().iter().map(|&x| unorm(x, scale, 255.0) as u8).collect();
            (wgpu::TextureFormat::R8Unorm, v)
        }
    })
}

/// The integer a normalised-integer texel `x` (I / I_max) stores: `x / scale`
/// in `steps` (0 for an all-zero texture).
fn unorm(x: f32, scale: f32, steps: f32) -> f32 {
    if scale > 0.0 {
        (x / scale * steps).round().clamp(0.0, steps)
    } else {
        0.0
    }
}

impl<'a> RealtimeTexture<'a> {
    /// Upload `rendered` (only `reduced`'s C sector when given) in
    /// `precision` (`F32` becomes `F16` when the adapter cannot filter
    /// `R32Float`; [`RealtimeTexture::precision`] says which was used), to
    /// be read with `lookup`.
    ///
    /// # Errors
    /// [`GpuError::TooLarge`] when the texture exceeds the device's 2D
    /// texture size; [`GpuError::InvalidJob`] for an empty texture.
    pub fn new(
        ctx: &'a GpuContext,
        rendered: &Rendered,
        reduced: Option<Symmetry>,
        precision: Precision,
        lookup: HardwareLookup,
    ) -> Result<Self, GpuError> {
        let precision = match precision {
            Precision::F32 if !ctx.float32_filterable() => Precision::F16,
            Precision::U16 if !ctx.unorm16() => Precision::F16,
            Precision::Bc6h if !ctx.bc_compression() => Precision::F16,
            p => p,
        };
        // The sizes come from an f16 store (cheap), checked before the slow BC6H encoder runs.
        let mut exact = StoredTexture::new(rendered, reduced, Precision::F16, lookup.exact());
        let (h, (_, cols)) = (exact.height(), exact.stored_columns());
        if h == 0 || cols == 0 {
            return Err(GpuError::InvalidJob {
                index: 0,
                reason: "empty texture".into(),
            });
        }
        // A BC6H texture is whole 4 x 4 blocks on the device; the shader addresses
        // the stored texels inside it and never reads the padding.
        let texture_size = match precision {
            Precision::Bc6h => (cols.next_multiple_of(4), h.next_multiple_of(4)),
            _ => (cols, h),
        };
        let max = ctx.limits.max_texture_dimension_2d as usize;
        if texture_size.0 > max || texture_size.1 > max {
            let (w, th) = texture_size;
            return Err(GpuError::TooLarge {
                index: 0,
                reason: format!("a {w} x {th} texture exceeds the device's {max} texels per side"),
            });
        }
        if precision != Precision::F16 {
            exact = StoredTexture::new(rendered, reduced, precision, lookup.exact());
        }
        let (format, bytes) = upload_texels(&exact)?;
        let fold = exact.reduced().map_or(0, |s| s.isym() as u32);
        Pipelines::of(ctx)?;
        let filter = if lookup == HardwareLookup::Nearest {
            wgpu::FilterMode::Nearest
        } else {
            wgpu::FilterMode::Linear
        };
        let (view, sampler) = upload(ctx, format, &bytes, texture_size, filter);
        Ok(RealtimeTexture {
            texture_size,
            ctx,
            view,
            sampler,
            format,
            lookup,
            fold,
            exact,
        })
    }

    /// The adapter it lives on.
    pub fn context(&self) -> &'a GpuContext {
        self.ctx
    }
    /// The texture format used (`R32Float`, `R16Float`, `R16Unorm` or `R8Unorm`).
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }
    /// The storage precision used.
    pub fn precision(&self) -> Precision {
        self.exact.precision()
    }
    /// The hardware lookup.
    pub fn lookup(&self) -> HardwareLookup {
        self.lookup
    }
    /// The CPU twin: the same texels read with the exact lookup (f64).
    pub fn exact(&self) -> &StoredTexture {
        &self.exact
    }

    /// Upload `dirs` (luminaire frame, any length; zero vectors give 0) for
    /// [`RealtimeTexture::run`].
    ///
    /// # Errors
    /// [`GpuError::TooLarge`] when the batch exceeds the device's binding or dispatch limits.
    pub fn prepare(&self, dirs: &[DVec3]) -> Result<LookupBatch, GpuError> {
        self.prepare_raw(&direction_data(dirs), self.lookup.mode())
    }

    pub(crate) fn prepare_raw(&self, data: &[[f32; 4]], mode: u32) -> Result<LookupBatch, GpuError> {
        let (h, (first, cols)) = (self.exact.height(), self.exact.stored_columns());
        let (texture_width, texture_height) = self.texture_size;
        let mut params = [0u32; 12];
        params[1] = mode;
        params[2] = self.fold;
        let sizes = [h, self.exact.full_width(), first, cols, texture_width, texture_height];
        for (p, v) in params[4..10].iter_mut().zip(sizes) {
            *p = (v as f32).to_bits();
        }
        let buffers = super::batch::upload(self.ctx, "realtime", data, params)?;
        let pipes = Pipelines::of(self.ctx)?;
        let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
        let bind_group = self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("realtime"),
            layout: &pipes.layout,
            entries: &[
                entry(0, wgpu::BindingResource::TextureView(&self.view)),
                entry(1, wgpu::BindingResource::Sampler(&self.sampler)),
                entry(2, buffers.input.as_entire_binding()),
                entry(3, buffers.output.as_entire_binding()),
                entry(4, buffers.uniform.as_entire_binding()),
            ],
        });
        Ok(LookupBatch::new(buffers, &pipes.pipeline, bind_group))
    }

    /// Run the lookups of an uploaded batch and wait for them; returns the
    /// wall time from submission to completion.
    pub fn run(&self, batch: &LookupBatch) -> Result<Duration, GpuError> {
        batch.run(self.ctx)
    }

    /// The results of the last [`RealtimeTexture::run`] of `batch`: I / I_max per direction.
    pub fn read(&self, batch: &LookupBatch) -> Result<Vec<f32>, GpuError> {
        batch.read(self.ctx)
    }

    /// Intensity (cd, ≥ 0) in each direction of `dirs` (luminaire frame):
    /// one upload, one dispatch, one read-back.
    ///
    /// # Errors
    /// As [`RealtimeTexture::prepare`], and device errors.
    pub fn sample_dirs_cd(&self, dirs: &[DVec3]) -> Result<Vec<f64>, GpuError> {
        let batch = self.prepare(dirs)?;
        self.run(&batch)?;
        // A normalised-integer texel of 1 is the largest texel, not I_max.
        let i_max = self.exact.i_max_cd() * f64::from(self.exact.unorm_scale());
        Ok(self.read(&batch)?.into_iter().map(|v| f64::from(v) * i_max).collect())
    }

    /// Median wall time (ns) per direction of the dispatch alone (the
    /// directions uploaded once, results not read back) over `repeats` runs.
    ///
    /// # Errors
    /// As [`RealtimeTexture::prepare`], and device errors.
    pub fn dispatch_ns_per_sample(&self, dirs: &[DVec3], repeats: usize) -> Result<f64, GpuError> {
        self.prepare(dirs)?.dispatch_ns_per_sample(self.ctx, repeats)
    }

    /// [`RealtimeTexture::sample_dirs_cd`] at (C, γ) degrees.
    pub fn sample_angles_cd(&self, angles: &[(f64, f64)]) -> Result<Vec<f64>, GpuError> {
        let dirs: Vec<DVec3> = angles.iter().map(|&(c, g)| frame::direction(c, g)).collect();
        self.sample_dirs_cd(&dirs)
    }
}

/// Create the texture (`cols` x `rows`, row-major `bytes`) and its sampler:
/// C repeats (or mirrors at a reduced sector's edges), γ clamps.
fn upload(
    ctx: &GpuContext,
    format: wgpu::TextureFormat,
    bytes: &[u8],
    (cols, rows): (usize, usize),
    filter: wgpu::FilterMode,
) -> (wgpu::TextureView, wgpu::Sampler) {
    let size = wgpu::Extent3d {
        width: cols as u32,
        height: rows as u32,
        depth_or_array_layers: 1,
    };
    let tex = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("light distribution texture"),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    // Rows of texels, or of 4 x 4 blocks for a block-compressed format (BC6H).
    let (block_w, block_h) = format.block_dimensions();
    let block_bytes = format.block_copy_size(None).unwrap_or(4);
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &tex,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some((cols as u32).div_ceil(block_w) * block_bytes),
            rows_per_image: Some((rows as u32).div_ceil(block_h)),
        },
        size,
    );
    // The shader applies the address modes itself (`texel_fetch` in realtime.wgsl)
    // and samples inside the stored texels only.
    let sampler = ctx.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("light distribution texture"),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: filter,
        min_filter: filter,
        ..Default::default()
    });
    (tex.create_view(&Default::default()), sampler)
}

/// The hardware lookup as an intensity field (cd). Batches
/// ([`IntensityField::sample_grid`], [`IntensityField::intensity_batch_cd`])
/// are one dispatch each; a single direction is a dispatch of its own
/// (correct, but slow: use batches). A device error gives 0 (the field has
/// no error channel); [`RealtimeTexture::sample_dirs_cd`] reports it.
impl IntensityField for RealtimeTexture<'_> {
    super::batch::gpu_sampling_methods!(clamp_gamma: true);
    fn name(&self) -> String {
        format!("{}+gpu", self.exact.name())
    }
    fn bytes(&self) -> usize {
        self.exact.texel_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Equations 1–3 give s = γ/180 and t = C/360 in the crate's frame.
    #[test]
    fn seed_coords_are_the_frame_angles() {
        for (c, g) in [
            (0.0, 0.0),
            (10.0, 30.0),
            (90.0, 90.0),
            (135.0, 120.0),
            (200.0, 45.0),
            (359.0, 179.0),
        ] {
            let (s, t) = seed_texture_coords(frame::direction(c, g)).unwrap();
            assert!((s - g / 180.0).abs() < 1e-9, "({c}, {g}): s {s}");
            if g > 0.0 && g < 180.0 {
                assert!((t - c / 360.0).abs() < 1e-9, "({c}, {g}): t {t}");
            }
        }
        // C = 0 (u0 . d = 0): t = 1, the same texel column as 0 under REPEAT.
        let (_, t) = seed_texture_coords(DVec3::new(1.0, 0.0, -1.0)).unwrap();
        assert_eq!(t, 1.0);
        assert!(seed_texture_coords(DVec3::ZERO).is_none());
        assert!(seed_texture_coords(DVec3::new(f64::NAN, 0.0, 1.0)).is_none());
    }

    #[test]
    fn hardware_lookup_names() {
        for l in HardwareLookup::ALL {
            assert_eq!(HardwareLookup::for_lookup(l.exact()), l);
        }
        assert_eq!(HardwareLookup::CatmullRomLinearFetch.fetches(), 9);
    }
}
