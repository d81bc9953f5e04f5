#!/usr/bin/env bash
# Regenerates data/: the project's own analytic distributions (closed-form answers in
# src/synth.rs). tests/it/data.rs checks that data/ matches what this script writes.
set -euo pipefail
cd "$(dirname "$0")/.."
# PHOTOSOLID_BIN (set by scripts/test-all.sh) avoids a second, release build.
if [ -n "${PHOTOSOLID_BIN:-}" ]; then
  ps() { "$PHOTOSOLID_BIN" synth "$@"; }
else
  ps() { cargo run --release --quiet -- synth "$@"; }
fi
for ext in ldt ies; do
  ps isotropic --intensity 1000 -o data/isotropic.$ext
  ps lambertian --intensity 1000 --gamma-step 2.5 -o data/lambertian.$ext
  ps cosine-power --p 5 --intensity 1000 --gamma-step 1 -o data/cosine_p5.$ext
  ps spot --p 8 --cutoff 40 --intensity 5000 --gamma-step 1 -o data/spot_p8_c40.$ext
  ps batwing --intensity 800 --gamma-step 2.5 -o data/batwing.$ext
  ps roadway --intensity 12000 --c-step 5 --gamma-step 2.5 -o data/roadway.$ext
  ps cosine-power --p 20 --intensity 2000 --gamma-list 0,0.5,1,2,3,5,7.5,10,15,20,25,30,40,50,60,75,90 -o data/cosine_p20_nonuniform.$ext
done
