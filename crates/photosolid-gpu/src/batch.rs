//! A batch of directions evaluated by a compute shader: the buffers, the
//! dispatch and the read-back that every direction-evaluating pipeline
//! shares (the texture lookups of [`super::realtime`], the spherical
//! harmonics and lobes of [`super::compact`]).
//!
//! Binding convention of those shaders: the directions (`array<vec4<f32>>`,
//! xyz a unit vector in the luminaire frame) at binding 2, the output
//! (`array<f32>`, one value per direction) at 3, a 32-byte uniform whose
//! fourth `u32` is the dispatch's x size at 4; what else a shader reads is
//! at other bindings. Workgroups of [`WORKGROUP`] threads, laid out in two
//! dimensions when one exceeds the device's per-dimension limit.

use std::sync::mpsc;
use std::time::{Duration, Instant};

use glam::DVec3;

use super::{GpuContext, GpuError};

/// The pipeline in `cell`, built by `build` on first use inside a validation
/// error scope: a driver that cannot compile the shader gives
/// [`GpuError::Pipeline`] naming `what`, not a panic. One per device.
pub(crate) fn built_once<'a, P>(
    cell: &'a std::sync::OnceLock<Result<P, GpuError>>,
    ctx: &GpuContext,
    what: &str,
    build: impl FnOnce(&GpuContext) -> P,
) -> Result<&'a P, GpuError> {
    cell.get_or_init(|| {
        let scope = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let p = build(ctx);
        match pollster::block_on(scope.pop()) {
            None => Ok(p),
            Some(e) => Err(GpuError::Pipeline(format!("{what} pipeline: {e}"))),
        }
    })
    .as_ref()
    .map_err(Clone::clone)
}

/// A compute shader's buffer binding of type `ty` at `binding`.
pub(crate) fn buffer_entry(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Threads per workgroup of the direction shaders (`@workgroup_size(64)`).
pub(crate) const WORKGROUP: usize = 64;

/// Directions uploaded once, dispatched as often as needed (for timing).
pub struct LookupBatch {
    n: usize,
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    output: wgpu::Buffer,
    staging: wgpu::Buffer,
    dispatch: (u32, u32),
}

impl std::fmt::Debug for LookupBatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LookupBatch")
            .field("n", &self.n)
            .finish_non_exhaustive()
    }
}

/// The device buffers of a batch before its bind group exists: bind
/// `input`, `output` and `uniform` at 2, 3 and 4.
pub(crate) struct BatchBuffers {
    pub(crate) n: usize,
    pub(crate) input: wgpu::Buffer,
    pub(crate) output: wgpu::Buffer,
    pub(crate) uniform: wgpu::Buffer,
    staging: wgpu::Buffer,
    dispatch: (u32, u32),
}

/// Unit directions as the shaders read them (f32 xyz, w = 0); a zero or
/// non-finite vector stays zero (the shaders answer 0 for it).
pub(crate) fn direction_data(dirs: &[DVec3]) -> Vec<[f32; 4]> {
    dirs.iter()
        .map(|d| {
            let d = if d.is_finite() {
                d.normalize_or_zero()
            } else {
                DVec3::ZERO
            };
            [d.x as f32, d.y as f32, d.z as f32, 0.0]
        })
        .collect()
}

