"""PriMo Pose: pose meshes in Blender with PriMo's solver (docs/blender.md).

In Edit Mode, selected faces become a handle (a vertex group and an Empty to move and turn) or
a fixed region; the mesh follows the Empties into a shape key; stiffness and width are painted
on vertex groups; scenarios go to and come from `primo deform` and the editor.
"""

bl_info = {
    "name": "PriMo Pose",
    "description": "Pose meshes with handles and coupled prisms (PriMo's solver)",
    "author": "The PriMo authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Sidebar > PriMo; File > Import/Export > PriMo scenario",
    "category": "Mesh",
}

from . import gltf_import_fix, live_follow, operators, panel, properties  # noqa: E402

_parts = (properties, operators, panel, live_follow, gltf_import_fix)


def register():
    for part in _parts:
        part.register()


def unregister():
    for part in reversed(_parts):
        part.unregister()
