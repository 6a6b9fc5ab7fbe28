"""curvenet from Python, notebook style: run it with `python python/examples/quickstart.py`.

Each block is a cell: surface a bundled network, measure it, build a network from NumPy arrays,
re-solve fast after editing normals, and hand the mesh to libigl.
"""

import time

import numpy as np

import curvenet

# %% 1. A bundled example: three great circles of the unit sphere with their normals.
net = curvenet.example("sphere")
V, F, info = curvenet.surface(net)  # normal-control, ~20k vertices
print(f"sphere: V {V.shape} {V.dtype}, F {F.shape} {F.dtype}, {info['timings']['total']:.2f} s")

# %% 2. Accuracy against the analytic sphere (curve vertices excluded, as in the paper).
e = curvenet.eval(V, F, "sphere", exclude=info["curve"])
print(f"mean distance {e['distance']['mean']:.2e}, mean normal angle {e['normal_angle']['mean']:.3f}°")

# %% 3. A network from arrays: the saddle z = (x² − y²)/2 bounded by the unit circle, with two
# crossing curves. Normals point to the side the surface faces (+z here).
def sample(x, y):
    p = np.stack([x, y, 0.5 * (x**2 - y**2)], axis=1)
    n = np.stack([-x, y, np.ones_like(x)], axis=1)
    return p, n / np.linalg.norm(n, axis=1, keepdims=True)

t = np.linspace(0, 2 * np.pi, 128, endpoint=False)
s = np.linspace(-1, 1, 64)
rim = sample(np.cos(t), np.sin(t))
xaxis = sample(s, np.zeros_like(s))
yaxis = sample(np.zeros_like(s), s)
saddle = curvenet.Network(curves=[
    curvenet.Curve(*rim, closed=True, boundary=True, name="rim"),
    curvenet.Curve(*xaxis, name="x axis"),
    curvenet.Curve(*yaxis, name="y axis"),
])
V, F, info = curvenet.surface(saddle, vertices=5000)
print(f"saddle: {len(V)} vertices, max |z − (x² − y²)/2| = "
      f"{np.abs(V[:, 2] - 0.5 * (V[:, 0]**2 - V[:, 1]**2)).max():.1e}")

# %% 4. Editing normals: the surfacer keeps the mesh and its factorisations.
surfacer = curvenet.Surfacer(saddle, preset="fast", vertices=20000)
clock = time.perf_counter()
V0, F0, _ = surfacer.solve()
first = time.perf_counter() - clock
p, n = xaxis
for angle in (0.1, 0.2, 0.3):
    tilted = n + angle * np.array([1.0, 0.0, 0.0])  # lean the x axis's normals
    surfacer.update_normals(1, tilted)
    clock = time.perf_counter()
    V1, _, _ = surfacer.solve()
    again = time.perf_counter() - clock
    print(f"tilt {angle:.1f}: surface moved by {np.abs(V1 - V0).max():.3f}, "
          f"re-solve {again * 1e3:.0f} ms (first solve {first * 1e3:.0f} ms)")

# %% 5. Interop: libigl's biharmonic interpolation on curvenet's mesh, curves fixed.
try:
    import igl
except ImportError:
    igl = None
if igl is not None:
    V, F, info = curvenet.surface(net, vertices=5000)
    b = np.flatnonzero(info["curve"])
    W_igl = igl.harmonic(V, F, b, V[b], 2)
    W_ours = curvenet.harmonic(V, F, b, V[b], 2)
    print(f"igl.harmonic vs curvenet.harmonic: max difference {np.abs(W_igl - W_ours).max():.1e}")
else:
    print("skipped cell 5 (libigl interop): libigl is not installed (`pip install libigl` to run it)")
