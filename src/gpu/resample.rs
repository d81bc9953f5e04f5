//! Table-driven tensor-product resampling: job description, the CPU
//! reference ([`resample_cpu`]) and the GPU path (upload, dispatch, read-back,
//! batches).
//!
//! # Semantics (identical on CPU and GPU)
//!
//! A job has a source grid `src` of `rows x cols` f32, row-major (row = gamma,
//! column = C; already padded with ghost rows/columns by the caller), and one
//! [`AxisTaps`] table per output axis: `row_taps` has one entry per output row
//! (gamma), `col_taps` one per output column (C). Output `r, c` is
//!
//! ```text
//! for j in 0..4:                       // the 4 C taps, column cj = col_taps.idx[c][j]
//!     v[j] = row_taps.eval(r, src[ri0][cj], src[ri1][cj], src[ri2][cj], src[ri3][cj])
//! out = col_taps.eval(c, v[0], v[1], v[2], v[3])
//! if clamp_negative { out = max(out, 0) }
//! ```
//!
//! i.e. gamma first within each of the 4 C-tap columns, then C. A weights
//! entry evaluates `((w0*y0 + w1*y1) + w2*y2) + w3*y3` left to right in f32; a
//! PCHIP entry evaluates [`pchip4`]. Output is row-major `out_rows x out_cols`.

use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::{GpuContext, GpuError};

/// Interpolation table for one output axis: 4 source taps per output sample.
#[derive(Clone, Debug, PartialEq)]
pub enum AxisTaps {
    /// Fixed weights: `y = w0*s[i0] + w1*s[i1] + w2*s[i2] + w3*s[i3]`
    /// (left to right). Unused taps: weight 0 with any valid index.
    Weights {
        /// Source indices per output sample (must be in range).
        idx: Vec<[u32; 4]>,
        /// Weights per output sample.
        w: Vec<[f32; 4]>,
    },
    /// Data-dependent PCHIP (Fritsch–Butland, SciPy `PchipInterpolator`) on
    /// the 4 taps, see [`pchip4`]. A data end is a repeated knot
    /// (`x0 == x1` or `x3 == x2`).
    Pchip {
        /// Source indices per output sample (must be in range).
        idx: Vec<[u32; 4]>,
        /// Knot positions (e.g. angles) of the 4 taps, non-decreasing.
        knots: Vec<[f32; 4]>,
        /// Evaluation position per output sample (normally in `[x1, x2]`).
        pos: Vec<f32>,
    },
}

impl AxisTaps {
    /// Number of output samples along this axis.
    pub fn len(&self) -> usize {
        match self {
            AxisTaps::Weights { idx, .. } | AxisTaps::Pchip { idx, .. } => idx.len(),
        }
    }

    /// True when the table has no entries.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether this is a PCHIP table.
    pub fn is_pchip(&self) -> bool {
        matches!(self, AxisTaps::Pchip { .. })
    }

    fn idx(&self) -> &[[u32; 4]] {
        match self {
            AxisTaps::Weights { idx, .. } | AxisTaps::Pchip { idx, .. } => idx,
        }
    }

    /// Words per packed GPU table entry.
    fn stride(&self) -> usize {
        if self.is_pchip() {
            12
        } else {
            8
        }
    }

