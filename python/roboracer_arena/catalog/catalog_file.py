"""The track catalog (``tracks/catalog.json``): one entry per track with its kind
(``recorded`` | ``circuit`` | ``generated``), provenance (repository, commit, licence),
scale, resolution, lap length, width statistics, minimum radius, raster size, the
sha256 of its map image, and notes; plus the recorded maps left out, with the reason.

Project-derived maps live under ``tracks/`` (paths relative to it); recorded maps are
referenced by their path relative to the sources directory and never copied.
"""

from __future__ import annotations

import hashlib
import json
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError

from ..errors import InvalidArgumentError, MapIOError
from ..foundation.fileio import atomic_write_text, file_lock, read_json, validate_model
from ..foundation.paths import PACKAGE_DIR, sources_dir, tracks_dir
from ..foundation.strict import format_validation_error
from .entry import CatalogMeta, Kind, LeftOut, OpenMap, TrackEntry

M = TypeVar("M", bound=BaseModel)
T = TypeVar("T")
KINDS = ("recorded", "circuit", "generated")
SCHEMA = "roboracer-arena track catalog v1"
#: Selections accepted by :func:`resolve` besides single ids.
SELECTIONS = {
    "all": KINDS,
    "recorded": ("recorded",),
    "circuits": ("circuit",),
    "circuit": ("circuit",),
    "generated": ("generated",),
}

#: Licence of each source folder (from ../shared/track-sources/SOURCES.md).
LICENCES = {
    "tumftm-racetrack-database": "LGPL-3.0",
    "bacinger-f1-circuits": "MIT",
    "f1tenth-racetracks": "GPL-3.0",
    "f1tenth-gym": "MIT",
    "f1tenth-gym-ros": "MIT",
    "f1tenth-simulator": "MIT (declared in package.xml; no LICENSE file)",
    "cps-tuwien-f1tenth-maps": "MIT (declared in package.xml; no LICENSE file; f1_* traced from Wikimedia Commons SVGs, licences unchecked)",
    "bdevan5-f1tenth-benchmarks": "Apache-2.0",
}


def default_tracks_dir() -> Path:
    """``$ROBORACER_ARENA_TRACKS``, else the catalog shipped in the package."""
    return tracks_dir()


def provenance(sources: Path, folder: str) -> dict[str, str]:
    """Repository URL, commit and licence of a source folder (its PROVENANCE.txt)."""
    text = ""
    try:
        text = (sources / folder / "PROVENANCE.txt").read_text(encoding="utf-8")
    except OSError:
        pass
    repo = re.search(r"^Source:\s*(\S+)", text, re.M)
    commit = re.search(r"\b([0-9a-f]{40})\b", text)
    return {
        "repository": repo.group(1) if repo else "",
        "commit": commit.group(1) if commit else "",
        "licence": LICENCES.get(folder, "unknown"),
    }


