# SPDX-License-Identifier: MIT
"""The scene file (docs/scene_format.md) of a Blender scene's supermodal bodies and constraints: the one
description that both the bake and `supermodal run` step, so the two agree bit for bit."""
import numpy as np
from mathutils import Quaternion

from . import constraints, coords
from .errors import SceneBuildError


def typed(x):
    """A single-precision property value as the shortest decimal that reads back to it: 0.0005 typed in
    Blender is written 0.0005, not 0.0005000000237."""
    return float(str(np.float32(x)))


def typed_list(v):
    return [typed(x) for x in v]


def body_objects(scene):
    """The scene's supermodal bodies, by name (the scene file's body order, which fixes the hash)."""
    return sorted((o for o in scene.objects if o.supermodal.enabled), key=lambda o: o.name)


def shape_offset(obj):
    """(position, orientation) of the shape frame in the object's scaled local frame."""
    body = obj.supermodal
    if body.shape == "SUPERQUADRIC" and body.source == "FIT":
        return typed_list(body.fit_position), typed_list(body.fit_orientation)
    return [0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]


def object_transform(obj):
    """(location, rotation quaternion, scale) of an unparented object, as typed."""
    if obj.parent is not None:
        raise SceneBuildError(obj.name, "a body must not have a parent (its keyframes are world poses)")
    scale = typed_list(obj.scale)
    if min(scale) <= 0.0:
        raise SceneBuildError(obj.name, f"scale must be positive, found {tuple(scale)}")
    return typed_list(obj.location), coords.q_normalize(typed_list(stored_rotation(obj))), np.array(scale)


def stored_rotation(obj):
    """The object's rotation as the single-precision quaternion Blender holds or computes for it: the
    bake keys exactly these numbers at the start frame, so a scene exported after a bake is the one the
    bake stepped."""
    if obj.rotation_mode == "QUATERNION":
        return list(obj.rotation_quaternion)
    if obj.rotation_mode == "AXIS_ANGLE":
        angle, *axis = obj.rotation_axis_angle
        return list(Quaternion(axis, angle))
    return list(obj.rotation_euler.to_quaternion())


def shape_json(obj):
    body = obj.supermodal
    if body.shape == "PLANE":
        location, rotation, _ = object_transform(obj)
        normal = coords.to_engine(coords.q_matrix(rotation) @ np.array([0.0, 0.0, 1.0]))
        offset = float(normal @ coords.to_engine(location))
        return {"type": "plane", "normal": [float(x) for x in normal], "offset": offset}
    fitted = body.source == "FIT"
    if fitted and not body.fitted:
        raise SceneBuildError(obj.name, "source is Fitted but the mesh was not fitted yet (Fit to mesh)")
    radii = body.fit_radii if fitted else body.radii
    exponents = body.fit_exponents if fitted else body.exponents
    return {"type": "superquadric", "radii": typed_list(radii), "exponents": typed_list(exponents)}


def material_json(body):
    return {"density": typed(body.density), "young": typed(body.young), "poisson": typed(body.poisson),
            "friction": typed(body.friction), "restitution": typed(body.restitution),
            "rolling_resistance": typed(body.rolling_resistance), "damping_ratio": typed(body.damping_ratio)}


def dynamics_json(body):
    out = {"type": body.dynamics}
    if body.dynamics != "rigid":
        out["modes"] = body.modes
        if any(body.lattice):
            if min(body.lattice) < 1:
                raise ValueError("lattice: give all three cell counts (each >= 1) or 0 0 0 for automatic")
            out["lattice"] = list(body.lattice)
    return out


def body_json(obj):
    body = obj.supermodal
    entry = {"name": obj.name, "material": obj.name, "shape": shape_json(obj)}
    if body.shape == "PLANE":
        entry["motion"] = "static"
        return entry
    location, rotation, _ = object_transform(obj)
    position, orientation = coords.body_pose(location, rotation, *shape_offset(obj))
    entry.update({"position": [float(x) for x in position], "orientation": [float(x) for x in orientation],
                  "motion": body.motion})
    if body.motion != "static":
        entry["velocity"] = [float(x) for x in coords.to_engine(typed_list(body.velocity))]
        entry["angular_velocity"] = [float(x) for x in coords.to_engine(typed_list(body.angular_velocity))]
    if body.motion == "dynamic":
        try:
            entry["dynamics"] = dynamics_json(body)
        except ValueError as e:
            raise SceneBuildError(obj.name, str(e)) from None
    return entry


def settings_json(scene):
    world = scene.supermodal
    gravity = coords.to_engine(typed_list(scene.gravity)) if scene.use_gravity else np.zeros(3)
    return {"dt": typed(world.dt), "substeps": world.substeps, "gravity": [float(x) for x in gravity],
            "duration": typed(world.duration), "contact": {"solver": world.contact_solver},
            "accuracy": {"displacement": typed(world.accuracy)}}


def scene_dict(scene):
    """The scene file of `scene` as a dict; SceneBuildError names the object it cannot describe."""
    objects = body_objects(scene)
    if not objects:
        raise SceneBuildError(scene.name, "no object is a supermodal body (sidebar > supermodal > Body)")
    bodies = [body_json(o) for o in objects]
    out = {"comment": f"Exported from Blender scene '{scene.name}' by the supermodal add-on.",
           "settings": settings_json(scene),
           "materials": {o.name: material_json(o.supermodal) for o in objects},
           "bodies": bodies}
    joints = constraints.constraints_json(scene, {b["name"]: b for b in bodies})
    if joints:
        out["constraints"] = joints
    return out