    fn validate(&self, n_src: usize, axis: &str) -> Result<(), String> {
        let n = self.len();
        match self {
            AxisTaps::Weights { w, .. } if w.len() != n => {
                return Err(format!("{axis}: {} index entries but {} weight entries", n, w.len()))
            }
            AxisTaps::Pchip { knots, pos, .. } if knots.len() != n || pos.len() != n => {
                return Err(format!(
                    "{axis}: {} index entries, {} knot entries, {} positions",
                    n,
                    knots.len(),
                    pos.len()
                ))
            }
            _ => {}
        }
        if let Some((k, bad)) = self
            .idx()
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&i| i as usize >= n_src))
        {
            return Err(format!(
                "{axis}: entry {k} has tap indices {bad:?} out of range (source size {n_src})"
            ));
        }
        Ok(())
    }

    /// Evaluate entry `k` on the 4 tap values (the CPU reference).
    #[inline]
    fn eval(&self, k: usize, y: [f32; 4]) -> f32 {
        match self {
            AxisTaps::Weights { w, .. } => {
                let w = &w[k];
                let mut acc = w[0] * y[0];
                acc += w[1] * y[1];
                acc += w[2] * y[2];
                acc += w[3] * y[3];
                acc
            }
            AxisTaps::Pchip { knots, pos, .. } => pchip4(knots[k], y, pos[k]),
        }
    }

    fn pack_into(&self, out: &mut Vec<u32>) {
        match self {
            AxisTaps::Weights { idx, w } => {
                for (i, w) in idx.iter().zip(w) {
                    out.extend_from_slice(i);
                    out.extend(w.iter().map(|v| v.to_bits()));
                }
            }
            AxisTaps::Pchip { idx, knots, pos } => {
                for ((i, x), p) in idx.iter().zip(knots).zip(pos) {
                    out.extend_from_slice(i);
                    out.extend(x.iter().map(|v| v.to_bits()));
                    out.extend_from_slice(&[p.to_bits(), 0, 0, 0]);
                }
            }
        }
    }
}

fn sgn(v: f32) -> f32 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Fritsch–Butland slope at an interior knot: 0 if `sign(dl)*sign(dr) <= 0`,
/// else `(w1 + w2) / (w1/dl + w2/dr)` with `w1 = 2*hr + hl`, `w2 = hr + 2*hl`.
fn slope_interior(hl: f32, hr: f32, dl: f32, dr: f32) -> f32 {
    if sgn(dl) * sgn(dr) <= 0.0 {
        return 0.0;
    }
    let w1 = 2.0 * hr + hl;
    let w2 = hr + 2.0 * hl;
    (w1 + w2) / (w1 / dl + w2 / dr)
}

/// SciPy's `_edge_case` end slope.
fn slope_edge(h0: f32, h1: f32, m0: f32, m1: f32) -> f32 {
    let d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
    if sgn(d) != sgn(m0) {
        0.0
    } else if sgn(m0) != sgn(m1) && d.abs() > 3.0 * m0.abs() {
        3.0 * m0
    } else {
        d
    }
}

/// 4-tap PCHIP, the exact formula of the GPU kernel (and of SciPy's
/// `PchipInterpolator` restricted to the interval `[x1, x2]`).
///
/// `h0 = x1-x0, h1 = x2-x1, h2 = x3-x2`, `d_k` the secant slopes
/// (`d1 = (y2-y1)/h1`, `d0`, `d2` only where `h0 > 0`, `h2 > 0`).
/// Slopes: `m1 = h0>0 ? interior(h0,h1,d0,d1) : h2>0 ? edge(h1,h2,d1,d2) : d1`,
/// `m2 = h2>0 ? interior(h1,h2,d1,d2) : h0>0 ? edge(h1,h0,d1,d0) : d1`, where
/// `interior(hl,hr,dl,dr) = 0` if `sign(dl)*sign(dr) <= 0`, else
/// `(w1+w2)/(w1/dl + w2/dr)`, `w1 = 2hr+hl`, `w2 = hr+2hl` (Fritsch–Butland),
/// and `edge(h0,h1,m0,m1)` is SciPy's three-point end formula
/// `d = ((2h0+h1)m0 - h0 m1)/(h0+h1)`, 0 if `sign(d) != sign(m0)`, `3 m0` if
/// `sign(m0) != sign(m1) && |d| > 3|m0|`.
/// Cubic: `t = (m1+m2-2d1)/h1, c3 = t/h1, c2 = (d1-m1)/h1 - t`,
/// `y = y1 + dx*(m1 + dx*(c2 + dx*c3))`, `dx = x - x1`; `y1` if `h1 <= 0`.
pub fn pchip4(knots: [f32; 4], y: [f32; 4], x: f32) -> f32 {
    let [x0, x1, x2, x3] = knots;
    let [y0, y1, y2, y3] = y;
    let h1 = x2 - x1;
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(h1 > 0.0) {
        return y1;
    }
    let h0 = x1 - x0;
    let h2 = x3 - x2;
    let d1 = (y2 - y1) / h1;
    let has_l = h0 > 0.0;
    let has_r = h2 > 0.0;
    let d0 = if has_l { (y1 - y0) / h0 } else { 0.0 };
    let d2 = if has_r { (y3 - y2) / h2 } else { 0.0 };
    let m1 = if has_l {
        slope_interior(h0, h1, d0, d1)
    } else if has_r {
        slope_edge(h1, h2, d1, d2)
    } else {
        d1
    };
    let m2 = if has_r {
        slope_interior(h1, h2, d1, d2)
    } else if has_l {
        slope_edge(h1, h0, d1, d0)
    } else {
        d1
    };
    let t = (m1 + m2 - 2.0 * d1) / h1;
    let c3 = t / h1;
    let c2 = (d1 - m1) / h1 - t;
    let dx = x - x1;
    y1 + dx * (m1 + dx * (c2 + dx * c3))
}

