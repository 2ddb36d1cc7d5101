#!/bin/sh
# tests/layout.sh BUILD — the layout rules of README "Layout", checked:
#   - no source file under src/ over 600 lines;
#   - no function over 80 lines (from the line after its opening brace at
#     column 0 to its closing brace at column 0);
#   - no circle of dependencies between concept files: file A uses a symbol
#     defined in B and B (through any chain) one defined in A, read from the
#     objects' symbol tables (nm), not from the #include lines.
# Places that broke a rule before the check existed are listed in
# tests/layout.allow with their size then; they may shrink, never grow, and
# nothing new may join them. Prints one line per breach and exits 1 if any.
BUILD=${1:-build}
allow=tests/layout.allow
fail=0

breach() {
    echo "layout: $*"
    fail=1
}

# 1. file sizes
for f in src/*/*.c src/*/*.h src/*/*.cpp; do
    n=$(wc -l <"$f")
    [ "$n" -le 600 ] && continue
    max=$(awk -v f="$f" '$1 == "lines" && $2 == f { print $3 }' "$allow")
    if [ -z "$max" ]; then breach "$f has $n lines (at most 600)"
    elif [ "$n" -gt "$max" ]; then breach "$f grew to $n lines (allowed $max while it is split)"
    fi
done

# 2. function lengths
awk '
    /^[A-Za-z_].*\(/ && !/;[ \t]*$/ { name = $0; sub(/\(.*/, "", name); sub(/.*[ *]/, "", name) }
    /^\{/ { start = FNR; fn = name }
    /^\}/ && start { if (FNR - start - 1 > 80) print FILENAME, fn, FNR - start - 1; start = 0 }
' src/*/*.c src/*/*.cpp | while read -r file fn n; do
    max=$(awk -v f="$file" -v g="$fn" '$1 == "function" && $2 == f && $3 == g { print $4 }' "$allow")
    if [ -z "$max" ]; then echo "layout: $file: $fn() has $n lines (at most 80)"
    elif [ "$n" -gt "$max" ]; then echo "layout: $file: $fn() grew to $n lines (allowed $max while it is split)"
    fi
done >"$BUILD/layout-functions.txt"
if [ -s "$BUILD/layout-functions.txt" ]; then cat "$BUILD/layout-functions.txt"; fail=1; fi

# 3. dependency circles between the object files of each part
objs=$(ls "$BUILD"/obj/core/*.o "$BUILD"/obj/constraints/*.o "$BUILD"/obj/collide/*.o \
          "$BUILD"/obj/mask/*.o "$BUILD"/obj/lua/*.o "$BUILD"/obj/render/*.o "$BUILD"/obj/runner/*.o \
          "$BUILD"/obj/scenes/*.o "$BUILD"/obj/box2d/*.o 2>/dev/null)
if [ -z "$objs" ]; then
    breach "no objects under $BUILD/obj: build first"
else
    for o in $objs; do
        src=${o#"$BUILD"/obj/}
        src=src/${src%.o}.c
        [ -e "$src" ] || src=${src%.c}.cpp
        nm --defined-only "$o" | awk -v s="$src" '$2 ~ /^[TDRBC]$/ { print "def", s, $3 }'
        nm -u "$o" | awk -v s="$src" '{ print "use", s, $NF }'
    done | awk '
        $1 == "def" { owner[$3] = $2; files[$2] = 1; next }
        { uses[++k] = $2 SUBSEP $3 }
        END {
            for (i = 1; i <= k; i++) {
                split(uses[i], u, SUBSEP)
                if ((u[2] in owner) && owner[u[2]] != u[1]) reach[u[1], owner[u[2]]] = 1
            }
            for (m in files) for (a in files) if ((a, m) in reach) for (b in files) if ((m, b) in reach) reach[a, b] = 1
            for (a in files) for (b in files) if (a < b && (a, b) in reach && (b, a) in reach) { cyc[a] = 1; cyc[b] = 1 }
            for (a in cyc) print a
        }' | sort >"$BUILD/layout-cycles.txt"
    while read -r f; do
        grep -q "^cycle $f\$" "$allow" || breach "$f is in a circle of dependencies between files (nm: each uses the other, directly or not)"
    done <"$BUILD/layout-cycles.txt"
fi

if [ "$fail" -eq 0 ]; then
    echo "layout: no new file over 600 lines, function over 80 or dependency circle ($(grep -c '^[lfc]' "$allow") older breaches listed in $allow, none grown)"
fi
exit "$fail"
