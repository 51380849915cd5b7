# SPDX-License-Identifier: MIT
"""What the add-on stores on objects (a body) and scenes (the world). Units are SI; vectors are in the
object's local axes (Blender's), which are the body's shape axes."""
import bpy
from bpy.props import (BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty,
                       IntVectorProperty, PointerProperty)


class SupermodalBody(bpy.types.PropertyGroup):
    enabled: BoolProperty(name="Body", description="Simulate this object as a supermodal body")
    shape: EnumProperty(name="Shape", items=[
        ("SUPERQUADRIC", "Superquadric", "A superquadric in the object's local frame"),
        ("PLANE", "Plane", "An infinite static plane through the object's origin, normal along its local Z"),
    ])
    source: EnumProperty(name="Source", items=[
        ("PARAMETRIC", "Parametric", "Radii and exponents as typed, centred on the object's origin"),
        ("FIT", "Fitted", "The superquadric fitted to the object's mesh (Fit to mesh)"),
    ])
    radii: FloatVectorProperty(name="Radii", description="Semi-axes along the object's local X, Y, Z [m]",
                               size=3, default=(0.5, 0.5, 0.5), min=1e-6, unit="LENGTH", precision=4)
    exponents: FloatVectorProperty(name="Exponents", description="epsilon1 (along Z), epsilon2 (around Z): "
                                   "1 ellipsoid, towards 0 box", size=2, default=(1.0, 1.0), min=0.01,
                                   max=4.0, precision=3)
    # What Fit to mesh found: the shape and its frame in the object's scaled local frame.
    fit_radii: FloatVectorProperty(size=3, default=(0.5, 0.5, 0.5), precision=4)
    fit_exponents: FloatVectorProperty(size=2, default=(1.0, 1.0), precision=3)
    fit_position: FloatVectorProperty(size=3)
    fit_orientation: FloatVectorProperty(size=4, default=(1.0, 0.0, 0.0, 0.0))
    fit_rms: FloatProperty(name="Fit RMS", description="RMS distance of the mesh to the fit [m]", unit="LENGTH")
    fitted: BoolProperty(default=False)
    motion: EnumProperty(name="Motion", items=[
        ("dynamic", "Dynamic", "Moves under forces and contact"),
        ("static", "Static", "Never moves"),
        ("kinematic", "Kinematic", "Moves with its initial velocity, ignores forces"),
    ])
    dynamics: EnumProperty(name="Dynamics", items=[
        ("rigid", "Rigid", "Rigid body"),
        ("modal", "Modal", "Deforms through its lowest vibration modes"),
        ("auto", "Auto", "Rigid until its loads need modes, then as many as the accuracy budget asks"),
    ])
    modes: IntProperty(name="Modes", description="Vibration modes kept (most, for auto)", default=8, min=1,
                       max=256)
    lattice: IntVectorProperty(name="Lattice", description="Cells along the local X, Y, Z; 0 0 0: automatic",
                               size=3, default=(0, 0, 0), min=0, max=128)
    density: FloatProperty(name="Density", description="[kg/m^3]", default=1000.0, min=1e-6)
    young: FloatProperty(name="Young's modulus", description="[Pa]", default=1e9, min=1.0)
    poisson: FloatProperty(name="Poisson's ratio", default=0.3, min=-0.99, max=0.49)
    friction: FloatProperty(name="Friction", default=0.5, min=0.0)
    restitution: FloatProperty(name="Restitution", default=0.2, min=0.0, max=1.0)
    rolling_resistance: FloatProperty(name="Rolling resistance", description="Lever arm [m]", default=0.0,
                                      min=0.0, precision=5)
    damping_ratio: FloatProperty(name="Modal damping", description="Damping ratio of every mode",
                                 default=0.01, min=0.0, precision=3)
    velocity: FloatVectorProperty(name="Velocity", description="Initial velocity, world [m/s]", size=3,
                                  unit="VELOCITY")
    angular_velocity: FloatVectorProperty(name="Angular velocity", description="Initial, world [rad/s]",
                                          size=3)


class SupermodalWorld(bpy.types.PropertyGroup):
    dt: FloatProperty(name="Step", description="Fixed step [s]", default=0.002, min=1e-6, max=1.0,
                      precision=5, step=0.01)
    substeps: IntProperty(name="Substeps", default=1, min=1, max=1000)
    duration: FloatProperty(name="Duration", description="Simulated time to bake [s]", default=2.0,
                            min=1e-3, unit="TIME_ABSOLUTE")
    accuracy: FloatProperty(name="Accuracy", description="Displacement auto bodies may leave out [m]",
                            default=0.001, min=1e-9, unit="LENGTH", precision=4)
    contact_solver: EnumProperty(name="Contact", default="soft", items=[
        ("soft", "Soft", "Implicit soft constraints, stable at any step (the engine's default)"),
        ("penalty", "Penalty", "The paper's explicit springs (small steps)"),
    ])
    bake_seconds: FloatProperty(name="Last bake", description="Wall time of the last bake [s]")


CLASSES = (SupermodalBody, SupermodalWorld)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Object.supermodal = PointerProperty(type=SupermodalBody)
    bpy.types.Scene.supermodal = PointerProperty(type=SupermodalWorld)


def unregister():
    del bpy.types.Scene.supermodal
    del bpy.types.Object.supermodal
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
