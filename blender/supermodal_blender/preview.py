# SPDX-License-Identifier: MIT
"""The fitted superquadric drawn as a wire object parented to the body's object, to judge the fit."""
import bpy
import numpy as np

from . import coords

SUFFIX = " supermodal fit"


def _spow(x, e):
    return np.sign(x) * np.abs(x) ** e


def superquadric_mesh(radii, exponents, rings=16, segments=32):
    """Vertices (shape frame) and faces of a superquadric: rings of latitude between two poles."""
    eta = np.linspace(-np.pi / 2, np.pi / 2, rings + 1)[1:-1]
    omega = np.linspace(-np.pi, np.pi, segments, endpoint=False)
    e, w = np.meshgrid(eta, omega, indexing="ij")
    ce = _spow(np.cos(e), exponents[0])
    ring = np.stack([radii[0] * ce * _spow(np.cos(w), exponents[1]), radii[1] * ce * _spow(np.sin(w), exponents[1]),
                     radii[2] * _spow(np.sin(e), exponents[0])], axis=-1).reshape(-1, 3)
    poles = np.array([[0.0, 0.0, -radii[2]], [0.0, 0.0, radii[2]]])
    vertices = np.vstack([ring, poles])
    south, north = len(ring), len(ring) + 1
    faces = []
    for i in range(rings - 2):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            faces.append((a, b, b + segments, a + segments))
    top = (rings - 2) * segments
    for j in range(segments):
        faces.append((south, (j + 1) % segments, j))
        faces.append((north, top + j, top + (j + 1) % segments))
    return vertices, faces


def show_fit(obj, radii, exponents, offset_position, offset_orientation, scale):
    """Creates or replaces the wire preview of `obj`'s fit; returns the preview object."""
    vertices, faces = superquadric_mesh(radii, exponents)
    rotation = coords.q_matrix(coords.q_normalize(offset_orientation))
    local = (vertices @ rotation.T + np.asarray(offset_position)) / np.asarray(scale)
    name = obj.name + SUFFIX
    old = bpy.data.objects.get(name)
    if old is not None:
        old_mesh = old.data
        bpy.data.objects.remove(old)
        bpy.data.meshes.remove(old_mesh)
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(local.tolist(), [], faces)
    preview = bpy.data.objects.new(name, mesh)
    preview.display_type = "WIRE"
    preview.hide_render = True
    preview.hide_select = True
    for collection in obj.users_collection:
        collection.objects.link(preview)
    preview.parent = obj  # identity parent inverse: the vertices are in the object's local frame
    return preview
