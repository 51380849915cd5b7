# Body.mode_shapes: the per-mode displacement field at given points, against the GLB export's morph
# targets (the same field, computed by the exporter's own loop over the lattice weights).
import json
import struct

import numpy as np
import pytest

import supermodal as sm


def glb_parts(path):
    """The JSON and binary chunks of a GLB file."""
    data = path.read_bytes()
    json_length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + json_length])
    bin_start = 20 + json_length + 8
    return doc, data[bin_start:]


def accessor(doc, blob, index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    assert a["componentType"] == 5126 and a["type"] == "VEC3"  # float32 triples, tightly packed
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    return np.frombuffer(blob, dtype="<f4", count=3 * a["count"], offset=start).reshape(-1, 3).astype(float)


def test_mode_shapes_equal_the_exported_morph_targets(tmp_path, scenes):
    w = sm.load_scene(scenes / "samples" / "ball_on_board.json")
    out = tmp_path / "board.glb"
    w.export_glb(out, seconds=0.01, fps=100)
    doc, blob = glb_parts(out)
    mesh = next(doc["meshes"][n["mesh"]] for n in doc["nodes"] if n.get("name") == "board")
    primitive = mesh["primitives"][0]
    rest = accessor(doc, blob, primitive["attributes"]["POSITION"])
    targets = np.array([accessor(doc, blob, t["POSITION"]) for t in primitive["targets"]])
    shapes = w.find_body("board").mode_shapes(rest)
    assert shapes.shape == targets.shape == (8, len(rest), 3)
    # Both in single precision at the end (the GLB's floats, and its positions as our input): agree to
    # 1e-5 of the largest displacement, far below the 1e-1 a wrong mode or axis would give.
    assert np.abs(shapes - targets).max() <= 1e-5 * np.abs(targets).max()


def test_mode_shapes_of_a_rigid_body_are_empty(scenes):
    w = sm.load_scene(scenes / "samples" / "ball_on_board.json")
    assert w.find_body("ball").mode_shapes(np.zeros((5, 3))).shape == (0, 5, 3)


def test_mode_shapes_name_bad_points(scenes):
    board = sm.load_scene(scenes / "samples" / "ball_on_board.json").find_body("board")
    with pytest.raises(sm.ArgumentTypeError) as e:
        board.mode_shapes(np.zeros((4, 2)))
    assert e.value.argument == "points"
    with pytest.raises(sm.ArgumentError) as e:
        board.mode_shapes([[0.0, float("nan"), 0.0]])
    assert e.value.argument == "points" and "row 0" in str(e.value)
