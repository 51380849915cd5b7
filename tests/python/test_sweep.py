# supermodal.load_scene(overrides=) and supermodal.sweep (python/_supermodal_sweep.py) on a 2-worker
# Dask LocalCluster: the grid's order, each run's summary against the closed form of a projectile, the
# same state hash as `supermodal run --set`, and errors naming the pointer.
import json
import math
import subprocess

import pytest
from distributed import Client, LocalCluster

import supermodal as sm

G = 9.81  # projectile.json's gravity [m/s²]
# Sums of products of values from the scene text: a few ulps of round-off on energies of ~10² J.
REL = 1e-9


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with Client(cluster) as c:
            yield c


@pytest.fixture
def projectile(scenes):
    return scenes / "tests" / "tools" / "scenes" / "projectile.json"


def test_load_scene_overrides_set_values_before_checking(projectile):
    w = sm.load_scene(projectile, {"/settings/dt": 0.002, "/bodies/0/name": "shot"})
    assert w.dt == 0.002
    assert w.find_body("shot") is not None
    text = projectile.read_text()
    assert sm.parse_scene(text, {"/settings/duration": 0.25}).duration == 0.25
    assert sm.load_scene(json.loads(text), {"/bodies/0/position/1": 3.0}).bodies[0].position[1] == 3.0


def test_load_scene_override_errors_name_the_pointer(projectile):
    with pytest.raises(sm.SceneError) as e:
        sm.load_scene(projectile, {"/bodies/1/position/0": 1.0})
    assert e.value.pointer == "/bodies/1/position/0" and "has 1 element" in str(e.value)
    with pytest.raises(sm.SceneError) as e:
        sm.load_scene(projectile, {"/settings/dt": -1})
    assert e.value.pointer == "/settings/dt"
    with pytest.raises(sm.ArgumentTypeError) as e:
        sm.load_scene(projectile, [("/settings/dt", 0.1)])
    assert e.value.argument == "overrides"
    with pytest.raises(sm.ArgumentError) as e:
        sm.load_scene(projectile, {"/settings/dt": math.nan})
    assert e.value.argument == "overrides[/settings/dt]"


def test_sweep_runs_the_cartesian_product_in_order(client, projectile):
    grid = {"/settings/dt": [0.001, 0.002], "/bodies/0/velocity": [[3, 4, -1], [3, 8, -1]]}
    rows = sm.sweep(projectile, grid, client, seconds=0.5)
    assert [(r["/settings/dt"], r["/bodies/0/velocity"][1]) for r in rows] == [
        (0.001, 4), (0.001, 8), (0.002, 4), (0.002, 8)]
    m = sm.load_scene(projectile).bodies[0].mass
    for r in rows:
        h = r["/settings/dt"]
        vx, vy, vz = r["/bodies/0/velocity"]
        n = round(0.5 / h)
        assert r["steps"] == n and r["time"] == pytest.approx(0.5, abs=1e-12)
        # Semi-implicit Euler under gravity alone, exactly: v_n = v0 − g h n, y_n = y0 + v0 t − g h² n(n+1)/2.
        y = 10 + vy * n * h - G * h * h * n * (n + 1) / 2
        assert r["potential_energy"] == pytest.approx(m * G * y, rel=REL)
        assert r["kinetic_energy"] == pytest.approx(0.5 * m * (vx**2 + (vy - G * h * n) ** 2 + vz**2), rel=REL)
        assert r["max_penetration"] == 0.0 and r["non_finite_bodies"] == 0 and r["ms_per_step"] > 0.0
    assert len({r["state_hash"] for r in rows}) == 4


def test_sweep_row_matches_supermodal_run_set(client, projectile, program):
    rows = sm.sweep(projectile, {"/bodies/0/velocity/1": [6.5]}, client, seconds=0.3)
    cli = subprocess.run([program("SUPERMODAL_CLI"), "run", str(projectile), "--seconds", "0.3",
                          "--set", "/bodies/0/velocity/1=6.5"], capture_output=True, text=True, check=True)
    summary = json.loads(cli.stdout)
    assert rows[0]["state_hash"] == summary["state_hash"]
    assert rows[0]["steps"] == summary["steps"]
    assert rows[0]["kinetic_energy"] == summary["energy"]["kinetic"]


def test_sweep_starts_a_local_cluster_without_a_client(projectile):
    rows = sm.sweep(projectile, {"/settings/dt": [0.001, 0.004]}, n_workers=2, seconds=0.1)
    assert [r["steps"] for r in rows] == [100, 25]
    w = sm.load_scene(projectile, {"/settings/dt": 0.004})
    w.step(25)
    assert rows[1]["state_hash"] == f"0x{w.state_hash():016x}"


def test_sweep_refused_point_raises_its_scene_error(client, projectile):
    with pytest.raises(sm.SceneError) as e:
        sm.sweep(projectile, {"/settings/dt": [0.001, -1.0]}, client, seconds=0.01)
    assert e.value.pointer == "/settings/dt"


@pytest.mark.parametrize("grid,argument", [
    ({}, "grid"), ({"settings/dt": [0.1]}, "grid"), ({"/settings/dt": []}, "grid[/settings/dt]")])
def test_sweep_bad_grid_is_an_argument_error(projectile, grid, argument):
    with pytest.raises(sm.ArgumentError) as e:
        sm.sweep(projectile, grid)
    assert e.value.argument == argument


def test_sweep_bad_types_are_argument_type_errors(projectile):
    with pytest.raises(sm.ArgumentTypeError) as e:
        sm.sweep(projectile, {"/settings/dt": 0.1})
    assert e.value.argument == "grid[/settings/dt]"
    with pytest.raises(sm.ArgumentTypeError) as e:
        sm.sweep(3, {"/settings/dt": [0.1]})
    assert e.value.argument == "scene"
    with pytest.raises(sm.ArgumentError) as e:
        sm.sweep(projectile, {"/settings/dt": [0.1]}, seconds=0.0)
    assert e.value.argument == "seconds"
    with pytest.raises(sm.ArgumentTypeError) as e:
        sm.sweep(projectile, {"/settings/dt": [0.1]}, "tcp://127.0.0.1:8786")
    assert e.value.argument == "client"
