"""The module's solver for one Blender object, and the shape key its result goes to.

"Solve now" and live follow share these functions: a Deformer is built from a PoseSetup and
kept while the setup's signature stays the same; each solve sets every handle's motion and
solves; the vertices become the shape key POSE_KEY, so the mesh itself (its Basis) keeps the
rest shape and Blender's undo restores poses as it restores any shape key.
"""

import threading

import numpy as np

POSE_KEY = "PriMo pose"

_solvers = {}  # Object.name_full -> PoseSolver
_solvers_lock = threading.Lock()


class PoseSolver:
    def __init__(self, primo, setup):
        mesh = primo.Mesh(setup.vertices, setup.faces)
        handles = [primo.Handle(faces, fix=fix, name=name) for name, faces, fix in setup.handles]
        self.signature = setup.signature
        self.n_handles = len(handles)
        self.deformer = primo.Deformer(
            mesh, handles, half_thickness=setup.half_thickness, normal_blend=setup.normal_blend,
            width=setup.width, height_factors=setup.height_factors, width_factors=setup.width_factors)

    def solve(self, matrices, from_rest):
        """The posed vertices (float64) and the SolveReport. From rest, the result is what
        `primo deform` gives for the same setup; otherwise the solve starts from the last
        pose, which is what a drag wants."""
        if from_rest:
            self.deformer.reset()
        for i, m in enumerate(matrices):
            self.deformer.set_handle_transform(i, matrix=m)
        report = self.deformer.solve()
        return self.deformer.vertices(), report


def solver_for(primo, object_name, setup):
    """The object's solver for this setup, built anew when the setup changed."""
    with _solvers_lock:
        solver = _solvers.get(object_name)
    if solver is None or solver.signature != setup.signature:
        solver = PoseSolver(primo, setup)
        with _solvers_lock:
            _solvers[object_name] = solver
    return solver


def cached_solver(object_name):
    with _solvers_lock:
        return _solvers.get(object_name)


def forget(object_name=None):
    """Drops the object's solver (all of them without `object_name`): its setup changed."""
    with _solvers_lock:
        if object_name is None:
            _solvers.clear()
        else:
            _solvers.pop(object_name, None)


def write_pose(obj, vertices):
    """Writes the posed vertices to the object's POSE_KEY shape key (made on first use, with
    a Basis holding the rest shape if there was none) and shows it at full strength."""
    mesh = obj.data
    if len(vertices) != len(mesh.vertices):
        raise ValueError("%s: the pose has %d vertices, the mesh %d (the mesh changed while "
                         "it was solved)" % (obj.name, len(vertices), len(mesh.vertices)))
    if mesh.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
    key = mesh.shape_keys.key_blocks.get(POSE_KEY)
    if key is None:
        key = obj.shape_key_add(name=POSE_KEY, from_mix=False)
    key.data.foreach_set("co", np.ascontiguousarray(vertices, dtype=np.float32).ravel())
    key.value = 1.0
    mesh.update()


def report_text(report):
    return "%s after %d iterations, energy %.3g, %.0f ms" % (
        "converged" if report.converged else "stopped (%s)" % report.stop_reason,
        report.iterations, report.energy, report.seconds * 1000.0)
