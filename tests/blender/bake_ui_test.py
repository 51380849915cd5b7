# SPDX-License-Identifier: MIT
"""Simulate & bake from Blender's interface: the modal operator, cancelled with Esc, then run to its end.
Run in Blender's window under a virtual X server, with simulated input:

    xvfb-run -a blender --factory-startup --enable-event-simulate --python bake_ui_test.py -- \
        --zip ADDON.zip --module-dir BUILD/python --cli unused --out DIR

The operator's modal() is wrapped to record the events it gets and what it answers. The checks run from
timers once the window is up; the process exits 0 when all pass, 1 otherwise."""
import os
import sys
import traceback

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ball_on_board_test as scene_test  # noqa: E402 (the folder goes on the path first)

EVENTS = []  # (event type, modal's answer, steps done) per modal() call


def record_modal():
    from supermodal_blender import operators
    modal = operators.SUPERMODAL_OT_bake.modal

    def recorded(self, context, event):
        answer = modal(self, context, event)
        EVENTS.append((event.type, answer, self._bake.progress))
        return answer
    operators.SUPERMODAL_OT_bake.modal = recorded


def start_bake():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    region = next(r for r in area.regions if r.type == "WINDOW")
    EVENTS.clear()
    with bpy.context.temp_override(window=window, area=area, region=region):
        result = bpy.ops.supermodal.bake("INVOKE_DEFAULT")
    scene_test.check(result == {"RUNNING_MODAL"}, "from the interface the bake runs as a modal operator")


def board_baked():
    board = bpy.context.scene.objects["board"]
    return board.animation_data is not None and board.data.shape_keys is not None


def sliced():
    """Waits for the first timer slice that stepped, then presses Esc."""
    if not any(kind == "TIMER" and steps > 0 for kind, _, steps in EVENTS):
        return 0.1
    window = bpy.context.window_manager.windows[0]
    window.event_simulate(type="ESC", value="PRESS")
    window.event_simulate(type="ESC", value="RELEASE")
    return None


def cancelled():
    if not EVENTS or EVENTS[-1][0] != "ESC":
        return 0.1
    kind, answer, steps = EVENTS[-1]
    scene_test.check(answer == {"CANCELLED"} and 0 < steps, f"Esc cancels the bake after {steps} steps")
    scene_test.check(not board_baked(), "the cancelled bake wrote nothing")
    return None


def finished():
    if not EVENTS or EVENTS[-1][1] == {"RUNNING_MODAL"}:
        return 0.2
    timers = sum(kind == "TIMER" for kind, _, _ in EVENTS)
    scene_test.check(EVENTS[-1][1] == {"FINISHED"} and board_baked(),
                     f"the modal bake finishes after {timers} timer slices and writes keys and shape keys")
    return None


def run(checks):
    """Runs the checks in turn from a timer; a check returning a number is run again that much later."""
    def tick():
        try:
            while checks:
                wait = checks[0]()
                if wait:
                    return wait
                checks.pop(0)
            print("all checks passed")
            os._exit(0)
        except Exception:  # a timer's exception would only be printed: fail the process instead
            traceback.print_exc()
            os._exit(1)
    bpy.app.timers.register(tick, first_interval=1.0)


def main():
    args = scene_test.parse_args()
    os.makedirs(args.out, exist_ok=True)
    scene_test.install_addon(args)
    scene = scene_test.build_scene()
    # A short run: each timer slice waits for the window's redraw, slow in a software-drawn X server.
    scene.supermodal.duration = 0.25
    record_modal()
    run([lambda: start_bake(), sliced, cancelled, lambda: start_bake(), finished])


main()
