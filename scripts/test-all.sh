#!/usr/bin/env bash
# Runs every test of photosolid on a fresh machine, installing what the tests need.
# Usage: bash scripts/test-all.sh            (from anywhere; CI calls it through .ci/run)
#        bash scripts/test-all.sh --probe    (only report which test groups can run here, and why not)
#
# Every test group that cannot run here is reported on one line, "SKIP <group>: <reason>", when it is
# found out and again in the summary at the end (the tests' own notices are captured by cargo and do not
# reach the log). With CI=true a missing GPU adapter, Chromium or notebook environment is a failure
# (exit 1), not a skip (the browser tests of the reports' 3D view, scripts/browser-tests.sh, likewise);
# a missing corpus (third-party files next to the checkout, or $PHOTOSOLID_CORPUS) is a skip everywhere,
# reported with the number of test checks that skipped it: each such test leaves one file in
# $PHOTOSOLID_SKIPPED_CORPUS_DIR (tests/common/mod.rs, `corpus()`), counted after the cargo tests.
#
# One build: the dev and test profiles share their settings (Cargo.toml), so `cargo build --all-targets`
# compiles the dependencies once, and the smoke run, data/ regeneration and notebooks use that binary
# (target/debug/photosolid) instead of building a release one. The apt packages and the Python
# environments are set up in the background while that build runs (see "set-up" below).
set -euo pipefail
cd "$(dirname "$0")/.."
PROBE_ONLY=0
[ "${1:-}" = "--probe" ] && PROBE_ONLY=1
CI_MODE=0
[ "${CI:-}" = "true" ] && CI_MODE=1
# One clean build, not an edit loop: incremental state would add about 5 GB to target/ (issue 26).
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
# Mesa's drivers want a runtime directory; without one they print a harmless "error:" line.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  XDG_RUNTIME_DIR=$(mktemp -d)
  export XDG_RUNTIME_DIR
fi

SKIPS=()
MISSING_REQUIRED=()
CORPUS_DIR="${PHOTOSOLID_CORPUS:-../shared/corpus}"
PHOTOSOLID_SKIPPED_CORPUS_DIR="$(pwd)/target/skipped-corpus-checks"
export PHOTOSOLID_SKIPPED_CORPUS_DIR
# skip GROUP REASON: a group that cannot run here (never required).
skip() {
  echo "SKIP $1: $2"
  SKIPS+=("SKIP $1: $2")
}
# need GROUP REASON: a group that must run in CI (CI=true); elsewhere a skip.
need() {
  if [ "$CI_MODE" = 1 ]; then
    echo "FAIL $1: $2 (required with CI=true)"
    MISSING_REQUIRED+=("FAIL $1: $2 (required with CI=true)")
  else
    skip "$1" "$2"
  fi
}
chromium_exe() {
  for e in chromium chromium-browser google-chrome; do
    if command -v "$e" >/dev/null 2>&1; then
      echo "$e"
      return 0
    fi
  done
  return 1
}
# gpu_adapter BACKEND: 0 when the CLI finds a GPU adapter with WGPU_BACKEND=BACKEND.
gpu_adapter() {
  local tmp
  tmp=$(mktemp -d)
  "$PHOTOSOLID_BIN" synth isotropic --c-step 90 --gamma-step 45 -o "$tmp/iso.ldt" >/dev/null 2>&1 &&
    WGPU_BACKEND="$1" "$PHOTOSOLID_BIN" texture "$tmp/iso.ldt" --backend gpu --factor 1 -o "$tmp/t.exr" \
      >/dev/null 2>"$tmp/err"
  local rc=$?
  [ $rc = 0 ] || GPU_ERR=$(head -c 300 "$tmp/err" | tr '\n' ' ')
  rm -rf "$tmp"
  return $rc
}
# probe: one line per test group (ok, or SKIP/FAIL with the reason); sets GPU_BACKENDS.
probe() {
  echo "== test groups on this machine (CI=${CI:-unset})"
  if [ -d "$CORPUS_DIR" ]; then
    echo "ok   corpus: $(cd "$CORPUS_DIR" && pwd)"
  elif [ "$PROBE_ONLY" = 1 ]; then
    skip "corpus tests" "$CORPUS_DIR not found; corpus tests check only built-in data"
  else
    echo "note corpus: $CORPUS_DIR not found; the count of skipped corpus checks follows the cargo tests"
  fi
  if exe=$(chromium_exe); then
    echo "ok   HTML report rendering: $exe"
  else
    need "HTML report rendering (tests/it/compare.rs)" "no chromium, chromium-browser or google-chrome on PATH"
  fi
  GPU_BACKENDS=()
  for backend in vulkan gl; do
    GPU_ERR=""
    if gpu_adapter "$backend"; then
      echo "ok   GPU tests, WGPU_BACKEND=$backend"
      GPU_BACKENDS+=("$backend")
    else
      need "GPU tests, WGPU_BACKEND=$backend (tests/gpu/textures.rs)" "no GPU adapter: ${GPU_ERR:-unknown}"
    fi
  done
  if [ -x .venv-notebooks/bin/python ] || python3 -c "import venv, ensurepip" >/dev/null 2>&1; then
    echo "ok   notebooks: python3 with venv"
  else
    need "notebooks (trimesh / colour-science cross-checks)" "python3 with the venv and ensurepip modules not found"
  fi
}
# corpus_skips: one SKIP line with the number of corpus checks the tests recorded as skipped
# (scripts/corpus-skips.sh counts the files tests/common/mod.rs `corpus()` leaves).
corpus_skips() {
  local reason
  reason=$(bash scripts/corpus-skips.sh "$PHOTOSOLID_SKIPPED_CORPUS_DIR" "$CORPUS_DIR")
  [ -z "$reason" ] || skip "corpus tests" "$reason"
}
summary() {
  echo "== skipped test groups: ${#SKIPS[@]}"
  for s in "${SKIPS[@]+"${SKIPS[@]}"}"; do echo "$s"; done
  if [ "${#MISSING_REQUIRED[@]}" -gt 0 ]; then
    for s in "${MISSING_REQUIRED[@]}"; do echo "$s"; done
    return 1
  fi
}

