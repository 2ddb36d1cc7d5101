#!/bin/sh
# tests/run.sh — the test driver behind `make test` (POSIX sh, run from the
# repository root). Environment: BUILD (build or build-san), SANITIZE (1 for
# the ASan+UBSan build).
#
# Parts, in order:
#   1. $BUILD/test_c                                 the C tests
#   1a. $BUILD/test_box2d                            the Box2D cross-check's tests (links Box2D)
#   1b. tests/layout.sh                              file/function sizes, dependency circles
#   1c. libtether.so and tether.so link neither Box2D nor libstdc++; `tether crosscheck` runs
#   2. $BUILD/tether tests/lua/test_*.lua            the Lua binding tests
#   3. fountain.lua run twice as two processes       must print the same hash
#   3b. tests/crossbuild/run.sh                    gcc -O0 and clang -O2 give this build's scene hashes
#   4. lua5.4 tests/lua/test_world.lua               stock Lua requires $BUILD/tether.so
#   4b. luajit tests/lua/test_*.lua (not test_render) LuaJIT requires $BUILD/luajit/tether.so
#   4c. tests/embed/install.sh, headers.sh            make install; the C game, C++ and the Lua
#                                                    modules on the installed copy; public headers as C99…C++20
#   4d. tests/love/run.sh                           LÖVE 11.4 under Xvfb runs a game that requires tether
#   5. $BUILD/tether --headless --steps 60 demos/*.lua   smoke test of each demo
#   6. the renderer: tests/lua/test_render.lua inside frames, every demo as
#      headless PNG frames, and the window under Xvfb (SDL_VIDEODRIVER=x11)
#   7. the checkout: no new untracked file outside build/ (tests/untracked.sh)
# Every test program ends with a line "N passed, M failed"; a non-zero exit
# or a missing line counts as a failure. One line per part, then the total
# "N passed, M failed" as the very last line; exit status 1 if anything failed.

BUILD=${BUILD:-build}
SANITIZE=${SANITIZE:-}
RUNNER="$BUILD/tether"

UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
export UBSAN_OPTIONS
# Leaks inside system GL libraries are suppressed by name, never our own.
LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
export LSAN_OPTIONS

total_pass=0
total_fail=0
tmp=$(mktemp "${TMPDIR:-/tmp}/tether-test.XXXXXX") || exit 1
tmp2=$(mktemp "${TMPDIR:-/tmp}/tether-test.XXXXXX") || exit 1
# 7. what is untracked at the start, to compare with the end (tests/untracked.sh)
. tests/untracked.sh
before=$(mktemp "${TMPDIR:-/tmp}/tether-test.XXXXXX") || exit 1
untracked_now >"$before"
trap 'rm -f "$tmp" "$tmp2" "$before"' EXIT INT TERM

add() { # add PASSED FAILED
    total_pass=$((total_pass + $1))
    total_fail=$((total_fail + $2))
}

# Shows the end of a failed part's output, indented.
show_tail() {
    tail -n 25 "$1" | sed 's/^/    | /'
}

