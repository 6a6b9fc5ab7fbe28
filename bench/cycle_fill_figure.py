#!/usr/bin/env python3
"""docs/figures/cycle-fill.png: the neatened `teapot` sketch with one patch left open
(`curvenet.open_patch`, the viewer's click on a patch: a hole in its side), and after one
`curvenet.fill_cycle` — the viewer's click on a curve along the hole (docs/design.md §15). Needs the Python package, trimesh and Pillow, and the CLI
binary (target/release/curvenet) for the pictures. Usage: bench/cycle_fill_figure.py."""

import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np
import trimesh
from PIL import Image

import curvenet

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "target", "release", "curvenet")


# The side panel of the teapot left open.
PATCH = 20


def border_edges(F):
    e = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return int((counts == 1).sum())


def main():
    warnings.simplefilter("ignore", curvenet.SurfacingWarning)
    chosen, _ = curvenet.cycles(curvenet.read_network(os.path.join(ROOT, "data", "sketches", "teapot.obj")))
    # The cycle choice closes the teapot; a side panel left open makes the hole.
    net = curvenet.open_patch(chosen, PATCH)
    filled, curve = None, None
    for c in range(len(net)):
        try:
            filled, curve = curvenet.fill_cycle(net, c), c
            break
        except curvenet.UsageError:
            continue
    if filled is None:
        sys.exit("no open cycle to fill")
    with tempfile.TemporaryDirectory() as tmp:
        network = os.path.join(tmp, "teapot.json")
        net.write(network)
        panels = []
        for name, n, title in [("before", net, f"patch {PATCH} left open"), ("after", filled, f"after fill_cycle(net, {curve})")]:
            V, F, _ = curvenet.surface(n)[:3]
            print(f"{name}: {len(F)} triangles, {border_edges(F)} border edges")
            ply, png = os.path.join(tmp, name + ".ply"), os.path.join(tmp, name + ".png")
            trimesh.Trimesh(V, F, process=False).export(ply)
            subprocess.run([BIN, "render", ply, "-o", png, "--curves", network, "--view", "30,25",
                            "--title", f"teapot, {title}", "-q"], check=True)
            panels.append(Image.open(png))
        out = Image.new("RGB", (sum(p.width for p in panels), max(p.height for p in panels)), "white")
        x = 0
        for p in panels:
            out.paste(p, (x, 0))
            x += p.width
        path = os.path.join(ROOT, "docs", "figures", "cycle-fill.png")
        out.save(path)
        print(f"{path}: {out.width}x{out.height}")


if __name__ == "__main__":
    main()
