#!/usr/bin/env bash
# One command for a machine with a (real) GPU: builds and runs the GPU
# benchmarks (benches/gpu.rs: both render kernels, the real-time lookups) and
# the GPU-vs-CPU checks, then prints samples/s for each path and the largest
# differences. Honours WGPU_BACKEND=vulkan|gl (default: the best adapter).
#
# Usage: bash scripts/bench-gpu.sh
#   BENCH_PROFILE=dev  build with the dev profile instead of bench/release (quicker
#                      to build; the GPU figures do not depend on it)
#   CORPUS=DIR         files for gpu-check (default ../shared/corpus when present, else data/)
#   PREBUILT=DIR       run DIR/photosolid, DIR/gpu-bench (`cargo bench --bench gpu --no-run`'s
#                      executable) and DIR/gpu-tests (`cargo test --test gpu --no-run`'s) instead
#                      of building them: a GPU machine without a Rust toolchain. The bench and
#                      the tests read data/ and ../shared/corpus where they were built.
# Exit status: non-zero when a build, a benchmark or a check fails.
set -euo pipefail
cd "$(dirname "$0")/.."

profile="${BENCH_PROFILE:-release}"
if [ "$profile" = release ]; then
  bench_profile=(); bin_dir=target/release; build_profile=(--release)
else
  bench_profile=(--profile "$profile"); bin_dir="target/$profile"; build_profile=(--profile "$profile")
  [ "$profile" = dev ] && bin_dir=target/debug
fi
corpus="${CORPUS:-}"
if [ -z "$corpus" ]; then
  if [ -d ../shared/corpus ]; then corpus=../shared/corpus; else corpus=data; fi
fi
log="$(mktemp -t photosolid-bench-gpu.XXXXXX)"
tests_log="$(mktemp -t photosolid-gpu-tests.XXXXXX)"
trap 'rm -f "$log" "$tests_log"' EXIT

# BENCHMARKS.md's short runs.
criterion_args=(--noplot --warm-up-time 1 --measurement-time 3)
if [ -n "${PREBUILT:-}" ]; then
  echo "== prebuilt binaries in $PREBUILT =="
  bin_dir="$PREBUILT"
  bench=("$PREBUILT/gpu-bench" --bench "${criterion_args[@]}")
  gpu_tests=("$PREBUILT/gpu-tests")
else
  echo "== build (profile $profile) =="
  cargo build --locked "${build_profile[@]}" --bin photosolid
  bench=(cargo bench --locked "${bench_profile[@]}" --bench gpu -- "${criterion_args[@]}")
  gpu_tests=(cargo test --locked "${build_profile[@]}" --test gpu --)
fi
echo "== benchmarks (benches/gpu.rs, WGPU_BACKEND=${WGPU_BACKEND:-unset}) =="
"${bench[@]}" 2>&1 | tee "$log"
if grep -q "GPU benchmarks skipped" "$log"; then
  echo "no GPU adapter: only the CPU benchmarks ran" >&2
  exit 1
fi

echo
echo "== samples/s (criterion's middle estimate) =="
adapter="$(grep -m1 '^gpu adapter:' "$log" || true)"
echo "${adapter:-gpu adapter: (not printed)}"
awk '
  /^gpu\// || /^cpu\// { name = $0; next }
  /thrpt:/ && name != "" {
    gsub(/[\[\]]/, "");
    for (i = 1; i <= NF; i++) if ($i == "thrpt:") { v = $(i + 3); u = $(i + 4) }
    printf "%-72s %10s %s\n", name, v, u; name = ""
  }' "$log"

echo
echo "== GPU vs CPU: supersampled render (photosolid gpu-check $corpus, every filter, factor 5) =="
"$bin_dir/photosolid" gpu-check "$corpus" | tail -n 3
echo
echo "== GPU vs CPU: real-time lookups (hardware vs exact lookup on the same texels, data/roadway.ldt) =="
"$bin_dir/photosolid" tradeoff data/roadway.ldt --gpu --factors 5 --repeats 3 | grep -E '\+gpu'

echo
echo "== GPU tests (tests/gpu: both render kernels, the real-time lookups, BC6H, SH and lobes; PHOTOSOLID_REQUIRE_GPU=1) =="
tests_rc=0
PHOTOSOLID_REQUIRE_GPU=1 "${gpu_tests[@]}" --nocapture >"$tests_log" 2>&1 || tests_rc=$?
grep -E 'sub-texel|BC6H|max \||FAILED|panicked' "$tests_log" || true
grep -E '^test result' "$tests_log" || tail -n 20 "$tests_log"
exit "$tests_rc"
