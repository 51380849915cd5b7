# SPDX-License-Identifier: MIT
"""supermodal.sweep: one scene run over a grid of values set at JSON pointers, on a Dask cluster.

Pure Python, installed next to the compiled module, which takes `sweep` from here when it is imported.
Nothing here imports `supermodal` or `distributed` at import time: the module imports this file while it
is itself being created, and Dask is only needed when a sweep runs.
"""
import itertools
import math
import os
import time

__all__ = ["sweep"]


def _argument_error(message, argument, type_error=False):
    import supermodal

    cls = supermodal.ArgumentTypeError if type_error else supermodal.ArgumentError
    return cls(f"{argument}: {message}", argument)


def _check_scene(scene):
    if isinstance(scene, dict):
        return scene
    if isinstance(scene, (str, os.PathLike)):
        # Absolute, so that a worker started in another folder reads the same file.
        return os.path.abspath(os.fspath(scene))
    raise _argument_error(f"expected a path or a dict, got {type(scene).__name__}", "scene", True)


def _check_grid(grid):
    if not isinstance(grid, dict) or not grid:
        raise _argument_error("expected a non-empty dict {JSON pointer: values}", "grid", not isinstance(grid, dict))
    axes = []
    for pointer, values in grid.items():
        if not isinstance(pointer, str):
            raise _argument_error(f"a key is {type(pointer).__name__}, expected a JSON pointer str", "grid", True)
        if not pointer.startswith("/"):
            raise _argument_error(f"{pointer!r} is not a JSON pointer (it starts with '/')", "grid")
        if isinstance(values, (str, bytes, dict)) or not hasattr(values, "__iter__"):
            raise _argument_error(f"expected a sequence of values, got {type(values).__name__}", f"grid[{pointer}]",
                                  True)
        values = list(values)
        if not values:
            raise _argument_error("no values", f"grid[{pointer}]")
        axes.append((pointer, values))
    return axes


def run_point(scene, overrides, seconds=None):
    """Loads `scene` with `overrides` ({pointer: value}) set, runs it for `seconds` (default: the scene's
    duration) and returns its summary: one row of sweep() (see there)."""
    import supermodal

    world = supermodal.load_scene(scene, overrides)
    seconds = world.duration if seconds is None else seconds
    # As `supermodal run`: whole steps covering the time, 1e-9 against round-off in seconds / dt.
    steps = max(1, math.ceil(seconds / world.dt - 1e-9))
    e0 = sum(b.kinetic_energy + b.potential_energy for b in world.bodies)
    total_ms = 0.0
    max_penetration = 0.0
    start = time.perf_counter()
    for _ in range(steps):
        world.step()
        total_ms += world.last_step_ms()
        max_penetration = max(max_penetration, world.max_penetration())
    wall_s = time.perf_counter() - start
    kinetic = sum(b.kinetic_energy for b in world.bodies)
    potential = sum(b.potential_energy for b in world.bodies)
    row = dict(overrides)
    row.update(
        steps=steps,
        time=world.time,
        state_hash=f"0x{world.state_hash():016x}",
        kinetic_energy=kinetic,
        potential_energy=potential,
        energy_drift=kinetic + potential - e0,
        max_penetration=max_penetration,
        ms_per_step=total_ms / steps,
        wall_s=wall_s,
        sleeping=sum(not b.awake for b in world.bodies),
        non_finite_bodies=world.warnings()["non_finite_bodies"],
    )
    return row


def sweep(scene, grid, client=None, *, n_workers=2, seconds=None):
    """Runs `scene` once per point of the grid (the cartesian product of `grid`'s value lists, the first
    key varying slowest) on a Dask cluster, and returns one summary dict per run, in grid order.

    scene: a scene file path (every worker must be able to read it) or a dict in the scene format.
    grid: {JSON pointer: sequence of values}, e.g. {"/bodies/1/material/friction": [0.2, 0.5]}. Each value
        is set in the scene's JSON before it is checked, as `supermodal run --set` does.
    client: a distributed.Client to run on; None starts a LocalCluster of `n_workers` single-threaded
        worker processes for this call and closes it afterwards.
    seconds: simulated time per run [s]; None: the scene's settings.duration.

    Each row holds the point's values under their pointers, then steps, time [s], state_hash (hex, as
    `supermodal run` prints it), kinetic_energy, potential_energy and energy_drift [J], max_penetration
    [m], ms_per_step (the engine's mean step time), wall_s, sleeping and non_finite_bodies. A run whose
    scene is refused raises its SceneError here; the other runs are then not waited for.
    """
    scene = _check_scene(scene)
    axes = _check_grid(grid)
    if seconds is not None and (isinstance(seconds, bool) or not isinstance(seconds, (int, float))
                                or not (math.isfinite(seconds) and seconds > 0)):
        raise _argument_error(f"expected a finite time > 0 s, got {seconds!r}", "seconds")
    pointers = [pointer for pointer, _ in axes]
    points = [dict(zip(pointers, values)) for values in itertools.product(*(v for _, v in axes))]
    if client is not None:
        if not (hasattr(client, "submit") and hasattr(client, "gather")):
            raise _argument_error(f"expected a distributed.Client, got {type(client).__name__}", "client", True)
        return _run_all(client, scene, points, seconds)
    if not isinstance(n_workers, int) or isinstance(n_workers, bool) or n_workers < 1:
        raise _argument_error(f"expected an int >= 1, got {n_workers!r}", "n_workers")
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with Client(cluster) as local:
            return _run_all(local, scene, points, seconds)


def _run_all(client, scene, points, seconds):
    # pure=False: every point is run, even two equal ones (their timings differ).
    futures = [client.submit(run_point, scene, point, seconds, pure=False) for point in points]
    return client.gather(futures)
