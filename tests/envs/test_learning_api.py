"""What RL needs from the env (issue 17): per-env reset options, autoreset DISABLED, one
episode limit across RoboRacerEnv / gymnasium.make / make_vec, the normalise preset,
stacked frames and the previous action, wrong-way flag, start noise, track pools."""

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import roboracer_arena
from roboracer_arena.envs.episode_limit import REGISTERED_MAX_EPISODE_STEPS
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.envs.vector import RoboRacerVectorEnv
from roboracer_arena.errors import ConfigError
from synthetic_tracks import stadium

SMALL = {"sim": {"lidar": {"num_beams": 61}}}
GO = np.array([0.0, 2.0], np.float32)


def vec(n, track, **kw):
    return gym.make_vec(
        "RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point", track=track, **{**SMALL, **kw}
    )


# ---------------------------------------------------------------- reset options
def test_single_env_reset_to_given_pose_and_track(oval):
    env = RoboRacerEnv(track=[oval, stadium(2.0, 2.0, name="small")], **SMALL)
    pose = [0.5, -3.4, 0.1]
    _, info = env.reset(seed=0, options={"track_ids": 0, "poses": pose})
    state, f = env.simulator_state
    assert info["track_id"] == 0
    assert state[0, f["x"]] == pytest.approx(0.5, abs=1e-3) and state[0, f["y"]] == pytest.approx(-3.4, abs=1e-3)
    assert state[0, f["yaw"]] == pytest.approx(0.1, abs=1e-3)
    with pytest.raises(ConfigError, match="poses"):
        env.reset(options={"poses": [[1.0, 2.0]]})
    with pytest.warns(UserWarning, match="pose"):
        env.reset(options={"pose": pose})


def test_vector_env_reset_poses_per_env_and_mask(oval):
    env = RoboRacerVectorEnv(num_envs=3, track=oval, **SMALL)
    poses = np.array([[0.0, -3.4, 0.0], [1.0, -3.4, 0.0], [2.0, -3.4, 0.0]])
    env.reset(seed=0, options={"poses": poses, "track_ids": [0, 0, 0]})
    x = env._batch.state[:, 0, env._batch.field_index["x"]]
    assert x == pytest.approx([0.0, 1.0, 2.0], abs=1e-3)
    for _ in range(5):
        env.step(np.tile(GO, (3, 1)))
    moved = env._batch.state[:, 0, env._batch.field_index["x"]].copy()
    # reset only env 1 to a new pose: the others keep driving from where they are
    env.reset(options={"reset_mask": [False, True, False], "poses": poses + [0, 0.1, 0]})
    x2 = env._batch.state[:, 0, env._batch.field_index["x"]]
    assert x2[1] == pytest.approx(1.0, abs=1e-3) and x2[0] == moved[0] and x2[2] == moved[2]


def test_paired_starts_give_identical_rollouts(oval):
    """ES pairs its +/- perturbations on the same start: same pose, same seed, same steps."""
    env = RoboRacerVectorEnv(num_envs=2, track=oval, **SMALL)
    pose = np.array([[0.3, -3.4, 0.05]] * 2)
    obs, _ = env.reset(seed=3, options={"poses": pose})
    assert np.array_equal(obs["scan"][0], obs["scan"][1])
    for _ in range(10):
        obs, *_ = env.step(np.tile(GO, (2, 1)))
    assert np.array_equal(obs["scan"][0], obs["scan"][1])


# ---------------------------------------------------------------- autoreset DISABLED
def test_autoreset_disabled_never_resets_by_itself(oval):
    env = vec(2, oval, reset_poses="centreline_start", max_episode_steps=5, autoreset_mode=AutoresetMode.DISABLED)
    assert env.metadata["autoreset_mode"] == AutoresetMode.DISABLED
    env.reset(seed=0)
    for _ in range(5):
        _, _, term, trunc, info = env.step(np.tile(GO, (2, 1)))
    assert trunc.all()
    progress = info["progress"].copy()
    _, rew, _, _, info = env.step(np.tile(GO, (2, 1)))  # no reset: the episodes just go on
    assert (info["progress"] > progress).all() and (rew > 0).all()
    _, info = env.reset(options={"reset_mask": np.array([True, False])})
    assert info["progress"][0] == 0.0 and info["progress"][1] > progress[1]


