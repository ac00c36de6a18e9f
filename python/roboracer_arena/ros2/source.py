"""What the bridge and the recorders simulate: one world (env 0) of a native
``_core.Simulator`` with its vehicles, configuration, track and (when known) the map.

:func:`sim_source` accepts a track (map YAML path, ``OccupancyMap``, ``Track``, catalog
id), a ``RoboRacerArena-v0`` env (possibly wrapped; its simulator is shared, so reset the
env after the bridge stops) or a ``_core.Simulator`` (env 0 is used). The cars start as
the env starts them (:meth:`SimSource.reset`, see :mod:`.start`).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..config.sim import SimConfig
from ..envs.track_argument import resolve_tracks
from ..errors import ArenaError, ConfigError
from ..maps.corridor import extract_corridor
from ..maps.occupancy import load_map
from ..raceline.limits import preset
from ..raceline.plan import plan_raceline
from ..track.start_grid import start_spec
from .start import StartConfig

_log = logging.getLogger(__name__)


@dataclass
class SimSource:
    """A simulator world plus what the ROS 2 side needs to describe it."""

    sim: Any
    vehicles: int
    config: SimConfig
    centreline: np.ndarray
    occupancy_map: Any = None
    #: The track's raceline (M, 2) with the car's own limits, published on /global_path.
    raceline: np.ndarray | None = None
    #: The track is an open map (walls only): a fixed start must fit the car's footprint.
    open_map: bool = False
    name: str = "track"
    track_id: int = 0
    fields: dict[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.fields = {f: i for i, f in enumerate(self.sim.state_fields)}
        self.num_envs = int(self.sim.num_envs)

    def reset(self, poses: np.ndarray | None = None, speeds: np.ndarray | None = None) -> np.ndarray:
        """Reset env 0 as the env does (``reset_drawn`` with the start spec set on the
        simulator): the configured start, or the fixed ``poses`` (1, V, 3) / ``speeds``
        (1, V). Returns the start poses (1, V, 3)."""
        E, V = self.num_envs, self.vehicles
        ids, out_poses, out_speeds = np.zeros(E, np.int64), np.zeros((E, V, 3)), np.zeros((E, V))
        if poses is not None and E > 1:
            poses = np.broadcast_to(poses, (E, V, 3)).copy()
        if speeds is not None and E > 1:
            speeds = np.broadcast_to(speeds, (E, V)).copy()
        fixed_track = np.full(E, self.track_id, np.int64)  # the bridge shows one track
        self.sim.reset_drawn(np.ones(E, bool), ids, out_poses, out_speeds, fixed_track, poses, speeds)
        return out_poses[:1]


def raceline_xy(track: Any) -> np.ndarray | None:
    """The minimum-curvature raceline of ``track`` with the car's own limits (what
    ``roboracer-arena raceline`` plans), or None for an open map or a track it cannot plan
    (logged): the bridge then publishes no /global_path."""
    if getattr(track, "is_open", False):
        return None
    try:
        return np.asarray(plan_raceline(track, preset("car")).xy)
    except ArenaError as e:
        _log.warning("ros2 bridge: no raceline for %s (%s); /global_path is not published", track.name, e)
        return None


def check_open_map_starts(src: SimSource, poses: np.ndarray | None) -> None:
    """On an open map, refuse (exit 2, naming the map and its free space) a fixed start
    pose where the car's whole footprint does not fit, as ``build --start`` does
    (:func:`roboracer_arena.maps.car_fit.check_start` through the open-map extraction)."""
    if poses is None or not src.open_map or src.occupancy_map is None:
        return
    for x, y, yaw in np.asarray(poses, dtype=np.float64).reshape(-1, 3):
        extract_corridor(src.occupancy_map, start=(float(x), float(y), float(yaw)), open=True)


def _load_map(source: Any) -> Any:
    if isinstance(source, (str, Path)) and str(source).lower().endswith((".yaml", ".yml")):
        return load_map(source)
    if all(hasattr(source, a) for a in ("data", "resolution", "origin")):
        return source
    return None


def sim_source(
    env_or_sim: Any,
    cars: int | None = None,
    config: SimConfig | None = None,
    seed: int = 0,
    start: StartConfig | None = None,
) -> SimSource:
    """Normalise the bridge's first argument (see module docstring). The start: a track
    gets ``start`` (default: the grid start) set on its new simulator, as the env sets
    its own; an env keeps the start its config set; a bare simulator without a start
    spec starts at s = 0 of its centreline."""
    if isinstance(env_or_sim, _core.Simulator):
        sim = env_or_sim
        tid = int(sim.track_ids()[0])
        # A bare simulator has no Track to place a grid on: s = 0 of each centreline.
        sim.set_start_spec(
            start_spec([None] * int(sim.num_tracks), int(sim.vehicles_per_env), reset_poses="centreline_start")
        )
        return SimSource(
            sim,
            int(sim.vehicles_per_env),
            SimConfig.model_validate(sim.config),
            np.asarray(sim.centreline(tid)),
            track_id=tid,
        )
    inner = getattr(env_or_sim, "unwrapped", None)
    if inner is not None and isinstance(getattr(inner, "simulator", None), _core.Simulator):  # a RoboRacerArena-v0 env
        tid = int(np.ravel(inner.current_track_ids if hasattr(inner, "num_envs") else inner.current_track_id)[0])
        track = inner.tracks[tid]
        return SimSource(
            inner.simulator,
            int(inner.vehicles_per_env),
            inner.config.sim,
            np.asarray(track.centreline),
            occupancy_map=_load_map(track.source),
            raceline=raceline_xy(track),
            open_map=bool(track.is_open),
            name=track.name,
            track_id=tid,
        )

    track = resolve_tracks(env_or_sim)[0]
    n = 1 if cars is None else int(cars)
    if not 1 <= n <= 64:
        raise ConfigError(f"--cars must be in 1..64, got {cars}")
    cfg = config or SimConfig()
    sim = _core.Simulator([track.native()], 1, n, cfg, seed)
    sim.set_start_spec((start or StartConfig()).start_spec([track], n, cfg.vehicle.chassis_width))
    src = track.source if track.source is not None else env_or_sim
    return SimSource(
        sim,
        n,
        cfg,
        np.asarray(track.centreline),
        occupancy_map=_load_map(src),
        raceline=raceline_xy(track),
        open_map=bool(track.is_open),
        name=track.name,
    )
