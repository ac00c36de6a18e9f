"""The native vector env: make_vec, autoreset (SAME_STEP), determinism across num_envs."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.envs.vector import RoboRacerVectorEnv

from synthetic_tracks import stadium

SMALL = {"sim": {"lidar": {"num_beams": 109}}}


def make_vec(n, track, **kw):
    return gym.make_vec("RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point",
                        track=track, **{**SMALL, **kw})


def test_make_vec_four_envs(oval):
    env = make_vec(4, oval)
    assert isinstance(env.unwrapped, RoboRacerVectorEnv)
    assert env.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    obs, info = env.reset(seed=0)
    assert obs["scan"].shape == (4, 109) and obs["odometry"].shape == (4, 7)
    assert env.observation_space.contains(obs)
    actions = env.action_space.sample()
    obs, rew, term, trunc, info = env.step(actions)
    assert rew.shape == term.shape == trunc.shape == (4,)
    assert env.observation_space.contains(obs)
    assert info["progress"].shape == (4,) and info["_progress"].all()


def test_each_env_samples_its_own_track_with_its_rng(oval):
    tracks = [oval, stadium(4.0, 2.0, name="b"), stadium(2.0, 2.5, name="c")]
    env = make_vec(16, tracks)
    _, info = env.reset(seed=3)
    ids = info["track_id"]
    assert len(set(ids.tolist())) > 1
    _, again = env.reset(seed=3)
    assert np.array_equal(again["track_id"], ids)


def rollout(n, seed, steps=25):
    env = make_vec(n, [oval_track(), stadium(4.0, 2.0, name="b")], reset_poses="random")
    obs, _ = env.reset(seed=seed)
    rng = np.random.default_rng(0)
    out = [(obs["scan"][0].copy(), obs["odometry"][0].copy())]
    for _ in range(steps):
        a = np.tile(rng.uniform([-0.3, 0.0], [0.3, 3.0]), (n, 1)).astype(np.float32)
        obs, *_ = env.step(a)
        out.append((obs["scan"][0].copy(), obs["odometry"][0].copy()))
    return out


def oval_track():
    return stadium()


def test_env_zero_is_identical_whatever_num_envs():
    one, four = rollout(1, 11), rollout(4, 11)
    for (s1, o1), (s4, o4) in zip(one, four):
        assert np.array_equal(s1, s4) and np.array_equal(o1, o4)


def test_same_step_autoreset_returns_reset_obs_and_final_obs(oval):
    env = make_vec(3, oval, reset_poses="grid", time_limit_s=0.5)  # 10 steps
    env.reset(seed=0)
    for k in range(10):
        obs, rew, term, trunc, info = env.step(np.tile([0.0, 2.0], (3, 1)).astype(np.float32))
    assert trunc.all() and not term.any()
    assert info["_final_obs"].all() and info["final_obs"][0]["odometry"].shape == (7,)
    # the returned observation is the new episode's first one: back at the grid start
    x_final = info["final_obs"][0]["odometry"][0]
    assert obs["odometry"][0, 0] < x_final - 0.3
    assert info["progress"][0] == 0.0 and info["final_info"]["progress"][0] > 0.3
    obs, rew, term, trunc, info = env.step(np.zeros((3, 2), np.float32))
    assert not trunc.any() and "final_obs" not in info


def test_partial_autoreset_keeps_other_envs_running(oval):
    env = make_vec(2, oval, reset_poses="grid", time_limit_s=None)
    env.reset(seed=0)
    act = np.array([[0.5, 2.0], [0.0, 1.0]], np.float32)  # env 0 turns into the wall
    for _ in range(200):
        obs, rew, term, trunc, info = env.step(act)
        if term[0]:
            break
    assert term[0] and not term[1]
    assert info["final_info"]["contact_wall"][0] and not info["_final_info"][1]
    assert info["progress"][1] > 0.5  # env 1 was not reset
    assert rew[0] < 0


def test_vector_render(oval):
    env = make_vec(2, oval, render_mode="rgb_array")
    env.reset(seed=0)
    frames = env.render()
    assert len(frames) == 2 and frames[0].dtype == np.uint8 and frames[0].ndim == 3 and frames[0].shape[2] == 3


def test_bad_num_envs(oval):
    with pytest.raises(ValueError):
        RoboRacerVectorEnv(num_envs=0, track=oval, **SMALL)
