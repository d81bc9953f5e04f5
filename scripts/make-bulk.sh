#!/usr/bin/env bash
# Makes a bulk-size catalogue of N photometric files in DIR from the project's own generators (never the corpus):
# distinct variants written by `photosolid synth` (6 kinds x exponents x cut-offs x grids x IES/LDT) and data/'s
# files, copied round-robin into DIR/shard-KK/NNNNNN.{ies,ldt} (100 sub-folders, as catalogues come in folders),
# with one file in 100 truncated to half its bytes (a broken file the batch must report, not fail on).
# Usage: bash scripts/make-bulk.sh N DIR      (PHOTOSOLID_BIN: the CLI; default target/debug/photosolid)
# Prints: files, distinct variants, broken files, bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:?N}
out=${2:?DIR}
bin=${PHOTOSOLID_BIN:-target/debug/photosolid}
mkdir -p "$out"
variants=$(mktemp -d)
trap 'rm -rf "$variants"' EXIT
k=0
for grid in "15 5" "10 2.5" "22.5 10"; do
  read -r cs gs <<<"$grid"
  for spec in "isotropic" "lambertian" "cosine-power --p 3" "cosine-power --p 20" \
              "spot --p 8 --cutoff 40" "spot --p 2 --cutoff 70" "batwing" "roadway"; do
    for ext in ies ldt; do
      # shellcheck disable=SC2086
      "$bin" synth $spec --intensity $((500 + 137 * k)) --c-step "$cs" --gamma-step "$gs" -o "$variants/v$k.$ext" >/dev/null
      k=$((k + 1))
    done
  done
done
cp data/*.ies data/*.ldt "$variants/"
mapfile -t files < <(ls "$variants"/*)
broken=0
for ((i = 0; i < n; i++)); do
  f=${files[i % ${#files[@]}]}
  dir="$out/shard-$(printf %02d $((i % 100)))"
  [ -d "$dir" ] || mkdir -p "$dir"
  dst="$dir/$(printf %06d "$i").${f##*.}"
  if ((i % 100 == 99)); then
    head -c $(($(stat -c %s "$f") / 2)) "$f" >"$dst"
    broken=$((broken + 1))
  else
    cp "$f" "$dst"
  fi
done
echo "bulk: $n files, ${#files[@]} distinct variants, $broken broken, $(du -sb "$out" | cut -f1) bytes in $out"
