"""A pose set up in Blender (a fixed region, a handle turned about its orientation only... and
a posed handle, painted stiffness, a thicker plate-like material) exported as a scenario:
`primo deform`'s solve of it (primo.deform_scenario) equals Blender's shape key; imported back,
the object has the same setup, and exporting it again gives the same scenario."""

import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import blender_test_support as t  # noqa: E402

import bpy  # noqa: E402
import mathutils  # noqa: E402
import numpy as np  # noqa: E402

cyl, z = t.fresh_cylinder()
t.add_handle(cyl, z < -0.8, kind='FIXED')
middle = t.add_handle(cyl, (z > -0.1) & (z < 0.1), fix='POSITION')
top = t.add_handle(cyl, z > 0.8)
cyl.primo.thickness_percent = 6.0
cyl.primo.normal_blend = 0.25
assert bpy.ops.primo.add_paint_group(layer='STIFFNESS') == {'FINISHED'}
stiffness = cyl.vertex_groups[cyl.primo.stiffness_group]
upper = [v.index for v in cyl.data.vertices if 0.3 < v.co.z < 0.7]
stiffness.add(upper, 0.8, 'REPLACE')  # x2.30 where painted

top.empty.location += mathutils.Vector((0.4, 0.1, -0.3))
top.empty.rotation_euler = (math.radians(35), math.radians(-10), 0.0)
middle.empty.location += mathutils.Vector((0.15, 0.0, 0.0))
bpy.context.view_layer.update()
assert bpy.ops.primo.solve_now() == {'FINISHED'}, cyl.primo.status
posed = t.shape_key(cyl)
D = t.diagonal(t.rest_of(cyl))

path = os.path.join(t.SCRATCH, "pose.json")
assert bpy.ops.primo.export_scenario(filepath=path) == {'FINISHED'}
with open(path) as f:
    first = json.load(f)
print(json.dumps({k: v for k, v in first.items() if k not in ("handles", "regions")}))
assert first["mesh"] == "pose.obj" and os.path.exists(os.path.join(t.SCRATCH, "pose.obj"))
assert [h["fix"] for h in first["handles"]] == ["all", "position", "all"]
assert first["editor"]["fixed_regions"] == [0]
assert [r["height"] for r in first["regions"]] == [2.3], first["regions"]
assert abs(first["prisms"]["half_thickness"] - 0.06) < 1e-7

import primo  # noqa: E402
X, report = primo.deform_scenario(path)
assert report.converged, report
# The export carries the Empties' motions as axis, angle and translation in decimal, so the two
# solves agree to about 1e-9 of the diagonal, not bit for bit: a coordinate lying that close
# to a float32 rounding boundary rounds the other way in the shape key (one float32 step).
t.check_close("primo deform of the export vs the shape key (float32)", posed, X,
              1e-9 * D + 2.0 ** -23 * np.abs(X).max())

# Back into Blender, and out again.
assert bpy.ops.primo.import_scenario(filepath=path) == {'FINISHED'}
imported = bpy.data.objects["pose"]
assert [(h.kind, h.fix) for h in imported.primo.handles] == [(h.kind, h.fix) for h in cyl.primo.handles]
assert abs(imported.primo.thickness_percent - 6.0) < 1e-5 and abs(imported.primo.normal_blend - 0.25) < 1e-7
bpy.context.view_layer.objects.active = imported
assert bpy.ops.primo.solve_now() == {'FINISHED'}, imported.primo.status
# The Empties' matrices are float32, so the handles' motions come back to about 1e-7.
t.check_close("the imported pose vs the original", t.shape_key(imported), posed, 1e-6 * D)

again = os.path.join(t.SCRATCH, "again.json")
assert bpy.ops.primo.export_scenario(filepath=again) == {'FINISHED'}
with open(again) as f:
    second = json.load(f)
second["mesh"] = first["mesh"]
for a, b in zip(first["handles"], second["handles"]):
    ta, tb = a.pop("transform"), b.pop("transform")
    assert ta.keys() == tb.keys(), (ta, tb)
    for key in ta:
        # The Empties hold float32 matrices: about 1e-7 in a vector, 1e-5 degrees in an angle.
        t.check_close("handle '%s' %s" % (a["name"], key), np.ravel(tb[key]), np.ravel(ta[key]),
                      1e-4 if key == "angle_deg" else 1e-6)
assert first["handles"] == second["handles"]
assert first["regions"] == second["regions"], (first["regions"], second["regions"])
assert first["editor"] == second["editor"]
for key in ("half_thickness", "normal_blend", "width"):
    assert abs(first["prisms"][key] - second["prisms"][key]) < 1e-7, key

# A scenario primo deform refuses is refused here too, naming the file, and nothing is written.
broken = os.path.join(t.SCRATCH, "broken.json")
with open(broken, "w") as f:
    f.write('{"format": "primo-scenario/1", "mesh": "pose.obj", "handels": []}')
try:
    bpy.ops.primo.import_scenario(filepath=broken)
    raise AssertionError("a scenario with an unknown key was imported")
except RuntimeError as e:
    assert "broken.json" in str(e) and "handels" in str(e), str(e)
    print("refused:", str(e).splitlines()[-1])

bpy.ops.preferences.addon_disable(module="primo_pose")
print("PASS")
