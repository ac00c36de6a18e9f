import numpy as np
import pytest

from roboracer_arena.envs.track_argument import resolve_tracks
from roboracer_arena.errors import ConfigError
from roboracer_arena.track.drivable import Track
from synthetic_tracks import stadium


def test_track_geometry_of_the_stadium(oval):
    assert oval.length == pytest.approx(2 * 6.0 + 2 * np.pi * 3.0, rel=2e-3)
    xmin, ymin, xmax, ymax = oval.bounds
    assert xmin == pytest.approx(-6.8, abs=0.01) and ymax == pytest.approx(3.8, abs=0.01)
    walls, centreline, wall_height = oval.native()
    assert len(walls) == 2 and centreline.dtype == np.float64 and wall_height == 0.5  # the build default


def test_one_or_many_tracks(oval):
    assert resolve_tracks(oval) == [oval]
    other = stadium(4.0, 2.0, name="small")
    assert [t.name for t in resolve_tracks([oval, other])] == ["stadium", "small"]


def test_corridor_like_objects_are_accepted(oval):
    class Corridor:
        walls = list(oval.walls)
        centreline = oval.centreline

    (t,) = resolve_tracks(Corridor())
    assert t.length == pytest.approx(oval.length)


@pytest.mark.parametrize("bad", [None, [], 42])
def test_bad_track_arguments(bad):
    with pytest.raises(ConfigError):
        resolve_tracks(bad)


def test_catalog_ids_resolve_through_the_library():
    from roboracer_arena.errors import InvalidArgumentError

    (monaco,) = resolve_tracks("monaco")
    assert 320 < monaco.length < 345  # 1:10 Monaco, 333 m
    with pytest.raises(InvalidArgumentError, match="unknown track id"):
        resolve_tracks("no-such-track")


def test_bad_polylines_are_rejected():
    with pytest.raises(ConfigError, match="centreline"):
        Track.from_polylines([np.zeros((3, 2))], np.array([[0.0, 0.0], [np.nan, 1.0], [1.0, 1.0]]))
    with pytest.raises(ConfigError, match="wall 0"):
        Track.from_polylines([np.zeros((1, 2))], np.eye(3)[:, :2])


def test_missing_map_file_is_a_map_io_error(tmp_path):
    from roboracer_arena.errors import MapIOError

    with pytest.raises(MapIOError, match="nope.yaml"):
        resolve_tracks(tmp_path / "nope.yaml")


def test_clearance_and_corridor_width(oval):
    assert oval.clearance([[0.0, -3.0], [0.0, -3.5]]) == pytest.approx([0.8, 0.3], abs=1e-6)
    assert oval.corridor_width_near(0.0, -3.0) == pytest.approx(1.6, abs=1e-3)
    narrow = stadium(half_width=0.2, name="narrow")
    assert narrow.corridor_width_near(6.0, 0.0) == pytest.approx(0.4, abs=1e-3)
