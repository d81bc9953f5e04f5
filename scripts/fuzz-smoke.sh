#!/usr/bin/env bash
# Bounded fuzz smoke run: each cargo-fuzz target for FUZZ_SECONDS (default 30)
# seconds on average, in FUZZ_JOBS (default 2) lanes run side by side, seeded from data/ and, when present, ../shared/corpus (copied at run
# time into fuzz/corpus-smoke/, which git ignores, and recreated each run so the
# time stays bounded; the long runs of RELIABILITY.md use fuzz/corpus/). Fails when a target crashes;
# prints one visible SKIP line and exits 0 when the toolchain or cargo-fuzz is
# unavailable. See RELIABILITY.md for the long runs.
set -uo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET="${FUZZ_SECONDS:-30}"
# The order deals `pipeline` (the slowest seed pass) into the lane of two targets (below).
TARGETS="${FUZZ_TARGETS:-ies_parse ldt_parse ies_reader pipeline ldt_reader}"

skip() {
    echo "SKIP fuzz smoke: $*"
    exit 0
}
read -r -a ALL <<<"$TARGETS"
[ "${#ALL[@]}" -gt 0 ] || skip "FUZZ_TARGETS names no target"

if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "fuzz smoke: cargo-fuzz not found; trying cargo install cargo-fuzz --locked"
    cargo install cargo-fuzz --locked >/tmp/fuzz-smoke-install.log 2>&1 \
        || skip "cargo-fuzz is not installed and cannot be installed (see /tmp/fuzz-smoke-install.log)"
fi
# libFuzzer instrumentation needs nightly flags; RUSTC_BOOTSTRAP=1 enables them on stable.
export RUSTC_BOOTSTRAP=1
if ! cargo fuzz build -s none --fuzz-dir fuzz >/tmp/fuzz-smoke-build.log 2>&1; then
    tail -5 /tmp/fuzz-smoke-build.log
    # Our own code failing to compile is a failure, never a skip.
    if grep -q "could not compile \`photosolid" /tmp/fuzz-smoke-build.log; then
        echo "fuzz smoke: FAIL: the fuzz targets do not compile (see /tmp/fuzz-smoke-build.log)"
        exit 1
    fi
    skip "the fuzz targets do not build with this toolchain ($(rustc --version)); see /tmp/fuzz-smoke-build.log"
fi

seed() { # seed TARGET MAX_SIZE EXTENSIONS...
    local dir="fuzz/corpus-smoke/$1" size="$2"
    shift 2
    rm -rf "$dir"
    mkdir -p "$dir"
    for ext in "$@"; do
        find data -maxdepth 1 -iname "*.$ext" -size "-$size" -exec cp {} "$dir/" \;
        if [ -d ../shared/corpus ]; then
            # Name each copy after its path so files of the same name do not collide.
            find ../shared/corpus -type f -iname "*.$ext" -size "-$size" -print0 |
                while IFS= read -r -d '' f; do
                    cp "$f" "$dir/$(echo "${f#../shared/corpus/}" | tr '/ ' '__')"
                done
        fi
    done
}

# One target's bounded run for SECONDS seconds: seeds, libFuzzer, and one result line in its log's .result file.
run_target() {
    local t="$1" secs="$2" log="/tmp/fuzz-smoke-$1.log" rc runs
    case "$t" in
        ies_reader | ies_parse) seed "$t" 256k ies ;;
        ldt_reader | ldt_parse) seed "$t" 256k ldt ;;
        # The pipeline thins every grid to 12 x 12 values, so large seeds cost what small ones do.
        *) seed "$t" 256k ies ldt ;;
    esac
    echo "fuzz smoke: $t for ${secs} s ($(ls "fuzz/corpus-smoke/$t" | wc -l) seeds)"
    # libFuzzer finishes its pass over the seeds before it looks at the clock;
    # `timeout` bounds that pass too (exit 124 = stopped at the limit, not a crash).
    timeout $((secs + 30)) cargo fuzz run -s none --fuzz-dir fuzz "$t" "fuzz/corpus-smoke/$t" -- \
        -dict=fuzz/dict/photometric.dict -max_total_time="$secs" \
        -max_len=65536 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 >"$log" 2>&1
    rc=$?
    runs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}')
    if [ "$rc" -eq 0 ]; then
        echo "fuzz smoke: $t ok: ${runs} executions in ${secs} s" >"$log.result"
    elif [ "$rc" -eq 124 ]; then
        echo "fuzz smoke: $t ok: stopped at the time limit during the seed pass, no crash" >"$log.result"
    else
        {
            echo "fuzz smoke: $t FAILED (exit $rc); the crashing input is in fuzz/artifacts/$t/:"
            grep -E "panicked|Test unit written|ERROR" "$log" | head -5
        } >"$log.result"
    fi
}

# libFuzzer runs one process per target. The targets are dealt into JOBS lanes (default 2, one
# per core of CI's machine) that run side by side, each lane its targets one after the other, and
# every lane gets the same time, SECONDS_PER_TARGET x targets / JOBS, shared among its targets:
# no core waits while a lone last target runs (5 targets at 30 s took 3 rounds, 90 s; now 75 s).
JOBS="${FUZZ_JOBS:-2}"
[ "$JOBS" -ge 1 ] || JOBS=1
[ "$JOBS" -le "${#ALL[@]}" ] || JOBS=${#ALL[@]}
LANE_SECONDS=$((SECONDS_PER_TARGET * ${#ALL[@]} / JOBS))
for t in "${ALL[@]}"; do rm -f "/tmp/fuzz-smoke-$t.log.result"; done
for ((lane = 0; lane < JOBS; lane++)); do
    (
        mine=()
        for ((k = lane; k < ${#ALL[@]}; k += JOBS)); do mine+=("${ALL[$k]}"); done
        for t in "${mine[@]}"; do
            run_target "$t" $((LANE_SECONDS / ${#mine[@]}))
        done
    ) &
done
wait
status=0
for t in $TARGETS; do
    if [ -f "/tmp/fuzz-smoke-$t.log.result" ]; then
        cat "/tmp/fuzz-smoke-$t.log.result"
        grep -q " FAILED " "/tmp/fuzz-smoke-$t.log.result" && status=1
    else
        echo "fuzz smoke: $t FAILED: no result (see /tmp/fuzz-smoke-$t.log)"
        status=1
    fi
done
exit $status