# ---------------------------------------------------------------- one episode limit
def test_gym_make_limit_is_the_one_limit(oval):
    env = gym.make("RoboRacerArena-v0", track=oval, collision_ends_episode=False, **SMALL)
    assert env.spec.max_episode_steps == REGISTERED_MAX_EPISODE_STEPS == 2400
    env = gym.make("RoboRacerArena-v0", track=oval, max_episode_steps=30, collision_ends_episode=False, **SMALL)
    assert env.spec.max_episode_steps == 30
    env.reset(seed=0)
    ends = [env.step(np.zeros(2, np.float32))[3] for _ in range(30)]
    assert ends == [False] * 29 + [True]
    # longer than the env's own default 2400 steps: the env no longer truncates by itself
    env = gym.make("RoboRacerArena-v0", track=oval, max_episode_steps=5000, **SMALL)
    assert env.spec.max_episode_steps == 5000 and env.unwrapped._batch.max_steps is None
    with pytest.raises(ConfigError, match="max_episode_steps"):
        gym.make("RoboRacerArena-v0", track=oval, time_limit_s=10.0, **SMALL)


def test_direct_env_spec_reports_its_own_limit(oval):
    env = RoboRacerEnv(track=oval, time_limit_s=1.0, **SMALL)
    assert env.config.max_episode_steps == 20
    env.reset(seed=0)
    ends = [env.step(np.zeros(2, np.float32))[3] for _ in range(20)]
    assert ends == [False] * 19 + [True]


def test_make_vec_limit_agrees_with_spec(oval):
    env = vec(2, oval)
    assert env.spec.max_episode_steps == env.config.max_episode_steps == REGISTERED_MAX_EPISODE_STEPS
    env = vec(2, oval, max_episode_steps=7)
    assert env.spec.max_episode_steps == env.config.max_episode_steps == 7
    env = vec(2, oval, time_limit_s=0.5)  # explicit seconds win over the registered default
    assert env.spec.max_episode_steps == env.config.max_episode_steps == 10
    env = vec(2, oval, max_episode_steps=-1)
    assert env.spec.max_episode_steps is None and env.config.max_episode_steps is None
    with pytest.raises(ConfigError, match="contradicts"):
        vec(2, oval, max_episode_steps=7, time_limit_s=0.5)


# ---------------------------------------------------------------- observations
def test_normalise_preset(oval):
    env = RoboRacerEnv(track=oval, observation="normalise", **SMALL)
    assert env.config.observation.normalise and "x" not in env.config.observation.odometry
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    assert 0.05 < obs["scan"].mean() <= 1.0  # horizon 10 m: ranges fill [0, 1]
    assert np.abs(obs["odometry"]).max() <= 1.0
    with pytest.raises(ConfigError, match="preset"):
        RoboRacerEnv(track=oval, observation="fancy", **SMALL)


def test_normalised_pose_is_in_the_start_frame_with_sin_cos_heading(oval):
    env = RoboRacerEnv(track=oval, observation={"normalise": True, "odometry": ("x", "y", "yaw")}, **SMALL)
    obs, _ = env.reset(seed=0, options={"poses": [0.0, -3.4, 0.0]})
    assert obs["odometry"] == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-3)  # x, y, sin, cos at the start
    for _ in range(30):
        obs, *_ = env.step(np.array([0.3, 2.0], np.float32))
    raw = env.odometry_raw(obs)[0]
    state, f = env.simulator_state
    assert raw == pytest.approx(state[0, [f["x"], f["y"], f["yaw"]]], abs=1e-4)
    s, c = obs["odometry"][2:]
    assert s * s + c * c == pytest.approx(1.0, abs=1e-5)
    # the same relative motion started elsewhere on the track gives the same normalised pose
    other, _ = env.reset(seed=0, options={"poses": [0.0, 3.4, math.pi]})
    assert other["odometry"] == pytest.approx([0.0, 0.0, 0.0, 1.0], abs=1e-3)


