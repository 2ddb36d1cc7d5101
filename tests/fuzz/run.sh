#!/bin/sh
# tests/fuzz/run.sh — `make fuzz`: every fuzz target, each for its share of
# FUZZ_SECONDS (default 60), from seed FUZZ_SEED (default: the clock). One
# summary line per target, then "N passed, M failed" (one per target); exit
# 1 if any failed. A failed target prints its seed, the failing call and how
# to replay it.
# Environment: BUILD (build or build-san), SANITIZE (1: ASan preloaded into
# luajit), FUZZ_OUT (where each target's logs, replays and files go:
# FUZZ_OUT/NAME; default BUILD/fuzz), FUZZ_TARGETS (names to run,
# default all), FUZZ_MIN_SECONDS (each minimiser's budget, default 120;
# 0 skips it; tests/fuzz/minimise.lua and minimise_c.lua), FUZZ_CALLS (replay: stop after this call; with one target).
# A run that leaves a new file in the checkout outside build/ fails
# (tests/untracked.sh), counted as one more failed target.
#
# Proof that the C fuzzer finds things, finding 5 of issue 14 (a step of dt
# 1e-320 put NaN into positions and velocities; fixed by refusing dt below
# TT_MIN_DT = 1e-9, test tests/core/test_guard.c
# step_refuses_dt_below_the_minimum_and_leaves_the_world_as_it_was): with
# world.c's check reverted to dt > 0 in a scratch copy, build-san/fuzz_c at
# commit 0153582 found it with seeds 1-6 at calls 3223, 1324, 410, 101, 47,
# 1191 (0.09 to 3.6 s; NaN positions, velocities and contact events), and
# minimise_c.lua cut seed 4's 101 calls to 4 in 3 s: a bounds constraint,
# tt_world_set_integrator(w, 0), one particle, tt_world_step(w, 1e-320).
#
# Adding a target: a function target_NAME taking (SECONDS SEED DIR) that
# prints one line and returns 0 when it passed, and NAME:WEIGHT in TARGETS.
TARGETS="lua_api:2 luajit:1 c_api:2 png:1 stream:1 journal:1"

BUILD=${BUILD:-build}
SECONDS_=${FUZZ_SECONDS:-60}
SEED=${FUZZ_SEED:-$(date +%s)}
OUT=${FUZZ_OUT:-$BUILD/fuzz}
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS LSAN_OPTIONS

# --- the Lua API fuzzer (tests/fuzz/fuzz_api.lua, under the runner) -------------
target_lua_api() {
    secs=$1 seed=$2 dir=$3 runner="$BUILD/tether"
    mkdir -p "$dir/frames"
    FUZZ_OUT="$dir" FUZZ_SEED=$seed FUZZ_SECONDS=$secs FUZZ_REPLAY="$dir/replay.lua" \
        "$runner" --headless --frames 1000000 --every 20 --size 96x72 --out "$dir/frames" tests/fuzz/fuzz_api.lua \
        >"$dir/log.txt" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$dir/log.txt"; then
        echo "fuzz lua_api: $(grep '^fuzz: .* calls' "$dir/log.txt" | tail -n 1 | sed 's/^fuzz: //') ($secs s)"
        return 0
    fi
    calls=$(grep -o -- '-- [0-9]*$' "$dir/replay.lua" | tail -n 1 | tr -dc 0-9)
    echo "fuzz lua_api: FAILED (exit $rc) at call $calls, seed $seed"
    grep -v 'frames, ETA' "$dir/log.txt" | grep 'FUZZ FAILURE\|ERROR:\|runtime error' | head -5 | sed 's/^/    | /'
    echo "    replay: $runner --headless --frames 1000000 --every 20 --size 96x72 --out /tmp/x $dir/replay.lua"
    echo "    or: FUZZ_TARGETS=lua_api FUZZ_SEED=$seed FUZZ_CALLS=$calls sh tests/fuzz/run.sh"
    tail -n 30 "$dir/log.txt" | grep -v 'frames, ETA' | sed 's/^/    | /'
    if [ "${FUZZ_MIN_SECONDS:-120}" != 0 ] && [ -n "$calls" ] && command -v lua5.4 >/dev/null 2>&1; then
        lua5.4 tests/fuzz/minimise.lua "$runner" "$seed" "$calls" "$dir" | sed 's/^/    /'
    fi
    return 1
}

