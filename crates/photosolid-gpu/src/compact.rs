//! The compact representations evaluated by the GPU beside the texture
//! lookups (issue 30): a spherical-harmonic series
//! ([`crate::reconstruct::ShField`]) or a mixture of cosine-power lobes
//! ([`crate::reconstruct::Lobes`]) evaluated for a batch of directions in a
//! compute shader (`compact.wgsl`), in f32 as a renderer's shader evaluates
//! them.
//!
//! A [`GpuCompact`] holds its CPU twin, the same stored parameters evaluated
//! in f64 ([`GpuCompact::exact`]), so the difference of the two is the cost
//! of evaluating in f32 on that adapter alone. Its parameters live in one
//! storage buffer: the coefficients and recurrence constants of the series,
//! or 5 floats per lobe; the bytes a renderer stores are the CPU
//! representation's ([`IntensityField::bytes`]: the recurrence constants
//! depend on L only and are not counted, as a shader's constants).

use glam::DVec3;

use super::batch::{buffer_entry, built_once, direction_data, upload, LookupBatch};
use super::{GpuContext, GpuError};
use crate::model::IntensityField;
use crate::reconstruct::Compact;

/// The shader's kind, count, offsets of the recurrence and diagonal
/// factors and zonal flag, the parameter floats (what the device stores:
/// only the L + 1 zonal coefficients of a zonal series), and the scale (cd)
/// of its output.
fn shader_data(exact: &Compact) -> ([u32; 5], Vec<f32>, f64) {
    match exact {
        Compact::Sh(s) => {
            let stored = s.stored_coefficients();
            let mut data: Vec<f32> = if s.is_zonal() {
                (0..=s.degree()).map(|l| stored[l * l + l] as f32).collect()
            } else {
                stored.iter().map(|&c| c as f32).collect()
            };
            let rec_at = data.len() as u32;
            data.extend(s.recurrence_constants().iter().flat_map(|&(a, b)| [a as f32, b as f32]));
            let diag_at = data.len() as u32;
            data.extend(s.diagonal_factors().iter().map(|&x| x as f32));
            let zonal = u32::from(s.is_zonal());
            ([0, s.degree() as u32, rec_at, diag_at, zonal], data, s.scale_cd())
        }
        Compact::Lobes(m) => {
            let data = m
                .lobes
                .iter()
                .flat_map(|l| [l.axis.x, l.axis.y, l.axis.z, l.exponent, l.weight_cd].map(|x| x as f32))
                .collect();
            // `zonal` marks rings about the vertical axis (`Lobes::rings`).
            ([1, m.lobes.len() as u32, 0, 0, u32::from(m.rings)], data, 1.0)
        }
    }
}

/// The compact pipeline and its bind group layout (one per device).
pub(crate) struct Pipeline {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl Pipeline {
    /// The pipeline of `ctx`, built on first use; a validation error (a
    /// driver that cannot compile the shader) is returned, not raised.
    fn of(ctx: &GpuContext) -> Result<&Pipeline, GpuError> {
        built_once(&ctx.compact, ctx, "compact representation", Pipeline::new)
    }

    fn new(ctx: &GpuContext) -> Self {
        let d = &ctx.device;
        let storage = |binding, read_only| buffer_entry(binding, wgpu::BufferBindingType::Storage { read_only });
        let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("compact"),
            entries: &[
                storage(0, true),
                storage(2, true),
                storage(3, false),
                buffer_entry(4, wgpu::BufferBindingType::Uniform),
            ],
        });
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("compact"),
            source: wgpu::ShaderSource::Wgsl(include_str!("compact.wgsl").into()),
        });
        let pl = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("compact"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("compact"),
            layout: Some(&pl),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Pipeline { layout, pipeline }
    }
}

/// A spherical-harmonic series or lobe mixture on the device, evaluated for
/// batches of directions.
pub struct GpuCompact<'a> {
    ctx: &'a GpuContext,
    exact: Compact,
    /// The parameter buffer (binding 0).
    params: wgpu::Buffer,
    /// Kind, count, recurrence offset, diagonal offset, zonal flag.
    header: [u32; 5],
    /// Intensity (cd) of an output of 1.
    scale_cd: f64,
}

impl std::fmt::Debug for GpuCompact<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuCompact")
            .field("adapter", self.ctx.adapter())
            .field("representation", &self.exact.field().name())
            .finish_non_exhaustive()
    }
}

