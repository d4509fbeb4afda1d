"""Finds PriMo's Python module (docs/python.md) for the add-on.

Blender's Python is Debian's /usr/bin/python3, so the module built for it imports here as it
does in a terminal. It is looked for, in order: in the folder set in the add-on's preferences
(a build folder's `build/python`, or an install's site folder); where Python looks anyway
(an install under /usr or /usr/local, or PYTHONPATH); in the user's site folder, which
Blender leaves off sys.path (`cmake --install build --prefix ~/.local`).
"""

import importlib
import os
import site
import sys


class ModuleNotFound(Exception):
    """The module is nowhere the add-on looked; the message says where that was."""


def _module_file_in(folder):
    try:
        names = os.listdir(folder)
    except OSError:
        return None
    for name in names:
        if name.startswith("primo.") and name.endswith(".so"):
            return os.path.join(folder, name)
    return None


def _import_from(folder):
    """Imports the module from `folder` first; a module imported before from elsewhere is kept
    only when it is the same file."""
    loaded = sys.modules.get("primo")
    wanted = _module_file_in(folder)
    if loaded is not None and os.path.realpath(getattr(loaded, "__file__", "")) == os.path.realpath(wanted):
        return loaded
    if loaded is not None:
        # An extension module cannot be unloaded: a second one of the same name would load
        # beside it and share nothing, so the folder takes effect after a restart.
        raise ModuleNotFound(
            "PriMo's module is already loaded from %s; restart Blender to use the one in %s"
            % (loaded.__file__, folder))
    sys.path.insert(0, folder)
    try:
        return importlib.import_module("primo")
    except ImportError as e:
        raise ModuleNotFound("%s: %s" % (wanted, e)) from None
    finally:
        sys.path.remove(folder)


def find_primo(preferred_folder=""):
    """The `primo` module, or ModuleNotFound naming every place looked in and what to do."""
    tried = []
    if preferred_folder:
        folder = os.path.abspath(bpy_path(preferred_folder))
        if _module_file_in(folder):
            return _import_from(folder)
        tried.append("%s (the add-on's preference: no primo.*.so there)" % folder)
    try:
        return importlib.import_module("primo")
    except ImportError as e:
        tried.append("Python's own path (%s)" % e)
    user_site = site.getusersitepackages()
    if _module_file_in(user_site):
        return _import_from(user_site)
    tried.append(user_site)
    raise ModuleNotFound(
        "PriMo's Python module was not found. Looked in: " + "; ".join(tried) + ". Set its "
        "folder in Edit > Preferences > Add-ons > PriMo Pose: build/python in a build folder, "
        "or the folder `cmake --install` put it in (docs/blender.md).")


def bpy_path(path):
    """A path as Blender writes it ('//' is the .blend file's folder)."""
    try:
        import bpy
    except ImportError:
        return path
    return bpy.path.abspath(path)
