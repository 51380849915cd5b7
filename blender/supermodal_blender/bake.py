# SPDX-License-Identifier: MIT
"""Simulate & bake: the scene file stepped by the engine, sampled once per frame, then written as
keyframes (rigid motion) and one shape key per mode (deformation). Nothing is written until the whole
run has been stepped, so a cancelled or failed bake leaves the scene as it was."""
import math
import time

import numpy as np

from . import keyframes, scene_json
from .errors import SceneBuildError

STATE_HASH = "supermodal_state_hash"  # the scene's custom property with the last bake's end state hash


def sample_steps(total_steps, dt, fps):
    """The step each frame shows: frame k at the step nearest k / fps, up to the run's last step."""
    frames = math.floor(total_steps * dt * fps + 1e-9)
    return [min(total_steps, round(k / (fps * dt))) for k in range(frames + 1)]


def run_steps(duration, dt):
    """Steps of a run of `duration`, as `supermodal run` counts them."""
    return math.ceil(duration / dt - 1e-9)


def scene_error(doc, error):
    """A SceneError from the engine as a SceneBuildError naming the Blender object it is about."""
    parts = error.pointer.split("/")
    name = doc.get("comment", "scene")
    if len(parts) > 2 and parts[1] in ("bodies", "constraints") and parts[2].isdigit():
        entries = doc.get(parts[1], [])
        if int(parts[2]) < len(entries):
            name = entries[int(parts[2])].get("name", name)
    return SceneBuildError(name, str(error))  # the message holds the pointer


class Bake:
    """One bake in progress: build with the scene, call advance() until done, then write()."""

    def __init__(self, scene, sm):
        self.scene = scene
        self.doc = scene_json.scene_dict(scene)
        try:
            self.world = sm.load_scene(self.doc)
        except sm.SceneError as e:
            raise scene_error(self.doc, e) from None
        self.names = [b["name"] for b in self.doc["bodies"]]
        # The start frame keeps the transforms as they are stored (see scene_json.stored_rotation).
        self.start = {o.name: (list(o.location), scene_json.stored_rotation(o))
                      for o in scene_json.body_objects(scene)}
        self.total = run_steps(self.doc["settings"]["duration"], self.world.dt)
        fps = scene.render.fps / scene.render.fps_base
        self.steps = sample_steps(self.total, self.world.dt, fps)
        self.bodies = self.world.bodies
        self.positions, self.orientations = [], []
        self.amplitudes = {b.name: [] for b in self.bodies if b.mode_count > 0}
        self.stepped_seconds = 0.0
        self._record()

    @property
    def done(self):
        return len(self.positions) == len(self.steps)

    @property
    def progress(self):
        return self.world.step_count

    def _record(self):
        self.positions.append(self.world.positions())
        self.orientations.append(self.world.orientations())
        for b in self.bodies:
            if b.name in self.amplitudes:
                self.amplitudes[b.name].append(np.array(b.modal_amplitudes))

    def advance(self, seconds=math.inf):
        """Steps frame by frame for about `seconds` of wall time (at least one frame)."""
        start = time.perf_counter()
        while not self.done:
            count = self.steps[len(self.positions)] - self.world.step_count
            if count > 0:
                self.world.step(count)
            self._record()
            if time.perf_counter() - start >= seconds:
                break
        self.stepped_seconds += time.perf_counter() - start

    def write(self):
        """Keyframes, shape keys and the double-precision record on each moving body's object."""
        frames = [self.scene.frame_start + k for k in range(len(self.steps))]
        # The run's end state, as `supermodal run` prints it: equal hashes, equal runs.
        self.scene[STATE_HASH] = f"0x{self.world.state_hash():016x}"
        positions = np.array(self.positions)
        orientations = np.array(self.orientations)
        for i, name in enumerate(self.names):
            entry = self.doc["bodies"][i]
            obj = self.scene.objects[name]
            if entry["shape"]["type"] == "plane" or entry.get("motion") == "static":
                keyframes.clear_body(obj)  # it does not move: an earlier bake's keys would move it
                continue
            body = self.bodies[i]
            amplitudes = np.array(self.amplitudes.get(name, np.zeros((len(frames), 0))))
            keyframes.write_body(obj, body, frames, self.steps, positions[:, i], orientations[:, i], amplitudes,
                                 self.start[name])
