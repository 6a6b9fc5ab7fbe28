#!/usr/bin/env python3
"""Re-solves from Python (issue 31): move the interior samples of one curve, re-solve with the
kept `curvenet.Surfacer`, against a fresh `curvenet.surface` run with `preset="fast"` and in
the default mode, measured in the same process. The Rust twin is
`cargo bench -p curvenet --bench resolve`; both move curve 0 by a bump of 1 % of the diagonal
that vanishes near the other curves (its nodes stay).

Usage: bench/resolve.py [--runs K] [--vertices N] [NETWORK ...]   (default: sphere torus)
Needs numpy and the curvenet package (`pip install ./python`). Prints one line per network
and mode: medians of the fresh run and of update + re-solve, and their ratios.
"""

import argparse
import statistics
import time

import numpy as np

import curvenet


def bumped(curves, c, h):
    """Curve `c`'s samples pushed along their normals by `h` times the diagonal, smoothly to
    zero within 15 % of the diagonal of the other curves."""
    points = np.concatenate([p for p, *_ in curves])
    diag = np.linalg.norm(points.max(0) - points.min(0))
    others = np.concatenate([p for i, (p, *_) in enumerate(curves) if i != c])
    p, n = curves[c][0], curves[c][1]
    d = np.sqrt(((p[:, None, :] - others[None, :, :]) ** 2).sum(-1)).min(1)
    t = np.clip(d / (0.15 * diag), 0.0, 1.0)
    w = t * t * (3.0 - 2.0 * t)
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    return p + n * (h * diag * w)[:, None]


def median_time(f, runs):
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--vertices", type=int, default=20000)
    ap.add_argument("networks", nargs="*", default=["sphere", "torus"])
    a = ap.parse_args()
    print(f"median of {a.runs}, {a.vertices} vertices; re-solve = update_points + solve")
    print(f"{'network':<8} {'mode':<8} {'fresh [s]':>10} {'re-solve [s]':>13} {'÷fresh':>8} {'÷fast':>8}")
    for name in a.networks:
        net = curvenet.example(name)
        curves = net.curves
        fast = median_time(lambda: curvenet.surface(net, vertices=a.vertices, preset="fast"), a.runs)
        for preset in ["fast", "default"]:
            fresh = median_time(lambda: curvenet.surface(net, vertices=a.vertices, preset=preset), a.runs)
            s = curvenet.Surfacer(net, vertices=a.vertices, preset=preset)
            s.solve()
            shapes = [bumped(curves, 0, h) for h in (0.01, -0.01)]
            times = []
            for k in range(a.runs):
                t = time.perf_counter()
                s.update_points(0, shapes[k % 2])
                s.solve()
                times.append(time.perf_counter() - t)
            again = statistics.median(times)
            print(f"{name:<8} {preset:<8} {fresh:>10.4f} {again:>13.4f} {again / fresh:>8.3f} {again / fast:>8.3f}")


if __name__ == "__main__":
    main()
