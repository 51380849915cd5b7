# SPDX-License-Identifier: MIT
"""View3D > Sidebar > supermodal: the active object's body, the world, bake and export."""
import bpy

TAB = "supermodal"


class SUPERMODAL_PT_body(bpy.types.Panel):
    bl_label = "Body"
    bl_idname = "SUPERMODAL_PT_body"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = TAB

    @classmethod
    def poll(cls, context):
        return context.active_object is not None

    def draw_header(self, context):
        self.layout.prop(context.active_object.supermodal, "enabled", text="")

    def draw(self, context):
        body = context.active_object.supermodal
        layout = self.layout
        layout.active = body.enabled
        layout.prop(body, "shape")
        if body.shape == "PLANE":
            layout.label(text="Static plane: normal along local Z")
            return
        layout.prop(body, "source", expand=True)
        if body.source == "FIT":
            layout.operator("supermodal.fit", icon="MESH_UVSPHERE")
            if body.fitted:
                column = layout.column(align=True)
                column.label(text=f"Radii {tuple(round(r, 4) for r in body.fit_radii)} m")
                column.label(text=f"Exponents {tuple(round(e, 3) for e in body.fit_exponents)}, "
                                  f"RMS {body.fit_rms:.3g} m")
        else:
            layout.prop(body, "radii")
            layout.prop(body, "exponents")
            layout.operator("supermodal.radii_from_bounds")
        layout.prop(body, "motion")
        if body.motion == "dynamic":
            layout.prop(body, "dynamics")
            if body.dynamics != "rigid":
                layout.prop(body, "modes")
                layout.prop(body, "lattice")
        if body.motion != "static":
            layout.prop(body, "velocity")
            layout.prop(body, "angular_velocity")


class SUPERMODAL_PT_material(bpy.types.Panel):
    bl_label = "Material"
    bl_parent_id = "SUPERMODAL_PT_body"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = TAB
    bl_options = {"DEFAULT_CLOSED"}

    def draw(self, context):
        body = context.active_object.supermodal
        for name in ("density", "young", "poisson", "friction", "restitution", "rolling_resistance",
                     "damping_ratio"):
            self.layout.prop(body, name)


class SUPERMODAL_PT_world(bpy.types.Panel):
    bl_label = "World"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = TAB

    def draw(self, context):
        world = context.scene.supermodal
        layout = self.layout
        for name in ("dt", "substeps", "duration", "contact_solver", "accuracy"):
            layout.prop(world, name)
        layout.label(text="Gravity: Scene > Gravity; frames: the scene's frame rate")
        layout.label(text="Joints: rigid-body constraints Point, Hinge, Fixed")


class SUPERMODAL_PT_bake(bpy.types.Panel):
    bl_label = "Bake"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = TAB

    def draw(self, context):
        layout = self.layout
        layout.operator("supermodal.bake", icon="PHYSICS")
        layout.operator("supermodal.clear_bake", icon="X")
        layout.operator("supermodal.export_scene", icon="EXPORT")
        if context.scene.supermodal.bake_seconds > 0.0:
            layout.label(text=f"Last bake: {context.scene.supermodal.bake_seconds:.2f} s")


CLASSES = (SUPERMODAL_PT_body, SUPERMODAL_PT_material, SUPERMODAL_PT_world, SUPERMODAL_PT_bake)
