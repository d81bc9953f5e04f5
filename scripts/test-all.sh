#!/usr/bin/env bash
# Runs every test of photosolid on a fresh machine, installing what the tests need.
# Usage: bash scripts/test-all.sh   (from anywhere; CI calls it through .ci/run)
set -euo pipefail
cd "$(dirname "$0")/.."
# Mesa's drivers want a runtime directory; without one they print a harmless "error:" line.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  XDG_RUNTIME_DIR=$(mktemp -d)
  export XDG_RUNTIME_DIR
fi

echo "== toolchain"
cargo --version
rustc --version

echo "== build (all targets, tests profile)"
cargo build --all-targets --locked 2>&1 | tail -n 3

echo "== headless Chromium for the HTML report test (tests/compare.rs skips with a notice without it)"
if ! command -v chromium >/dev/null 2>&1; then
  if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
    (apt-get update -qq && apt-get install -y -qq chromium >/dev/null) \
      || echo "WARNING: chromium could not be installed; the HTML rendering check will be skipped"
  else
    echo "WARNING: no root/apt to install chromium; the HTML rendering check will be skipped"
  fi
fi
command -v chromium >/dev/null 2>&1 && chromium --version || true

echo "== cargo test (library, integration, doc tests; corpus at ../shared/corpus when present)"
if [ -d ../shared/corpus ]; then
  echo "corpus: $(cd ../shared/corpus && pwd)"
else
  echo "corpus: ../shared/corpus not found; corpus tests print a notice and check only built-in data"
fi
cargo test --all-targets --locked
cargo test --doc --locked

echo "== the library alone (--no-default-features: no GPU, no CLI) builds and passes its unit tests; the CLI builds without the GPU"
cargo test --no-default-features --lib --locked 2>&1 | grep -E "^test result|FAILED|panicked|^error" || true
cargo test --no-default-features --lib --locked --quiet >/dev/null
cargo check --no-default-features --features cli --bins --locked 2>&1 | tail -n 1

echo "== GPU: the wgpu render against the CPU render (tests/gpu.rs) on Mesa lavapipe (Vulkan) and llvmpipe (GL)"
gpu_start=$SECONDS
if bash scripts/install-gpu-drivers.sh; then
  gpu_env="PHOTOSOLID_REQUIRE_GPU=1"
else
  echo "WARNING: GPU drivers could not be installed; running the GPU tests without PHOTOSOLID_REQUIRE_GPU (they skip without an adapter)"
  gpu_env="PHOTOSOLID_REQUIRE_GPU=0"
fi
for backend in vulkan gl; do
  echo "-- WGPU_BACKEND=$backend $gpu_env"
  env "$gpu_env" WGPU_BACKEND="$backend" cargo test --locked --test gpu
done
echo "GPU tests: $((SECONDS - gpu_start)) s"

echo "== benches compile"
cargo bench --no-run --locked 2>&1 | tail -n 1

echo "== data/ is reproducible from the code (scripts/make-data.sh)"
bash scripts/make-data.sh 2>/dev/null
if git rev-parse --git-dir >/dev/null 2>&1; then
  git diff --exit-code --stat -- data || { echo "data/ differs from what scripts/make-data.sh writes"; exit 1; }
fi

echo "== CLI smoke: demo and validate on the project's own data/"
cargo run --release --locked --quiet -- demo --output target/demo-smoke
cargo run --release --locked --quiet -- validate data

echo "== notebooks: cross-checks with trimesh / colour-science (executed copies and speed.json in target/notebooks/)"
bash scripts/notebooks.sh

echo "all tests passed"
