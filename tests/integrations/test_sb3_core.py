"""The SB3 adapter's conversion (numpy only, no SB3 or torch needed): SAME_STEP autoreset
to SB3's ``terminal_observation`` / ``TimeLimit.truncated`` / ``reset_infos``, checked
against an independent DISABLED-autoreset vector env stepped with the same actions."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import roboracer_arena  # noqa: F401  (registers the env)
from roboracer_arena.integrations.sb3_core import Sb3Translator

TRACK = "gen-l070-w20-h0c0s0-ccw-s0"
#: Every per-env info key the README lists (section "Reinforcement learning").
README_INFO_KEYS = {
    "track_id",
    "track",
    "progress",
    "contact_wall",
    "contact_vehicle",
    "lap_completed",
    "wrong_way",
    "laps",
    "lap_time",
    "last_lap_time",
    "progress_s",
}
KW = dict(num_envs=4, vectorization_mode="vector_entry_point", track=TRACK, sim={"lidar": {"num_beams": 16}})


def _venv(mode: AutoresetMode, **kw):
    return gym.make_vec("RoboRacerArena-v0", autoreset_mode=mode, **{**KW, **kw})


def test_vector_info_carries_every_readme_key():
    venv = _venv(AutoresetMode.NEXT_STEP)
    _, info = venv.reset(seed=0)
    _, _, _, _, info = venv.step(np.zeros((4, 2), np.float32))
    assert README_INFO_KEYS <= set(info)
    assert list(info["track"]) == [TRACK] * 4


@pytest.mark.parametrize("ends", ["time limit", "crash"])
def test_same_step_becomes_sb3_terminal_observation(ends):
    # "time limit": 7 steps, no crash at 1 m/s; "crash": straight at full speed into a wall.
    kw = {"time_limit_s": 0.35} if ends == "time limit" else {"time_limit_s": None}
    speed = 1.0 if ends == "time limit" else 7.0
    core = Sb3Translator(_venv(AutoresetMode.SAME_STEP, **kw))
    ref = _venv(AutoresetMode.DISABLED, **kw)
    actions = np.tile(np.array([0.0, speed], np.float32), (4, 1))
    actions[1, 0] = 0.2  # env 1 steers: envs do not all end together
    obs = core.reset(seed=3)
    ref_obs, _ = ref.reset(seed=3)
    assert all(np.array_equal(obs[k], ref_obs[k]) for k in obs)
    assert set(core.reset_infos[0]) >= README_INFO_KEYS
    for _ in range(400):
        obs, rew, dones, infos = core.step(actions)
        r_obs, r_rew, r_term, r_trunc, r_info = ref.step(actions)
        assert rew.dtype == np.float32 and dones.dtype == bool and len(infos) == 4
        np.testing.assert_array_equal(rew, r_rew.astype(np.float32))
        np.testing.assert_array_equal(dones, r_term | r_trunc)
        for i, info in enumerate(infos):
            assert README_INFO_KEYS <= set(info) and not any(k.startswith("_") for k in info)
            if dones[i]:  # the last step: its observation, its info, why it ended
                term = info["terminal_observation"]
                assert all(np.array_equal(term[k], r_obs[k][i]) for k in term)
                assert info["TimeLimit.truncated"] == bool(r_trunc[i] and not r_term[i])
                assert info["progress"] == r_info["progress"][i] and info["track"] == TRACK
                assert core.reset_infos[i]["progress"] == 0.0  # the new episode's first info
            else:
                assert "terminal_observation" not in info and "TimeLimit.truncated" not in info
                assert all(np.array_equal(obs[k][i], r_obs[k][i]) for k in obs)
        if dones.any():
            assert r_trunc[dones].all() if ends == "time limit" else r_term[dones].all()
            # the adapter's obs for a done env is the reset one: reset the reference the same way
            r_obs, _ = ref.reset(options={"reset_mask": dones})
            for k in obs:
                np.testing.assert_array_equal(obs[k][dones], r_obs[k][dones])
            break
    else:
        pytest.fail("no episode ended")


def test_the_adapter_needs_same_step():
    with pytest.raises(ValueError, match="SAME_STEP"):
        Sb3Translator(_venv(AutoresetMode.NEXT_STEP))
