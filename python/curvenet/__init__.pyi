"""Type stubs of curvenet (NumPy arrays: shapes in the docstrings)."""

import os
from typing import Any, Callable, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]
ArrayLike = npt.ArrayLike

Method = Literal["normal-control", "biharmonic", "triharmonic", "method4", "short-paper", "cauchy"]
Preset = Literal["default", "fast", "paper"]

#: ``{name: (value_name, choices, help, default)}`` of every surfacing option.
OPTIONS: dict[str, Tuple[str, Tuple[str, ...], str, str]]

class Error(ValueError):
    """Every curvenet error; the place where known, else ``None``."""

    kind: str
    curve: Optional[int]
    sample: Optional[int]
    node: Optional[int]
    segment: Optional[int]
    patch: Optional[int]
    vertex: Optional[int]
    point: Optional[Tuple[float, float, float]]
    path: Optional[str]
    line: Optional[int]
    column: Optional[int]

class InputError(Error): ...
class TopologyError(Error): ...
class NumericalError(Error): ...
class UsageError(Error): ...

class SurfacingWarning(UserWarning):
    message: str
    curve: Optional[int]
    sample: Optional[int]
    node: Optional[int]
    patch: Optional[int]

class Curve(dict[str, Any]):
    """One curve with the network JSON's keys; a ``dict`` with the same keys works too."""

    def __init__(
        self,
        points: ArrayLike,
        normals: Optional[ArrayLike] = None,
        *,
        closed: bool = False,
        boundary: bool = False,
        name: Optional[str] = None,
        normals_right: Optional[ArrayLike] = None,
    ) -> None: ...
    points: ArrayLike
    normals: Optional[ArrayLike]
    closed: bool
    boundary: bool
    name: Optional[str]
    normals_right: Optional[ArrayLike]

class Network:
    """A curve network. ``curves``: :class:`Curve` objects or dicts with the JSON keys,
    ``(points (k,3), normals (k,3) or None, closed, boundary)`` tuples, or bare ``(k,3)``
    polylines (open, normals inferred); ``None`` normals are unknown (inferred)."""

    def __init__(
        self,
        curves: Sequence[Union[Curve, dict[str, Any], Tuple[ArrayLike, Optional[ArrayLike], bool, bool], ArrayLike]],
        snap: Optional[float] = None,
    ) -> None: ...
    @property
    def curves(self) -> list[Tuple[FloatArray, Optional[FloatArray], bool, bool]]: ...
    @property
    def snap(self) -> Optional[float]: ...
    @property
    def cycles(self) -> Optional[list[list[Tuple[int, int, int, bool]]]]: ...
    @cycles.setter
    def cycles(self, cycles: Optional[list[list[Tuple[int, int, int, bool]]]]) -> None: ...
    def write(self, path: str) -> None: ...
    def __len__(self) -> int: ...

def read_network(path: str) -> Network: ...
def read_mesh(path: str) -> Tuple[FloatArray, IntArray]: ...
def example(name: str) -> Network: ...
def examples() -> list[Tuple[str, str]]: ...
#: A network, or what :class:`Network` takes as its curves (e.g. a list of ``(k,3)`` polylines).
NetworkLike = Union[Network, Sequence[Union[Curve, dict[str, Any], Tuple[Any, ...], ArrayLike]]]

