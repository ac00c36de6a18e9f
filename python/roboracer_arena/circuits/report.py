"""Typed reports of the circuit build (:mod:`.build`): one :class:`CircuitReport` per built
circuit (also written as its ``circuit.json``), a :class:`CircuitFailure` for one that
raised, and the run's :class:`CircuitBuildSummary` (what ``roboracer-arena circuits
--json`` prints). Frozen, ``extra="forbid"``; fields in the order the JSON holds them."""

from __future__ import annotations

from typing import Any

from ..foundation.frozen_model import FrozenModel


class CircuitRaster(FrozenModel):
    """Map image size in cells and its ROS origin ``(x, y, yaw)``."""

    width_px: int
    height_px: int
    origin: tuple[float, float, float]


class RasterMeasurement(FrozenModel):
    """The raster measured back (``_core.measure_map``); ``error`` when it has no closed
    corridor (then only the component counts are set)."""

    corridor_components: int
    infields: int
    raster_centreline_m: float | None = None
    mean_width_m: float | None = None
    min_width_m: float | None = None
    error: str | None = None


class CircuitReport(FrozenModel):
    """One built circuit at vehicle scale (metres). ``length_error`` is the raster
    centreline's relative error against the smoothed centreline (None when not
    comparable: a grade-separated crossing or no corridor)."""

    id: str
    name: str
    source: str
    source_file: str
    scale: float
    resolution_m: float
    width_note: str
    full_scale_length_m: float
    input_length_m: float
    lap_length_m: float
    nominal_width_mean_m: float
    nominal_width_min_m: float
    width_mean_m: float
    width_min_m: float
    min_radius_m: float
    narrowed_fraction: float
    unresolved_fraction: float
    min_separation_m: float | None
    direction: str
    direction_source: str
    grade_separated: bool
    crossings: list[tuple[float, float]]
    raster: CircuitRaster
    measured: RasterMeasurement
    length_error: float | None
    one_corridor: bool
    map_sha256: str
    map_yaml: str
    seconds: float
    seconds_raster: float
    meta: dict[str, Any]


class CircuitFailure(FrozenModel):
    """A circuit whose build raised: reported, never fatal to the batch."""

    id: str
    name: str
    source: str
    error: str


class CircuitBuildSummary(FrozenModel):
    """A ``build_all`` run: counts, length errors, time, the config and every result."""

    circuits: int
    built: int
    one_corridor: int
    grade_separated: list[str]
    mean_length_error: float | None
    max_length_error: float | None
    seconds: float
    jobs: int
    config: dict[str, Any]
    skipped_as_covered: list[dict[str, Any]]
    results: list[CircuitReport | CircuitFailure]

    def reports(self) -> list[CircuitReport]:
        """The circuits that were built."""
        return [r for r in self.results if isinstance(r, CircuitReport)]
