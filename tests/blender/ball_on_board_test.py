# SPDX-License-Identifier: MIT
"""The Blender add-on end to end, run inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python ball_on_board_test.py -- \
        --zip ADDON.zip --module-dir BUILD/python --cli BUILD/tools/supermodal --out DIR [--render PNG]

Installs the add-on from its zip, builds the ball-on-board scene (samples/ball_on_board.json) from Blender
objects, bakes 2 s at 24 fps and checks the keyframes, the mode shape keys, where the ball ends, the
board's ringing, and that `supermodal run` on the exported scene gives the same poses and state hash.
Any failed check raises, and Blender exits with status 1."""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import bmesh
import bpy
import numpy as np


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    for name in ("--zip", "--module-dir", "--cli", "--out"):
        parser.add_argument(name, required=True)
    parser.add_argument("--render", help="also render a frame to this PNG (docs/images)")
    parser.add_argument("--render-frame", type=int, default=25)
    parser.add_argument("--exaggerate", type=float, default=1.0, help="draw the modes this many times larger")
    return parser.parse_args(argv)


def check(ok, what):
    if not ok:
        raise AssertionError(what)
    print(f"ok: {what}")


def install_addon(args):
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.preferences.addon_install(filepath=args.zip, overwrite=True)
    bpy.ops.preferences.addon_enable(module="supermodal_blender")
    bpy.context.preferences.addons["supermodal_blender"].preferences.module_dir = args.module_dir
    check(hasattr(bpy.types, "SUPERMODAL_PT_body") and hasattr(bpy.ops.supermodal, "bake"),
          "the add-on installs from its zip and registers its panel and operators")


def box_mesh(name, cuts):
    """A cube [-1, 1]^3 with `cuts` cuts per edge (the object's scale makes it a box)."""
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=2.0)
    bmesh.ops.subdivide_edges(bm, edges=bm.edges[:], cuts=cuts, use_grid_fill=True)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def add_object(name, mesh, location, scale=(1.0, 1.0, 1.0)):
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    obj.location = location
    obj.scale = scale
    return obj


def set_material(body, density, young, poisson, friction, restitution, rolling=0.0, damping=0.01):
    body.density, body.young, body.poisson = density, young, poisson
    body.friction, body.restitution, body.rolling_resistance, body.damping_ratio = friction, restitution, rolling, damping


WOOD = dict(density=450, young=11e9, poisson=0.3, friction=0.5, restitution=0.3, rolling=0.0002, damping=0.02)
STEEL = dict(density=7850, young=200e9, poisson=0.29, friction=0.4, restitution=0.6)


def build_scene():
    """samples/ball_on_board.json in Blender's frame (Z up): engine (x, y, z) is Blender (x, -z, y)."""
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = 24, 1.0
    scene.frame_start, scene.frame_end = 1, 49
    world = scene.supermodal
    world.dt, world.substeps, world.duration = 0.0005, 1, 2.0
    bpy.ops.mesh.primitive_plane_add(size=2.0)
    floor = bpy.context.active_object
    floor.name = "floor"
    floor.supermodal.enabled, floor.supermodal.shape = True, "PLANE"
    for name, x in (("support_left", -0.4), ("support_right", 0.4)):
        support = add_object(name, box_mesh(name, 3), (x, 0.0, 0.05), (0.04, 0.1, 0.05))
        body = support.supermodal
        body.enabled, body.motion, body.radii, body.exponents = True, "static", (0.04, 0.1, 0.05), (0.2, 0.2)
        set_material(body, **WOOD)
    board = add_object("board", box_mesh("board", 15), (0.0, 0.0, 0.119), (0.5, 0.0445, 0.019))
    body = board.supermodal
    body.enabled, body.radii, body.exponents = True, (0.5, 0.0445, 0.019), (0.1, 0.1)
    body.dynamics, body.modes, body.lattice = "modal", 8, (16, 2, 1)
    set_material(body, **WOOD)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.025, location=(0.1, 0.0, 0.4), segments=32, ring_count=16)
    ball = bpy.context.active_object
    ball.name = "ball"
    ball.supermodal.enabled, ball.supermodal.velocity = True, (0.0, 0.0, -3.0)
    set_material(ball.supermodal, **STEEL)
    return scene


