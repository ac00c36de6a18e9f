"""One start for both front ends: the bridge starts its cars where
``gym.make("RoboRacerArena-v0", track=T, reset_poses="grid")`` does (same code:
``start_grid.start_spec`` and the simulator's ``reset_drawn``), with the env's start
options; ``--start X Y YAW`` places them anywhere, as f1tenth_gym_ros' start pose does."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import roboracer_arena  # noqa: F401  (registers the env)
from roboracer_arena.errors import ArenaError, InvalidArgumentError
from roboracer_arena.ros2 import Bridge, BridgeConfig
from roboracer_arena.ros2.start import StartConfig


def _env_start(track, seed=0, **kw) -> np.ndarray:
    env = gym.make("RoboRacerArena-v0", track=track, **kw)
    try:
        env.reset(seed=seed)
        return env.unwrapped._batch.start_pose[0].copy()
    finally:
        env.close()


def _bridge_start(track, cars=1, config=None, **kw) -> np.ndarray:
    b = Bridge(track, cars=cars, dds=False, rate=None, config=config, **kw)
    b.start()
    b.stop()
    assert b.error is None
    f = b.src.fields
    observed = b.state[0][:, [f["x"], f["y"], f["yaw"]]]
    # The simulator holds the reported pose: the loop may already have run a few idle
    # steps before stop() (the car settles by micrometres), so within a tenth of a mm.
    assert np.allclose(observed, b.start_poses[0], rtol=0, atol=1e-4)
    return b.start_poses[0]


@pytest.mark.parametrize("track", ["gym-berlin", "austin", "gym-vegas"])
def test_bridge_starts_where_the_env_starts(track):
    env_pose = _env_start(track, reset_poses="grid")
    assert np.array_equal(_bridge_start(track), env_pose)
    if track == "gym-berlin":  # the numbers: not the old s = 0 start
        assert env_pose[0] == pytest.approx([7.01, -22.67, 1.53], abs=0.01)


def test_two_cars_take_the_env_grid(ellipse_map):
    env_pose = _env_start(str(ellipse_map), reset_poses="grid", vehicles_per_env=2)
    assert np.array_equal(_bridge_start(str(ellipse_map), cars=2), env_pose)


@pytest.mark.parametrize("reset_poses", ["centreline_start", "random"])
def test_start_options_mirror_the_env(ellipse_map, reset_poses):
    """Start noise and the other reset_poses draw from the same seeded streams."""
    kw = {"reset_poses": reset_poses, "start_lateral_noise": 0.2, "start_heading_noise": 0.1}
    env_pose = _env_start(str(ellipse_map), seed=0, **kw)
    start = StartConfig(**kw)
    got = _bridge_start(str(ellipse_map), config=BridgeConfig(start=start), seed=0)
    assert np.array_equal(got, env_pose)


def test_start_pose_puts_the_cars_anywhere(ellipse_map):
    assert np.array_equal(_bridge_start(str(ellipse_map), start_poses=[5.5, 0.3, 2.0]), [[5.5, 0.3, 2.0]])
    two = [[5.5, 0.3, math.pi / 2], [5.6, -0.8, math.pi / 2]]
    assert np.array_equal(_bridge_start(str(ellipse_map), cars=2, start_poses=two), two)


@pytest.mark.parametrize(
    ("poses", "cars", "message"),
    [
        ([1.0, 2.0], 1, "one X Y YAW per car"),
        ([1.0, 2.0, 0.0], 2, "one X Y YAW per car"),
        ([1, math.nan, 0], 1, "finite"),
    ],
)
def test_bad_start_pose_fails_with_a_typed_error(ellipse_map, poses, cars, message):
    with pytest.raises(InvalidArgumentError, match=message):
        Bridge(str(ellipse_map), cars=cars, dds=False, start_poses=poses)


def test_cli_start_and_reset_poses(ellipse_map, capsys):
    from roboracer_arena.cli import main

    args = ["ros2", str(ellipse_map), "--sim-time", "0.05", "--rate", "max", "--json"]
    assert main([*args, "--start", "5.5", "0.3", "2.0"]) == 0
    assert main([*args, "--reset-poses", "centreline_start"]) == 0
    assert main([*args, "--cars", "2", "--start", "5.5", "0.3", "2.0"]) != 0
    err = capsys.readouterr().err
    assert "--start needs one X Y YAW per car (2 car(s)), got 1" in err and "Traceback" not in err


def test_bad_start_config_names_the_field(tmp_path):
    from roboracer_arena.errors import ConfigError

    p = tmp_path / "bridge.json"
    p.write_text('{"start": {"reset_poses": "pole"}}')
    with pytest.raises(ConfigError, match=r"start\.reset_poses"):
        BridgeConfig.load(p)
    assert issubclass(ConfigError, ArenaError)