/// The [`IntensityField`](crate::model::IntensityField) methods every GPU
/// evaluator shares, written once: a direction, a batch of angle pairs or a
/// grid is one call of the type's `sample_dirs_cd` (one dispatch), answered 0
/// where that call fails or the direction is not finite (the trait has no
/// error channel; `sample_dirs_cd` reports the error to callers that want
/// it). With `clamp_gamma: true` γ is clamped to [0, 180] as a texture's rows
/// clamp; a series or a lobe mixture is a function of the direction and is
/// not clamped.
macro_rules! gpu_sampling_methods {
    (clamp_gamma: $clamp:expr) => {
        fn intensity_cd(&self, c_deg: f64, gamma_deg: f64) -> f64 {
            if !(c_deg.is_finite() && gamma_deg.is_finite()) {
                return 0.0;
            }
            let gamma = if $clamp {
                gamma_deg.clamp(0.0, 180.0)
            } else {
                gamma_deg
            };
            self.intensity_dir_cd($crate::model::frame::direction(c_deg, gamma))
        }
        fn intensity_dir_cd(&self, d: glam::DVec3) -> f64 {
            if !(d.is_finite() && d.length_squared() > 0.0) {
                return 0.0;
            }
            self.sample_dirs_cd(&[d]).map_or(0.0, |v| v[0])
        }
        fn intensity_batch_cd(&self, dirs: &[(f64, f64)]) -> Vec<f64> {
            self.sample_dirs_cd(&$crate::batch::angle_directions(dirs, $clamp))
                .unwrap_or_else(|_| vec![0.0; dirs.len()])
        }
        fn sample_grid(&self, c_deg: &[f64], gamma_deg: &[f64], out: &mut [f64]) {
            assert_eq!(
                out.len(),
                c_deg.len() * gamma_deg.len(),
                "one output per grid direction"
            );
            out.copy_from_slice(&self.intensity_batch_cd(&$crate::batch::grid_angles(c_deg, gamma_deg)));
        }
        /// One direction is a dispatch of its own: searches use batches instead.
        fn prefers_batches(&self) -> bool {
            true
        }
        fn batch_time_per_sample_ns(&self, dirs: &[glam::DVec3], repeats: usize) -> Option<f64> {
            $crate::batch::end_to_end_ns_per_sample(dirs.len(), repeats, || {
                self.sample_dirs_cd(std::hint::black_box(dirs))
            })
        }
    };
}
pub(crate) use gpu_sampling_methods;

/// The unit directions of (C, γ) pairs in degrees (γ clamped to [0, 180]
/// with `clamp_gamma`, as a texture's rows clamp); a non-finite pair gives
/// the zero vector (answered 0).
pub(crate) fn angle_directions(angles: &[(f64, f64)], clamp_gamma: bool) -> Vec<DVec3> {
    angles
        .iter()
        .map(|&(c, g)| {
            if c.is_finite() && g.is_finite() {
                crate::model::frame::direction(c, if clamp_gamma { g.clamp(0.0, 180.0) } else { g })
            } else {
                DVec3::ZERO
            }
        })
        .collect()
}

/// The (C, γ) pairs of a grid, plane-major (`IntensityField::sample_grid`'s order).
pub(crate) fn grid_angles(c_deg: &[f64], gamma_deg: &[f64]) -> Vec<(f64, f64)> {
    c_deg
        .iter()
        .flat_map(|&c| gamma_deg.iter().map(move |&g| (c, g)))
        .collect()
}

/// Upload `data` and `params` (N >= 4 words: `n`, a word of the shader's, its
/// own, then the dispatch's x size, which is written here, then the shader's
/// own) into the buffers of a batch, labelled `label`.
///
/// # Errors
/// [`GpuError::TooLarge`] when the batch exceeds the device's binding or dispatch limits.
pub(crate) fn upload<const N: usize>(
    ctx: &GpuContext,
    label: &str,
    data: &[[f32; 4]],
    mut params: [u32; N],
) -> Result<BatchBuffers, GpuError> {
    const { assert!(N >= 4, "the first four words are the batch's") };
    let n = data.len();
    let max_dim = ctx.max_workgroups_per_dim().max(1) as usize;
    let groups = n.div_ceil(WORKGROUP).max(1);
    let dx = groups.min(max_dim);
    let dy = groups.div_ceil(dx);
    if (n * 16) as u64 > ctx.max_binding_bytes() || dy > max_dim {
        return Err(GpuError::TooLarge {
            index: 0,
            reason: format!("{n} directions exceed the device's binding or dispatch limits"),
        });
    }
    params[0] = n as u32;
    params[3] = dx as u32;
    let d = &ctx.device;
    let buf = |what: &str, size: u64, usage| {
        d.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{label} {what}")),
            size: size.max(16),
            usage,
            mapped_at_creation: false,
        })
    };
    use wgpu::BufferUsages as U;
    let input = buf("directions", (n * 16) as u64, U::STORAGE | U::COPY_DST);
    ctx.queue.write_buffer(&input, 0, bytemuck::cast_slice(data));
    let output = buf("output", (n * 4) as u64, U::STORAGE | U::COPY_SRC);
    let staging = buf("staging", (n * 4) as u64, U::MAP_READ | U::COPY_DST);
    // A uniform block is a whole number of 16-byte vectors.
    let uniform = buf("params", (N * 4).next_multiple_of(16) as u64, U::UNIFORM | U::COPY_DST);
    ctx.queue.write_buffer(&uniform, 0, bytemuck::cast_slice(&params));
    Ok(BatchBuffers {
        n,
        input,
        output,
        uniform,
        staging,
        dispatch: (dx as u32, dy as u32),
    })
}

