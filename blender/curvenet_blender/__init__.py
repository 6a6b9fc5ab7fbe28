"""curvenet in Blender: Object › Surface Curves (curvenet) surfaces the selected curve objects,
Grease Pencil strokes and edge-only meshes into a new smooth mesh object.

A thin front end (no numerics here): the selection is read as polylines in world space, each
object's edges chained into curves by the library (``curvenet.network_from_edges``), surfaced by
``curvenet.surface``, and the mesh is added with its attributes. The input objects are left as
they were. Errors and warnings are Blender reports naming the object (the curves are named after
their objects). In the interface, the run goes on in a background thread with Blender's progress
indicator, and Esc cancels it (the run's result is dropped); the redo panel runs it again with
other options.
"""

import math
import threading

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty

import curvenet

#: Faces meeting at more than this angle are marked sharp (the library's shading threshold for
#: split normals, `operators::SHARP_SHADING_DEG`).
SHARP_DEG = 30.0
#: At most this many warnings are reported one by one; the rest as a count.
MAX_WARNINGS = 8


class SelectionError(Exception):
    """A selection that cannot be surfaced: the message names the object."""


def _world(obj, points):
    """``points`` (k,3) in ``obj``'s local space, in world space."""
    m = np.array(obj.matrix_world, dtype=float)
    return points @ m[:3, :3].T + m[:3, 3]


def _mesh_graph(obj, mesh):
    """The vertices and edges of a mesh of edges only (an evaluated curve or a mesh object)."""
    if len(mesh.polygons) > 0:
        raise SelectionError(
            f"{obj.name}: has faces (a curve with bevel, extrusion or fill, or a mesh with faces); "
            "select curves, Grease Pencil strokes or meshes of edges only"
        )
    co = np.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", co)
    ed = np.empty(len(mesh.edges) * 2, dtype=np.int64)
    mesh.edges.foreach_get("vertices", ed)
    return _world(obj, co.reshape(-1, 3)), ed.reshape(-1, 2)


def _stroke_graph(obj, strokes):
    """Nodes and edges of Grease Pencil strokes: ``(points (k,3), cyclic)`` each."""
    nodes, edges = [], []
    base = 0
    for pts, cyclic in strokes:
        k = len(pts)
        if k < 2:
            continue
        nodes.append(pts)
        idx = np.arange(base, base + k)
        edges.append(np.c_[idx[:-1], idx[1:]])
        if cyclic and k > 2:
            edges.append(np.array([[base + k - 1, base]]))
        base += k
    if not nodes:
        raise SelectionError(f"{obj.name}: has no stroke of two points or more on the current frame")
    return _world(obj, np.vstack(nodes)), np.vstack(edges).astype(np.int64)


def _grease_pencil_strokes(obj):
    """The strokes of every visible layer on the current frame: Grease Pencil v3 (Blender 4.3
    and later) or the legacy one (4.2)."""
    out = []
    for layer in obj.data.layers:
        if getattr(layer, "hide", False):
            continue
        if hasattr(layer, "current_frame"):  # v3: drawings of points with `position`
            f = layer.current_frame()
            if f is None or f.drawing is None:
                continue
            for s in f.drawing.strokes:
                pts = np.array([p.position for p in s.points], dtype=float).reshape(-1, 3)
                out.append((pts, bool(s.cyclic)))
        else:  # legacy: frames of strokes of points with `co`
            f = layer.active_frame
            if f is None:
                continue
            for s in f.strokes:
                pts = np.array([p.co for p in s.points], dtype=float).reshape(-1, 3)
                out.append((pts, bool(getattr(s, "use_cyclic", getattr(s, "draw_cyclic", False)))))
    return out


def object_graph(obj, depsgraph):
    """An object's curves as a graph in world space: ``(nodes (N,3), edges (E,2))``. Curves are
    evaluated as Blender draws them (resolution, modifiers); meshes must have no faces."""
    if obj.type in {"CURVE", "MESH"}:
        ev = obj.evaluated_get(depsgraph)
        mesh = ev.to_mesh()
        try:
            return _mesh_graph(obj, mesh)
        finally:
            ev.to_mesh_clear()
    if obj.type in {"GREASEPENCIL", "GPENCIL"}:
        return _stroke_graph(obj, _grease_pencil_strokes(obj))
    raise SelectionError(f"{obj.name}: a {obj.type.lower()} object; select curves, Grease Pencil strokes or meshes of edges")


