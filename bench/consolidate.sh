#!/usr/bin/env bash
# Raw strokes (issue 28, docs/design.md §14): consolidation's time against the whole run, and
# what the run gives, on
#   1. the raw VR strokes of data/sketches/raw (CASSIE data set), default options, 20k vertices;
#   2. plane sections of the real meshes redrawn as strokes (`sample --as-drawn GAP`: gaps and
#      overshoots up to GAP of the diagonal, overdraw, hooks, uneven spacing; normals given),
#      at growing numbers of stroke samples, measured against the mesh.
# Usage: bench/consolidate.sh [GAP]   (default 0.01). Writes its files to target/consolidate.
set -uo pipefail
cd "$(dirname "$0")/.."
GAP=${1:-0.01}
BIN=target/release/curvenet
OUT=${OUT:-target/consolidate}
mkdir -p "$OUT"
stat() { python3 -c "import json,sys; s=json.load(open('$1')); c=s.get('consolidation') or {}; t=s['timings']
print('%6d %8.4f %8.4f %6.1f%% %5s %5s %5s %6s' % (s['vertices'], t['consolidate'], t['total'], 100*t['consolidate']/t['total'], '%s+%s' % (c.get('joined'), c.get('crossed')), c.get('merged'), c.get('trimmed'), '%.3f' % s['coverage'] if s.get('coverage') is not None else '-'))"; }
echo "## raw VR strokes (data/sketches/raw), --vertices 20000"
printf "%-16s %5s %7s %6s %8s %8s %7s %5s %5s %5s %6s  %s\n" sketch exit samples vert consol total share join+x merge trim cover error
for f in data/sketches/raw/*.obj; do
  name=$(basename "$f" .obj)
  samples=$(grep -c '^v ' "$f")
  rm -f "$OUT/$name.stats.json"
  $BIN surface "$f" -o "$OUT/$name.ply" --vertices 20000 -q --stats "$OUT/$name.stats.json" 2>"$OUT/$name.log"
  code=$?
  if [ $code -eq 0 ]; then
    printf "%-16s %5s %7s %s\n" "$name" 0 "$samples" "$(stat "$OUT/$name.stats.json")"
  else
    printf "%-16s %5s %7s  %s\n" "$name" $code "$samples" "$(grep -v '^warning' "$OUT/$name.log" | head -1 | cut -c1-110)"
  fi
done
echo
echo "## sections redrawn as strokes (sample --as-drawn $GAP), default options"
printf "%-12s %6s %4s %5s %7s %6s %8s %8s %7s %5s %5s %5s %6s %10s\n" mesh spacing seed exit samples vert consol total share join+x merge trim cover rms/diag
for m in bumpy-cube.obj beetle.off fandisk.off; do
  name=${m%.*}
  for spacing in 0.02 0.005 0.001 0.0002; do
    for seed in 1 2 3; do
      net=$OUT/$name-$spacing-$seed.json
      diag=$(python3 -c "
import re
v=[list(map(float,l.split()[1:4])) for l in open('data/meshes/$m') if l.startswith('v ')]
if not v:
    L=open('data/meshes/$m').read().split(); n=int(L[1]); v=[list(map(float,L[4+3*i:7+3*i])) for i in range(n)]
import math; lo=[min(p[k] for p in v) for k in range(3)]; hi=[max(p[k] for p in v) for k in range(3)]
print(math.dist(lo,hi))")
      $BIN sample "data/meshes/$m" -o "$net" --spacing "$(echo "$spacing * $diag" | bc -l)" --as-drawn "$GAP" --seed $seed --no-creases >/dev/null 2>&1 || continue
      samples=$(python3 -c "import json; print(sum(len(c['points']) for c in json.load(open('$net'))['curves']))")
      rm -f "$OUT/s.stats.json"
      $BIN surface "$net" -o "$OUT/s.ply" -q --stats "$OUT/s.stats.json" 2>"$OUT/s.log"
      code=$?
      if [ $code -eq 0 ]; then
        rms=$($BIN eval "$OUT/s.ply" --truth "data/meshes/$m" --json 2>/dev/null | python3 -c "import json,sys; print('%.2e' % (json.load(sys.stdin)['evaluation']['distance']['rms'] / $diag))" 2>/dev/null)
        printf "%-12s %6s %4s %5s %7s %s %10s\n" "$name" "$spacing" $seed 0 "$samples" "$(stat "$OUT/s.stats.json")" "$rms"
      else
        printf "%-12s %6s %4s %5s %7s  %s\n" "$name" "$spacing" $seed $code "$samples" "$(grep -v '^warning' "$OUT/s.log" | head -1 | cut -c1-100)"
      fi
    done
  done
done
