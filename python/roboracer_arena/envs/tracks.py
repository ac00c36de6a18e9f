"""Resolve the ``track=`` argument of the environments into :class:`Track` objects.

``track`` may be one item or a list of items, each of which is

* a ROS map YAML path (``str`` / ``os.PathLike``): the corridor is extracted with
  :func:`roboracer_arena.corridor.extract_corridor` and cached per (path, mtime, size);
* an ``OccupancyMap`` (anything with ``data``, ``resolution`` and ``origin``): extracted;
* a ``CorridorGeometry`` (anything with ``walls`` and ``centreline``): used as is;
* a :class:`Track` (e.g. :meth:`Track.from_polylines` for synthetic tracks);
* a catalog id or selection (a string that is not an existing file), resolved by the
  track library (``roboracer_arena.library``) through :func:`resolve_catalog`.

Every track is driven in its racing direction (see :mod:`roboracer_arena.direction`): a
map path takes it from the centreline file beside the map, a catalog id from the catalog,
an object from its ``direction`` attribute (a string) when it has one; otherwise the
documented default (counter-clockwise). ``reverse=True`` drives every track the other way.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..direction import DEFAULT_DIRECTION, TrackDirection, check_direction, direction_for_map, direction_of, orient_to
from ..direction import reverse as reverse_line
from ..errors import ConfigError
from ..maps import OccupancyMap

MAP_SUFFIXES = (".yaml", ".yml")


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

    @classmethod
    def from_polylines(cls, walls: Sequence[Any], centreline: Any, name: str = "track") -> Track:
        """A track from wall polylines ((N_i, 2) arrays) and a closed centreline ((M, 2))."""
        ws = tuple(np.ascontiguousarray(np.asarray(w, dtype=np.float64)) for w in walls)
        c = np.ascontiguousarray(np.asarray(centreline, dtype=np.float64))
        for i, w in enumerate(ws):
            if w.ndim != 2 or w.shape[1] != 2 or len(w) < 2 or not np.isfinite(w).all():
                raise ConfigError(f"track {name!r}: wall {i} must be a finite (N>=2, 2) array, got shape {w.shape}")
        if c.ndim != 2 or c.shape[1] != 2 or len(c) < 3 or not np.isfinite(c).all():
            raise ConfigError(f"track {name!r}: centreline must be a finite (M>=3, 2) array, got shape {c.shape}")
        if not ws:
            raise ConfigError(f"track {name!r}: no walls")
        return cls(name=name, walls=ws, centreline=c)

    @property
    def direction(self) -> str:
        """``"clockwise"`` or ``"counterclockwise"``: the way the centreline runs."""
        return direction_of(self.loop)

    def reversed(self) -> Track:
        """The same track driven the other way (same start vertex)."""
        return Track(name=self.name, walls=self.walls, centreline=reverse_line(self.centreline), source=self.source,
                     source_start=self.source_start)

    def oriented(self, how: TrackDirection) -> Track:
        """The same track in ``how.direction``, starting at ``how.start`` when that lies on it."""
        return Track(name=self.name, walls=self.walls, centreline=orient_to(self.centreline, how), source=self.source,
                     source_start=self.source_start or how.start is not None)

    @cached_property
    def loop(self) -> np.ndarray:
        """The centreline ring without a duplicated closing vertex, (M, 2)."""
        c = self.centreline
        return c[:-1] if len(c) > 3 and np.allclose(c[0], c[-1]) else c

    @cached_property
    def arclength(self) -> np.ndarray:
        """Cumulative arc length at each :attr:`loop` vertex, (M+1,) ending with the lap length."""
        seg = np.linalg.norm(np.diff(np.vstack([self.loop, self.loop[:1]]), axis=0), axis=1)
        return np.concatenate([[0.0], np.cumsum(seg)])

    @property
    def length(self) -> float:
        """Lap length along the centreline (m)."""
        return float(self.arclength[-1])

    @cached_property
    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of walls and centreline."""
        pts = np.vstack([*self.walls, self.centreline])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])

    @cached_property
    def _segments(self) -> tuple[np.ndarray, np.ndarray]:
        """(starts (S, 2), deltas (S, 2)) of every wall edge, closing edges included."""
        rings = [np.vstack([w, w[:1]]) if len(w) > 2 and not np.allclose(w[0], w[-1]) else w for w in self.walls]
        starts = np.vstack([r[:-1] for r in rings])
        return starts, np.vstack([r[1:] for r in rings]) - starts

    def clearance(self, points: Any) -> np.ndarray:
        """Distance (m) from each of ``points`` ((N, 2)) to the nearest wall (walls are closed rings)."""
        p = np.atleast_2d(np.asarray(points, dtype=np.float64))
        a, d = self._segments
        l2 = np.maximum((d * d).sum(axis=1), 1e-18)
        out = np.empty(len(p))
        for i, q in enumerate(p):
            t = np.clip(((q - a) * d).sum(axis=1) / l2, 0.0, 1.0)
            out[i] = np.sqrt((((a + t[:, None] * d) - q) ** 2).sum(axis=1).min())
        return out

    def corridor_width_near(self, x: float, y: float, radius: float = 1.0) -> float:
        """Narrowest corridor width (2 × wall clearance of the centreline) within ``radius`` of (x, y)."""
        c = self.loop
        near = c[np.hypot(c[:, 0] - x, c[:, 1] - y) <= radius]
        if len(near) == 0:
            near = c[[int(np.argmin(np.hypot(c[:, 0] - x, c[:, 1] - y)))]]
        return float(2.0 * self.clearance(near).min())

    def native(self) -> tuple[list[np.ndarray], np.ndarray]:
        """The ``(walls, centreline)`` pair the native simulator takes."""
        return list(self.walls), self.centreline


