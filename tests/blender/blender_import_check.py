"""Run inside Blender (`blender -b --factory-startup --python blender_import_check.py -- GLB
FRAMES_DIR REST_OBJ TIMES_JSON`): imports GLB, and at each replayed frame's scene frame (its
time in TIMES_JSON, {"frame_000003": seconds, ...}, times the scene's frame rate) compares the
evaluated mesh with FRAMES_DIR/frame_000003.obj.

Blender's glTF importer turns +Y up into +Z up ((x, y, z) -> (x, -z, y)) and may order the
vertices its own way, so vertices are matched to the OBJ's through the rest positions.
"""

import json
import math
import os
import sys

import bpy
from mathutils import kdtree

sys.path.insert(0, os.path.dirname(__file__))
from gltf_import_support import read_points  # noqa: E402


def main():
    glb, frames_dir, rest_obj, times_json = sys.argv[sys.argv.index("--") + 1:]
    with open(times_json) as f:
        times = json.load(f)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=glb)
    obj = next(o for o in bpy.context.scene.objects if o.type == "MESH")
    keys = obj.data.shape_keys
    assert keys.animation_data and keys.animation_data.action, "the animation was not imported"
    rest = read_points(rest_obj)
    tree = kdtree.KDTree(len(rest))
    for i, p in enumerate(rest):
        tree.insert(p, i)
    tree.balance()
    # Blender vertex -> OBJ vertex, through the rest (basis) positions in glTF axes.
    order = []
    for v in obj.data.vertices:
        x, y, z = v.co
        _, index, distance = tree.find((x, z, -y))
        assert distance < 1e-6, "a Blender vertex is no vertex of the rest mesh"
        order.append(index)
    assert len(set(order)) == len(rest), "not every vertex of the rest mesh was imported"

    fps = bpy.context.scene.render.fps / bpy.context.scene.render.fps_base
    names = [kb.name for kb in keys.key_blocks[1:]]
    assert names == sorted(times), "shape keys %s, frames %s" % (names, sorted(times))
    worst_all = 0.0
    for name in names:
        frame = times[name] * fps
        whole = math.floor(frame)
        bpy.context.scene.frame_set(int(whole), subframe=frame - whole)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        mesh = obj.evaluated_get(depsgraph).to_mesh()
        expected = read_points(os.path.join(frames_dir, name + ".obj"))
        worst = 0.0
        for v, index in zip(mesh.vertices, order):
            x, y, z = v.co
            e = expected[index]
            worst = max(worst, abs(x - e[0]), abs(z - e[1]), abs(-y - e[2]))
        obj.evaluated_get(depsgraph).to_mesh_clear()
        print("frame %s at scene frame %.4f: largest difference %.3g" % (name, frame, worst))
        worst_all = max(worst_all, worst)
        if worst > 1e-6:  # float32 precision of coordinates of the order of 1
            print("FAIL: %s differs from the replay's frame by %.3g" % (name, worst))
            sys.exit(1)
    print("CHECK: %d frames match the replay's within %.3g" % (len(names), worst_all))


main()
