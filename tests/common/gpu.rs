//! The GPU context for GPU tests: `None` (the test prints why and passes)
//! without an adapter, unless `PHOTOSOLID_REQUIRE_GPU=1`.

use photosolid::gpu::GpuContext;

/// Whether a missing adapter is a failure (`PHOTOSOLID_REQUIRE_GPU=1`).
pub fn require_gpu() -> bool {
    std::env::var("PHOTOSOLID_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

/// The process-wide context, or `None` (test skipped, reason printed).
pub fn ctx(test: &str) -> Option<&'static GpuContext> {
    // The library's layers (the registry's `+gpu` fields, the trade table's GPU rows) ask for the
    // installed device, as the binary installs it at start-up.
    photosolid::gpu::install();
    match GpuContext::global() {
        Ok(c) => {
            eprintln!("{test}: gpu adapter {}", c.adapter());
            Some(c)
        }
        Err(e) if require_gpu() => panic!("PHOTOSOLID_REQUIRE_GPU=1 but: {e}"),
        Err(e) => {
            eprintln!("SKIPPED {test}: {e}");
            None
        }
    }
}
