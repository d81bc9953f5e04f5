//! The GPU render of light distribution textures: jobs, upload, dispatch,
//! read-back, batches.
//!
//! # Semantics: exactly [`reconstruct::render_planned`]
//!
//! A [`RenderJob`] is a [`LightTexture`] and a [`RenderPlan`] built from it by
//! [`LightTexture::render_plan`]: the same tap tables ([`reconstruct::AxisTaps`],
//! one entry per output row and per output column) and the same padded,
//! column-major texture ([`LightTexture::normalized`]) the CPU render reads.
//! There is no GPU-specific table type and no second formula: both kernels
//! ([`RenderKernel`]: `separable.wgsl`, the default, and `kernel.wgsl`) are
//! line-by-line ports of [`reconstruct::combine`] and of the row loop of the
//! CPU render, in f32, in the same order:
//!
//! ```text
//! gw, gi = plan.gamma.weight[i], plan.gamma.index[i]
//! if gw == [0; 4] { out = 0 }                            // outside the measured band
//! else {
//!     for m in 0..4:                                     // the 4 C taps, column cj = plan.c.index[j][m]
//!         v[m] = combine(pchip, texture[cj][gi[0..4]], gw)   // texture[c][r] = norm[c * rows_per_column + r]
//!     out = combine(pchip, v, plan.c.weight[j])
//!     if clamp && out < 0 { out = 0; clamped += 1 }
//! }
//! ```
//!
//! The results agree with the CPU up to FMA contraction and the drivers'
//! division rounding (well below 1e-5 of I_max; `photosolid gpu-check`).

use std::sync::mpsc;

use rayon::prelude::*;
use std::time::{Duration, Instant};

use crate::reconstruct::{self, LightTexture, RenderOptions, RenderPlan, Rendered};

use super::{GpuContext, GpuError};

/// One texture to render on the GPU: the texture and a plan built from it.
#[derive(Clone, Copy, Debug)]
pub struct RenderJob<'a> {
    /// The light distribution texture (its padded normalised values are uploaded).
    pub texture: &'a LightTexture,
    /// Tap tables and sizes from [`LightTexture::render_plan`] of `texture`.
    pub plan: &'a RenderPlan,
    /// Clamp negative results to 0 and count them ([`Rendered::clamped`]).
    pub clamp: bool,
}

impl RenderJob<'_> {
    /// Output rows (γ).
    pub fn height(&self) -> usize {
        self.plan.mapping.height
    }

    /// Output columns (C).
    pub fn width(&self) -> usize {
        self.plan.mapping.width
    }

    /// Check that the plan belongs to the texture (layout, table sizes, index ranges).
    ///
    /// # Errors
    /// [`GpuError::InvalidJob`] naming `index`, the job's place in its batch, and what is wrong.
    pub fn validate(&self, index: usize) -> Result<(), GpuError> {
        let invalid = |reason: String| GpuError::InvalidJob { index, reason };
        let (p, t) = (self.plan, self.texture);
        let rows = t.rows_per_column();
        let cols = t.columns().len();
        if p.rows_per_column != rows || p.columns != cols {
            return Err(invalid(format!(
                "plan for a {} x {} texture (padded rows x columns), texture is {rows} x {cols}",
                p.rows_per_column, p.columns
            )));
        }
        if t.normalized().len() != rows * cols {
            return Err(invalid("texture storage does not match its size".into()));
        }
        for (name, taps, n_out, n_src) in [
            ("gamma", &p.gamma, p.mapping.height, rows),
            ("C", &p.c, p.mapping.width, cols),
        ] {
            if taps.index.len() != n_out || taps.weight.len() != n_out {
                return Err(invalid(format!(
                    "{name} table has {} index / {} weight entries for {n_out} output samples",
                    taps.index.len(),
                    taps.weight.len()
                )));
            }
            if taps.filter != p.filter {
                return Err(invalid(format!(
                    "{name} table is for filter {}, plan for {}",
                    taps.filter, p.filter
                )));
            }
            if let Some((k, bad)) = taps
                .index
                .iter()
                .enumerate()
                .find(|(_, t)| t.iter().any(|&i| i as usize >= n_src))
            {
                return Err(invalid(format!(
                    "{name} table entry {k} has indices {bad:?} out of range 0..{n_src}"
                )));
            }
        }
        Ok(())
    }

    fn rendered(&self, data: Vec<f32>, clamped: usize) -> Rendered {
        Rendered {
            data,
            mapping: self.plan.mapping,
            i_max_cd: self.texture.i_max_cd(),
            filter: self.plan.filter,
            factor: self.plan.factor,
            measured_gamma: self.texture.measured_gamma(),
            clamped: if self.clamp { clamped } else { 0 },
        }
    }
}