def fit_ball(scene):
    ball = scene.objects["ball"]
    bpy.context.view_layer.objects.active = ball
    check(bpy.ops.supermodal.fit() == {"FINISHED"}, "Fit to mesh runs on the ball's UV sphere")
    body = ball.supermodal
    # The sphere's vertices lie on r = 0.025 m: the fit finds it to well under its 32-segment faceting.
    check(body.source == "FIT" and max(abs(r - 0.025) for r in body.fit_radii) < 0.025 * 0.01,
          f"fitted radii {tuple(body.fit_radii)} within 1% of 0.025 m")
    check(max(abs(e - 1.0) for e in body.fit_exponents) < 0.1, f"fitted exponents {tuple(body.fit_exponents)} ~ 1")
    preview = scene.objects.get("ball supermodal fit")
    check(preview is not None and preview.display_type == "WIRE" and preview.parent == ball,
          "the fit shows as a wire preview parented to the ball")


class Layout:
    """Stands in for a panel's layout (background mode draws no interface): every property and operator a
    panel names must exist."""

    def __init__(self):
        self.names = []

    def prop(self, data, name, **_):
        assert name in data.bl_rna.properties, f"{data} has no property {name}"
        self.names.append(name)

    def operator(self, idname, **_):
        category, name = idname.split(".")
        assert hasattr(getattr(bpy.ops, category), name), f"no operator {idname}"
        self.names.append(idname)

    def label(self, **_):
        pass

    def column(self, **_):
        return self


def check_panels_draw(scene):
    from types import SimpleNamespace
    for obj in (scene.objects[n] for n in ("floor", "support_left", "board", "ball")):
        bpy.context.view_layer.objects.active = obj
        layout = Layout()
        for panel in (bpy.types.SUPERMODAL_PT_body, bpy.types.SUPERMODAL_PT_material, bpy.types.SUPERMODAL_PT_world,
                      bpy.types.SUPERMODAL_PT_bake):
            panel.draw(SimpleNamespace(layout=layout), bpy.context)
        check(len(layout.names) > 10, f"the panels draw for {obj.name} ({len(layout.names)} settings and buttons)")


def check_cancel_writes_nothing(scene):
    """A bake stopped before its end (what Esc does) leaves no keyframe or shape key behind."""
    from supermodal_blender import bake, engine
    partial = bake.Bake(scene, engine.load(bpy.context))
    partial.advance(0.0)
    check(not partial.done and partial.progress > 0, "a bake advances frame by frame")
    del partial
    board = scene.objects["board"]
    check(board.animation_data is None and board.data.shape_keys is None,
          "a bake that is not finished writes nothing")


def check_bad_input(scene, out):
    """Refused by the add-on (a zero lattice count) or by the engine (more modes than the lattice has):
    the bake and the export name the board, change nothing and write no file."""
    board = scene.objects["board"].supermodal
    exported = os.path.join(out, "refused.json")
    for lattice, modes, expected in (((16, 0, 1), 8, "lattice"), ((1, 1, 1), 200, "/dynamics")):
        board.lattice, board.modes = lattice, modes
        for call in (bpy.ops.supermodal.bake, lambda: bpy.ops.supermodal.export_scene(filepath=exported)):
            try:
                call()
                raise AssertionError(f"lattice {lattice} with {modes} modes was accepted")
            except RuntimeError as e:
                check("board" in str(e) and expected in str(e), f"refused naming the board: {e}")
        check(scene.objects["board"].animation_data is None and not os.path.exists(exported),
              "the refused bake and export changed nothing and wrote no file")
    board.lattice, board.modes = (16, 2, 1), 8


def fcurve_values(action, path, index):
    fc = action.fcurves.find(path, index=index)
    co = np.empty(2 * len(fc.keyframe_points), dtype=np.float32)
    fc.keyframe_points.foreach_get("co", co)
    return co[1::2].astype(float), co[0::2].astype(float)


