#!/usr/bin/env python3
"""Peers measured side by side with curvenet, in the same run.

Times, on curvenet's own output mesh with its curve vertices fixed (the biharmonic system
`K = (Ls M⁻¹ Ls)_ff`, Ls the cotangent Laplacian, M the Voronoi mass, f the free vertices,
right-hand side `−(Ls M⁻¹ Ls)_fc X_c`, three columns):
- curvenet's whole file-to-file run (read the network, surface, write the mesh) on the same
  network, against libigl's `igl.harmonic(V, F, b, bc, 2)` (SciPy's sparse solver underneath);
- CHOLMOD (scikit-sparse): `sksparse.cholmod.cholesky(K)` (symbolic and numeric, supernodal,
  METIS ordering when CHOLMOD has it, or --cholmod-ordering) and, separately, its solve;
  assembling K is not timed;
- `curvenet.harmonic(V, F, b, bc, 2)` (the installed Python package), its assembly,
  factorisation and solve included, against CHOLMOD's factor + solve.
CHOLMOD's and curvenet.harmonic's times are medians of --runs runs after a discarded warm-up;
both solutions are checked against libigl's on the free vertices (max difference printed).

Installs libigl, numpy and scipy from PyPI when missing, and for CHOLMOD Debian's
libsuitesparse-dev (SuiteSparse 5.12, OpenBLAS) with apt-get and scikit-sparse 0.4.16 from
PyPI; when CHOLMOD (or the curvenet package) cannot be had, says why and leaves its columns out.

    bench/peer.py [--sizes 10000,100000] [--runs 5] [--modes fast,default] [--network sphere]
                  [--curvenet PATH] [--cholmod-ordering metis] [--report docs/performance.md]

With --report, the results replace the peer section of that file (from its `<!-- peer -->`
marker to its `<!-- /peer -->` marker, or to the next section's `<!-- ... -->` marker when it
has none); what follows is kept.
"""
import argparse
import ctypes
import ctypes.util
import json
import os
import platform
from importlib import metadata
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

# 0.4.16 builds against SuiteSparse 5 (Debian 12's libsuitesparse-dev); 0.5 needs a newer one.
SCIKIT_SPARSE = "scikit-sparse==0.4.16"
DEBIAN_CHOLMOD = ["libsuitesparse-dev", "libopenblas-dev"]
ORDERINGS = {"metis": "METIS", "amd": "AMD", "nesdis": "NESDIS", "default": "CHOLMOD's default",
             "best": "CHOLMOD's best"}


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


def _run(cmd):
    """Runs cmd, its output on stderr; the reason it failed, or None."""
    print("+ " + " ".join(cmd), file=sys.stderr)
    r = subprocess.run(cmd, stdout=sys.stderr, stderr=subprocess.PIPE, text=True)
    if r.returncode == 0:
        return None
    return f"`{' '.join(cmd)}` failed: " + (r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1]


def ensure_cholmod():
    """sksparse.cholmod, installed when missing (Debian's SuiteSparse, then scikit-sparse from
    PyPI), and None; or None and why it cannot be had."""
    try:
        import sksparse.cholmod
        return sksparse.cholmod, None
    except ImportError:
        pass
    if not os.path.exists("/usr/include/suitesparse/cholmod.h"):
        if not shutil.which("apt-get"):
            return None, "no CHOLMOD headers (/usr/include/suitesparse/cholmod.h) and no apt-get to install them"
        if os.geteuid() != 0:
            return None, "no CHOLMOD headers; run `apt-get install -y " + " ".join(DEBIAN_CHOLMOD) + "` as root"
        apt = ["apt-get", "install", "-y", "--no-install-recommends", *DEBIAN_CHOLMOD]
        if _run(apt):  # perhaps a stale package list: update it and try once more
            why = _run(["apt-get", "update"]) or _run(apt)
            if why:
                return None, why
    pip = [sys.executable, "-m", "pip", "install", "--quiet", SCIKIT_SPARSE]
    why = _run(pip)
    if why:
        # Without build isolation, against the numpy and scipy already here.
        why = _run([sys.executable, "-m", "pip", "install", "--quiet", "cython", "setuptools", "wheel"]) or _run(
            [*pip, "--no-build-isolation"]
        )
    if why:
        return None, why
    try:
        import sksparse.cholmod
        return sksparse.cholmod, None
    except ImportError as e:
        return None, f"scikit-sparse installed but `import sksparse.cholmod` fails: {e}"


def _dist_version(name):
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def _loaded(name):
    """The path of the shared library `name` (e.g. libcholmod) loaded in this process, or None."""
    try:
        with open("/proc/self/maps") as f:
            for line in f:
                path = line.split()[-1]
                if os.path.basename(path).startswith(name + ".so"):
                    return path
    except OSError:
        pass
    return None


