"""What the bridge and the recorders simulate: one world (env 0) of a native
``_core.Simulator`` with its vehicles, configuration, track and (when known) the map.

:func:`sim_source` accepts a track (map YAML path, ``OccupancyMap``, ``Track``, catalog
id), a ``RoboRacerArena-v0`` env (possibly wrapped; its simulator is shared, so reset the
env after the bridge stops) or a ``_core.Simulator`` (env 0 is used).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ConfigError
from ..sim_config import SimConfig


@dataclass
class SimSource:
    """A simulator world plus what the ROS 2 side needs to describe it."""

    sim: Any
    vehicles: int
    config: SimConfig
    centreline: np.ndarray
    occupancy_map: Any = None
    name: str = "track"
    track_id: int = 0
    fields: dict[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.fields = {f: i for i, f in enumerate(self.sim.state_fields)}
        self.num_envs = int(self.sim.num_envs)

    def grid_poses(self, spacing: float = 1.0, offset: float = 0.2) -> np.ndarray:
        """Start poses (E, V, 3): car 0 at the centreline start (s = 0), the others in a
        staggered two-wide grid behind it (as the envs' ``reset_poses="grid"``)."""
        length = self.sim.centreline_length(self.track_id)
        poses = np.zeros((self.num_envs, self.vehicles, 3))
        for k in range(self.vehicles):
            s = -k * spacing  # an open map's anchor has length 0: the grid lines up behind its start
            x, y, yaw = self.sim.centreline_pose(self.track_id, s % length if length > 0 else s)
            lat = 0.0 if self.vehicles == 1 else (offset if k % 2 == 0 else -offset)
            poses[:, k] = (x - lat * math.sin(yaw), y + lat * math.cos(yaw), yaw)
        return poses


def _load_map(source: Any) -> Any:
    if isinstance(source, (str, Path)) and str(source).lower().endswith((".yaml", ".yml")):
        from ..maps import load_map

        return load_map(source)
    if all(hasattr(source, a) for a in ("data", "resolution", "origin")):
        return source
    return None


def sim_source(env_or_sim: Any, cars: int | None = None, config: SimConfig | None = None, seed: int = 0) -> SimSource:
    """Normalise the bridge's first argument (see module docstring)."""
    from .. import _core

    if isinstance(env_or_sim, _core.Simulator):
        sim = env_or_sim
        tid = int(sim.track_ids()[0])
        return SimSource(
            sim,
            int(sim.vehicles_per_env),
            SimConfig.model_validate(json.loads(sim.config_json)),
            np.asarray(sim.centreline(tid)),
            track_id=tid,
        )
    inner = getattr(env_or_sim, "unwrapped", None)
    batch = getattr(inner, "_batch", None)
    if inner is not None and batch is not None and hasattr(batch, "sim"):  # a RoboRacerArena-v0 env
        tid = int(batch.track_ids[0])
        track = inner.tracks[tid]
        return SimSource(
            batch.sim,
            int(batch.vehicles),
            inner.config.sim,
            np.asarray(track.centreline),
            occupancy_map=_load_map(track.source),
            name=track.name,
            track_id=tid,
        )
    from ..envs.tracks import resolve_tracks

    track = resolve_tracks(env_or_sim)[0]
    n = 1 if cars is None else int(cars)
    if not 1 <= n <= 64:
        raise ConfigError(f"--cars must be in 1..64, got {cars}")
    cfg = config or SimConfig()
    sim = _core.Simulator([track.native()], 1, n, cfg.to_json(), seed)
    src = track.source if track.source is not None else env_or_sim
    return SimSource(sim, n, cfg, np.asarray(track.centreline), occupancy_map=_load_map(src), name=track.name)
