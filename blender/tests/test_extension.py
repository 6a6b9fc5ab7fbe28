"""The Blender extension, headless (issue 32): Blender as a Python module (`bpy` from PyPI), the
extension registered from its built zip's contents (CURVENET_BLENDER_EXTENSION: the folder it was
unpacked to, whose wheel is installed in this environment). Run by blender/test.sh."""

import importlib.util
import math
import os
import sys

import bpy
import numpy as np
import pytest

K = 96  # samples per circle


def circle(axis):
    """The unit great circle perpendicular to ``axis`` (0, 1, 2), K points."""
    t = np.linspace(0, 2 * math.pi, K, endpoint=False)
    c, s, z = np.cos(t), np.sin(t), np.zeros_like(t)
    return [np.c_[c, s, z], np.c_[c, z, s], np.c_[z, c, s]][axis]


@pytest.fixture(scope="module")
def extension():
    folder = os.environ["CURVENET_BLENDER_EXTENSION"]
    spec = importlib.util.spec_from_file_location(
        "curvenet_extension", os.path.join(folder, "__init__.py"), submodule_search_locations=[folder]
    )
    module = importlib.util.module_from_spec(spec)
    sys.modules["curvenet_extension"] = module
    spec.loader.exec_module(module)
    module.register()
    yield module
    module.unregister()


@pytest.fixture()
def scene(extension):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    # read_factory_settings unregisters add-ons that are not enabled in the preferences.
    if not hasattr(bpy.types, "CURVENET_OT_surface"):
        extension.register()
    return bpy.context.scene


def link(obj, select=True):
    bpy.context.collection.objects.link(obj)
    obj.select_set(select)
    return obj


def surface_of_selection(**options):
    before = set(bpy.data.objects)
    assert bpy.ops.curvenet.surface(**options) == {"FINISHED"}
    new = set(bpy.data.objects) - before
    assert len(new) == 1, new
    obj = new.pop()
    assert obj.type == "MESH" and bpy.context.view_layer.objects.active == obj
    return obj


