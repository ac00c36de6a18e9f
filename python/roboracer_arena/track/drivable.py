"""A drivable track (:class:`Track`: collision walls and a closed centreline in its racing
direction) and the track of a ROS map file (:func:`track_from_map_path`, cached per file
version). A neutral module: the envs, the track library, the drivers and the ROS 2 bridge
all use it, and it imports none of them.
"""

from __future__ import annotations

import os
import weakref
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..errors import ConfigError, MapIOError
from ..maps.corridor import DEFAULT_PARAMS, extract_corridor
from ..maps.direction import TrackDirection, direction_for_map, direction_of, orient_to
from ..maps.direction import reverse as reverse_line

MAP_SUFFIXES = (".yaml", ".yml")
#: The build geometry's default wall height (the core's ``DEFAULT_WALL_HEIGHT_M``).
DEFAULT_WALL_HEIGHT_M: float = DEFAULT_PARAMS["wall_height_m"]


@dataclass(frozen=True, eq=False)
class Track:
    """A drivable closed track: collision walls and a closed centreline (map frame, m).

    ``centreline`` is what the simulator receives: its vertex order is the direction of
    travel and its first vertex the start of the grid (:attr:`direction`,
    :meth:`reversed`); :attr:`loop` is the same ring without a repeated closing vertex.
    """

    name: str
    walls: tuple[np.ndarray, ...]
    centreline: np.ndarray
    source: Any = field(default=None, repr=False)
    #: True when the first centreline vertex is the source's own start line (a circuit's
    #: or recorded map's centreline file), not wherever an extracted centreline begins.
    source_start: bool = field(default=False, repr=False)
    #: Height (m) of the collision walls the simulator extrudes: the build geometry's
    #: ``wall_height_m`` when the track comes from a map, so physics and USD walls agree.
    wall_height: float = field(default=DEFAULT_WALL_HEIGHT_M, repr=False)
    #: ``"track"`` (a closed centreline: laps and progress) or ``"open"`` (an open map,
    #: :meth:`open_map`: walls only; ``centreline`` is the start anchor).
    kind: str = field(default="track", repr=False)
    #: Why a map asked for as a track became an open map (the corridor error), if it did.
    open_reason: str | None = field(default=None, repr=False)

    #: Length (m) of an open map's start anchor (start point to the point it heads to).
    ANCHOR_M = 1.0

    @classmethod
    def open_map(
        cls,
        walls: Sequence[Any],
        start_pose: Sequence[float],
        name: str = "open map",
        wall_height: float = DEFAULT_WALL_HEIGHT_M,
    ) -> Track:
        """An open map (a floor plan, as F1TENTH Gym simulates any map): collision walls
        and a start pose (x, y, yaw), no reference path. Its ``centreline`` is the start
        *anchor*, two points: the start and :attr:`ANCHOR_M` ahead along the yaw. The
        simulator starts cars there (a grid lines up behind it) and counts no progress
        and no laps: :attr:`length` is 0."""
        x, y, yaw = (float(v) for v in start_pose)
        if not np.isfinite([x, y, yaw]).all():
            raise ConfigError(f"track {name!r}: start pose must be finite (x, y, yaw), got {(x, y, yaw)}")
        anchor = np.array([[x, y], [x + cls.ANCHOR_M * np.cos(yaw), y + cls.ANCHOR_M * np.sin(yaw)]])
        walls_ = _checked_walls(walls, name)
        return cls(name=name, walls=walls_, centreline=anchor, wall_height=float(wall_height), kind="open")

    @property
    def is_open(self) -> bool:
        """True for an open map (no lap, no progress)."""
        return self.kind == "open"

    @property
    def start_pose(self) -> tuple[float, float, float] | None:
        """An open map's start pose (x, y, yaw); None for a track."""
        if not self.is_open:
            return None
        (x, y), (bx, by) = self.centreline
        return float(x), float(y), float(np.arctan2(by - y, bx - x))

    @classmethod
    def from_polylines(
        cls, walls: Sequence[Any], centreline: Any, name: str = "track", wall_height: float = DEFAULT_WALL_HEIGHT_M
    ) -> Track:
        """A track from wall polylines ((N_i, 2) arrays), a closed centreline ((M, 2)) and
        the height of its collision walls (m)."""
        ws = _checked_walls(walls, name)
        c = np.ascontiguousarray(np.asarray(centreline, dtype=np.float64))
        if c.ndim != 2 or c.shape[1] != 2 or len(c) < 3 or not np.isfinite(c).all():
            raise ConfigError(f"track {name!r}: centreline must be a finite (M>=3, 2) array, got shape {c.shape}")
        return cls(name=name, walls=ws, centreline=c, wall_height=float(wall_height))

    @property
    def direction(self) -> str:
        """``"clockwise"`` or ``"counterclockwise"``: the way the centreline runs
        (``"open"`` for an open map)."""
        return "open" if self.is_open else direction_of(self.loop)

    def reversed(self) -> Track:
        """The same track driven the other way (same start vertex); an open map's start
        turned round."""
        if self.is_open:
            x, y, yaw = self.start_pose or (0.0, 0.0, 0.0)
            return self._with_centreline(Track.open_map(self.walls, (x, y, yaw + np.pi)).centreline)
        return self._with_centreline(reverse_line(self.centreline))

    def oriented(self, how: TrackDirection) -> Track:
        """The same track in ``how.direction``, starting at ``how.start`` when that lies on
        it; an open map has no direction and stays as it is."""
        if self.is_open:
            return self
        return self._with_centreline(orient_to(self.centreline, how), self.source_start or how.start is not None)

    def _with_centreline(self, centreline: np.ndarray, source_start: bool | None = None) -> Track:
        return replace(
            self,
            centreline=centreline,
            source_start=self.source_start if source_start is None else source_start,
        )

    @cached_property
    def loop(self) -> np.ndarray:
        """The centreline ring without a duplicated closing vertex, (M, 2)."""
        c = self.centreline
        return c[:-1] if len(c) > 3 and np.allclose(c[0], c[-1]) else c

    @cached_property
    def arclength(self) -> np.ndarray:
        """Cumulative arc length at each :attr:`loop` vertex, (M+1,) ending with the lap length."""
        return _core.cumulative_length(self.loop, closed=True)

    @property
    def length(self) -> float:
        """Lap length along the centreline (m); 0 for an open map."""
        return 0.0 if self.is_open else float(self.arclength[-1])

    @cached_property
    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of walls and centreline."""
        pts = np.vstack([*self.walls, self.centreline])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])

    @property
    def start_grid(self) -> _core.StartGrid:
        """This track's start geometry in the core (wall clearance, free run ahead, the grid
        start and its poses; :mod:`~roboracer_arena.track.start_grid` is its typed view), built on
        first use."""
        grid = _START_GRIDS.get(self)
        if grid is None:
            walls = [np.asarray(w, dtype=np.float64) for w in self.walls]
            line = np.asarray(self.centreline if self.is_open else self.loop, dtype=np.float64)
            grid = _core.StartGrid(walls, line, open_map=self.is_open, source_start=self.source_start)
            _START_GRIDS[self] = grid
        return grid

    def clearance(self, points: Any) -> np.ndarray:
        """Distance (m) from each of ``points`` ((N, 2)) to the nearest wall (walls are closed rings)."""
        return self.start_grid.clearance(np.atleast_2d(np.asarray(points, dtype=np.float64)))

    def corridor_width_near(self, x: float, y: float, radius: float = 1.0) -> float:
        """Narrowest corridor width (2 × wall clearance of the centreline) within ``radius`` of (x, y)."""
        c = self.loop
        near = c[np.hypot(c[:, 0] - x, c[:, 1] - y) <= radius]
        if len(near) == 0:
            near = c[[int(np.argmin(np.hypot(c[:, 0] - x, c[:, 1] - y)))]]
        return float(2.0 * self.clearance(near).min())

    def native(self) -> tuple[list[np.ndarray], np.ndarray, float]:
        """The ``(walls, centreline, wall_height)`` the native simulator takes."""
        return list(self.walls), self.centreline, self.wall_height


#: Each track's core start geometry (``Track.start_grid``), kept beside the Track rather
#: than in it so that a Track still pickles (the core object does not).
_START_GRIDS: weakref.WeakKeyDictionary[Track, _core.StartGrid] = weakref.WeakKeyDictionary()


def _checked_walls(walls: Sequence[Any], name: str) -> tuple[np.ndarray, ...]:
    """Wall polylines as finite (N >= 2, 2) float64 arrays, at least one."""
    ws = tuple(np.ascontiguousarray(np.asarray(w, dtype=np.float64)) for w in walls)
    for i, w in enumerate(ws):
        if w.ndim != 2 or w.shape[1] != 2 or len(w) < 2 or not np.isfinite(w).all():
            raise ConfigError(f"track {name!r}: wall {i} must be a finite (N>=2, 2) array, got shape {w.shape}")
    if not ws:
        raise ConfigError(f"track {name!r}: no walls")
    return ws


def track_from_map_path(
    path: str | os.PathLike[str],
    corridor_params: Any = None,
    direction: TrackDirection | None = None,
    open: bool | None = False,
    unknown: str = "occupied",
    close_gaps_m: float | None = None,
) -> Track:
    """The track of a ROS map YAML in its racing direction: ``direction`` if given, else
    the one :func:`~roboracer_arena.maps.direction.direction_for_map` finds beside the map.
    The corridor is extracted once per file version and parameters.

    ``open``: ``False`` a closed corridor or a ``CorridorError``; ``True`` the map as an
    open map (:meth:`Track.open_map`, walls only); ``None`` a track when the map has a
    closed corridor, else an open map (``Track.open_reason`` says why). ``unknown``: how
    an open map reads unknown cells (``"occupied"`` or ``"free"``). ``close_gaps_m``: close
    the openings of the walls up to this width first (:mod:`roboracer_arena.maps.gaps`; the
    track's ``source`` geometry lists them in ``closed_gaps``)."""
    p = Path(path).expanduser().resolve()
    try:
        st = p.stat()
    except OSError as e:
        raise MapIOError(f"{path}: cannot read map YAML: {e.strerror or e}") from e
    key = (str(p), st.st_mtime_ns, st.st_size, _params_key(corridor_params), open, unknown, close_gaps_m)
    cached = _TRACK_CACHE.get(key)
    if cached is None:
        geo = extract_corridor(p, corridor_params, open=open, unknown=unknown, close_gaps_m=close_gaps_m)
        cached = track_from_corridor(geo, p.stem, source=p if close_gaps_m is None else geo)
        if len(_TRACK_CACHE) >= _CACHE_SIZE:
            _TRACK_CACHE.pop(next(iter(_TRACK_CACHE)))
        _TRACK_CACHE[key] = cached
    return cached.oriented(direction if direction is not None else direction_for_map(p))


_CACHE_SIZE = 64
_TRACK_CACHE: dict[tuple[Any, ...], Track] = {}


def _params_key(params: Any) -> str | None:
    if params is None:
        return None
    if hasattr(params, "model_dump_json"):
        return str(params.model_dump_json())
    return repr(params)


def track_from_corridor(corridor: Any, name: str, source: Any = None) -> Track:
    """The :class:`Track` of a corridor geometry (``walls``, ``centreline``; an ``"open"``
    ``kind`` makes an open map from its ``start_pose``), named ``name``, its walls as tall
    as the geometry's ``params["wall_height_m"]`` (default :data:`DEFAULT_WALL_HEIGHT_M`).
    ``source`` (default: the geometry) is kept as ``Track.source``."""
    params = getattr(corridor, "params", None) or {}  # corridor-like objects may have none
    height = float(params.get("wall_height_m", DEFAULT_WALL_HEIGHT_M))
    if getattr(corridor, "kind", "track") == "open":
        t = Track.open_map(list(corridor.walls), corridor.start_pose, name=name, wall_height=height)
        object.__setattr__(t, "open_reason", getattr(corridor, "open_reason", None))
        object.__setattr__(t, "source", source if source is not None else corridor)
        return t
    t = Track.from_polylines(list(corridor.walls), corridor.centreline, name=name, wall_height=height)
    object.__setattr__(t, "source", source if source is not None else corridor)
    return t