/// Render `texture` on the GPU: the same result as [`reconstruct::render_with`]
/// (`options.parallel` is ignored).
///
/// # Errors
/// [`GpuError::InvalidJob`] for an invalid factor (as [`LightTexture::render_plan`]),
/// [`GpuError::TooLarge`] / [`GpuError::Device`] from the device.
pub fn render_gpu(ctx: &GpuContext, texture: &LightTexture, options: &RenderOptions) -> Result<Rendered, GpuError> {
    render_batch(ctx, &[(texture, *options)])?
        .pop()
        .ok_or_else(|| GpuError::BufferMap("one job gave no result".into()))
}

/// Render many textures in one submission (one upload, one dispatch per
/// chunk, one read-back wait); results in input order.
///
/// # Errors
/// As [`render_gpu`]; the error names the index of the offending item.
pub fn render_batch(ctx: &GpuContext, items: &[(&LightTexture, RenderOptions)]) -> Result<Vec<Rendered>, GpuError> {
    let plans = plans(items)?;
    let jobs = jobs(items, &plans);
    ctx.render_jobs(&jobs)
}

/// The plans of `items` (built once on the CPU, as the CPU render builds them).
pub fn plans(items: &[(&LightTexture, RenderOptions)]) -> Result<Vec<RenderPlan>, GpuError> {
    items
        .iter()
        .enumerate()
        .map(|(index, (t, o))| {
            t.render_plan(o.filter, o.factor).map_err(|e| GpuError::InvalidJob {
                index,
                reason: e.to_string(),
            })
        })
        .collect()
}

/// Jobs pairing `items` with their `plans` (from [`plans`]).
pub fn jobs<'a>(items: &[(&'a LightTexture, RenderOptions)], plans: &'a [RenderPlan]) -> Vec<RenderJob<'a>> {
    items
        .iter()
        .zip(plans)
        .map(|((t, o), p)| RenderJob {
            texture: t,
            plan: p,
            clamp: o.clamp,
        })
        .collect()
}

/// The CPU reference of a job: [`reconstruct::render_planned`] on the same plan.
pub fn render_cpu(job: &RenderJob<'_>) -> Rendered {
    reconstruct::render_planned(job.texture, job.plan, job.clamp, true)
}

/// The clamped-texel counts a device may report for `job` when each of its
/// texels is within `tolerance` (fraction of I_max) of the CPU's: a texel
/// whose unclamped CPU value is below −`tolerance` is clamped on any device,
/// one below +`tolerance` may be (a cubic's overshoot that ends within
/// rounding of 0 takes either sign under FMA contraction), one outside the
/// measured band never is. `0..=0` for a job that does not clamp.
pub fn clamp_count_range(job: &RenderJob<'_>, tolerance: f32) -> std::ops::RangeInclusive<usize> {
    if !job.clamp {
        return 0..=0;
    }
    let unclamped = reconstruct::render_planned(job.texture, job.plan, false, true);
    let width = job.plan.mapping.width.max(1);
    let (mut surely, mut maybe) = (0, 0);
    for (row, weights) in unclamped.data.chunks(width).zip(&job.plan.gamma.weight) {
        if *weights == [0.0; 4] {
            continue;
        }
        surely += row.iter().filter(|&&v| v < -tolerance).count();
        maybe += row.iter().filter(|&&v| v < tolerance).count();
    }
    surely..=maybe
}

