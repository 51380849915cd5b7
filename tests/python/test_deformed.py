# Body.deformed_points, Body.track_points (DeformedPoints) and Body.render_mesh: deformed positions as
# numpy arrays, against the modes' own field (Body.mode_shapes) and the pose, and against each other.
import gc

import numpy as np
import pytest

import supermodal as sm


def quat_matrix(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def board_points(count, seed=1):
    """Points in and around the board's box (radii 0.5, 0.019, 0.0445 m), some outside its lattice."""
    return np.random.default_rng(seed).uniform(-1.1, 1.1, size=(count, 3)) * (0.5, 0.019, 0.0445)


@pytest.fixture
def hit_board(scenes):
    """ball_on_board after the ball has struck the board, so that the board is bent."""
    w = sm.load_scene(scenes / "samples" / "ball_on_board.json")
    w.step(150)
    return w, w.find_body("board")


def test_deformed_points_are_the_posed_rest_points_plus_the_modes(hit_board):
    w, board = hit_board
    points = board_points(500)
    q = board.modal_amplitudes
    shapes = board.mode_shapes(points)
    u = np.tensordot(q, shapes, axes=1)  # displacement, shape frame
    R = quat_matrix(board.orientation)
    expected = np.asarray(board.position) + (points + u) @ R.T
    got = board.deformed_points(points)
    # The same field summed in another order (modes per node in the engine, here per point), and the pose
    # applied to p + u instead of p - com + u: rounding of doubles, a few 1e-16 of the 0.6 m coordinates;
    # 1e-12 of them is far above it and far below the deformation checked next.
    scale = np.abs(expected).max()
    assert np.abs(got - expected).max() <= 1e-12 * scale
    rigid = np.asarray(board.position) + points @ R.T
    assert np.abs(got - rigid).max() > 1e4 * 1e-12 * scale  # the board is bent: the modes count here


def test_tracked_points_are_a_shared_read_only_buffer_equal_to_deformed_points(hit_board):
    w, board = hit_board
    points = board_points(300)
    tracked = board.track_points(points)
    view = tracked.array
    assert view.shape == (300, 3) and view.dtype == np.float64 and len(tracked) == 300
    # Weights found once and the modes summed once per node: the same products in the same order as
    # body_deformed_point, so equal bit for bit.
    assert np.array_equal(view, board.deformed_points(points))
    assert not view.flags.writeable
    with pytest.raises(ValueError):
        view[0, 0] = 1.0
    assert np.shares_memory(view, tracked.update()) and np.shares_memory(view, tracked.array)
    assert not np.shares_memory(view, points)
    np.testing.assert_array_equal(tracked.rest, points)

    before = view.copy()
    w.step(20)
    assert np.array_equal(view, before)  # stepping does not refresh the buffer
    returned = tracked.update()
    now = board.deformed_points(points)
    assert not np.array_equal(now, before)  # the board moved in those 20 steps
    assert np.array_equal(view, now) and np.array_equal(returned, now)


def test_a_view_keeps_its_buffer_alive(hit_board):
    w, board = hit_board
    points = board_points(50)
    view = board.track_points(points).update()
    expected = board.deformed_points(points)
    gc.collect()  # the DeformedPoints has no other reference: the view's base holds it
    assert np.array_equal(view, expected)


def test_rigid_bodies_move_their_points_with_the_pose(scenes):
    w = sm.load_scene(scenes / "samples" / "ball_on_board.json")
    w.step(150)
    ball = w.find_body("ball")
    assert ball.mode_count == 0
    ball.orientation = (0.9, 0.1, -0.3, 0.2)  # a turn, so that the rotation is exercised
    points = np.random.default_rng(2).normal(size=(40, 3)) * 0.025
    expected = np.asarray(ball.position) + points @ quat_matrix(ball.orientation).T
    got = ball.deformed_points(points)
    assert np.abs(got - expected).max() <= 1e-12 * np.abs(expected).max()  # rounding only, as above
    assert np.array_equal(ball.track_points(points).array, got)


def test_out_is_filled_and_returned(hit_board):
    w, board = hit_board
    points = board_points(10)
    out = np.empty((10, 3))
    assert board.deformed_points(points, out=out) is out
    assert np.array_equal(out, board.deformed_points(points))


def test_bad_points_and_out_name_the_argument_and_change_nothing(hit_board):
    w, board = hit_board
    before = w.state_hash()
    out = np.full((2, 3), 7.0)
    type_cases = [np.zeros((4, 2)), np.zeros(3), [["a", "b", "c"]], np.zeros((2, 3), complex),
                  np.zeros((2, 3), bool), "points", None]
    for bad in type_cases:
        for call in (board.deformed_points, board.track_points, board.mode_shapes):
            with pytest.raises(sm.ArgumentTypeError) as e:
                call(bad)
            assert e.value.argument == "points"
    for bad in ([[0.0, 0.0, 0.0], [0.0, float("nan"), 0.0]], [[0.0, 0.0, 0.0], [np.inf, 0.0, 0.0]]):
        for call in (board.deformed_points, board.track_points):
            with pytest.raises(sm.ArgumentError) as e:
                call(bad)
            assert e.value.argument == "points" and "row 1" in str(e.value)
        with pytest.raises(sm.ArgumentError):
            board.deformed_points(bad, out=out)
    # float32, Fortran order, int64, a list: not an array the rows can be written into as they are.
    for bad_out in (np.zeros((2, 3), np.float32), np.zeros((2, 3), order="F"), np.zeros((2, 3), np.int64),
                    [[0.0] * 3] * 2):
        with pytest.raises(sm.ArgumentTypeError) as e:
            board.deformed_points(np.zeros((2, 3)), out=bad_out)
        assert e.value.argument == "out"
    read_only = np.zeros((2, 3))
    read_only.flags.writeable = False
    with pytest.raises(sm.ArgumentTypeError):
        board.deformed_points(np.zeros((2, 3)), out=read_only)
    with pytest.raises(sm.ArgumentError) as e:
        board.deformed_points(np.zeros((2, 3)), out=np.zeros((3, 3)))
    assert e.value.argument == "out"
    assert np.array_equal(out, np.full((2, 3), 7.0))  # nothing written
    assert w.state_hash() == before


def test_a_destroyed_body_is_refused(hit_board):
    w, board = hit_board
    tracked = board.track_points(board_points(5))
    w.destroy_body(board)
    with pytest.raises(sm.StateError):
        tracked.update()
    with pytest.raises(sm.StateError):
        board.deformed_points(np.zeros((1, 3)))


def test_a_render_mesh_deforms_through_track_points(scenes):
    mesh_file = scenes / "samples" / "meshes" / "pebble.obj"
    w = sm.load_scene({"bodies": [
        {"name": "floor", "motion": "static", "shape": {"type": "plane"}},
        {"name": "pebble", "shape": {"type": "superquadric", "radii": [0.06, 0.04, 0.03]},
         "position": [0, 0.2, 0], "velocity": [0, -4, 0], "mesh": str(mesh_file),
         "dynamics": {"type": "modal", "modes": 6}}]})
    pebble = w.find_body("pebble")
    assert w.find_body("floor").render_mesh is None
    vertices, triangles = pebble.render_mesh
    file_vertices = np.array([[float(x) for x in line.split()[1:4]]
                              for line in mesh_file.read_text().splitlines() if line.startswith("v ")])
    assert vertices.shape == file_vertices.shape and not vertices.flags.writeable
    # The same vertices (the import may reorder them), to the file's 6 decimals and the import's floats.
    order = lambda v: v[np.lexsort(v.T[::-1])]
    assert np.abs(order(vertices) - order(file_vertices)).max() <= 1e-6
    assert triangles.dtype == np.uint32 and triangles.shape[1] == 3 and triangles.max() == len(vertices) - 1
    tracked = pebble.track_points(vertices)
    w.step(60)  # into the floor: the pebble's modes are excited
    assert np.abs(pebble.modal_amplitudes).max() > 0
    assert np.array_equal(tracked.update(), pebble.deformed_points(vertices))


def squeezed_ellipsoid(correction):
    """A soft ellipsoid (E 1 MPa) squeezed by 60 N at its poles, with or without the static correction."""
    w = sm.World(dt=1e-3, gravity=(0.0, 0.0, 0.0))
    body = w.create_body(radii=(0.3, 0.2, 0.15), young=1e6, modal=True, mode_count=12,
                         lattice=(6, 4, 3), damping_ratio=1.0, static_correction=correction)
    for _ in range(50):
        body.apply_force((0.0, 0.0, -60.0), (0.0, 0.0, 0.15))
        body.apply_force((0.0, 0.0, 60.0), (0.0, 0.0, -0.15))
        w.step()
    return w, body


def test_tracked_points_carry_the_static_correction():
    _, plain = squeezed_ellipsoid(False)
    _, corrected = squeezed_ellipsoid(True)
    poles = np.array([[0.0, 0.0, 0.15], [0.0, 0.0, -0.15], [0.3, 0.0, 0.0]])
    # The same sums in the same order as body_deformed_point: equal bit for bit.
    assert np.array_equal(corrected.track_points(poles).array, corrected.deformed_points(poles))
    # The correction dents the loaded poles by about a millimetre more than the modes alone
    # (tests/modal/static_correction_test.cpp: 1.6 mm against 0.11 mm once settled).
    dent = corrected.deformed_points(poles)[:, 2] - plain.deformed_points(poles)[:, 2]
    assert dent[0] < -2e-4 and dent[1] > 2e-4
