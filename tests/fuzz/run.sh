#!/bin/sh
# tests/fuzz/run.sh — `make fuzz`: the Lua API fuzzer for FUZZ_SECONDS
# (default 60) from seed FUZZ_SEED (default: the clock). On a failure it
# prints the seed and the replay script, shortens it with minimise.lua
# (FUZZ_MIN_SECONDS, default 120; 0 skips it) and exits 1.
# Then the mask PNG loader's fuzzer ($BUILD/fuzz_png, tests/fuzz/fuzz_png.c)
# for FUZZ_PNG_SECONDS and the snapshot stream reader's (tests/fuzz/
# fuzz_stream.c, a C test in $BUILD/test_c) for FUZZ_STREAM_SECONDS (each by
# default half of FUZZ_SECONDS), from the same seed.
# Environment: BUILD (build or build-san).
BUILD=${BUILD:-build}
RUNNER="$BUILD/tether"
SECONDS_=${FUZZ_SECONDS:-60}
SEED=${FUZZ_SEED:-$(date +%s)}
OUT="$BUILD/fuzz"
rm -rf "$OUT"
mkdir -p "$OUT/frames"
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
FUZZ_OUT="$OUT" # where m:save writes (tests/fuzz/fuzz_lib.lua)
export UBSAN_OPTIONS LSAN_OPTIONS FUZZ_OUT

echo "fuzz: seed $SEED, $SECONDS_ s, $RUNNER"
FUZZ_SEED=$SEED FUZZ_SECONDS=$SECONDS_ FUZZ_REPLAY="$OUT/replay.lua" \
    "$RUNNER" --headless --frames 1000000 --every 20 --size 96x72 --out "$OUT/frames" tests/fuzz/fuzz_api.lua \
    >"$OUT/log.txt" 2>&1
rc=$?
grep -v 'frames, ETA' "$OUT/log.txt" | grep '^fuzz:\|passed, \|FUZZ FAILURE\|ERROR:\|runtime error' | head -20
if [ "$rc" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$OUT/log.txt"; then
    PNG_SECONDS=${FUZZ_PNG_SECONDS:-$((SECONDS_ / 2))}
    "$BUILD/fuzz_png" "$PNG_SECONDS" "$SEED" "$OUT/png-last.bin" >"$OUT/png-log.txt" 2>&1
    rc=$?
    grep '^fuzz_png: \|passed, \|ERROR:\|runtime error' "$OUT/png-log.txt" | head -20
    if [ "$rc" -ne 0 ] || ! grep -q '^1 passed, 0 failed$' "$OUT/png-log.txt"; then
        echo "fuzz: the PNG fuzzer FAILED (exit $rc), seed $SEED; its last input: $OUT/png-last.bin"
        echo "fuzz: replay: $BUILD/fuzz_png $PNG_SECONDS $SEED"
        tail -n 30 "$OUT/png-log.txt" | sed 's/^/    | /'
        echo "1 passed, 1 failed"
        exit 1
    fi
    STREAM_SECONDS=${FUZZ_STREAM_SECONDS:-$((SECONDS_ / 2))}
    echo "fuzz: snapshot stream reader, seed $SEED, $STREAM_SECONDS s"
    FUZZ_SEED=$SEED FUZZ_STREAM_SECONDS=$STREAM_SECONDS "$BUILD/test_c" fuzz_stream_reader >"$OUT/stream.txt" 2>&1
    src=$?
    grep 'fuzz_stream\|passed, \|runtime error\|ERROR' "$OUT/stream.txt" | head -20
    if [ "$src" -eq 0 ] && grep -q '^1 passed, 0 failed$' "$OUT/stream.txt"; then
        echo "3 passed, 0 failed"
        exit 0
    fi
    echo "fuzz: the stream fuzzer FAILED, seed $SEED: FUZZ_SEED=$SEED FUZZ_STREAM_SECONDS=$STREAM_SECONDS $BUILD/test_c fuzz_stream_reader"
    tail -n 30 "$OUT/stream.txt" | sed 's/^/    | /'
    echo "2 passed, 1 failed"
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