def selection_network(objects, depsgraph):
    """One curvenet network of every selected object's curves, named after their objects."""
    curves = []
    for obj in sorted(objects, key=lambda o: o.name):
        nodes, edges = object_graph(obj, depsgraph)
        if len(edges) == 0:
            raise SelectionError(f"{obj.name}: has no edges")
        part = curvenet.network_from_edges(nodes, edges)
        many = len(part) > 1
        for k, (points, _, closed, _) in enumerate(part.curves):
            name = f"{obj.name} {k + 1}" if many else obj.name
            curves.append(curvenet.Curve(points, closed=closed, name=name))
    if not curves:
        raise SelectionError("nothing selected: select curve objects, Grease Pencil strokes or meshes of edges")
    return curvenet.Network(curves=curves)


def add_surface(context, V, F, info, sharp_angle=math.radians(SHARP_DEG), name="curvenet surface"):
    """A new mesh object of ``V``, ``F`` with the attributes ``curvature`` (signed mean
    curvature) and ``on_curve``, smooth shading, edges sharp where the faces meet at more than
    ``sharp_angle`` (creases); active and selected."""
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(V))
    mesh.vertices.foreach_set("co", np.ascontiguousarray(V, dtype=np.float32).ravel())
    mesh.loops.add(3 * len(F))
    mesh.loops.foreach_set("vertex_index", np.ascontiguousarray(F, dtype=np.int32).ravel())
    mesh.polygons.add(len(F))
    mesh.polygons.foreach_set("loop_start", np.arange(0, 3 * len(F), 3, dtype=np.int32))
    mesh.update(calc_edges=True)
    curvature = mesh.attributes.new("curvature", "FLOAT", "POINT")
    curvature.data.foreach_set("value", np.asarray(info["mean_curvature"], dtype=np.float32))
    on_curve = mesh.attributes.new("on_curve", "BOOLEAN", "POINT")
    on_curve.data.foreach_set("value", np.asarray(info["curve"], dtype=bool))
    mesh.shade_smooth()
    mesh.set_sharp_from_angle(angle=sharp_angle)
    obj = bpy.data.objects.new(name, mesh)
    context.collection.objects.link(obj)
    for o in context.selected_objects:
        o.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj
    return obj


METHODS = [
    ("normal-control", "Normal control", "Stanko et al. 2016: the surface follows the curves' normals (inferred)"),
    ("biharmonic", "Biharmonic", "Δ²V = 0 through the curves"),
    ("triharmonic", "Triharmonic", "Δ³V = 0 through the curves"),
]
PRESETS = [
    ("default", "Default", "Conformal patching and 3D iterations: the most accurate"),
    ("fast", "Fast", "One planar pass: about half the time"),
    ("paper", "Paper", "The published method as written"),
]


