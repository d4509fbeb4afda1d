"""A cylinder with two handles in Blender: the top one's Empty moved and turned. "Solve now"
and the live follow both write a shape key equal to the module's own solve of the same handles
(rounded to float32, as Blender stores shape keys) within 1e-9 of the diagonal, and the mesh
keeps its rest shape."""

import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(__file__))
import blender_test_support as t  # noqa: E402

import bpy  # noqa: E402
import mathutils  # noqa: E402
import numpy as np  # noqa: E402

cyl, z = t.fresh_cylinder()
bottom_mask, top_mask = z < -0.8, z > 0.8
t.add_handle(cyl, bottom_mask)
top = t.add_handle(cyl, top_mask)
rest = t.rest_of(cyl)
D = t.diagonal(rest)

# The top Empty moves and turns by 40 degrees about x, as G and R would.
empty = top.empty
empty.location += mathutils.Vector((0.3, 0.0, -0.2))
empty.rotation_euler = (math.radians(40), 0.0, 0.0)
bpy.context.view_layer.update()

assert bpy.ops.primo.solve_now() == {'FINISHED'}, cyl.primo.status
print("solve now:", cyl.primo.status)
posed = t.shape_key(cyl)
t.check_close("the Basis keeps the rest shape", t.rest_of(cyl), rest, 0.0)

# The module's solve, set up from what Blender holds: the faces all of whose corners are in a
# handle's selection, the Empty's motion since the handle was made.
import primo  # the add-on imported it from MODULE_DIR  # noqa: E402
assert os.path.dirname(primo.__file__) == os.path.abspath(t.MODULE_DIR), primo.__file__
mesh = primo.Mesh(rest, t.faces_of(cyl))
handles = [primo.Handle(np.flatnonzero(bottom_mask)), primo.Handle(np.flatnonzero(top_mask))]
deformer = primo.Deformer(mesh, handles, half_thickness=0.08)
rest_matrix = np.array(top.rest_matrix).reshape(4, 4)
# Each frame's rotation is its polar factor: Blender's float32 matrices are orthonormal only to
# about 1e-7, and the module wants a rotation.
motion = t.rigid(np.array(empty.matrix_world)) @ np.linalg.inv(t.rigid(rest_matrix))
deformer.set_handle_transform(1, matrix=motion)
report = deformer.solve()
assert report.converged, report
want = deformer.vertices()
moved = float(np.abs(want - rest).max())
assert moved > 0.1 * D, "the pose hardly moved (%g): the test would prove nothing" % moved
t.check_close("solve now vs the module (float32)", posed, want.astype(np.float32), 1e-9 * D)
t.check_close("solve now vs the module (float64)", posed, want, 2.0 ** -24 * np.abs(want).max())

# Live follow: the depsgraph handler queues the solve when the Empty moves, a worker thread
# solves, the main thread writes the key. Background Blender runs no timers, so the test calls
# the delivering function itself until the worker is idle.
from primo_pose import live_follow, pose_solver  # noqa: E402
pose_solver.forget()
cyl.data.shape_keys.key_blocks["PriMo pose"].data.foreach_set("co", rest.astype(np.float32).ravel())
empty.location += mathutils.Vector((0.0, 0.0, 0.0))  # a transform update with the same pose
empty.rotation_euler = (math.radians(40), 0.0, 0.0)
bpy.context.view_layer.update()
assert not live_follow.is_idle(), "moving the Empty queued no solve"
deadline = time.time() + 120
while not live_follow.is_idle():
    live_follow._deliver()
    time.sleep(0.01)
    assert time.time() < deadline, "the live solve did not finish in 120 s"
print("live follow:", cyl.primo.status)
t.check_close("live follow vs the module (float32)", t.shape_key(cyl), want.astype(np.float32), 1e-9 * D)

bpy.ops.preferences.addon_disable(module="primo_pose")
print("PASS")
