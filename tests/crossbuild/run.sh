#!/bin/sh
# tests/crossbuild/run.sh — cross-build determinism: the engine and
# tests/crossbuild/scene_hashes.c (the reference scenes of
# tests/core/scenes.c, 600 steps each) built with gcc -O0 and with clang -O2
# must print the same hashes as the engine `make` built (gcc -O2: its
# build/libtether.a; with SANITIZE=1, whose engine is instrumented, the same
# flags compiled here).
# Prints one line; exits 0 when all agree. A missing clang is a failure with
# the apt-get line (make deps installs it).
# Usage: tests/crossbuild/run.sh BUILD_DIR
BUILD=${1:-build}
OUT=$(mktemp -d /tmp/tether_crossbuild.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
SRC="src/core/*.c src/constraints/*.c src/collide/*.c src/mask/*.c"
FLAGS="-std=c11 -D_DEFAULT_SOURCE -ffp-contract=off -Iinclude -Isrc -Itests $(pkg-config --cflags libpng)"
LIBS="$(pkg-config --libs libpng) -lm"

if ! command -v clang >/dev/null 2>&1; then
    echo "crossbuild: FAILED: clang is not installed (as root: apt-get install -y clang, or make deps)"
    exit 1
fi
# the reference: the engine as make built it
if [ "$SANITIZE" = 1 ]; then
    # shellcheck disable=SC2086
    cc $FLAGS -O2 -o "$OUT/ref" tests/crossbuild/scene_hashes.c tests/core/scenes.c $SRC $LIBS || exit 1
else
    cc $FLAGS -O2 -o "$OUT/ref" tests/crossbuild/scene_hashes.c tests/core/scenes.c "$BUILD/libtether.a" $LIBS || exit 1
fi
# the others, each one compiler call (a few seconds each), two at a time
# shellcheck disable=SC2086
gcc $FLAGS -O0 -o "$OUT/gcc-O0" tests/crossbuild/scene_hashes.c tests/core/scenes.c $SRC $LIBS &
p1=$!
# shellcheck disable=SC2086
clang $FLAGS -O2 -o "$OUT/clang-O2" tests/crossbuild/scene_hashes.c tests/core/scenes.c $SRC $LIBS 2>"$OUT/clang.err" &
p2=$!
wait $p1 || { echo "crossbuild: FAILED: gcc -O0 did not build"; exit 1; }
wait $p2 || { echo "crossbuild: FAILED: clang -O2 did not build"; head -5 "$OUT/clang.err"; exit 1; }
"$OUT/ref" >"$OUT/ref.txt" || { echo "crossbuild: FAILED: the reference run failed"; exit 1; }
fail=0
for b in gcc-O0 clang-O2; do
    "$OUT/$b" >"$OUT/$b.txt"
    if ! cmp -s "$OUT/ref.txt" "$OUT/$b.txt"; then
        echo "crossbuild: FAILED: $b disagrees with the $BUILD build:"
        diff "$OUT/ref.txt" "$OUT/$b.txt" | sed 's/^/    /'
        fail=1
    fi
done
[ "$fail" = 0 ] && echo "crossbuild: gcc -O0 and clang -O2 agree with the $BUILD build on $(wc -l <"$OUT/ref.txt") scenes × 600 steps: $(awk '{printf "%s %s  ", $1, substr($3, 1, 8)}' "$OUT/ref.txt")"
exit $fail