def _suitesparse_versions():
    """'SuiteSparse 5.12.0, CHOLMOD 3.0.14, OpenBLAS', as much of it as can be read from the
    libraries loaded by sksparse.cholmod (scikit-sparse 0.4 has no version call of its own)."""
    parts = []
    for lib, name, call in [("libsuitesparseconfig", "SuiteSparse", "SuiteSparse_version"),
                            ("libcholmod", "CHOLMOD", "cholmod_version")]:
        try:
            dll = ctypes.CDLL(_loaded(lib) or ctypes.util.find_library(lib[3:]))
            v = (ctypes.c_int * 3)()
            getattr(dll, call)(v)
            parts.append(f"{name} {v[0]}.{v[1]}.{v[2]}")
        except (OSError, AttributeError, TypeError):
            parts.append(f"{name} ?")
    blas = _loaded("libblas")
    if blas:
        blas = os.path.realpath(blas)
        parts.append("OpenBLAS" if "openblas" in blas else "BLAS " + blas)
    return ", ".join(parts)


def biharmonic_system(igl, V, F, b, bc):
    """K = (Ls M⁻¹ Ls)_ff (CSC) and the right-hand side −(Ls M⁻¹ Ls)_fc X_c, f the free vertices."""
    import numpy as np
    import scipy.sparse as sparse

    L = igl.cotmatrix(V, F)
    M = igl.massmatrix(V, F, igl.MASSMATRIX_TYPE_VORONOI)
    Q = (L @ sparse.diags(1.0 / M.diagonal()) @ L).tocsr()
    free = np.setdiff1d(np.arange(V.shape[0]), b)
    Qf = Q[free]
    return Qf[:, free].tocsc(), -(Qf[:, b] @ bc), free


