"""Classes 9, 14 (env API), 15 and 16: env sizes budgeted before allocation (10**6 envs
aborted the process with SIGABRT), hostile actions and reset masks refused with typed
errors, Ray's unknown track reported as the local env's typed error before any actor
starts, and the reference driver reading the speed from the env instead of guessing 0."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from roboracer_arena.errors import ConfigError, InvalidArgumentError

# -- class 9 ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs",
    [
        "num_envs=10**6",
        "num_envs=4096, vehicles_per_env=8",
        "num_envs=3000, observation={'frame_stack': 64}, sim={'lidar': {'num_beams': 100000}}",
    ],
)
def test_an_env_too_large_is_a_typed_error_not_an_abort(kwargs):
    code = (
        "import gymnasium as gym, roboracer_arena\n"
        "from roboracer_arena.errors import ConfigError\n"
        "from synthetic_tracks import stadium\n"
        "try:\n"
        f"    gym.make_vec('RoboRacerArena-v0', track=stadium(), {kwargs})\n"
        "except ConfigError as e:\n"
        "    print('typed:', e)\n"
    )
    tests = str(__import__("pathlib").Path(__file__).resolve().parents[1])
    r = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env={"PYTHONPATH": tests, **_env()}
    )
    assert r.returncode == 0 and r.stdout.startswith("typed:"), (r.returncode, r.stderr[-500:])


@pytest.mark.parametrize(
    "size",
    [
        "num_envs=10**6, vehicles_per_env=1",
        "num_envs=4096, vehicles_per_env=8",
        'num_envs=16384, vehicles_per_env=1, config={"lidar": {"num_beams": 100000}}',
    ],
)
def test_the_core_simulator_refuses_a_size_over_budget_without_aborting(size):
    """Straight to ``_core``: no Python budget in between, the core's own check answers."""
    code = (
        "from roboracer_arena import _core\n"
        "from roboracer_arena.errors import ConfigError\n"
        "track = _core.stadium_track()\n"
        "try:\n"
        f"    _core.Simulator([track], {size})\n"
        "except ConfigError as e:\n"
        "    print('typed:', e)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=_env())
    assert r.returncode == 0 and r.stdout.startswith("typed:"), (r.returncode, r.stderr[-500:])


def test_the_env_budget_is_the_cores():
    """One rule: the env refuses exactly one vehicle over the core's exported limit."""
    from roboracer_arena import _core
    from roboracer_arena.envs.batch import check_size_budget
    from roboracer_arena.envs.env_config import EnvConfig

    cfg = EnvConfig(vehicles_per_env=2, observation={"scan": False})
    check_size_budget(_core.SIM_MAX_VEHICLES // 2, cfg)
    with pytest.raises(ConfigError, match=str(_core.SIM_MAX_VEHICLES)):
        check_size_budget(_core.SIM_MAX_VEHICLES // 2 + 1, cfg)
    stacked = EnvConfig(observation={"frame_stack": 3}, sim={"lidar": {"num_beams": 100_000}})
    fits = _core.SIM_MAX_SCAN_VALUES // (100_000 * 4)  # (frame_stack + 1) scans a vehicle
    check_size_budget(fits, stacked)
    with pytest.raises(ConfigError, match="scan"):
        check_size_budget(fits + 1, stacked)


def _env() -> dict:
    import os

    return {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}


# -- class 14: actions and reset masks ---------------------------------------------------


@pytest.fixture(scope="module")
def vec(oval):
    import gymnasium as gym

    return gym.make_vec("RoboRacerArena-v0", track=oval, num_envs=2)


@pytest.mark.parametrize("action", [[None, None], ["a", "b"], [object(), 1.0], [1.0, 2.0, 3.0]])
def test_step_refuses_non_numbers(oval, action):
    import gymnasium as gym

    env = gym.make("RoboRacerArena-v0", track=oval)
    env.reset(seed=0)
    with pytest.raises(InvalidArgumentError, match="actions must be"):
        env.step(action)


@pytest.mark.parametrize("mask", ["abc", "10", [0.5, 1.0], [True], [2, 0]])
def test_a_bad_reset_mask_is_refused(vec, mask):
    vec.reset(seed=0)
    with pytest.raises(ConfigError, match="reset_mask"):
        vec.reset(options={"reset_mask": mask})


def test_a_first_reset_must_reset_every_env(oval):
    import gymnasium as gym

    env = gym.make_vec("RoboRacerArena-v0", track=oval, num_envs=2)
    with pytest.raises(ConfigError, match="never reset"):
        env.reset(seed=0, options={"reset_mask": [False, False]})
    with pytest.raises(ConfigError, match="never reset"):
        env.reset(seed=0, options={"reset_mask": [True, False]})
    obs, _ = env.reset(seed=0)
    obs, _ = env.reset(options={"reset_mask": [False, True]})  # after a full reset, partial is fine
    assert np.asarray(obs["scan"]).min() > 0


# -- class 15 ----------------------------------------------------------------------------


def test_ray_reports_an_unknown_track_like_the_local_env_before_starting_actors():
    pytest.importorskip("ray")
    import gymnasium as gym
    import ray

    from roboracer_arena.distributed.ray_vector import RayVectorEnv

    with pytest.raises(InvalidArgumentError) as local:
        gym.make_vec("RoboRacerArena-v0", track="no-such-track", num_envs=1)
    with pytest.raises(InvalidArgumentError) as remote:
        RayVectorEnv(1, 1, track="no-such-track")
    assert str(remote.value) == str(local.value)
    assert not ray.is_initialized()  # refused before connecting or starting actors


# -- class 16 ----------------------------------------------------------------------------


def test_pure_pursuit_reads_the_speed_from_the_env_when_the_observation_has_none(oval):
    import gymnasium as gym

    from roboracer_arena.drivers import PurePursuitDriver

    runs = []
    for odometry in (("x", "y", "yaw", "vx"), ("x", "y", "yaw")):
        env = gym.make("RoboRacerArena-v0", track=oval, reset_poses="grid", observation={"odometry": odometry})
        driver = PurePursuitDriver.for_env(env)
        obs, _ = env.reset(seed=0)
        acts = []
        for _ in range(60):
            a = driver.act(obs)
            acts.append(np.asarray(a, float))
            obs, *_ = env.step(a)
        runs.append(np.array(acts))
    np.testing.assert_allclose(runs[1], runs[0])  # the same drive: no speed of 0 guessed
