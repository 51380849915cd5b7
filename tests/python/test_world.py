# Making worlds and bodies from keywords, stepping, the clock and the speed/accuracy settings.
import math

import numpy as np
import pytest

import supermodal as sm


def ball_world(**settings):
    w = sm.World(**settings)
    w.create_body(name="ground", shape="plane", motion="static")
    ball = w.create_body(name="ball", radii=(0.5, 0.5, 0.5), position=(0, 2, 0))
    return w, ball


def test_defaults_mirror_the_defs():
    w = sm.World()
    s = w.settings()
    assert s["dt"] == 0.002 and s["substep_count"] == 1
    assert s["gravity"] == (0.0, -9.81, 0.0)
    assert s["contact_solver"] == "soft" and s["contact_iterations"] == 10
    assert s["solver_substeps"] == 0  # automatic: each solver substep at most 1/240 s
    assert s["relax_iterations"] == 0  # as many as contact_iterations
    assert s["split_islands"] is False
    b = w.create_body()
    assert b.position == (0.0, 0.0, 0.0) and b.orientation == (1.0, 0.0, 0.0, 0.0)
    # A water-density sphere of radius 0.5 m: m = 1000 * 4/3 pi 0.5^3.
    assert b.mass == pytest.approx(1000 * 4 / 3 * math.pi * 0.125, rel=1e-9)


def test_free_fall_matches_the_integrator():
    w = sm.World(dt=0.01, gravity=(0, -10, 0))
    b = w.create_body(position=(0, 0, 0))
    w.step(100)
    assert w.step_count == 100 and w.time == pytest.approx(1.0)
    # Semi-implicit Euler over the automatic solver substeps (3 per 0.01 s step, h = 1/300 s): v_n = -10 n h,
    # y_n = -10 h^2 n(n+1)/2 = -5 (1 + 1/300) m after 1 s (exactly, to round-off).
    assert b.linear_velocity[1] == pytest.approx(-10.0, rel=1e-12)
    assert b.position[1] == pytest.approx(-5.0 * (1.0 + 1.0 / 300.0), rel=1e-12)
    # One solver substep integrates over the whole step: -5.05 m.
    w1 = sm.World(dt=0.01, gravity=(0, -10, 0), solver_substeps=1)
    b1 = w1.create_body(position=(0, 0, 0))
    w1.step(100)
    assert b1.position[1] == pytest.approx(-5.05, rel=1e-12)


def test_ball_comes_to_rest_on_the_ground():
    w, ball = ball_world()
    w.step(1500)  # 3 s
    # Rests on the plane y = 0 at its radius, within the contact spring's sag (a few mm at most).
    assert ball.position[1] == pytest.approx(0.5, abs=5e-3)


def test_advance_and_interpolation_alpha():
    w = sm.World(dt=0.01)
    assert w.advance(0.025) == 2
    assert w.interpolation_alpha == pytest.approx(0.5, abs=1e-9)
    assert w.advance(0.0) == 0


def test_settings_change_between_steps():
    w, _ = ball_world()
    w.substep_count = 4
    w.contact_solver = "penalty"
    w.contact_iterations = 20
    w.constraint_iterations = 8
    w.configure(gravity=(0, -1.62, 0))
    s = w.settings()
    assert (s["substep_count"], s["contact_solver"], s["contact_iterations"], s["constraint_iterations"]) == (
        4, "penalty", 20, 8)
    assert s["gravity"] == (0.0, -1.62, 0.0)
    assert s["deformed_inside_test"] is False
    w.configure(deformed_inside_test=True, split_islands=True)
    assert w.settings()["deformed_inside_test"] is True and w.settings()["split_islands"] is True
    with pytest.raises(sm.ArgumentTypeError) as e:
        w.configure(deformed_inside_test="yes")
    assert e.value.argument == "deformed_inside_test" and w.settings()["deformed_inside_test"] is True
    w.step()
    with pytest.raises(sm.ArgumentError) as e:
        w.dt = 0.001  # fixed after the first step: time is step_count * dt
    assert w.dt == 0.002 and e.value.argument


def test_constraint_holds_a_pendulum():
    w = sm.World()
    bob = w.create_body(name="bob", radii=(0.1, 0.1, 0.1), position=(1, 0, 0))
    j = w.create_constraint(type="distance", a=bob, anchor_a=(0, 0, 0), anchor_b=(0, 0, 0))
    w.step(500)
    # The rod keeps the bob 1 m from the pivot; the soft spring (30 Hz) lets it stretch by under a cm.
    assert np.linalg.norm(bob.position) == pytest.approx(1.0, abs=1e-2)
    assert j.valid and not j.broken
    assert w.constraints == [j]


def test_material_fills_the_body():
    rubber = sm.Material(name="rubber", density=1100, friction=0.9, restitution=0.8)
    w = sm.World()
    b = w.create_body(material=rubber, radii=(1, 1, 1))
    assert b.mass == pytest.approx(1100 * 4 / 3 * math.pi, rel=1e-9)
    heavier = w.create_body(material=rubber, density=2200, radii=(1, 1, 1), position=(3, 0, 0))
    assert heavier.mass == pytest.approx(2 * b.mass, rel=1e-12)


def test_modal_body_exposes_its_amplitudes(scenes):
    w = sm.load_scene(scenes / "samples" / "ball_on_board.json")
    board = w.find_body("board")
    assert board.mode_count > 0
    w.step(200)
    q = board.modal_amplitudes
    assert q.shape == (board.mode_count,) and q.dtype == np.float64
    assert not q.flags.writeable
    assert np.all(np.isfinite(q)) and np.any(q != 0.0)  # the ball's impact rings the board
    assert w.find_body("ball").modal_amplitudes.shape == (0,)


def test_bodies_keep_their_world_alive():
    def make():
        w = sm.World()
        return w.create_body(position=(0, 1, 0))

    b = make()
    assert b.position == (0.0, 1.0, 0.0)


def test_destroyed_body_raises():
    w = sm.World()
    b = w.create_body()
    w.destroy_body(b)
    assert not b.valid
    with pytest.raises(sm.StateError):
        b.position
