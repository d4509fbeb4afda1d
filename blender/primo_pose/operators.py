"""The add-on's operators: handles and fixed regions from selected faces, painted layers,
"Solve now", and scenario export and import."""

import os

import bmesh
import bpy
import mathutils
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import live_follow, module_finder, pose_setup, pose_solver, properties, scenario_io


def _mesh_object(context):
    obj = context.active_object
    return obj if obj is not None and obj.type == 'MESH' else None


class PRIMO_OT_add_handle(bpy.types.Operator):
    """Make the selected faces a handle (with an Empty to move and turn) or a fixed region"""
    bl_idname = "primo.add_handle"
    bl_label = "Add PriMo handle"
    bl_options = {'REGISTER', 'UNDO'}

    kind: bpy.props.EnumProperty(items=[('HANDLE', "Handle", ""), ('FIXED', "Fixed region", "")])
    fix: bpy.props.EnumProperty(name="Mode", items=properties.FIX_ITEMS, default='ALL')

    @classmethod
    def poll(cls, context):
        return _mesh_object(context) is not None and context.mode == 'EDIT_MESH'

    def execute(self, context):
        obj = _mesh_object(context)
        bm = bmesh.from_edit_mesh(obj.data)
        faces = [f for f in bm.faces if f.select]
        if not faces:
            self.report({'ERROR'}, "Select the faces of the handle first (face select mode)")
            return {'CANCELLED'}
        settings = obj.primo
        stem = "Handle" if self.kind == 'HANDLE' else "Fixed"
        number = 1 + sum(1 for h in settings.handles if h.kind == self.kind)
        name = "%s %d" % (stem, number)
        while obj.vertex_groups.get("PriMo " + name) is not None:
            number += 1
            name = "%s %d" % (stem, number)
        group = obj.vertex_groups.new(name="PriMo " + name)
        deform = bm.verts.layers.deform.verify()
        for f in faces:
            for v in f.verts:
                v[deform][group.index] = 1.0
        area = sum(f.calc_area() for f in faces)
        centroid = sum((f.calc_center_median() * f.calc_area() for f in faces), mathutils.Vector())
        centroid = centroid / area if area > 0 else faces[0].calc_center_median()
        bmesh.update_edit_mesh(obj.data)

        handle = settings.handles.add()
        handle.name = name
        handle.kind = self.kind
        handle.fix = self.fix
        handle.vertex_group = group.name
        if self.kind == 'HANDLE':
            pose_setup.make_handle_empty(
                handle, "PriMo " + obj.name + " " + name,
                pose_setup.matrix_array(mathutils.Matrix.Translation(obj.matrix_world @ centroid)),
                max(obj.dimensions) * 0.15 or 0.1, obj.users_collection[0])
        settings.active_handle = len(settings.handles) - 1
        pose_solver.forget(obj.name_full)
        return {'FINISHED'}


class PRIMO_OT_remove_handle(bpy.types.Operator):
    """Remove the active handle, its vertex group and its Empty"""
    bl_idname = "primo.remove_handle"
    bl_label = "Remove PriMo handle"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        obj = _mesh_object(context)
        return obj is not None and 0 <= obj.primo.active_handle < len(obj.primo.handles)

    def execute(self, context):
        obj = _mesh_object(context)
        settings = obj.primo
        handle = settings.handles[settings.active_handle]
        group = obj.vertex_groups.get(handle.vertex_group)
        if group is not None:
            obj.vertex_groups.remove(group)
        if handle.empty is not None:
            bpy.data.objects.remove(handle.empty)
        settings.handles.remove(settings.active_handle)
        settings.active_handle = max(0, settings.active_handle - 1)
        pose_solver.forget(obj.name_full)
        return {'FINISHED'}


