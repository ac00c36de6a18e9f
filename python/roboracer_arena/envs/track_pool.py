"""A pool of tracks drawn per reset: ``track=`` as catalog patterns and weights.

Besides everything :func:`~roboracer_arena.envs.track_argument.resolve_tracks` accepts, ``track``
may hold

* catalog patterns: ``"generated:*"`` (kind, colon, shell pattern on the catalog id),
  ``"gen-l040-*"`` (a pattern on the id alone), besides ids and the selections
  ``"circuits"``, ``"recorded"``, ``"generated"``, ``"all"``;
* a dict ``{item: weight}``: each reset draws an item with probability proportional to
  its weight, then one of the item's tracks uniformly, e.g.
  ``{"generated:*": 3, "circuits": 1}``.

:func:`resolve_track_pool` returns the tracks and the probability of drawing each
(``None`` = uniform).
"""

from __future__ import annotations

import fnmatch
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..catalog.catalog_file import load_catalog
from ..errors import ConfigError
from ..track.drivable import MAP_SUFFIXES, Track
from .track_argument import resolve_catalog, resolve_tracks

#: Track used when ``track=`` is not given: a 40 m generated catalog track (1.2 m wide).
DEFAULT_TRACK = "gen-l040-w12-h2c1s1-clo-s0"

_KINDS = {"circuit": "circuit", "circuits": "circuit", "recorded": "recorded", "generated": "generated", "all": None}


def resolve_track_pool(
    track: Any, corridor_params: Any = None, reverse: bool = False, **reading: Any
) -> tuple[list[Track], np.ndarray | None]:
    """(tracks, probability of each or None for uniform) for ``track=`` (see module docstring),
    each in its racing direction, or the other way round with ``reverse=True``; ``reading``
    (``open``, ``unknown``) says how maps are read (:func:`.tracks.resolve_tracks`)."""
    if track is None:
        track = DEFAULT_TRACK
    if isinstance(track, Mapping):
        if not track:
            raise ConfigError("track= is an empty dict")
        tracks: list[Track] = []
        probs: list[float] = []
        for item, weight in track.items():
            w = float(weight)
            if not np.isfinite(w) or w < 0:
                raise ConfigError(f"track weight of {item!r} must be a finite number >= 0, got {weight!r}")
            group = resolve_tracks(_expand(item), corridor_params, reverse=reverse, **reading)
            tracks.extend(group)
            probs.extend([w / len(group)] * len(group))
        total = sum(probs)
        if total <= 0:
            raise ConfigError("track= weights sum to 0")
        return tracks, np.asarray(probs) / total
    items = list(track) if isinstance(track, (list, tuple)) else [track]
    expanded = [x for item in items for x in _expand_list(item)]
    return resolve_tracks(expanded, corridor_params, reverse=reverse, **reading), None


def check_track_names(track: Any) -> None:
    """Resolve every catalog id, selection and pattern named by ``track=`` (the keys of a
    weights dict too) without building a track, so a caller that builds the env elsewhere
    (Ray actors) raises the same typed error as the local env, before starting anything.
    Map paths, maps and tracks are left to the env."""
    if track is None:
        track = DEFAULT_TRACK
    items = list(track) if isinstance(track, (Mapping, list, tuple)) else [track]
    for item in items:
        for name in _expand_list(item):
            if isinstance(name, str) and not (Path(name).suffix.lower() in MAP_SUFFIXES or Path(name).is_file()):
                resolve_catalog(name)


def _expand_list(item: Any) -> list[Any]:
    out = _expand(item)
    return out if isinstance(out, list) else [out]


def _expand(item: Any) -> Any:
    """Catalog ids for a pattern string; anything else unchanged."""
    if not isinstance(item, str) or not any(c in item for c in "*?["):
        return item
    kind, _, pattern = item.rpartition(":") if ":" in item else ("all", "", item)
    if kind not in _KINDS:
        raise ConfigError(f"track pattern {item!r}: unknown kind {kind!r}; use one of {sorted(_KINDS)}")
    want = _KINDS[kind]
    ids = [
        e.id for e in load_catalog().entries if (want is None or e.kind == want) and fnmatch.fnmatchcase(e.id, pattern)
    ]
    if not ids:
        raise ConfigError(f"track pattern {item!r} matched no catalog track")
    return ids
