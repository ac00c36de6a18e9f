"""Masked native resets (issue 14) and the simulator's input checks (issue 10):

* an env's episodes, lidar noise and dropout included, are bit-identical whatever the
  number of envs and whenever the other envs autoreset;
* the single env's scalar step path gives exactly what the batched path gives;
* bad reset inputs (pose 1e300, track id 0.7, wrong shapes) are refused with typed errors.
"""

from __future__ import annotations

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.envs.env_config import EnvConfig
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.envs.vector import RoboRacerVectorEnv
from roboracer_arena.errors import ConfigError, InvalidArgumentError
from roboracer_arena.track.start_grid import start_spec

NOISY = {
    "sim": {"lidar": {"num_beams": 61, "noise_std": 0.01}},
    "randomisation": {"lidar_noise_std": (0.02, 0.05), "lidar_dropout": 0.1},
    "start_lateral_noise": 0.2,
    "start_heading_noise": 0.05,
    "reset_poses": "random",
}


def _env0_run(oval, num_envs: int, steps: int = 80) -> tuple[list[np.ndarray], int]:
    """Env 0 driven gently; the others at full speed and full lock, so they crash and
    autoreset at their own times. Returns env 0's per-step arrays and the others' resets."""
    env = RoboRacerVectorEnv(num_envs=num_envs, track=oval, **NOISY)
    obs, _ = env.reset(seed=11)
    hist = [obs["scan"][0].copy(), obs["odometry"][0].copy()]
    resets = 0
    for t in range(steps):
        act = np.tile(np.array([0.5, 7.0], np.float32), (num_envs, 1))
        act[0] = [0.1 * np.sin(0.1 * t), 1.0]
        obs, rew, term, trunc, info = env.step(act)
        resets += int(np.count_nonzero((term | trunc)[1:]))
        hist += [obs["scan"][0].copy(), obs["odometry"][0].copy(), np.array([rew[0], term[0], trunc[0]])]
    return hist, resets


def test_env_streams_are_bit_exact_with_noise_across_num_envs_and_partial_resets(oval):
    alone, _ = _env0_run(oval, 1)
    crowded, resets = _env0_run(oval, 5)
    assert resets >= 4  # the other envs did autoreset, at their own times
    assert len(alone) == len(crowded)
    for a, b in zip(alone, crowded):
        assert a.tobytes() == b.tobytes()
    scans = np.array([h for h in alone if h.shape == (61,)])
    range_max = EnvConfig.build(None, **NOISY).sim.lidar.range_max
    assert 0.02 < np.mean(scans == np.float32(range_max)) < 0.3  # dropout (p = 0.1) reads range_max


def test_noise_streams_differ_between_envs_and_seeds(oval):
    a = RoboRacerVectorEnv(
        num_envs=2,
        track=oval,
        **{**NOISY, "reset_poses": "centreline_start", "start_lateral_noise": 0.0, "start_heading_noise": 0.0},
    )
    o, _ = a.reset(seed=1)
    assert not np.array_equal(o["scan"][0], o["scan"][1])  # same pose, own noise
    o2, _ = a.reset(seed=2)
    assert not np.array_equal(o["scan"][0], o2["scan"][0])
    o3, _ = a.reset(seed=1)
    assert np.array_equal(o["scan"], o3["scan"])


def test_single_env_scalar_path_equals_the_batched_path(oval):
    kw = {
        "sim": {"lidar": {"num_beams": 61}},
        "wrong_way_distance": 0.3,
        "collision_ends_episode": True,
        "reward": {"time_penalty": 0.5, "wrong_way_penalty": 0.25},
    }
    single = RoboRacerEnv(track=oval, **kw)
    vector = RoboRacerVectorEnv(num_envs=1, track=oval, autoreset_mode="Disabled", **kw)
    so, si = single.reset(seed=5)
    vo, vi = vector.reset(seed=5)
    rng = np.random.default_rng(0)
    for t in range(120):
        a = rng.uniform([-0.4, -3.0], [0.4, 7.0]).astype(np.float32)
        so, sr, sterm, strunc, si = single.step(a)
        vo, vr, vterm, vtrunc, vi = vector.step(a[None])
        for k in so:
            assert so[k].tobytes() == vo[k][0].tobytes(), (t, k)
        assert (sr, sterm, strunc) == (vr[0], vterm[0], vtrunc[0]), t
        for k in ("progress", "contact_wall", "wrong_way", "laps", "progress_s", "lap_time"):
            assert si[k] == vi[k][0], (t, k)
        if sterm:
            break
    assert sterm  # random actions crash before long: the contact path was compared too


