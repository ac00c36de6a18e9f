"""The default reward teaches racing: standing still scores below driving, even driving
that ends in a crash (issue 27: with the old reward, PPO learned to park). Numpy only."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena.drivers import PurePursuitDriver, PurePursuitParams
from roboracer_arena.envs.env_config import EnvConfig, RewardConfig
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.errors import ConfigError

EPISODE_S = 20.0  # short episodes keep the test fast; the ordering holds for any length


def _episode_return(oval, policy: str, **overrides) -> tuple[float, bool]:
    """Return of one episode from the grid start, and whether it ended in a crash."""
    env = RoboRacerEnv(track=oval, reset_poses="grid", time_limit_s=EPISODE_S, **overrides)
    obs, _ = env.reset(seed=0)
    driver = PurePursuitDriver.for_env(env, PurePursuitParams(max_speed=1.0, min_speed=1.0))
    total = 0.0
    while True:
        if policy == "parked":
            action = np.array([0.0, 0.0], np.float32)
        elif policy == "slow":
            action = driver.act(obs)
        else:  # "straight": 1 m/s without steering, into the first bend's wall
            action = np.array([0.0, 1.0], np.float32)
        obs, r, term, trunc, info = env.step(action)
        total += r
        if term or trunc:
            return total, bool(term and info["contact_wall"])


def test_parked_scores_below_slow_driving_and_below_a_crash(oval):
    parked, _ = _episode_return(oval, "parked")
    slow, slow_crashed = _episode_return(oval, "slow")
    straight, straight_crashed = _episode_return(oval, "straight")
    assert not slow_crashed and straight_crashed
    assert parked == pytest.approx(-RewardConfig().stall_penalty * EPISODE_S, rel=1e-6)
    assert parked < straight < slow


def test_without_the_stall_cost_parking_beats_a_crash(oval):
    """The old reward (stall_penalty=0): parking scores 0, above the crash -- the local
    optimum PPO found. Kept reachable through the config."""
    parked, _ = _episode_return(oval, "parked", reward={"stall_penalty": 0.0})
    straight, crashed = _episode_return(oval, "straight", reward={"stall_penalty": 0.0})
    assert crashed and parked == pytest.approx(0.0, abs=1e-3) and straight < parked


def test_stall_cost_is_charged_per_second_below_the_stall_speed(oval):
    """At 1 m/s (above the 0.5 m/s stall speed) the car pays the stall cost only while it
    accelerates from rest: its return is its progress minus a fraction of a second."""
    env = RoboRacerEnv(track=oval, reset_poses="grid", time_limit_s=None)
    env.reset(seed=0)
    total, stalled_steps = 0.0, 0
    dt = env.config.control_dt
    for _ in range(100):
        before = env._batch.progress[0, 0]
        _, r, term, _, info = env.step(np.array([0.0, 1.0], np.float32))
        assert not term
        ds = info["progress"] - before
        stalled = ds < env.config.reward.stall_speed * dt
        stalled_steps += stalled
        assert r == pytest.approx(ds - (dt if stalled else 0.0), abs=1e-12)
        total += r
    assert 0 < stalled_steps < 10  # the first steps from rest


def test_normalised_speed_zero_drives_by_default():
    """A zero-mean policy drives: normalised speed action 0 is the middle of the default
    range (15-70 % of max_speed), -1 and 1 its ends; None restores stop at 0."""
    cfg = EnvConfig(action_mode="normalised")
    env = RoboRacerEnv(config=cfg)
    vmax = cfg.sim.vehicle.max_speed
    lo, hi = cfg.normalised_speed_range
    for a, want in ((-1.0, lo * vmax), (0.0, (lo + hi) / 2 * vmax), (1.0, hi * vmax)):
        env._batch.set_actions(np.array([0.0, a], np.float32))
        assert env._batch.actions[0, 0, 1] == pytest.approx(want)
        back = env._batch.from_ackermann(np.array([[0.0, want]]))
        assert back[0, 1] == pytest.approx(a, abs=1e-6)
    old = RoboRacerEnv(action_mode="normalised", normalised_speed_range=None)
    old._batch.set_actions(np.array([0.0, 0.0], np.float32))
    assert old._batch.actions[0, 0, 1] == 0.0


@pytest.mark.parametrize("bad", [(0.5, 0.5), (0.7, 0.2), (0.1, 1.5), (-0.9, 0.5)])
def test_normalised_speed_range_is_checked(bad):
    with pytest.raises(ConfigError, match="normalised_speed_range"):
        EnvConfig.build(normalised_speed_range=bad)