def check_keys(scene):
    frames = len(range(scene.frame_start, scene.frame_end + 1))
    for name in ("ball", "board"):
        action = scene.objects[name].animation_data.action
        count = {(fc.data_path, fc.array_index): len(fc.keyframe_points) for fc in action.fcurves}
        check(len(count) == 7 and set(count.values()) == {frames},
              f"{name}: location and rotation keyframed at each of {frames} frames")
    for name in ("support_left", "support_right", "floor"):
        check(scene.objects[name].animation_data is None, f"{name} (static) has no keyframes")
    keys = scene.objects["board"].data.shape_keys
    modes = [b for b in keys.key_blocks if b.name.startswith("supermodal mode ")]
    check(len(modes) == 8 and len(keys.animation_data.action.fcurves) == 8, "board: 8 mode shape keys, keyed")
    check(scene.objects["ball"].data.shape_keys is None, "the rigid ball has no shape keys")


def check_ball_on_board(scene):
    ball = scene.objects["ball"].animation_data.action
    z, _ = fcurve_values(ball, "location", 2)
    x, _ = fcurve_values(ball, "location", 0)
    top = 0.119 + 0.019 + 0.025  # board centre + half thickness + ball radius [m]
    # Within 3 mm: the penalty contact's overlap and the board's sag under the ball are each about 1 mm.
    check(abs(z[-1] - top) < 0.003 and abs(x[-1]) < 0.5, f"the ball ends on the board: z {z[-1]:.4f} m, top {top} m")
    check(abs(z[-1] - z[-2]) < 1e-3, "the ball is at rest on the board at the end")


def check_ringing(scene):
    board = scene.objects["board"]
    values = np.array([fcurve_values(board.data.shape_keys.animation_data.action,
                                     f'key_blocks["supermodal mode {k + 1}"].value', 0)[0] for k in range(8)])
    q = values * np.array(board["supermodal_bake"]["mode_scale"])[:, None]  # amplitudes [sqrt(kg) m]
    first = q[0]
    settled = first[-12:]  # the last half second
    swing = np.abs(first - settled.mean())
    crossings = int(np.sum(np.diff(np.sign(first - settled.mean())) != 0))
    print("mode 1 amplitude per frame:", np.array2string(first, precision=6, max_line_width=200))
    check(crossings >= 4, f"mode 1 rings: its amplitude crosses its rest value {crossings} times")
    check(swing[-12:].max() < 0.1 * swing.max(), f"mode 1 decays: last 0.5 s swing {swing[-12:].max():.3g} "
          f"under a tenth of the largest {swing.max():.3g}")
    return q


def read_trace(path):
    rows = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            rows[(int(row["step"]), row["body"])] = [float(row[k]) for k in
                                                       ("px", "py", "pz", "qw", "qx", "qy", "qz")]
    return rows


def check_schema(path):
    """The exported file against docs/scene.schema.json (python3-jsonschema, Debian's, on Blender's path)."""
    import jsonschema
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "..", "..", "docs", "scene.schema.json")) as f:
        schema = json.load(f)
    with open(path) as f:
        errors = [e.message for e in jsonschema.Draft7Validator(schema).iter_errors(json.load(f))]
    check(not errors, f"the exported scene validates against docs/scene.schema.json {errors[:3]}")