# run_counted LABEL COMMAND... — runs a program that prints "N passed, M failed".
run_counted() {
    label=$1
    shift
    "$@" >"$tmp" 2>&1
    rc=$?
    line=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$tmp" | tail -n 1)
    if [ -z "$line" ]; then
        echo "$label: FAILED (exit $rc, no 'N passed, M failed' line)"
        show_tail "$tmp"
        add 0 1
        return
    fi
    p=${line%% passed*}
    f=${line#*passed, }
    f=${f%% failed*}
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        f=1 # it said all passed, yet exited non-zero (a sanitizer report at exit, say)
        echo "$label: $line, but exit status $rc: FAILED"
    else
        echo "$label: $line"
    fi
    if [ "$f" -ne 0 ]; then show_tail "$tmp"; fi
    add "$p" "$f"
}

# run_check LABEL COMMAND... — one check: passes if the command exits 0.
run_check() {
    label=$1
    shift
    if "$@" >"$tmp" 2>&1; then
        echo "$label: ok"
        add 1 0
    else
        echo "$label: FAILED (exit $?)"
        show_tail "$tmp"
        add 0 1
    fi
}

for f in "$BUILD/test_c" "$RUNNER" "$BUILD/tether.so" "$BUILD/luajit/tether.so"; do
    if [ ! -e "$f" ]; then
        echo "tests: $f is missing: run 'make all${SANITIZE:+ SANITIZE=$SANITIZE}' first"
        add 0 1
    fi
done

# 1. C tests
if [ -x "$BUILD/test_c" ]; then
    run_counted "c: $BUILD/test_c" "$BUILD/test_c"
fi

# 1a. The cross-check: the bridge, and the agreement measured between the engines.
if [ -x "$BUILD/test_box2d" ]; then
    run_counted "c: $BUILD/test_box2d" "$BUILD/test_box2d"
else
    echo "c: $BUILD/test_box2d is missing"
    add 0 1
fi

# 1c. Only the cross-check's own products link Box2D and libstdc++: the
# engine and the Lua module stay plain C. The module that must link them is
# checked too, so the check cannot pass by looking at nothing. The direct
# needs (readelf), not ldd's closure: under SANITIZE=1 libasan itself pulls
# libstdc++ into every program.
no_cxx() {
    for f in "$BUILD/libtether.so" "$BUILD/tether.so"; do
        if readelf -d "$f" | grep NEEDED | grep -Eq 'box2d|stdc\+\+'; then echo "$f links Box2D or libstdc++:"; readelf -d "$f"; return 1; fi
        if nm -D --undefined-only "$f" | grep -q ' _Z'; then echo "$f needs C++ symbols"; return 1; fi
    done
    readelf -d "$BUILD/tether_box2d.so" | grep NEEDED | grep -q box2d || { echo "$BUILD/tether_box2d.so does not link Box2D"; return 1; }
}
run_check "link: libtether.so and tether.so need neither Box2D nor libstdc++" no_cxx
crosscheck_ok() {
    "$RUNNER" crosscheck --quick --runs 1 fall >"$tmp2" 2>&1 || { cat "$tmp2"; return 1; }
    cat "$tmp2"
    grep -q '^fall  *dropped box: fall in 1 s' "$tmp2" || return 1
    "$RUNNER" crosscheck nope >/dev/null 2>&1
    [ $? -eq 1 ]
}
run_check "runner: tether crosscheck --quick fall prints its table; an unknown scene exits 1" crosscheck_ok
atlas_ok() {
    d=$(mktemp -d)
    "$RUNNER" atlas --quick --out "$d" docs/atlas_example.lua >"$tmp2" 2>&1 || { cat "$tmp2"; rm -rf "$d"; return 1; }
    cat "$tmp2"
    n=$(grep -c '^grapple,' "$d/grapple.csv")
    rm -rf "$d"
    [ "$n" -eq 4 ] || { echo "grapple.csv has $n rows, not 4"; return 1; }
    "$RUNNER" atlas --out "$d" /nonexistent.lua >/dev/null 2>&1
    [ $? -eq 1 ]
}
run_check "runner: tether atlas --quick SCRIPT sweeps a user's scene into CSV; a missing script exits 1" atlas_ok
# The atlas in instructions: callgrind counts each point's steps alone, so
# a point with more substeps or sweeps counts more (under the sanitizers
# Valgrind cannot run: the normal build checks it).
atlas_cg_ok() {
    d=$(mktemp -d)
    sh bench/atlas_cg.sh "$RUNNER" "$d" --quick docs/atlas_example.lua >"$tmp2" 2>&1 || { cat "$tmp2"; rm -rf "$d"; return 1; }
    cat "$tmp2"
    # substeps x iterations -> instructions, the columns found by name
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        { ir[$col["substeps"] "x" $col["iterations"]] = $col["instructions"] } END {
        ok = length(ir) == 4 && ir["1x2"] > 0 && ir["1x2"] < ir["1x8"] && ir["1x8"] < ir["4x8"] && ir["1x2"] < ir["4x2"] && ir["4x2"] < ir["4x8"]
        if (!ok) { for (k in ir) print "  " k ": " ir[k]; exit 1 } }' "$d/instructions.csv"
    r=$?
    rm -rf "$d"
    [ $r -eq 0 ] || { echo "the counts do not follow the work"; return 1; }
    "$RUNNER" atlas --instructions --quick docs/atlas_example.lua >/dev/null 2>&1
    [ $? -eq 2 ] || { echo "--instructions outside callgrind did not refuse"; return 1; }
}
if [ -z "$SANITIZE" ] && command -v valgrind >/dev/null 2>&1; then
    run_check "runner: bench/atlas_cg.sh counts the instructions of each point of a user's scene (more work, more instructions)" atlas_cg_ok
fi

# 1b. The layout rules (file and function sizes, no dependency circles).
run_check "layout: tests/layout.sh" sh tests/layout.sh "$BUILD"

# 2. Lua binding tests under the runner
for t in tests/lua/test_*.lua; do
    [ -e "$t" ] || continue
    run_counted "lua: $t" "$RUNNER" "$t"
done

# 3. Determinism across processes: two runs, one hash.
hash_of() {
    "$RUNNER" --headless --steps 300 demos/fountain.lua 2>&1 | grep -E 'hash [0-9a-f]{16}' | tail -n 1
}
h1=$(hash_of)
h2=$(hash_of)
if [ -n "$h1" ] && [ "$h1" = "$h2" ]; then
    echo "determinism: two processes agree: $h1"
    add 1 0
else
    echo "determinism: FAILED: first run '$h1', second run '$h2'"
    add 0 1
fi

# 3b. Determinism across builds: gcc -O0 and clang -O2 agree with this build.
if SANITIZE=$SANITIZE sh tests/crossbuild/run.sh "$BUILD"; then add 1 0; else add 0 1; fi

# 4. Stock lua5.4 loads the module.
if ! command -v lua5.4 >/dev/null 2>&1; then
    echo "stock lua5.4: skipped: lua5.4 is not installed"
elif [ "$SANITIZE" = 1 ]; then
    # The module is built with ASan, lua5.4 is not: the ASan runtime must be
    # loaded first. Leak checking is off: lua5.4 itself does not free its
    # state at exit, and the runner tests above already check for leaks.
    asan=$(${CC:-gcc} -print-file-name=libasan.so 2>/dev/null)
    if [ -n "$asan" ] && [ -e "$asan" ]; then
        run_counted "stock lua5.4 (ASan preloaded): tests/lua/test_world.lua" \
            env LD_PRELOAD="$asan" ASAN_OPTIONS=detect_leaks=0 LUA_CPATH="$BUILD/?.so" lua5.4 tests/lua/test_world.lua
    else
        echo "stock lua5.4: skipped: the ASan runtime (libasan.so) was not found for LD_PRELOAD"
    fi
else
    run_counted "stock lua5.4: tests/lua/test_world.lua" env LUA_CPATH="$BUILD/?.so" lua5.4 tests/lua/test_world.lua
fi

# 4b. LuaJIT, LÖVE's Lua, loads the same binding built against its 5.1 API
# (src/lua/lua_compat.h): every Lua test a plain host can run. test_render
# needs the runner's frames.
if ! command -v luajit >/dev/null 2>&1; then
    echo "luajit: FAILED: luajit is not installed (make deps installs it)"
    add 0 1
else
    if [ "$SANITIZE" = 1 ]; then
        asan=$(${CC:-gcc} -print-file-name=libasan.so 2>/dev/null)
        lj_env="LD_PRELOAD=$asan ASAN_OPTIONS=detect_leaks=0"
        lj_note=" (ASan preloaded)"
    else
        lj_env="LD_PRELOAD="
        lj_note=""
    fi
    for t in tests/lua/test_*.lua; do
        case "$t" in
        # the runner's frames
        tests/lua/test_render.lua) continue ;;
        esac
        # shellcheck disable=SC2086
        run_counted "luajit$lj_note: $t" env $lj_env LUA_CPATH="$BUILD/luajit/?.so" luajit "$t"
    done
