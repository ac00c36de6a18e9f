"""Resolve the ``track=`` argument of the environments into :class:`Track` objects.

``track`` may be one item or a list of items, each of which is

* a ROS map YAML path (``str`` / ``os.PathLike``): the corridor is extracted with
  :func:`roboracer_arena.maps.corridor.extract_corridor` and cached per (path, mtime, size);
* an ``OccupancyMap`` (anything with ``data``, ``resolution`` and ``origin``): extracted;
* a ``CorridorGeometry`` (anything with ``walls`` and ``centreline``): used as is;
* a :class:`Track` (e.g. :meth:`Track.from_polylines` for synthetic tracks);
* a catalog id or selection (a string that is not an existing file), resolved by the
  track catalog (``roboracer_arena.catalog``) through :func:`resolve_catalog`.

Every track is driven in its racing direction (see :mod:`roboracer_arena.maps.direction`): a
map path takes it from the centreline file beside the map, a catalog id from the catalog,
an object from its ``direction`` attribute (a string) when it has one; otherwise the
documented default (counter-clockwise). ``reverse=True`` drives every track the other way.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from .. import catalog
from ..errors import ConfigError
from ..maps.corridor import extract_corridor
from ..maps.direction import DEFAULT_DIRECTION, TrackDirection, check_direction, direction_for_map
from ..maps.occupancy import OccupancyMap
from ..track.drivable import MAP_SUFFIXES, Track, track_from_corridor, track_from_map_path

__all__ = ["Track", "resolve_catalog", "resolve_tracks", "track_from_map_path"]


def resolve_tracks(
    track: Any,
    corridor_params: Any = None,
    reverse: bool = False,
    open: bool | None = None,
    unknown: str = "occupied",
    close_gaps: float | None = None,
) -> list[Track]:
    """Resolve ``track=`` (one item or a list/tuple of items) to a non-empty list of tracks,
    each in its racing direction, or the other way round with ``reverse=True``.

    ``open`` and ``unknown`` say how a map is read (see :func:`track_from_map_path`): by
    default (``open=None``) a map with a closed corridor is a track and any other map an
    open map (walls only, no laps; ``Track.open_reason`` says why); ``open=True`` reads
    every map as an open map, ``open=False`` refuses maps without a closed corridor.
    ``close_gaps`` (m): close the openings of a map's walls up to this width first
    (:mod:`roboracer_arena.maps.gaps`), so that a leaking loop is a track."""
    if track is None:
        raise ConfigError("track= is required: a map YAML path, an OccupancyMap, a CorridorGeometry or a catalog id")
    items = list(track) if isinstance(track, (list, tuple)) else [track]
    if not items:
        raise ConfigError("track= is an empty list")
    out: list[Track] = []
    for item in items:
        out.extend(_resolve_one(item, corridor_params, open, unknown, close_gaps))
    return [t.reversed() for t in out] if reverse else out


def _resolve_one(
    item: Any,
    corridor_params: Any,
    open: bool | None = None,
    unknown: str = "occupied",
    close_gaps: float | None = None,
) -> list[Track]:
    if isinstance(item, Track):
        return [item]
    if isinstance(item, (str, os.PathLike)):
        path = Path(item)
        if path.suffix.lower() in MAP_SUFFIXES or path.is_file():
            return [track_from_map_path(path, corridor_params, open=open, unknown=unknown, close_gaps_m=close_gaps)]
        srcs = resolve_catalog(str(item))
        return [t for src in srcs for t in _resolve_one(src, corridor_params, open, unknown, close_gaps)]
    if hasattr(item, "walls") and hasattr(item, "centreline"):
        return [_with_own_direction(track_from_corridor(item, getattr(item, "name", None) or "corridor"), item)]
    if isinstance(getattr(item, "map", None), OccupancyMap) and hasattr(item, "direction"):  # an Acceptance
        t = track_from_corridor(_extract(item.map, corridor_params, open, unknown, close_gaps), item.spec.name)
        return [_with_own_direction(t, item)]
    if all(hasattr(item, a) for a in ("data", "resolution", "origin")):
        t = track_from_corridor(
            _extract(item, corridor_params, open, unknown, close_gaps), getattr(item, "name", None) or "map"
        )
        return [_with_own_direction(t, item)]
    raise ConfigError(
        f"cannot use {type(item).__name__} as a track: expected a map YAML path, an OccupancyMap, "
        "a generate_track Acceptance, a CorridorGeometry, a Track or a catalog id"
    )


def _extract(
    m: Any, corridor_params: Any, open: bool | None = None, unknown: str = "occupied", close_gaps: float | None = None
) -> Any:
    return extract_corridor(m, corridor_params, open=open, unknown=unknown, close_gaps_m=close_gaps)


def _with_own_direction(t: Track, item: Any) -> Track:
    """``t`` in the direction ``item`` declares (a ``direction`` string attribute; an
    optional ``start`` (x, y)), else in that of the map file it was loaded from (its
    ``path``, or its ``map``'s), else in the default direction."""
    declared = getattr(item, "direction", None)
    if declared is None:
        path = getattr(item, "path", None) or getattr(getattr(item, "map", None), "path", None)
        return t.oriented(direction_for_map(path) if path else TrackDirection(DEFAULT_DIRECTION))
    start = getattr(item, "start", None)
    return t.oriented(
        TrackDirection(
            check_direction(declared, f"{type(item).__name__}.direction"),
            None if start is None else (float(start[0]), float(start[1])),
            "object",
        )
    )


def resolve_catalog(selection: str) -> list[Any]:
    """Resolve a catalog id or selection (e.g. ``"circuits"``) to track sources.

    The track catalog (``roboracer_arena.catalog.resolve_tracks``) returns items this module
    accepts (map YAML paths, Tracks).
    """
    sources = list(catalog.resolve_tracks(selection))
    if not sources:
        raise ConfigError(f"catalog selection {selection!r} matched no tracks")
    return sources