if [ "$PROBE_ONLY" = 1 ]; then
  PHOTOSOLID_BIN="${PHOTOSOLID_BIN:-target/debug/photosolid}"
  [ -x "$PHOTOSOLID_BIN" ] || { echo "no photosolid binary at $PHOTOSOLID_BIN: run cargo build first"; exit 1; }
  probe
  summary
  exit $?
fi

start_all=$SECONDS
# section TITLE: prints "== TITLE" and how long the previous section took (the summary lists them all).
TIMES=()
section_title=""
section_start=$SECONDS
section() {
  if [ -n "$section_title" ]; then
    local name="${section_title%%:*}"
    TIMES+=("$((SECONDS - section_start)) s  ${name%% (*}")
    echo "-- $((SECONDS - section_start)) s"
  fi
  section_title="$1"
  section_start=$SECONDS
  echo "== $1"
}
section "toolchain"
cargo --version
rustc --version

section "layers: imports only point down (scripts/check_layers.py, the order in ARCHITECTURE.md)"
python3 scripts/check_layers.py
section "functions a reader can hold: none over 80 lines in src/ beyond the shrinking allow list (scripts/check_fn_length.py)"
python3 scripts/check_fn_length.py

# The set-up that waits on the network and the disk (apt packages, the Python environments of the
# notebooks, the bindings and the browser tests) runs beside the build, which keeps the cores busy;
# what it printed comes out in the install section. Each step is idempotent and is checked again
# where it is used (the probe below; notebooks.sh, python.sh and browser-tests.sh set up what is
# still missing and exit 3 when they cannot), so a step that failed here is reported there.
install_chromium() {
  if ! chromium_exe >/dev/null; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
      (apt-get update -qq && apt-get install -y -qq chromium >/dev/null) || echo "chromium could not be installed"
    else
      echo "no root/apt to install chromium"
    fi
  fi
}
SETUP_LOG="$(mktemp)"
(
  set +e
  install_chromium
  bash scripts/install-gpu-drivers.sh
  bash scripts/notebooks.sh --setup
  bash scripts/browser-tests.sh --setup
  true
) >"$SETUP_LOG" 2>&1 &
SETUP_PID=$!
# kill_tree PID: the set-up and what it started, when the script stops before waiting for it.
kill_tree() {
  local child
  for child in $(pgrep -P "$1" 2>/dev/null); do kill_tree "$child"; done
  kill "$1" 2>/dev/null || true
}
trap '[ -z "${SETUP_PID:-}" ] || kill_tree "$SETUP_PID"; rm -f "$SETUP_LOG"' EXIT

section "build (all targets: library, binary, tests, benches; dev profile = test profile, one build; the set-up of the optional groups runs beside it)"
build_start=$SECONDS
cargo build --all-targets --locked 2>&1 | tail -n 3
echo "build: $((SECONDS - build_start)) s, target/ $(du -sh target 2>/dev/null | cut -f1)"
PHOTOSOLID_BIN="$(pwd)/target/debug/photosolid"
export PHOTOSOLID_BIN

section "install what the optional groups need (headless Chromium, Mesa's software GPU drivers, the Python environments; started beside the build)"
wait_start=$SECONDS
wait "$SETUP_PID" || true
SETUP_PID=""
cat "$SETUP_LOG"
rm -f "$SETUP_LOG"
echo "set-up: waited $((SECONDS - wait_start)) s after the build"
# Again in the foreground: a no-op when the background set-up did it, the reason when it could not.
install_chromium
bash scripts/install-gpu-drivers.sh || true
probe
if [ "${#MISSING_REQUIRED[@]}" -gt 0 ]; then
  summary || exit 1
fi

section "cargo test (library, integration, doc tests)"
rm -rf "$PHOTOSOLID_SKIPPED_CORPUS_DIR"
# Every target but tests/gpu, which the GPU section runs once per backend (here it would run a
# third time, on the default adapter).
cargo test --lib --bins --test it --benches --examples --locked
cargo test --doc --locked

