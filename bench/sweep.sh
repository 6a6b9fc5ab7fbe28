#!/usr/bin/env bash
# Sweep of bench/real_meshes.sh over plane counts and noise seeds (docs/robustness.md).
# Usage: bench/sweep.sh ["5 6 7 8 9 10 12 14"] ["1 2 3"]   (plane counts: one number for all
# three axes, or X,Y,Z)
set -uo pipefail
cd "$(dirname "$0")/.."
PLANES=${1:-5 6 7 8 9 10 12 14}
SEEDS=${2:-1 2 3}
for p in $PLANES; do
  case $p in *,*) pp=$p ;; *) pp=$p,$p,$p ;; esac
  for s in $SEEDS; do
    OUT=target/real-meshes/$pp-$s bench/real_meshes.sh "$pp" --seed "$s" | tail -n +2 | sed "s/^/seed $s  /"
  done
done
