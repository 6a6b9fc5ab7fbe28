#!/usr/bin/env bash
# The global cycle choice (issue 30, docs/design.md §15): its time against the network's size.
# Plane sections of the bumpy cube without normals (`sample --planes P --no-normals`), at
# growing numbers of planes, surfaced with default options; the cycle search's seconds and the
# whole normal inference's from --stats. Usage: bench/cycles.sh. Writes to target/cycles.
set -uo pipefail
cd "$(dirname "$0")/.."
BIN=target/release/curvenet
OUT=target/cycles
mkdir -p "$OUT"
printf "%7s %7s %9s %7s %10s %10s %9s %9s\n" planes curves segments cycles search_s normals_s total_s fallback
for p in 4 8 16 24 32 48 64; do
  net=$OUT/bumpy-$p.json
  $BIN sample data/meshes/bumpy-cube.obj -o "$net" --planes $p --no-normals --no-creases >/dev/null 2>&1 || continue
  best=""
  for run in 1 2 3; do
    $BIN surface "$net" -o "$OUT/s.ply" -q --stats "$OUT/s.$run.json" 2>/dev/null || { echo "planes $p: exit $?"; continue 2; }
  done
  python3 - "$net" "$OUT"/s.1.json "$OUT"/s.2.json "$OUT"/s.3.json <<'PY'
import json, statistics, sys
net = json.load(open(sys.argv[1]))
runs = [json.load(open(f)) for f in sys.argv[2:]]
med = lambda f: statistics.median(f(s) for s in runs)
s, i = runs[0], runs[0]["inferred_normals"]
p = sys.argv[1].rsplit("-", 1)[1].split(".")[0]
print("%7s %7d %9d %7d %10.4f %10.4f %9.3f %9s" % (p, len(net["curves"]), s["segments"], i["chosen_cycles"],
      med(lambda r: r["inferred_normals"]["cycles_seconds"]), med(lambda r: r["timings"]["normals"]),
      med(lambda r: r["timings"]["total"]), i["walk_fallback"]))
PY
done