/// Which compute kernel renders a batch on the GPU. Both give the CPU's
/// numbers (to FMA contraction); they differ in speed only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RenderKernel {
    /// `separable.wgsl`: a γ pass writing one value per output row and
    /// texture column, then a C pass combining four of them per texel (the
    /// CPU's order). The default: fewer reads per texel (see BENCHMARKS.md).
    #[default]
    TwoPass,
    /// `kernel.wgsl`: one pass, each texel repeating the γ combine for each
    /// of its four C taps (the first GPU kernel, kept for comparison).
    Fused,
}

impl RenderKernel {
    /// Both kernels, the default first.
    pub const ALL: [RenderKernel; 2] = [RenderKernel::TwoPass, RenderKernel::Fused];
    /// The name used in benchmarks and reports.
    pub fn name(self) -> &'static str {
        match self {
            RenderKernel::TwoPass => "two-pass",
            RenderKernel::Fused => "fused",
        }
    }
}

const TILE_X: usize = 16;
const TILE_Y: usize = 4;
/// Entries of the γ pass per workgroup (`separable.wgsl`).
const GAMMA_TILE: usize = 64;
const HEADER: usize = 4;
const DESC: usize = 16;
/// Words per tap-table entry: 4 indices, 4 weights.
const ENTRY: usize = 8;

/// Durations of the phases of a GPU render (see [`GpuContext::render_jobs_timed`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Timings {
    /// Packing the jobs into the word buffer on the CPU.
    pub pack: Duration,
    /// Buffer creation and upload, until the queue has finished the copies.
    pub upload: Duration,
    /// Compute dispatch(es), from submission to completion.
    pub dispatch: Duration,
    /// Copy to staging buffers, mapping, and copying out into `Vec`s.
    pub readback: Duration,
}

impl Timings {
    /// Sum of all phases.
    pub fn total(&self) -> Duration {
        self.pack + self.upload + self.dispatch + self.readback
    }
}

struct Chunk {
    /// Job indices in this chunk.
    jobs: std::ops::Range<usize>,
    /// Output f32 offset of each job within the chunk output.
    out_offsets: Vec<usize>,
    out_len: usize,
    dispatch: (u32, u32),
    /// Workgroups of the γ pass (two-pass kernel).
    dispatch_gamma: (u32, u32),
    _input: wgpu::Buffer,
    output: wgpu::Buffer,
    /// One clamped-texel counter (u32) per job of the chunk.
    counts: wgpu::Buffer,
    /// Output, then the counters.
    staging: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// A batch uploaded to the device: buffers and bind groups, ready to dispatch.
pub struct GpuBatch {
    kernel: RenderKernel,
    chunks: Vec<Chunk>,
    /// One result per job without its data (filled in by the read-back).
    meta: Vec<Rendered>,
}

impl std::fmt::Debug for GpuBatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuBatch")
            .field("jobs", &self.meta.len())
            .field("chunks", &self.chunks.len())
            .finish()
    }
}

impl GpuBatch {
    /// Number of jobs.
    pub fn len(&self) -> usize {
        self.meta.len()
    }

    /// True for an empty batch.
    pub fn is_empty(&self) -> bool {
        self.meta.is_empty()
    }

    /// The kernel this batch was packed for.
    pub fn kernel(&self) -> RenderKernel {
        self.kernel
    }

    /// Number of chunks (dispatches) the batch was split into to respect the
    /// device's buffer-binding limit.
    pub fn chunks(&self) -> usize {
        self.chunks.len()
    }
}

/// Words a job occupies in the input buffer (excluding its descriptor).
fn job_words(job: &RenderJob<'_>) -> usize {
    job.texture.normalized().len() + (job.height() + job.width()) * ENTRY
}

fn tiles(job: &RenderJob<'_>) -> usize {
    job.width().div_ceil(TILE_X) * job.height().div_ceil(TILE_Y)
}

/// Entries of the γ pass's scratch (one per output row and texture column).
fn gamma_entries(job: &RenderJob<'_>) -> usize {
    job.height() * job.plan.columns
}

fn pack_taps(taps: &reconstruct::AxisTaps, out: &mut Vec<u32>) {
    for (i, w) in taps.index.iter().zip(&taps.weight) {
        out.extend_from_slice(i);
        out.extend(w.iter().map(|v| v.to_bits()));
    }
}