def sha256_file(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def count_kinds(entries: Sequence[TrackEntry]) -> dict[Kind, int]:
    """Entries per kind, in the catalog's order of kinds."""
    kinds: tuple[Kind, ...] = ("circuit", "recorded", "generated")
    return {k: sum(e.kind == k for e in entries) for k in kinds}


@dataclass
class Catalog:
    """The loaded catalog. ``entries`` keeps file order; ``path`` is where it was read.
    ``meta`` is the file's header (schema, counts, how it was built)."""

    entries: list[TrackEntry]
    meta: CatalogMeta
    left_out: list[LeftOut] = field(default_factory=list)
    path: Path | None = None
    #: Left-out recorded maps offered as open maps (``library.open_maps``).
    open_maps: list[OpenMap] = field(default_factory=list)

    def get(self, track_id: str) -> TrackEntry:
        for e in self.entries:
            if e.id == track_id:
                return e
        close = [e.id for e in self.entries if track_id.lower() in e.id][:5]
        hint = f"; did you mean {', '.join(close)}?" if close else "; see 'roboracer-arena tracks list'"
        raise InvalidArgumentError(f"unknown track id {track_id!r}{hint}")

    def select(self, selection: str) -> list[TrackEntry]:
        """Entries of a selection (``all``, ``circuits``, ``recorded``, ``generated``) or one id."""
        kinds = SELECTIONS.get(selection)
        if kinds is not None:
            return [e for e in self.entries if e.kind in kinds]
        return [self.get(selection)]

    def select_many(self, selections: str | list[str]) -> list[TrackEntry]:
        """Entries of one selection or id, or of each in a list, in that order."""
        items = [selections] if isinstance(selections, str) else selections
        return [e for item in items for e in self.select(item)]

    def file_path(self, entry: TrackEntry, rel: str, sources: Path | None = None, tracks: Path | None = None) -> Path:
        """Absolute path of a file ``rel`` of ``entry`` (its map, centreline, spec): under the
        sources directory for a recorded map, else under the catalog's directory."""
        if entry.kind == "recorded":
            return sources_dir(sources, f"recorded map {entry.id!r}") / rel
        base = Path(tracks) if tracks else (self.path.parent if self.path else default_tracks_dir())
        return base / rel

    def map_path(self, entry: TrackEntry, sources: Path | None = None, tracks: Path | None = None) -> Path:
        """Absolute path of an entry's map YAML."""
        return self.file_path(entry, entry.map, sources, tracks)

    def counts(self) -> dict[Kind, int]:
        """Entries per kind, in the catalog's order of kinds."""
        return count_kinds(self.entries)

    def to_json(self) -> str:
        """The catalog file's text (header, count, tracks, left-out maps)."""
        doc = {
            **self.meta.to_json_dict(),
            "count": len(self.entries),
            "tracks": [e.to_json_dict() for e in self.entries],
            "left_out": [lo.to_json_dict() for lo in self.left_out],
        }
        if self.open_maps:
            doc["open_maps"] = [o.to_json_dict() for o in self.open_maps]
        return json.dumps(doc, indent=2) + "\n"


class CatalogShape(BaseModel):
    """The catalog file's outline, checked before its entries: an object whose
    ``tracks``, ``left_out`` and ``open_maps`` are lists of objects (each entry is then
    read as its own model, so an error names the entry)."""

    model_config = ConfigDict(extra="allow")

    tracks: list[dict[str, Any]] = []
    left_out: list[dict[str, Any]] = []
    open_maps: list[dict[str, Any]] = []
    count: int | None = None


def load_catalog(path: str | Path | None = None) -> Catalog:
    """Read ``tracks/catalog.json`` (or ``path``) with the package's one JSON reader
    (regular file, 64 MiB, bounded nesting); a document of the wrong shape or an entry
    that does not fit :class:`TrackEntry` is a :class:`MapIOError` naming the file and
    the entry or field."""
    p = Path(path) if path else default_tracks_dir() / "catalog.json"
    doc = read_json(p, "track catalog", MapIOError, max_bytes=64 * 2**20)
    if not isinstance(doc, dict):
        raise MapIOError(f"{p}: track catalog must be a JSON object, not {_json_kind(doc)}")
    shape = validate_model(doc, CatalogShape, p, "track catalog", MapIOError)
    meta = _parse(
        p,
        "header",
        CatalogMeta,
        {k: v for k, v in doc.items() if k not in ("tracks", "left_out", "count", "open_maps")},
    )
    entries = [_parse(p, f"tracks[{_name(x, i)!r}]", TrackEntry, x) for i, x in enumerate(shape.tracks)]
    left_out = [_parse(p, f"left_out[{_name(x, i)!r}]", LeftOut, x) for i, x in enumerate(shape.left_out)]
    opens = [_parse(p, f"open_maps[{_name(x, i)!r}]", OpenMap, x) for i, x in enumerate(shape.open_maps)]
    return Catalog(entries=entries, left_out=left_out, meta=meta, path=p, open_maps=opens)


def _json_kind(doc: Any) -> str:
    return {list: "an array", str: "a string", bool: "a boolean", type(None): "null"}.get(
        type(doc), "a number" if isinstance(doc, (int, float)) else type(doc).__name__
    )


def writable_catalog(path: str | Path | None, flag: str = "--catalog") -> Path:
    """The catalog file a job that records results may write: given explicitly (``flag``)
    and outside the installed package (whose catalog is package data and never written).
    Raises :class:`InvalidArgumentError` (CLI exit 2) otherwise, before any work."""
    if path is None:
        raise InvalidArgumentError(
            f"{flag} FILE is required to record results: the default catalog is the installed package's "
            f"({default_tracks_dir() / 'catalog.json'}), which is never written; copy it and pass the copy"
        )
    p = Path(path)
    try:
        inside = p.resolve().is_relative_to(PACKAGE_DIR)
    except OSError:
        inside = False
    if inside:
        raise InvalidArgumentError(
            f"{p}: is inside the installed package ({PACKAGE_DIR}), which is never written; copy the catalog "
            f"elsewhere and pass the copy as {flag}"
        )
    return p


def update_catalog(path: str | Path, change: Callable[[Catalog], T]) -> T:
    """Read the catalog at ``path`` afresh, apply ``change`` to it and write it back
    atomically, all under :func:`~roboracer_arena.foundation.fileio.file_lock`: concurrent writers
    (two ``tracks verify --update-catalog`` runs on one library) take turns, and each
    merges its change into what the other wrote, so no change is lost. Returns what
    ``change`` returns."""
    p = Path(path)
    with file_lock(p):
        cat = load_catalog(p)
        out = change(cat)
        atomic_write_text(p, cat.to_json())
    return out


def _name(item: Any, i: int) -> Any:
    name = item.get("id", i) if isinstance(item, dict) else i
    return name if not isinstance(name, str) or len(name) <= 60 else f"{name[:59]}…"


def _parse(path: Path, where: str, model: type[M], item: Any) -> M:
    """``item`` as ``model``; else a :class:`MapIOError` naming the file, ``where`` and the field."""
    try:
        return model.model_validate(item)
    except ValidationError as e:
        raise MapIOError(f"{path}: {where}.{format_validation_error(e, top='(entry)')}") from None


def resolve(
    id_or_selection: str | list[str], catalog: str | Path | Catalog | None = None, sources: str | Path | None = None
) -> list[Path]:
    """Map YAML paths for a catalog id, a list of ids, or a selection (``"circuits"``,
    ``"generated"``, ``"recorded"``, ``"all"``). Raises ``InvalidArgumentError`` for an
    unknown id."""
    cat = catalog if isinstance(catalog, Catalog) else load_catalog(catalog)
    return [cat.map_path(e, Path(sources) if sources else None) for e in cat.select_many(id_or_selection)]