/// One texture to render: source grid plus the two axis tables.
#[derive(Clone, Copy, Debug)]
pub struct ResampleJob<'a> {
    /// Source grid, `rows x cols`, row-major (gamma rows, C columns), padded.
    pub src: &'a [f32],
    /// Source rows (gamma samples incl. ghost rows).
    pub rows: usize,
    /// Source columns (C samples incl. ghost columns).
    pub cols: usize,
    /// One entry per output row (gamma); indices into `0..rows`.
    pub row_taps: &'a AxisTaps,
    /// One entry per output column (C); indices into `0..cols`.
    pub col_taps: &'a AxisTaps,
    /// Clamp negative results (ringing of 4-tap kernels) to 0.
    pub clamp_negative: bool,
}

impl ResampleJob<'_> {
    /// Output rows (= `row_taps.len()`).
    pub fn out_rows(&self) -> usize {
        self.row_taps.len()
    }

    /// Output columns (= `col_taps.len()`).
    pub fn out_cols(&self) -> usize {
        self.col_taps.len()
    }

    /// Check sizes and index ranges.
    pub fn validate(&self) -> Result<(), String> {
        if self.rows == 0 || self.cols == 0 {
            return Err(format!("empty source grid {} x {}", self.rows, self.cols));
        }
        if self.src.len() != self.rows * self.cols {
            return Err(format!(
                "source has {} values, expected {} x {}",
                self.src.len(),
                self.rows,
                self.cols
            ));
        }
        self.row_taps.validate(self.rows, "row (gamma) taps")?;
        self.col_taps.validate(self.cols, "column (C) taps")
    }
}

/// CPU reference: the same arithmetic in the same order as the kernel.
/// Panics on an invalid job (see [`ResampleJob::validate`]).
pub fn resample_cpu(job: &ResampleJob<'_>) -> Vec<f32> {
    if let Err(e) = job.validate() {
        panic!("invalid resample job: {e}");
    }
    let (nr, nc, cols) = (job.out_rows(), job.out_cols(), job.cols);
    let (ri, ci) = (job.row_taps.idx(), job.col_taps.idx());
    let mut out = Vec::with_capacity(nr * nc);
    for (r, rtaps) in ri.iter().enumerate() {
        let rt = rtaps.map(|i| i as usize * cols);
        for (c, ctaps) in ci.iter().enumerate() {
            let mut v = [0.0f32; 4];
            for (j, &cj) in ctaps.iter().enumerate() {
                let cj = cj as usize;
                let y = [
                    job.src[rt[0] + cj],
                    job.src[rt[1] + cj],
                    job.src[rt[2] + cj],
                    job.src[rt[3] + cj],
                ];
                v[j] = job.row_taps.eval(r, y);
            }
            let mut x = job.col_taps.eval(c, v);
            if job.clamp_negative {
                x = x.max(0.0);
            }
            out.push(x);
        }
    }
    out
}

const TILE_X: usize = 16;
const TILE_Y: usize = 4;
const HEADER: usize = 4;
const DESC: usize = 16;

/// Durations of the phases of a GPU render (see [`GpuContext::render_batch_timed`]).
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
    _input: wgpu::Buffer,
    output: wgpu::Buffer,
    staging: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// A batch uploaded to the device: buffers and bind groups, ready to dispatch.
