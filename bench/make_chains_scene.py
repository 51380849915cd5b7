#!/usr/bin/env python3
"""Writes a chains scene for the thread benchmark's constraint solver: N chains of L links (ellipsoids
0.05 x 0.1 x 0.05 m, 1000 kg/m^3) hung from world points on an 8-wide grid, 0.4 m apart, ball joints
with swing limits and joint friction, each chain swinging about its top at its own rate (they never
reach each other). Every chain is its own island. dt = 1/240 s, 8 constraint iterations.
Usage: bench/make_chains_scene.py [N] [L] > chains.json   (default 64 chains of 10 links)"""
import json
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 64
links = int(sys.argv[2]) if len(sys.argv) > 2 else 10
pitch, length, top_y = 0.4, 0.1, 2.0

bodies, constraints = [], []
for c in range(n):
    top = [pitch * (c % 8), top_y, pitch * (c // 8)]
    # A rigid swing about the top, about x or z by turns: v = w x r with r = (0, -depth, 0).
    w = 0.3 + 0.05 * (c % 7)
    for i in range(links):
        depth = length * (i + 0.5)
        v = [w * depth, 0, 0] if c % 2 else [0, 0, -w * depth]
        name = f"c{c}_l{i}"
        bodies.append({"name": name, "material": "wood",
                       "shape": {"type": "superquadric", "radii": [0.025, 0.5 * length, 0.025]},
                       "position": [top[0], round(top_y - depth, 6), top[2]], "velocity": [round(x, 6) for x in v]})
        joint = {"name": f"c{c}_j{i}", "type": "point", "a": name, "anchor_a": [0, 0.5 * length, 0],
                 "swing_limit": 1.0, "angular_damping": 1.0}
        if i == 0:
            joint.update({"b": "world", "anchor_b": top})
        else:
            joint.update({"b": f"c{c}_l{i - 1}", "anchor_b": [0, -0.5 * length, 0]})
        constraints.append(joint)

head = {"comment": f"{n} chains of {links} links swinging from world points (the thread benchmark's "
                   "constraint scene); written by bench/make_chains_scene.py.",
        "settings": {"dt": 1.0 / 240.0, "constraint_iterations": 8, "duration": 3.0},
        "materials": {"wood": {"density": 1000, "friction": 0.5}}}
# One body or constraint per line keeps the file short.
lines = [json.dumps(head)[:-1] + ', "bodies": [']
lines += ["  " + json.dumps(b) + ("," if i + 1 < len(bodies) else "") for i, b in enumerate(bodies)]
lines.append('], "constraints": [')
lines += ["  " + json.dumps(c) + ("," if i + 1 < len(constraints) else "") for i, c in enumerate(constraints)]
lines.append("]}")
sys.stdout.write("\n".join(lines) + "\n")
