# SPDX-License-Identifier: MIT
"""Fit to mesh: the superquadric through a mesh's vertices (supermodal.fit), in the object's scaled
local frame, stored on the object with its offset."""
import numpy as np

from . import keyframes, preview, scene_json


def fit_object(obj, sm):
    """Fits `obj`'s mesh, stores the result in obj.supermodal and shows the wire preview. Returns the
    fit's dict (supermodal.fit)."""
    _, _, scale = scene_json.object_transform(obj)
    points = keyframes.rest_vertices(obj) * scale
    result = sm.fit(points)
    shape = result["body"]
    body = obj.supermodal
    body.fit_radii = shape["radii"]
    body.fit_exponents = (shape["epsilon1"], shape["epsilon2"])
    body.fit_position = shape["position"]
    body.fit_orientation = shape["orientation"]
    body.fit_rms = result["rms_m"]
    body.fitted = True
    body.source = "FIT"
    # The preview shows the stored (single-precision) values: what the scene file will say.
    preview.show_fit(obj, scene_json.typed_list(body.fit_radii), scene_json.typed_list(body.fit_exponents),
                     *scene_json.shape_offset(obj), scale)
    return result


def radii_from_bounds(obj):
    """Parametric radii from the object's bounding box (half its dimensions)."""
    obj.supermodal.radii = [float(d) / 2 for d in obj.dimensions]
    return np.array(obj.supermodal.radii)
