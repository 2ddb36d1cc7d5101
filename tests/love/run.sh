#!/bin/sh
# tests/love/run.sh — Debian's LÖVE (11.4, LuaJIT) runs the game in
# tests/love/ under Xvfb with the LuaJIT module of $BUILD; the scene's hash
# after its frames must equal what plain luajit and lua5.4 reach with the
# same scene (tests/love/scene.lua). Run from the repository root;
# environment BUILD, SANITIZE. The picture LÖVE drew is kept as
# $BUILD/love_test.png. Then the LÖVE demo (demos/love/) plays 120 frames
# and must exit 0 with its summary line, and the main.lua of README
# "Embedding" plays 120 frames: its ball must come to rest on its floor.
# Prints "N passed, M failed".
BUILD=${BUILD:-build}
root=$(pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tether-love.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
preload=
if [ "${SANITIZE:-}" = 1 ]; then preload=$(${CC:-cc} -print-file-name=libasan.so); fi
ref='package.path = "tests/love/?.lua;" .. package.path
local S, tether = require "scene", require "tether"
local s = S.build(tether)
for _ = 1, S.FRAMES do S.step(s) end
print(s.world:hash())'
lj=$(LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0 LUA_CPATH="$BUILD/luajit/?.so" luajit -e "$ref") || exit 1
l54=$(LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0 LUA_CPATH="$BUILD/?.so" lua5.4 -e "$ref") || exit 1
pass=0
fail=0
if [ -n "$lj" ] && [ "$lj" = "$l54" ]; then
    pass=1
    echo "ok the scene reaches one hash under luajit and lua5.4: $lj"
else
    fail=1
    echo "FAIL the scene under luajit: '$lj', under lua5.4: '$l54'"
fi
# LÖVE writes into $XDG_DATA_HOME/love/<identity>: a fresh one per run.
XDG_DATA_HOME=$tmp TETHER_LOVE_HASH=$lj LUA_CPATH="$root/$BUILD/luajit/?.so" LD_PRELOAD="$preload" \
    ASAN_OPTIONS=detect_leaks=0 timeout 120 xvfb-run -a love tests/love >"$tmp/out.txt" 2>&1
rc=$?
cat "$tmp/out.txt"
cp "$tmp/love/tether-love-test/love_test.png" "$BUILD/love_test.png" 2>/dev/null
line=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$tmp/out.txt" | tail -n 1)
if [ "$rc" -ne 0 ] || [ -z "$line" ]; then
    echo "love exited $rc"
    fail=$((fail + 1))
else
    pass=$((pass + ${line%% passed*}))
    f=${line#*passed, }
    fail=$((fail + ${f%% failed*}))
fi
XDG_DATA_HOME=$tmp LUA_CPATH="$root/$BUILD/luajit/?.so" LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0 \
    timeout 120 xvfb-run -a love demos/love --frames 120 >"$tmp/demo.txt" 2>&1
rc=$?
if [ "$rc" -eq 0 ] && grep -q '^love demo: 12[0-9] steps, [0-9]* particles, hash [0-9a-f]*$' "$tmp/demo.txt"; then
    pass=$((pass + 1))
    echo "ok the LÖVE demo: $(grep '^love demo:' "$tmp/demo.txt")"
else
    fail=$((fail + 1))
    echo "FAIL the LÖVE demo exited $rc:"
    tail -n 15 "$tmp/demo.txt"
fi
# README's example, as written there, plus a few lines that stop it and report
mkdir -p "$tmp/readme"
awk '/^\*\*LÖVE \(LuaJIT\)\.\*\*/ { on = 1 } on && /^```lua$/ { code = 1; next } code && /^```$/ { exit } code' \
    README.md >"$tmp/readme/main.lua"
# no sound device on a test machine: audio off (ASan-preloaded OpenAL waits for one)
cp tests/love/conf.lua "$tmp/readme/conf.lua"
cat >>"$tmp/readme/main.lua" <<'EOF'
local frames, update = 0, love.update
function love.update(dt)
  update(dt)
  frames = frames + 1
  if frames == 120 then
    local _, y = world:position(ball)
    print(("readme: ball at y = %.3f"):format(y))
    love.event.quit(math.abs(y - 0.3) < 0.02 and 0 or 1)
  end
end
EOF
XDG_DATA_HOME=$tmp LUA_CPATH="$root/$BUILD/luajit/?.so" LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=0 \
    timeout 120 xvfb-run -a love "$tmp/readme" >"$tmp/readme.txt" 2>&1
rc=$?
if [ "$rc" -eq 0 ] && grep -q '^readme: ball at' "$tmp/readme.txt"; then
    pass=$((pass + 1))
    echo "ok README's LÖVE example: $(grep '^readme:' "$tmp/readme.txt")"
else
    fail=$((fail + 1))
    echo "FAIL README's LÖVE example exited $rc:"
    tail -n 15 "$tmp/readme.txt"
    cat "$tmp/readme/main.lua"
fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