pub struct GpuBatch {
    chunks: Vec<Chunk>,
    shapes: Vec<(usize, usize)>,
}

impl std::fmt::Debug for GpuBatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuBatch")
            .field("jobs", &self.shapes.len())
            .field("chunks", &self.chunks.len())
            .finish()
    }
}

impl GpuBatch {
    /// Number of jobs.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// True for an empty batch.
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// Number of chunks (dispatches) the batch was split into to respect the
    /// device's buffer-binding limit.
    pub fn chunks(&self) -> usize {
        self.chunks.len()
    }
}

/// Words a job occupies in the input buffer (excluding its descriptor).
fn job_words(job: &ResampleJob<'_>) -> usize {
    job.rows * job.cols + job.out_rows() * job.row_taps.stride() + job.out_cols() * job.col_taps.stride()
}

fn tiles(job: &ResampleJob<'_>) -> usize {
    job.out_cols().div_ceil(TILE_X) * job.out_rows().div_ceil(TILE_Y)
}

/// Pack jobs into the kernel's word layout (see `kernel.wgsl`). Returns the
/// words, the per-job output offsets, the output length and the tile count.
fn pack_chunk(jobs: &[ResampleJob<'_>], dispatch_x: u32) -> (Vec<u32>, Vec<usize>, usize, usize) {
    let n = jobs.len();
    let total: usize = HEADER + n * DESC + jobs.iter().map(job_words).sum::<usize>();
    let mut w = Vec::with_capacity(total);
    w.resize(HEADER + n * DESC, 0u32);
    let (mut out_off, mut tile_begin) = (0usize, 0usize);
    let mut out_offsets = Vec::with_capacity(n);
    for (k, job) in jobs.iter().enumerate() {
        let src_off = w.len();
        w.extend(job.src.iter().map(|v| v.to_bits()));
        let row_tab = w.len();
        job.row_taps.pack_into(&mut w);
        let col_tab = w.len();
        job.col_taps.pack_into(&mut w);
        let flags =
            job.clamp_negative as u32 | (job.row_taps.is_pchip() as u32) << 1 | (job.col_taps.is_pchip() as u32) << 2;
        let d = HEADER + k * DESC;
        let desc = [
            src_off,
            job.rows,
            job.cols,
            row_tab,
            col_tab,
            out_off,
            job.out_rows(),
            job.out_cols(),
            job.out_cols().div_ceil(TILE_X),
            tile_begin,
            flags as usize,
            job.row_taps.stride(),
            job.col_taps.stride(),
        ];
        for (i, v) in desc.iter().enumerate() {
            w[d + i] = *v as u32;
        }
        out_offsets.push(out_off);
        out_off += job.out_rows() * job.out_cols();
        tile_begin += tiles(job);
    }
    w[0] = n as u32;
    w[1] = tile_begin as u32;
    w[2] = dispatch_x;
    debug_assert_eq!(w.len(), total);
    (w, out_offsets, out_off, tile_begin)
}

impl GpuContext {
    /// Render one job on the GPU.
    pub fn render(&self, job: &ResampleJob<'_>) -> Result<Vec<f32>, GpuError> {
        Ok(self.render_batch(std::slice::from_ref(job))?.pop().unwrap_or_default())
    }

    /// Render many jobs with one upload, one command submission (one
    /// dispatch per chunk; a chunk is as many jobs as fit the device's
    /// storage-binding limit) and one read-back wait.
    pub fn render_batch(&self, jobs: &[ResampleJob<'_>]) -> Result<Vec<Vec<f32>>, GpuError> {
        self.render_batch_chunked(jobs, self.max_binding_bytes())
    }

    /// [`render_batch`](Self::render_batch) with a smaller per-chunk binding
    /// limit (bytes), to exercise the chunking in tests.
    #[doc(hidden)]
    pub fn render_batch_chunked(
        &self,
        jobs: &[ResampleJob<'_>],
        max_binding_bytes: u64,
    ) -> Result<Vec<Vec<f32>>, GpuError> {
        let batch = self.upload_inner(
            jobs,
            &mut Timings::default(),
            max_binding_bytes.min(self.max_binding_bytes()),
        )?;
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("render") });
        self.encode_dispatch(&batch, &mut enc);
        self.encode_copies(&batch, &mut enc);
        self.queue.submit([enc.finish()]);
        self.map_and_read(&batch)
    }

    /// [`render_batch`](Self::render_batch) in separately synchronised phases
    /// (pack, upload, dispatch, read-back), each timed; slightly slower than
    /// `render_batch` because of the extra waits.
    pub fn render_batch_timed(&self, jobs: &[ResampleJob<'_>]) -> Result<(Vec<Vec<f32>>, Timings), GpuError> {
        let mut t = Timings::default();
        let batch = self.upload_inner(jobs, &mut t, self.max_binding_bytes())?;
        let t0 = Instant::now();
        self.dispatch(&batch)?;
        t.dispatch = t0.elapsed();
        let t0 = Instant::now();
        let out = self.read_back(&batch)?;
        t.readback = t0.elapsed();
        Ok((out, t))
    }

    /// Validate, pack and upload a batch; waits until the upload is complete.
    pub fn upload(&self, jobs: &[ResampleJob<'_>]) -> Result<GpuBatch, GpuError> {
        self.upload_inner(jobs, &mut Timings::default(), self.max_binding_bytes())
    }

    fn upload_inner(&self, jobs: &[ResampleJob<'_>], t: &mut Timings, max_bytes: u64) -> Result<GpuBatch, GpuError> {
        let t0 = Instant::now();
        for (k, job) in jobs.iter().enumerate() {
            job.validate()
                .map_err(|reason| GpuError::InvalidJob { index: k, reason })?;
        }
        let max_words = (max_bytes / 4) as usize;
        let max_dim = self.max_workgroups_per_dim().max(1) as usize;
        // Greedy chunking: as many consecutive jobs as fit in one binding.
        let mut ranges = Vec::new();
        let mut start = 0;
        while start < jobs.len() {
            let (mut in_w, mut out_w, mut n_tiles) = (HEADER, 0usize, 0usize);
            let mut end = start;
            while end < jobs.len() {
                let j = &jobs[end];
                let (iw, ow, tl) = (DESC + job_words(j), j.out_rows() * j.out_cols(), tiles(j));
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
                        j.out_rows() * j.out_cols(),
                        max_bytes
                    ),
                });
            }
            ranges.push(start..end);
            start = end;
        }
        let mut packed = Vec::with_capacity(ranges.len());
        for r in ranges {
            let n_tiles: usize = jobs[r.clone()].iter().map(tiles).sum();
            let dx = n_tiles.clamp(1, max_dim);
            let dy = n_tiles.div_ceil(dx).max(1);
            let (words, out_offsets, out_len, _) = pack_chunk(&jobs[r.clone()], dx as u32);
            packed.push((r, words, out_offsets, out_len, (dx as u32, dy as u32)));
        }
        t.pack = t0.elapsed();

        let t0 = Instant::now();
        let mut chunks = Vec::with_capacity(packed.len());
        for (r, words, out_offsets, out_len, dispatch) in packed {
            let in_bytes = (words.len() * 4) as u64;
            let out_bytes = (out_len.max(1) * 4) as u64;
            let input = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("resample input"),
                size: in_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            self.queue.write_buffer(&input, 0, bytemuck::cast_slice(&words));
            let output = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("resample output"),
                size: out_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("resample staging"),
                size: out_bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("resample"),
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
                ],
            });
            chunks.push(Chunk {
                jobs: r,
                out_offsets,
                out_len,
                dispatch,
                _input: input,
                output,
                staging,
                bind_group,
            });
        }
        self.queue.submit(std::iter::empty());
        self.wait()?;
        t.upload = t0.elapsed();
        let shapes = jobs.iter().map(|j| (j.out_rows(), j.out_cols())).collect();
        Ok(GpuBatch { chunks, shapes })
    }

    fn encode_dispatch(&self, batch: &GpuBatch, enc: &mut wgpu::CommandEncoder) {
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("resample"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        for c in &batch.chunks {
            if c.out_len == 0 {
                continue;
            }
            pass.set_bind_group(0, &c.bind_group, &[]);
            pass.dispatch_workgroups(c.dispatch.0, c.dispatch.1, 1);
        }
    }

    fn encode_copies(&self, batch: &GpuBatch, enc: &mut wgpu::CommandEncoder) {
        for c in &batch.chunks {
            enc.copy_buffer_to_buffer(&c.output, 0, &c.staging, 0, c.output.size());
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
    pub fn read_back(&self, batch: &GpuBatch) -> Result<Vec<Vec<f32>>, GpuError> {
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

    fn map_and_read(&self, batch: &GpuBatch) -> Result<Vec<Vec<f32>>, GpuError> {
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
            r.map_err(|e| GpuError::Device(format!("mapping read-back buffer {k}: {e}")))?;
        }
        let mut out: Vec<Vec<f32>> = Vec::with_capacity(batch.len());
        for c in &batch.chunks {
            {
                let view = c
                    .staging
                    .get_mapped_range(..)
                    .map_err(|e| GpuError::Device(e.to_string()))?;
                let all: &[f32] = bytemuck::try_cast_slice(&view[..c.out_len * 4])
                    .map_err(|e| GpuError::Device(format!("read-back buffer: {e}")))?;
                for (k, j) in c.jobs.clone().enumerate() {
                    let (r, cc) = batch.shapes[j];
                    let off = c.out_offsets[k];
                    out.push(all[off..off + r * cc].to_vec());
                }
            }
            c.staging.unmap();
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Global PCHIP in f64 following SciPy's `PchipInterpolator` (written
    /// from its algorithm), to check that the 4-tap windows reproduce it.
    fn pchip_global(x: &[f64], y: &[f64], at: f64) -> f64 {
        let n = x.len();
        let h: Vec<f64> = (0..n - 1).map(|k| x[k + 1] - x[k]).collect();
        let d: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
        let sign = |v: f64| {
            if v > 0.0 {
                1.0
            } else if v < 0.0 {
                -1.0
            } else {
                0.0
            }
        };
        let edge = |h0: f64, h1: f64, m0: f64, m1: f64| {
            let dd = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1);
            if sign(dd) != sign(m0) {
                0.0
            } else if sign(m0) != sign(m1) && dd.abs() > 3.0 * m0.abs() {
                3.0 * m0
            } else {
                dd
            }
        };
        let mut m = vec![0.0; n];
        if n == 2 {
            m = vec![d[0], d[0]];
        } else {
            for k in 1..n - 1 {
                if sign(d[k - 1]) * sign(d[k]) > 0.0 {
                    let (w1, w2) = (2.0 * h[k] + h[k - 1], h[k] + 2.0 * h[k - 1]);
                    m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
                }
            }
            m[0] = edge(h[0], h[1], d[0], d[1]);
            m[n - 1] = edge(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
        }
        let k = (0..n - 1).rev().find(|&k| x[k] <= at).unwrap_or(0).min(n - 2);
        let (hk, dk) = (h[k], d[k]);
        let t = (m[k] + m[k + 1] - 2.0 * dk) / hk;
        let c3 = t / hk;
        let c2 = (dk - m[k]) / hk - t;
        let dx = at - x[k];
        y[k] + dx * (m[k] + dx * (c2 + dx * c3))
    }

    fn window(n: usize, k: usize) -> [usize; 4] {
        // Repeat the knot at a data end (x0 == x1 or x3 == x2).
        [k.saturating_sub(1), k, k + 1, (k + 2).min(n - 1)]
    }

    #[test]
    fn pchip4_matches_global_scipy_algorithm() {
        let x = [
            0.0, 5.0, 7.5, 10.0, 15.0, 25.0, 35.0, 45.0, 55.0, 65.0, 75.0, 85.0, 90.0,
        ];
        let y = [
            100.0, 98.0, 97.0, 99.0, 80.0, 40.0, 40.0, 10.0, 12.0, 3.0, 0.0, 0.0, 1.0,
        ];
        for n in [2usize, 3, 4, 13] {
            let (xs, ys) = (&x[..n], &y[..n]);
            for k in 0..n - 1 {
                let w = window(n, k);
                let knots = w.map(|i| xs[i] as f32);
                let vals = w.map(|i| ys[i] as f32);
                for s in 0..=10 {
                    let at = xs[k] + (xs[k + 1] - xs[k]) * s as f64 / 10.0;
                    let g = pchip4(knots, vals, at as f32) as f64;
                    let r = pchip_global(xs, ys, at);
                    assert!((g - r).abs() < 1e-4, "n {n} k {k} at {at}: {g} vs {r}");
                }
            }
        }
    }

    #[test]
    fn pchip4_known_values() {
        // x = 0..3, y = x^2: slopes 1.5 and 3.75 at x = 1, 2.
        let v = pchip4([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 4.0, 9.0], 1.5);
        assert!((v - 2.21875).abs() < 1e-6, "{v}");
        // Linear data is reproduced exactly; flat at a local extremum.
        let v = pchip4([0.0, 2.0, 3.0, 7.0], [1.0, 5.0, 7.0, 15.0], 2.25);
        assert!((v - 5.5).abs() < 1e-6, "{v}");
        let v = pchip4([0.0, 1.0, 2.0, 3.0], [0.0, 1.0, 0.0, 1.0], 1.0);
        assert_eq!(v, 1.0);
        // Degenerate interval.
        assert_eq!(pchip4([0.0, 1.0, 1.0, 2.0], [0.0, 3.0, 4.0, 5.0], 1.0), 3.0);
    }

    #[test]
    fn identity_taps_reproduce_source() {
        let src: Vec<f32> = (0..12).map(|i| i as f32 - 3.0).collect();
        let taps = |n: u32| AxisTaps::Weights {
            idx: (0..n).map(|i| [i, 0, 0, 0]).collect(),
            w: (0..n).map(|_| [1.0, 0.0, 0.0, 0.0]).collect(),
        };
        let (rt, ct) = (taps(3), taps(4));
        let job = ResampleJob {
            src: &src,
            rows: 3,
            cols: 4,
            row_taps: &rt,
            col_taps: &ct,
            clamp_negative: false,
        };
        assert_eq!(resample_cpu(&job), src);
        let job = ResampleJob {
            clamp_negative: true,
            ..job
        };
        assert_eq!(resample_cpu(&job), src.iter().map(|v| v.max(0.0)).collect::<Vec<_>>());
    }

    #[test]
    fn validation_catches_bad_tables() {
        let src = vec![0.0f32; 6];
        let rt = AxisTaps::Weights {
            idx: vec![[0, 1, 2, 0]],
            w: vec![[1.0; 4]],
        };
        let ct = AxisTaps::Weights {
            idx: vec![[0, 1, 2, 3]],
            w: vec![[1.0; 4]],
        };
        let job = ResampleJob {
            src: &src,
            rows: 2,
            cols: 3,
            row_taps: &rt,
            col_taps: &ct,
            clamp_negative: false,
        };
        let e = job.validate().unwrap_err();
        assert!(e.contains("row (gamma) taps") && e.contains("out of range"), "{e}");
        let rt = AxisTaps::Pchip {
            idx: vec![[0, 0, 1, 1]],
            knots: vec![],
            pos: vec![0.0],
        };
        let job = ResampleJob { row_taps: &rt, ..job };
        assert!(job.validate().unwrap_err().contains("knot"));
    }

    #[test]
    fn backend_parsing() {
        use crate::gpu::Backend;
        assert_eq!("auto".parse::<Backend>().unwrap(), Backend::Auto);
        assert_eq!("GPU".parse::<Backend>().unwrap(), Backend::Gpu);
        assert_eq!(" cpu ".parse::<Backend>().unwrap(), Backend::Cpu);
        assert!("cuda".parse::<Backend>().unwrap_err().contains("auto, gpu or cpu"));
        assert_eq!(Backend::default().to_string(), "auto");
        // `cpu` never initialises wgpu.
        assert!(matches!(
            crate::gpu::resolve(Backend::Cpu).unwrap(),
            crate::gpu::Resolved::Cpu { notice: None }
        ));
    }
}
