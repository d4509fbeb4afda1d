"""Run inside Blender (`blender -b --factory-startup --python skinned_glb_check.py -- GLB OBJ
BONES`): imports GLB and checks that it holds an armature of BONES bones, that its mesh is
skinned by that armature (an Armature modifier and a vertex group per bone it weighs), and that
the mesh Blender evaluates at rest is OBJ's (the posed positions are the skin's bind pose).

Blender's glTF importer turns +Y up into +Z up ((x, y, z) -> (x, -z, y)) and may order the
vertices its own way, so every evaluated vertex is matched to its nearest OBJ vertex.
"""

import os
import sys

import bpy
from mathutils import kdtree

sys.path.insert(0, os.path.dirname(__file__))
from gltf_import_support import read_points  # noqa: E402


def main():
    glb, obj_path, bones = sys.argv[sys.argv.index("--") + 1:]
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=glb)
    armatures = [o for o in bpy.context.scene.objects if o.type == "ARMATURE"]
    assert len(armatures) == 1, f"{len(armatures)} armatures imported"
    armature = armatures[0]
    assert len(armature.data.bones) == int(bones), f"{len(armature.data.bones)} bones"
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    assert meshes, "no mesh imported"
    posed = read_points(obj_path)
    tree = kdtree.KDTree(len(posed))
    for i, (x, y, z) in enumerate(posed):
        tree.insert((x, -z, y), i)
    tree.balance()
    size = max(max(abs(c) for c in p) for p in posed)
    worst = 0.0
    depsgraph = bpy.context.evaluated_depsgraph_get()
    for obj in meshes:
        modifiers = [m for m in obj.modifiers if m.type == "ARMATURE"]
        assert modifiers and modifiers[0].object == armature, f"{obj.name} is not skinned"
        groups = {g.name for g in obj.vertex_groups}
        assert groups and groups <= {b.name for b in armature.data.bones}, groups
        evaluated = obj.evaluated_get(depsgraph).to_mesh()
        for v in evaluated.vertices:
            _, _, distance = tree.find(obj.matrix_world @ v.co)
            worst = max(worst, distance)
        obj.evaluated_get(depsgraph).to_mesh_clear()
    print(f"skinned_glb_check: {len(meshes)} meshes, {len(armature.data.bones)} bones, "
          f"largest distance from the posed OBJ {worst:.3g} (size {size:.3g})")
    assert worst < 1e-4 * size, f"the evaluated mesh is {worst} from the posed positions"


main()
