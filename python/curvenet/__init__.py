"""curvenet: surfacing 3D curve networks with normal control (Stanko et al., C&G 2016).

NumPy in, NumPy out, like libigl and gpytoolbox. Shapes: ``V`` (n, 3) float64 vertex
positions, ``F`` (m, 3) int64 triangles (counter-clockwise seen from outside), curves as
``points`` (k, 3) and ``normals`` (k, 3) float64. Options have the names of the library's
``curvenet::Options`` and of the CLI's ``curvenet surface`` flags (``--inner-steps`` is
``inner_steps``). Library errors raise ``ValueError`` with the library's message; arrays of
the wrong shape raise ``ValueError``, of a non-numeric dtype ``TypeError``. The GIL is
released during solves.

>>> import curvenet
>>> V, F, info = curvenet.surface(curvenet.example("sphere"), vertices=5000)
"""

import json as _json

from . import _curvenet
from ._curvenet import Network, example, examples, read_mesh, read_network

__all__ = [
    "Network",
    "Surfacer",
    "eval",
    "example",
    "examples",
    "harmonic",
    "read_mesh",
    "read_network",
    "surface",
]

_OPTION_NAMES = (
    "method",
    "spacing",
    "vertices",
    "soft",
    "w1",
    "patching",
    "iterations",
    "inner_steps",
    "tolerance",
    "normal_prior",
    "energy",
    "guide_area",
    "guide_updates",
    "snap",
)


def _options(preset, given):
    unknown = sorted(set(given) - set(_OPTION_NAMES))
    if unknown:
        raise TypeError(f"unknown option(s) {', '.join(unknown)}; the options are {', '.join(_OPTION_NAMES)}")
    return _curvenet._options(preset, **given)


def _result(t):
    V, F, raw = t
    info = _json.loads(raw.pop("stats_json"))
    info.update(raw)
    return V, F, info


def surface(network, method="normal-control", spacing=None, vertices=None, soft=None, iterations=None,
            *, preset="default", **options):
    """Surfaces ``network`` (a :class:`Network`): ``(V (n,3) float64, F (m,3) int64, info)``.

    ``preset``: ``"default"``, ``"fast"`` (planar patching, no 3D iteration: one
    factorisation) or ``"paper"`` (the paper's method as published); every option given (not
    ``None``) overrides the preset: ``method`` (normal-control, biharmonic, triharmonic,
    method4, short-paper), ``spacing`` (target edge length) or ``vertices`` (approximate
    count, default 20000), ``soft`` (soft curve constraints, in input sample spacings),
    ``iterations`` (3D-operator iterations, default 2), and the keyword-only ``w1``,
    ``patching``, ``inner_steps``, ``tolerance``, ``normal_prior``, ``energy``,
    ``guide_area``, ``guide_updates``, ``snap``.

    ``info``: the run's statistics as ``curvenet surface --stats`` writes them (``vertices``,
    ``faces``, ``spacing``, ``timings``, ...), ``warnings`` (list of str), ``num_curve`` (the
    first ``num_curve`` vertices lie on the curves), ``curve`` (n,) bool, ``normals`` (n,3),
    ``mean_curvature`` (n,), ``propagated_normals`` (n,3) or ``None``.
    """
    given = dict(method=method, spacing=spacing, vertices=vertices, soft=soft, iterations=iterations, **options)
    opts = _options(preset, {k: v for k, v in given.items() if v is not None})
    return _result(_curvenet._surface(network, opts))


class Surfacer:
    """A network prepared for repeated solves: keeps the mesh and the factorisations.

    ``Surfacer(network, **options)`` takes the options of :func:`surface`; ``solve()`` returns
    ``(V, F, info)``; ``update_normals(curve, normals (k,3))`` replaces the normals of curve
    ``curve`` (one per sample), after which ``solve()`` reuses the factorisations (with
    ``preset="fast"`` or ``iterations=0`` a re-solve is only triangular solves). The mesh
    stays the one built with the first normals.
    """

    def __init__(self, network, method="normal-control", spacing=None, vertices=None, soft=None,
                 iterations=None, *, preset="default", **options):
        given = dict(method=method, spacing=spacing, vertices=vertices, soft=soft, iterations=iterations, **options)
        opts = _options(preset, {k: v for k, v in given.items() if v is not None})
        self._inner = _curvenet._Surfacer(network, opts)

    def solve(self):
        """Surfaces the network with the current normals: ``(V, F, info)`` as :func:`surface`."""
        return _result(self._inner.solve())

    def update_normals(self, curve, normals):
        """Replaces the normals of curve ``curve`` by ``normals`` ((k,3), one per sample)."""
        self._inner.update_normals(curve, normals)

    @property
    def network(self):
        """The network with the current normals."""
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
