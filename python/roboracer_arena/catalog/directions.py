"""The racing direction of every catalog entry (see :mod:`roboracer_arena.maps.direction`):
``direction``, ``direction_source`` (what decided it) and ``start`` (the start point in
the map frame, or None), derived from the source data beside each map."""

from __future__ import annotations

from pathlib import Path

from ..maps.direction import TrackDirection, direction_for_map
from .catalog_file import Catalog
from .entry import TrackEntry


def entry_direction(cat: Catalog, entry: TrackEntry, sources: Path | None = None) -> TrackDirection:
    """The direction the catalog records for ``entry``; for an entry without one (an old
    catalog), the one found beside its map."""
    if entry.direction:
        return TrackDirection(entry.direction, entry.start, entry.direction_source or "catalog")
    return direction_for_map(cat.map_path(entry, sources))


def derive_direction(
    cat: Catalog, entry: TrackEntry, sources: Path | None = None, generated: Path | None = None
) -> TrackEntry:
    """``entry`` with its direction fields derived from the data beside its map (a
    generated track's in ``generated`` when given: a stage of ``generated/``)."""
    yaml_path = cat.map_path(entry, sources)
    if generated is not None and entry.kind == "generated":
        yaml_path = generated / Path(entry.map).relative_to("generated")
    how = direction_for_map(yaml_path)
    if entry.kind == "circuit":
        what = f"point order of the source centreline {entry.source.path} (kept in {how.source})"
    elif entry.kind == "generated":
        what = f"requested direction (spec.json), as written in {how.source}"
    elif how.source == "default":
        what = "default: counter-clockwise (the source has no centreline or raceline for this map)"
    else:
        rel = Path(entry.map).parent / how.source
        what = f"point order of the source file {rel.as_posix()}"
    start = None if how.start is None else (round(how.start[0], 3), round(how.start[1], 3))
    return entry.with_fields(direction=how.direction, start=start, direction_source=what)


def annotate_directions(cat: Catalog, sources: Path | None = None, generated: Path | None = None) -> None:
    """Set ``direction``, ``direction_source`` and ``start`` on every entry."""
    cat.entries = [derive_direction(cat, e, sources, generated) for e in cat.entries]