fi

# 4c. Embedding: tether installed as a game developer installs it, used
# from the installed copy only; the public headers under every standard.
run_counted "install: tests/embed/install.sh (make install; C game, C++, renderer, Lua paths)" \
    env BUILD="$BUILD" SANITIZE="$SANITIZE" sh tests/embed/install.sh
run_counted "headers: tests/embed/headers.sh (C99, C11, C++11/17/20, -Wpedantic -Werror)" sh tests/embed/headers.sh

# 4d. LÖVE (its LuaJIT) runs a tiny game that requires the LuaJIT module,
# under Xvfb.
if command -v love >/dev/null 2>&1 && command -v xvfb-run >/dev/null 2>&1; then
    run_counted "love: tests/love/run.sh (LÖVE 11.4 under Xvfb${SANITIZE:+, ASan preloaded})" \
        env BUILD="$BUILD" SANITIZE="$SANITIZE" sh tests/love/run.sh
else
    echo "love: FAILED: love or xvfb-run is not installed (make deps installs them)"
    add 0 1
fi

# 5. Each demo runs headless for 60 steps and prints the runner's summary.
demo_ok() {
    "$RUNNER" --headless --steps 60 "$1" >"$tmp2" 2>&1 || { cat "$tmp2"; return 1; }
    cat "$tmp2"
    grep -q '^tether: 60 steps of ' "$tmp2"
}
for d in demos/*.lua; do
    [ -e "$d" ] || continue
    run_check "demo: $d" demo_ok "$d"
done

# 6. The renderer.
frames=$(mktemp -d "${TMPDIR:-/tmp}/tether-frames.XXXXXX") || exit 1
trap 'rm -f "$tmp" "$tmp2" "$before"; rm -rf "$frames"' EXIT INT TERM
run_counted "lua: tests/lua/test_render.lua (inside frames)" \
    "$RUNNER" --headless --frames 2 --size 200x150 --out "$frames/lua" tests/lua/test_render.lua
run_counted "lua: tests/lua/auto_view.lua (no tether.draw: every world shown)" \
    "$RUNNER" --headless --frames 2 --size 160x120 --out "$frames/auto" tests/lua/auto_view.lua

# the renderer's command line: misuse exits 2 and says why
bad_options_ok() {
    for opts in "--headless --frames 3" "--out $frames/x" "--size 10x10" "--frames 0" "--headless --screenshot a.png" \
                "--headless --events e.txt" "--every 0 --headless --out $frames/x"; do
        # shellcheck disable=SC2086
        "$RUNNER" $opts demos/fountain.lua >"$tmp2" 2>&1
        rc=$?
        if [ "$rc" -ne 2 ] || ! grep -q '^tether: .*--' "$tmp2"; then
            echo "'$opts': exit $rc, expected 2 with a message naming the option"; cat "$tmp2"; return 1
        fi
    done
}
run_check "runner: misused frame/window options exit 2 with a message" bad_options_ok

# each demo as 3 headless PNG frames of 320x240, 10 steps apart
demo_frames_ok() {
    out="$frames/$(basename "$1" .lua)"
    "$RUNNER" --headless --frames 3 --every 10 --size 320x240 --out "$out" "$1" >"$tmp2" 2>&1 || { cat "$tmp2"; return 1; }
    cat "$tmp2"
    grep -q '^tether: 3 frames 320x240 ' "$tmp2" || return 1
    for k in 00000 00001 00002; do
        [ -s "$out/frame_$k.png" ] || { echo "missing $out/frame_$k.png"; return 1; }
    done
}
for d in demos/*.lua; do
    [ -e "$d" ] || continue
    run_check "demo frames: $d" demo_frames_ok "$d"
done

# the window: each demo for 20 frames under Xvfb, a screenshot of the last, exit status 0
window_ok() {
    shot="$frames/window-$(basename "$1" .lua).png"
    SDL_VIDEODRIVER=x11 ASAN_OPTIONS="$window_asan" xvfb-run -a "$RUNNER" --frames 20 --size 320x240 --screenshot "$shot" "$1" \
        >"$tmp2" 2>&1 || { cat "$tmp2"; return 1; }
    cat "$tmp2"
    grep -q '^tether: window: 20 frames' "$tmp2" && [ -s "$shot" ] && [ "$(od -An -c -N4 "$shot" | tr -d ' ')" = "211PNG" ]
}
# the window's keys and mouse drag, driven by scripted events
window_input() {
    SDL_VIDEODRIVER=x11 ASAN_OPTIONS="$window_asan" xvfb-run -a "$RUNNER" --frames 40 --size 320x240 \
        --events tests/window_input.events tests/window_input.lua
}
if command -v xvfb-run >/dev/null 2>&1; then
    if [ "$SANITIZE" = 1 ]; then
        # ASan stays on; leak checking is off for this one process: the X11,
        # dbus and GL driver libraries SDL loads leak a few blocks, and the
        # driver is unloaded before exit, so no suppression can name it. Our
        # own code's leaks are checked by every other (headless) run above.
        window_asan="detect_leaks=0${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
        for d in demos/*.lua; do
            run_check "window under Xvfb: $d, 20 frames + screenshot (ASan, leak check off)" window_ok "$d"
        done
        run_counted "window under Xvfb: keys and mouse drag, tests/window_input.lua (ASan, leak check off)" window_input
    else
        window_asan=${ASAN_OPTIONS:-}
        for d in demos/*.lua; do
            run_check "window under Xvfb: $d, 20 frames + screenshot" window_ok "$d"
        done
        run_counted "window under Xvfb: keys and mouse drag, tests/window_input.lua" window_input
    fi
else
    echo "window under Xvfb: skipped: xvfb-run is not installed (apt-get install xvfb xauth)"
fi

# 7. The checkout as it was: no new file outside the build folders.
untracked_new "$before" >"$tmp"
if [ -s "$tmp" ]; then
    echo "checkout: FAILED: the tests left new files outside build/ (write scratch files to \$TMPDIR or \$BUILD):"
    sed 's/^/    | /' "$tmp"
    add 0 1
else
    echo "checkout: ok: no new untracked file outside build/"
    add 1 0
fi

echo "$total_pass passed, $total_fail failed"
[ "$total_fail" -eq 0 ]
