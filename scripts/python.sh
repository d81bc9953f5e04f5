#!/usr/bin/env bash
# Builds the Python package (python/: maturin + PyO3), installs the wheel into .venv-notebooks/ and runs pytest
# over python/tests (the bindings against the CLI, and the Dask recipe of docs/scale.md on a 2-worker LocalCluster),
# then mypy.stubtest over the package's stubs.
# Usage: bash scripts/python.sh [--no-tests]      (from anywhere)
#
# - the venv comes from scripts/notebooks.sh --setup (pinned notebooks/requirements.txt: maturin, pytest, pyarrow,
#   dask, distributed among them); exit 3 when it cannot be set up, as notebooks.sh;
# - the wheel is built with the dev profile into the root's target/ (shared with `cargo build`: the dependencies
#   the library already compiled are reused), from the workspace's one Cargo.lock (--locked);
# - PHOTOSOLID_BIN (the CLI the tests compare with): default target/debug/photosolid, built when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
VENV="$ROOT/.venv-notebooks"
bash scripts/notebooks.sh --setup || exit $?
start=$SECONDS
rm -rf target/wheels
"$VENV/bin/maturin" build --quiet --profile dev --locked -m python/Cargo.toml --target-dir "$ROOT/target" \
  -i "$VENV/bin/python" -o target/wheels
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --no-deps --force-reinstall target/wheels/*.whl
echo "python: wheel $(basename target/wheels/*.whl) built and installed in $((SECONDS - start)) s"
[ "${1:-}" = "--no-tests" ] && exit 0
if [ -z "${PHOTOSOLID_BIN:-}" ]; then
  cargo build --quiet --locked
  PHOTOSOLID_BIN="$ROOT/target/debug/photosolid"
fi
export PHOTOSOLID_BIN PHOTOSOLID_ROOT="$ROOT"
start=$SECONDS
"$VENV/bin/python" -m pytest -q -p no:cacheprovider python/tests
echo "python: pytest in $((SECONDS - start)) s"
# The stubs against the installed package: every name, signature, default and class property.
start=$SECONDS
"$VENV/bin/python" -m mypy.stubtest photosolid --mypy-config-file python/mypy.ini
echo "python: mypy.stubtest in $((SECONDS - start)) s"
