"""The core's episode step (progress, reward terms, wrong-way, termination, truncation)
equals the old Python arithmetic (``episode_oracle``) bit for bit or to 1e-12, through the
single env, ``gymnasium.make``, the vector env in both autoreset modes and several vehicles
per env. The drivers reverse, U-turn, park and hit walls so that every term fires."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest
from episode_oracle import CONTACT_VEHICLE, CONTACT_WALL, LAP_COMPLETED, EpisodeOracle, OracleStep
from gymnasium.vector import AutoresetMode

from roboracer_arena import _core
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.envs.vector import RoboRacerVectorEnv

SMALL = {"sim": {"lidar": {"num_beams": 31}}}
#: Every reward term on, with weights that keep the terms apart.
ALL_TERMS = {
    "progress": 1.5,
    "collision_penalty": 7.0,
    "stall_penalty": 0.8,
    "stall_speed": 0.4,
    "time_penalty": 0.3,
    "wrong_way_penalty": 2.5,
}
#: Steering / speed per driver: reverse, straight on (into the first bend's wall), parked,
#: hard left (into the infield wall and along it).
DRIVERS = {
    "reverse": (0.0, -2.0),
    "straight": (0.0, 2.5),
    "parked": (0.0, 0.0),
    "circle": (0.4, 1.5),
}


def _travel_vx_events(b) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    f = b.field_index
    return b.state[:, :, f["travel"]].copy(), b.state[:, :, f["vx"]].copy(), b.events.copy()


def _close(got, want, what: str) -> None:
    np.testing.assert_allclose(np.asarray(got, np.float64), want, rtol=0, atol=1e-12, err_msg=what)


def _same(got, want, what: str) -> None:
    np.testing.assert_array_equal(np.asarray(got), want, err_msg=what)


def test_event_bits_are_the_cores():
    assert (_core.EVENT_WALL, _core.EVENT_VEHICLE, _core.EVENT_LAP) == (CONTACT_WALL, CONTACT_VEHICLE, LAP_COMPLETED)
    assert _core.EVENT_FAULT == 8


@pytest.mark.parametrize(
    ("driver", "overrides"),
    [
        ("reverse", {"wrong_way_ends_episode": False, "collision_ends_episode": False, "time_limit_s": 3.0}),
        ("reverse", {"wrong_way_ends_episode": True, "collision_ends_episode": False}),
        ("straight", {"collision_ends_episode": True}),
        ("straight", {"collision_ends_episode": False, "time_limit_s": 5.0}),
        ("parked", {"time_limit_s": 1.0}),
    ],
)
def test_single_env_matches_the_oracle(oval, driver, overrides):
    env = RoboRacerEnv(
        track=oval, reset_poses="centreline_start", wrong_way_distance=0.5, reward=ALL_TERMS, **SMALL, **overrides
    )
    b = env._batch
    oracle = EpisodeOracle(env.config, 1, 1, env.config.max_episode_steps)
    action = np.array(DRIVERS[driver], np.float32)
    _, info = env.reset(seed=3)
    oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    fired = {"wrong": 0, "contact": 0, "term": 0, "trunc": 0}
    for _ in range(160):
        _, reward, term, trunc, info = env.step(action)
        want = oracle.step(*_travel_vx_events(b))
        _close(reward, want.reward[0], "reward")
        assert (term, trunc) == (bool(want.terminated[0]), bool(want.truncated[0]))
        assert isinstance(reward, float) and isinstance(term, bool) and isinstance(trunc, bool)
        _close(info["progress"], want.progress[0, 0], "progress")
        assert info["wrong_way"] == want.wrong_way[0, 0] and isinstance(info["wrong_way"], int)
        fired["wrong"] += info["wrong_way"] != 0
        fired["contact"] += info["contact_wall"]
        fired["term"] += term
        fired["trunc"] += trunc
        if term or trunc:
            env.reset()
            oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    ends = overrides.get("wrong_way_ends_episode") or overrides.get("collision_ends_episode")
    if driver == "reverse":
        assert fired["wrong"] > 0
    if driver == "straight":
        assert fired["contact"] > 0
    if ends and driver != "parked":
        assert fired["term"] > 0
    if "time_limit_s" in overrides:
        assert fired["trunc"] > 0


def test_u_turn_nose_first_matches_the_oracle(oval):
    env = RoboRacerEnv(
        track=oval, wrong_way_distance=0.5, reward=ALL_TERMS, wrong_way_ends_episode=True, time_limit_s=None, **SMALL
    )
    b = env._batch
    oracle = EpisodeOracle(env.config, 1, 1, None)
    env.reset(seed=0, options={"poses": [0.0, -3.4, math.pi]})  # bottom straight, facing backwards
    oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    for _ in range(60):
        _, reward, term, trunc, info = env.step(np.array([0.0, 2.0], np.float32))
        want = oracle.step(*_travel_vx_events(b))
        _close(reward, want.reward[0], "reward")
        assert info["wrong_way"] == want.wrong_way[0, 0] and term == bool(want.terminated[0])
        if term:
            break
    assert term and info["wrong_way"] == 1


def test_gym_make_matches_the_oracle_with_its_time_limit(oval):
    env = gym.make(
        "RoboRacerArena-v0",
        track=oval,
        reset_poses="centreline_start",
        wrong_way_distance=0.5,
        reward=ALL_TERMS,
        collision_ends_episode=False,
        max_episode_steps=25,
        **SMALL,
    )
    b = env.unwrapped._batch
    oracle = EpisodeOracle(env.unwrapped.config, 1, 1, None)  # gymnasium's TimeLimit truncates
    env.reset(seed=1)
    oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    truncations = 0
    for i in range(80):
        _, reward, term, trunc, info = env.step(np.array(DRIVERS["reverse" if i % 50 < 30 else "circle"], np.float32))
        want = oracle.step(*_travel_vx_events(b))
        _close(reward, want.reward[0], "reward")
        _close(info["progress"], want.progress[0, 0], "progress")
        assert info["wrong_way"] == want.wrong_way[0, 0] and term == bool(want.terminated[0])
        truncations += trunc
        if term or trunc:
            env.reset()
            oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    assert truncations == 3


def test_single_env_with_several_vehicles_matches_the_oracle(oval):
    env = RoboRacerEnv(
        track=oval,
        vehicles_per_env=3,
        reset_poses="grid",
        wrong_way_distance=0.5,
        reward=ALL_TERMS,
        collision_ends_episode=False,
        wrong_way_ends_episode=True,
        time_limit_s=4.0,
        **SMALL,
    )
    b = env._batch
    oracle = EpisodeOracle(env.config, 1, 3, env.config.max_episode_steps)
    actions = np.array([DRIVERS["reverse"], DRIVERS["straight"], DRIVERS["circle"]], np.float32)
    env.reset(seed=2)
    oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    seen_term = False
    for _ in range(120):
        _, reward, term, trunc, info = env.step(actions)
        want = oracle.step(*_travel_vx_events(b))
        _compare_env(0, reward, term, trunc, info, want)
        seen_term |= term
        if term or trunc:
            env.reset()
            oracle.reset(np.ones(1, bool), _travel_vx_events(b)[0])
    assert seen_term


def _compare_env(e: int, reward, term, trunc, info, want: OracleStep) -> None:
    _close(reward, want.reward[e], "reward")
    assert (bool(term), bool(trunc)) == (bool(want.terminated[e]), bool(want.truncated[e]))
    _close(info["vehicle_rewards"], want.vehicle_rewards[e], "vehicle_rewards")
    _same(info["vehicle_terminated"], want.vehicle_terminated[e], "vehicle_terminated")
    _close(info["progress"], want.progress[e], "progress")
    _same(info["wrong_way"], want.wrong_way[e], "wrong_way")


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
@pytest.mark.parametrize("vehicles", [1, 2])
def test_vector_env_matches_the_oracle(oval, mode, vehicles):
    E = 4
    env = RoboRacerVectorEnv(
        num_envs=E,
        track=oval,
        vehicles_per_env=vehicles,
        reset_poses="grid",
        wrong_way_distance=0.5,
        reward=ALL_TERMS,
        collision_ends_episode=True,
        wrong_way_ends_episode=False,
        max_episode_steps=30,
        autoreset_mode=mode,
        **SMALL,
    )
    b = env._batch
    # A same-step autoreset replaces the finished envs' state before step() returns: keep
    # the state the step left (what the oracle steps on) by looking before each reset.
    before_reset: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
    reset = b.reset

    def spy(mask, *args, **kwargs):
        before_reset.append(_travel_vx_events(b))
        return reset(mask, *args, **kwargs)

    b.reset = spy
    oracle = EpisodeOracle(env.config, E, vehicles, 30)
    per_env = [DRIVERS[d] for d in ("reverse", "straight", "parked", "circle")]
    actions = np.array([[a] * vehicles for a in per_env], np.float32)
    env.reset(seed=5)
    oracle.reset(np.ones(E, bool), _travel_vx_events(b)[0])
    pending = np.zeros(E, bool)
    counts = np.zeros(2, int)
    for _ in range(90):
        before_reset.clear()
        _, reward, term, trunc, info = env.step(actions[:, 0] if vehicles == 1 else actions)
        after = _travel_vx_events(b)
        want = oracle.step(*(before_reset[0] if before_reset else after))
        if mode == AutoresetMode.NEXT_STEP:
            if pending.any():  # reset at the start of this step: its action was moot
                oracle.reset(pending, after[0])
                want = oracle.after_reset(pending, want)
            pending = want.terminated | want.truncated
            done, final = np.zeros(E, bool), None
        else:
            done = info.get("_final_info", np.zeros(E, bool))
            final = info.get("final_info")
        for e in range(E):
            src = final if done[e] else info
            one = {k: src[k][e] for k in ("progress", "wrong_way")}
            if vehicles == 1:
                one = {k: np.atleast_1d(v) for k, v in one.items()}
                one["vehicle_rewards"], one["vehicle_terminated"] = want.vehicle_rewards[e], want.vehicle_terminated[e]
            else:
                one["vehicle_rewards"], one["vehicle_terminated"] = (
                    src["vehicle_rewards"][e],
                    src["vehicle_terminated"][e],
                )
            _compare_env(e, reward[e], term[e], trunc[e], one, want)
        if done.any():
            oracle.reset(done, after[0])
            for k in ("progress", "wrong_way"):  # the new episode's first info
                assert not np.asarray(info[k])[done].any()
        counts += (term.sum(), trunc.sum())
    assert counts[0] > 0 and counts[1] > 0


@pytest.mark.parametrize("odometry", [("x", "y", "yaw", "vx"), ("speed", "x"), ()])
@pytest.mark.parametrize("num_envs", [1, 3])
def test_raw_observation_is_the_state_after_every_step(oval, odometry, num_envs):
    """The one refresh path (direct copies for a column run, a gather otherwise) shows
    each step's state, in the single and the vector env."""
    kw = {"observation": {"odometry": odometry}, **SMALL}
    env = RoboRacerEnv(track=oval, **kw) if num_envs == 1 else RoboRacerVectorEnv(num_envs=num_envs, track=oval, **kw)
    b = env._batch
    obs, _ = env.reset(seed=0)
    for i in range(15):
        act = np.array([0.1 * (i % 3), 1.5], np.float32)
        obs, *_ = env.step(act if num_envs == 1 else np.tile(act, (num_envs, 1)))
        cols = [b.field_index[f] for f in odometry]
        want = b.state[:, 0][:, cols].astype(np.float32)
        if odometry:
            _same(np.reshape(obs["odometry"], want.shape), want, "odometry")
        _same(np.reshape(obs["scan"], (num_envs, -1)), b.scans[:, 0], "scan")


