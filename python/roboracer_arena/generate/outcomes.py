"""The three typed outcomes of requirements → track (the paper's Sec. "Occupancy Maps as
a Common Interface"): a proven rejection, a bounded-search generation failure, or an
acceptance carrying a map that passed every raster-level check."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..maps.occupancy import OccupancyMap
from ..spec import TrackSpec
from .nearest import NearestSpecs
from .report import ScreenResult, ValidationReport


@dataclass(frozen=True)
class Acceptance:
    """A validated map: every check in ``report.checks`` passed."""

    spec: TrackSpec
    map: OccupancyMap
    centreline: np.ndarray  # (N, 2) metres, driving direction, constructor's curve
    report: ValidationReport
    constructor: str
    seed: int
    candidates_tried: int
    seconds: float
    kind: str = "accepted"

    @property
    def direction(self) -> str:
        """The requested racing direction (the env drives an Acceptance this way)."""
        return self.spec.direction

    @property
    def start(self) -> tuple[float, float]:
        """Where the constructor's centreline, and so the grid, starts."""
        return float(self.centreline[0, 0]), float(self.centreline[0, 1])

    def summary(self) -> str:
        h, w = self.map.shape
        return (
            f"accepted '{self.spec.name}': {w}x{h} cells at {self.map.resolution} m, "
            f"{len(self.report.checks)} checks passed after {self.candidates_tried} candidate(s) "
            f"in {self.seconds:.2f} s"
        )


@dataclass(frozen=True)
class Rejection:
    """The screen proved the spec infeasible; ``violations`` state the bounds with numbers."""

    spec: TrackSpec
    violations: list[str]
    screen: ScreenResult
    seconds: float
    kind: str = "rejected"

    def summary(self) -> str:
        return "rejected by the screen: " + "; ".join(self.violations)


@dataclass(frozen=True)
class GenerationFailure:
    """No candidate passed within the budget; this does not prove infeasibility.
    ``nearest`` holds the nearest specs that did build (each with the seed that built
    it), or None when the search was not run (the DE / random baselines, or
    ``suggest_timeout=None``)."""

    spec: TrackSpec
    constructor: str
    seed: int
    candidates_tried: int
    reasons: dict[str, int] = field(default_factory=dict)
    seconds: float = 0.0
    built_invalid_report: ValidationReport | None = None
    stopped: str | None = None  # "timeout" when the time budget cut the search short
    nearest: NearestSpecs | None = None
    kind: str = "failed"

    def summary(self) -> str:
        top = ", ".join(f"{k}: {v}" for k, v in sorted(self.reasons.items(), key=lambda kv: -kv[1])[:5])
        why = " (time budget exhausted)" if self.stopped == "timeout" else ""
        head = f"generation failure after {self.candidates_tried} candidate(s){why} ({top})"
        if self.nearest is None:
            return head
        return "\n".join([head, *(f"  {line}" for line in self.nearest.lines())])


Outcome = Acceptance | Rejection | GenerationFailure
