#!/bin/sh
# tests/fuzz/run.sh — `make fuzz`: the Lua API fuzzer for FUZZ_SECONDS
# (default 60) from seed FUZZ_SEED (default: the clock). On a failure it
# prints the seed and the replay script, shortens it with minimise.lua
# (FUZZ_MIN_SECONDS, default 120; 0 skips it) and exits 1. Then the same
# fuzzer against the LuaJIT module under luajit (no frames: the update phase)
# for FUZZ_LUAJIT_SECONDS (default a third of FUZZ_SECONDS).
# Environment: BUILD (build or build-san), SANITIZE (1: ASan preloaded into luajit).
BUILD=${BUILD:-build}
RUNNER="$BUILD/tether"
SECONDS_=${FUZZ_SECONDS:-60}
SEED=${FUZZ_SEED:-$(date +%s)}
OUT="$BUILD/fuzz"
rm -rf "$OUT"
mkdir -p "$OUT/frames"
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export UBSAN_OPTIONS LSAN_OPTIONS

echo "fuzz: seed $SEED, $SECONDS_ s, $RUNNER"
FUZZ_SEED=$SEED FUZZ_SECONDS=$SECONDS_ FUZZ_REPLAY="$OUT/replay.lua" \
    "$RUNNER" --headless --frames 1000000 --every 20 --size 96x72 --out "$OUT/frames" tests/fuzz/fuzz_api.lua \
    >"$OUT/log.txt" 2>&1
rc=$?
grep -v 'frames, ETA' "$OUT/log.txt" | grep '^fuzz:\|passed, \|FUZZ FAILURE\|ERROR:\|runtime error' | head -20
if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$OUT/log.txt"; then
    LJ_SECONDS=${FUZZ_LUAJIT_SECONDS:-$(( (SECONDS_ + 2) / 3 ))}
    [ "$LJ_SECONDS" = 0 ] && exit 0
    lj_preload=
    if [ "${SANITIZE:-}" = 1 ]; then lj_preload=$(${CC:-gcc} -print-file-name=libasan.so); fi
    echo "fuzz: seed $SEED, $LJ_SECONDS s, luajit with $BUILD/luajit/tether.so"
    FUZZ_SEED=$SEED FUZZ_SECONDS=$LJ_SECONDS FUZZ_REPLAY="$OUT/replay-luajit.lua" LUA_CPATH="$BUILD/luajit/?.so" \
        LD_PRELOAD="$lj_preload" ASAN_OPTIONS=detect_leaks=0 luajit tests/fuzz/fuzz_api.lua >"$OUT/log-luajit.txt" 2>&1
    rc=$?
    grep '^fuzz:\|passed, \|FUZZ FAILURE\|ERROR:\|runtime error' "$OUT/log-luajit.txt" | head -20
    if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$OUT/log-luajit.txt"; then
        exit 0
    fi
    calls=$(grep -o -- '-- [0-9]*$' "$OUT/replay-luajit.lua" | tail -n 1 | tr -dc 0-9)
    echo "fuzz: luajit FAILED (exit $rc) at call $calls, seed $SEED"
    echo "fuzz: replay: FUZZ_SEED=$SEED FUZZ_CALLS=$calls LUA_CPATH='$BUILD/luajit/?.so' luajit tests/fuzz/fuzz_api.lua"
    tail -n 30 "$OUT/log-luajit.txt" | sed 's/^/    | /'
    echo "0 passed, 1 failed"
    exit 1
fi
calls=$(grep -o -- '-- [0-9]*$' "$OUT/replay.lua" | tail -n 1 | tr -dc 0-9)
echo "fuzz: FAILED (exit $rc) at call $calls, seed $SEED"
echo "fuzz: replay: $RUNNER --headless --frames 1000000 --every 20 --size 96x72 --out /tmp/x $OUT/replay.lua"
echo "fuzz: or: FUZZ_SEED=$SEED FUZZ_CALLS=$calls sh tests/fuzz/run.sh"
tail -n 30 "$OUT/log.txt" | grep -v 'frames, ETA' | sed 's/^/    | /'
if [ "${FUZZ_MIN_SECONDS:-120}" != 0 ] && [ -n "$calls" ] && command -v lua5.4 >/dev/null 2>&1; then
    lua5.4 tests/fuzz/minimise.lua "$RUNNER" "$SEED" "$calls" "$OUT"
fi
echo "0 passed, 1 failed"
exit 1
