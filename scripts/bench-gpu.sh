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
trap 'rm -f "$log"' EXIT

echo "== build (profile $profile) =="
cargo build --locked "${build_profile[@]}" --bin photosolid
echo "== benchmarks (benches/gpu.rs, WGPU_BACKEND=${WGPU_BACKEND:-unset}) =="
cargo bench --locked "${bench_profile[@]}" --bench gpu -- --noplot 2>&1 | tee "$log"
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
