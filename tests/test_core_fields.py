"""The core's plain-data pyclasses show their fields (issue 37): what was given to the
constructor can be read back as read-only attributes, named in ``_core.pyi``.

Plain data: ``EpisodeConfig`` (every keyword), ``StartSpec`` (every keyword),
``EpisodeBuffers`` (its arrays, which the simulator writes in place) and ``StartGrid``'s
flags (``open_map``, ``source_start``; its geometry is queried through its methods).
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from roboracer_arena import _core
from roboracer_arena.envs.env_config import EnvConfig, RewardConfig

EPISODE = {
    "progress": 1.5,
    "collision_penalty": 2.0,
    "stall_penalty": 0.25,
    "stall_speed": 0.5,
    "time_penalty": 0.125,
    "wrong_way_penalty": 3.0,
    "wrong_way_distance": 1.0,
    "dt": 0.05,
    "collision_ends_episode": True,
    "wrong_way_ends_episode": False,
    "max_steps": 400,
}


def _public(obj: object) -> set[str]:
    return {n for n in dir(obj) if not n.startswith("_")}


def test_the_episode_config_reads_back_every_keyword():
    cfg = _core.EpisodeConfig(**EPISODE)
    assert {k: getattr(cfg, k) for k in EPISODE} == EPISODE
    assert set(inspect.signature(_core.EpisodeConfig).parameters) == set(EPISODE) == _public(cfg)
    assert _core.EpisodeConfig(**{**EPISODE, "max_steps": None}).max_steps is None
    with pytest.raises(AttributeError):
        cfg.progress = 2.0  # type: ignore[misc]


def test_the_episode_config_mirrors_the_reward_config():
    """Every reward weight of the env config is an episode field of the same name, and the
    other episode fields are the env config's (``control_dt`` is ``dt``)."""
    assert set(RewardConfig.model_fields) <= set(EPISODE)
    rest = set(EPISODE) - set(RewardConfig.model_fields) - {"dt", "max_steps"}
    assert rest <= set(EnvConfig.model_fields), rest


def test_the_start_spec_reads_back_every_keyword():
    kw = {
        "random_s": True,
        "s0": [1.0, 2.0],
        "grid_spacing": 1.5,
        "grid_offset": 0.25,
        "lateral_noise": 0.1,
        "heading_noise": 0.05,
        "side_clearance": 0.3,
        "speed_noise": 0.5,
        "noise_std": (0.0, 0.01),
        "dropout": 0.1,
        "track_weights": [1.0, 3.0],
    }
    spec = _core.StartSpec(**kw)
    assert {k: getattr(spec, k) for k in kw} == kw
    assert set(inspect.signature(_core.StartSpec).parameters) == set(kw) == _public(spec)


@pytest.mark.parametrize("open_map,source_start", [(False, False), (False, True), (True, False)])
def test_the_start_grid_shows_how_it_was_built(open_map, source_start):
    walls, line = _core.stadium_track()
    centreline = line[:2] if open_map else line
    grid = _core.StartGrid(walls, centreline, open_map=open_map, source_start=source_start)
    assert (grid.open_map, grid.source_start) == (open_map, source_start)
    assert (grid.length == 0.0) == open_map
    with pytest.raises(AttributeError):
        grid.open_map = not open_map  # type: ignore[misc]


def test_the_episode_buffers_show_their_arrays():
    buf = _core.EpisodeBuffers(3, 2)
    shapes = {n: getattr(buf, n).shape for n in _public(buf)}
    assert shapes == {
        "reward": (3,),
        "terminated": (3,),
        "truncated": (3,),
        "elapsed": (3,),
        "vehicle_reward": (3, 2),
        "vehicle_terminated": (3, 2),
        "progress": (3, 2),
        "wrong_way": (3, 2),
    }
    assert buf.reward is buf.reward and not np.any(buf.progress)
