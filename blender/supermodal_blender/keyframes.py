# SPDX-License-Identifier: MIT
"""Writing one baked body onto its object: location and rotation keyframes, one shape key per mode with
its value keyframed, and the run's poses in double precision (keyframes hold single precision)."""
import bpy
import numpy as np

from . import coords, scene_json

GROUP = "supermodal"
MODE_KEY = "supermodal mode "  # shape-key name prefix, then the mode's number from 1
RECORD = "supermodal_bake"     # the object's custom property with the double-precision record


def _fcurve(action, path, index, frames, values):
    fc = action.fcurves.new(path, index=index, action_group=GROUP)
    fc.keyframe_points.add(len(frames))
    co = np.empty(2 * len(frames))
    co[0::2] = frames
    co[1::2] = values
    fc.keyframe_points.foreach_set("co", co)
    for point in fc.keyframe_points:
        point.interpolation = "LINEAR"  # samples of a simulation: no overshoot between them
    fc.update()
    return fc


def _new_action(owner, name):
    """A fresh action on `owner` (an object or a shape-key block), replacing one an earlier bake made; an
    action of the user's is kept in the file (fake user), only unassigned."""
    owner.animation_data_create()
    old = owner.animation_data.action
    if old is not None and old.get(GROUP):
        bpy.data.actions.remove(old)
    elif old is not None:
        old.use_fake_user = True
    action = bpy.data.actions.new(name)
    action[GROUP] = True
    owner.animation_data.action = action
    return action


def write_motion(obj, frames, locations, rotations):
    obj.rotation_mode = "QUATERNION"
    action = _new_action(obj, f"{obj.name} supermodal")
    for axis in range(3):
        _fcurve(action, "location", axis, frames, locations[:, axis])
    for axis in range(4):
        _fcurve(action, "rotation_quaternion", axis, frames, rotations[:, axis])


def clear_mode_keys(obj):
    """Removes an earlier bake's mode shape keys and their action (and the basis when nothing else is
    left)."""
    keys = obj.data.shape_keys if obj.type == "MESH" else None
    if keys is None:
        return
    if keys.animation_data is not None and keys.animation_data.action is not None \
            and keys.animation_data.action.get(GROUP):
        bpy.data.actions.remove(keys.animation_data.action)
    for block in [b for b in keys.key_blocks if b.name.startswith(MODE_KEY)]:
        obj.shape_key_remove(block)
    if len(keys.key_blocks) == 1:
        obj.shape_key_remove(keys.key_blocks[0])


def clear_body(obj):
    """Removes what a bake wrote on an object: its action, mode shape keys and record."""
    data = obj.animation_data
    if data is not None and data.action is not None and data.action.get(GROUP):
        bpy.data.actions.remove(data.action)
    clear_mode_keys(obj)
    if RECORD in obj:
        del obj[RECORD]


def rest_vertices(obj):
    """The mesh's rest vertices [local units], from the basis shape key when there is one."""
    mesh = obj.data
    source = mesh.shape_keys.reference_key.data if mesh.shape_keys else mesh.vertices
    co = np.empty(3 * len(mesh.vertices), dtype=np.float32)
    source.foreach_get("co", co)
    return co.reshape(-1, 3).astype(float)


def mode_displacements(obj, body):
    """(r, n, 3) displacement of each vertex per unit amplitude [local units]."""
    _, _, scale = scene_json.object_transform(obj)
    offset_position, offset_orientation = scene_json.shape_offset(obj)
    rotation = coords.q_matrix(coords.q_normalize(offset_orientation))
    shape_points = (rest_vertices(obj) * scale - offset_position) @ rotation
    return (body.mode_shapes(shape_points) @ rotation.T) / scale


def write_modes(obj, frames, amplitudes, shapes):
    """One shape key per mode, at the largest amplitude of the run (values then stay in [-1, 1])."""
    clear_mode_keys(obj)
    if obj.data.shape_keys is None:
        obj.shape_key_add(name="Basis", from_mix=False)
    basis = rest_vertices(obj)
    scales = np.abs(amplitudes).max(axis=0)
    scales[scales == 0.0] = 1.0
    action = _new_action(obj.data.shape_keys, f"{obj.name} supermodal modes")
    for k in range(shapes.shape[0]):
        block = obj.shape_key_add(name=f"{MODE_KEY}{k + 1}", from_mix=False)
        block.slider_min = -1.0
        block.data.foreach_set("co", (basis + scales[k] * shapes[k]).astype(np.float32).ravel())
        _fcurve(action, f'key_blocks["{block.name}"].value', 0, frames, amplitudes[:, k] / scales[k])
    return scales


def write_body(obj, body, frames, steps, positions, orientations, amplitudes, start):
    """Keys a body's run on its object; `start` is its (location, rotation) before the bake, keyed as is
    at the first frame (the run's first pose converted back would differ in the last bits)."""
    offset = scene_json.shape_offset(obj)
    poses = [coords.object_pose(p, q, *offset) for p, q in zip(positions, orientations)]
    locations = np.array([p[0] for p in poses])
    locations[0] = start[0]
    rotations = coords.continuous([start[1]] + [p[1] for p in poses[1:]])
    write_motion(obj, frames, locations, rotations)
    record = {"frames": list(frames), "steps": list(steps), "position": positions.ravel().tolist(),
              "orientation": orientations.ravel().tolist()}
    if amplitudes.shape[1] > 0 and obj.type == "MESH":
        scales = write_modes(obj, frames, amplitudes, mode_displacements(obj, body))
        record["amplitudes"] = amplitudes.ravel().tolist()
        record["mode_scale"] = scales.tolist()
    else:
        clear_mode_keys(obj)  # a body that was modal in an earlier bake
    obj[RECORD] = record