def check_against_cli(scene, args):
    exported = os.path.join(args.out, "ball_on_board_from_blender.json")
    check(bpy.ops.supermodal.export_scene(filepath=exported) == {"FINISHED"}, "Export scene writes the JSON")
    check_schema(exported)
    trace, summary = os.path.join(args.out, "trace.csv"), os.path.join(args.out, "summary.json")
    subprocess.run([args.cli, "run", exported, "--csv", trace, "--csv-every", "1", "--json", summary, "--quiet"],
                   check=True)
    rows = read_trace(trace)
    with open(summary) as f:
        cli = json.load(f)
    check(cli["state_hash"] == scene["supermodal_state_hash"],
          f"the bake and `supermodal run` end in the same state (hash {cli['state_hash']})")
    worst_double = worst_key = 0.0
    for name in ("ball", "board"):
        obj = scene.objects[name]
        record = obj["supermodal_bake"]
        position = np.array(record["position"]).reshape(-1, 3)
        orientation = np.array(record["orientation"]).reshape(-1, 4)
        for k, step in enumerate(record["steps"]):
            want = np.array(rows[(step, name)])
            worst_double = max(worst_double, np.abs(np.concatenate([position[k], orientation[k]]) - want).max())
        # The keyframes (single precision) against the run's positions in Blender's frame.
        action = obj.animation_data.action
        for axis, engine_axis, sign in ((0, 0, 1.0), (1, 2, -1.0), (2, 1, 1.0)):
            values, _ = fcurve_values(action, "location", axis)
            want = np.array([sign * rows[(s, name)][engine_axis] for s in record["steps"]])
            worst_key = max(worst_key, np.abs(values - want).max())
    check(worst_double <= 1e-9, f"baked poses equal `supermodal run`'s to 1e-9 (largest difference {worst_double:.3g})")
    # Keyframes are single precision: positions under 1 m round by at most 6e-8 m.
    check(worst_key <= 1e-7, f"location keyframes equal the run's to single precision ({worst_key:.3g} m)")


def check_rebake_and_clear(scene):
    """A second bake replaces the first (same run, no doubled keys or actions); Clear bake removes it all."""
    first = scene["supermodal_state_hash"]
    actions = len(bpy.data.actions)
    check(bpy.ops.supermodal.bake() == {"FINISHED"} and scene["supermodal_state_hash"] == first,
          "a second bake from the baked scene runs the same (same end state hash)")
    keys = scene.objects["board"].data.shape_keys.key_blocks
    check(len(keys) == 9 and len(bpy.data.actions) == actions, "it replaces the keys and actions, not adds")
    check(bpy.ops.supermodal.clear_bake() == {"FINISHED"}, "Clear bake runs")
    for name in ("ball", "board"):
        obj = scene.objects[name]
        check((obj.animation_data is None or obj.animation_data.action is None)
              and (obj.type != "MESH" or obj.data.shape_keys is None) and "supermodal_bake" not in obj,
              f"{name}: no keyframes, mode shape keys or record left")


def check_constraints(scene, sm):
    """Blender's Point, Hinge and Fixed constraints in the scene file, and the engine accepts them."""
    from supermodal_blender import scene_json
    if scene.rigidbody_world is None:
        bpy.ops.rigidbody.world_add()  # Blender keeps constraints in its rigid-body world
    pieces = []
    for i, kind in enumerate(("POINT", "HINGE", "FIXED")):
        for end in "ab":
            bpy.ops.mesh.primitive_uv_sphere_add(radius=0.05, location=(2.0 + i, 0.2 * (end == "b"), 1.0))
            obj = bpy.context.active_object
            obj.name = f"{kind.lower()}_{end}"
            obj.supermodal.enabled, obj.supermodal.radii = True, (0.05, 0.05, 0.05)
            pieces.append(obj)
        empty = bpy.data.objects.new(f"joint_{kind.lower()}", None)
        scene.collection.objects.link(empty)
        empty.location = (2.0 + i, 0.1, 1.0)
        empty.rotation_euler = (math.pi / 2, 0.0, 0.0)  # local Z along world -Y: the hinge axis
        bpy.context.view_layer.objects.active = empty
        bpy.ops.rigidbody.constraint_add(type=kind)
        empty.rigid_body_constraint.object1 = scene.objects[f"{kind.lower()}_a"]
        empty.rigid_body_constraint.object2 = scene.objects[f"{kind.lower()}_b"]
    doc = scene_json.scene_dict(scene)
    joints = {c["name"]: c for c in doc["constraints"]}
    check([joints[f"joint_{k}"]["type"] for k in ("point", "hinge", "fixed")] == ["point", "point", "weld"],
          "Point, Hinge, Fixed become point, point (hinge), weld")
    hinge = joints["joint_hinge"]
    # Unrotated bodies: shape frame = Blender axes; the pivot 0.1 m along +Y from a, -Y from b.
    check(np.allclose(hinge["anchor_a"], [0, 0.1, 0], atol=1e-6) and np.allclose(hinge["anchor_b"], [0, -0.1, 0], atol=1e-6),
          f"anchors at the pivot in each body's frame: {hinge['anchor_a']}, {hinge['anchor_b']}")
    check(np.allclose(hinge["axis_a"], [0, -1, 0], atol=1e-6) and hinge["swing_limit"] == 0.0,
          f"the hinge axis is the constraint's local Z in a's frame: {hinge['axis_a']}")
    world = sm.load_scene(doc)
    check(len(world.constraints) == 3, "the engine builds the three constraints")


