# SPDX-License-Identifier: MIT
"""The add-on's operators: fit, bake (modal, cancellable with Esc), clear, export."""
import json
import os
import time

import bpy
from bpy_extras.io_utils import ExportHelper

from . import bake, engine, fitting, keyframes, scene_json
from .errors import SceneBuildError


class SUPERMODAL_OT_fit(bpy.types.Operator):
    """Fit a superquadric to the active mesh object and use it as the body's shape"""
    bl_idname = "supermodal.fit"
    bl_label = "Fit to mesh"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.active_object is not None and context.active_object.type == "MESH"

    def execute(self, context):
        obj = context.active_object
        try:
            sm = engine.load(context)
            result = fitting.fit_object(obj, sm)
        except (engine.ModuleMissing, SceneBuildError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        except ValueError as e:  # supermodal.ArgumentError: too few points, a flat mesh
            self.report({"ERROR"}, f"{obj.name}: fit failed: {e}")
            return {"CANCELLED"}
        self.report({"INFO"}, f"{obj.name}: RMS {result['rms_m']:.3g} m over size {result['size_m']:.3g} m")
        return {"FINISHED"}


class SUPERMODAL_OT_radii_from_bounds(bpy.types.Operator):
    """Set the parametric radii to half the object's dimensions"""
    bl_idname = "supermodal.radii_from_bounds"
    bl_label = "Radii from bounds"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.active_object is not None

    def execute(self, context):
        fitting.radii_from_bounds(context.active_object)
        return {"FINISHED"}


class SUPERMODAL_OT_bake(bpy.types.Operator):
    """Simulate the scene's supermodal bodies and bake keyframes and mode shape keys (Esc cancels)"""
    bl_idname = "supermodal.bake"
    bl_label = "Simulate & bake"
    bl_options = {"REGISTER", "UNDO"}

    _bake = None
    _timer = None

    def _start(self, context):
        context.scene.frame_set(context.scene.frame_start)  # the poses the run starts from
        try:
            self._bake = bake.Bake(context.scene, engine.load(context))
        except (engine.ModuleMissing, SceneBuildError) as e:
            self.report({"ERROR"}, str(e))
            return False
        self._started = time.perf_counter()
        context.window_manager.progress_begin(0, self._bake.total)
        return True

    def _finish(self, context):
        context.window_manager.progress_end()
        self._bake.write()
        seconds = time.perf_counter() - self._started
        context.scene.supermodal.bake_seconds = seconds
        context.scene.frame_set(context.scene.frame_current)
        self.report({"INFO"}, f"baked {len(self._bake.steps)} frames ({self._bake.total} steps) in {seconds:.2f} s, "
                              f"{self._bake.stepped_seconds:.2f} s of it stepping")
        return {"FINISHED"}

    def execute(self, context):
        if not self._start(context):
            return {"CANCELLED"}
        while not self._bake.done:
            self._bake.advance(0.1)
            context.window_manager.progress_update(self._bake.progress)
        return self._finish(context)

    def invoke(self, context, event):
        if not self._start(context):
            return {"CANCELLED"}
        self._timer = context.window_manager.event_timer_add(0.01, window=context.window)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        if event.type == "ESC":
            self._stop(context)
            self.report({"WARNING"}, "bake cancelled: nothing was changed")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"RUNNING_MODAL"}  # other input waits: an edit mid-bake would not match the run
        self._bake.advance(0.05)  # a slice short enough to keep Blender responsive
        context.window_manager.progress_update(self._bake.progress)
        if not self._bake.done:
            return {"RUNNING_MODAL"}
        self._stop(context, ended=False)
        return self._finish(context)

    def _stop(self, context, ended=True):
        context.window_manager.event_timer_remove(self._timer)
        if ended:
            context.window_manager.progress_end()


class SUPERMODAL_OT_clear_bake(bpy.types.Operator):
    """Remove the baked keyframes and mode shape keys of the scene's supermodal bodies"""
    bl_idname = "supermodal.clear_bake"
    bl_label = "Clear bake"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        for obj in scene_json.body_objects(context.scene):
            keyframes.clear_body(obj)
        return {"FINISHED"}


def write_scene(scene, path, sm):
    """Writes the scene file of the start frame's poses (what a bake starts from), once the engine has
    accepted it, next to its final name, then renames it: no half-written file."""
    current = scene.frame_current
    scene.frame_set(scene.frame_start)
    try:
        doc = scene_json.scene_dict(scene)
    finally:
        scene.frame_set(current)
    try:
        sm.load_scene(doc)
    except sm.SceneError as e:
        raise bake.scene_error(doc, e) from None
    text = json.dumps(doc, indent=2) + "\n"
    temporary = path + ".part"
    try:
        with open(temporary, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(temporary, path)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


class SUPERMODAL_OT_export_scene(bpy.types.Operator, ExportHelper):
    """Write the scene file that `supermodal run` steps to reproduce the bake"""
    bl_idname = "supermodal.export_scene"
    bl_label = "Export scene"
    filename_ext = ".json"
    filter_glob: bpy.props.StringProperty(default="*.json", options={"HIDDEN"})

    def execute(self, context):
        try:
            write_scene(context.scene, self.filepath, engine.load(context))
        except (engine.ModuleMissing, SceneBuildError, OSError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        self.report({"INFO"}, f"wrote {self.filepath}")
        return {"FINISHED"}


CLASSES = (SUPERMODAL_OT_fit, SUPERMODAL_OT_radii_from_bounds, SUPERMODAL_OT_bake, SUPERMODAL_OT_clear_bake,
           SUPERMODAL_OT_export_scene)
