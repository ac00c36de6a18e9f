"""The single env on the native simulator: gymnasium's checker, determinism, bad actions,
reward / termination / truncation, observation options."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import roboracer_arena  # noqa: F401  (registers RoboRacerArena-v0)
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.errors import ConfigError

SMALL = {"sim": {"lidar": {"num_beams": 109}}}


def make(track, **kw):
    return RoboRacerEnv(track=track, **{**SMALL, **kw})


@pytest.mark.filterwarnings("ignore:.*(infinity|symmetric and normalized|not having a spec).*")
def test_check_env_passes(oval):
    env = gym.make("RoboRacerArena-v0", track=oval, render_mode="rgb_array", **SMALL)
    check_env(env.unwrapped)
    obs, info = env.reset(seed=0)
    assert obs["scan"].shape == (109,) and obs["odometry"].shape == (7,)
    assert info["track"] == "stadium"


@pytest.mark.filterwarnings("ignore:.*(infinity|symmetric and normalized|not having a spec).*")
@pytest.mark.parametrize(
    "options",
    [
        {"action_mode": "normalised", "observation": {"normalise": True}},
        {"vehicles_per_env": 2, "observation": {"scan": False}},
    ],
)
def test_check_env_passes_with_options(oval, options):
    check_env(RoboRacerEnv(track=oval, **SMALL, **options))


def test_make_with_module_prefix(oval):
    env = gym.make("roboracer_arena:RoboRacerArena-v0", track=oval, **SMALL)
    assert isinstance(env.unwrapped, RoboRacerEnv)


def test_same_seed_same_observations(oval):
    def rollout(seed):
        env = make([oval, oval], reset_poses="random")
        obs, _ = env.reset(seed=seed)
        out = [obs["scan"].copy(), obs["odometry"].copy()]
        for k in range(15):
            obs, *_ = env.step(np.array([0.2 * np.sin(k), 2.0], np.float32))
            out += [obs["scan"].copy(), obs["odometry"].copy()]
        return out

    a, b, c = rollout(7), rollout(7), rollout(8)
    assert all(np.array_equal(x, y) for x, y in zip(a, b))
    assert not all(np.array_equal(x, y) for x, y in zip(a, c))


@pytest.mark.parametrize("mode", ["ackermann", "normalised"])
def test_bad_actions_are_clipped_never_nan(oval, mode):
    env = make(oval, action_mode=mode, reset_poses="grid", normalised_speed_range=None)  # stop at 0
    env.reset(seed=0)
    for a in ([np.nan, np.nan], [np.inf, -np.inf], [-1e9, 1e9], [np.nan, 1.0], [5.0, 50.0]):
        obs, reward, *_ = env.step(np.array(a, np.float32))
        assert np.isfinite(obs["odometry"]).all() and np.isfinite(obs["scan"]).all() and np.isfinite(reward)
    b = env._batch
    b.set_actions([np.nan, np.inf])
    veh = env.config.sim.vehicle
    assert b.actions[0, 0, 0] == 0.0 and b.actions[0, 0, 1] == veh.max_speed
    b.set_actions([-np.inf, np.nan])
    assert b.actions[0, 0, 0] == -veh.max_steer and b.actions[0, 0, 1] == 0.0


def test_normalised_action_mapping(oval):
    """The piecewise map (normalised_speed_range=None); the default range: tests/envs/test_reward.py."""
    env = make(oval, action_mode="normalised", normalised_speed_range=None)
    veh = env.config.sim.vehicle
    b = env._batch
    b.set_actions([0.5, 0.0])
    assert b.actions[0, 0].tolist() == pytest.approx([0.5 * veh.max_steer, 0.0])
    b.set_actions([-1.0, 1.0])
    assert b.actions[0, 0].tolist() == pytest.approx([-veh.max_steer, veh.max_speed])
    b.set_actions([0.0, -1.0])
    assert b.actions[0, 0, 1] == pytest.approx(veh.min_speed)
    assert env.from_ackermann([veh.max_steer / 2, veh.max_speed / 2]).tolist() == pytest.approx([0.5, 0.5])


def test_progress_reward_and_rest(oval):
    env = make(oval, reset_poses="grid", time_limit_s=None, reward={"stall_penalty": 0.0})  # progress only
    env.reset(seed=0)
    rest = sum(env.step(np.array([0.0, 0.0], np.float32))[1] for _ in range(10))
    assert abs(rest) < 0.02  # a car at rest makes no progress
    total = 0.0
    for _ in range(20):  # 1 s straight along the bottom straight at up to 2 m/s
        obs, r, term, trunc, info = env.step(np.array([0.0, 2.0], np.float32))
        total += r
        assert not term and not trunc
    assert 0.5 < total < 2.1
    assert info["progress"] == pytest.approx(rest + total, abs=1e-9)


def test_wall_contact_terminates_with_penalty(oval):
    env = make(oval, reset_poses="grid", reward={"collision_penalty": 7.0})
    env.reset(seed=0)
    for _ in range(200):  # full left lock into the inner wall
        obs, r, term, trunc, info = env.step(np.array([0.5, 2.0], np.float32))
        if term:
            break
    assert term and not trunc and info["contact_wall"]
    assert r < -6.0


def test_contact_does_not_end_the_episode_when_configured(oval):
    env = make(oval, reset_poses="grid", collision_ends_episode=False, time_limit_s=4.0)
    env.reset(seed=0)
    terms, contacts, trunc, steps = [], [], False, 0
    while not trunc:
        _, _, term, trunc, info = env.step(np.array([0.5, 2.0], np.float32))
        terms.append(term)
        contacts.append(bool(info["contact_wall"]))
        steps += 1
    assert not any(terms) and any(contacts)
    assert steps == round(4.0 / env.config.control_dt)


def test_observation_options(oval):
    env = make(oval, observation={"scan": False, "odometry": ["speed", "yaw"], "normalise": True}, vehicles_per_env=2)
    obs, _ = env.reset(seed=1)
    assert set(obs) == {"odometry"} and obs["odometry"].shape == (2, 3)  # speed, sin yaw, cos yaw
    assert env.observation_space.contains(obs)
    obs, *_ = env.step(np.zeros((2, 2), np.float32))
    assert np.abs(obs["odometry"]).max() <= 1.0
    env = make(oval, observation={"normalise": True})
    obs, _ = env.reset(seed=1)
    assert env.observation_space.contains(obs) and obs["scan"].max() <= 1.0
    raw = env.odometry_raw(obs)
    state, f = env.simulator_state
    assert raw[0, 0] == pytest.approx(state[0, f["x"]], abs=1e-4)


def test_grid_start_and_track_choice(oval):
    from synthetic_tracks import stadium

    env = make([oval, stadium(2.0, 2.0, name="small")], reset_poses="grid", vehicles_per_env=3)
    _, info = env.reset(seed=0, options={"track_id": 1})
    assert info["track"] == "small"
    state, f = env.simulator_state
    xy = state[:, [f["x"], f["y"]]]
    gaps = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    assert (gaps > 0.9).all()  # grid slots 1 m apart along the line, staggered
    with pytest.raises(ConfigError):
        env.reset(options={"track_id": 5})


def test_lidar_rate_holds_the_scan_under_a_faster_control_loop(oval):
    # 100 Hz control, 40 Hz scanner: 2 fresh scans in every 5 steps, the rest repeat the last one.
    env = RoboRacerEnv(
        track=oval, control_rate_hz=100.0, sim={"physics": {"dt": 0.01}, "lidar": {"num_beams": 61, "rate_hz": 40.0}}
    )
    obs, _ = env.reset(seed=0)
    scans = [obs["scan"].copy()]
    for _ in range(10):
        obs, *_ = env.step(np.array([0.0, 3.0]))
        scans.append(obs["scan"].copy())
    fresh = [not np.array_equal(a, b) for a, b in zip(scans, scans[1:])]
    assert sum(fresh) == 4, fresh
    # At or below the scan rate every step scans (the default: 20 Hz control, 40 Hz scanner).
    env = RoboRacerEnv(track=oval, sim={"lidar": {"num_beams": 61}})
    obs, _ = env.reset(seed=0)
    prev = obs["scan"].copy()
    for _ in range(3):
        obs, *_ = env.step(np.array([0.0, 3.0]))
        assert not np.array_equal(obs["scan"], prev)
        prev = obs["scan"].copy()