def check_sphere(obj, rms_max, vertices=None):
    mesh = obj.data
    V = np.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", V)
    V = (np.array(obj.matrix_world)[:3, :3] @ V.reshape(-1, 3).T).T
    if vertices is not None:
        assert 0.75 * vertices < len(V) < 1.25 * vertices, len(V)
    # Closed and manifold: every edge in exactly two faces, consistently oriented.
    F = np.array([tuple(p.vertices) for p in mesh.polygons])
    assert F.shape[1] == 3
    directed = np.vstack([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    assert len(np.unique(directed, axis=0)) == len(directed), "an edge used twice the same way"
    undirected = np.sort(directed, axis=1)
    _, counts = np.unique(undirected, axis=0, return_counts=True)
    assert (counts == 2).all(), f"{(counts != 2).sum()} edges not in two faces"
    r = np.linalg.norm(V, axis=1)
    rms = math.sqrt(np.mean((r - 1) ** 2))
    print(f"\n{obj.name}: {len(V)} vertices, RMS distance to the unit sphere {rms:.2e}")
    assert rms <= rms_max, rms
    # The attributes and shading the operator promises; faces wind outward.
    h = np.empty(len(V), dtype=np.float32)
    mesh.attributes["curvature"].data.foreach_get("value", h)
    assert abs(np.median(h) - 1) < 0.05, np.median(h)
    on = np.empty(len(V), dtype=bool)
    mesh.attributes["on_curve"].data.foreach_get("value", on)
    assert 0 < on.sum() < len(V)
    assert all(p.use_smooth for p in mesh.polygons)
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    assert (np.einsum("ij,ij->i", np.cross(b - a, c - a), a + b + c) > 0).mean() > 0.99
    return rms


def test_three_great_circle_curves_give_the_sphere(scene):
    objs = []
    for axis in range(3):
        cu = bpy.data.curves.new(f"circle{axis}", "CURVE")
        cu.dimensions = "3D"
        spline = cu.splines.new("POLY")
        pts = circle(axis)
        if axis == 2:
            # Drawn in its own plane and turned into place by the object's transform.
            pts = pts[:, [1, 2, 0]]
        spline.points.add(len(pts) - 1)
        spline.points.foreach_set("co", np.c_[pts, np.ones(len(pts))].ravel())
        spline.use_cyclic_u = True
        obj = link(bpy.data.objects.new(f"circle{axis}", cu))
        if axis == 2:
            obj.matrix_world = np.eye(4)[[2, 0, 1, 3]].T.tolist()
        objs.append(obj)
    bpy.context.view_layer.update()
    obj = surface_of_selection()
    check_sphere(obj, 1e-3, vertices=20000)
    # The inputs are untouched.
    assert all(o.name in bpy.data.objects and o.type == "CURVE" for o in objs)
    assert len(objs[0].data.splines[0].points) == K


def test_bezier_circles_are_evaluated_as_drawn(scene):
    for rot in [(0, 0, 0), (math.pi / 2, 0, 0), (0, math.pi / 2, 0)]:
        bpy.ops.curve.primitive_bezier_circle_add(radius=1.0, rotation=rot)
        bpy.context.active_object.data.resolution_u = 24
    for o in bpy.data.objects:
        o.select_set(True)
    obj = surface_of_selection(vertices=8000, preset="fast")
    # A four-arc Bézier circle is within 2.7e-4 of the true one.
    check_sphere(obj, 2e-3, vertices=8000)


def test_a_grease_pencil_sketch_and_an_edge_mesh(scene):
    if hasattr(bpy.data, "grease_pencils_v3"):
        gp = bpy.data.grease_pencils_v3.new("sketch")
        layer = gp.layers.new("strokes")
        drawing = layer.frames.new(scene.frame_current).drawing
        drawing.add_strokes([K, K, K])
        for axis, stroke in enumerate(drawing.strokes):
            for p, q in zip(stroke.points, circle(axis)):
                p.position = tuple(q)
            stroke.cyclic = True
    else:
        gp = bpy.data.grease_pencils.new("sketch")
        frame = gp.layers.new("strokes").frames.new(scene.frame_current)
        for axis in range(3):
            stroke = frame.strokes.new()
            stroke.points.add(K)
            for p, q in zip(stroke.points, circle(axis)):
                p.co = tuple(q)
            stroke.use_cyclic = True
    sketch = link(bpy.data.objects.new("sketch", gp))
    check_sphere(surface_of_selection(vertices=5000), 1e-3, vertices=5000)

    # The new surface is the selection now (the sketch was deselected): start again.
    assert not sketch.select_get()
    for o in bpy.context.selected_objects:
        o.select_set(False)
    verts, edges = [], []
    for axis in range(3):
        base = len(verts)
        verts.extend(map(tuple, circle(axis)))
        edges.extend((base + i, base + (i + 1) % K) for i in range(K))
    mesh = bpy.data.meshes.new("edges")
    mesh.from_pydata(verts, edges, [])
    link(bpy.data.objects.new("edges", mesh))
    check_sphere(surface_of_selection(vertices=5000), 1e-3, vertices=5000)


def test_creases_are_marked_sharp(scene):
    """The redo panel's sharp angle reaches the mesh: a cube's twelve edges (an edge-only
    mesh) surface as a rounded box; at 1° its faces' edges are marked sharp, at 180° none."""
    verts = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8) if sum(u != v for u, v in zip(verts[a], verts[b])) == 1]
    mesh = bpy.data.meshes.new("box")
    mesh.from_pydata(verts, edges, [])
    box = link(bpy.data.objects.new("box", mesh))
    sharp = {}
    for angle in (math.radians(1), math.pi):
        for o in bpy.context.selected_objects:
            o.select_set(False)
        box.select_set(True)
        obj = surface_of_selection(vertices=3000, preset="fast", sharp_angle=angle)
        flags = np.zeros(len(obj.data.edges), dtype=bool)
        if "sharp_edge" in obj.data.attributes:
            obj.data.attributes["sharp_edge"].data.foreach_get("value", flags)
        sharp[angle] = int(flags.sum())
    assert sharp[math.pi] == 0 and sharp[math.radians(1)] > 0, sharp


def test_a_bad_selection_is_a_report_not_a_traceback(scene):
    with pytest.raises(RuntimeError, match="nothing selected"):
        bpy.ops.curvenet.surface()
    bpy.ops.mesh.primitive_cube_add()
    with pytest.raises(RuntimeError, match="Cube: has faces"):
        bpy.ops.curvenet.surface()
    bpy.context.active_object.select_set(False)
    # One open stroke bounds nothing: the library's error, named by the object.
    cu = bpy.data.curves.new("line", "CURVE")
    cu.dimensions = "3D"
    spline = cu.splines.new("POLY")
    spline.points.add(2)
    spline.points.foreach_set("co", [0, 0, 0, 1, 1, 0, 0, 1, 2, 1, 0, 1])
    link(bpy.data.objects.new("line", cu))
    with pytest.raises(RuntimeError, match=r"curvenet: .*\"line\""):
        bpy.ops.curvenet.surface()
    assert set(o.name for o in bpy.data.objects) == {"Cube", "line"}


def test_the_operator_is_in_the_object_menus(extension):
    for name in extension.MENUS:
        menu = getattr(bpy.types, name)
        assert extension.menu in menu._dyn_ui_initialize(), name
