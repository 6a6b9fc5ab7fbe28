#!/usr/bin/env bash
# `curvenet batch` against a sequential shell loop of `curvenet surface` over the same folder
# (docs/performance.md, "Batches"): 30 good networks (the 10 bundled examples × 3 noise seeds,
# JSON and .net) and 3 malformed ones. Medians of RUNS runs, both measured in the same run.
# Usage: bench/batch.sh [RUNS] [SURFACE FLAGS...]   (default 3 runs, default options)
# With REPORT=docs/performance.md: also replaces that file's section between <!-- batch -->
# and <!-- /batch --> (appended when missing) by the line measured.
set -uo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-3}
shift || true
BIN=target/release/curvenet
DIR=${OUT:-target/bench-batch}
rm -rf "$DIR"
mkdir -p "$DIR/in"
i=0
for ex in sphere globe cube torus cylinder barrel bottleneck saddle lens can; do
  for seed in 1 2 3; do
    i=$((i + 1))
    ext=json
    # .net holds no crease: lens and can stay JSON.
    if [ $((i % 2)) = 0 ] && [ $ex != lens ] && [ $ex != can ]; then ext=net; fi
    $BIN example $ex --noise 0.05 --seed $seed -o "$DIR/in/$ex-$seed.$ext" >/dev/null
  done
done
head -c 500 "$DIR/in/sphere-1.json" > "$DIR/in/truncated.json"
printf '3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n1\n1\n0 1 7 0\n' > "$DIR/in/badindex.net"
printf 'v 0 0 0\nv 1 0 nan\nv 0 1 0\nl 1 2 3 1\n' > "$DIR/in/nan.obj"
now() { date +%s.%N; }
seq_t=(); batch_t=()
for r in $(seq "$RUNS"); do
  rm -rf "$DIR/seq" "$DIR/out"; mkdir -p "$DIR/seq"
  s=$(now)
  for f in "$DIR"/in/*; do b=$(basename "$f"); $BIN surface "$f" -o "$DIR/seq/${b%.*}.ply" -q "$@" 2>/dev/null; done
  seq_t+=("$(echo "$(now) - $s" | bc)")
  s=$(now)
  $BIN batch "$DIR/in" --out "$DIR/out" -q "$@" 2>/dev/null
  code=$?
  batch_t+=("$(echo "$(now) - $s" | bc)")
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
ms=$(median "${seq_t[@]}"); mb=$(median "${batch_t[@]}")
ok=$(grep -c '"status":"ok"' "$DIR/out/report.jsonl")
lines=$(wc -l < "$DIR/out/report.jsonl")
echo "inputs: $(ls "$DIR/in" | wc -l), report lines: $lines, ok: $ok, batch exit: $code"
speedup=$(echo "scale=2; $ms / $mb" | bc)
echo "sequential loop: $ms s (median of $RUNS), batch: $mb s, speed-up: ${speedup}×"
if [ -n "${REPORT:-}" ]; then
  flags="${*:-(default options)}"
  row=$(printf '| %s | %s | %s/%s ok | %.2f | %.2f | %s× |' "$flags" "$(nproc)" "$ok" "$lines" "$ms" "$mb" "$speedup")
  python3 - "$REPORT" "$row" <<'PY'
import sys
path, row = sys.argv[1], sys.argv[2]
text = open(path).read()
open_tag, close_tag = "<!-- batch -->", "<!-- /batch -->"
head = ("## Batches: `curvenet batch` against a shell loop\n\n"
        "`REPORT=docs/performance.md bench/batch.sh 3 [FLAGS]`: a folder of 33 networks (the 10 bundled "
        "examples × 3 noise seeds, 5 % noise, JSON and `.net`; 3 malformed), surfaced by a sequential "
        "loop of `curvenet surface` and by one `curvenet batch` (jobs = cores, each with cores / jobs "
        "threads), medians of 3 runs of each, measured in the same run.\n\n"
        "| flags | cores | report | loop [s] | batch [s] | speed-up |\n|---|---|---|---|---|---|\n")
if open_tag in text:
    start = text.index(open_tag)
    end = text.index(close_tag) if close_tag in text else len(text)
    rows = [l for l in text[start:end].splitlines() if l.startswith("| ") and not l.startswith("| flags")]
    rows = [r for r in rows if r.split("|")[1] != row.split("|")[1]]
    text = text[:start] + open_tag + "\n" + head + "\n".join(rows + [row]) + "\n" + close_tag + text[end + len(close_tag):]
else:
    text = text.rstrip("\n") + "\n\n" + open_tag + "\n" + head + row + "\n" + close_tag + "\n"
open(path, "w").write(text)
PY
fi
