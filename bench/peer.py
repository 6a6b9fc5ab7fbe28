#!/usr/bin/env python3
"""A peer measured side by side with curvenet, in the same run.

Times libigl's `igl.harmonic(V, F, b, bc, 2)` (the biharmonic solve with the curve vertices
fixed, SciPy's sparse solver underneath) on curvenet's own output mesh and constraints, and
curvenet's whole file-to-file run (read the network, surface, write the mesh) on the same
network; prints both and their ratio. Installs libigl, numpy and scipy from PyPI when missing.

    bench/peer.py [--sizes 10000,100000] [--runs 5] [--modes fast,default] [--network sphere]
                  [--curvenet PATH] [--report docs/performance.md]

With --report, the results replace the peer section of that file (after its `<!-- peer -->`
marker).
"""
import argparse
import json
import os
import platform
from importlib import metadata
import statistics
import subprocess
import sys
import tempfile
import time


def ensure(packages):
    missing = []
    for module, package in packages:
        try:
            __import__(module)
        except ImportError:
            missing.append(package)
    if missing:
        print("installing " + " ".join(missing) + " from PyPI", file=sys.stderr)
        subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", *missing])


def _dist_version(name):
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10000,100000")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--modes", default="fast,default", help="comma-separated: fast, default")
    ap.add_argument("--network", default="sphere")
    ap.add_argument("--curvenet", default=os.path.join(root, "target", "release", "curvenet"))
    ap.add_argument("--report")
    args = ap.parse_args()
    ensure([("numpy", "numpy"), ("scipy", "scipy"), ("igl", "libigl")])
    import igl
    import numpy as np

    if not os.path.exists(args.curvenet):
        sys.exit(f"{args.curvenet} not found: build it with `cargo build --release -p curvenet-cli`")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        net = os.path.join(tmp, "net.json")
        subprocess.check_call([args.curvenet, "example", args.network, "-o", net], stdout=subprocess.DEVNULL)
        modes = [m for m in args.modes.split(",") if m]
        if any(m not in ("fast", "default") for m in modes):
            sys.exit(f"--modes: expected fast and/or default, got {args.modes}")
        for size, mode in [(int(s), m) for s in args.sizes.split(",") for m in modes]:
            mesh, stats = os.path.join(tmp, "out.obj"), os.path.join(tmp, "stats.json")
            cmd = [args.curvenet, "surface", net, "-o", mesh, "--vertices", str(size), "--stats", stats, "-q"]
            if mode == "fast":
                cmd.append("--fast")
            ours = []
            for _ in range(args.runs):
                t = time.perf_counter()
                subprocess.check_call(cmd)
                ours.append(time.perf_counter() - t)
            s = json.load(open(stats))
            V, F = igl.read_triangle_mesh(mesh)
            # curvenet numbers the curve vertices first.
            b = np.arange(s["curve_vertices"], dtype=F.dtype)
            bc = V[b]
            theirs = []
            for _ in range(args.runs):
                t = time.perf_counter()
                Z = igl.harmonic(V, F, b, bc, 2)
                theirs.append(time.perf_counter() - t)
            assert Z.shape == V.shape
            row = dict(mode=mode, vertices=V.shape[0], curve=int(s["curve_vertices"]), curvenet=statistics.median(ours),
                       factor=s["timings"]["factor"], igl=statistics.median(theirs))
            row["ratio"] = row["curvenet"] / row["igl"]
            rows.append(row)
            print(f"{row['vertices']:>8} vertices: curvenet {mode} file to file {row['curvenet']:.3f} s; "
                  f"igl.harmonic(k=2) solve alone {row['igl']:.3f} s; ratio {row['ratio']:.2f}")
    if args.report:
        text = [
            "## A peer in the same run: libigl\n",
            f"`bench/peer.py --modes {args.modes}` (Python {platform.python_version()}, libigl "
            f"{_dist_version('libigl')}, numpy {np.__version__}). curvenet's time is its whole "
            "process, file to file (read the network, surface, write OBJ); libigl's is "
            "`igl.harmonic(V, F, b, bc, 2)` alone, on curvenet's output mesh with its curve vertices "
            f"fixed. Medians of {args.runs} runs, {args.network} network.\n",
            "| mode | vertices (curve) | curvenet, whole run [s] | igl.harmonic k=2, solve alone [s] | ratio |",
            "|---|---|---|---|---|",
        ]
        for r in rows:
            text.append(
                f"| {r['mode']} | {r['vertices']} ({r['curve']}) | {r['curvenet']:.3f} | {r['igl']:.3f} | {r['ratio']:.2f} |"
            )
        doc = open(args.report).read() if os.path.exists(args.report) else ""
        marker = "<!-- peer -->"
        head = doc.split(marker)[0] if marker in doc else doc
        open(args.report, "w").write(head + marker + "\n" + "\n".join(text) + "\n")
        print(f"wrote {args.report}")


if __name__ == "__main__":
    main()
