"""The grid starts at the source's start line, facing the racing direction (or the other
way with ``reverse=True``), in the single and the vector env."""

from __future__ import annotations

import gymnasium as gym
import numpy as np

import roboracer_arena  # noqa: F401  (registers the env)
from roboracer_arena.foundation.paths import tracks_dir
from roboracer_arena.maps.direction import read_centreline_file


def _heading(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.arctan2(b[1] - a[1], b[0] - a[0]))


def _angle_between(a: float, b: float) -> float:
    return abs((a - b + np.pi) % (2 * np.pi) - np.pi)


def test_grid_starts_at_the_source_start_facing_the_racing_direction():
    src = read_centreline_file(tracks_dir() / "circuits" / "monza" / "centreline.csv")  # source order, 0.5 m steps
    forward = _heading(src[0], src[4])
    for reverse, want in ((False, forward), (True, forward + np.pi)):
        env = gym.make("RoboRacerArena-v0", track="monza", reset_poses="grid", reverse=reverse)
        obs, _ = env.reset(seed=0)
        x, y, yaw = env.unwrapped.odometry_raw(obs)[0, :3]
        assert np.hypot(x - src[0, 0], y - src[0, 1]) < 1.0, (x, y, src[0])
        assert _angle_between(yaw, want) < 0.35, (reverse, yaw, want)
        env.close()


def test_vector_env_reverses_every_track():
    kw = dict(num_envs=2, vectorization_mode="vector_entry_point", track=["monza", "sao-paulo"])
    fwd = gym.make_vec("RoboRacerArena-v0", **kw)
    rev = gym.make_vec("RoboRacerArena-v0", reverse=True, **kw)
    assert [t.direction for t in fwd.unwrapped.tracks] == ["clockwise", "counterclockwise"]
    assert [t.direction for t in rev.unwrapped.tracks] == ["counterclockwise", "clockwise"]
    fwd.close()
    rev.close()
