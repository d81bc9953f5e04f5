#!/usr/bin/env bash
# Counts the corpus checks the tests skipped: tests/common/mod.rs `corpus()` leaves one file per
# skipping test in DIR, named <test file>__<test> and holding the line "<file>::<test>" (the file being the module of tests/it/main.rs).
# Usage: bash scripts/corpus-skips.sh DIR CORPUS_DIR
# Prints "N checks in M test files skipped: CORPUS_DIR not found" when N > 0, nothing otherwise.
set -euo pipefail
dir="$1"
corpus="$2"
[ -d "$dir" ] || exit 0
n=$(find "$dir" -type f | wc -l)
[ "$n" -gt 0 ] || exit 0
m=$(find "$dir" -type f -exec cat {} + | sed 's/::.*//' | sort -u | wc -l)
echo "$n checks in $m test files skipped: $corpus not found"
