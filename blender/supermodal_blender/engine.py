# SPDX-License-Identifier: MIT
"""Finding the `supermodal` Python module (docs/python.md): the folder in the add-on's preferences,
else $SUPERMODAL_PYTHONPATH (Blender ignores $PYTHONPATH), else wherever Python finds it already."""
import importlib
import os
import sys


class ModuleMissing(RuntimeError):
    pass


def _folders(context):
    addon = context.preferences.addons.get(__package__) if context is not None else None
    if addon is not None and addon.preferences.module_dir:
        yield bpy_abspath(addon.preferences.module_dir)
    for folder in os.environ.get("SUPERMODAL_PYTHONPATH", "").split(os.pathsep):
        if folder:
            yield folder


def bpy_abspath(path):
    import bpy
    return os.path.abspath(bpy.path.abspath(path))


def load(context=None):
    """The supermodal module; ModuleMissing says where it was looked for."""
    for folder in _folders(context):
        if folder not in sys.path:
            sys.path.insert(0, folder)
    try:
        return importlib.import_module("supermodal")
    except ImportError as e:
        raise ModuleMissing("the Python module supermodal was not found: set its folder (the build's python/ "
                            "or the install's site-packages) in the add-on's preferences or in "
                            f"SUPERMODAL_PYTHONPATH ({e})") from None