class PRIMO_OT_add_paint_group(bpy.types.Operator):
    """Add the vertex group to paint (every vertex at 0.5, neutral) and switch to Weight Paint"""
    bl_idname = "primo.add_paint_group"
    bl_label = "Paint PriMo layer"
    bl_options = {'REGISTER', 'UNDO'}

    layer: bpy.props.EnumProperty(items=[('STIFFNESS', "Stiffness", ""), ('WIDTH', "Width", "")])

    @classmethod
    def poll(cls, context):
        return _mesh_object(context) is not None

    def execute(self, context):
        obj = _mesh_object(context)
        name = obj.primo.stiffness_group if self.layer == 'STIFFNESS' else obj.primo.width_group
        group = obj.vertex_groups.get(name)
        if group is None:
            if obj.mode != 'OBJECT':
                bpy.ops.object.mode_set(mode='OBJECT')
            group = obj.vertex_groups.new(name=name)
            group.add(range(len(obj.data.vertices)), 0.5, 'REPLACE')
        obj.vertex_groups.active_index = group.index
        pose_solver.forget(obj.name_full)
        if context.area is not None:  # not in background mode
            bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
        return {'FINISHED'}


class PRIMO_OT_solve_now(bpy.types.Operator):
    """Solve the pose from rest for the handles where their Empties are and write the shape key
    (the result primo deform gives for the exported scenario)"""
    bl_idname = "primo.solve_now"
    bl_label = "Solve now"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        obj = _mesh_object(context)
        return obj is not None and obj.mode == 'OBJECT'

    def execute(self, context):
        obj = _mesh_object(context)
        try:
            primo = live_follow.primo_module()
            setup = pose_setup.PoseSetup(obj)
            solver = pose_solver.solver_for(primo, obj.name_full, setup)
            vertices, report = solver.solve(pose_setup.handle_matrices(obj), from_rest=True)
            pose_solver.write_pose(obj, vertices)
        except (module_finder.ModuleNotFound, pose_setup.SetupError) as e:
            obj.primo.status = str(e)
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        except RuntimeError as e:  # primo.Error: the message names the problem
            obj.primo.status = str(e)
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        obj.primo.status = pose_solver.report_text(report)
        return {'FINISHED'}


class PRIMO_OT_export_scenario(bpy.types.Operator, ExportHelper):
    """Write the active object's handles, fixed regions, painted factors and material as a PriMo
    scenario (primo-scenario/1), with its rest mesh as an OBJ beside it"""
    bl_idname = "primo.export_scenario"
    bl_label = "Export PriMo scenario"
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={'HIDDEN'})

    @classmethod
    def poll(cls, context):
        obj = _mesh_object(context)
        return obj is not None and obj.mode == 'OBJECT'

    def execute(self, context):
        obj = _mesh_object(context)
        try:
            mesh_path = scenario_io.export_scenario(live_follow.primo_module(), obj, self.filepath)
        except (module_finder.ModuleNotFound, pose_setup.SetupError, RuntimeError, ValueError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "Wrote %s and %s" % (self.filepath, os.path.basename(mesh_path)))
        return {'FINISHED'}


class PRIMO_OT_import_scenario(bpy.types.Operator, ImportHelper):
    """Read a PriMo scenario: its mesh as a new object with the handles (Empties where the
    scenario puts them), fixed regions, painted factors and material"""
    bl_idname = "primo.import_scenario"
    bl_label = "Import PriMo scenario"
    bl_options = {'REGISTER', 'UNDO'}
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        try:
            obj, notes = scenario_io.import_scenario(live_follow.primo_module(), context, self.filepath)
        except (module_finder.ModuleNotFound, RuntimeError, ValueError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        for note in notes:
            self.report({'WARNING'}, note)
        return {'FINISHED'}


def _menu_export(self, context):
    self.layout.operator(PRIMO_OT_export_scenario.bl_idname, text="PriMo scenario (.json)")


def _menu_import(self, context):
    self.layout.operator(PRIMO_OT_import_scenario.bl_idname, text="PriMo scenario (.json)")


classes = (PRIMO_OT_add_handle, PRIMO_OT_remove_handle, PRIMO_OT_add_paint_group, PRIMO_OT_solve_now,
           PRIMO_OT_export_scenario, PRIMO_OT_import_scenario)


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.TOPBAR_MT_file_export.append(_menu_export)
    bpy.types.TOPBAR_MT_file_import.append(_menu_import)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
    bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
