"""Live follow: while an Empty of a handle moves, the mesh follows.

Blender calls on_depsgraph_update on the main thread after every change. It reads the handles'
motions there (bpy may only be used on the main thread) and hands them to one worker thread,
which solves with the module (it releases the GIL, so Blender stays responsive); a timer on the
main thread writes each finished pose to the shape key. Requests for the same object replace
one another, so a fast drag solves only for the newest position.
"""

import threading

import bpy
from bpy.app.handlers import persistent

from . import module_finder, pose_setup, pose_solver

_lock = threading.Lock()
_wake = threading.Condition(_lock)
_pending = {}   # object_name -> (setup or None, matrices)
_finished = {}  # object_name -> (vertices, report text) or (None, error text)
_busy = set()
_worker = None
_stopping = False
POLL_SECONDS = 1.0 / 30.0


def primo_module():
    prefs = bpy.context.preferences.addons.get(__package__)
    folder = prefs.preferences.module_folder if prefs else ""
    return module_finder.find_primo(folder)


def _work():
    while True:
        with _wake:
            while not _pending and not _stopping:
                _wake.wait()
            if _stopping:
                return
            object_name, (primo, setup, matrices) = _pending.popitem()
            _busy.add(object_name)
        try:
            solver = pose_solver.solver_for(primo, object_name, setup) if setup else pose_solver.cached_solver(object_name)
            if solver is None:  # the setup changed after the request: the next one rebuilds
                result = (None, "The setup changed: move an Empty again or press Solve now")
            else:
                vertices, report = solver.solve(matrices, from_rest=False)
                result = (vertices, pose_solver.report_text(report))
        except Exception as e:  # shown in the panel: primo.Error names the problem
            result = (None, str(e))
        with _wake:
            _busy.discard(object_name)
            _finished[object_name] = result


def request(obj):
    """Queues a solve of `obj` for its handles' current motions (main thread)."""
    global _worker
    object_name = obj.name_full
    try:
        primo = primo_module()
        cached = pose_solver.cached_solver(object_name)
        setup = None if cached is not None and cached.n_handles == len(obj.primo.handles) else pose_setup.PoseSetup(obj)
        matrices = pose_setup.handle_matrices(obj)
    except (module_finder.ModuleNotFound, pose_setup.SetupError) as e:
        obj.primo.status = str(e)
        return
    with _wake:
        _pending[object_name] = (primo, setup, matrices)
        if _worker is None or not _worker.is_alive():
            _worker = threading.Thread(target=_work, name="PriMo live follow", daemon=True)
            _worker.start()
        _wake.notify()
    if not bpy.app.timers.is_registered(_deliver):
        bpy.app.timers.register(_deliver, first_interval=POLL_SECONDS)


def _deliver():
    """Writes finished poses (main thread); keeps polling while solves are under way."""
    with _wake:
        finished = dict(_finished)
        _finished.clear()
        running = bool(_pending or _busy)
    if finished:
        by_name = {o.name_full: o for o in bpy.data.objects if o.type == 'MESH'}
        for object_name, (vertices, text) in finished.items():
            obj = by_name.get(object_name)
            if obj is None:
                continue
            if vertices is not None:
                try:
                    pose_solver.write_pose(obj, vertices)
                except ValueError as e:
                    text = str(e)
                    pose_solver.forget(object_name)
            obj.primo.status = text
    return POLL_SECONDS if running else None


def is_idle():
    with _wake:
        return not (_pending or _busy or _finished)


def _followers(scene):
    return [o for o in scene.objects if o.type == 'MESH' and o.primo.live and len(o.primo.handles)]


@persistent
def on_depsgraph_update(scene, depsgraph):
    moved = set()
    for update in depsgraph.updates:
        if isinstance(update.id, bpy.types.Object):
            original = update.id.original
            if original.type == 'EMPTY' and update.is_updated_transform:
                moved.add(original.name_full)
            elif original.type == 'MESH' and update.is_updated_geometry and original.mode in {'EDIT', 'WEIGHT_PAINT'}:
                # Painted weights or edited groups: the next solve rebuilds its setup.
                pose_solver.forget(original.name_full)
    if not moved:
        return
    for obj in _followers(scene):
        if obj.mode == 'OBJECT' and any(h.empty is not None and h.empty.name_full in moved for h in obj.primo.handles):
            request(obj)


def register():
    global _stopping
    _stopping = False
    bpy.app.handlers.depsgraph_update_post.append(on_depsgraph_update)


def unregister():
    global _stopping, _worker
    if on_depsgraph_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(on_depsgraph_update)
    if bpy.app.timers.is_registered(_deliver):
        bpy.app.timers.unregister(_deliver)
    with _wake:
        _stopping = True
        _pending.clear()
        _finished.clear()
        _wake.notify_all()
    if _worker is not None:
        _worker.join()
        _worker = None
    pose_solver.forget()
