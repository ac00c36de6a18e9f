"""``env.simulator``: the public door to the native simulator an env steps (issue #37: the
ROS 2 bridge and the drivers read it without reaching into the env's private batch)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np

import roboracer_arena  # noqa: F401  (registers the env id)
from roboracer_arena import _core
from roboracer_arena.ros2.source import sim_source

TRACK = "gen-l040-w12-h1c1s0-ccw-s0"


def test_single_and_vector_envs_expose_their_simulator() -> None:
    env = gym.make("RoboRacerArena-v0", track=TRACK).unwrapped
    env.reset(seed=1)
    sim = env.simulator
    assert isinstance(sim, _core.Simulator)
    assert int(sim.num_envs) == 1 and tuple(sim.state_fields) == tuple(env.simulator_state[1])
    assert int(np.asarray(sim.track_ids())[0]) == env.current_track_id
    venv = gym.make_vec("RoboRacerArena-v0", num_envs=2, vectorization_mode="vector_entry_point", track=TRACK)
    venv.reset(seed=1)
    assert isinstance(venv.unwrapped.simulator, _core.Simulator)
    assert int(venv.unwrapped.simulator.num_envs) == 2


def test_the_bridge_source_of_an_env_steps_that_envs_simulator() -> None:
    env = gym.make("RoboRacerArena-v0", track=TRACK)
    env.reset(seed=1)
    src = sim_source(env)
    assert src.sim is env.unwrapped.simulator
    assert src.track_id == env.unwrapped.current_track_id
