//! photosolid's GPU: rendering light distribution textures and evaluating
//! stored textures and compact representations on a headless wgpu device.
//!
//! This crate implements [`photosolid_fields::device::GpuDevice`] ([`Wgpu`]);
//! a program plugs it in at start-up with [`install`] (the `photosolid`
//! binary does, behind its feature `gpu`, on by default). The layers that ask
//! for a GPU know only the trait, so none of them depends on wgpu.
//!
//! A headless [wgpu](https://wgpu.rs) compute pipeline that renders a
//! [`LightTexture`](crate::reconstruct::LightTexture) exactly as the CPU
//! [`crate::reconstruct::render_with`] does, from the same
//! [`RenderPlan`](crate::reconstruct::RenderPlan) tap tables and the same
//! padded texture, with a WGSL port of [`crate::reconstruct::combine`] (see
//! [`resample`] for the semantics), on Vulkan or GL/EGL adapters, including
//! Mesa's software drivers (lavapipe, llvmpipe).
//!
//! - [`GpuContext::global`]: instance, adapter, device and pipeline, created
//!   once per process (honours `WGPU_BACKEND=vulkan|gl`);
//! - [`render_gpu`] / [`render_batch`]: one texture, or many in one submission;
//! - [`RenderJob`] with [`GpuContext::upload`] / [`GpuContext::dispatch`] /
//!   [`GpuContext::read_back`] and [`GpuContext::render_jobs_timed`]: the
//!   phases, separately, for a plan built once and shared with the CPU
//!   ([`render_cpu`]);
//! - [`Backend`] / [`resolve`]: `--backend auto|gpu|cpu`;
//! - [`RenderKernel`]: the two-pass kernel (`separable.wgsl`, γ pass then C
//!   pass, the default) or the fused first kernel (`kernel.wgsl`);
//! - [`realtime`]: Wallner's (2008) real-time path, a stored texture sampled by the
//!   texture hardware (bilinear, Catmull–Rom from linear fetches) for
//!   batches of directions; [`precision`]: what that costs per adapter
//!   (sub-texel weight bits, difference from the exact lookup); a plane
//!   lit through those lookups (Wallner's (2008) Figure 5 setting) is a
//!   report figure, `photosolid::report::shading`.
//!
//! Output goes to a storage buffer rather than an `r32float` storage texture:
//! it needs no 256-byte row padding on read-back, a whole batch fits in one
//! binding with per-item offsets, and storage buffers in compute shaders are
//! available on every backend we target (GLES 3.1+, which llvmpipe provides).

#![forbid(unsafe_code)]
#![warn(missing_docs)]

// The layers below, under the names this crate's modules use (`crate::reconstruct`, ...).
use photosolid_fields::{device, error, formats, model, reconstruct};

mod backend;
pub mod check;
mod context;
pub mod resample;
mod wgpu_device;

pub use backend::{resolve, Backend, Resolved};
pub use context::{list_adapters, requested_backends, AdapterSummary, GpuContext, COMPILED_BACKENDS};
pub use wgpu_device::{install, Wgpu};
mod batch;
pub mod compact;
pub mod precision;
pub mod realtime;
pub use resample::{
    clamp_count_range, jobs, plans, render_batch, render_cpu, render_gpu, GpuBatch, RenderJob, RenderKernel, Timings,
};

pub use photosolid_fields::error::GpuError;
/// The texture formats a [`realtime::RealtimeTexture`] reports, wgpu's own type.
pub use wgpu::TextureFormat;
