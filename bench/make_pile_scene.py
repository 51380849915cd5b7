#!/usr/bin/env python3
"""Writes a pile scene: bodies on a jittered grid falling into an open box of static planes,
dt = 1/240 s, so the CLI, the soak script and the benchmarks can run it.
- default: samples/pile.json, N ellipsoids (0.06 x 0.04 x 0.03 m, 1000 kg/m^3), pitch 0.2 m, 10 layers
  (the pile benchmark's protocol);
- --soft: samples/soft_pile.json, N soft modal balls (radius 0.1 m, rubber-like: E = 1 MPa,
  1000 kg/m^3, 6 modes each), pitch 0.24 m, 4 layers (the thread benchmark's modal scene).
Usage: bench/make_pile_scene.py [N] [--soft] > samples/pile.json"""
import json
import math
import sys

soft = "--soft" in sys.argv
numbers = [a for a in sys.argv[1:] if a != "--soft"]
n = int(numbers[0]) if numbers else (64 if soft else 100)
layers, pitch, jitter = (4, 0.24, 0.02) if soft else (10, 0.2, 0.02)
per_layer = (n + layers - 1) // layers
side = math.ceil(math.sqrt(per_layer))
half = 0.5 * side * pitch
state = 2027 if soft else 2026


def rnd():
    """Fixed LCG in [-1, 1): the same pile every time."""
    global state
    state = (state * 1664525 + 1013904223) % 2**32
    return (state >> 8) / 8388608.0 - 1.0


def plane(name, normal, offset):
    return {"name": name, "shape": {"type": "plane", "normal": normal, "offset": offset}}


def ellipsoid(i, pos):
    q = [rnd(), rnd(), rnd(), rnd()]
    norm = math.sqrt(sum(c * c for c in q))
    return {"name": f"e{i}", "material": "plastic",
            "shape": {"type": "superquadric", "radii": [0.06, 0.04, 0.03]},
            "position": [round(c, 6) for c in pos],
            "orientation": [round(c / norm, 9) for c in q]}


def soft_ball(i, pos):
    return {"name": f"ball{i}", "material": "rubber",
            "shape": {"type": "superquadric", "radii": [0.1, 0.1, 0.1]},
            "position": [round(c, 6) for c in pos], "dynamics": {"type": "modal", "modes": 6}}


bodies = [plane("floor", [0, 1, 0], 0.0), plane("wall_x0", [1, 0, 0], -half),
          plane("wall_x1", [-1, 0, 0], -half), plane("wall_z0", [0, 0, 1], -half),
          plane("wall_z1", [0, 0, -1], -half)]
for i in range(n):
    layer, cell = divmod(i, per_layer)
    pos = [-half + pitch * (cell % side + 0.5) + jitter * rnd(),
           (0.15 + pitch * layer if soft else pitch * (layer + 0.5)) + jitter * rnd(),
           -half + pitch * (cell // side + 0.5) + jitter * rnd()]
    bodies.append(soft_ball(i, pos) if soft else ellipsoid(i, pos))

# The scene schema, relative to samples/ where the scenes are kept (docs/scene_format.md).
SCHEMA = "../docs/scene.schema.json"
if soft:
    head = {"$schema": SCHEMA,
            "comment": f"{n} soft modal balls falling into an open box (the thread benchmark's modal "
                       "scene); written by bench/make_pile_scene.py --soft.",
            "settings": {"dt": 1.0 / 240.0, "duration": 3.0},
            "materials": {"rubber": {"density": 1000, "young": 1e6, "poisson": 0.45, "friction": 0.6,
                                     "restitution": 0.3, "damping_ratio": 0.05}}}
else:
    head = {"$schema": SCHEMA,
            "comment": f"Pile protocol (docs/contact.md) on the penalty solver, {n} ellipsoids falling into an "
                       "open box; written by bench/make_pile_scene.py.",
            "settings": {"dt": 1.0 / 240.0, "duration": 3.0, "contact": {"solver": "penalty"}},
            "materials": {"plastic": {"density": 1000, "friction": 0.5, "rolling_resistance": 0.001}}}
# One body per line keeps the file short and its diffs readable.
lines = [json.dumps(head)[:-1] + ', "bodies": [']
lines += ["  " + json.dumps(b) + ("," if i + 1 < len(bodies) else "") for i, b in enumerate(bodies)]
lines.append("]}")
sys.stdout.write("\n".join(lines) + "\n")