def test_episode_buffers_and_their_errors(oval):
    from roboracer_arena.errors import ConfigError, InvalidArgumentError

    ep = _core.EpisodeBuffers(3, 2)
    want = {
        "reward": ((3,), np.float64),
        "terminated": ((3,), np.bool_),
        "truncated": ((3,), np.bool_),
        "elapsed": ((3,), np.int64),
        "vehicle_reward": ((3, 2), np.float64),
        "vehicle_terminated": ((3, 2), np.bool_),
        "progress": ((3, 2), np.float64),
        "wrong_way": ((3, 2), np.int8),
    }
    for name, (shape, dtype) in want.items():
        a = getattr(ep, name)
        assert a.shape == shape and a.dtype == dtype and a.flags.c_contiguous and not a.any(), name
        assert getattr(ep, name) is a  # the same array every time: views stay valid
    sim = _core.Simulator([oval.native()], 3, 2, {}, 0)
    state = np.zeros((3, 2, len(sim.state_fields)))
    events = np.zeros((3, 2), np.uint8)
    acts = np.zeros((3, 2, 2))
    with pytest.raises(InvalidArgumentError, match="set_episode"):
        sim.step(acts, 1, None, state, events, ep)
    cfg = {**ALL_TERMS, "wrong_way_distance": 1.0, "dt": 0.05}
    sim.set_episode(_core.EpisodeConfig(**cfg, collision_ends_episode=True, wrong_way_ends_episode=False))
    with pytest.raises(InvalidArgumentError, match="elements"):
        sim.step(acts, 1, None, state, events, _core.EpisodeBuffers(2, 2))
    sim.step(acts, 1, None, state, events, ep)
    assert (ep.elapsed == 1).all()
    with pytest.raises(InvalidArgumentError, match="dt"):
        _core.EpisodeConfig(**{**cfg, "dt": 0.0}, collision_ends_episode=True, wrong_way_ends_episode=False)
    with pytest.raises(ConfigError, match="vehicles"):  # the size budget, before allocating
        _core.EpisodeBuffers(2**40, 2**20)
