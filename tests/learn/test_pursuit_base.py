"""The residual policy's base is the reference pure pursuit: the vectorised
:class:`PursuitBase` gives the single-car driver's commands, for many cars on several
tracks at once."""

from __future__ import annotations

import numpy as np

from roboracer_arena.drivers import PurePursuitDriver, PurePursuitParams
from roboracer_arena.envs.track_argument import resolve_tracks
from roboracer_arena.learn.pursuit_base import PursuitBase


def test_pool_pursuit_matches_the_single_car_driver():
    tracks = resolve_tracks(["gen-l040-w12-h2c1s1-clo-s0", "gen-l070-w20-h0c0s0-ccw-s0"])
    params = PurePursuitParams()
    base = PursuitBase([t.centreline for t in tracks], params)
    rng = np.random.default_rng(0)
    ids, poses = [], []
    for tid, t in enumerate(tracks):
        c = t.centreline
        for i in rng.integers(0, len(c), 6):
            d = c[(i + 1) % len(c)] - c[i]
            poses.append(
                (
                    c[i, 0] + rng.normal(0, 0.1),
                    c[i, 1] + rng.normal(0, 0.1),
                    np.arctan2(d[1], d[0]) + rng.normal(0, 0.1),
                    rng.uniform(0, 4),
                )
            )
            ids.append(tid)
    x, y, yaw, v = np.array(poses).T
    steer, speed = base.act(np.array(ids), x, y, yaw, v)
    for k, (tid, p) in enumerate(zip(ids, poses)):
        want = PurePursuitDriver(tracks[tid].centreline, params).act_pose(*p)
        assert abs(steer[k] - want[0]) < 1e-9 and abs(speed[k] - want[1]) < 1e-9


def test_non_finite_poses_get_a_stop_command():
    t = resolve_tracks(["gen-l040-w12-h2c1s1-clo-s0"])[0]
    base = PursuitBase([t.centreline], PurePursuitParams())
    steer, speed = base.act([0, 0], [np.nan, 0.0], [0.0, np.inf], [0.0, 0.0], [1.0, 1.0])
    assert np.all(steer == 0) and np.all(speed == 0)
