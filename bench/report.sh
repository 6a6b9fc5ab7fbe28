#!/usr/bin/env bash
# Regenerates docs/performance.md: curvenet's own benchmark (per-stage medians, peak memory,
# whole run ÷ factorisation) and the libigl peer measured in the same run.
# Usage: bench/report.sh [--quick]   (--quick: 10k and 100k only, 3 runs)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p curvenet-cli
sizes=10000,100000,1000000
runs=5
if [ "${1:-}" = "--quick" ]; then sizes=10000,100000; runs=3; fi
target/release/curvenet bench --sizes "$sizes" --runs "$runs" --out docs/performance.md
python3 bench/peer.py --sizes 10000,100000 --modes fast,default --runs "$runs" --report docs/performance.md
target/release/curvenet bench --sizes 10000,100000 --modes fast,fast-nn,default,default-nn --runs "$runs" \
  --out docs/performance.md --section no-normals