def resolve_tracks(track: Any, corridor_params: Any = None, reverse: bool = False) -> list[Track]:
    """Resolve ``track=`` (one item or a list/tuple of items) to a non-empty list of tracks,
    each in its racing direction, or the other way round with ``reverse=True``."""
    if track is None:
        raise ConfigError("track= is required: a map YAML path, an OccupancyMap, a CorridorGeometry or a catalog id")
    items = list(track) if isinstance(track, (list, tuple)) else [track]
    if not items:
        raise ConfigError("track= is an empty list")
    out: list[Track] = []
    for item in items:
        out.extend(_resolve_one(item, corridor_params))
    return [t.reversed() for t in out] if reverse else out


def _resolve_one(item: Any, corridor_params: Any) -> list[Track]:
    if isinstance(item, Track):
        return [item]
    if isinstance(item, (str, os.PathLike)):
        path = Path(item)
        if path.suffix.lower() in MAP_SUFFIXES or path.is_file():
            return [track_from_map_path(path, corridor_params)]
        return [t for src in resolve_catalog(str(item)) for t in _resolve_one(src, corridor_params)]
    if hasattr(item, "walls") and hasattr(item, "centreline"):
        return [_with_own_direction(_from_corridor(item, getattr(item, "name", None) or "corridor"), item)]
    if isinstance(getattr(item, "map", None), OccupancyMap) and hasattr(item, "direction"):  # an Acceptance
        t = _from_corridor(_extract(item.map, corridor_params), item.spec.name)
        return [_with_own_direction(t, item)]
    if all(hasattr(item, a) for a in ("data", "resolution", "origin")):
        t = _from_corridor(_extract(item, corridor_params), getattr(item, "name", None) or "map")
        return [_with_own_direction(t, item)]
    raise ConfigError(
        f"cannot use {type(item).__name__} as a track: expected a map YAML path, an OccupancyMap, "
        "a generate_track Acceptance, a CorridorGeometry, a Track or a catalog id"
    )


def _extract(m: Any, corridor_params: Any) -> Any:
    from ..corridor import extract_corridor

    return extract_corridor(m, corridor_params)


def _with_own_direction(t: Track, item: Any) -> Track:
    """``t`` in the direction ``item`` declares (a ``direction`` string attribute; an
    optional ``start`` (x, y)), else in that of the map file it was loaded from (its
    ``path``, or its ``map``'s), else in the default direction."""
    declared = getattr(item, "direction", None)
    if declared is None:
        path = getattr(item, "path", None) or getattr(getattr(item, "map", None), "path", None)
        return t.oriented(direction_for_map(path) if path else TrackDirection(DEFAULT_DIRECTION))
    start = getattr(item, "start", None)
    return t.oriented(TrackDirection(check_direction(declared, f"{type(item).__name__}.direction"),
                                     None if start is None else (float(start[0]), float(start[1])), "object"))


def track_from_map_path(path: str | os.PathLike[str], corridor_params: Any = None,
                        direction: TrackDirection | None = None) -> Track:
    """The track of a ROS map YAML in its racing direction: ``direction`` if given, else
    the one :func:`~roboracer_arena.direction.direction_for_map` finds beside the map.
    The corridor is extracted once per file version and parameters."""
    p = Path(path).expanduser().resolve()
    try:
        st = p.stat()
    except OSError as e:
        from ..errors import MapIOError

        raise MapIOError(f"{path}: cannot read map YAML: {e.strerror or e}") from e
    key = (str(p), st.st_mtime_ns, st.st_size, _params_key(corridor_params))
    cached = _TRACK_CACHE.get(key)
    if cached is None:
        from ..corridor import extract_corridor

        cached = _from_corridor(extract_corridor(p, corridor_params), p.stem, source=p)
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


def _from_corridor(corridor: Any, name: str, source: Any = None) -> Track:
    t = Track.from_polylines(list(corridor.walls), corridor.centreline, name=name)
    object.__setattr__(t, "source", source if source is not None else corridor)
    return t


def resolve_catalog(selection: str) -> list[Any]:
    """Resolve a catalog id or selection (e.g. ``"circuits"``) to track sources.

    Hook for the track library: ``roboracer_arena.library.resolve_tracks(selection)`` must
    return a list of items this module accepts (map YAML paths, OccupancyMaps, CorridorGeometry).
    """
    try:
        from .. import library  # type: ignore[attr-defined]
    except ImportError:
        library = None
    resolver = getattr(library, "resolve_tracks", None)
    if resolver is None:
        raise ConfigError(
            f"track {selection!r} is not a map file; catalog ids need the track library "
            "(roboracer_arena.library), which is not installed in this build"
        )
    sources = list(resolver(selection))
    if not sources:
        raise ConfigError(f"catalog selection {selection!r} matched no tracks")
    return sources
