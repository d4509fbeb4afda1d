"""What the add-on's tests share: installing the add-on from its zip as a user would, a
tessellated cylinder, selecting faces in Edit Mode, and the checks' tolerances."""

import math
import os
import sys
import tempfile

import bpy
import numpy as np

ZIP, MODULE_DIR = sys.argv[sys.argv.index("--") + 1:][:2]
SCRATCH = os.environ.get("PRIMO_TEST_SCRATCH") or tempfile.mkdtemp(prefix="primo-blender-")


def install_addon(module_dir=MODULE_DIR):
    """Installs and enables the add-on from its zip, its module folder set to `module_dir`."""
    bpy.ops.preferences.addon_install(filepath=ZIP, overwrite=True)
    bpy.ops.preferences.addon_enable(module="primo_pose")
    prefs = bpy.context.preferences.addons["primo_pose"].preferences
    prefs.module_folder = module_dir
    return prefs


def cylinder(name="Cylinder", segments=24, rings=12, radius=0.25, height=2.0):
    """A closed cylinder along z with quads on its side and n-gon caps, at the origin."""
    vertices, faces = [], []
    for r in range(rings + 1):
        z = -height / 2 + height * r / rings
        for s in range(segments):
            a = 2 * math.pi * s / segments
            vertices.append((radius * math.cos(a), radius * math.sin(a), z))
    for r in range(rings):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            faces.append((a, b, b + segments, a + segments))
    faces.append(tuple(reversed(range(segments))))
    faces.append(tuple(rings * segments + s for s in range(segments)))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    mesh.update()
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    return obj


def fresh_cylinder():
    """The add-on installed, an empty scene, a cylinder, and its faces' centroids' heights."""
    install_addon()
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    obj = cylinder()
    return obj, face_centroids(obj)[:, 2]


def face_centroids(obj):
    return np.array([np.mean([obj.data.vertices[v].co for v in p.vertices], axis=0) for p in obj.data.polygons])


def select_faces(obj, mask):
    """Selects exactly the faces of `mask` and enters Edit Mode (face select)."""
    if obj.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    for v in obj.data.vertices:
        v.select = False
    for e in obj.data.edges:
        e.select = False
    for p, selected in zip(obj.data.polygons, mask):
        p.select = bool(selected)
    bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_mode(type='FACE')


def add_handle(obj, mask, kind='HANDLE', fix='ALL'):
    select_faces(obj, mask)
    assert bpy.ops.primo.add_handle(kind=kind, fix=fix) == {'FINISHED'}
    bpy.ops.object.mode_set(mode='OBJECT')
    return obj.primo.handles[-1]


def shape_key(obj, name="PriMo pose"):
    data = obj.data.shape_keys.key_blocks[name].data
    co = np.empty(len(data) * 3, dtype=np.float32)
    data.foreach_get("co", co)
    return co.reshape(-1, 3)


def rest_of(obj):
    source = obj.data.shape_keys.reference_key.data if obj.data.shape_keys else obj.data.vertices
    co = np.empty(len(source) * 3, dtype=np.float32)
    source.foreach_get("co", co)
    return co.reshape(-1, 3).astype(np.float64)


def faces_of(obj):
    return [list(p.vertices) for p in obj.data.polygons]


def diagonal(vertices):
    return float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))


def rigid(m):
    """The rotation nearest to m's 3x3 block (polar factor) with m's translation."""
    u, _, vt = np.linalg.svd(m[:3, :3])
    out = np.eye(4)
    out[:3, :3] = u @ vt
    out[:3, 3] = m[:3, 3]
    return out


def check_close(what, got, want, tolerance):
    error = float(np.abs(np.asarray(got, dtype=np.float64) - np.asarray(want, dtype=np.float64)).max())
    print("%s: max difference %.3g (tolerance %.3g)" % (what, error, tolerance))
    assert error <= tolerance, "%s: %.3g > %.3g" % (what, error, tolerance)
    return error