class CURVENET_OT_surface(bpy.types.Operator):
    """Surface the selected curves, Grease Pencil strokes and edge-only meshes into a new mesh"""

    bl_idname = "curvenet.surface"
    bl_label = "Surface Curves (curvenet)"
    bl_options = {"REGISTER", "UNDO"}

    preset: EnumProperty(name="Preset", items=PRESETS, default="default")
    method: EnumProperty(name="Method", items=METHODS, default="normal-control")
    vertices: IntProperty(name="Vertices", description="Approximate vertex count of the mesh",
                          default=20000, min=500, soft_max=500000)
    snap: FloatProperty(name="Snap", description="Curves closer than this meet (0: from the curves' sampling)",
                        default=0.0, min=0.0, subtype="DISTANCE")
    gap: FloatProperty(name="Gap", description="Stroke ends this close to another stroke are joined to it "
                       "(0: from the sketch)", default=0.0, min=0.0, subtype="DISTANCE")
    consolidate: BoolProperty(name="Consolidate strokes", default=True,
                              description="Join strokes that nearly meet, merge overdrawn ones, trim hooks")
    sharp_angle: FloatProperty(name="Sharp angle", subtype="ANGLE", default=math.radians(SHARP_DEG), min=0.0,
                               max=math.pi, description="Edges where the faces meet at more than this are marked "
                               "sharp (creases shade sharp; the surface is the same)")

    @classmethod
    def poll(cls, context):
        return context.mode == "OBJECT"

    def surfacing_options(self):
        opts = dict(preset=self.preset, method=self.method, vertices=self.vertices,
                    consolidate="on" if self.consolidate else "off")
        if self.snap > 0:
            opts["snap"] = self.snap
        if self.gap > 0:
            opts["gap"] = self.gap
        return opts

    def selection(self, context):
        try:
            return selection_network(context.selected_objects, context.evaluated_depsgraph_get())
        except SelectionError as e:
            self.report({"ERROR"}, str(e))
        except curvenet.Error as e:
            self.report({"ERROR"}, f"curvenet: {e}")
        return None

    def conclude(self, context, result):
        """Reports the run's outcome; adds the mesh when it succeeded."""
        if isinstance(result, BaseException):
            self.report({"ERROR"}, f"curvenet: {result}")
            return {"CANCELLED"}
        V, F, info = result
        warnings = info["warnings"]
        for w in warnings[:MAX_WARNINGS]:
            self.report({"WARNING"}, f"curvenet: {w}")
        if len(warnings) > MAX_WARNINGS:
            self.report({"WARNING"}, f"curvenet: {len(warnings) - MAX_WARNINGS} more warnings (see the console)")
            for w in warnings[MAX_WARNINGS:]:
                print(f"curvenet warning: {w}")
        obj = add_surface(context, V, F, info, self.sharp_angle)
        self.report({"INFO"}, f"{obj.name}: {len(V)} vertices, {len(F)} faces")
        return {"FINISHED"}

    @staticmethod
    def solve(net, opts, progress=None):
        import warnings
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # reported as Blender reports instead
                return curvenet.surface(net, progress=progress, **opts)
        except curvenet.Error as e:
            return e

    def execute(self, context):
        net = self.selection(context)
        if net is None:
            return {"CANCELLED"}
        return self.conclude(context, self.solve(net, self.surfacing_options()))

    def invoke(self, context, event):
        if bpy.app.background or context.window is None:
            return self.execute(context)
        net = self.selection(context)
        if net is None:
            return {"CANCELLED"}
        # What the worker thread writes: a plain dict, not the operator (a Blender struct).
        state = {"result": None, "stages": 0}
        self._state = state
        opts = self.surfacing_options()

        def progress(stage, seconds, detail):
            state["stages"] += 1

        solve = CURVENET_OT_surface.solve  # the thread touches no Blender data

        def work():
            state["result"] = solve(net, opts, progress)

        self._thread = threading.Thread(target=work, daemon=True)
        self._thread.start()
        wm = context.window_manager
        wm.progress_begin(0, 12)
        self._timer = wm.event_timer_add(0.1, window=context.window)
        wm.modal_handler_add(self)
        context.workspace.status_text_set("curvenet: surfacing… (Esc cancels)")
        return {"RUNNING_MODAL"}

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)

    def modal(self, context, event):
        if event.type == "ESC":
            self._end(context)
            self.report({"INFO"}, "curvenet: cancelled (the run ends in the background; its result is dropped)")
            return {"CANCELLED"}
        if event.type == "TIMER":
            context.window_manager.progress_update(min(self._state["stages"], 12))
            if not self._thread.is_alive():
                self._end(context)
                return self.conclude(context, self._state["result"])
        return {"PASS_THROUGH"}


def menu(self, context):
    self.layout.operator(CURVENET_OT_surface.bl_idname, icon="SURFACE_DATA")


MENUS = ["VIEW3D_MT_object", "VIEW3D_MT_object_context_menu"]


def register():
    bpy.utils.register_class(CURVENET_OT_surface)
    for m in MENUS:
        getattr(bpy.types, m).append(menu)


def unregister():
    for m in MENUS:
        getattr(bpy.types, m).remove(menu)
    bpy.utils.unregister_class(CURVENET_OT_surface)
