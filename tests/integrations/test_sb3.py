"""The SB3 VecEnv on the native batch, with SB3 itself: its VecEnv machinery
(VecCheckNan, VecMonitor, VecNormalize), evaluate_policy and a few PPO updates.

SB3 imports torch (``stable_baselines3/__init__`` loads every algorithm), and torch from
PyPI brings ~3 GB of CUDA wheels, so CI does not install the ``sb3`` extra and these tests
skip there; the numpy-only conversion is tested in CI by test_sb3_core.py, and the PPO
recipe was run by hand (BENCHMARKS.md, "PPO with Stable-Baselines3")."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip(
    "stable_baselines3",
    reason="needs the sb3 extra (stable-baselines3 + torch, ~3 GB of CUDA wheels; not installed in CI)",
)

from stable_baselines3 import PPO
from stable_baselines3.common.evaluation import evaluate_policy
from stable_baselines3.common.vec_env import VecCheckNan, VecEnv, VecMonitor, VecNormalize

from roboracer_arena.integrations.sb3 import RoboRacerVecEnv, make_sb3_vec_env

TRACK = "gen-l070-w20-h0c0s0-ccw-s0"
KW = dict(
    track=TRACK, observation="normalise", action_mode="normalised", sim={"lidar": {"num_beams": 16}}, time_limit_s=2.0
)


def test_it_is_an_sb3_vecenv_with_the_native_spaces():
    venv = make_sb3_vec_env(4, **KW)
    assert isinstance(venv, VecEnv) and venv.num_envs == 4
    assert venv.observation_space == venv.venv.single_observation_space
    assert venv.get_attr("render_mode") == [None] * 4 and venv.env_is_wrapped(object) == [False] * 4
    checked = VecCheckNan(venv, raise_exception=True)
    checked.seed(0)
    obs = checked.reset()
    assert obs["scan"].shape == (4, 16)
    for _ in range(50):
        obs, rew, dones, infos = checked.step(np.tile(venv.action_space.sample(), (4, 1)))
    assert rew.shape == (4,) and len(infos) == 4 and "track" in infos[0]


def test_seed_makes_resets_repeat():
    a, b = make_sb3_vec_env(3, **KW), make_sb3_vec_env(3, **KW)
    a.seed(7)
    b.seed(7)
    oa, ob = a.reset(), b.reset()
    assert all(np.array_equal(oa[k], ob[k]) for k in oa)


def test_vecmonitor_episodes_are_the_summed_rewards():
    venv = VecMonitor(make_sb3_vec_env(2, **KW))
    venv.seed(0)
    venv.reset()
    totals, seen = np.zeros(2), []
    for _ in range(200):
        obs, rew, dones, infos = venv.step(np.zeros((2, 2), np.float32))
        totals += rew
        for i in np.flatnonzero(dones):
            seen.append((infos[i]["episode"]["r"], totals[i], infos[i]["episode"]["l"]))
            totals[i] = 0.0
    assert seen
    for r, total, length in seen:
        assert r == pytest.approx(total, abs=1e-4) and 1 <= length <= 40  # at most 2 s at 20 Hz


def test_a_few_ppo_updates_and_evaluate_policy():
    venv = VecNormalize(VecMonitor(make_sb3_vec_env(4, **KW)), norm_obs=False)
    model = PPO("MultiInputPolicy", venv, n_steps=32, batch_size=64, n_epochs=2, seed=0, device="cpu")
    model.learn(256)
    assert model.num_timesteps == 256
    mean, std = evaluate_policy(model, model.get_env(), n_eval_episodes=4)
    assert np.isfinite(mean) and np.isfinite(std)


def test_it_refuses_other_autoreset_modes():
    with pytest.raises(ValueError, match="SAME_STEP"):
        make_sb3_vec_env(2, autoreset_mode="NextStep", **KW)
    assert issubclass(RoboRacerVecEnv, VecEnv)
