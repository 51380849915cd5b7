#!/usr/bin/env python3
"""Writes samples/soft_pile.json: N soft modal balls (radius 0.1 m, rubber-like: E = 1 MPa,
1000 kg/m^3, 6 modes each) on a jittered grid falling into an open box of static planes,
dt = 1/240 s: the modal-heavy scene of the thread benchmark (bench/threads_bench.cpp).
Usage: bench/make_soft_pile_scene.py [N] > samples/soft_pile.json"""
import json
import math
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 64
layers, pitch, jitter = 4, 0.24, 0.02
per_layer = (n + layers - 1) // layers
side = math.ceil(math.sqrt(per_layer))
half = 0.5 * side * pitch
state = 2027


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
           0.15 + pitch * layer + jitter * rnd(),
           -half + pitch * (cell // side + 0.5) + jitter * rnd()]
    bodies.append({"name": f"ball{i}", "material": "rubber",
                   "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]},
                   "position": [round(c, 6) for c in pos],
                   "dynamics": {"type": "modal", "modes": 6}})

head = {"comment": f"{n} soft modal balls falling into an open box (the thread benchmark's modal "
                   "scene); written by bench/make_soft_pile_scene.py.",
        "settings": {"dt": 1.0 / 240.0, "duration": 3.0},
        "materials": {"rubber": {"density": 1000, "young": 1e6, "poisson": 0.45, "friction": 0.6,
                                 "restitution": 0.3, "damping_ratio": 0.05}}}
lines = [json.dumps(head)[:-1] + ', "bodies": [']
lines += ["  " + json.dumps(b) + ("," if i + 1 < len(bodies) else "") for i, b in enumerate(bodies)]
lines.append("]}")
sys.stdout.write("\n".join(lines) + "\n")