def test_frame_stack_and_previous_action(oval):
    env = RoboRacerEnv(
        track=oval, observation={"frame_stack": 3, "previous_action": True}, action_mode="normalised", **SMALL
    )
    obs, _ = env.reset(seed=0)
    assert obs["scan"].shape == (3, 61) and obs["odometry"].shape == (3, 7) and obs["previous_action"].shape == (3, 2)
    assert env.observation_space.contains(obs)
    assert np.array_equal(obs["scan"][0], obs["scan"][2])  # history filled with the first frame
    a = np.array([0.25, 0.5], np.float32)
    obs1, *_ = env.step(a)
    obs2, *_ = env.step(a)
    assert np.array_equal(obs2["scan"][1], obs1["scan"][2])  # shifted by one
    assert obs2["previous_action"][2] == pytest.approx(a) and obs1["previous_action"][1] == pytest.approx([0, 0])
    env.odometry_raw(obs2)  # newest frame, SI


def test_lidar_noise_and_dropout_are_per_episode_and_seeded(oval):
    kw = dict(randomisation={"lidar_noise_std": (0.05, 0.1), "lidar_dropout": 0.2}, **SMALL)
    clean = RoboRacerEnv(track=oval, **SMALL).reset(seed=0, options={"poses": [0, -3.4, 0]})[0]["scan"]
    env = RoboRacerEnv(track=oval, **kw)
    a = env.reset(seed=0, options={"poses": [0, -3.4, 0]})[0]["scan"]
    b = env.reset(seed=0, options={"poses": [0, -3.4, 0]})[0]["scan"]
    assert np.array_equal(a, b)  # seeded
    dropped = a == env.config.sim.lidar.range_max
    assert 2 <= dropped.sum() <= 30
    assert 0.02 < np.std((a - clean)[~dropped]) < 0.15


# ---------------------------------------------------------------- racing semantics
def test_wrong_way_flag_penalty_termination_and_laps_count_down(oval):
    env = RoboRacerEnv(
        track=oval,
        reset_poses="centreline_start",
        wrong_way_distance=0.5,
        reward={"wrong_way_penalty": 1.0},
        wrong_way_ends_episode=False,
        time_limit_s=None,
        collision_ends_episode=False,
        **SMALL,
    )
    env.reset(seed=0)
    flags, laps = [], []
    for _ in range(25):  # reverse: backwards along the track, facing the right way
        _, r, term, _, info = env.step(np.array([0.0, -2.0], np.float32))
        flags.append(info["wrong_way"])
        laps.append(info["laps"])
    assert flags[0] == 0 and flags[-1] == -1 and not term
    assert laps[-1] == -1  # backwards through the start line counts down
    assert r < -1.0 + 1e-9  # penalty on top of the negative progress
    env = RoboRacerEnv(
        track=oval,
        reset_poses="centreline_start",
        wrong_way_distance=0.5,
        wrong_way_ends_episode=True,
        collision_ends_episode=False,
        time_limit_s=None,
        **SMALL,
    )
    env.reset(seed=0)
    for _ in range(60):
        _, _, term, _, info = env.step(np.array([0.0, -2.0], np.float32))
        if term:
            break
    assert term and info["wrong_way"] == -1


def test_u_turn_is_flagged_nose_first(oval):
    env = RoboRacerEnv(track=oval, wrong_way_distance=0.5, time_limit_s=None, **SMALL)
    env.reset(seed=0, options={"poses": [0.0, -3.4, math.pi]})  # on the bottom straight facing backwards
    for _ in range(30):
        _, _, term, _, info = env.step(GO)
    assert info["wrong_way"] == 1 and not term