def timed(f, runs):
    """Median seconds of f() over runs calls after a discarded warm-up, and the last result."""
    out = f()
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="10000,100000")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--modes", default="fast,default", help="comma-separated: fast, default")
    ap.add_argument("--network", default="sphere")
    ap.add_argument("--curvenet", default=os.path.join(root, "target", "release", "curvenet"))
    ap.add_argument("--cholmod-ordering", default="metis",
                    help="CHOLMOD's fill-reducing ordering: metis (falls back to default when CHOLMOD has no METIS), "
                         "default (CHOLMOD's own choice: AMD, METIS if AMD fills in much), amd, nesdis, best")
    ap.add_argument("--report")
    args = ap.parse_args()
    ensure([("numpy", "numpy"), ("scipy", "scipy"), ("igl", "libigl")])
    import igl
    import numpy as np

    if not os.path.exists(args.curvenet):
        sys.exit(f"{args.curvenet} not found: build it with `cargo build --release -p curvenet-cli`")
    cholmod, no_cholmod = ensure_cholmod()
    if no_cholmod:
        print(f"CHOLMOD skipped: {no_cholmod}", file=sys.stderr)
    try:
        import curvenet
        no_package = None if hasattr(curvenet, "harmonic") else "the installed curvenet package has no harmonic"
    except ImportError as e:
        no_package = f"`import curvenet` fails ({e}): install the package with `pip install ./python`"
    if no_package:
        print(f"curvenet.harmonic skipped: {no_package}", file=sys.stderr)
    ordering = None
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
            line = (f"{row['vertices']:>8} vertices: curvenet {mode} file to file {row['curvenet']:.3f} s; "
                    f"igl.harmonic(k=2) solve alone {row['igl']:.3f} s; ratio {row['ratio']:.2f}")
            if cholmod or not no_package:
                K, rhs, free = biharmonic_system(igl, V, F, b, bc)
            if cholmod:
                if ordering is None:
                    ordering = args.cholmod_ordering
                    try:
                        cholmod.cholesky(K, mode="supernodal", ordering_method=ordering)
                    except cholmod.CholmodError as e:
                        if ordering != "metis":
                            raise
                        print(f"CHOLMOD without METIS ({e}): its default ordering instead", file=sys.stderr)
                        ordering = "default"
                factors, solves, sums = [], [], []
                for i in range(args.runs + 1):  # the first is the warm-up
                    t = time.perf_counter()
                    fac = cholmod.cholesky(K, mode="supernodal", ordering_method=ordering)
                    t1 = time.perf_counter()
                    X = fac(rhs)
                    t2 = time.perf_counter()
                    if i:
                        factors.append(t1 - t)
                        solves.append(t2 - t1)
                        sums.append(t2 - t)
                row.update(chol_factor=statistics.median(factors), chol_solve=statistics.median(solves),
                           chol=statistics.median(sums), chol_diff=float(np.abs(X - Z[free]).max()))
                line += (f"; CHOLMOD factor {row['chol_factor']:.3f} s + solve {row['chol_solve']:.3f} s "
                         f"= {row['chol']:.3f} s (max |CHOLMOD − igl| {row['chol_diff']:.1e})")
            if not no_package:
                row["harmonic"], W = timed(lambda: curvenet.harmonic(V, F, b, bc, 2), args.runs)
                row["harmonic_diff"] = float(np.abs(W[free] - Z[free]).max())
                line += (f"; curvenet.harmonic(k=2) {row['harmonic']:.3f} s "
                         f"(max |curvenet − igl| {row['harmonic_diff']:.1e})")
                if cholmod:
                    row["harmonic_ratio"] = row["harmonic"] / row["chol"]
                    line += f"; curvenet.harmonic ÷ CHOLMOD {row['harmonic_ratio']:.2f}"
            rows.append(row)
            print(line)
    if args.report:
        peers = "libigl, CHOLMOD" if cholmod else "libigl"
        versions = f"Python {platform.python_version()}, libigl {_dist_version('libigl')}, numpy {np.__version__}"
        versions += f", scipy {_dist_version('scipy')}"
        if cholmod:
            versions += f", scikit-sparse {_dist_version('scikit-sparse')} ({_suitesparse_versions()})"
        if not no_package:
            versions += f", curvenet package {_dist_version('curvenet')}"
        text = [
            f"## Peers in the same run: {peers}\n",
            f"`bench/peer.py --modes {args.modes}` ({versions}). curvenet's time is its whole "
            "process, file to file (read the network, surface, write OBJ); libigl's is "
            "`igl.harmonic(V, F, b, bc, 2)` alone, on curvenet's output mesh with its curve vertices "
            f"fixed. Medians of {args.runs} runs, {args.network} network.",
        ]
        cols = ["mode", "vertices (curve)", "curvenet, whole run [s]", "igl.harmonic k=2, solve alone [s]",
                "ratio (run ÷ igl)"]
        if cholmod:
            text[-1] += (
                " CHOLMOD solves the same system, `K = (Ls M⁻¹ Ls)_ff` (Ls `igl.cotmatrix`, M "
                "`igl.massmatrix` Voronoi, f the free vertices) with right-hand side `−(Ls M⁻¹ Ls)_fc X_c` "
                "(3 columns): factor = `sksparse.cholmod.cholesky(K)` (symbolic and numeric, supernodal, "
                f"{ORDERINGS.get(ordering, ordering)} ordering), solve = the factor applied to the "
                "right-hand side; assembling K is not counted."
            )
            cols += ["CHOLMOD factor [s]", "CHOLMOD solve [s]", "CHOLMOD factor+solve [s]"]
        else:
            text[-1] += f" CHOLMOD left out: {no_cholmod}."
        if not no_package:
            text[-1] += (
                " `curvenet.harmonic(V, F, b, bc, 2)` solves it too, its own assembly (3D cotangent Laplacian, "
                "Voronoi mass), factorisation and solve counted"
                + (", and is divided by CHOLMOD's factor + solve." if cholmod else ".")
            )
            cols.append("curvenet.harmonic k=2 [s]")
            if cholmod:
                cols.append("curvenet.harmonic ÷ CHOLMOD")
        else:
            text[-1] += f" curvenet.harmonic left out: {no_package}."
        if cholmod or not no_package:
            text[-1] += " Those are medians of as many runs after a discarded warm-up."
        text[-1] += "\n"
        text += ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
        for r in rows:
            cells = [r["mode"], f"{r['vertices']} ({r['curve']})", f"{r['curvenet']:.3f}", f"{r['igl']:.3f}",
                     f"{r['ratio']:.2f}"]
            if cholmod:
                cells += [f"{r['chol_factor']:.3f}", f"{r['chol_solve']:.3f}", f"{r['chol']:.3f}"]
            if not no_package:
                cells.append(f"{r['harmonic']:.3f}")
                if cholmod:
                    cells.append(f"{r['harmonic_ratio']:.2f}")
            text.append("| " + " | ".join(cells) + " |")
        doc = open(args.report).read() if os.path.exists(args.report) else ""
        marker, end = "<!-- peer -->", "<!-- /peer -->"
        head, rest = doc.split(marker, 1) if marker in doc else (doc, "")
        if end in rest:
            tail = rest.split(end, 1)[1]
        else:  # no end marker (older reports): the section runs to the next section's marker
            i = rest.find("\n<!-- ")
            tail = rest[i:] if i >= 0 else ""
        tail = tail.lstrip("\n")
        open(args.report, "w").write(head + marker + "\n" + "\n".join(text) + "\n" + end + "\n" + tail)
        print(f"wrote {args.report}")


if __name__ == "__main__":
    main()
