# Bad input raises a ValueError or TypeError subclass naming the argument (or the scene's JSON pointer)
# and leaves the world exactly as it was: the same state hash, the same bodies, the same settings.
import math

import pytest

import supermodal as sm


@pytest.fixture
def world():
    w = sm.World()
    w.create_body(name="ground", shape="plane", motion="static")
    ball = w.create_body(name="ball", position=(0, 1, 0), modal=False)
    w.create_constraint(type="distance", a=ball, anchor_b=(0, 3, 0))
    w.step(10)
    return w


def unchanged(world, call, error, argument=None):
    before = (world.state_hash(), len(world.bodies), len(world.constraints), world.settings())
    with pytest.raises(error) as e:
        call()
    if argument is not None:
        assert e.value.argument == argument
        assert argument in str(e.value)
    assert (world.state_hash(), len(world.bodies), len(world.constraints), world.settings()) == before
    return e.value


BAD_BODIES = [
    ({"density": math.nan}, sm.ArgumentError, "density"),
    ({"density": -1.0}, sm.ArgumentError, "density"),
    ({"density": "heavy"}, sm.ArgumentTypeError, "density"),
    ({"density": True}, sm.ArgumentTypeError, "density"),
    ({"position": (0, math.inf, 0)}, sm.ArgumentError, "position[1]"),
    ({"position": (0, 1)}, sm.ArgumentError, "position"),
    ({"radii": (1, -1, 1)}, sm.ArgumentError, "radii"),
    ({"epsilon1": 5.0}, sm.ArgumentError, "epsilon1"),
    ({"orientation": (0, 0, 0, 0)}, sm.ArgumentError, "orientation"),
    ({"motion": "flying"}, sm.ArgumentError, "motion"),
    ({"restitution": 1.5}, sm.ArgumentError, "restitution"),
    ({"poisson": 0.5}, sm.ArgumentError, "poisson"),
    ({"modal": True, "motion": "static"}, sm.ArgumentError, "modal"),
    ({"modal": True, "damping_ratio": -0.1}, sm.ArgumentError, "damping_ratio"),
    ({"name": "ball"}, sm.ArgumentError, "name"),  # names are unique
    ({"colour": "red"}, sm.ArgumentTypeError, "colour"),  # unknown keyword
    ({"material": "steel"}, sm.ArgumentTypeError, "material"),
]


@pytest.mark.parametrize("kwargs,error,argument", BAD_BODIES)
def test_bad_body_changes_nothing(world, kwargs, error, argument):
    unchanged(world, lambda: world.create_body(**kwargs), error, argument)


def test_error_classes_are_value_and_type_errors():
    assert issubclass(sm.ArgumentError, ValueError) and issubclass(sm.SceneError, ValueError)
    assert issubclass(sm.StateError, ValueError) and issubclass(sm.ArgumentTypeError, TypeError)


def test_bad_constraint_changes_nothing(world):
    ball = world.find_body("ball")
    unchanged(world, lambda: world.create_constraint(a=ball, frequency_hz=0.0), sm.ArgumentError, "frequency_hz")
    unchanged(world, lambda: world.create_constraint(a=ball, b=ball), sm.ArgumentError, "b")
    unchanged(world, lambda: world.create_constraint(a="ball"), sm.ArgumentTypeError, "a")
    unchanged(world, lambda: world.create_constraint(a=ball, anchor_a={"dir": (1, 0, 0)}), sm.ArgumentTypeError, "dir")
    other = sm.World().create_body()
    unchanged(world, lambda: world.create_constraint(a=other), sm.ArgumentError, "a")


def test_bad_settings_change_nothing(world):
    unchanged(world, lambda: world.configure(substep_count=0), sm.ArgumentError, "substep_count")
    unchanged(world, lambda: world.configure(gravity=(0, math.nan, 0)), sm.ArgumentError, "gravity[1]")
    unchanged(world, lambda: world.configure(contact_solver="magic"), sm.ArgumentError, "contact_solver")
    unchanged(world, lambda: world.configure(contact_iterations=0), sm.ArgumentError, "contact_iterations")
    unchanged(world, lambda: world.configure(relax_iterations=-1), sm.ArgumentError, "relax_iterations")
    unchanged(world, lambda: world.configure(solver_substeps=65), sm.ArgumentError, "solver_substeps")
    # All or nothing: a good value next to a bad one is not applied either.
    unchanged(world, lambda: world.configure(substep_count=4, constraint_iterations=1000), sm.ArgumentError,
              "constraint_iterations")
    with pytest.raises(sm.ArgumentError):
        sm.World(dt=-0.001)


def test_bad_step_arguments_change_nothing(world):
    unchanged(world, lambda: world.advance(math.nan), sm.ArgumentError, "seconds")
    unchanged(world, lambda: world.advance(-1.0), sm.ArgumentError, "seconds")
    unchanged(world, lambda: world.step(-1), sm.ArgumentError, "count")
    unchanged(world, lambda: world.step(1.5), sm.ArgumentTypeError, "count")


def test_bad_body_writes_change_nothing(world):
    ball = world.find_body("ball")

    def set_position():
        ball.position = (0, math.nan, 0)

    unchanged(world, set_position, sm.ArgumentError, "position[1]")
    unchanged(world, lambda: ball.apply_force((math.inf, 0, 0)), sm.ArgumentError, "force[0]")
    unchanged(world, lambda: ball.apply_impulse((1, 0, 0), point="here"), sm.ArgumentTypeError, "point")


def test_bad_snapshot_changes_nothing(world):
    good = world.snapshot()
    unchanged(world, lambda: world.restore(good[:-8]), sm.StateError)
    unchanged(world, lambda: world.restore(b"not a snapshot"), sm.StateError)
    unchanged(world, lambda: world.restore("text"), sm.ArgumentTypeError, "snapshot")
    world.create_body(position=(5, 0, 0))  # bodies changed since: refused
    with pytest.raises(sm.StateError):
        world.restore(good)


def test_scene_errors_carry_the_json_pointer():
    scene = {"bodies": [{"name": "a", "shape": {"type": "superquadric", "radii": [1, -1, 1]}}]}
    with pytest.raises(sm.SceneError) as e:
        sm.load_scene(scene)
    assert e.value.pointer.startswith("/bodies/0/shape/radii")
    assert e.value.pointer in str(e.value) and e.value.file == "<dict>"


def test_scene_file_errors_name_the_file(scenes):
    path = scenes / "tests" / "tools" / "scenes" / "bad_field.json"
    with pytest.raises(sm.SceneError) as e:
        sm.load_scene(path)
    assert e.value.pointer.startswith("/") and "bad_field.json" in str(e.value)
    with pytest.raises(sm.SceneError):
        sm.load_scene(scenes / "no_such_scene.json")


def test_scene_dict_with_nan_is_refused():
    with pytest.raises(sm.ArgumentError) as e:
        sm.load_scene({"settings": {"dt": math.nan}, "bodies": []})
    assert e.value.argument == "scene"
    with pytest.raises(sm.ArgumentTypeError):
        sm.load_scene(42)
