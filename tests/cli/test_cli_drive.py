"""``roboracer-arena drive`` end to end on a small ROS map written on the fly."""

import json

import numpy as np
import pytest
from PIL import Image

from roboracer_arena import _core
from roboracer_arena.cli import main
from roboracer_arena.maps.occupancy import OccupancyMap


@pytest.fixture(scope="module")
def stadium_map(tmp_path_factory):
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    xy = np.column_stack([6.0 * np.cos(t), 3.5 * np.sin(t)])  # an ellipse, CCW
    data, origin = _core.rasterise_centreline(xy, np.full(len(xy), 1.8), resolution=0.05)
    path = tmp_path_factory.mktemp("map") / "ellipse.yaml"
    return OccupancyMap(data, 0.05, origin).save(path)


def test_drive_reports_a_clean_lap_and_writes_a_gif(stadium_map, tmp_path, capsys):
    gif = tmp_path / "drive.gif"
    code = main(["drive", str(stadium_map), "--laps", "1", "--gif", str(gif), "--fps", "4", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["completed"] and out["laps_completed"] == 1 and not out["collided"]
    assert 20.0 < out["track_length"] < 35.0 and out["lap_times"][0] > 0
    with Image.open(gif) as im:
        assert im.n_frames > 5


def test_drive_bad_input_exits_2(tmp_path, capsys):
    assert main(["drive", str(tmp_path / "missing.yaml")]) == 2
    assert "missing.yaml" in capsys.readouterr().err
    assert main(["drive", "x.yaml", "--laps", "0"]) == 2
