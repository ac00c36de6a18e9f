"""Open maps (issue 29): a map without a closed corridor — f1tenth_gym_ros's default
``levine.yaml`` and a small room with a doorway written here — builds, simulates and
bridges as a floor plan: walls only, no laps, no progress."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from PIL import Image

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.errors import CorridorError, InvalidArgumentError
from roboracer_arena.maps.corridor import extract_corridor, extract_open
from roboracer_arena.track.drivable import Track, track_from_map_path


def _room(tmp_path, door: bool = True):
    """A 6 x 4 m room (0.05 m cells) with a 1 m doorway in its right wall opening onto
    unknown space: no closed corridor."""
    h, w = 80, 120
    img = np.full((h, w), 205, np.uint8)
    img[4:-4, 4:-4] = 255
    img[4:-4, 4:6] = img[4:-4, -6:-4] = 0
    img[4:6, 4:-4] = img[-6:-4, 4:-4] = 0
    if door:
        img[30:50, -6:] = 255
    Image.fromarray(img).save(tmp_path / "room.png")
    y = tmp_path / "room.yaml"
    y.write_text(
        "image: room.png\nresolution: 0.05\norigin: [-1.0, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return y


@pytest.fixture(scope="module")
def levine(sources):
    return sources / "f1tenth-gym-ros" / "maps" / "levine.yaml"


def test_a_room_with_a_doorway_is_an_open_map_never_silently(tmp_path):
    y = _room(tmp_path)
    with pytest.raises(CorridorError, match="room.yaml"):
        extract_corridor(y)
    geo = extract_corridor(y, open=None)
    assert geo.kind == "open" and geo.open_reason and "corridor" in geo.open_reason
    assert len(geo.centreline) == 0 and geo.walls and geo.iou > 0.95
    x, y0, _ = geo.start_pose
    assert -0.7 < x < 4.7 and -1.7 < y0 < 1.7  # inside the room
    forced = extract_open(y, start=(0.0, 0.0, 1.0))
    assert forced.start_pose == (0.0, 0.0, 1.0)
    with pytest.raises(CorridorError, match="not on a drivable cell"):
        extract_open(y, start=(-0.95, -1.95))  # the unknown margin: a wall by default
    # read as floor, the margin is drivable, but only 0.2 m wide: the car's box would cross the
    # map edge, so the start is refused by name (issue 38), not "not on a drivable cell"
    with pytest.raises(CorridorError, match="does not fit the car.*free space"):
        extract_open(y, start=(-0.95, -1.95), unknown="free")
    with pytest.raises(InvalidArgumentError):
        extract_open(y, unknown="maybe")


def test_open_track_has_no_length_and_turns_round(tmp_path):
    t = track_from_map_path(_room(tmp_path), open=True)
    assert t.is_open and t.length == 0.0 and t.direction == "open"
    x, y, yaw = t.start_pose
    rx, ry, ryaw = t.reversed().start_pose
    assert (rx, ry) == pytest.approx((x, y)) and abs(np.cos(ryaw - yaw) + 1) < 1e-9
    assert not Track.from_polylines(t.walls, [[0, 0], [1, 0], [1, 1]]).is_open


def test_env_on_an_open_map_ends_on_collision_with_no_progress(tmp_path):
    env = gym.make("RoboRacerArena-v0", track=str(_room(tmp_path)))
    obs, info = env.reset(seed=1)
    assert info["open_map"] is True and info["progress"] == 0.0
    x, y, _ = env.unwrapped.tracks[0].start_pose
    odo = env.unwrapped.simulator_state
    assert odo[0][0, odo[1]["x"]] == pytest.approx(x, abs=0.05)
    ended = None
    for k in range(400):  # full speed ahead, straight: a wall comes within 6 m
        obs, r, term, trunc, info = env.step(np.array([0.0, 3.0], np.float32))
        assert info["progress"] == 0.0 and info["laps"] == 0 and not info["lap_completed"]
        if term or trunc:
            ended = (k, term, info["contact_wall"])
            break
    assert ended is not None and ended[1] and ended[2], ended
    # The start pose as f1tenth_gym_ros gives it: reset options.
    _, info = env.reset(options={"poses": np.array([0.5, 0.0, np.pi / 2])})
    st, idx = env.unwrapped.simulator_state
    assert st[0, idx["x"]] == pytest.approx(0.5, abs=0.02) and st[0, idx["yaw"]] == pytest.approx(np.pi / 2, abs=0.02)
    env.close()


def test_open_false_refuses_an_open_map(tmp_path):
    with pytest.raises(CorridorError):
        gym.make("RoboRacerArena-v0", track=str(_room(tmp_path)), open=False)


def test_levine_runs_in_gym(levine):
    env = gym.make("RoboRacerArena-v0", track=str(levine))
    obs, info = env.reset(seed=0)
    assert info["open_map"] is True
    assert "walls leak" in (env.unwrapped.tracks[0].open_reason or "")
    assert np.isfinite(obs["scan"]).all() and obs["scan"].max() > 1.0
    for _ in range(50):
        obs, r, term, trunc, info = env.step(np.array([0.0, 1.0], np.float32))
        if term or trunc:
            break
    assert info["progress"] == 0.0
    env.close()


def test_levine_builds_a_valid_stage(levine, tmp_path):
    from roboracer_arena.builder import build_environment
    from roboracer_arena.usd import stage_metadata, validate_stage

    out = tmp_path / "levine.usdc"
    rep = build_environment(levine, out)
    assert rep.map_kind == "open" and rep.open_reason and rep.start_pose is not None
    assert rep.walls > 0 and rep.iou > 0.95 and rep.centreline_length_m == 0.0
    assert validate_stage(out) == []
    from pxr import Usd

    meta = stage_metadata(Usd.Stage.Open(str(out)))
    assert meta["map_kind"] == "open" and len(meta["start"]) == 3


def test_build_cli_track_only_refuses_levine(levine, tmp_path):
    from roboracer_arena.cli import main

    assert main(["build", str(levine), "-o", str(tmp_path / "l.usdc"), "--track-only"]) != 0
    assert not (tmp_path / "l.usdc").exists()
    assert main(["build", str(levine), "-o", str(tmp_path / "l.usdc"), "--open", "--unknown", "free"]) == 0
    assert (tmp_path / "l.usdc").is_file()
