#!/usr/bin/env bash
# Cross-check photosolid's Blender Cycles emulation against Blender itself.
# Needs `blender` (Debian: apt-get install --no-install-recommends blender;
# checked with 3.4.1). Renders data/{roadway,cosine_p5,batwing,spot_p8_c40}.ies
# through Cycles (scripts/blender_ies_render.py) and runs the ignored test
# tests/it/engines.rs::blender_render_matches_the_emulation on the renders.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v blender >/dev/null || { echo "blender not found (apt-get install --no-install-recommends blender)" >&2; exit 1; }
out="$(mktemp -d)"
[ -n "${KEEP_RENDERS:-}" ] || trap 'rm -rf "$out"' EXIT; echo "renders: $out"
for name in roadway cosine_p5 batwing spot_p8_c40; do
    blender -b --factory-startup --python scripts/blender_ies_render.py -- \
        "$PWD/data/$name.ies" "$out/$name.exr" 201 3.0 >"$out/$name.log" 2>&1 \
        || { cat "$out/$name.log" >&2; exit 1; }
done
PHOTOSOLID_BLENDER_RENDERS="$out" cargo test --locked --test it engines::blender_render_matches_the_emulation -- --ignored --nocapture "$@"