def test_bad_reset_inputs_are_refused_with_typed_errors(oval):
    env = RoboRacerEnv(track=oval, sim={"lidar": {"num_beams": 61}})
    env.reset(seed=0)
    for bad in ([1e300, 0.0, 0.0], [0.0, float("nan"), 0.0], [0.0, 0.0, float("inf")], [0.0, -1e300, 0.0]):
        with pytest.raises(InvalidArgumentError, match="poses"):
            env.reset(options={"poses": bad})
    with pytest.raises(ConfigError, match="track_ids"):
        env.reset(options={"track_id": 0.7})
    with pytest.raises(ConfigError, match="track_ids"):
        env.reset(options={"track_id": True})
    with pytest.raises(ConfigError, match="poses"):
        env.reset(options={"poses": [0.0, 0.0]})
    env.step(np.zeros(2, np.float32))  # still usable after the refusals


def test_simulator_refuses_fractional_and_bool_track_ids(oval):
    sim = _core.Simulator([oval.native()], 2, 1, {"lidar": {"num_beams": 11}}, 0)
    for bad in ([0.7, 0], np.array([0.7, 0.0]), [True, 0], np.array([True, False])):
        with pytest.raises(InvalidArgumentError, match="track_ids"):
            sim.set_tracks(bad)
    with pytest.raises(InvalidArgumentError, match="track_ids"):
        sim.set_tracks([0])
    for bad in (0.7, True, 5, -1):
        with pytest.raises(InvalidArgumentError, match="track_id"):
            sim.centreline_pose(bad, 0.0)
    with pytest.raises(InvalidArgumentError, match="s must be finite"):
        sim.centreline_pose(0, float("nan"))
    sim.set_tracks(np.array([0, 0], np.int32))
    assert sim.centreline_pose(np.int64(0), 0.0) == sim.centreline_pose(0, 0.0)
    mask = np.ones(2, bool)
    with pytest.raises(InvalidArgumentError, match="poses"):
        sim.reset(mask, np.full((2, 1, 3), 1e300))
    state, events = np.zeros((2, 1, len(sim.state_fields))), np.zeros((2, 1), np.uint8)
    with pytest.raises(InvalidArgumentError, match="env_mask"):
        sim.observe(None, state, events, np.ones(3, bool))
    with pytest.raises(InvalidArgumentError, match="start spec"):
        sim.reset_drawn(mask, np.zeros(2, np.int64), np.zeros((2, 1, 3)), np.zeros((2, 1)))
    with pytest.raises(InvalidArgumentError, match="start spec: s0 has 2 entries, expected one per track"):
        sim.set_start_spec(start_spec([None, None], 1, reset_poses="centreline_start"))
    with pytest.raises(TypeError):
        sim.set_start_spec('{"random_s": true}')  # no JSON crosses the boundary


def test_simulator_integer_arguments_are_checked(oval):
    native = [oval.native()]
    for kwargs, name in (
        ({"seed": -1}, "seed"),
        ({"seed": 2**64}, "seed"),
        ({"seed": 1.5}, "seed"),
        ({"num_envs": -1}, "num_envs"),
        ({"num_envs": 1.5}, "num_envs"),
        ({"vehicles_per_env": True}, "vehicles_per_env"),
    ):
        args = {"num_envs": 1, "vehicles_per_env": 1, "config": {}, **kwargs}
        with pytest.raises(InvalidArgumentError, match=name):
            _core.Simulator(native, **args)
    sim = _core.Simulator(native, np.int64(1), 1, {}, 2**64 - 1)
    state, events = np.zeros((1, 1, len(sim.state_fields))), np.zeros((1, 1), np.uint8)
    for bad in (-1, 2.5, 10**6):
        with pytest.raises(InvalidArgumentError, match="substeps"):
            sim.step(np.zeros((1, 1, 2)), bad, None, state, events)
