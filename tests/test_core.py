"""The Rust extension loads, maps errors to typed exceptions and computes exact EDTs."""

import numpy as np
import pytest

import roboracer_arena
from roboracer_arena import _core, errors


def test_version_matches_package():
    assert roboracer_arena.__version__ == _core.__version__


def test_error_hierarchy():
    for cls in (
        errors.MapFormatError,
        errors.MapIOError,
        errors.CorridorError,
        errors.SpecError,
        errors.ConfigError,
        errors.BackendError,
        errors.GroundingError,
    ):
        assert issubclass(cls, errors.ArenaError)


def test_distance_transform_exact():
    f = np.zeros((5, 7), dtype=bool)
    f[2, 3] = True
    d = _core.distance_transform(f)
    assert d.shape == (5, 7) and d.dtype == np.float32
    assert d[2, 3] == 0 and d[2, 6] == 3
    assert d[0, 0] == pytest.approx(np.hypot(3, 2))


@pytest.mark.parametrize(
    ("straight", "radius", "width"),
    [(-1.0, 3.0, 2.0), (6.0, 0.0, 2.0), (6.0, 3.0, 6.0), (6.0, 3.0, float("nan")), (float("inf"), 3.0, 2.0)],
)
def test_stadium_track_refuses_bad_sizes_with_the_cores_check(straight, radius, width):
    with pytest.raises(errors.InvalidArgumentError, match="stadium_track needs"):
        _core.stadium_track(straight, radius, width)


def test_stadium_track_builds_two_walls_and_a_centreline():
    walls, centre = _core.stadium_track(6.0, 3.0, 2.0)
    assert len(walls) == 2 and centre.shape[1] == 2
