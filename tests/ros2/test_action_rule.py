"""One action rule: the env's step and the ROS 2 bridge's ``drive`` hand their commands to
the core, which sanitises them once (``_core.Simulator.sanitise_actions`` and ``step``: NaN
-> 0, straight and stop; ±inf -> the bound), so the same NaN / ±inf commands drive the same
car through either front end."""

from __future__ import annotations

import math
import time

import gymnasium as gym
import numpy as np
import pytest

import roboracer_arena  # noqa: F401  (registers the env)
from roboracer_arena.ros2 import Bridge

NAN, INF = math.nan, math.inf
#: [steer rad, speed m/s] per control period (20 Hz): a finite lead-in, then every kind of
#: non-finite value in each slot. Under the old rules (env: ±inf -> bound, core: ±inf -> 0)
#: the car's speed and heading differ after the second of these.
COMMANDS = [
    (0.1, 1.5),
    (0.0, 2.0),
    (NAN, INF),
    (INF, 2.0),
    (0.2, NAN),
    (-INF, 1.0),
    (0.0, -INF),
    (NAN, NAN),
    (INF, INF),
    (0.05, 1.0),
]
CAR = ("x", "y", "yaw", "vx", "vy", "yaw_rate", "steer", "speed")


def _car(state: np.ndarray, fields: dict[str, int]) -> np.ndarray:
    return state[..., [fields[f] for f in CAR]]


def _through_env(track: str) -> np.ndarray:
    env = gym.make(
        "RoboRacerArena-v0", track=track, reset_poses="grid", control_rate_hz=20.0, collision_ends_episode=False
    ).unwrapped
    env.reset(seed=0)
    for steer, speed in COMMANDS:
        env.step(np.array([steer, speed]))
    state, fields = env.simulator_state
    env.close()
    return _car(state, fields)


def _through_bridge(track: str) -> np.ndarray:
    bridge = Bridge(track, dds=False, rate=None, lockstep=True)  # one control period per command
    steps = bridge.control_steps * len(COMMANDS)
    assert bridge.control_steps * bridge.dt == pytest.approx(0.05)
    bridge.start()
    for steer, speed in COMMANDS:
        bridge.drive(0, steer, speed)
    deadline = time.monotonic() + 60.0
    while bridge.step < steps and time.monotonic() < deadline:
        bridge.wait(0.01)
    stats = bridge.stop()
    assert stats["error"] is None and bridge.step == steps
    return _car(bridge.state[0], bridge.src.fields)


def test_env_and_bridge_drive_the_same_car_on_non_finite_commands(ellipse_map):
    env_car, bridge_car = _through_env(str(ellipse_map)), _through_bridge(str(ellipse_map))
    assert np.isfinite(env_car).all()
    assert np.array_equal(env_car, bridge_car), f"env {env_car.tolist()} != bridge {bridge_car.tolist()}"


def test_the_rule_is_nan_to_zero_and_inf_to_the_bound(ellipse_map):
    """The rule itself, as the core states it and the env stores the applied action."""
    env = gym.make("RoboRacerArena-v0", track=str(ellipse_map)).unwrapped
    veh = env.config.sim.vehicle
    actions = np.array([[[NAN, INF]]])
    env._batch.sim.sanitise_actions(actions)
    assert actions.tolist() == [[[0.0, veh.max_speed]]]
    actions = np.array([[[-INF, NAN]]])
    env._batch.sim.sanitise_actions(actions)
    assert actions.tolist() == [[[-veh.max_steer, 0.0]]]
    actions = np.array([[[0.1, 1.25]]])  # an action inside the bounds passes unchanged
    env._batch.sim.sanitise_actions(actions)
    assert actions.tolist() == [[[0.1, 1.25]]]
    env.close()
