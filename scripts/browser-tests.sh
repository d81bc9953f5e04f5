#!/usr/bin/env bash
# Runs the browser tests of the HTML reports' interactive 3D view (tests/browser/test_viewer.py) in headless
# Chromium, driven by Playwright; WebGL on SwiftShader (software), so no GPU is needed.
# Usage: bash scripts/browser-tests.sh        (from anywhere)
#        bash scripts/browser-tests.sh --setup  (only create/update the virtual environment; no Chromium needed)
#
# - creates/updates the virtual environment .venv-browser/ from tests/browser/requirements.txt (pinned); the
#   install is skipped when the requirements did not change since the last one (stamp file);
# - Playwright drives the system Chromium (CHROMIUM, else chromium / chromium-browser / google-chrome on PATH):
#   `playwright install` would download a browser, which a machine without network cannot;
# - uses PHOTOSOLID_BIN (default: target/debug/photosolid, built when missing) to write the reports;
# - screenshots go to target/browser-tests/.
# Exit status 3: Chromium or the environment is missing (scripts/test-all.sh reports it as a skip, or as a
# failure with CI=true); 1: a test failed.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
VENV="$ROOT/.venv-browser"
REQ="$ROOT/tests/browser/requirements.txt"
SETUP_ONLY=0
[ "${1:-}" = "--setup" ] && SETUP_ONLY=1

exe="${CHROMIUM:-}"
if [ -z "$exe" ]; then
  for e in chromium chromium-browser google-chrome; do
    if command -v "$e" >/dev/null 2>&1; then
      exe="$(command -v "$e")"
      break
    fi
  done
fi
[ -n "$exe" ] || [ "$SETUP_ONLY" = 1 ] || { echo "browser tests: no chromium, chromium-browser or google-chrome on PATH"; exit 3; }

if [ ! -x "$VENV/bin/python" ]; then
  echo "== browser tests: creating $VENV"
  python3 -m venv "$VENV" || { echo "browser tests: python3 -m venv failed"; exit 3; }
fi
STAMP="$VENV/.requirements.sha256"
WANT="$(sha256sum "$REQ" | cut -d' ' -f1)"
if [ "$(cat "$STAMP" 2>/dev/null || true)" != "$WANT" ]; then
  echo "== browser tests: installing tests/browser/requirements.txt"
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check -r "$REQ" \
    || { echo "browser tests: pip install -r tests/browser/requirements.txt failed"; exit 3; }
  echo "$WANT" > "$STAMP"
fi
[ "$SETUP_ONLY" = 1 ] && exit 0

if [ -z "${PHOTOSOLID_BIN:-}" ]; then
  cargo build --quiet --bin photosolid
  PHOTOSOLID_BIN="$(cd "${CARGO_TARGET_DIR:-target}" && pwd)/debug/photosolid"
fi
export PHOTOSOLID_BIN
export CHROMIUM="$exe"
export BROWSER_TEST_OUT="${BROWSER_TEST_OUT:-$ROOT/target/browser-tests}"
echo "== browser tests: $exe, $PHOTOSOLID_BIN"
"$VENV/bin/python" -m pytest -q -p no:cacheprovider tests/browser