fn device_error(what: &str, e: impl std::fmt::Display) -> GpuError {
    GpuError::Device(format!("{what}: {e}"))
}

impl LookupBatch {
    /// The batch of `buffers`, run by `pipeline` with `bind_group`.
    pub(crate) fn new(buffers: BatchBuffers, pipeline: &wgpu::ComputePipeline, bind_group: wgpu::BindGroup) -> Self {
        Self {
            n: buffers.n,
            pipeline: pipeline.clone(),
            bind_group,
            output: buffers.output,
            staging: buffers.staging,
            dispatch: buffers.dispatch,
        }
    }

    /// Directions in the batch.
    pub fn len(&self) -> usize {
        self.n
    }
    /// True for an empty batch.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Run the batch on `ctx` and wait for it; returns the wall time from
    /// submission to completion.
    ///
    /// # Errors
    /// [`GpuError::Device`] when the wait fails.
    pub fn run(&self, ctx: &GpuContext) -> Result<Duration, GpuError> {
        let t0 = Instant::now();
        let mut enc = ctx.device.create_command_encoder(&Default::default());
        if self.n > 0 {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            pass.dispatch_workgroups(self.dispatch.0, self.dispatch.1, 1);
        }
        ctx.queue.submit([enc.finish()]);
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| device_error("direction batch dispatch", e))?;
        Ok(t0.elapsed())
    }

    /// The results of the last [`LookupBatch::run`]: one value per direction.
    ///
    /// # Errors
    /// [`GpuError::BufferMap`] or [`GpuError::Device`] when the read-back fails.
    pub fn read(&self, ctx: &GpuContext) -> Result<Vec<f32>, GpuError> {
        if self.n == 0 {
            return Ok(Vec::new());
        }
        let mut enc = ctx.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(&self.output, 0, &self.staging, 0, (self.n * 4) as u64);
        ctx.queue.submit([enc.finish()]);
        let (tx, rx) = mpsc::channel();
        self.staging.map_async(wgpu::MapMode::Read, .., move |r| {
            let _ = tx.send(r);
        });
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| device_error("direction batch read-back wait", e))?;
        let mapped = |e: &dyn std::fmt::Display| GpuError::BufferMap(format!("direction batch read-back: {e}"));
        rx.recv().map_err(|e| mapped(&e))?.map_err(|e| mapped(&e))?;
        let out = {
            let view = self.staging.get_mapped_range(..).map_err(|e| mapped(&e))?;
            bytemuck::cast_slice::<u8, f32>(&view[..self.n * 4]).to_vec()
        };
        self.staging.unmap();
        Ok(out)
    }

    /// Median wall time (ns) per direction of the dispatch alone (the
    /// directions resident, results not read back) over `repeats` runs
    /// after one warm-up run.
    ///
    /// # Errors
    /// As [`LookupBatch::run`].
    pub fn dispatch_ns_per_sample(&self, ctx: &GpuContext, repeats: usize) -> Result<f64, GpuError> {
        self.run(ctx)?; // warm-up
        let mut t = (0..repeats.max(1))
            .map(|_| self.run(ctx).map(|d| d.as_secs_f64()))
            .collect::<Result<Vec<_>, _>>()?;
        t.sort_by(f64::total_cmp);
        Ok(1e9 * t[t.len() / 2] / self.n.max(1) as f64)
    }
}

/// Median wall time (ns) per direction of `evaluate` on `n` directions over
/// `repeats` calls: a whole batch as its caller sees it (upload, dispatch,
/// read-back). `None` when a call fails.
pub(crate) fn end_to_end_ns_per_sample<T>(
    n: usize,
    repeats: usize,
    evaluate: impl Fn() -> Result<T, GpuError>,
) -> Option<f64> {
    let mut t: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let t0 = Instant::now();
            let v = evaluate();
            std::hint::black_box(v).ok().map(|_| t0.elapsed().as_secs_f64())
        })
        .collect::<Option<_>>()?;
    t.sort_by(f64::total_cmp);
    Some(1e9 * t[t.len() / 2] / n.max(1) as f64)
}
