#!/usr/bin/env python3
"""Draws the engine's layer picture from the real include graph.

Reads every #include "area/..." under engine/src, counts the includes between folders and writes
docs/images/layers.dot (and layers.svg, layers.png when graphviz's `dot` is installed). Folders sit
in rows by layer, the lowest at the bottom; an arrow A -> B labelled n means n includes from A into B
(all point down).
The layer table is the one tests/support/include_layers.h enforces (capi and render share the top row
but are separate libraries: neither includes the other).
Usage: scripts/layer_graph.py [repository root]
"""
import collections
import os
import re
import shutil
import subprocess
import sys

LAYERS = [["core"], ["geometry"], ["dynamics"], ["contact"], ["modal"], ["constraints"], ["world"],
          ["scene", "io", "fit"], ["capi", "render"]]
NOTES = {"core": "registry, tasks, faults", "geometry": "superquadrics, sampling, mass",
         "dynamics": "body components, rotation", "contact": "broadphase, MPR, manifolds, penalty",
         "modal": "lattice, bases, integrators, stress", "constraints": "constraint components, anchors",
         "world": "registry, systems, the step", "capi": "C API", "scene": "scene files",
         "io": "mesh import, glTF", "fit": "superquadric fitting", "render": "EGL / GLES"}


def include_counts(src):
    pattern = re.compile(r'^\s*#\s*include\s*"([a-z_0-9]+)/')
    counts = collections.Counter()
    for folder, _, files in os.walk(src):
        for name in files:
            if not name.endswith((".h", ".cpp")):
                continue
            area = os.path.relpath(folder, src).split(os.sep)[0]
            with open(os.path.join(folder, name), encoding="utf-8") as f:
                for line in f:
                    m = pattern.match(line)
                    if m and m.group(1) not in ("supermodal", area):
                        counts[(area, m.group(1))] += 1
    return counts


def dot_text(counts):
    lines = ["digraph layers {", "  rankdir=TB; nodesep=0.35; ranksep=0.4; newrank=true;",
             '  node [shape=box, style="rounded,filled", fillcolor="#eef3fb", fontname="Helvetica", fontsize=11];',
             '  edge [color="#7a869a", fontname="Helvetica", fontsize=9, arrowsize=0.6];']
    for level, row in enumerate(LAYERS):
        names = " ".join(f'"{a}" [label="{a}\\n{NOTES[a]}"];' for a in row)
        lines.append(f"  {{ rank=same; {names} }}  // layer {level}")
    # Invisible edges keep the rows in layer order for folders that include only the public headers.
    for upper, lower in zip(LAYERS[1:], LAYERS[:-1]):
        lines.append(f'  "{upper[0]}" -> "{lower[0]}" [style=invis];')
    for (a, b), n in sorted(counts.items()):
        lines.append(f'  "{a}" -> "{b}" [label="{n}"];')
    lines.append("}")
    return "\n".join(lines) + "\n"


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    out = os.path.join(root, "docs", "images", "layers")
    with open(out + ".dot", "w", encoding="utf-8") as f:
        f.write(dot_text(include_counts(os.path.join(root, "engine", "src"))))
    if shutil.which("dot"):
        for fmt in ("svg", "png"):
            subprocess.run(["dot", f"-T{fmt}", "-Gdpi=110", out + ".dot", "-o", f"{out}.{fmt}"], check=True)
    print(out + ".dot")


if __name__ == "__main__":
    main()
