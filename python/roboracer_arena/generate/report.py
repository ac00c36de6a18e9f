"""Typed results of the generator's core calls: the raster validator's report, the
admissibility screen, the curve analysis and the derived geometry. The core returns them
as read-only objects mirroring its structs (``_core.ValidationReport``, ...); these frozen
models are built from their attributes (``from_attributes``) with ``extra="forbid"`` and
add what code and the JSON outputs use (``Check.line``, ``failed``, tuples, ``model_dump``).
``tests/generate/test_report_models.py`` holds each model's fields to its core object's."""

from __future__ import annotations

from typing import Literal

import numpy as np
import numpy.typing as npt
from pydantic import BaseModel, ConfigDict

from .. import _core


class _Result(BaseModel):
    model_config = ConfigDict(frozen=True, extra="forbid")


class Check(_Result):
    """One acceptance test: ``measured`` and ``bound`` are for people, ``passed`` decides."""

    name: str
    measured: str
    bound: str
    passed: bool

    def line(self) -> str:
        """One aligned line for a terminal: verdict, name, measured value, bound."""
        return f"{'ok ' if self.passed else 'BAD'} {self.name:<17} {self.measured:<34} {self.bound}"


class FeatureAt(_Result):
    """A detected feature, ``at_m`` metres along the lap in the driving direction."""

    kind: Literal["hairpin", "chicane", "sweeper"]
    at_m: float
    x: float
    y: float


class Measurements(_Result):
    """What the validator measured, in SI units; code reads these, not the checks' text.
    ``self_clearance_m`` is None when the lap has no non-local passes."""

    corridor_components: int
    infields: int
    lap_length_m: float
    width_mean_m: float
    width_min_m: float
    min_radius_m: float
    hairpins: int
    chicanes: int
    sweepers: int
    longest_straight_m: float
    self_clearance_m: float | None
    extent_m: tuple[float, float]


class ValidationReport(_Result):
    """The raster validator's verdict on one map."""

    valid: bool
    checks: tuple[Check, ...]
    #: None when the map has no measurable corridor (the ``corridor`` check says why).
    measurements: Measurements | None
    features: tuple[FeatureAt, ...]

    def failed(self) -> list[Check]:
        """The checks that did not pass."""
        return [c for c in self.checks if not c.passed]


class ScreenResult(_Result):
    """The admissibility screen (the paper's Eqs. 1–2): ``passed`` or the ``violations``
    stated with numbers, and every quantity the bounds use."""

    passed: bool
    violations: tuple[str, ...]
    r_min_m: float
    pitch_m: float
    l_max_m: float
    l_min_m: float
    feature_length_m: float
    feature_budget_m: float


class Turn(_Result):
    """One turn of a closed curve: where it runs (m along the lap), by how much (signed,
    + = left) and its tightest radius."""

    start_m: float
    end_m: float
    angle_rad: float
    peak_radius_m: float


class CurveAnalysis(_Result):
    """The core's curvature analysis of a closed curve in its driving direction
    (``_core.analyse_curve``): turns, detected features, minimum radius, longest straight,
    total turn, and the self-clearance outside the excluded arc (None when no other pass
    comes near)."""

    length_m: float
    min_radius_m: float
    turns: tuple[Turn, ...]
    features: tuple[FeatureAt, ...]
    longest_straight_m: float
    total_turn_rad: float
    self_clearance_m: float | None

    @classmethod
    def of(cls, xy: npt.ArrayLike, corner_radius: float, exclude_m: float) -> CurveAnalysis:
        """Analyse the closed curve ``xy`` (N, 2) with the core."""
        raw = _core.analyse_curve(np.ascontiguousarray(xy, np.float64), corner_radius, exclude_m)
        return cls.model_validate(raw, from_attributes=True)


class DerivedGeometry(_Result):
    """Lengths derived from a spec (m): minimum radius, pitch, L_max, the lattice pitch
    bound and the corner radius."""

    r_min: float
    pitch: float
    l_max: float
    s_min: float
    corner_radius: float


__all__ = [
    "Check",
    "CurveAnalysis",
    "DerivedGeometry",
    "Turn",
    "FeatureAt",
    "Measurements",
    "ScreenResult",
    "ValidationReport",
]
