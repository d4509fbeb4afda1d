"""The PriMo tab of the 3D view's sidebar (N): handles, material, painting, solving, scenarios."""

import bpy


class PRIMO_UL_handles(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index):
        # The name only, so that it is not cut: the kind shows as the icon, the mode below.
        layout.prop(item, "name", text="", emboss=False,
                    icon='EMPTY_ARROWS' if item.kind == 'HANDLE' else 'PINNED')


class PRIMO_PT_pose(bpy.types.Panel):
    bl_label = "PriMo Pose"
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "PriMo"

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == 'MESH'

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        settings = obj.primo

        box = layout.box()
        box.label(text="Handles")
        row = box.row()
        row.template_list("PRIMO_UL_handles", "", settings, "handles", settings, "active_handle", rows=3)
        column = row.column(align=True)
        column.operator("primo.remove_handle", text="", icon='REMOVE')
        row = box.row(align=True)
        add = row.operator("primo.add_handle", text="Handle", icon='EMPTY_ARROWS')
        add.kind = 'HANDLE'
        add = row.operator("primo.add_handle", text="Fixed", icon='PINNED')
        add.kind = 'FIXED'
        if obj.mode != 'EDIT':
            box.label(text="Edit Mode: select faces, add", icon='INFO')
        if 0 <= settings.active_handle < len(settings.handles):
            handle = settings.handles[settings.active_handle]
            box.prop(handle, "kind")
            if handle.kind == 'HANDLE':
                box.prop(handle, "fix")
                box.prop(handle, "empty")

        box = layout.box()
        box.label(text="Material")
        box.prop(settings, "thickness_percent")
        box.prop(settings, "normal_blend")
        box.prop(settings, "width")

        box = layout.box()
        box.label(text="Painting (Weight Paint)")
        box.prop_search(settings, "stiffness_group", obj, "vertex_groups", text="Stiffness")
        box.prop_search(settings, "width_group", obj, "vertex_groups", text="Width")
        row = box.row(align=True)
        row.operator("primo.add_paint_group", text="Paint stiffness", icon='BRUSH_DATA').layer = 'STIFFNESS'
        row.operator("primo.add_paint_group", text="Paint width", icon='BRUSH_DATA').layer = 'WIDTH'

        box = layout.box()
        box.label(text="Solver")
        box.prop(settings, "live")
        box.operator("primo.solve_now", icon='PLAY')
        if settings.status:
            # About 7 pixels a character at the interface's scale.
            characters = int(context.region.width / (7.0 * context.preferences.view.ui_scale)) - 4
            for line in _wrapped(settings.status, max(characters, 20)):
                box.label(text=line)

        row = layout.row(align=True)
        row.operator("primo.export_scenario", text="Export scenario", icon='EXPORT')
        row.operator("primo.import_scenario", text="Import", icon='IMPORT')


def _wrapped(text, width):
    words, lines, line = text.split(), [], ""
    for word in words:
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = (line + " " + word).strip()
    return lines + [line] if line else lines


classes = (PRIMO_UL_handles, PRIMO_PT_pose)


def register():
    for c in classes:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
