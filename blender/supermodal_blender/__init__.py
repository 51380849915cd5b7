# SPDX-License-Identifier: MIT
"""supermodal for Blender: objects become superquadric bodies that move rigidly and deform through their
vibration modes; a bake writes keyframes and one shape key per mode, an export writes the scene file
that `supermodal run` steps to the same poses (docs/blender.md)."""
import bpy

from . import operators, panel, preferences, properties

bl_info = {
    "name": "supermodal",
    "author": "supermodal contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > supermodal",
    "description": "Superquadric bodies with vibration modes: simulate, bake keyframes and shape keys, export",
    "category": "Physics",
}

CLASSES = preferences.CLASSES + operators.CLASSES + panel.CLASSES


def register():
    properties.register()
    for cls in CLASSES:
        bpy.utils.register_class(cls)


def unregister():
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
    properties.unregister()
