"""The track a ``raceline`` or ``drive --raceline`` command names: a ROS map YAML, or a
catalog id (the catalog's map, in the catalog's racing direction)."""

from __future__ import annotations

from pathlib import Path

from ..catalog.catalog_file import load_catalog
from ..catalog.entry_tracks import entry_track
from ..errors import InvalidArgumentError
from ..track.drivable import MAP_SUFFIXES, Track, track_from_map_path


def resolve_track(source: str | Path) -> tuple[Track, Path]:
    """``(track, map YAML path)`` for a map file or a catalog id."""
    p = Path(source)
    if p.suffix.lower() in MAP_SUFFIXES or p.exists():
        return track_from_map_path(p), p
    cat = load_catalog()
    try:
        entry = cat.get(str(source))
    except Exception as e:  # the catalog's own message names the id
        raise InvalidArgumentError(f"{source}: neither a map YAML nor a catalog id ({e})") from None
    track, _ = entry_track(cat, entry)
    return track, cat.map_path(entry)
