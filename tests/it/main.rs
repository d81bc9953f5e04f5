//! The CPU integration tests, one binary (issue 26: 32 binaries that each
//! linked wgpu made target/ 18 GB and the CI build 12 minutes). Each module
//! was its own test file; `cargo test --test it <module>::` runs one.
//! The GPU tests are the other binary, `tests/gpu/`.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "in a test a panic is the failure report"
)]

#[macro_use]
#[path = "../common/mod.rs"]
mod common;

mod adaptive_solid;
mod angles_agree;
mod atomic_writes;
mod batch;
mod cli;
mod cli_edges;
mod cli_messages;
mod compare;
mod conversions;
mod corpus;
mod damaged;
mod data;
mod engines;
mod engines_renderers;
mod extension;
mod fit;
mod front;
mod fuzz_regressions;
mod gldf_tm33;
mod holdout_peers;
mod ies;
mod ldt;
mod mesh_files;
mod nearest;
mod photometry;
mod plots;
mod plots_legible;
mod public_api;
mod reader_errors;
mod reconstruct;
mod road;
mod road_design;
mod roundtrip_props;
mod scene;
mod scene_plans;
mod scripts;
mod sh;
mod sh_trade;
mod solid;
mod trade;
mod typed_errors;
mod viewer;
