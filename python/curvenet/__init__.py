"""curvenet: surfacing 3D curve networks with normal control (Stanko et al., C&G 2016).

NumPy in, NumPy out, like libigl and gpytoolbox. Shapes: ``V`` (n, 3) float64 vertex
positions, ``F`` (m, 3) int64 triangles (counter-clockwise seen from outside), curves as
``points`` (k, 3) and ``normals`` (k, 3) float64.

Options have one set of names for the library, the command line and Python (``OPTIONS``; the
CLI's ``--inner-steps`` is ``inner_steps``); presets ``"default"``, ``"fast"`` and
``"paper"`` are defined by the library, and every option given overrides the preset.

Errors raise :class:`Error` (a ``ValueError``) or one of its subclasses :class:`InputError`,
:class:`TopologyError`, :class:`NumericalError`, :class:`UsageError`; their attributes
``curve``, ``sample``, ``node``, ``segment``, ``patch``, ``vertex``, ``point`` (and ``path``,
``line``, ``column`` for a malformed file) name the place where known, ``None`` elsewhere.
Arrays of a non-numeric dtype raise ``TypeError``. What a run repaired or left out comes back
as :class:`SurfacingWarning` objects in ``info["warnings"]``, and is issued through Python's
``warnings`` module. The GIL is released during solves.

>>> import curvenet
>>> V, F, info = curvenet.surface(curvenet.example("sphere"), vertices=5000)
"""

import json as _json
import numbers as _numbers
import warnings as _warnings

from . import _curvenet
from ._curvenet import (
    Error,
    InputError,
    Network,
    NumericalError,
    TopologyError,
    UsageError,
    example,
    examples,
    read_mesh,
    read_network,
)

__all__ = [
    "consolidate",
    "Curve",
    "cycles",
    "Error",
    "InputError",
    "Network",
    "NumericalError",
    "OPTIONS",
    "Surfacer",
    "SurfacingWarning",
    "TopologyError",
    "UsageError",
    "eval",
    "example",
    "examples",
    "fill_cycle",
    "harmonic",
    "infer_normals",
    "network_from_edges",
    "open_patch",
    "read_mesh",
    "read_network",
    "surface",
    "surface_curves",
    "surface_files",
]

class Curve(dict):
    """One curve of a :class:`Network`, with the keys of the network JSON: ``points`` (k, 3),
    ``normals`` (k, 3) or ``None`` (unknown: inferred), ``closed``, ``boundary`` (an open
    border of the surface), ``name`` (used in warnings and errors), ``normals_right`` (k, 3)
    for a crease (the surface's normal on the right of the curve). A plain ``dict`` with the
    same keys works as well; an unknown key is an error naming the closest known one.

    >>> import numpy as np, curvenet
    >>> t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    >>> ring = curvenet.Curve(np.c_[np.cos(t), np.sin(t), 0 * t], closed=True, name="rim")
    >>> ring.closed, ring["name"]
    (True, 'rim')
    """

    def __init__(self, points, normals=None, *, closed=False, boundary=False, name=None, normals_right=None):
        super().__init__(points=points, normals=normals, closed=bool(closed), boundary=bool(boundary),
                         name=name, normals_right=normals_right)

    def __getattr__(self, key):
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    def __repr__(self):
        n = len(self["points"]) if hasattr(self["points"], "__len__") else "?"
        what = "closed" if self["closed"] else "open"
        name = f" {self['name']!r}" if self["name"] is not None else ""
        return f"Curve({n} points, {what}{', boundary' if self['boundary'] else ''}{name})"


#: The surfacing options, from the library's table: ``{name: (value_name, choices, help,
#: default)}``. The keyword arguments of :func:`surface` and :class:`Surfacer`.
OPTIONS = {name: (value, tuple(choices), help_, default) for name, value, choices, help_, default in
           _curvenet._option_specs()}


class SurfacingWarning(UserWarning):
    """Something a run repaired, assumed or left out (a merged sample, a snapped crossing, a
    trimmed curve, a patch on a fallback domain). ``curve``, ``sample``, ``node``, ``patch``:
    where, or ``None``."""

    def __init__(self, message, curve=None, sample=None, node=None, patch=None):
        super().__init__(message)
        self.message = message
        self.curve, self.sample, self.node, self.patch = curve, sample, node, patch

    def __str__(self):
        return self.message


