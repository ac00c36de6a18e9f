"""Catalog entries as drivable tracks for the simulator (``track="monaco"``, ``"circuits"``).

A track is named by its catalog id. A grade-separated circuit (Suzuka's bridge) follows
its own centreline through the crossing, between the builder's walls: the planar map is
open there, so the builder's medial centreline would lap only one lobe of the figure 8.
Every other track uses the builder's corridor centreline.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from ..foundation.paths import sources_dir
from ..track.drivable import Track, track_from_map_path
from .catalog_file import Catalog, load_catalog
from .directions import entry_direction
from .entry import TrackEntry


def centreline_path(cat: Catalog, entry: TrackEntry, sources: Path | None = None) -> Path | None:
    """The entry's own centreline CSV (circuits and generated tracks), if it has one."""
    return cat.file_path(entry, entry.centreline, sources) if entry.centreline else None


def entry_track(cat: Catalog, entry: TrackEntry, sources: Path | None = None) -> tuple[Track, str]:
    """``(Track, what its centreline is)`` for one catalog entry."""
    yaml_path = cat.map_path(entry, sources)
    line_csv = centreline_path(cat, entry, sources)
    how = entry_direction(cat, entry, sources)
    if entry.grade_separated and line_csv is not None and line_csv.is_file():
        line = np.loadtxt(line_csv, delimiter=",", comments="#", ndmin=2)[:, :2]
        base = track_from_map_path(yaml_path)
        t = Track.from_polylines(base.walls, line, name=entry.id, wall_height=base.wall_height)
        return t.oriented(how), "circuit centreline"
    t = track_from_map_path(yaml_path, direction=how)
    return dataclasses.replace(t, name=entry.id), "corridor centreline"


def resolve_tracks(
    selection: str | list[str], catalog: str | Path | Catalog | None = None, sources: str | Path | None = None
) -> list[Track]:
    """Tracks (named by catalog id, each in the direction the catalog records) for an id,
    a list of ids, or a selection (``"circuits"``, ``"recorded"``, ``"generated"``, ``"all"``)."""
    cat = catalog if isinstance(catalog, Catalog) else load_catalog(catalog)
    opens = {o.id: o for o in cat.open_maps}
    if isinstance(selection, str) and (selection == "open" or selection in opens):
        return open_map_tracks(cat, list(opens) if selection == "open" else [selection], sources)
    return [entry_track(cat, e, Path(sources) if sources else None)[0] for e in cat.select_many(selection)]


def open_map_tracks(cat: Catalog, ids: list[str], sources: str | Path | None = None) -> list[Track]:
    """The catalog's open maps ``ids`` (``track="gym-ros-levine"``, or ``"open"`` for all)
    as open-map tracks from their recorded start, named by id."""
    base = sources_dir(sources, "open maps (recorded maps)")
    opens = {o.id: o for o in cat.open_maps}
    out = []
    for i in ids:
        o = opens[i]
        t = track_from_map_path(base / o.source_path, open=True)
        out.append(Track.open_map(t.walls, o.start, name=o.id, wall_height=t.wall_height))
    return out