section "rustdoc: the API docs build with every intra-doc link resolved (RUSTDOCFLAGS=-D warnings)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib --locked 2>&1 | tail -n 3

section "clippy: the [lints] of Cargo.toml hold on every target (-D warnings; no unwrap/expect in the library)"
if ! cargo clippy --version >/dev/null 2>&1; then
  rustup component add clippy >/dev/null 2>&1 || true
fi
if cargo clippy --version >/dev/null 2>&1; then
  clippy_start=$SECONDS
  cargo clippy --all-targets --locked -- -D warnings 2>&1 | tail -n 5
  echo "clippy: $((SECONDS - clippy_start)) s"
else
  need "clippy" "cargo clippy is not installed and rustup cannot add it"
fi

section "the library alone (--no-default-features: no GPU, no CLI) type-checks with its unit tests; the CLI without the GPU"
# photosolid without its features checks every crate but photosolid-gpu (wgpu is its one reason
# to exist): none of them may need it. A feature only adds code (the BC6H encoder, the CLI's
# derives, the Parquet writer), so the code without it is the code the sections above test: here
# it is type-checked, unit tests included (after clippy, whose dependency metadata it reuses),
# instead of built and run again (built and run, it cost the fresh-clone run 172 s).
cargo check --no-default-features --lib --profile test --locked -p photosolid -p photosolid-fields 2>&1 | tail -n 1
cargo check --no-default-features --features cli --bins --locked -p photosolid 2>&1 | tail -n 1
if cargo tree --no-default-features -e normal -p photosolid --prefix none 2>/dev/null | grep -q "^wgpu "; then
  echo "FAIL: photosolid without its feature gpu depends on wgpu"
  exit 1
fi

section "GPU: the wgpu render against the CPU render (tests/gpu/textures.rs) and the real-time lookups (tests/gpu/realtime.rs) on Mesa lavapipe (Vulkan) and llvmpipe (GL)"
gpu_start=$SECONDS
for backend in "${GPU_BACKENDS[@]+"${GPU_BACKENDS[@]}"}"; do
  echo "-- WGPU_BACKEND=$backend PHOTOSOLID_REQUIRE_GPU=1"
  PHOTOSOLID_REQUIRE_GPU=1 WGPU_BACKEND="$backend" cargo test --locked --test gpu
done
echo "GPU tests: $((SECONDS - gpu_start)) s"
corpus_skips

section "data/ is reproducible from the code (scripts/make-data.sh)"
bash scripts/make-data.sh 2>/dev/null
if git rev-parse --git-dir >/dev/null 2>&1; then
  git diff --exit-code --stat -- data || { echo "data/ differs from what scripts/make-data.sh writes"; exit 1; }
fi

section "CLI smoke: demo and validate on the project's own data/"
rm -rf target/demo-smoke
"$PHOTOSOLID_BIN" demo --output target/demo-smoke
[ -f target/demo-smoke/index.html ] || { echo "demo --output target/demo-smoke wrote no index.html"; exit 1; }
# The browser tests open this demo report instead of running the demo again (about 25 s).
PHOTOSOLID_DEMO_DIR="$(pwd)/target/demo-smoke"
export PHOTOSOLID_DEMO_DIR
"$PHOTOSOLID_BIN" validate data

section "browser: the HTML reports' interactive 3D view in headless Chromium (scripts/browser-tests.sh, tests/browser/)"
br_rc=0
bash scripts/browser-tests.sh || br_rc=$?
if [ "$br_rc" = 3 ]; then
  need "browser tests of the 3D view (tests/browser)" "Chromium or the Playwright environment is missing (see above)"
elif [ "$br_rc" != 0 ]; then
  echo "browser tests failed"
  exit 1
fi

section "fuzz smoke: each cargo-fuzz target for FUZZ_SECONDS (default 30) s on average, in two lanes side by side (scripts/fuzz-smoke.sh; RELIABILITY.md)"
bash scripts/fuzz-smoke.sh

section "Python bindings: wheel (maturin), pytest over python/tests: bindings vs the CLI, Dask recipe (scripts/python.sh)"
py_rc=0
bash scripts/python.sh || py_rc=$?
if [ "$py_rc" = 3 ]; then
  need "Python bindings (python/tests)" "the virtual environment could not be set up (see above)"
elif [ "$py_rc" != 0 ]; then
  echo "Python bindings failed"
  exit 1
fi

section "notebooks: cross-checks with trimesh / colour-science (executed copies and speed.json in target/notebooks/)"
nb_rc=0
bash scripts/notebooks.sh || nb_rc=$?
if [ "$nb_rc" = 3 ]; then
  need "notebooks (trimesh / colour-science cross-checks)" "the virtual environment could not be set up (see above)"
elif [ "$nb_rc" != 0 ]; then
  echo "notebooks failed"
  exit 1
fi

section "done in $((SECONDS - start_all)) s; target/ uses $(du -sh target 2>/dev/null | cut -f1)"
echo "== time per section"
for t in "${TIMES[@]}"; do echo "   $t"; done
summary || exit 1
echo "all tests passed"