def network_from_edges(nodes: ArrayLike, edges: ArrayLike, normals: Optional[ArrayLike] = None) -> Network: ...
def surface_curves(
    nodes: ArrayLike,
    edges: ArrayLike,
    normals: Optional[ArrayLike] = None,
    **options: Any,
) -> Tuple[FloatArray, IntArray, dict[str, Any]]: ...
def infer_normals(
    network: NetworkLike, *, all: bool = False, snap: Optional[float] = None
) -> Tuple[Network, dict[str, Any], list[SurfacingWarning]]: ...
def consolidate(
    network: NetworkLike, *, gap: Optional[float] = None, snap: Optional[float] = None
) -> Tuple[Network, dict[str, Any], list[SurfacingWarning]]: ...
def open_patch(network: NetworkLike, patch: int, **options: Any) -> Network: ...
def fill_cycle(network: NetworkLike, curve: int, **options: Any) -> Network: ...
def cycles(
    network: NetworkLike,
    *,
    consolidate: Optional[str] = None,
    gap: Optional[float] = None,
    snap: Optional[float] = None,
) -> Tuple[Network, list[SurfacingWarning]]: ...
def surface(
    network: NetworkLike,
    method: Optional[Method] = None,
    spacing: Optional[float] = None,
    vertices: Optional[int] = None,
    soft: Optional[float] = None,
    iterations: Optional[int] = None,
    *,
    preset: Preset = "default",
    progress: Optional[Callable[[str, float, str], Any]] = None,
    w1: Optional[float] = None,
    patching: Optional[Literal["planar", "conformal"]] = None,
    inner_steps: Optional[int] = None,
    tolerance: Optional[float] = None,
    normal_prior: Optional[float] = None,
    fine_solve: Optional[Literal["auto", "two-level", "direct"]] = None,
    energy: Optional[Literal["area", "uniform"]] = None,
    guide_area: Optional[Literal["barycentric", "mass", "surface"]] = None,
    guide_updates: Optional[int] = None,
    snap: Optional[float] = None,
    consolidate: Optional[Literal["on", "off"]] = None,
    gap: Optional[float] = None,
    max_memory: Union[float, str, None] = None,
    infer_normals: Optional[Union[bool, Literal["missing", "all"]]] = None,
    order: Optional[int] = None,
    ghost_updates: Optional[int] = None,
) -> Tuple[FloatArray, IntArray, dict[str, Any]]:
    """``(V (n,3) float64, F (m,3) int64, info)``."""

def surface_files(
    inputs: Union[str, "os.PathLike[str]", Sequence[Union[str, "os.PathLike[str]"]]],
    out_dir: Union[str, "os.PathLike[str]"],
    *,
    client: Any = None,
    jobs: Optional[int] = None,
    format: Literal["ply", "obj", "off", "glb"] = "ply",
    preset: Preset = "default",
    **options: Any,
) -> list[dict[str, Any]]:
    """One report dict per input (the fields of a ``curvenet batch`` report line); options as
    :func:`surface`; ``client``: a ``dask.distributed.Client`` to map the files over."""

class Surfacer:
    def __init__(
        self,
        network: NetworkLike,
        method: Optional[Method] = None,
        spacing: Optional[float] = None,
        vertices: Optional[int] = None,
        soft: Optional[float] = None,
        iterations: Optional[int] = None,
        *,
        preset: Preset = "default",
        w1: Optional[float] = None,
        patching: Optional[Literal["planar", "conformal"]] = None,
        inner_steps: Optional[int] = None,
        tolerance: Optional[float] = None,
        normal_prior: Optional[float] = None,
        fine_solve: Optional[Literal["auto", "two-level", "direct"]] = None,
        energy: Optional[Literal["area", "uniform"]] = None,
        guide_area: Optional[Literal["barycentric", "mass", "surface"]] = None,
        guide_updates: Optional[int] = None,
        snap: Optional[float] = None,
        consolidate: Optional[Literal["on", "off"]] = None,
        gap: Optional[float] = None,
        max_memory: Union[float, str, None] = None,
    infer_normals: Optional[Union[bool, Literal["missing", "all"]]] = None,
        order: Optional[int] = None,
        ghost_updates: Optional[int] = None,
    ) -> None: ...
    def solve(self) -> Tuple[FloatArray, IntArray, dict[str, Any]]: ...
    def update_normals(self, curve: int, normals: ArrayLike) -> None:
        """``normals``: (k,3), one per sample of curve ``curve``."""
    def update_points(self, curve: int, points: ArrayLike) -> None:
        """``points``: (k,3), one per sample of curve ``curve``."""
    @property
    def network(self) -> Network: ...
    @property
    def is_factored(self) -> bool: ...

def harmonic(V: ArrayLike, F: ArrayLike, b: ArrayLike, bc: ArrayLike, k: int) -> FloatArray:
    """``W`` (n, d) (or (n,) for a 1-D ``bc``) with ``W[b] = bc`` and ``Δᵏ W = 0`` elsewhere."""

def eval(
    V: ArrayLike,
    F: ArrayLike,
    truth: Optional[str] = None,
    *,
    reference: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    exclude: Optional[ArrayLike] = None,
    normals: Optional[ArrayLike] = None,
) -> dict[str, Any]: ...