def _text(name, value):
    """An option value as the text the library parses (the command line's form)."""
    if name == "infer_normals" and isinstance(value, bool):
        return "all" if value else "missing"
    if isinstance(value, bool):
        raise TypeError(f"option {name} takes a number or a name, not a bool")
    if isinstance(value, str):
        return value
    if isinstance(value, _numbers.Integral):
        return str(int(value))
    if isinstance(value, _numbers.Real):
        return repr(float(value))
    raise TypeError(f"option {name} takes a number or a name, not {type(value).__name__}")


def _options(preset, given):
    unknown = sorted(set(given) - set(OPTIONS))
    if unknown:
        raise TypeError(f"unknown option(s) {', '.join(unknown)}; the options are {', '.join(OPTIONS)}")
    named = [(k, _text(k, v)) for k, v in given.items() if v is not None]
    return _curvenet._options(preset, named)


def _result(t):
    V, F, raw = t
    info = _json.loads(raw.pop("stats_json"))
    info.update(raw)
    info["warnings"] = [SurfacingWarning(*w) for w in info["warnings"]]
    for w in info["warnings"]:
        _warnings.warn(w, stacklevel=3)
    return V, F, info


def _as_network(network):
    """A :class:`Network` as it is; a list of curves (``(k,3)`` polylines, :class:`Curve`
    dicts or tuples, as :class:`Network` takes them) made into one."""
    if isinstance(network, Network):
        return network
    if isinstance(network, (str, bytes)) or not hasattr(network, "__iter__"):
        raise TypeError(f"expected a curvenet.Network or a list of (k, 3) polylines, got {type(network).__name__}"
                        + (" (read a file with curvenet.read_network)" if isinstance(network, str) else ""))
    return Network(curves=list(network))


def network_from_edges(nodes, edges, normals=None):
    """A :class:`Network` from a graph, as polyscope and meshio hold one: ``nodes`` (N,3)
    float64, ``edges`` (E,2) integer indices into ``nodes`` (from 0), optional ``normals``
    (N,3), one per node (else they are inferred). The edges are chained into curves through
    the nodes they share and split where a node has other than two edges, as the OBJ reader
    does for an edge soup; a chain that comes back to its start is a closed curve."""
    return _curvenet._network_from_edges(nodes, edges, normals)


def surface_curves(nodes, edges, normals=None, **options):
    """Surfaces a curve network given as a graph, as polyscope and meshio hold one: ``nodes``
    (N,3) float64, ``edges`` (E,2) integer indices into ``nodes`` (from 0), optional
    ``normals`` (N,3), one per node (else they are inferred). The edges are chained into
    curves through the nodes they share and split where a node has other than two edges, as
    the OBJ reader does for an edge soup (an OBJ of the same ``v`` and ``l`` lines gives the
    same surface). ``options``: those of :func:`surface`. Returns ``(V, F, info)``.
    """
    return surface(network_from_edges(nodes, edges, normals), **options)


