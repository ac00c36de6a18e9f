"""Grid start placement (start_grid.py): on the line, clear of the walls, facing the
longest free run ahead -- not wherever the extracted centreline happens to begin."""

import numpy as np
import pytest

from roboracer_arena.envs.track_pool import resolve_track_pool
from roboracer_arena.start_grid import centreline_pose, free_run_ahead, grid_start_s


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