/// Pack jobs into the kernels' word layout (see `kernel.wgsl` and
/// `separable.wgsl`). Returns the words, the per-job output offsets, the
/// output length and the γ-pass scratch length (after the outputs in the
/// same buffer; 0 for the fused kernel).
fn pack_chunk(jobs: &[RenderJob<'_>], dispatch_x: u32, kernel: RenderKernel) -> (Vec<u32>, Vec<usize>, usize, usize) {
    let n = jobs.len();
    let total: usize = HEADER + n * DESC + jobs.iter().map(job_words).sum::<usize>();
    let mut w = Vec::with_capacity(total);
    w.resize(HEADER + n * DESC, 0u32);
    let (mut out_off, mut tile_begin) = (0usize, 0usize);
    let out_total: usize = jobs.iter().map(|j| j.height() * j.width()).sum();
    let (mut tmp_off, mut gamma_tile) = (out_total, 0usize);
    let two_pass = kernel == RenderKernel::TwoPass;
    let mut out_offsets = Vec::with_capacity(n);
    for (k, job) in jobs.iter().enumerate() {
        let tex_off = w.len();
        w.extend(job.texture.normalized().iter().map(|v| v.to_bits()));
        let gamma_tab = w.len();
        pack_taps(&job.plan.gamma, &mut w);
        let c_tab = w.len();
        pack_taps(&job.plan.c, &mut w);
        let flags = job.clamp as u32 | (job.plan.filter.is_data_dependent() as u32) << 1;
        let d = HEADER + k * DESC;
        let desc = [
            tex_off,
            job.plan.rows_per_column,
            job.plan.columns,
            gamma_tab,
            c_tab,
            out_off,
            job.height(),
            job.width(),
            job.width().div_ceil(TILE_X),
            tile_begin,
            flags as usize,
            k,
            if two_pass { tmp_off } else { 0 },
            gamma_tile,
        ];
        for (i, v) in desc.iter().enumerate() {
            w[d + i] = *v as u32;
        }
        out_offsets.push(out_off);
        out_off += job.height() * job.width();
        tile_begin += tiles(job);
        if two_pass {
            tmp_off += gamma_entries(job);
            gamma_tile += gamma_entries(job).div_ceil(GAMMA_TILE);
        }
    }
    w[0] = n as u32;
    w[1] = tile_begin as u32;
    w[2] = dispatch_x;
    w[3] = gamma_tile as u32;
    debug_assert_eq!(w.len(), total);
    (w, out_offsets, out_off, tmp_off - out_total)
}

/// `jobs` cut greedily into chunks of consecutive jobs, each chunk as many as
/// fit one storage binding of `max_bytes` (input words; output values plus,
/// for the two-pass kernel, the γ scratch) and `max_dim`² workgroups.
///
/// Errors: [`GpuError::TooLarge`] naming the first job that fits no chunk alone.
fn chunk_ranges(
    jobs: &[RenderJob<'_>],
    max_bytes: u64,
    max_dim: usize,
    kernel: RenderKernel,
) -> Result<Vec<std::ops::Range<usize>>, GpuError> {
    let two_pass = kernel == RenderKernel::TwoPass;
    let max_words = (max_bytes / 4) as usize;
    let mut ranges = Vec::new();
    let mut start = 0;
    while start < jobs.len() {
        let (mut in_w, mut out_w, mut n_tiles) = (HEADER, 0usize, 0usize);
        let mut end = start;
        while end < jobs.len() {
            let j = &jobs[end];
            // The two-pass kernel's γ scratch shares the output binding.
            let scratch = if two_pass { gamma_entries(j) } else { 0 };
            let (iw, ow, tl) = (DESC + job_words(j), j.height() * j.width() + scratch, tiles(j));
            let fits = in_w + iw <= max_words
                && out_w + ow <= max_words
                && n_tiles + tl <= max_dim.saturating_mul(max_dim)
                && in_w + iw <= u32::MAX as usize;
            if !fits {
                break;
            }
            in_w += iw;
            out_w += ow;
            n_tiles += tl;
            end += 1;
        }
        if end == start {
            let j = &jobs[start];
            return Err(GpuError::TooLarge {
                index: start,
                reason: format!(
                    "{} input words / {} output values exceed the device's storage binding limit of {} bytes",
                    DESC + job_words(j),
                    j.height() * j.width(),
                    max_bytes
                ),
            });
        }
        ranges.push(start..end);
        start = end;
    }
    Ok(ranges)
}

/// One chunk of jobs packed for upload ([`pack_chunk`]) with its workgroup counts.
struct PackedChunk {
    /// Job indices in this chunk.
    jobs: std::ops::Range<usize>,
    /// The kernels' input words.
    words: Vec<u32>,
    /// Output f32 offset of each job within the chunk output.
    out_offsets: Vec<usize>,
    /// Output values of the chunk, and the γ-pass scratch after them (two-pass kernel).
    out_len: usize,
    tmp_len: usize,
    /// Workgroups of the render (fused kernel, or the C pass).
    dispatch: (u32, u32),
    /// Workgroups of the γ pass (two-pass kernel).
    dispatch_gamma: (u32, u32),
}

impl PackedChunk {
    /// The jobs `r` of `jobs` packed for `kernel`, their tiles laid out at most
    /// `max_dim` workgroups wide.
    fn new(jobs: &[RenderJob<'_>], r: std::ops::Range<usize>, max_dim: usize, kernel: RenderKernel) -> Self {
        let n_tiles: usize = jobs[r.clone()].iter().map(tiles).sum();
        let dx = n_tiles.clamp(1, max_dim);
        let dy = n_tiles.div_ceil(dx).max(1);
        let (words, out_offsets, out_len, tmp_len) = pack_chunk(&jobs[r.clone()], dx as u32, kernel);
        let dy_gamma = (words[3] as usize).div_ceil(dx).max(1);
        Self {
            jobs: r,
            words,
            out_offsets,
            out_len,
            tmp_len,
            dispatch: (dx as u32, dy as u32),
            dispatch_gamma: (dx as u32, dy_gamma as u32),
        }
    }
}

impl GpuContext {
    /// Render one job on the GPU.
    pub fn render_job(&self, job: &RenderJob<'_>) -> Result<Rendered, GpuError> {
        self.render_jobs(std::slice::from_ref(job))?
            .pop()
            .ok_or_else(|| GpuError::BufferMap("one job gave no result".into()))
    }

    /// Render many jobs with one upload, one command submission (one
    /// dispatch per chunk; a chunk is as many jobs as fit the device's
    /// storage-binding limit) and one read-back wait.
    pub fn render_jobs(&self, jobs: &[RenderJob<'_>]) -> Result<Vec<Rendered>, GpuError> {
        self.render_jobs_with(jobs, RenderKernel::default())
    }

    /// [`render_jobs`](Self::render_jobs) with a chosen kernel.
    pub fn render_jobs_with(&self, jobs: &[RenderJob<'_>], kernel: RenderKernel) -> Result<Vec<Rendered>, GpuError> {
        self.render_jobs_chunked(jobs, self.max_binding_bytes(), kernel)
    }

    /// [`render_jobs`](Self::render_jobs) with a smaller per-chunk binding
    /// limit (bytes), to exercise the chunking in tests.
    #[doc(hidden)]
    pub fn render_jobs_chunked(
        &self,
        jobs: &[RenderJob<'_>],
        max_binding_bytes: u64,
        kernel: RenderKernel,
    ) -> Result<Vec<Rendered>, GpuError> {
        let batch = self.upload_inner(
            jobs,
            &mut Timings::default(),
            max_binding_bytes.min(self.max_binding_bytes()),
            kernel,
        )?;
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("render") });
        self.encode_dispatch(&batch, &mut enc);
        self.encode_copies(&batch, &mut enc);
        self.queue.submit([enc.finish()]);
        self.map_and_read(&batch)
    }

    /// [`render_jobs`](Self::render_jobs) in separately synchronised phases
    /// (pack, upload, dispatch, read-back), each timed; slightly slower than
    /// `render_jobs` because of the extra waits.
    pub fn render_jobs_timed(&self, jobs: &[RenderJob<'_>]) -> Result<(Vec<Rendered>, Timings), GpuError> {
        self.render_jobs_timed_with(jobs, RenderKernel::default())
    }

    /// [`render_jobs_timed`](Self::render_jobs_timed) with a chosen kernel.
    pub fn render_jobs_timed_with(
        &self,
        jobs: &[RenderJob<'_>],
        kernel: RenderKernel,
    ) -> Result<(Vec<Rendered>, Timings), GpuError> {
        let mut t = Timings::default();
        let batch = self.upload_inner(jobs, &mut t, self.max_binding_bytes(), kernel)?;
        let t0 = Instant::now();
        self.dispatch(&batch)?;
        t.dispatch = t0.elapsed();
        let t0 = Instant::now();
        let out = self.read_back(&batch)?;
        t.readback = t0.elapsed();
        Ok((out, t))
    }

    /// Validate, pack and upload a batch; waits until the upload is complete.
    pub fn upload(&self, jobs: &[RenderJob<'_>]) -> Result<GpuBatch, GpuError> {
        self.upload_with(jobs, RenderKernel::default())
    }

    /// [`upload`](Self::upload) packed for a chosen kernel.
    pub fn upload_with(&self, jobs: &[RenderJob<'_>], kernel: RenderKernel) -> Result<GpuBatch, GpuError> {
        self.upload_inner(jobs, &mut Timings::default(), self.max_binding_bytes(), kernel)
    }

    /// Validate, pack and upload `jobs` in chunks of at most `max_bytes` per
    /// binding for `kernel`, timing the packing and the upload into `t`; waits
    /// until the upload is complete.
    fn upload_inner(
        &self,
        jobs: &[RenderJob<'_>],
        t: &mut Timings,
        max_bytes: u64,
        kernel: RenderKernel,
    ) -> Result<GpuBatch, GpuError> {
        let t0 = Instant::now();
        for (k, job) in jobs.iter().enumerate() {
            job.validate(k)?;
        }
        let max_dim = self.max_workgroups_per_dim().max(1) as usize;
        let packed: Vec<PackedChunk> = chunk_ranges(jobs, max_bytes, max_dim, kernel)?
            .into_iter()
            .map(|r| PackedChunk::new(jobs, r, max_dim, kernel))
            .collect();
        t.pack = t0.elapsed();

        let t0 = Instant::now();
        let chunks: Vec<Chunk> = packed.into_iter().map(|p| self.upload_chunk(p)).collect();
        self.queue.submit(std::iter::empty());
        self.wait()?;
        t.upload = t0.elapsed();
        let meta = jobs.iter().map(|j| j.rendered(Vec::new(), 0)).collect();
        Ok(GpuBatch { kernel, chunks, meta })
    }

    /// The buffers and bind group of one packed chunk, its words written to the
    /// input buffer (queued: the caller submits and waits).
    fn upload_chunk(&self, p: PackedChunk) -> Chunk {
        let PackedChunk {
            jobs: r,
            words,
            out_offsets,
            out_len,
            tmp_len,
            dispatch,
            dispatch_gamma,
        } = p;
        let in_bytes = (words.len() * 4) as u64;
        let out_bytes = ((out_len + tmp_len).max(1) * 4) as u64;
        let staged_out_bytes = (out_len.max(1) * 4) as u64;
        let count_bytes = (r.len() * 4) as u64;
        let input = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render input"),
            size: in_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.queue.write_buffer(&input, 0, bytemuck::cast_slice(&words));
        let output = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render output"),
            size: out_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let counts = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render clamped counts"),
            size: count_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render staging"),
            size: staged_out_bytes + count_bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: input.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: output.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: counts.as_entire_binding(),
                },
            ],
        });
        Chunk {
            jobs: r,
            out_offsets,
            out_len,
            dispatch,
            dispatch_gamma,
            _input: input,
            output,
            counts,
            staging,
            bind_group,
        }
    }

    fn encode_dispatch(&self, batch: &GpuBatch, enc: &mut wgpu::CommandEncoder) {
        for c in &batch.chunks {
            enc.clear_buffer(&c.counts, 0, None);
        }
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("render"),
            timestamp_writes: None,
        });
        for c in &batch.chunks {
            if c.out_len == 0 {
                continue;
            }
            pass.set_bind_group(0, &c.bind_group, &[]);
            match batch.kernel {
                RenderKernel::Fused => {
                    pass.set_pipeline(&self.pipeline);
                    pass.dispatch_workgroups(c.dispatch.0, c.dispatch.1, 1);
                }
                RenderKernel::TwoPass => {
                    // wgpu orders the two dispatches (a storage-buffer barrier between them).
                    pass.set_pipeline(&self.two_pass[0]);
                    pass.dispatch_workgroups(c.dispatch_gamma.0, c.dispatch_gamma.1, 1);
                    pass.set_pipeline(&self.two_pass[1]);
                    pass.dispatch_workgroups(c.dispatch.0, c.dispatch.1, 1);
                }
            }
        }
    }

    fn encode_copies(&self, batch: &GpuBatch, enc: &mut wgpu::CommandEncoder) {
        for c in &batch.chunks {
            let out_bytes = c.staging.size() - c.counts.size();
            enc.copy_buffer_to_buffer(&c.output, 0, &c.staging, 0, out_bytes);
            enc.copy_buffer_to_buffer(&c.counts, 0, &c.staging, out_bytes, c.counts.size());
        }
    }

    /// Run the compute dispatches of an uploaded batch (one submission) and
    /// wait for completion. May be repeated.
    pub fn dispatch(&self, batch: &GpuBatch) -> Result<(), GpuError> {
        let mut enc = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("dispatch"),
        });
        self.encode_dispatch(batch, &mut enc);
        self.queue.submit([enc.finish()]);
        self.wait()
    }

    /// Copy the results of the last dispatch back to the host.
    pub fn read_back(&self, batch: &GpuBatch) -> Result<Vec<Rendered>, GpuError> {
        let mut enc = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("read-back"),
        });
        self.encode_copies(batch, &mut enc);
        self.queue.submit([enc.finish()]);
        self.map_and_read(batch)
    }

    fn wait(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| GpuError::Device(e.to_string()))
    }

    fn map_and_read(&self, batch: &GpuBatch) -> Result<Vec<Rendered>, GpuError> {
        let (tx, rx) = mpsc::channel();
        for (k, c) in batch.chunks.iter().enumerate() {
            let tx = tx.clone();
            c.staging.map_async(wgpu::MapMode::Read, .., move |r| {
                let _ = tx.send((k, r));
            });
        }
        drop(tx);
        self.wait()?;
        for (k, r) in rx.iter() {
            r.map_err(|e| GpuError::BufferMap(format!("mapping read-back buffer {k}: {e}")))?;
        }
        let mut out: Vec<Rendered> = Vec::with_capacity(batch.len());
        for c in &batch.chunks {
            {
                let view = c
                    .staging
                    .get_mapped_range(..)
                    .map_err(|e| GpuError::BufferMap(e.to_string()))?;
                let out_bytes = (c.staging.size() - c.counts.size()) as usize;
                let all: &[f32] = bytemuck::try_cast_slice(&view[..c.out_len * 4])
                    .map_err(|e| GpuError::BufferMap(format!("read-back buffer: {e}")))?;
                let counts: &[u32] = bytemuck::try_cast_slice(&view[out_bytes..out_bytes + c.jobs.len() * 4])
                    .map_err(|e| GpuError::BufferMap(format!("read-back buffer: {e}")))?;
                // The copies out of the mapped range in parallel: a large batch's read-back
                // is bound by them (and by the new vectors' first touch), not by the transfer.
                let rendered: Vec<Rendered> = c
                    .jobs
                    .clone()
                    .into_par_iter()
                    .enumerate()
                    .map(|(k, j)| {
                        let m = &batch.meta[j];
                        let n = m.mapping.height * m.mapping.width;
                        let off = c.out_offsets[k];
                        let mut r = m.clone();
                        r.data = all[off..off + n].to_vec();
                        // The kernel counts only where the job clamps.
                        r.clamped = counts[k] as usize;
                        r
                    })
                    .collect();
                out.extend(rendered);
            }
            c.staging.unmap();
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn cpu_backend_resolves_without_wgpu() {
        // The spellings are tested with `reconstruct::Backend`; `cpu` never initialises wgpu.
        use crate::Backend;
        assert!(matches!(
            crate::resolve(Backend::Cpu).unwrap(),
            crate::Resolved::Cpu { notice: None }
        ));
    }
}