def test_start_noise_moves_the_start_within_the_corridor(oval):
    env = RoboRacerEnv(track=oval, reset_poses="grid", start_lateral_noise=0.3, start_heading_noise=0.2, **SMALL)
    poses = []
    for seed in range(8):
        env.reset(seed=seed)
        st, f = env.simulator_state
        poses.append(st[0, [f["x"], f["y"], f["yaw"]]])
    poses = np.array(poses)
    assert np.ptp(poses[:, 2]) > 0.05  # heading varies
    assert oval.clearance(poses[:, :2]).min() > env.config.sim.vehicle.chassis_width / 2


# ---------------------------------------------------------------- track pools
def test_weighted_track_pool_draws_by_weight():
    a, b = stadium(name="a"), stadium(2.0, 2.0, name="b")
    env = RoboRacerVectorEnv(num_envs=16, track={a: 1.0, b: 3.0}, **SMALL)
    counts = np.zeros(2)
    for seed in range(5):
        env.reset(seed=seed)
        counts += np.bincount(env.current_track_ids, minlength=2)
    assert 0.6 < counts[1] / counts.sum() < 0.9  # 3:1 weights
    env = RoboRacerVectorEnv(num_envs=8, track={a: 0.0, b: 1.0}, **SMALL)
    env.reset(seed=0)
    assert set(env.current_track_ids.tolist()) == {1}
    with pytest.raises(ConfigError, match="weight"):
        RoboRacerEnv(track={a: -1.0}, **SMALL)


def test_catalog_patterns_expand_to_ids():
    from roboracer_arena.envs.track_pool import _expand

    ids = _expand("generated:gen-l040-*")
    assert ids and all(i.startswith("gen-l040-") for i in ids)
    with pytest.raises(ConfigError, match="matched no"):
        _expand("circuits:nothing-*")
    with pytest.raises(ConfigError, match="unknown kind"):
        _expand("planets:*")


def test_make_with_no_arguments_uses_the_small_default_track():
    env = gym.make("RoboRacerArena-v0")
    obs, info = env.reset(seed=0)
    assert info["track"].startswith("gen-l040") and obs["scan"].shape == (1081,)


def test_human_render_mode_goes_through_gymnasiums_human_rendering(oval):
    from gymnasium.wrappers import HumanRendering

    with pytest.warns(UserWarning, match="HumanRendering"):
        env = gym.make("RoboRacerArena-v0", track=oval, render_mode="human", **SMALL)
    assert isinstance(env, HumanRendering) and env.unwrapped.render_mode == "rgb_array"


def test_rolling_start_speed_noise_and_speeds_option(oval):
    env = RoboRacerEnv(track=oval, reset_poses="grid", start_speed_noise=3.0, **SMALL)
    speeds = []
    for seed in range(4):
        _, info = env.reset(seed=seed)
        st, f = env.simulator_state
        speeds.append(st[0, f["vx"]])
    assert 0.0 <= min(speeds) and max(speeds) <= 3.0 + 1e-3 and np.ptp(speeds) > 0.1
    env.reset(seed=0, options={"poses": [0.0, -3.4, 0.0], "speeds": 2.5})
    st, f = env.simulator_state
    assert st[0, f["vx"]] == pytest.approx(2.5, abs=1e-3)
    _, _, _, _, info = env.step(np.array([0.0, 2.5], np.float32))
    assert info["progress"] == pytest.approx(2.5 * env.config.control_dt, rel=0.05)  # rolled on at speed
    with pytest.raises(roboracer_arena.errors.InvalidArgumentError, match="speed"):
        env.reset(options={"speeds": 99.0})
    with pytest.raises(ConfigError, match="start_speed_noise"):
        RoboRacerEnv(track=oval, start_speed_noise=50.0, **SMALL)
