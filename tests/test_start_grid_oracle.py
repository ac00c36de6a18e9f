"""The core's start grid (``arena_core::sim::start_grid``, through ``start_grid.py``) gives
bit-identical results to the numpy algorithm it replaced (``start_grid_oracle.py``): the
documented ES curve and generalisation figures depend on the start poses. Circuits (one
with its source start line), recorded maps, generated tracks, an open map and a synthetic
stadium, each in both directions, plus source-start variants of tracks whose s = 0 is an
extracted one, so every branch of the choice is taken somewhere."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import start_grid_oracle as oracle
from roboracer_arena.envs.track_pool import resolve_track_pool
from roboracer_arena.track.start_grid import centreline_pose, free_run_ahead, grid_poses, grid_start_s

TRACKS = [
    "austin",  # circuit
    "oschersleben",  # circuit with its own start line (source_start)
    "gym-berlin",  # recorded
    "gym-vegas",
    "cps-f1-aut",
    "gen-l040-w12-h2c1s1-clo-s0",  # generated
    "gen-l100-w15-h2c1s1-clo-s0",
    "gym-ros-levine",  # open map
]
GRIDS = [(1, 1.0), (3, 0.7), (24, 2.5)]


@pytest.fixture(scope="module", params=TRACKS)
def track(request, sources):
    (t,), _ = resolve_track_pool(request.param)
    return t


def _variants(track):
    out = [track, track.reversed()]
    if not track.is_open and not track.source_start:
        out.append(dataclasses.replace(track, source_start=True))
    return out


def _same(a, b) -> bool:
    return np.array_equal(np.asarray(a), np.asarray(b))


def _check(t) -> None:
    for slots, spacing in GRIDS:
        s0 = oracle.grid_start_s(t, slots, spacing)
        assert grid_start_s(t, slots, spacing) == s0, (t.name, slots, spacing)
        assert _same(grid_poses(t, slots, spacing, 0.2), oracle.grid_poses(t, slots, spacing, 0.2, s0=s0))
    length = t.length
    for s in (0.0, 0.1, length / 3, length - 1e-9, length, length + 0.3, -0.4, -2 * length - 1.7):
        assert centreline_pose(t, s) == oracle.centreline_pose(t, s), (t.name, s)
        x, y, h = centreline_pose(t, s)
        for heading in (h, h + 1.0, h - 2.5):
            assert free_run_ahead(t, x, y, heading) == oracle.free_run_ahead(t, x, y, heading)
    assert _same(grid_poses(t, 4, 1.3, 0.25, s0=length * 0.6), oracle.grid_poses(t, 4, 1.3, 0.25, s0=length * 0.6))
    lo, hi = np.array(t.bounds[:2]), np.array(t.bounds[2:])
    pts = lo + np.random.default_rng(0).random((64, 2)) * (hi - lo)
    assert _same(t.clearance(pts), oracle.clearance(t, pts))


def test_the_core_grid_start_is_the_numpy_one_bit_for_bit(track):
    for t in _variants(track):
        _check(t)


def test_on_a_synthetic_stadium(oval):
    for t in _variants(oval):
        _check(t)
