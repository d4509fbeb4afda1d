"""Debian 12's Blender 3.4 imports glTF meshes with `numpy.bool`, an alias of the builtin `bool`
that NumPy 1.24 (Debian 12's) removed: every glTF import of a mesh with normals fails there,
PriMo's animated sessions (`primo replay --animation`) included. While the add-on is enabled
the alias exists again; disabling the add-on removes it only if the add-on put it there."""

import numpy

_added = False


def register():
    global _added
    if "bool" not in numpy.__dict__:
        numpy.bool = bool
        _added = True


def unregister():
    global _added
    if _added:
        del numpy.bool
        _added = False
