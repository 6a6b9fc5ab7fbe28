"""Issue 32: curve networks in the field's Python conventions — polyscope's ``nodes (N,3)`` and
``edges (E,2)``, and plain lists of ``(k,3)`` polylines wherever a network is taken."""

import warnings
from pathlib import Path

import numpy as np
import pytest

import curvenet

ROOT = Path(__file__).resolve().parents[2]
SKETCHES = sorted((ROOT / "data" / "sketches").glob("*.obj")) + sorted((ROOT / "data" / "sketches" / "raw").glob("*.obj"))


def obj_graph(path):
    """An OBJ's ``v`` lines and the edges of its ``l`` lines, 0-based: what polyscope holds."""
    nodes, edges = [], []
    for line in path.read_text().splitlines():
        parts = line.split()
        if parts and parts[0] == "v":
            nodes.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "l":
            ids = [int(p.split("/")[0]) for p in parts[1:]]
            ids = [i - 1 if i > 0 else len(nodes) + i for i in ids]
            edges.extend(zip(ids[:-1], ids[1:]))
    return np.array(nodes, float), np.array(edges, np.int64)


def run(f):
    """``f()``'s result, or the error it raised (its kind and text): a failure must match too."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return f()
        except curvenet.Error as e:
            return (type(e).__name__, str(e))


@pytest.mark.parametrize("path", SKETCHES, ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_surface_curves_on_polyscope_arrays_gives_the_obj_files_mesh(path):
    nodes, edges = obj_graph(path)
    assert len(edges) > 0
    opts = dict(vertices=3000, preset="fast")
    a = run(lambda: curvenet.surface_curves(nodes, edges, **opts))
    b = run(lambda: curvenet.surface(curvenet.read_network(str(path)), **opts))
    if isinstance(b, tuple) and isinstance(b[0], str):
        # The same error, word for word but for the curves' names: the OBJ's are their lines
        # in the file ("curve at line 1234"), the arrays' their numbers.
        import re
        same = lambda e: (e[0], re.sub(r"curve (at line )?\d+", "curve N", e[1]))
        assert isinstance(a, tuple) and same(a) == same(b), (a, b)
        return
    (Va, Fa, ia), (Vb, Fb, ib) = a, b
    assert Va.shape == Vb.shape and Fa.shape == Fb.shape
    assert np.array_equal(Va, Vb) and np.array_equal(Fa, Fb)
    assert ia["num_curve"] == ib["num_curve"]


def test_surface_curves_takes_normals_per_node_and_checks_the_edges():
    net = curvenet.example("sphere")
    nodes, normals, edges = [], [], []
    for points, n, closed, _ in net.curves:
        base = len(nodes)
        nodes.extend(points)
        normals.extend(n)
        k = len(points)
        edges.extend((base + i, base + (i + 1) % k) for i in range(k if closed else k - 1))
    nodes, normals, edges = np.array(nodes), np.array(normals), np.array(edges)
    # Three great circles sampled separately: each its own closed curve (they cross without
    # sharing a node), with the normals given — the example's own surface.
    V, F, info = curvenet.surface_curves(nodes, edges, normals, vertices=3000)
    V0, F0, _ = curvenet.surface(net, vertices=3000)
    assert np.array_equal(V, V0) and np.array_equal(F, F0)
    assert abs(np.linalg.norm(V, axis=1) - 1).max() < 0.01
    with pytest.raises(curvenet.InputError, match=r"edge 2: point index 999999 is out of range"):
        bad = edges.copy()
        bad[2, 1] = 999999
        curvenet.surface_curves(nodes, bad)
    with pytest.raises(curvenet.InputError, match="edge 0: point index -1"):
        curvenet.surface_curves(nodes, np.array([[-1, 0]]))
    with pytest.raises(curvenet.InputError, match="normals for"):
        curvenet.surface_curves(nodes, edges, normals[:-1])
    with pytest.raises(curvenet.UsageError, match=r"edges must have shape \(n, 2\)"):
        curvenet.surface_curves(nodes, edges[:, :1])
    with pytest.raises(TypeError, match="edges must be an integer array"):
        curvenet.surface_curves(nodes, edges.astype(float))


def test_a_list_of_polylines_is_a_network_everywhere():
    t = np.linspace(0, 2 * np.pi, 65)[:-1]
    c, s, z = np.cos(t), np.sin(t), np.zeros_like(t)
    # Three great circles: closed curves (dicts with closed=True) as the reference, and the
    # same circles as bare open polylines whose last point repeats the first.
    circles = [np.c_[c, s, z], np.c_[c, z, s], np.c_[z, c, s]]
    as_dicts = [curvenet.Curve(p, closed=True) for p in circles]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        V0, F0, _ = curvenet.surface(curvenet.Network(curves=as_dicts), vertices=2000, preset="fast")
        # Bare polylines (arrays, and lists of points) through every entry point.
        open_lines = [np.vstack([p, p[:1]]) for p in circles]
        V1, F1, _ = curvenet.surface(open_lines, vertices=2000, preset="fast")
        net, report, _ = curvenet.infer_normals([p.tolist() for p in open_lines])
        cons, _, _ = curvenet.consolidate(open_lines)
        s = curvenet.Surfacer(open_lines, vertices=2000, preset="fast")
        V2, F2, _ = s.solve()
    assert len(net) == 3 and all(n is not None for _, n, _, _ in net.curves)
    assert len(cons) == 3
    # An open polyline whose ends meet is the closed circle after node finding: a surface of
    # the same size and accuracy (its vertices in another order).
    assert V1.shape == V0.shape and F1.shape == F0.shape
    assert abs(np.linalg.norm(V0, axis=1) - 1).max() < 0.02
    assert np.array_equal(V1, V2) and np.array_equal(F1, F2)
    assert abs(np.linalg.norm(V1, axis=1) - 1).max() < 0.02
    with pytest.raises(curvenet.UsageError, match=r"curve 1: points must have shape \(n, 3\)"):
        curvenet.surface([circles[0], np.zeros((4, 2))])
    with pytest.raises(TypeError, match="read a file with curvenet.read_network"):
        curvenet.surface("net.json")


def test_obj_with_shared_normals_is_watertight_in_trimesh(tmp_path):
    """Issue 32: trimesh splits an OBJ's vertices where its corners name different normals (the
    crease rims of the can), so the default OBJ is not watertight there; ``--obj-normals
    shared`` and PLY are."""
    import subprocess
    trimesh = pytest.importorskip("trimesh")
    cli = ROOT / "target" / "release" / "curvenet"
    if not cli.exists():
        pytest.skip(f"{cli} not built")
    net = tmp_path / "can.json"
    subprocess.run([str(cli), "example", "can", "-o", str(net), "-q"], check=True)
    loaded = {}
    for name, extra in [("split.obj", []), ("shared.obj", ["--obj-normals", "shared"]), ("can.ply", [])]:
        out = tmp_path / name
        subprocess.run([str(cli), "surface", str(net), "-o", str(out), "--vertices", "3000", "-q", *extra], check=True)
        loaded[name] = trimesh.load(str(out))
    assert not loaded["split.obj"].is_watertight
    assert loaded["shared.obj"].is_watertight and loaded["can.ply"].is_watertight
    assert len(loaded["shared.obj"].vertices) == len(loaded["can.ply"].vertices) < len(loaded["split.obj"].vertices)


def test_every_info_key_is_documented():
    """Issue 33: ``info`` holds what ``surface``'s docstring lists, every key; the statistics
    are in docs/design.md's table too."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for net in [curvenet.example("sphere"), [c[0] for c in curvenet.example("sphere").curves]]:
            _, _, info = curvenet.surface(net, vertices=2000, preset="fast")
            doc = curvenet.surface.__doc__
            design = (ROOT / "docs" / "design.md").read_text()
            python_only = {"warnings", "num_curve", "curve", "normals", "mean_curvature", "propagated_normals"}
            for key in info:
                assert f"``{key}``" in doc, f"info[{key!r}] is not in surface()'s docstring"
                if key not in python_only:
                    assert f"`{key}`" in design, f"info[{key!r}] is not in docs/design.md"
            for key in info.get("inferred_normals") or {}:
                assert f"`{key}`" in design, f"inferred_normals[{key!r}] is not in docs/design.md"
