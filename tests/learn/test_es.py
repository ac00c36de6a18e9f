"""The evolution-strategies trainer (``roboracer_arena.learn.es``): the policy, the rank
shaping, seeding and learning on a packaged catalog track (no shared data needed)."""

import numpy as np
import pytest

from roboracer_arena.learn import ESConfig, MLPPolicy, train
from roboracer_arena.learn.es import _centred_ranks

TRACK = "gen-l070-w20-h0c0s0-ccw-s0"  # 70 m, 2 m wide: a few generations show progress


def test_policy_actions_are_in_range_and_one_parameter_vector_per_row():
    cfg = ESConfig(hidden=8, min_speed_frac=0.2, max_speed_frac=0.5)
    policy = MLPPolicy(5, 8, cfg)
    rng = np.random.default_rng(0)
    thetas = np.stack([policy.init(rng) * 20 for _ in range(4)])  # large weights saturate tanh
    x = rng.normal(size=(4, 5))
    a = policy.act(thetas, x)
    assert a.shape == (4, 2) and a.dtype == np.float32
    assert np.all(np.abs(a[:, 0]) <= 1) and np.all((a[:, 1] >= 0.2) & (a[:, 1] <= 0.5))
    for i in range(4):  # row i is policy i on input i, nothing mixed across rows
        assert np.allclose(policy.act(thetas[i], x[i : i + 1]), a[i : i + 1])


def test_centred_ranks_span_minus_half_to_half_in_rank_order():
    r = _centred_ranks(np.array([10.0, -3.0, 7.0, 100.0]))
    assert np.allclose(r, [1 / 6, -0.5, -1 / 6, 0.5])


def test_es_is_seeded():
    cfg = ESConfig(generations=2, pairs=4, episode_steps=20, seed=3)
    a, b = train(TRACK, cfg), train(TRACK, cfg)
    assert np.array_equal(a.theta, b.theta)
    c = train(TRACK, ESConfig(generations=2, pairs=4, episode_steps=20, seed=4))
    assert not np.array_equal(a.theta, c.theta)


@pytest.mark.slow
def test_es_return_improves_in_a_few_generations():
    cfg = ESConfig(generations=14, pairs=8, episode_steps=80, seed=1)
    result = train(TRACK, cfg)
    means = np.array([r["mean_return"] for r in result.curve])
    assert len(means) == 14 and result.env_steps > 0
    # Start poses differ per generation, so single generations are noisy: compare thirds.
    assert means[-3:].mean() > means[:3].mean() + 2.0, means