def exaggerate(obj, factor):
    """Scales the mode shape keys' displacements by `factor`, for a picture (millimetres on a metre)."""
    keys = obj.data.shape_keys.key_blocks
    basis = np.empty(3 * len(obj.data.vertices), dtype=np.float32)
    keys[0].data.foreach_get("co", basis)
    for block in keys[1:]:
        co = np.empty_like(basis)
        block.data.foreach_get("co", co)
        block.data.foreach_set("co", basis + factor * (co - basis))


def render(scene, path, frame, factor):
    """Workbench (no GPU needed) at `frame`, objects in flat colours, from the front and a little above;
    the board's modes drawn `factor` times their size."""
    exaggerate(scene.objects["board"], factor)
    scene.frame_set(frame)
    cam = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(cam)
    cam.location = (0.3, -1.6, 0.55)
    cam.rotation_euler = (math.radians(76), 0.0, math.radians(10.6))  # at (0, 0, 0.15)
    cam.data.lens = 35
    scene.camera = cam
    colors = {"floor": (0.55, 0.55, 0.58, 1), "board": (0.80, 0.60, 0.35, 1), "ball": (0.25, 0.35, 0.75, 1),
              "support_left": (0.45, 0.30, 0.20, 1), "support_right": (0.45, 0.30, 0.20, 1)}
    for name, color in colors.items():
        scene.objects[name].color = color
    scene.objects["ball supermodal fit"].hide_render = True
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "STUDIO"
    scene.display.shading.color_type = "OBJECT"
    scene.display.shading.show_shadows = True
    scene.display.shading.show_cavity = True
    scene.render.resolution_x, scene.render.resolution_y = 960, 540
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.compression = 100
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print("rendered", path, "at frame", frame)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    install_addon(args)
    from supermodal_blender import engine
    sm = engine.load(bpy.context)
    scene = build_scene()
    fit_ball(scene)
    check_panels_draw(scene)
    check_cancel_writes_nothing(scene)
    check_bad_input(scene, args.out)
    before = os.path.join(args.out, "unbaked.blend")
    bpy.ops.wm.save_as_mainfile(filepath=before, copy=True)
    start = time.perf_counter()
    check(bpy.ops.supermodal.bake() == {"FINISHED"}, "Simulate & bake finishes")
    bake_seconds = time.perf_counter() - start
    baked = os.path.join(args.out, "baked.blend")
    bpy.ops.wm.save_as_mainfile(filepath=baked, copy=True)
    print(f"bake: {bake_seconds:.2f} s for 2 s at 24 fps (4000 steps), board of "
          f"{len(scene.objects['board'].data.vertices)} vertices; .blend {os.path.getsize(before)} bytes "
          f"before, {os.path.getsize(baked)} after")
    check_keys(scene)
    check_ball_on_board(scene)
    check_ringing(scene)
    check_against_cli(scene, args)
    if args.render:
        render(scene, args.render, args.render_frame, args.exaggerate)
    check_rebake_and_clear(scene)
    check_constraints(scene, sm)
    print("all checks passed")


if __name__ == "__main__":  # tests/blender/bake_ui_test.py imports the scene from here
    main()
