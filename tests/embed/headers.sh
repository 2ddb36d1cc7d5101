#!/bin/sh
# tests/embed/headers.sh — every public header compiles on its own, warning
# free with -Wpedantic -Werror, as C99, C11, C++11, C++17 and C++20: a game
# may be written in any of them. Run from the repository root; prints
# "N passed, M failed".
pass=0
fail=0
tmp=$(mktemp -d "${TMPDIR:-/tmp}/tether-headers.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
for h in include/tether.h include/tether/*.h; do
    name=${h#include/}
    printf '#include <%s>\nint tether_header_check;\n' "$name" >"$tmp/t.c"
    cp "$tmp/t.c" "$tmp/t.cpp"
    for std in c99 c11 c++11 c++17 c++20; do
        case $std in
        c++*) compiler=${CXX:-c++} src=$tmp/t.cpp ;;
        *) compiler=${CC:-cc} src=$tmp/t.c ;;
        esac
        if out=$($compiler -std=$std -Wall -Wextra -Wpedantic -Werror -fsyntax-only -Iinclude "$src" 2>&1); then
            pass=$((pass + 1))
        else
            fail=$((fail + 1))
            echo "FAIL $name as $std:"
            printf '%s\n' "$out" | head -n 10 | sed 's/^/    | /'
        fi
    done
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
