"""One track of the catalog (``tracks/catalog.json``) as a typed, frozen model.

The fields are declared in the order the catalog writes them, and an entry is written
with only the fields it was given (``exclude_unset``), so the shipped catalog loads and
writes back byte for byte (``tests/library/test_entry.py``). An unknown key is refused:
a field added to the catalog is added here first.
"""

from __future__ import annotations

import math
from pathlib import PurePosixPath
from typing import Any, Literal

from pydantic import ConfigDict, Field, field_validator, model_validator

from ..foundation.frozen_model import FrozenModel

Kind = Literal["recorded", "circuit", "generated"]
Status = Literal["pass", "FAIL", "not run"]

#: Track ids: printed by the CLI and used as folder names, so a safe character set only
#: (no newline, escape code, slash or leading dot).
ID_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,119}$"
#: Largest raster side (px) and resolution (m/cell) a catalog entry may declare (the map
#: loader's own limits are the real gate; these keep a tampered entry from lying).
MAX_RASTER_PX = 1 << 16


class Source(FrozenModel):
    """Where a track comes from: repository, commit and licence of its source data, the
    source file's path, and how the project derived the map from it (if it did)."""

    repository: str
    commit: str = ""
    licence: str
    path: str
    derived: str | None = None


class Raster(FrozenModel):
    """Size of the map image in cells."""

    width_px: int = Field(ge=1, le=MAX_RASTER_PX)
    height_px: int = Field(ge=1, le=MAX_RASTER_PX)


class LeftOut(FrozenModel):
    """A recorded map the catalog does not offer, with the reason."""

    id: str = Field(pattern=ID_PATTERN)
    source_path: str
    reason: str


class OpenMap(FrozenModel):
    """A recorded map the catalog offers as an *open map* (walls only, no lap; see
    ``corridor.extract_open``): not a track for ``reason`` (its ``left_out`` reason), yet
    simulated the way F1TENTH Gym does. ``start`` is the default start pose (x, y, yaw:
    the free cell farthest from the walls) and ``start_clearance_m`` its clearance;
    ``narrowest_gap_m`` the corridor's narrowest free width, when it has a closed one,
    beside the car's ``car_width_m``."""

    id: str
    source_path: str
    reason: str
    resolution_m: float
    raster: Raster
    start: tuple[float, float, float]
    start_clearance_m: float
    narrowest_gap_m: float | None = None
    car_width_m: float | None = None


class SweepCounts(FrozenModel):
    """A ``tracks generate --sweep`` catalog's sweep: its grid and the run's counts."""

    sweep: dict[str, Any]
    count: int
    requests: int
    accepted: int
    rejected: int
    failed: int


class CatalogMeta(FrozenModel):
    """The catalog file's header: schema, builder, where paths are relative to, entries
    per kind, and the build's seconds (``tracks catalog``) or sweep (``tracks generate``)."""

    model_config = ConfigDict(serialize_by_alias=True, validate_by_name=True)

    catalog_schema: str = Field(alias="schema")  # (``schema`` is a pydantic method name)
    built_with: str
    sources_note: str
    counts: dict[Kind, int]
    seconds: float | None = None
    sweep: SweepCounts | None = None


class TrackEntry(FrozenModel):
    """One catalog track. Lengths in metres; ``map`` (and ``centreline``, ``spec``) are
    relative to the sources directory for recorded maps, else to the catalog's directory.
    ``direction``, ``start`` and ``direction_source`` come from
    :mod:`~roboracer_arena.catalog.directions`; ``verified`` and ``drive`` from
    ``tracks verify --update-catalog``."""

    id: str = Field(pattern=ID_PATTERN)
    name: str
    kind: Kind
    source: Source
    scale: float | None = Field(gt=0, allow_inf_nan=False)
    resolution_m: float = Field(gt=0, le=1.0, allow_inf_nan=False)
    lap_length_m: float = Field(gt=0, le=100_000, allow_inf_nan=False)
    width_mean_m: float = Field(gt=0, le=100, allow_inf_nan=False)
    width_min_m: float = Field(gt=0, le=100, allow_inf_nan=False)
    min_radius_m: float = Field(ge=0, le=100_000, allow_inf_nan=False)
    raster: Raster
    sha256: str = Field(pattern=r"^[0-9a-f]{64}$")
    map: str
    centreline: str | None = None
    spec: str | None = None
    seed: int | None = None
    grade_separated: bool = False
    narrowed_fraction: float | None = None
    length_error: float | None = None
    notes: list[str] = []
    direction: Literal["clockwise", "counterclockwise"] | None = None
    start: tuple[float, float] | None = None
    direction_source: str | None = None
    verified: dict[str, Status] | None = None
    drive: str | None = None

    @field_validator("map", "centreline", "spec")
    @classmethod
    def _inside_the_library(cls, v: str | None) -> str | None:
        # Relative to the catalog's folder (or the sources for recorded maps) and staying
        # there: an absolute or ../ path would make verify read files anywhere.
        if v is None:
            return v
        p = PurePosixPath(v)
        if not v or p.is_absolute() or ".." in p.parts or "\\" in v or any(ord(c) < 32 for c in v):
            raise ValueError(f"must be a relative path inside the library without '..', got {v!r:.80}")
        return v

    @model_validator(mode="after")
    def _widths_ordered(self) -> TrackEntry:
        if self.width_min_m > self.width_mean_m + 1e-9:
            raise ValueError(f"width_min_m {self.width_min_m} is above width_mean_m {self.width_mean_m}")
        if self.start is not None and not all(math.isfinite(v) for v in self.start):
            raise ValueError(f"start must be finite, got {self.start}")
        return self