def surface(network, method=None, spacing=None, vertices=None, soft=None, iterations=None,
            *, preset="default", progress=None, **options):
    """Surfaces ``network`` (a :class:`Network`, or a list of ``(k,3)`` polylines):
    ``(V (n,3) float64, F (m,3) int64, info)``.

    ``preset``: ``"default"``, ``"fast"`` (planar patching, no 3D iteration: one
    factorisation) or ``"paper"`` (the paper's method as published); every option given (not
    ``None``) overrides the preset. The options (``OPTIONS`` has each one's help and default):
    ``method`` (normal-control, biharmonic, triharmonic, method4, short-paper, cauchy),
    ``spacing`` (target edge length) or ``vertices`` (approximate count, default 20000),
    ``soft`` (soft curve constraints, in input sample spacings), ``iterations`` (3D-operator
    iterations, default 2), and the keyword-only ``patching``, ``inner_steps``,
    ``tolerance``, ``normal_prior``, ``fine_solve`` (``"auto"``, ``"two-level"`` or ``"direct"``:
    the fine level by conjugate gradients preconditioned by the coarse level, less memory),
    ``energy``, ``guide_area``, ``guide_updates``, ``w1``,
    ``snap``, ``consolidate`` (``"on"``/``"off"``: raw strokes joined, merged and trimmed
    first, :func:`consolidate`), ``gap`` (its tolerance), ``max_memory`` (bytes or ``"4G"``; a run whose estimated peak exceeds it, or the
    memory available, raises ``MemoryError`` before it starts), ``order``, ``ghost_updates``.
    With ``method="cauchy"`` a network read from JSON
    keeps its per-curve ``kind``, ``sharpness`` and ``stretch``.

    ``info``, a dict (every key below is always there; docs/design.md §5 details the statistics):

    - the run's statistics, as ``curvenet surface --stats`` writes them: ``vertices``,
      ``faces``, ``curve_vertices`` (ints); ``cycles`` (patches), ``components``, ``nodes``,
      ``segments`` (ints); ``spacing`` (the edge length used); ``method``; ``iterations``,
      ``iteration_stop`` (``"converged"``, ``"max-iterations"``, ``"degenerate"``,
      ``"diverging"`` or ``None``), ``iteration_updates`` (list); ``coarse_vertices``,
      ``coarse_iteration_updates`` (the default's coarse level); ``fine_cg`` (when the
      fine level was solved two-level: dict of ``iterations`` per solve, ``fallbacks``, ``residual``;
      else ``None``); ``peak_memory_bytes`` (``None``
      in Python); ``consolidation`` (dict: ``gap``, ``joined``, ``crossed``, ``merged``, ``trimmed``, ...,
      or ``None``); ``inferred_normals`` (dict of the inference's counts, or ``None`` when every
      normal was given); ``coverage`` (share of the strokes' length near the surface, or
      ``None``); ``open_borders`` (loops of open border off the boundary curves: holes, or a
      sketch's border; ``None`` where not measured); ``reach``; ``self_intersections``;
      ``timings`` (dict of seconds per stage);
    - ``warnings``: list of :class:`SurfacingWarning`;
    - ``num_curve``: the first ``num_curve`` vertices lie on the curves; ``curve``: (n,) bool,
      the same per vertex;
    - ``normals`` (n,3) unit vertex normals, ``mean_curvature`` (n,) signed (+1 on a unit
      sphere), ``propagated_normals`` (n,3) (normal-control's ``N*``) or ``None``.

    ``progress``: an optional callable ``progress(stage, seconds, detail)``, called after each
    stage (``"nodes"``, ``"cycles"``, the default's coarse level (``"coarse start"``, each
    ``"coarse iteration"``, ``"coarse level"``), ``"resample"``,
    ``"tessellate"``, ``"first solve"`` (without a coarse level),
    each ``"iteration"``, ``"solve"``) with its seconds and a detail line — for a progress bar
    on long runs; ``"warning"`` (seconds 0) carries a warning said before the run, e.g. a
    ``spacing`` far above the default size (it is also in ``info["warnings"]``). An exception it raises is raised after the run.
    """
    given = dict(method=method, spacing=spacing, vertices=vertices, soft=soft, iterations=iterations, **options)
    return _result(_curvenet._surface(_as_network(network), _options(preset, given), progress))


def _surface_file(job):
    """One network file to one mesh file (runs in a worker process): the report dict."""
    input_, output, preset, named = job
    return _json.loads(_curvenet._surface_file(input_, output, preset, named))


def _init_worker(threads):
    import os as _os

    # Before the first solve builds the worker's thread pool.
    _os.environ["RAYON_NUM_THREADS"] = str(threads)


