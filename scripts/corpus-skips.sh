#!/usr/bin/env bash
# Counts the corpus checks the tests skipped: tests/common/mod.rs `corpus()` leaves one file per
# skipping test in DIR, named <test binary>__<test> and holding the line "<binary>::<test>".
# Usage: bash scripts/corpus-skips.sh DIR CORPUS_DIR
# Prints "N checks in M test binaries skipped: CORPUS_DIR not found" when N > 0, nothing otherwise.
set -euo pipefail
dir="$1"
corpus="$2"
[ -d "$dir" ] || exit 0
n=$(find "$dir" -type f | wc -l)
[ "$n" -gt 0 ] || exit 0
m=$(find "$dir" -type f -exec cat {} + | sed 's/::.*//' | sort -u | wc -l)
echo "$n checks in $m test binaries skipped: $corpus not found"
