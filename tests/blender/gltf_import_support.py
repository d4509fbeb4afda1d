"""What the scripts that import a glTF written by PriMo into Blender share (run inside Blender):
the NumPy alias Blender 3.4's glTF importer needs, and an OBJ's vertex positions."""

import numpy

# Debian 12's Blender 3.4 glTF importer uses numpy.bool, which NumPy 1.24 removed (it was the
# builtin bool): without it every import of a mesh with normals fails.
if "bool" not in numpy.__dict__:
    numpy.bool = bool


def read_points(path):
    """The `v` lines of the OBJ at `path`, as [x, y, z] lists."""
    with open(path) as f:
        return [[float(x) for x in line.split()[1:4]] for line in f if line.startswith("v ")]
