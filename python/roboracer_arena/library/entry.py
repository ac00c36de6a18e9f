"""One track of the catalog (``tracks/catalog.json``) as a typed, frozen model.

The fields are declared in the order the catalog writes them, and an entry is written
with only the fields it was given (``exclude_unset``), so the shipped catalog loads and
writes back byte for byte (``tests/library/test_entry.py``). An unknown key is refused:
a field added to the catalog is added here first.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import ConfigDict, Field

from ..frozen_model import FrozenModel

Kind = Literal["recorded", "circuit", "generated"]
Status = Literal["pass", "FAIL", "not run"]


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

    width_px: int
    height_px: int


class LeftOut(FrozenModel):
    """A recorded map the catalog does not offer, with the reason."""

    id: str
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
    :mod:`~roboracer_arena.library.directions`; ``verified`` and ``drive`` from
    ``tracks verify --update-catalog``."""

    id: str
    name: str
    kind: Kind
    source: Source
    scale: float | None
    resolution_m: float
    lap_length_m: float
    width_mean_m: float
    width_min_m: float
    min_radius_m: float
    raster: Raster
    sha256: str
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