# --- the C API fuzzer (tests/fuzz/fuzz_c*.c) --------------------------------------
# Every public function of tether.h must have a wrapper: the fuzzer's list
# is checked against the headers first (the static inline handle helpers
# included), so a new function without one fails here.
c_api_names() {
    for h in base world particle spring constraint composite collide terrain rewind journal clock mask; do
        sed -n 's/^TT_API[^(]*[ *]\(tt_[a-z0-9_]*\)(.*/\1/p' "include/tether/$h.h"
    done
    grep -q 'static inline tt_kind tt_handle_kind' include/tether/base.h && echo tt_handle_kind
    sed -n 's/^TT__HANDLE_U64(\(tt_[a-z]*\), .*/\1_to_u64\n\1_from_u64/p' include/tether/base.h
}

target_c_api() {
    secs=$1 seed=$2 dir=$3 bin="$BUILD/fuzz_c"
    c_api_names | sort >"$dir/headers.txt"
    "$bin" --list | sort >"$dir/wrapped.txt"
    if ! cmp -s "$dir/headers.txt" "$dir/wrapped.txt"; then
        echo "fuzz c_api: FAILED: tests/fuzz/fuzz_c_api.h and the headers disagree (< headers, > fuzzer):"
        diff "$dir/headers.txt" "$dir/wrapped.txt" | grep '^[<>]' | sed 's/^/    /'
        return 1
    fi
    FUZZ_SEED=$seed FUZZ_SECONDS=$secs "$bin" >"$dir/log.txt" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$dir/log.txt"; then
        echo "fuzz c_api: $(grep '^fuzz_c: .* calls' "$dir/log.txt" | tail -n 1 | sed 's/^fuzz_c: //')"
        return 0
    fi
    echo "fuzz c_api: FAILED (exit $rc), seed $seed"
    grep 'FUZZ FAILURE\|FUZZ CRASH\|ERROR: \|runtime error\|never reached' "$dir/log.txt" | head -5 | sed 's/^/    | /'
    grep 'replay: ' "$dir/log.txt" | head -n 1 | sed 's/^fuzz_c: /    /'
    tail -n 50 "$dir/log.txt" | cut -c1-300 | sed 's/^/    | /'
    calls=$(grep -o 'FUZZ \(FAILURE\|CRASH\) at call [0-9]*' "$dir/log.txt" | head -n 1 | tr -dc 0-9)
    if [ "${FUZZ_MIN_SECONDS:-120}" != 0 ] && [ -n "$calls" ] && command -v lua5.4 >/dev/null 2>&1; then
        lua5.4 tests/fuzz/minimise_c.lua "$bin" "$seed" "$calls" "$dir" | sed 's/^/    /'
    fi
    return 1
}

# --- the mask PNG loader (tests/fuzz/fuzz_png.c) ---------------------------------------
target_png() {
    secs=$1 seed=$2 dir=$3
    "$BUILD/fuzz_png" "$secs" "$seed" "$dir/png-last.bin" >"$dir/log.txt" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$dir/log.txt"; then
        echo "fuzz png: $(grep '^fuzz_png: ' "$dir/log.txt" | tail -n 1 | sed 's/^fuzz_png: //')"
        return 0
    fi
    echo "fuzz png: FAILED (exit $rc), seed $seed; its last input: $dir/png-last.bin"
    echo "    replay: $BUILD/fuzz_png $secs $seed"
    tail -n 30 "$dir/log.txt" | sed 's/^/    | /'
    return 1
}

