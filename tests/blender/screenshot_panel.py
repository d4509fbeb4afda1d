"""The screenshots of docs/blender.md, from Blender itself (not a test): a cylinder bent by its
top handle with the PriMo tab open, and the same in Weight Paint with a painted stiffness band.
Run with a window, under Xvfb, with a scratch user folder (docs/blender.md, "Tests"):
  BLENDER_USER_SCRIPTS=$(mktemp -d) xvfb-run -a -s "-screen 0 1280x800x24" blender \
    --factory-startup --python tests/blender/screenshot_panel.py -- ZIP MODULE_DIR IMAGE_DIR"""

import math
import os
import subprocess
import sys
import traceback

sys.path.insert(0, os.path.dirname(__file__))
import blender_test_support as t  # noqa: E402

import bpy  # noqa: E402
import mathutils  # noqa: E402

IMAGES = sys.argv[sys.argv.index("--") + 3]

bpy.context.preferences.view.show_splash = False
t.install_addon()
for obj in list(bpy.data.objects):
    if obj.type != 'CAMERA' and obj.type != 'LIGHT':
        bpy.data.objects.remove(obj)
cyl = t.cylinder(segments=32, rings=20)
z = t.face_centroids(cyl)[:, 2]
t.add_handle(cyl, z < -0.85, kind='FIXED')
top = t.add_handle(cyl, z > 0.85)
assert bpy.ops.primo.add_paint_group(layer='STIFFNESS') == {'FINISHED'}
band = [v.index for v in cyl.data.vertices if -0.3 < v.co.z < 0.1]
cyl.vertex_groups[cyl.primo.stiffness_group].add(band, 0.35, 'REPLACE')
top.empty.location += mathutils.Vector((0.45, 0.0, -0.2))
top.empty.rotation_euler = (0.0, math.radians(45), 0.0)
bpy.context.view_layer.update()
assert bpy.ops.primo.solve_now() == {'FINISHED'}, cyl.primo.status
bpy.context.view_layer.objects.active = cyl
for o in bpy.data.objects:
    o.select_set(o == cyl)


def view3d():
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == 'VIEW_3D':
            return window, area, next(r for r in area.regions if r.type == 'WINDOW')


def shoot(name):
    """The 3D view, scaled to 80% as an 8-bit RGB PNG: under 200 kB for the docs."""
    window, area, region = view3d()
    path = os.path.join(IMAGES, name)
    full = os.path.join(t.SCRATCH, name)
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screenshot_area(filepath=full)
    image = bpy.data.images.load(full)
    image.scale(int(image.size[0] * 0.8), int(image.size[1] * 0.8))
    settings = bpy.context.scene.render.image_settings
    settings.file_format, settings.color_mode, settings.color_depth = 'PNG', 'RGB', '8'
    settings.compression = 100
    image.save_render(path, scene=bpy.context.scene)
    print("wrote", path, os.path.getsize(path), "bytes")


def frame():
    window, area, region = view3d()
    space = area.spaces.active
    space.show_region_ui = True
    space.region_3d.view_rotation = mathutils.Euler((math.radians(80), 0, math.radians(20))).to_quaternion()
    space.region_3d.view_location = (0.2, 0.0, 0.0)
    space.region_3d.view_distance = 4.2


def open_primo_tab():
    """Blender 3.4 has no API for the sidebar's tab: Ctrl + wheel over the sidebar steps
    through its tabs (Item, Tool, View, PriMo), sent with xdotool to this Xvfb window."""
    window, area, region = view3d()
    sidebar = next(r for r in area.regions if r.type == 'UI')
    x = sidebar.x + sidebar.width // 2
    y = window.height - (sidebar.y + sidebar.height // 2)
    subprocess.run(["xdotool", "mousemove", str(x), str(y), "sleep", "0.3", "keydown", "ctrl",
                    "click", "5", "sleep", "0.2", "click", "5", "sleep", "0.2", "click", "5",
                    "sleep", "0.2", "keyup", "ctrl"], check=True)
    # Wider, so that names are not cut: its left edge dragged 110 pixels to the left.
    edge = sidebar.x
    steps = []
    for dx in range(10, 120, 10):
        steps += ["mousemove", str(edge - dx), str(y), "sleep", "0.05"]
    subprocess.run(["xdotool", "mousemove", str(edge), str(y), "sleep", "0.5", "mousedown", "1",
                    "sleep", "0.3"] + steps + ["sleep", "0.3", "mouseup", "1"], check=True)


def step(state=[0]):
    state[0] += 1
    try:
        if state[0] == 1:
            frame()
            return 1.0
        if state[0] == 2:
            open_primo_tab()
            return 1.0
        if state[0] == 3:
            shoot("blender-panel.png")
            window, area, region = view3d()
            with bpy.context.temp_override(window=window, area=area, region=region):
                bpy.ops.object.mode_set(mode='WEIGHT_PAINT')
            cyl.vertex_groups.active_index = cyl.vertex_groups[cyl.primo.stiffness_group].index
            return 1.0
        shoot("blender-weight-paint.png")
    except Exception:
        traceback.print_exc()
    bpy.ops.wm.quit_blender()
    return None


bpy.app.timers.register(step, first_interval=1.0)
