# SPDX-License-Identifier: MIT
"""Blender's rigid-body constraints as supermodal constraints (docs/constraints.md).

Point is a ball joint ("point"); Hinge is a ball joint whose swing away from its axis (the constraint
object's local Z) is limited to zero, twist free; Fixed is a weld. The pivot is the constraint object's
origin. The other Blender types have no counterpart here and are refused by name."""
import numpy as np

from . import coords
from .errors import SceneBuildError

KINDS = {"POINT": "point", "HINGE": "point", "FIXED": "weld"}


def _body_frame(obj_name, bodies):
    body = bodies.get(obj_name)
    if body is None or body["shape"]["type"] != "superquadric":
        return None
    return np.array(body["position"]), coords.q_matrix(body["orientation"])


def _anchor(frame, pivot):
    position, rotation = frame
    return [float(x) for x in rotation.T @ (pivot - position)]


def constraint_json(obj, bodies):
    """One constraint object's entry; SceneBuildError for what cannot be mapped."""
    rbc = obj.rigid_body_constraint
    if rbc.type not in KINDS:
        raise SceneBuildError(obj.name, f"rigid-body constraint type {rbc.type} has no supermodal counterpart "
                              "(Point, Hinge and Fixed have)")
    ends = [rbc.object1, rbc.object2]
    if ends[0] is None or ends[1] is None:
        raise SceneBuildError(obj.name, "the constraint needs both objects set")
    frames = [_body_frame(o.name, bodies) for o in ends]
    for o, f in zip(ends, frames):
        if f is None:
            raise SceneBuildError(obj.name, f"{o.name} is not a supermodal superquadric body")
    world = obj.matrix_world
    pivot = coords.to_engine([float(x) for x in world.translation])
    out = {"type": KINDS[rbc.type], "name": obj.name, "a": ends[0].name, "b": ends[1].name,
           "anchor_a": _anchor(frames[0], pivot), "anchor_b": _anchor(frames[1], pivot),
           "collide_connected": not rbc.disable_collisions}
    if rbc.type == "HINGE":
        axis = coords.to_engine([float(x) for x in world.to_3x3().col[2].normalized()])
        out["axis_a"] = [float(x) for x in frames[0][1].T @ axis]
        out["swing_limit"] = 0.0
    return out


def constraints_json(scene, bodies):
    """Every enabled rigid-body constraint of the scene, by object name."""
    found = sorted((o for o in scene.objects if o.rigid_body_constraint is not None
                    and o.rigid_body_constraint.enabled), key=lambda o: o.name)
    return [constraint_json(o, bodies) for o in found]
