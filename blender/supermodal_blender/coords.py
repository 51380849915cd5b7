# SPDX-License-Identifier: MIT
"""Blender's frame (Z up) and the engine's (Y up), in double precision.

mathutils works in single precision, so every pose that reaches the engine or comes back from it is
converted here with plain floats and numpy. The engine's world is Blender's rotated by -90 degrees
about X: engine (x, y, z) = Blender (x, z, -y). A body's shape frame is its object's local frame
(radii along the object's X, Y, Z; Z is the superquadric's polar axis) moved by the shape's offset.
"""
import math

import numpy as np

# Engine-from-Blender rotation as a matrix and as a quaternion (w, x, y, z).
ENGINE_FROM_BLENDER = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
Q_ENGINE_FROM_BLENDER = np.array([math.sqrt(0.5), -math.sqrt(0.5), 0.0, 0.0])


def to_engine(v):
    """A Blender vector (point or direction) in the engine's frame."""
    return ENGINE_FROM_BLENDER @ np.asarray(v, dtype=float)


def to_blender(v):
    """An engine vector (point or direction) in Blender's frame; rows of an (n, 3) array too."""
    return np.asarray(v, dtype=float) @ ENGINE_FROM_BLENDER


def q_mul(a, b):
    """Hamilton product of two quaternions (w, x, y, z)."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


def q_conj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


def q_normalize(q):
    q = np.asarray(q, dtype=float)
    return q / math.sqrt(float(q @ q))


def q_matrix(q):
    """The rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def body_pose(location, rotation, offset_position, offset_orientation):
    """Engine pose (position, orientation) of a body whose object sits at `location` with `rotation`
    (Blender world, unit quaternion) and whose shape frame is offset by (offset_position,
    offset_orientation) in the object's scaled local frame."""
    q_object = q_normalize(rotation)
    q_offset = q_normalize(offset_orientation)
    world = q_matrix(q_object) @ np.asarray(offset_position, dtype=float) + np.asarray(location, dtype=float)
    return to_engine(world), q_normalize(q_mul(Q_ENGINE_FROM_BLENDER, q_mul(q_object, q_offset)))


def object_pose(position, orientation, offset_position, offset_orientation):
    """The inverse of body_pose: Blender (location, rotation) of the object of a body at an engine
    pose."""
    q_object = q_mul(q_conj(Q_ENGINE_FROM_BLENDER), q_mul(orientation, q_conj(q_normalize(offset_orientation))))
    location = to_blender(position) - q_matrix(q_object) @ np.asarray(offset_position, dtype=float)
    return location, q_object


def continuous(quaternions):
    """Flips quaternion signs along a sequence so that neighbours agree (q and -q are one rotation),
    which keeps interpolation between keyframes on the short way."""
    out = np.array(quaternions, dtype=float)
    for i in range(1, len(out)):
        if out[i] @ out[i - 1] < 0.0:
            out[i] = -out[i]
    return out