def surface_files(inputs, out_dir, *, client=None, jobs=None, format="ply", preset="default", **options):
    """Surfaces many network files: ``inputs`` (a path, or a list of files, folders and glob
    patterns) into ``out_dir/STEM.FORMAT``; returns a list of dicts, one per input in input
    order, with the fields of a ``curvenet batch`` report line: ``input``, ``output``,
    ``status`` (``"ok"``, ``"error"``, or ``"crashed"`` when the process surfacing it died),
    ``error_kind``, ``error`` and ``exit_code`` of a failure, ``warnings``, ``seconds``,
    ``stats``, and what the mesh was made from (``input_hash``, ``options``, ``output_bytes``,
    ``output_hash``). A bad network, or a worker dying on one, never stops the others: every
    input's report comes back.

    Without ``client`` the files are surfaced by ``jobs`` local processes (default: the number
    of cores; each with cores / jobs solver threads); an input whose process dies is tried
    again alone, then reported as crashed. With a ``dask.distributed.Client`` they are mapped
    over the cluster's workers (every worker needs curvenet installed, and ``out_dir`` must be
    a folder every worker can write: a shared file system); an input whose workers die as often
    as Dask allows (``KilledWorker``) is reported as crashed. The options are those of
    :func:`surface` and are checked here, before any work (``UsageError``), as is every output
    path against the inputs: no output may overwrite an input. One run writes into
    ``out_dir`` at a time (a lock; ``UsageError`` when another holds it); temporary files that
    killed runs left there are removed.
    """
    import os as _os

    if format not in ("ply", "obj", "off", "glb"):
        raise ValueError(f"format {format!r} is not ply, obj, off or glb")
    _options(preset, options)  # raises on a bad option before any work
    named = [(k, _text(k, v)) for k, v in options.items() if v is not None]
    if isinstance(inputs, (str, _os.PathLike)):
        inputs = [inputs]
    out_dir = _os.fspath(out_dir)
    # The library expands and names them, as `curvenet batch` does, and checks them apart.
    plan = _curvenet._plan_files([_os.fspath(i) for i in inputs], out_dir, format)
    _os.makedirs(out_dir, exist_ok=True)
    work = [(i, o, preset, named) for i, o in plan]
    if not work:
        return []
    lock, _removed = _curvenet._lock_folder(out_dir)
    try:
        if client is not None:
            return _on_dask(client, work)
        return _in_processes(work, jobs)
    finally:
        lock.release()


def _crashed(job, why):
    """The report of an input whose worker process died."""
    input_, _output, _preset, _named = job
    return {"input": input_, "output": None, "status": "crashed", "error_kind": "crashed",
            "error": f"{input_}: the process surfacing it died ({why}); the other inputs went on",
            "exit_code": None, "warnings": [], "seconds": 0.0, "stats": None}


def _on_dask(client, work, task=None):
    """``work`` mapped over a Dask cluster: each future's report, or crashed, in input order.
    A worker that dies takes every input it held with it (Dask marks them all suspect), so
    each input whose future failed is tried again alone, one at a time: only an input that
    fails on its own is reported crashed."""
    task = task or _surface_file
    futures = client.map(task, work, pure=False)
    reports = [None] * len(work)
    suspects = []
    for k, future in enumerate(futures):
        try:
            reports[k] = future.result()
        except Exception:  # KilledWorker and other worker faults: tried again alone below
            suspects.append(k)
    for k in suspects:
        try:
            reports[k] = client.submit(task, work[k], pure=False).result()
        except Exception as e:
            reports[k] = _crashed(work[k], f"{type(e).__name__}: {e}")
    return reports


