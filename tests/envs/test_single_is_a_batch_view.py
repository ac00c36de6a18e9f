"""The single env is a view of a batch of one: its observation and info are the batch's
env 0 (``SimBatch.single_observation`` / ``single_info``), the same values the batch's
array readers (``observation(0)``, ``info(0)``) hold, with no path of its own."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena.envs.single import RoboRacerEnv

SMALL = {"sim": {"lidar": {"num_beams": 109}}}


@pytest.mark.parametrize("vehicles", [1, 2])
def test_single_env_reads_its_batch_of_one(oval, vehicles):
    env = RoboRacerEnv(track=oval, vehicles_per_env=vehicles, reset_poses="grid", **SMALL)
    b = env._batch
    assert b.num_envs == 1
    obs, info = env.reset(seed=3)
    action = np.array([0.05, 2.0]) if vehicles == 1 else np.array([[0.05, 2.0], [-0.05, 1.5]])
    for _ in range(15):
        obs, _, _, _, info = env.step(action)
    assert info.keys() == b.single_info().keys()
    one = vehicles == 1  # one vehicle: the vehicle axis is dropped, info values are scalars

    def env0(value):
        return np.asarray(value)[0] if one and np.ndim(value) else value

    for key, value in b.info(0).items():
        assert np.array_equal(np.asarray(info[key]), env0(value)), key
    for key, value in b.observation(0).items():
        assert np.array_equal(obs[key], env0(value)), key
    assert info["track"] == b.track_names[info["track_id"]] == env.tracks[0].name
    if one:  # per step: Python scalars, as before
        assert all(isinstance(v, (bool, int, float, str)) for v in info.values())
