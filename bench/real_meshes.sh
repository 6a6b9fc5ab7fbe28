#!/usr/bin/env bash
# Networks sampled from the real meshes of data/meshes (plane sections, crossings between
# samples, 1% noise), surfaced, and measured against the source mesh (docs/robustness.md).
# Usage: bench/real_meshes.sh [PLANES] [EXTRA SAMPLE FLAGS...]   (default 8,8,8)
set -uo pipefail
cd "$(dirname "$0")/.."
DATA=${DATA:-data/meshes}
PLANES=${1:-8,8,8}
shift || true
BIN=target/release/curvenet
OUT=${OUT:-target/real-meshes}
mkdir -p "$OUT"
printf "%-12s %-8s %5s %8s %10s %10s %10s %8s %s %s\n" mesh planes exit diag rms rms/diag hausdorff time warnings components
for m in bumpy-cube.obj beetle.off fandisk.off; do
  name=${m%.*}
  net=$OUT/$name.json
  ply=$OUT/$name.ply
  rm -f "$ply"
  start=$(date +%s.%N)
  if ! $BIN sample "$DATA/$m" -o "$net" --planes "$PLANES" --no-shared-nodes --noise 0.01 "$@" >"$OUT/$name.sample.log" 2>&1; then
    printf "%-12s %-8s %5s  sample failed: %s\n" "$name" "$PLANES" 1 "$(tail -1 "$OUT/$name.sample.log")"
    continue
  fi
  $BIN surface "$net" -o "$ply" -q --stats "$OUT/$name.stats.json" 2>"$OUT/$name.surface.log"
  code=$?
  t=$(echo "$(date +%s.%N) - $start" | bc)
  if [ $code -ne 0 ]; then
    printf "%-12s %-8s %5s  %s\n" "$name" "$PLANES" $code "$(tail -1 "$OUT/$name.surface.log")"
    continue
  fi
  $BIN eval "$ply" --truth "$DATA/$m" --json >"$OUT/$name.eval.json"
  python3 - "$OUT/$name.eval.json" "$DATA/$m" "$name" "$PLANES" "$t" "$(grep -c warning "$OUT/$name.surface.log")" "$OUT/$name.stats.json" <<'PY'
import json, sys
e = json.load(open(sys.argv[1]))["evaluation"]
# bounding-box diagonal of the source mesh
xs = []
with open(sys.argv[2]) as f:
    text = f.read().split()
if sys.argv[2].endswith(".off"):
    nv = int(text[1]); v = [tuple(map(float, text[4 + 3 * i:7 + 3 * i])) for i in range(nv)]
else:
    lines = open(sys.argv[2]).read().splitlines()
    v = [tuple(map(float, l.split()[1:4])) for l in lines if l.startswith("v ")]
lo = [min(p[k] for p in v) for k in range(3)]; hi = [max(p[k] for p in v) for k in range(3)]
diag = sum((hi[k] - lo[k]) ** 2 for k in range(3)) ** 0.5
rms = e["distance"]["rms"]
print(f"{sys.argv[3]:<12} {sys.argv[4]:<8} {0:>5} {diag:>8.4f} {rms:>10.3e} {100*rms/diag:>9.3f}% {e.get('hausdorff') or 0:>10.3e} {float(sys.argv[5]):>7.1f}s {sys.argv[6]} {json.load(open(sys.argv[7]))['components']}")
PY
done