# --- the byte-stream readers, each a test in test_c: the snapshot stream
# (tests/fuzz/fuzz_stream.c) and the replay journal (fuzz_journal.c) ----------
reader_target() {
    what=$1 secs=$2 seed=$3 dir=$4
    var="FUZZ_$(echo "$what" | tr a-z A-Z)_SECONDS"
    env FUZZ_SEED="$seed" "$var=$secs" "$BUILD/test_c" "fuzz_${what}_reader" >"$dir/log.txt" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$dir/log.txt"; then
        echo "fuzz $what: $(grep "^ *fuzz_$what: " "$dir/log.txt" | tail -n 1 | sed "s/^ *fuzz_$what: //") ($secs s)"
        return 0
    fi
    echo "fuzz $what: FAILED (exit $rc), seed $seed"
    echo "    replay: FUZZ_SEED=$seed $var=$secs $BUILD/test_c fuzz_${what}_reader"
    tail -n 30 "$dir/log.txt" | sed 's/^/    | /'
    return 1
}
target_stream() { reader_target stream "$@"; }
target_journal() { reader_target journal "$@"; }

# --- the same Lua fuzzer against the LuaJIT module, under luajit ----------------
# No frames (a plain host runs the update phase alone): the binding's 5.1 path.
target_luajit() {
    secs=$1 seed=$2 dir=$3 preload=
    if [ "${SANITIZE:-}" = 1 ]; then preload=$(${CC:-gcc} -print-file-name=libasan.so); fi
    FUZZ_OUT="$dir" FUZZ_SEED=$seed FUZZ_SECONDS=$secs FUZZ_REPLAY="$dir/replay.lua" LUA_CPATH="$BUILD/luajit/?.so" \
        LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0 luajit tests/fuzz/fuzz_api.lua >"$dir/log.txt" 2>&1
    rc=$?
    if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$dir/log.txt"; then
        echo "fuzz luajit: $(grep '^fuzz: .* calls' "$dir/log.txt" | tail -n 1 | sed 's/^fuzz: //') ($secs s)"
        return 0
    fi
    calls=$(grep -o -- '-- [0-9]*$' "$dir/replay.lua" | tail -n 1 | tr -dc 0-9)
    echo "fuzz luajit: FAILED (exit $rc) at call $calls, seed $seed"
    echo "    replay: FUZZ_SEED=$seed FUZZ_CALLS=$calls LUA_CPATH='$BUILD/luajit/?.so' luajit tests/fuzz/fuzz_api.lua"
    tail -n 30 "$dir/log.txt" | sed 's/^/    | /'
    return 1
}

# --- driver ---------------------------------------------------------------------------
selected=""
total_weight=0
for t in $TARGETS; do
    name=${t%%:*}
    case " ${FUZZ_TARGETS:-$name} " in *" $name "*) ;; *) continue ;; esac
    selected="$selected $t"
    total_weight=$((total_weight + ${t#*:}))
done
echo "fuzz: seed $SEED, $SECONDS_ s over:$(for t in $selected; do printf ' %s' "${t%%:*}"; done)"
# The checkout as it was at the end (tests/untracked.sh): a fuzz run once
# wrote files named nan, rk4, 42 … into the repository root.
. tests/untracked.sh
before=$(mktemp "${TMPDIR:-/tmp}/tether-fuzz.XXXXXX") || exit 1
after=$(mktemp "${TMPDIR:-/tmp}/tether-fuzz.XXXXXX") || exit 1
trap 'rm -f "$before" "$after"' EXIT INT TERM
untracked_now >"$before"
pass=0
fail=0
for t in $selected; do
    name=${t%%:*}
    share=$((SECONDS_ * ${t#*:} / total_weight))
    [ "$share" -ge 1 ] || share=1
    rm -rf "${OUT:?}/$name"
    mkdir -p "$OUT/$name"
    if "target_$name" "$share" "$SEED" "$OUT/$name"; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
done
untracked_new "$before" >"$after"
if [ -s "$after" ]; then
    echo "fuzz checkout: FAILED: the run left new files outside build/ (fuzzers write under FUZZ_OUT):"
    sed 's/^/    | /' "$after"
    fail=$((fail + 1))
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
