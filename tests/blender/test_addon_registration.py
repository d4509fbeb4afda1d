"""The add-on installs from its zip, registers everything it adds (the object settings, the
operators, the sidebar panel, the scenario menu entries, the depsgraph handler), and disabling
it removes all of that; twice, so that a second enable after a disable works. With its module
folder pointing where there is no module, "Solve now" fails naming that folder."""

import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import blender_test_support as t  # noqa: E402

import bpy  # noqa: E402
import numpy  # noqa: E402

# Debian's NumPy 1.24 has no numpy.bool, which Blender 3.4's glTF importer uses; the add-on
# restores it while enabled (gltf_import_fix.py). Elsewhere the alias may exist already.
numpy_had_bool = "bool" in numpy.__dict__


def handler_names():
    return [h.__name__ for h in bpy.app.handlers.depsgraph_update_post]


def export_menu_entries():
    return [f.__name__ for f in getattr(bpy.types.TOPBAR_MT_file_export, "_dyn_ui_initialize")()]


for round_ in (1, 2):
    t.install_addon()
    assert hasattr(bpy.types.Object, "primo")
    for op in ("add_handle", "remove_handle", "add_paint_group", "solve_now", "export_scenario", "import_scenario"):
        assert hasattr(bpy.types, "PRIMO_OT_" + op), op
    assert hasattr(bpy.types, "PRIMO_PT_pose")
    assert "on_depsgraph_update" in handler_names()
    assert "_menu_export" in export_menu_entries()
    assert numpy.bool is bool, "glTF imports need numpy.bool while the add-on is enabled"
    bpy.ops.preferences.addon_disable(module="primo_pose")
    assert not hasattr(bpy.types.Object, "primo")
    for op in ("add_handle", "solve_now", "export_scenario", "import_scenario"):
        assert not hasattr(bpy.types, "PRIMO_OT_" + op), op
    assert not hasattr(bpy.types, "PRIMO_PT_pose")
    assert "on_depsgraph_update" not in handler_names(), handler_names()
    assert "_menu_export" not in export_menu_entries()
    assert ("bool" in numpy.__dict__) == numpy_had_bool, "disabling leaves numpy as it was"
    print("round %d: registered and unregistered" % round_)

# No module where the preference points (and none on Python's path in this process, which
# has not imported one): the error names the folder and says what to set.
empty_folder = os.path.join(t.SCRATCH, "no-module-here")
os.makedirs(empty_folder)
t.install_addon(module_dir=empty_folder)
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
cyl = t.cylinder()
try:
    bpy.ops.primo.solve_now()
    raise AssertionError("solve now worked without a module")
except RuntimeError as e:
    assert empty_folder in str(e) and "Preferences" in str(e), str(e)
    print("without the module:", cyl.primo.status)
bpy.ops.preferences.addon_disable(module="primo_pose")
print("PASS")
