#!/usr/bin/env python3
"""Writes samples/pile.json: N ellipsoids (0.06 x 0.04 x 0.03 m, 1000 kg/m^3) on a jittered grid
(pitch 0.2 m, 10 layers) falling into an open box of static planes, dt = 1/240 s: the issue #5 pile
protocol as a scene file, so the CLI, the soak script and the bench suite can run it.
Usage: bench/make_pile_scene.py [N] > samples/pile.json"""
import json
import math
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 100
layers, pitch, jitter = 10, 0.2, 0.02
per_layer = (n + layers - 1) // layers
side = math.ceil(math.sqrt(per_layer))
half = 0.5 * side * pitch
state = 2026


def rnd():
    """Fixed LCG in [-1, 1): the same pile every time."""
    global state
    state = (state * 1664525 + 1013904223) % 2**32
    return (state >> 8) / 8388608.0 - 1.0


def plane(name, normal, offset):
    return {"name": name, "shape": {"type": "plane", "normal": normal, "offset": offset}}


bodies = [plane("floor", [0, 1, 0], 0.0), plane("wall_x0", [1, 0, 0], -half),
          plane("wall_x1", [-1, 0, 0], -half), plane("wall_z0", [0, 0, 1], -half),
          plane("wall_z1", [0, 0, -1], -half)]
for i in range(n):
    layer, cell = divmod(i, per_layer)
    pos = [-half + pitch * (cell % side + 0.5) + jitter * rnd(),
           pitch * (layer + 0.5) + jitter * rnd(),
           -half + pitch * (cell // side + 0.5) + jitter * rnd()]
    q = [rnd(), rnd(), rnd(), rnd()]
    norm = math.sqrt(sum(c * c for c in q))
    bodies.append({"name": f"e{i}", "material": "plastic",
                   "shape": {"type": "superquadric", "radii": [0.06, 0.04, 0.03]},
                   "position": [round(c, 6) for c in pos],
                   "orientation": [round(c / norm, 9) for c in q]})

head = {"comment": f"Issue #5 pile protocol, {n} ellipsoids falling into an open box; written by "
                   "bench/make_pile_scene.py.",
        "settings": {"dt": 1.0 / 240.0, "duration": 3.0},
        "materials": {"plastic": {"density": 1000, "friction": 0.5}}}
# One body per line keeps the file short and its diffs readable.
lines = [json.dumps(head)[:-1] + ', "bodies": [']
lines += ["  " + json.dumps(b) + ("," if i + 1 < len(bodies) else "") for i, b in enumerate(bodies)]
lines.append("]}")
sys.stdout.write("\n".join(lines) + "\n")
