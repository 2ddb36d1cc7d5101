#!/bin/sh
# tether — the pay-only table in instructions: runs `BENCH DIR payonly-cg`
# under callgrind, which dumps each world's measured steps apart, and prints
# each feature's instructions over the plain world's.
#   sh bench/payonly_cg.sh [build/bench] [out dir]
BENCH=${1:-build/bench}
OUT=${2:-$(mktemp -d)}
if ! command -v valgrind >/dev/null 2>&1; then
  echo "payonly_cg: valgrind is not installed: no instruction ratios"; exit 0
fi
mkdir -p "$OUT"
rm -f "$OUT"/payonly.cg*
valgrind --tool=callgrind --callgrind-out-file="$OUT/payonly.cg" "$BENCH" "$OUT" payonly-cg > "$OUT/payonly-cg.txt" 2>"$OUT/payonly-cg.log" || {
  echo "payonly_cg: valgrind failed (see $OUT/payonly-cg.log)"; exit 1; }
echo
echo "== Pay only for what is used, in instructions (callgrind; the same worlds, 3 steps each after 2) =="
echo "target: each <= 1.05x the plain world; pairs on, nothing touching <= 1.5x"
for f in "$OUT"/payonly.cg.*; do
  row=$(sed -n "s/^desc: Trigger: Client Request: payonly-//p" "$f")
  [ -n "$row" ] || continue
  ir=$(sed -n 's/^summary: *//p;s/^totals: *//p' "$f" | head -n 1 | cut -d' ' -f1)
  echo "$row $ir"
done | sort -n | awk -v names="$OUT/payonly-cg.txt" '
  BEGIN { while ((getline l < names) > 0) { k = l; sub(/ .*/, "", k); sub(/^[0-9]+ /, "", l); name[k] = l } }
  { ir[$1] = $2; if ($1 == 0) plain = $2 }
  END {
    printf "%-28s %16s %10s\n", "scene", "Ir/step", "ratio"
    for (r = 0; r in ir; r++) printf "%-28s %16.0f %9.3fx\n", name[r], ir[r] / 3, ir[r] / plain
  }'
