#!/usr/bin/env bash
# Runs the cross-check notebooks (notebooks/*.ipynb) headless; exits non-zero when any cell fails.
# Usage: bash scripts/notebooks.sh [NOTEBOOK.ipynb ...]   (from anywhere; default: every notebook)
#        bash scripts/notebooks.sh --setup                 (only create/update the virtual environment)
#
# - creates/updates the virtual environment .venv-notebooks/ from notebooks/requirements.txt (pinned);
#   the install is skipped when the requirements did not change since the last one (stamp file);
# - hands the binary PHOTOSOLID_BIN to the notebooks; when unset, builds the release binary
#   (cargo build --release) and uses ${CARGO_TARGET_DIR:-target}/release/photosolid;
# - executes each notebook with nbclient (no network needed at run time) and writes the executed copy to
#   target/notebooks/<name>.ipynb, NB_JOBS (default 2) at a time; the notebooks write their scratch files and
#   speed.json there too.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
VENV="$ROOT/.venv-notebooks"
REQ="$ROOT/notebooks/requirements.txt"
OUT="$ROOT/target/notebooks"

# Exit status 3: the environment could not be set up (scripts/test-all.sh reports it as a skip, or as a
# failure with CI=true); 1: a notebook failed.
if [ ! -x "$VENV/bin/python" ]; then
  echo "== notebooks: creating $VENV"
  python3 -m venv "$VENV" || { echo "notebooks: python3 -m venv failed"; exit 3; }
fi
STAMP="$VENV/.requirements.sha256"
WANT="$(sha256sum "$REQ" | cut -d' ' -f1)"
if [ "$(cat "$STAMP" 2>/dev/null || true)" != "$WANT" ]; then
  echo "== notebooks: installing notebooks/requirements.txt"
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check -r "$REQ" \
    || { echo "notebooks: pip install -r notebooks/requirements.txt failed"; exit 3; }
  echo "$WANT" > "$STAMP"
fi
[ "${1:-}" = "--setup" ] && exit 0
# The notebooks use the Python bindings: build and install the wheel when the venv lacks it.
if ! "$VENV/bin/python" -c "import photosolid" >/dev/null 2>&1; then
  bash scripts/python.sh --no-tests || { echo "notebooks: the photosolid wheel could not be built"; exit 1; }
fi

if [ -z "${PHOTOSOLID_BIN:-}" ]; then
  echo "== notebooks: release binary"
  cargo build --release --quiet
  PHOTOSOLID_BIN="$(cd "${CARGO_TARGET_DIR:-target}" && pwd)/release/photosolid"
fi
export PHOTOSOLID_BIN
export PHOTOSOLID_ROOT="$ROOT"
export PHOTOSOLID_NB_OUT="$OUT"
export MPLBACKEND=module://matplotlib_inline.backend_inline
"$PHOTOSOLID_BIN" --version

mkdir -p "$OUT"
if [ "$#" -gt 0 ]; then NBS=("$@"); else NBS=(notebooks/*.ipynb); fi
# One notebook: executed with nbclient, its summary cells' output and its errors in $OUT/<name>.log,
# its exit status in $OUT/<name>.status.
run_notebook() {
  local nb="$1" name
  name="$(basename "$nb")"
  local start=$SECONDS rc=0
  "$VENV/bin/python" - "$nb" "$OUT/$name" >"$OUT/$name.log" 2>&1 <<'PY' || rc=$?
import sys, os, nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError
src, dst = sys.argv[1], sys.argv[2]
nb = nbformat.read(src, as_version=4)
client = NotebookClient(nb, timeout=600, kernel_name="python3",
                        resources={"metadata": {"path": os.path.dirname(os.path.abspath(src))}})
try:
    client.execute()
    ok = True
except CellExecutionError as e:
    print(str(e)[-4000:], file=sys.stderr)
    ok = False
finally:
    nbformat.write(nb, dst)
# echo the notebook's own printed lines (the check summary) so the test log shows them
for cell in nb.cells:
    if cell.cell_type == "code" and "summary" in cell.metadata.get("tags", []):
        for o in cell.get("outputs", []):
            if o.get("output_type") == "stream":
                sys.stdout.write(o.get("text", ""))
sys.exit(0 if ok else 1)
PY
  echo "$rc $((SECONDS - start))" >"$OUT/$name.status"
}

# NB_JOBS notebooks at a time (default 2, one per core of CI's machine: a notebook's kernel runs
# Python on one core, and the notebooks write to their own folders under $OUT); their output is
# printed in order when all have run.
JOBS="${NB_JOBS:-2}"
running=0
for nb in "${NBS[@]}"; do
  rm -f "$OUT/$(basename "$nb").status"
  run_notebook "$nb" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait
status=0
for nb in "${NBS[@]}"; do
  name="$(basename "$nb")"
  echo "== notebook $name"
  cat "$OUT/$name.log" 2>/dev/null || true
  read -r rc secs <"$OUT/$name.status" 2>/dev/null || { rc=1; secs=0; }
  if [ "$rc" = 0 ]; then
    echo "   ok ($secs s; executed copy: target/notebooks/$name)"
  else
    echo "   FAILED ($secs s; executed copy: target/notebooks/$name)"
    status=1
  fi
done
[ -f "$OUT/speed.json" ] && echo "speed: $(cat "$OUT/speed.json")"
exit $status