def _in_processes(work, jobs, task=None):
    """``work`` in ``jobs`` local processes, at most ``jobs`` inputs in flight. A child that
    dies breaks the pool: the inputs in flight then are tried again, each in a process of its
    own (crashed if that one dies too), and the rest go on in a new pool."""
    import concurrent.futures as _cf
    import multiprocessing as _mp
    import os as _os
    from concurrent.futures.process import BrokenProcessPool

    task = task or _surface_file
    cores = _os.cpu_count() or 1
    jobs = max(1, min(int(jobs or cores), len(work)))
    if jobs == 1 and task is _surface_file:
        return [_surface_file(w) for w in work]
    ctx = _mp.get_context("spawn")  # no fork of a process that holds solver threads

    def pool(n):
        return _cf.ProcessPoolExecutor(n, mp_context=ctx, initializer=_init_worker,
                                       initargs=(max(1, cores // n),))

    reports = [None] * len(work)
    todo = list(range(len(work)))
    while todo:
        suspects = []
        with pool(jobs) as p:
            flight = {}
            while (todo or flight) and not suspects:
                while todo and len(flight) < jobs:
                    k = todo.pop(0)
                    flight[p.submit(task, work[k])] = k
                done, _ = _cf.wait(flight, return_when=_cf.FIRST_COMPLETED)
                for f in done:
                    k = flight.pop(f)
                    try:
                        reports[k] = f.result()
                    except BrokenProcessPool:
                        suspects.append(k)
            if suspects:  # the pool is broken: everything in flight with it
                for f, k in flight.items():
                    try:
                        reports[k] = f.result()
                    except BrokenProcessPool:
                        suspects.append(k)
        for k in sorted(suspects):
            try:
                with pool(1) as alone:
                    reports[k] = alone.submit(task, work[k]).result()
            except BrokenProcessPool as e:
                reports[k] = _crashed(work[k], f"BrokenProcessPool: {e}")
    return reports


def infer_normals(network, *, all=False, snap=None):
    """The network with the normals of its curves that have none inferred from its shape.

    Returns ``(network, report, warnings)``: a :class:`Network` with a unit normal at every
    sample (``curves`` gives them), the report as ``--stats`` writes it under
    ``inferred_normals`` (a dict), and a list of :class:`SurfacingWarning`. ``all=True``
    re-infers every curve's normals, also where they are given (to compare with them).
    :func:`surface` does this by itself for curves whose normals are ``None``.
    """
    given = {"infer_normals": "all" if all else "missing", "snap": snap}
    net, report, warnings = _curvenet._infer_normals(_as_network(network), _options("default", given))
    warnings = [SurfacingWarning(*w) for w in warnings]
    for w in warnings:
        _warnings.warn(w, stacklevel=2)
    return net, _json.loads(report), warnings


def consolidate(network, *, gap=None, snap=None):
    """The network with its raw strokes consolidated, as :func:`surface` does first.

    Stroke ends that stop short of or overshoot another stroke within ``gap`` become junctions
    on it, strokes drawn along each other (twice, retraced) become one curve with averaged
    positions, hooks and stubs at stroke ends are trimmed; a clean network comes back as
    given. ``gap``: the tolerance (default: from the sketch, 0.5–2 % of its bounding-box
    diagonal). Returns ``(network, report, warnings)``: the report as ``--stats`` writes it
    under ``consolidation`` (``gap``, ``joined``, ``crossed``, ``merged``, ``trimmed``, …) and a list of
    :class:`SurfacingWarning`. ``surface(..., consolidate="off")`` skips the stage.
    """
    given = {"gap": gap, "snap": snap}
    net, report, warnings = _curvenet._consolidate(_as_network(network), _options("default", given))
    warnings = [SurfacingWarning(*w) for w in warnings]
    for w in warnings:
        _warnings.warn(w, stacklevel=2)
    return net, _json.loads(report), warnings


def cycles(network, *, consolidate=None, gap=None, snap=None):
    """The network a :func:`surface` run uses — consolidated, normals inferred — with the
    cycles of its patches in ``network.cycles`` (one list per patch, in patch order, of
    ``(curve, first sample, last sample, forward)`` segments; docs/design.md §15), as
    ``curvenet cycles`` writes it. Surfaced, it gives the run's mesh; remove a cycle
    (``net.cycles = net.cycles[:k] + net.cycles[k + 1:]``) to leave that patch open. Returns
    ``(network, warnings)``.
    """
    given = {"consolidate": consolidate, "gap": gap, "snap": snap}
    net, warnings = _curvenet._cycles(_as_network(network), _options("default", given))
    warnings = [SurfacingWarning(*w) for w in warnings]
    for w in warnings:
        _warnings.warn(w, stacklevel=2)
    return net, warnings


def open_patch(network, patch, **options):
    """The network with patch ``patch`` of its surface left open (numbered as
    ``surface(network, **options)`` numbers them): its cycle removed from ``network.cycles``,
    which :func:`cycles` writes first when the network has none. The viewer's click on a patch."""
    return _curvenet._open_patch(_as_network(network), _options("default", options), patch)


def fill_cycle(network, curve, **options):
    """The network with the open cycle along curve ``curve`` filled (a hole the cycle choice
    left): the loop of curves with a patch on one side only through it, added to
    ``network.cycles``. Raises :class:`UsageError` when the curve borders no open cycle or
    several open borders meet on the loop. The viewer's click on a curve."""
    return _curvenet._fill_cycle(_as_network(network), _options("default", options), curve)


class Surfacer:
    """A network prepared for repeated solves: keeps the mesh and the method's factorisations.

    ``Surfacer(network, **options)`` takes the options of :func:`surface` (every method);
    ``solve()`` returns ``(V, F, info)``; ``update_normals(curve, normals (k,3))`` and
    ``update_points(curve, points (k,3))`` replace the normals or the samples of curve
    ``curve`` (one per sample), after which ``solve()`` reuses the factorisations (with
    ``preset="fast"`` or ``iterations=0`` a re-solve is only right-hand sides and triangular
    solves). The mesh stays the one built with the first curves.
    """

    def __init__(self, network, method=None, spacing=None, vertices=None, soft=None,
                 iterations=None, *, preset="default", **options):
        given = dict(method=method, spacing=spacing, vertices=vertices, soft=soft, iterations=iterations, **options)
        self._inner = _curvenet._Surfacer(_as_network(network), _options(preset, given))

    def solve(self):
        """Surfaces the network with the current curves: ``(V, F, info)`` as :func:`surface`."""
        return _result(self._inner.solve())

    def update_normals(self, curve, normals):
        """Replaces the normals of curve ``curve`` by ``normals`` ((k,3), one per sample)."""
        self._inner.update_normals(curve, normals)

    def update_points(self, curve, points):
        """Moves the samples of curve ``curve`` to ``points`` ((k,3), one per sample); the
        network's nodes and segments must stay the same."""
        self._inner.update_points(curve, points)

    @property
    def network(self):
        """The network with the current curves."""
        return self._inner.network

    @property
    def is_factored(self):
        """Whether factorisations from an earlier solve are kept."""
        return self._inner.is_factored


def harmonic(V, F, b, bc, k):
    """k-harmonic interpolation (k = 1, 2, 3) on the mesh ``(V (n,3), F (m,3))``: ``W`` (n, d)
    with ``W[b] = bc`` ((len(b), d)) and ``Δᵏ W = 0`` elsewhere, with the 3D cotangent
    Laplacian and the mixed Voronoi mass matrix — the system of ``igl.harmonic(V, F, b, bc, k)``.
    """
    import numpy as _np

    bc = _np.asarray(bc)
    one_column = bc.ndim == 1
    W = _curvenet._harmonic(V, F, b, bc[:, None] if one_column else bc, int(k))
    return W[:, 0] if one_column else W


def eval(V, F, truth=None, *, reference=None, exclude=None, normals=None):
    """Measures the mesh ``(V, F)`` as ``curvenet eval``: against ``truth`` (``"sphere"``,
    ``"sphere:r"``, ``"torus:R,r"``, ``"cylinder:r"``, ``"ellipsoid:a,b,c"``, ``"plane"``,
    ``"saddle"``, or a mesh file) or ``reference=(V_ref, F_ref)``. ``exclude``: (n,) bool,
    vertices left out (e.g. ``info["curve"]``); ``normals``: (n,3) vertex normals (computed
    from the faces if omitted). Returns a dict: ``distance``, ``normal_angle`` (degrees),
    each with ``count``, ``min``, ``max``, ``mean``, ``rms``; for a reference mesh also
    ``reverse`` and ``hausdorff``.
    """
    import numpy as _np

    ref_v = ref_f = None
    if reference is not None:
        if truth is not None:
            raise ValueError("give truth or reference, not both")
        ref_v, ref_f = reference
    if exclude is not None:
        exclude = _np.ascontiguousarray(exclude, dtype=bool)
    return _json.loads(_curvenet._eval(V, F, truth, ref_v, ref_f, exclude, normals))
