"""The README's Blender picture: the neatened teapot sketch (data/sketches/teapot.obj, an edge
soup) as an edge-only mesh, surfaced by the extension's operator, rendered by Cycles on the CPU.

    CURVENET_BLENDER_EXTENSION=FOLDER target/bpy-venv/bin/python blender/figure.py OUT.png

FOLDER: the extension's folder (blender/curvenet_blender, with curvenet installed in that
Python), as blender/test.sh prepares it.
"""

import importlib.util
import math
import os
import sys

import bpy
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
folder = os.environ.get("CURVENET_BLENDER_EXTENSION", os.path.join(ROOT, "blender", "curvenet_blender"))
spec = importlib.util.spec_from_file_location("curvenet_extension", os.path.join(folder, "__init__.py"),
                                              submodule_search_locations=[folder])
ext = importlib.util.module_from_spec(spec)
spec.loader.exec_module(ext)
bpy.ops.wm.read_factory_settings(use_empty=True)
ext.register()

verts, edges = [], []
for line in open(os.path.join(ROOT, "data", "sketches", "teapot.obj")):
    p = line.split()
    if p and p[0] == "v":
        verts.append(tuple(float(x) for x in p[1:4]))
    elif p and p[0] == "l":
        ids = [int(x) - 1 for x in p[1:]]
        edges.extend(zip(ids[:-1], ids[1:]))
mesh = bpy.data.meshes.new("teapot strokes")
mesh.from_pydata(verts, edges, [])
strokes = bpy.data.objects.new("teapot strokes", mesh)
strokes.rotation_euler = (math.pi / 2, 0.0, 0.0)  # the sketch is y-up (VR), Blender z-up
bpy.context.collection.objects.link(strokes)
bpy.context.view_layer.update()
strokes.select_set(True)
assert bpy.ops.curvenet.surface() == {"FINISHED"}
surface = bpy.context.active_object

# The strokes drawn as thin dark tubes over the surface (a copy as a curve with a bevel).
tubes = strokes.copy()
tubes.data = strokes.data.copy()
bpy.context.collection.objects.link(tubes)
bpy.context.view_layer.objects.active = tubes
for o in bpy.context.selected_objects:
    o.select_set(False)
tubes.select_set(True)
bpy.ops.object.convert(target="CURVE")
tubes.data.bevel_depth = 0.0012
dark = bpy.data.materials.new("ink")
dark.diffuse_color = (0.05, 0.05, 0.08, 1)
dark.use_nodes = True
dark.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.02, 0.02, 0.03, 1)
tubes.data.materials.append(dark)
clay = bpy.data.materials.new("clay")
clay.use_nodes = True
clay.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.75, 0.55, 0.35, 1)
clay.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 0.45
surface.data.materials.append(clay)

# Camera framing the bounding box, a sun and a soft world.
V = np.array([v.co for v in surface.data.vertices])
centre, size = (V.min(0) + V.max(0)) / 2, np.linalg.norm(V.max(0) - V.min(0))
cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
bpy.context.collection.objects.link(cam)
direction = np.array([0.35, -1.0, 0.45])
direction /= np.linalg.norm(direction)
cam.location = tuple(centre + direction * size * 1.25)
cam.rotation_euler = (
    math.atan2(math.hypot(direction[0], direction[1]), direction[2]),
    0.0,
    math.atan2(direction[1], direction[0]) + math.pi / 2,
)
cam.data.lens = 50
bpy.context.scene.camera = cam
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 3.5
sun.rotation_euler = (math.radians(40), math.radians(20), math.radians(30))
bpy.context.collection.objects.link(sun)
world = bpy.data.worlds.new("world")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.9, 0.92, 0.95, 1)
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.6
bpy.context.scene.world = world

scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 48
scene.render.resolution_x, scene.render.resolution_y = 720, 540
scene.render.filepath = sys.argv[-1]
bpy.ops.render.render(write_still=True)
print(f"{surface.name}: {len(surface.data.vertices)} vertices -> {sys.argv[-1]}")
