#!/usr/bin/env python3
"""What the Python module costs over the engine (docs/python.md, "Overheads").

Per step: the same steps run from one snapshot twice, as one call world.step(n) (the loop in C++) and as
n calls world.step() from a Python loop; their difference per step is what a Python frame loop adds, but
on a shared machine it is within the steps' own noise, so the cost of one call is also measured alone:
world.step(0), everything a call does but the step.
Arrays: World.positions()/orientations() (one call, one numpy copy) against reading Body.position for
every body, on a world of 10^4 bodies. Deformed points: 10^5 points on the surface of ball_on_board's
bent board, read as a new array (Body.deformed_points, point by point), into a given one (out=), and
through Body.track_points (weights found once; update() refills a buffer numpy views share, then an
optional copy). Each figure is the median of REPEATS interleaved runs; for the
steps also the minimum of each (the least disturbed run).
Usage: PYTHONPATH=build/python python3 bench/python_overhead.py [--steps N] [--repeats R] [--only deformed]"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import supermodal as sm

ROOT = pathlib.Path(__file__).resolve().parents[1]


def per_step_overhead(world, steps, repeats):
    start = world.snapshot()
    in_cpp, in_python = [], []
    def one_call():
        world.restore(start)
        t = time.perf_counter()
        world.step(steps)
        in_cpp.append((time.perf_counter() - t) / steps)
        return world.state_hash()

    def python_loop():
        world.restore(start)
        step = world.step
        t = time.perf_counter()
        for _ in range(steps):
            step()
        in_python.append((time.perf_counter() - t) / steps)
        return world.state_hash()

    for r in range(repeats):  # alternating which goes first, so drift favours neither
        first, second = (one_call, python_loop) if r % 2 == 0 else (python_loop, one_call)
        assert first() == second()  # the same steps either way
    c, p = statistics.median(in_cpp), statistics.median(in_python)
    c_min, p_min = min(in_cpp), min(in_python)  # the least disturbed run of each
    call = call_cost(world)
    return {"step_us": c * 1e6, "python_loop_step_us": p * 1e6, "loop_difference_us": (p - c) * 1e6,
            "min_step_us": c_min * 1e6, "min_loop_difference_us": (p_min - c_min) * 1e6,
            "call_us": call * 1e6, "call_percent_of_step": 100.0 * call / c}


def call_cost(world, calls=20000):
    """One world.step() call without its step: world.step(0) (argument check, GIL release, return)."""
    step = world.step
    runs = []
    for _ in range(5):
        t = time.perf_counter()
        for _ in range(calls):
            step(0)
        runs.append((time.perf_counter() - t) / calls)
    return statistics.median(runs)


def array_costs(count, repeats):
    w = sm.World(contact_enabled=False, gravity=(0, 0, 0))
    side = round(count ** (1 / 3)) + 1
    for i in range(count):
        w.create_body(radii=(0.1, 0.1, 0.1), position=(i % side, (i // side) % side, i // side // side))
    bodies = w.bodies
    timings = {"positions()": lambda: w.positions(), "orientations()": lambda: w.orientations(),
               "[b.position for b in bodies]": lambda: [b.position for b in bodies],
               "World.bodies": lambda: w.bodies}
    out = {}
    for name, fn in timings.items():
        fn()  # warm: first touches of the bodies' memory
        runs = []
        for _ in range(repeats):
            t = time.perf_counter()
            fn()
            runs.append(time.perf_counter() - t)
        out[name] = {"ms": 1e3 * statistics.median(runs), "ns_per_body": 1e9 * statistics.median(runs) / count}
    return out


def surface_points(radii, exponents, count, seed=1):
    """Random points on a superquadric's surface [m], shape frame (its parametric form)."""
    rng = np.random.default_rng(seed)
    eta, omega = rng.uniform(-np.pi / 2, np.pi / 2, count), rng.uniform(-np.pi, np.pi, count)
    spow = lambda c, e: np.sign(c) * np.abs(c) ** e
    e1, e2 = exponents
    return np.stack([radii[0] * spow(np.cos(eta), e1) * spow(np.cos(omega), e2),
                     radii[1] * spow(np.cos(eta), e1) * spow(np.sin(omega), e2),
                     radii[2] * spow(np.sin(eta), e1)], axis=1)


def deformed_costs(count, repeats):
    world = sm.load_scene(ROOT / "samples" / "ball_on_board.json")
    world.step(150)  # the ball has struck: the board is bent
    board = world.find_body("board")
    points = surface_points((0.5, 0.019, 0.0445), (0.1, 0.1), count)
    out = np.empty_like(points)
    tracked = board.track_points(points)
    view = tracked.array
    timings = {"Body.deformed_points(points)": lambda: board.deformed_points(points),
               "Body.deformed_points(points, out=out)": lambda: board.deformed_points(points, out=out),
               "DeformedPoints.update() (view, no copy)": tracked.update,
               "np.copyto(out, DeformedPoints.update())": lambda: np.copyto(out, tracked.update()),
               "np.array(DeformedPoints.update()) (new copy)": lambda: np.array(tracked.update()),
               "np.array(view) alone (the copy)": lambda: np.array(view),
               "Body.track_points(points) (weights, once)": lambda: board.track_points(points)}
    runs = {name: [] for name in timings}
    for fn in timings.values():
        fn()  # warm
    for _ in range(repeats):  # interleaved, so that the machine's load drifts over all alike
        for name, fn in timings.items():
            t = time.perf_counter()
            fn()
            runs[name].append(time.perf_counter() - t)
    assert np.array_equal(tracked.update(), board.deformed_points(points))
    return {"points": count, "modes": board.mode_count, **{
        name: {"ms": 1e3 * statistics.median(r), "ns_per_point": 1e9 * statistics.median(r) / count,
               "min_ms": 1e3 * min(r)}
        for name, r in runs.items()}}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--only", choices=["deformed"], help="run one part only")
    args = parser.parse_args()
    report = {"python": sys.version.split()[0], "module": sm.__file__, "step": {}}
    report["deformed_100k_points"] = deformed_costs(100_000, args.repeats)
    if args.only == "deformed":
        print(json.dumps(report, indent=2))
        return
    with tempfile.TemporaryDirectory() as tmp:
        pile = pathlib.Path(tmp) / "pile_1000.json"
        pile.write_text(subprocess.run([sys.executable, str(ROOT / "bench" / "make_pile_scene.py"), "1000"],
                                       capture_output=True, text=True, check=True).stdout)
        scenes = {"chair_with_dummy": ROOT / "samples" / "chair_with_dummy.json",
                  "ball_on_board": ROOT / "samples" / "ball_on_board.json", "pile_1000": pile}
        for name, path in scenes.items():
            world = sm.load_scene(path)
            world.step(50)  # past the first contacts' set-up
            steps = args.steps if name != "pile_1000" else max(20, args.steps // 10)
            report["step"][name] = {"bodies": len(world.bodies), "steps": steps,
                                    **per_step_overhead(world, steps, args.repeats)}
    report["arrays_10k_bodies"] = array_costs(10_000, args.repeats)
    print(json.dumps(report, indent=2))


if __name__ == "__main__":
    main()
