"""Grid start placement (start_grid.py): on the line, clear of the walls, facing the
longest free run ahead -- not wherever the extracted centreline happens to begin."""

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.envs.track_pool import resolve_track_pool
from roboracer_arena.errors import InvalidArgumentError
from roboracer_arena.track.start_grid import (
    GRID_OFFSET,
    GRID_SPACING,
    centreline_pose,
    free_run_ahead,
    grid_start_s,
    start_spec,
)


def test_centreline_pose_interpolates_and_wraps(oval):
    x, y, yaw = centreline_pose(oval, 0.0)
    assert (x, y) == pytest.approx(tuple(oval.loop[0]))
    assert centreline_pose(oval, oval.length + 0.3) == pytest.approx(centreline_pose(oval, 0.3))


def test_grid_start_on_the_stadium_faces_a_straight(oval):
    s = grid_start_s(oval, slots=3, spacing=1.0)
    x, y, yaw = centreline_pose(oval, s)
    assert free_run_ahead(oval, x, y, yaw) > 5.0
    for k in range(3):  # every slot keeps its distance from the walls
        px, py, _ = centreline_pose(oval, s - k)
        assert oval.clearance([[px, py]])[0] > 0.5


@pytest.mark.parametrize("track_id", ["cps-f1-aut"])
def test_grid_start_is_clear_where_the_centreline_start_is_not(track_id, sources):
    (track,), _ = resolve_track_pool(track_id)
    x0, y0, h0 = centreline_pose(track, 0.0)
    assert free_run_ahead(track, x0, y0, h0) < 3.0  # the extracted start: ~2 m from a wall ahead
    x, y, h = centreline_pose(track, grid_start_s(track))
    assert free_run_ahead(track, x, y, h) > 15.0
    assert track.clearance([[x, y]])[0] >= 0.75 * np.median(track.clearance(track.loop[::5]))


def test_grid_start_keeps_a_clear_source_start_line(sources):
    """Oschersleben's centreline file defines its start line: the grid stays there."""
    (track,), _ = resolve_track_pool("oschersleben")
    assert track.source_start
    assert grid_start_s(track, slots=2) == 0.0
    x, y, h = centreline_pose(track, 0.0)
    assert track.clearance([[x, y]])[0] >= 0.75 * np.median(track.clearance(track.loop[::5]))


def test_the_start_spec_is_a_typed_object_checked_by_the_core(oval):
    spec = start_spec([oval], 2, lateral_noise=0.1, noise_std=(0.0, 0.02), dropout=0.05)
    assert isinstance(spec, _core.StartSpec)
    assert spec.s0 == [grid_start_s(oval, 2, GRID_SPACING)] and not spec.random_s
    assert (spec.grid_spacing, spec.grid_offset, spec.lateral_noise) == (GRID_SPACING, GRID_OFFSET, 0.1)
    assert spec.noise_std == (0.0, 0.02) and spec.dropout == 0.05 and spec.track_weights == []
    assert spec == start_spec([oval], 2, lateral_noise=0.1, noise_std=(0.0, 0.02), dropout=0.05)
    assert spec != start_spec([oval], 2, reset_poses="random")
    assert start_spec([oval, oval], 1, track_weights=np.array([1.0, 3.0])).track_weights == [1.0, 3.0]
    sim = _core.Simulator([oval.native()], 1, 2, {"lidar": {"num_beams": 11}}, 0)
    sim.set_start_spec(spec)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"lateral_noise": -0.1}, "lateral_noise must be finite and in"),
        ({"grid_spacing": float("inf")}, "grid_spacing must be finite and in"),
        ({"heading_noise": 2e4}, "heading_noise must be finite and in"),
        ({"noise_std": (0.2, 0.1)}, "noise_std must be"),
        ({"dropout": 1.0}, "dropout must be in"),
        ({"track_weights": [0.0]}, "track_weights must be"),
        ({"track_weights": [float("nan")]}, "track_weights must be"),
    ],
)
def test_start_spec_ranges_are_checked_on_the_rust_side(oval, kwargs, message):
    with pytest.raises(InvalidArgumentError, match=f"start spec: {message}"):
        start_spec([oval], 1, reset_poses="centreline_start", **kwargs)
    fields = {
        "random_s": False,
        "s0": [0.0],
        "grid_spacing": 1.0,
        "grid_offset": 0.2,
        "lateral_noise": 0.0,
        "heading_noise": 0.0,
        "side_clearance": 0.0,
        "speed_noise": 0.0,
        "noise_std": (0.0, 0.0),
        "dropout": 0.0,
    }
    with pytest.raises(InvalidArgumentError, match="s0 must be finite"):
        _core.StartSpec(**{**fields, "s0": [float("nan")]})
    with pytest.raises(TypeError):
        _core.StartSpec(**{k: v for k, v in fields.items() if k != "dropout"})  # every field is stated


def test_bad_start_geometry_is_a_typed_error(oval):
    walls = [np.asarray(w, dtype=np.float64) for w in oval.walls]
    with pytest.raises(InvalidArgumentError, match="start grid"):
        _core.StartGrid(walls, np.zeros((3, 2)))
    with pytest.raises(InvalidArgumentError, match="start anchor"):
        _core.StartGrid(walls, np.zeros((3, 2)), open_map=True)
    with pytest.raises(InvalidArgumentError, match=r"slots in \[1, "):
        grid_start_s(oval, 0)
    with pytest.raises(InvalidArgumentError, match="s must be finite"):
        centreline_pose(oval, float("nan"))


def test_a_track_still_pickles_after_its_start_grid_is_built(oval):
    """The core object lives beside the Track, not in it (vector envs ship tracks to workers)."""
    import pickle

    s = grid_start_s(oval, 2)
    copy = pickle.loads(pickle.dumps(oval))
    assert grid_start_s(copy, 2) == s and copy.start_grid is not oval.start_grid
