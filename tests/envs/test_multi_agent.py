"""vehicles_per_env > 1 as a multi-agent env: per-vehicle rewards and terminations in the
single env's info, and the PettingZoo ParallelEnv wrapper (checked with PettingZoo's own
API test when PettingZoo is installed)."""

import numpy as np
import pytest

from roboracer_arena.envs.multi_agent import RoboRacerParallelEnv
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.errors import ConfigError

SMALL = {"sim": {"lidar": {"num_beams": 61}}}


def test_per_vehicle_rewards_and_terminations_in_info(oval):
    env = RoboRacerEnv(track=oval, vehicles_per_env=2, reset_poses="grid", **SMALL)
    env.reset(seed=0)
    act = np.array([[0.0, 2.0], [0.0, 0.0]], np.float32)
    _, r, term, _, info = env.step(act)
    assert info["vehicle_rewards"].shape == (2,) and info["vehicle_terminated"].shape == (2,)
    assert r == pytest.approx(info["vehicle_rewards"].sum())
    assert info["vehicle_rewards"][0] > info["vehicle_rewards"][1]


def test_parallel_env_agents_leave_when_their_car_crashes(oval):
    env = RoboRacerParallelEnv(track=oval, vehicles_per_env=2, reset_poses="grid", **SMALL)
    obs, infos = env.reset(seed=0)
    assert env.agents == ["car_0", "car_1"] and set(obs) == set(env.agents)
    assert env.observation_space("car_0").contains(obs["car_0"])
    crashed = None
    for _ in range(200):
        obs, rew, term, trunc, infos = env.step(
            {
                "car_0": np.array([0.52, 2.0], np.float32),  # into the wall
                "car_1": np.array([0.0, 0.5], np.float32),
            }
        )
        if term.get("car_0"):
            crashed = rew["car_0"]
            break
    assert crashed is not None and crashed < 0 and env.agents == ["car_1"]
    obs, rew, term, trunc, infos = env.step({"car_1": np.array([0.0, 0.5], np.float32)})
    assert set(rew) == {"car_1"} and rew["car_1"] > 0
    with pytest.raises(ConfigError):
        RoboRacerParallelEnv(track=oval, vehicles_per_env=1, **SMALL)


@pytest.mark.filterwarnings("ignore:reset options")
def test_pettingzoo_parallel_api(oval):
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import parallel_api_test

    env = RoboRacerParallelEnv(track=oval, vehicles_per_env=3, reset_poses="grid", time_limit_s=2.0, **SMALL)
    parallel_api_test(env, num_cycles=50)
