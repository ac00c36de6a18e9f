"""Actuation delay (``randomisation.action_delay_steps``): the car executes the action
given that many control steps earlier, the delay drawn per episode from each env's own
stream; (0, 0) leaves the env unchanged."""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena.envs.env_config import EnvConfig
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.envs.vector import RoboRacerVectorEnv
from roboracer_arena.errors import ConfigError

TRACK = "gen-l040-w12-h2c1s1-clo-s0"


def _steer_trace(delay: tuple[int, int], steps: int = 8) -> np.ndarray:
    env = RoboRacerEnv(
        track=TRACK,
        randomisation={"action_delay_steps": delay},
        observation={"odometry": ("steer",)},
        reset_poses="grid",
    )
    env.reset(seed=0)
    out = []
    for k in range(steps):
        obs, *_ = env.step(np.array([0.3 if k >= 1 else 0.0, 1.0], np.float32))
        out.append(float(env.odometry_raw(obs)[0, 0]))
    env.close()
    return np.array(out)


def test_a_fixed_delay_shifts_the_response_by_that_many_steps():
    now, late = _steer_trace((0, 0)), _steer_trace((2, 2))
    first = lambda tr: int(np.flatnonzero(np.abs(tr) > 1e-6)[0])
    assert first(late) - first(now) == 2
    assert np.allclose(late[2:], now[:-2], atol=1e-9)


def test_random_delays_are_drawn_per_env_and_reproducible():
    def draws(seed: int) -> list[int]:
        env = RoboRacerVectorEnv(num_envs=6, track=TRACK, randomisation={"action_delay_steps": (0, 3)})
        env.reset(seed=seed)
        d = env.unwrapped._batch.delay.steps.tolist()
        env.close()
        return d

    a, b = draws(5), draws(5)
    assert a == b and all(0 <= x <= 3 for x in a) and len(set(a)) > 1


@pytest.mark.parametrize("bad", [(-1, 0), (2, 1), (0, 65)])
def test_bad_delay_ranges_are_refused(bad):
    with pytest.raises(ConfigError, match="action_delay_steps"):
        EnvConfig.build({"randomisation": {"action_delay_steps": bad}})
