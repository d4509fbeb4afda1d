"""The add-on's data, saved in the .blend file: per mesh object its handles and fixed regions,
the names of its painted vertex groups and its material; and the add-on's preferences."""

import bpy

from . import pose_solver

FIX_ITEMS = [
    ('ALL', "Pose", "Position and orientation follow the Empty"),
    ('POSITION', "Position only", "The centre follows the Empty; the turn is left to the solver"),
    ('ORIENTATION', "Orientation only", "The turn follows the Empty; the position is left to the solver"),
]


def _setup_changed(self, context):
    pose_solver.forget(self.id_data.name_full)


class PrimoHandle(bpy.types.PropertyGroup):
    name: bpy.props.StringProperty(name="Name", update=_setup_changed)
    kind: bpy.props.EnumProperty(
        name="Kind", update=_setup_changed,
        items=[('HANDLE', "Handle", "Moved and turned with its Empty"),
               ('FIXED', "Fixed region", "Stays where it is")])
    fix: bpy.props.EnumProperty(name="Mode", items=FIX_ITEMS, default='ALL', update=_setup_changed)
    vertex_group: bpy.props.StringProperty(name="Vertex group", update=_setup_changed)
    empty: bpy.props.PointerProperty(name="Empty", type=bpy.types.Object)
    # The Empty's world matrix when the handle was made, row by row: its motion since then is
    # the handle's.
    rest_matrix: bpy.props.FloatVectorProperty(size=16)


class PrimoObjectSettings(bpy.types.PropertyGroup):
    handles: bpy.props.CollectionProperty(type=PrimoHandle)
    active_handle: bpy.props.IntProperty(name="Active handle", default=0)
    thickness_percent: bpy.props.FloatProperty(
        name="Thickness", default=8.0, min=0.0, soft_max=20.0, subtype='PERCENTAGE', update=_setup_changed,
        description="Half-thickness of the prism layer in percent of the bounding-box diagonal, the "
                    "same material at every resolution: thicker is stiffer against bending")
    normal_blend: bpy.props.FloatProperty(
        name="Shell/plate", default=0.0, soft_min=-0.5, soft_max=1.5, update=_setup_changed,
        description="0: thin shell (prisms along vertex normals); 1: thin plate (face normals); "
                    "below 0 enhances detail")
    width: bpy.props.FloatProperty(
        name="Width", default=1.0, min=0.01, soft_min=0.5, soft_max=1.5, update=_setup_changed,
        description="Scale of every prism about its face centre: below 1 the surface shrinks, "
                    "above 1 it grows")
    stiffness_group: bpy.props.StringProperty(
        name="Stiffness group", default="primo_stiffness", update=_setup_changed,
        description="Vertex group painted with Weight Paint: 0.5 neutral, 0 soft (x0.05), 1 stiff (x4)")
    width_group: bpy.props.StringProperty(
        name="Width group", default="primo_width", update=_setup_changed,
        description="Vertex group painted with Weight Paint: 0.5 neutral, 0 shrink (x0.5), 1 grow (x1.5)")
    live: bpy.props.BoolProperty(
        name="Follow live", default=True,
        description="Solve in the background while an Empty of a handle moves")
    status: bpy.props.StringProperty(name="Status", default="")


class PrimoPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_folder: bpy.props.StringProperty(
        name="Module folder", subtype='DIR_PATH', default="",
        description="Folder of PriMo's Python module (primo.*.so): build/python in a build folder, "
                    "or where cmake --install put it; empty: look where Python looks")

    def draw(self, context):
        self.layout.prop(self, "module_folder")


classes = (PrimoHandle, PrimoObjectSettings, PrimoPreferences)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.Object.primo = bpy.props.PointerProperty(type=PrimoObjectSettings)


def unregister():
    del bpy.types.Object.primo
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
