"""Issue 38, classes B and F for open maps: the car starts where its whole footprint fits.

* An almost blank map whose origin is its corner used to start the car at (0, 0), across
  the border wall (every episode ended on step 1); the default start is now checked for
  the car's whole box, the map edge counting as a wall.
* A map with no room for the car (a 1 x 1 map, a maze of 0.2 m corridors) is refused
  with exit 2 naming the map and its free space; so is a user's ``--start`` that does not
  fit.
* ``build --car`` on an open map says it needs a closed track (it named neither file nor
  reason).
"""

from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from PIL import Image

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.cli import main
from roboracer_arena.errors import CorridorError
from roboracer_arena.maps.car_fit import NoRoomForCarError, footprint_fits
from roboracer_arena.maps.corridor import extract_corridor


def _map(d: Path, name: str, img: np.ndarray, origin=(0.0, 0.0, 0.0), res: float = 0.05) -> Path:
    Image.fromarray(img).save(d / f"{name}.png")
    y = d / f"{name}.yaml"
    y.write_text(
        f"image: {name}.png\nresolution: {res}\norigin: [{origin[0]}, {origin[1]}, {origin[2]}]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return y


@pytest.fixture
def corner_map(tmp_path) -> Path:
    """A 6 x 5 m almost blank map (one obstacle) whose origin (0, 0) is its lower-left corner."""
    img = np.full((100, 120), 254, np.uint8)
    img[40:44, 70:74] = 0
    return _map(tmp_path, "corner", img)


def test_the_default_start_holds_the_whole_car(corner_map):
    geo = extract_corridor(corner_map, open=None)
    assert geo.kind == "open"
    x, y, yaw = geo.start_pose
    assert (x, y) != (0.0, 0.0)  # the corner would put half the car off the map
    m = geo.map
    assert footprint_fits(np.asarray(geo.corridor_mask, bool), tuple(m.origin), m.resolution, (x, y, yaw))


def test_an_episode_on_the_corner_map_does_not_end_on_step_1(corner_map):
    env = gym.make("RoboRacerArena-v0", track=str(corner_map))
    try:
        env.reset(seed=0)
        for _ in range(5):
            _, _, terminated, truncated, info = env.step(np.zeros(env.action_space.shape, np.float32))
            assert not terminated, info
    finally:
        env.close()


def test_a_map_with_no_room_for_the_car_is_refused_naming_its_free_space(tmp_path, capsys):
    one = _map(tmp_path, "one", np.full((1, 1), 254, np.uint8))
    maze = np.zeros((60, 60), np.uint8)
    maze[5:55:8, 5:55] = 254  # 0.2 m wide corridors: the car's 0.29 m box fits nowhere
    narrow = _map(tmp_path, "narrow", maze)
    for y in (one, narrow):
        with pytest.raises(NoRoomForCarError, match=rf"{y.name}: no room for the car.*free space is \d+ cell"):
            extract_corridor(y, open=None)
        assert main(["build", str(y), "-o", str(tmp_path / "o.usdc")]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and y.name in err and "no room for the car" in err and "m across" in err, err
        with pytest.raises(CorridorError, match="no room for the car"):
            gym.make("RoboRacerArena-v0", track=str(y))
    assert not (tmp_path / "o.usdc").exists()


def test_a_user_start_that_does_not_fit_is_refused(corner_map, tmp_path, capsys):
    out = tmp_path / "o.usdc"
    for start in ("0.05,0.05", "0.1,2.5,0", "3.3,2.9,0"):  # the corner, the edge, against the obstacle
        assert main(["build", str(corner_map), "-o", str(out), "--start", start]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "corner.yaml" in err and "does not fit the car" in err and "free space" in err
    assert main(["build", str(corner_map), "-o", str(out), "--start", "2,2.5,0"]) == 0
    capsys.readouterr()


def test_build_car_on_an_open_map_says_it_needs_a_closed_track(corner_map, tmp_path, capsys):
    pytest.importorskip("physx_usd_schemas")
    assert main(["build", str(corner_map), "-o", str(tmp_path / "o.usdc"), "--car"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "corner.yaml" in err and "--car needs a closed track" in err, err
    assert "centreline must be" not in err


def test_physx_check_holds_on_builds_own_stage_of_the_corner_map(corner_map, tmp_path):
    from roboracer_arena.physx import available

    if not available():
        pytest.skip("the 'physx' extra is not installed")
    out = tmp_path / "corner.usda"
    assert main(["build", str(corner_map), "-o", str(out)]) == 0
    assert main(["physx-check", str(out), "--points", "2", "--seconds", "0.5"]) == 0


def test_the_ros2_bridge_refuses_a_start_that_does_not_fit_on_an_open_map(corner_map, capsys):
    pytest.importorskip("cyclonedds", reason="needs the [ros2] extra")
    from roboracer_arena.ros2.bridge import Bridge

    with pytest.raises(NoRoomForCarError, match="does not fit the car"):
        Bridge(str(corner_map), start_poses=[0.0, 0.0, 0.0], dds=False)
    args = ["ros2", str(corner_map), "--start", "0", "0", "0", "--sim-time", "0.1", "--rate", "max", "--loopback"]
    assert main([*args, "--domain-id", "117"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "corner.yaml" in err[0] and "does not fit" in err[0]
    bridge = Bridge(str(corner_map), start_poses=[3.0, 1.0, 0.0], dds=False)  # open floor: fits
    assert bridge.src.open_map