impl<'a> GpuCompact<'a> {
    /// Upload the stored parameters of `exact` to `ctx`'s device.
    ///
    /// # Errors
    /// [`GpuError::Pipeline`] when the driver cannot build the shader.
    pub fn new(ctx: &'a GpuContext, exact: Compact) -> Result<Self, GpuError> {
        Pipeline::of(ctx)?;
        let (header, data, scale_cd) = shader_data(&exact);
        let params = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("compact parameters"),
            size: ((data.len() * 4) as u64).max(16),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&params, 0, bytemuck::cast_slice(&data));
        Ok(Self {
            ctx,
            exact,
            params,
            header,
            scale_cd,
        })
    }

    /// The adapter it lives on.
    pub fn context(&self) -> &'a GpuContext {
        self.ctx
    }

    /// The CPU twin: the same stored parameters evaluated in f64.
    pub fn exact(&self) -> &dyn IntensityField {
        self.exact.field()
    }

    /// The representation on the device (its stored parameters).
    pub fn compact(&self) -> &Compact {
        &self.exact
    }

    /// Upload `dirs` (luminaire frame, any length; zero vectors give 0) as a batch.
    ///
    /// # Errors
    /// [`GpuError::TooLarge`] when the batch exceeds the device's binding or dispatch limits.
    pub fn prepare(&self, dirs: &[DVec3]) -> Result<LookupBatch, GpuError> {
        let [kind, count, rec_at, diag_at, zonal] = self.header;
        let params = [0, kind, count, 0, rec_at, diag_at, zonal, 0];
        let buffers = upload(self.ctx, "compact", &direction_data(dirs), params)?;
        let pipe = Pipeline::of(self.ctx)?;
        let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
        let bind_group = self.ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("compact"),
            layout: &pipe.layout,
            entries: &[
                entry(0, self.params.as_entire_binding()),
                entry(2, buffers.input.as_entire_binding()),
                entry(3, buffers.output.as_entire_binding()),
                entry(4, buffers.uniform.as_entire_binding()),
            ],
        });
        Ok(LookupBatch::new(buffers, &pipe.pipeline, bind_group))
    }

    /// Intensity (cd, ≥ 0) in each direction of `dirs` (luminaire frame):
    /// one upload, one dispatch, one read-back.
    ///
    /// # Errors
    /// As [`GpuCompact::prepare`], and device errors.
    pub fn sample_dirs_cd(&self, dirs: &[DVec3]) -> Result<Vec<f64>, GpuError> {
        let batch = self.prepare(dirs)?;
        batch.run(self.ctx)?;
        Ok(batch
            .read(self.ctx)?
            .into_iter()
            .map(|v| {
                let cd = f64::from(v) * self.scale_cd;
                if cd.is_finite() {
                    cd.max(0.0)
                } else {
                    0.0
                }
            })
            .collect())
    }

    /// Median wall time (ns) per direction of the dispatch alone over `repeats` runs.
    ///
    /// # Errors
    /// As [`GpuCompact::prepare`], and device errors.
    pub fn dispatch_ns_per_sample(&self, dirs: &[DVec3], repeats: usize) -> Result<f64, GpuError> {
        self.prepare(dirs)?.dispatch_ns_per_sample(self.ctx, repeats)
    }
}

/// What the GPU evaluation of a compact representation costs, on one adapter.
#[derive(Debug, Clone, PartialEq)]
pub struct CompactRow {
    /// Median ns per direction of the dispatch alone.
    pub ns_per_sample_dispatch: f64,
    /// Largest |GPU − CPU (f64) evaluation| of the same stored parameters
    /// over the directions, cd.
    pub vs_exact_max_cd: f64,
}

/// Evaluate `gpu` at `dirs` against its CPU twin and time its dispatch over `repeats` runs.
///
/// # Errors
/// Device errors.
pub fn compact_row(gpu: &GpuCompact<'_>, dirs: &[DVec3], repeats: usize) -> Result<CompactRow, GpuError> {
    let on_gpu = gpu.sample_dirs_cd(dirs)?;
    let worst = on_gpu
        .iter()
        .zip(dirs)
        .map(|(g, d)| (g - gpu.exact().intensity_dir_cd(*d)).abs())
        .fold(0.0, f64::max);
    Ok(CompactRow {
        ns_per_sample_dispatch: gpu.dispatch_ns_per_sample(dirs, repeats)?,
        vs_exact_max_cd: worst,
    })
}

/// The GPU evaluation as an intensity field (cd). Batches are one dispatch
/// each; a single direction is a dispatch of its own (correct, but slow:
/// use batches). A device error gives 0 (the field has no error channel);
/// [`GpuCompact::sample_dirs_cd`] reports it.
impl IntensityField for GpuCompact<'_> {
    super::batch::gpu_sampling_methods!(clamp_gamma: false);
    fn name(&self) -> String {
        format!("{}+gpu", self.exact.field().name())
    }
    fn form(&self) -> Option<String> {
        self.exact.field().form()
    }
    fn bytes(&self) -> usize {
        self.exact.field().bytes()
    }
    fn is_continuous(&self) -> bool {
        self.exact.field().is_continuous()
    }
}
