# SPDX-License-Identifier: MIT
"""The add-on's preferences: where the supermodal Python module lives."""
import bpy


class SupermodalPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    module_dir: bpy.props.StringProperty(
        name="Module folder", subtype="DIR_PATH",
        description="Folder holding the supermodal Python module (the build's python/ folder, or the "
                    "site-packages it was installed to); empty: $SUPERMODAL_PYTHONPATH or Python's path")

    def draw(self, context):
        self.layout.prop(self, "module_dir")


CLASSES = (SupermodalPreferences,)
