#!/usr/bin/env bash
# Times `photosolid validate` over a directory of N photometric files (default 8000),
# made by copying the loadable corpus files (../shared/corpus) round-robin into a
# temporary directory (never into the repository). Prints files, bytes and seconds.
# Usage: bash scripts/bench-validate.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-8000}
corpus=../shared/corpus
[ -d "$corpus" ] || { echo "no $corpus: nothing to benchmark"; exit 0; }
cargo build --release --quiet
bin=${CARGO_TARGET_DIR:-target}/release/photosolid
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mapfile -t files < <("$bin" validate --json "$corpus" | python3 -c '
import json, sys
for line in sys.stdin:
    r = json.loads(line)
    if r["ok"]:
        print(r["path"])')
for ((i = 0; i < n; i++)); do
  f=${files[i % ${#files[@]}]}
  ext=${f##*.}
  cp "$f" "$tmp/$i.$ext"
done
# A TILT=<file> reference must resolve next to its copy.
cp "$corpus"/luxera/*.dat "$tmp/" 2>/dev/null || true
bytes=$(du -sb "$tmp" | cut -f1)
sync
start=$(date +%s%N)
"$bin" validate --json "$tmp" > /dev/null || true
end=$(date +%s%N)
echo "validate: $n files, $bytes bytes, $(( (end - start) / 1000000 )) ms on $(nproc) cores"
