"""Normalised observations are the core's (``_core.ObservationNormaliser``, issue 37) and
the same bit for bit as the numpy code the env ran before (``observation_oracle.py``):
on random states, on NaN, infinite and huge values, at start headings of ±pi, for every
field order and frame stack, and for the envs a masked reset leaves alone."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from observation_oracle import ObservationOracle

from roboracer_arena._core import STATE_FIELDS, ObservationNormaliser
from roboracer_arena.envs.env_config import ODOMETRY_FIELDS, EnvConfig
from roboracer_arena.envs.observation import ObservationAssembler
from roboracer_arena.errors import ConfigError, InvalidArgumentError

FIELD_INDEX = {f: i for i, f in enumerate(STATE_FIELDS)}
E, V, B = 16, 3, 41
ORDERS = [ODOMETRY_FIELDS, ("vx", "vy", "yaw_rate", "steer"), ("yaw", "speed", "y", "x"), ("steer",)]


def config(fields=ODOMETRY_FIELDS, frame_stack=1, **kw) -> EnvConfig:
    obs = {"normalise": True, "odometry": fields, "frame_stack": frame_stack}
    return EnvConfig.build(None, observation={**obs, **kw.pop("observation", {})}, **kw)


def core_and_oracle(cfg: EnvConfig, frames: int = 1) -> tuple[ObservationAssembler, ObservationOracle]:
    asm = ObservationAssembler(cfg, FIELD_INDEX, E, V, B)
    assert asm.norm is not None
    return asm, ObservationOracle(cfg, FIELD_INDEX)


def core_odometry(asm: ObservationAssembler, state: np.ndarray, start: np.ndarray) -> np.ndarray:
    out = np.full((E, V, len(asm.columns)), 7.0, np.float32)
    asm.norm.odometry(state, start, out)
    return out


def assert_same_bits(got: np.ndarray, want: np.ndarray) -> None:
    """Equal bit for bit, NaN at the same places (its payload aside)."""
    assert got.dtype == want.dtype == np.float32 and got.shape == want.shape
    nan = np.isnan(want)
    assert np.array_equal(np.isnan(got), nan)
    assert np.array_equal(np.where(nan, 0, got).view(np.uint32), np.where(nan, 0, want).view(np.uint32))


def random_states(rng: np.random.Generator, magnitude: float = 60.0) -> tuple[np.ndarray, np.ndarray]:
    state = rng.uniform(-magnitude, magnitude, (E, V, len(STATE_FIELDS)))
    start = np.stack(
        [rng.uniform(-60, 60, (E, V)), rng.uniform(-60, 60, (E, V)), rng.uniform(-np.pi, np.pi, (E, V))], -1
    )
    return state, start


@pytest.mark.parametrize("fields", ORDERS)
@pytest.mark.parametrize(
    "kw",
    [{}, {"observation": {"position_scale": 3.7}, "sim": {"vehicle": {"max_speed": 5.3, "max_steer": 0.41}}}],
)
def test_odometry_is_the_numpy_reference_bit_for_bit(fields, kw):
    cfg = config(fields, **kw)
    asm, oracle = core_and_oracle(cfg)
    assert asm.columns == oracle.columns
    rng = np.random.default_rng(37)
    for magnitude in (0.5, 8.0, 60.0, 1e3, 1e9):
        for _ in range(5):
            state, start = random_states(rng, magnitude)
            assert_same_bits(core_odometry(asm, state, start), oracle.odometry(state, start))


def test_odometry_edge_cases_match_the_reference():
    asm, oracle = core_and_oracle(config())
    rng = np.random.default_rng(3)
    state, start = random_states(rng)
    specials = np.array([np.nan, np.inf, -np.inf, 1e300, -1e300, 1e-310, -0.0, 0.0, 3e38, 4e38])
    state.reshape(-1)[rng.choice(state.size, state.size // 3, replace=False)] = rng.choice(specials, state.size // 3)
    start[..., 2] = rng.choice([np.pi, -np.pi, np.nextafter(np.pi, 0), -np.nextafter(np.pi, 0), 0.0, -0.0], (E, V))
    with np.errstate(all="ignore"):  # (numpy warns of the NaN and overflow it is fed)
        want = oracle.odometry(state, start)
    got = core_odometry(asm, state, start)
    assert np.isnan(want).any() and np.isinf(want).any()  # the edge cases are exercised
    assert_same_bits(got, want)
    state[:] = np.nan  # an all-NaN state: every column NaN, none raises
    assert np.isnan(core_odometry(asm, state, start)).all()


@pytest.mark.parametrize("horizon", [3.3, 10.0, 30.0, 45.0])
def test_scans_are_the_numpy_reference_bit_for_bit(horizon):
    asm, oracle = core_and_oracle(config(observation={"horizon": horizon}))
    rng = np.random.default_rng(int(horizon * 10))
    scans = rng.uniform(0.0, 30.0, (E, V, B)).astype(np.float32)
    scans.reshape(-1)[:5] = [np.nan, np.inf, 0.0, 30.0, horizon]
    out = np.zeros_like(scans)
    asm.norm.scan(scans, out)
    assert_same_bits(out, oracle.scan(scans))


def test_only_the_newest_frame_of_the_masked_envs_is_written():
    asm, oracle = core_and_oracle(config())
    state, start = random_states(np.random.default_rng(5))
    out = np.full((E, V, 4, len(asm.columns)), 7.0, np.float32)
    mask = np.arange(E) % 3 == 0
    asm.norm.odometry(state, start, out, mask)
    assert_same_bits(out[mask, :, -1], oracle.odometry(state, start)[mask])
    assert (out[mask, :, :-1] == 7.0).all() and (out[~mask] == 7.0).all()


def test_bad_fields_shapes_and_scales_are_refused():
    ok = dict(position_scale=20.0, horizon=10.0, range_max=30.0, max_speed=7.0, max_steer=0.5)
    with pytest.raises(InvalidArgumentError, match="progress_s"):
        ObservationNormaliser(["x", "progress_s"], **ok)
    with pytest.raises(InvalidArgumentError, match="must be a str"):
        ObservationNormaliser(["x", 3], **ok)  # type: ignore[list-item]
    with pytest.raises(ConfigError, match="repeats"):
        ObservationNormaliser(["x", "x"], **ok)
    with pytest.raises(ConfigError, match="position_scale"):
        ObservationNormaliser(["x"], **{**ok, "position_scale": 0.0})
    n = ObservationNormaliser(["x", "yaw"], **ok)
    state, start = np.zeros((2, 1, len(STATE_FIELDS))), np.zeros((2, 1, 3))
    for bad_out in (
        np.zeros((2, 1, 2), np.float32),
        np.zeros((2, 1, 3), np.float64),
        np.zeros((2, 1, 6), np.float32)[..., ::2],
    ):
        with pytest.raises(InvalidArgumentError):
            n.odometry(state, start, bad_out)
    with pytest.raises(InvalidArgumentError, match="start_poses"):
        n.odometry(state, np.zeros((1, 1, 3)), np.zeros((2, 1, 3), np.float32))
    with pytest.raises(InvalidArgumentError, match="env_mask"):
        n.odometry(state, start, np.zeros((2, 1, 3), np.float32), np.ones(3, bool))


def test_a_vector_env_observes_the_reference_through_steps_stacks_and_masked_resets(oval):
    n = 3
    env = gym.make_vec(
        "RoboRacerArena-v0",
        num_envs=n,
        vectorization_mode="vector_entry_point",
        track=oval,
        sim={"lidar": {"num_beams": 61}},
        observation={"normalise": True, "odometry": ODOMETRY_FIELDS, "frame_stack": 3},
    )
    batch = env.unwrapped._batch
    oracle = ObservationOracle(env.unwrapped.config, batch.field_index)

    def newest_is_the_reference(obs):
        assert_same_bits(obs["odometry"][:, -1], oracle.odometry(batch.state, batch.start_pose)[:, 0])
        assert_same_bits(obs["scan"][:, -1], oracle.scan(batch.scans)[:, 0])

    obs, _ = env.reset(seed=1)
    newest_is_the_reference(obs)
    assert (obs["odometry"] == obs["odometry"][:, -1:]).all()  # the history is the first frame
    rng = np.random.default_rng(0)
    for i in range(25):
        prev = obs
        obs, *_ = env.step(rng.uniform([-0.4, 0.5], [0.4, 3.0], (n, 2)).astype(np.float32))
        newest_is_the_reference(obs)
        if i == 10:
            mask, stepped = np.array([False, True, False]), obs
            obs, _ = env.reset(options={"reset_mask": mask})
            newest_is_the_reference(obs)
            assert (obs["odometry"][1] == obs["odometry"][1, -1:]).all()
            assert np.array_equal(obs["odometry"][~mask], stepped["odometry"][~mask])  # the others untouched
        else:
            assert np.array_equal(obs["scan"][:, :-1], prev["scan"][:, 1:])  # shifted by one
    env.close()


def test_the_config_literal_names_the_fields_the_core_accepts():
    """``ObservationConfig.odometry``'s literal and the core's ``OdometryField`` agree: the
    first state fields, in state order; yaw gives two columns."""
    assert STATE_FIELDS[: len(ODOMETRY_FIELDS)] == ODOMETRY_FIELDS
    n = ObservationNormaliser(
        ODOMETRY_FIELDS, position_scale=20.0, horizon=10.0, range_max=30.0, max_speed=7.0, max_steer=0.5
    )
    assert n.columns == ("x", "y", "yaw_sin", "yaw_cos", *ODOMETRY_FIELDS[3:])
