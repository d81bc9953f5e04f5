//! The GPU integration tests, one binary: headless wgpu textures against the
//! CPU reference (`textures`), the real-time lookups (`realtime`) and the
//! compact representations evaluated by the compute shader (`compact`).
//! `scripts/test-all.sh` runs it once per backend with
//! `PHOTOSOLID_REQUIRE_GPU=1 WGPU_BACKEND=<vulkan|gl>`.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a test a panic is the failure report"
)]

#[macro_use]
#[path = "../common/mod.rs"]
mod common;

mod compact;
mod realtime;
mod textures;
