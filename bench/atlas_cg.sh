#!/bin/sh
# tether — the atlas's cost in instructions: runs `tether atlas --instructions`
# under callgrind (each point once; only its w:step calls counted, each point
# dumped apart: src/runner/runner_probe.c), then writes OUT/instructions.csv,
# the atlas's CSV with three more columns (instructions of the point's steps,
# per particle-step, per particle per simulated second), and prints each
# scene's front by instructions. CPU time moves with the machine's load;
# these counts do not.
#   sh bench/atlas_cg.sh [build/tether] [OUT] [atlas options: --quick, --only NAME, SCRIPT]
# Under callgrind a point runs about 50 times slower: the quick sweep takes a
# few minutes, one scene of the full sweep (--only NAME) up to an hour.
RUNNER=${1:-build/tether}
OUT=${2:-build/atlas-cg}
[ $# -ge 2 ] && shift 2 || shift $#
[ $# -eq 0 ] && set -- --quick
if ! command -v valgrind >/dev/null 2>&1; then
  echo "atlas_cg: valgrind is not installed: no instruction counts"; exit 1
fi
mkdir -p "$OUT"
rm -f "$OUT"/atlas.cg*
valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$OUT/atlas.cg" \
  "$RUNNER" atlas --instructions --out "$OUT" "$@" > "$OUT/atlas-cg.txt" 2> "$OUT/atlas-cg.log" || {
  echo "atlas_cg: the atlas under callgrind failed (see $OUT/atlas-cg.log)"; exit 1; }
for f in "$OUT"/atlas.cg.*; do
  label=$(sed -n "s/^desc: Trigger: Client Request: atlas //p" "$f")
  [ -n "$label" ] || continue
  ir=$(sed -n 's/^summary: *//p;s/^totals: *//p' "$f" | head -n 1 | cut -d' ' -f1)
  echo "$label ${ir:-0}"
done > "$OUT/instructions.txt"
awk -F, -v counts="$OUT/instructions.txt" -v out="$OUT/instructions.csv" '
  BEGIN { while ((getline l < counts) > 0) { split(l, f, " "); ir[f[1] " " f[2]] = f[3] } }
  NR == 1 { print $0 ",instructions,instructions_per_particle_step,instructions_per_particle_second" > out; next }
  {
    k[$1]++; key = $1 " " k[$1]
    if (!(key in ir)) { missing++; next }
    per = ir[key] / ($8 * $9)
    printf "%s,%s,%.1f,%.0f\n", $0, ir[key], per, per / $4 > out
    n++; scene[n] = $1; err[n] = $10; cost[n] = per / $4
    what[n] = sprintf("%s dt 1/%d, %d x %d %s", $3, 1 / $4 + 0.5, $5, $6, $7 == "jacobi" ? "jacobi" : "gs")
  }
  END {
    if (missing) { print "atlas_cg: " missing " points without a count"; exit 1 }
    printf "%s\n", "== The atlas in instructions (callgrind: each point once, its steps alone) =="
    # each scene front: no other point of the scene is at once cheaper and more accurate
    for (i = 1; i <= n; i++) {
      front = 1
      for (j = 1; j <= n && front; j++)
        if (j != i && scene[j] == scene[i] && cost[j] <= cost[i] && err[j] <= err[i] && (cost[j] < cost[i] || err[j] < err[i])) front = 0
      if (front) printf "%-16s %12.0f instructions/particle/s  error %-10.3g %s\n", scene[i], cost[i], err[i], what[i] | "sort -k1,1 -k2,2n"
    }
    close("sort -k1,1 -k2,2n")
    printf "%d points; CSV %s\n", n, out
  }' "$OUT/atlas.csv"
