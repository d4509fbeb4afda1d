"""What the solver needs from a Blender mesh object, read on the main thread: the rest mesh,
the handles and fixed regions with their faces, the painted factors and the material, and each
handle's target as a rigid motion in the object's own coordinates."""

import hashlib

import numpy as np

from . import painted_factors


class SetupError(Exception):
    """The object cannot be posed as it is set up; the message says what to change."""


def rest_vertices(mesh):
    """The rest shape: the Basis shape key when there are shape keys (the pose is a shape key
    of its own), else the vertices. Blender keeps float32; the solve works in float64."""
    source = mesh.shape_keys.reference_key.data if mesh.shape_keys else mesh.vertices
    co = np.empty(len(source) * 3, dtype=np.float32)
    source.foreach_get("co", co)
    return co.reshape(-1, 3).astype(np.float64)


def face_corners(mesh):
    """(corner vertex indices of all faces, each face's first corner), as Blender's loops."""
    corners = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", corners)
    starts = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_start", starts)
    return corners, starts


def face_lists(corners, starts):
    ends = np.append(starts[1:], len(corners))
    return [corners[s:e].tolist() for s, e in zip(starts, ends)]


def vertex_group_weights(obj, group_name, default):
    """Per-vertex weights of a group; `default` where a vertex is not in it (or no group)."""
    weights = np.full(len(obj.data.vertices), default, dtype=np.float64)
    group = obj.vertex_groups.get(group_name)
    if group is None:
        return weights
    index = group.index
    for v in obj.data.vertices:
        for g in v.groups:
            if g.group == index:
                weights[v.index] = g.weight
    return weights


def faces_of_group(obj, group_name, corners, starts):
    """The faces all of whose corners are in the vertex group with a weight above 0."""
    if obj.vertex_groups.get(group_name) is None:
        raise SetupError("%s: the vertex group '%s' is gone" % (obj.name, group_name))
    inside = vertex_group_weights(obj, group_name, 0.0) > 0.0
    faces = np.flatnonzero(np.logical_and.reduceat(inside[corners], starts))
    if len(faces) == 0:
        raise SetupError("%s: the vertex group '%s' covers no whole face" % (obj.name, group_name))
    return faces


class PoseSetup:
    """Everything a Deformer is built from. `signature` changes whenever any of it changes, so
    a solver built for one setup is reused only for the same setup."""

    def __init__(self, obj):
        mesh = obj.data
        settings = obj.primo
        if len(mesh.polygons) == 0:
            raise SetupError("%s has no faces" % obj.name)
        self.vertices = rest_vertices(mesh)
        corners, starts = face_corners(mesh)
        self.faces = face_lists(corners, starts)
        self.handles = []  # (name, faces, fix)
        for h in settings.handles:
            faces = faces_of_group(obj, h.vertex_group, corners, starts)
            self.handles.append((h.name, faces, h.fix.lower() if h.kind == 'HANDLE' else "all"))
        self.height_factors = painted_factors.face_factors(
            vertex_group_weights(obj, settings.stiffness_group, 0.5), corners, starts,
            painted_factors.stiffness_factor)
        self.width_factors = painted_factors.face_factors(
            vertex_group_weights(obj, settings.width_group, 0.5), corners, starts,
            painted_factors.width_factor)
        self.half_thickness = settings.thickness_percent / 100.0
        self.normal_blend = settings.normal_blend
        self.width = settings.width
        digest = hashlib.sha1()
        for array in (self.vertices, corners, starts, self.height_factors, self.width_factors):
            digest.update(np.ascontiguousarray(array).tobytes())
        for name, faces, fix in self.handles:
            digest.update(repr((name, fix)).encode())
            digest.update(faces.tobytes())
        digest.update(repr((self.half_thickness, self.normal_blend, self.width)).encode())
        self.signature = digest.hexdigest()


def matrix_array(matrix):
    return np.array([list(row) for row in matrix], dtype=np.float64)


def rigid_part(m):
    """The nearest rotation to m's 3x3 block (its polar factor: an Empty's scale, and float32
    rounding, are left out) and m's translation."""
    u, _, vt = np.linalg.svd(m[:3, :3])
    r = u @ vt
    if np.linalg.det(r) < 0:
        r = u @ np.diag([1.0, 1.0, -1.0]) @ vt
    return r, m[:3, 3]


def handle_matrix(obj, handle):
    """The handle's rigid motion in the object's coordinates: where its Empty went from where it
    stood when the handle was made. An Empty's scale is ignored; under an object scaled unevenly
    the motion is the nearest rigid one."""
    if handle.kind != 'HANDLE':
        return np.eye(4)
    if handle.empty is None:
        raise SetupError("%s: handle '%s' has lost its Empty" % (obj.name, handle.name))
    rest = np.array(handle.rest_matrix, dtype=np.float64).reshape(4, 4)
    now = matrix_array(handle.empty.matrix_world)
    r_rest, t_rest = rigid_part(rest)
    r_now, t_now = rigid_part(now)
    # The Empty's motion in the world, x -> R x + t, taking its rest frame to its frame now.
    motion = np.eye(4)
    motion[:3, :3] = r_now @ r_rest.T
    motion[:3, 3] = t_now - motion[:3, :3] @ t_rest
    world = matrix_array(obj.matrix_world)
    local = np.linalg.solve(world, motion @ world)
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = rigid_part(local)
    return m


def make_handle_empty(handle, name, rest_matrix, size, collection):
    """The handle's Empty, standing at `rest_matrix` (world, 4x4 rows), which is where its
    motion is measured from."""
    import bpy
    import mathutils
    empty = bpy.data.objects.new(name, None)
    empty.empty_display_type = 'ARROWS'
    empty.empty_display_size = size
    empty.matrix_world = mathutils.Matrix(np.asarray(rest_matrix).tolist())
    collection.objects.link(empty)
    handle.empty = empty
    handle.rest_matrix = np.asarray(rest_matrix, dtype=np.float64).ravel().tolist()
    return empty


def handle_matrices(obj):
    return [handle_matrix(obj, h) for h in obj.primo.handles]
