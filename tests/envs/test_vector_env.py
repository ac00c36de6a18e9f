"""The native vector env: make_vec, autoreset (NEXT_STEP default, SAME_STEP option),
determinism across num_envs, gymnasium's vector wrappers."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.envs.vector import RoboRacerVectorEnv
from synthetic_tracks import stadium

SMALL = {"sim": {"lidar": {"num_beams": 109}}}


def make_vec(n, track, **kw):
    return gym.make_vec(
        "RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point", track=track, **{**SMALL, **kw}
    )


def test_make_vec_four_envs(oval):
    env = make_vec(4, oval)
    assert isinstance(env.unwrapped, RoboRacerVectorEnv)
    assert env.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
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


def test_next_step_autoreset(oval):
    env = make_vec(3, oval, reset_poses="grid", time_limit_s=0.5)  # 10 steps
    env.reset(seed=0)
    go = np.tile([0.0, 2.0], (3, 1)).astype(np.float32)
    for _ in range(10):
        obs, rew, term, trunc, info = env.step(go)
    assert trunc.all() and not term.any() and "final_obs" not in info
    x_last = obs["odometry"][0, 0]
    obs, rew, term, trunc, info = env.step(go)  # the reset step: action ignored
    assert not (term | trunc).any() and (rew == 0).all()
    assert obs["odometry"][0, 0] < x_last - 0.3 and info["progress"][0] == 0.0
    first = obs["odometry"].copy()
    env.reset(seed=0)
    again, _ = env.reset(seed=0)
    assert np.array_equal(again["odometry"], first)  # the reset observation, exactly
    obs, rew, term, trunc, info = env.step(go)
    assert (info["progress"] > 0).all()  # the reward of a first step from rest includes the stall cost


def test_same_step_autoreset_returns_reset_obs_and_final_obs(oval):
    env = make_vec(3, oval, reset_poses="grid", time_limit_s=0.5, autoreset_mode="SameStep")  # 10 steps
    assert env.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    env.reset(seed=0)
    for _ in range(10):
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
    env = make_vec(2, oval, reset_poses="grid", time_limit_s=None, autoreset_mode="SameStep")
    env.reset(seed=0)
    act = np.array([[0.5, 2.0], [0.0, 1.0]], np.float32)  # env 0 turns into the wall
    for _ in range(200):
        obs, rew, term, trunc, info = env.step(act)
        if term[0]:
            break
    assert term[0] and not term[1]
    assert info["final_info"]["contact_wall"][0] and not info["_final_info"][1]
    assert info["progress"][1] > 0.2  # env 1 was not reset
    assert rew[0] < 0


def test_vector_render(oval):
    env = make_vec(2, oval, render_mode="rgb_array")
    env.reset(seed=0)
    frames = env.render()
    assert len(frames) == 2 and frames[0].dtype == np.uint8 and frames[0].ndim == 3 and frames[0].shape[2] == 3


def test_bad_num_envs_and_modes(oval):
    with pytest.raises(ValueError):
        RoboRacerVectorEnv(num_envs=0, track=oval, **SMALL)
    with pytest.raises(ValueError, match="autoreset_mode"):
        RoboRacerVectorEnv(num_envs=1, track=oval, autoreset_mode="sometimes", **SMALL)
    env = RoboRacerVectorEnv(num_envs=1, track=oval, autoreset_mode="same_step", **SMALL)
    assert env.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP


def test_several_vehicles_per_env(oval):
    env = make_vec(3, oval, vehicles_per_env=2, reset_poses="grid", grid_offset=0.0, autoreset_mode="SameStep")
    obs, info = env.reset(seed=0)
    assert obs["scan"].shape == (3, 2, 109) and obs["odometry"].shape == (3, 2, 7)
    assert info["progress"].shape == (3, 2)
    assert env.single_action_space.shape == (2, 2)
    # the car behind sees the one in front: its forward beam is shorter than the leader's
    mid = 109 // 2
    assert obs["scan"][0, 1, mid] < obs["scan"][0, 0, mid]
    obs, rew, term, trunc, info = env.step(np.tile([[0.0, 1.0], [0.0, 3.0]], (3, 1, 1)).astype(np.float32))
    assert env.observation_space.contains(obs) and rew.shape == (3,)
    for _ in range(60):  # the second car runs into the first
        obs, rew, term, trunc, info = env.step(np.tile([[0.0, 0.5], [0.0, 3.0]], (3, 1, 1)).astype(np.float32))
        if term.any():
            break
    assert term.all() and info["final_info"]["contact_vehicle"].any()


def test_gymnasium_vector_wrappers(oval):
    from gymnasium.wrappers.vector import FlattenObservation, RecordEpisodeStatistics

    env = RecordEpisodeStatistics(FlattenObservation(make_vec(4, oval, time_limit_s=0.5, action_mode="normalised")))
    obs, _ = env.reset(seed=0)
    assert obs.shape == (4, 109 + 7)
    env.action_space.seed(0)
    episodes = 0
    for _ in range(12):
        obs, rew, term, trunc, info = env.step(env.action_space.sample())
        if "episode" in info:
            episodes += int(info["_episode"].sum())
            assert (info["episode"]["l"][info["_episode"]] <= 10).all()
    assert episodes == 4


def test_pure_pursuit_drives_every_env_of_a_vector_env(oval):
    from roboracer_arena.drivers import PurePursuitDriver

    tracks = [oval, stadium(4.0, 2.5, name="b")]
    env = make_vec(
        4,
        tracks,
        reset_poses="random",
        vehicles_per_env=2,
        grid_offset=0.0,
        grid_spacing=1.5,
        observation={"normalise": True},
        action_mode="normalised",
        time_limit_s=None,
    )
    driver = PurePursuitDriver.for_env(env)
    obs, info = env.reset(seed=5)
    total = np.zeros(4)
    for _ in range(80):  # 4 s
        action = driver.act(obs)
        assert env.action_space.contains(action)
        obs, rew, term, trunc, info = env.step(action)
        assert not term.any()
        total += rew
    assert (total > 2 * 6.0).all()  # both cars of every env made progress (summed reward)
