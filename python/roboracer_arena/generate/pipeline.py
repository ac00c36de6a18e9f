"""``generate_track``: screen → constructor → rasterise → validate (Algorithm 1), and the
raster validator on its own (``validate_map``). The pipeline never returns an invalid map:
every acceptance passed the raster validator."""

from __future__ import annotations

import math
import time
from typing import Literal

import numpy as np

from .. import _core
from ..config.constructor import ConstructorConfig
from ..errors import InternalError, InvalidArgumentError
from ..maps.occupancy import OccupancyMap
from ..spec import TrackSpec
from .nearest import DEFAULT_SUGGEST_TIMEOUT_S, nearest_specs
from .outcomes import Acceptance, GenerationFailure, Outcome, Rejection
from .report import DerivedGeometry, ScreenResult, ValidationReport

Constructor = Literal["lattice"]
CONSTRUCTORS: tuple[str, ...] = ("lattice",)
#: The paper's baseline constructors, which left the package for the checkout's benchmarks.
MOVED_CONSTRUCTORS: tuple[str, ...] = ("de", "random")
DEFAULT_TIMEOUT_S = 60.0
"""Default wall-clock budget of :func:`generate_track` (seconds)."""


def check_timeout(timeout: object, what: str = "timeout") -> float | None:
    """``timeout`` as seconds (None = unbounded); refuses bools, NaN, inf and ≤ 0."""
    if timeout is None:
        return None
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not math.isfinite(timeout) or timeout <= 0:
        raise InvalidArgumentError(f"{what} must be a finite number of seconds > 0, got {timeout!r}")
    return float(timeout)


def screen(spec: TrackSpec, config: ConstructorConfig | None = None) -> ScreenResult:
    """The admissibility screen (Eqs. 1–2): ``passed``, ``violations`` and every quantity."""
    return ScreenResult.model_validate(_core.screen(spec, config), from_attributes=True)


def derived_geometry(spec: TrackSpec, config: ConstructorConfig | None = None) -> DerivedGeometry:
    """r_min, pitch p, L_max, lattice pitch bound s_min and corner radius r_c for a spec."""
    return DerivedGeometry.model_validate(_core.derived_geometry(spec, config), from_attributes=True)


def validate_map(
    m: OccupancyMap, spec: TrackSpec, config: ConstructorConfig | None = None
) -> tuple[ValidationReport, np.ndarray]:
    """Measure the raster against the spec; returns (report, measured centreline (N, 2))."""
    report, line = _core.validate_map(
        np.ascontiguousarray(m.data, np.uint8),
        m.resolution,
        m.origin,
        spec,
        config,
    )
    return ValidationReport.model_validate(report, from_attributes=True), line


def rasterise(centreline: np.ndarray, spec: TrackSpec, config: ConstructorConfig) -> OccupancyMap:
    """Eq. 3 at the configured resolution and wall thickness, constant corridor width."""
    xy = np.ascontiguousarray(centreline, np.float64)
    data, origin = _core.rasterise_centreline(
        xy, np.full(len(xy), spec.corridor_width_m), config.resolution_m, config.wall_thickness_m, config.map_margin_m
    )
    return OccupancyMap(data, config.resolution_m, origin)


def generate_track(
    spec: TrackSpec,
    seed: int = 0,
    constructor: Constructor = "lattice",
    config: ConstructorConfig | None = None,
    timeout: float | None = DEFAULT_TIMEOUT_S,
    suggest_timeout: float | None = DEFAULT_SUGGEST_TIMEOUT_S,
) -> Outcome:
    """Turn a spec into a validated map, a proven rejection or a generation failure.

    ``constructor`` is ``"lattice"`` (the paper's method, Rust). The paper's DE / random
    baselines are not in the package any more: ``"de"`` or ``"random"`` raises
    :class:`~roboracer_arena.errors.InvalidArgumentError` naming where they went
    (``python -m benchmarks constructors`` in a checkout).

    ``timeout`` bounds the lattice search in wall-clock seconds (default 60; None = no
    limit): when it runs out the result is a :class:`GenerationFailure` with
    ``stopped="timeout"``; the call returns at most about a second after the budget even
    when one candidate (a very large map) is still being rasterised, which then stops in the
    background at its next check. Ctrl-C raises KeyboardInterrupt at once the same way. A hall whose raster would exceed the generator's cell budget
    raises :class:`~roboracer_arena.errors.SpecError`.

    When the lattice search fails, the nearest specs that build are searched within
    ``suggest_timeout`` seconds (default 20; None = no search) and returned on the
    failure's ``nearest`` (:mod:`~roboracer_arena.generate.nearest`).
    """
    if constructor in MOVED_CONSTRUCTORS:
        raise InvalidArgumentError(
            f"constructor {constructor!r} (a paper baseline) is no longer in the package; run it from a "
            f"checkout of the repository: python -m benchmarks constructors --constructors {constructor}"
        )
    if constructor not in CONSTRUCTORS:
        raise InvalidArgumentError(f"constructor must be one of {', '.join(CONSTRUCTORS)}; got {constructor!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed < 2**64:
        raise InvalidArgumentError(f"seed must be an integer in [0, 2**64), got {seed!r}")
    timeout = check_timeout(timeout)
    suggest_timeout = check_timeout(suggest_timeout, "suggest_timeout")
    config = config or ConstructorConfig()
    t0 = time.perf_counter()
    if constructor == "lattice":
        out = _core.generate_lattice(spec, config, seed, timeout)  # screens once, first
        if out.kind == "rejected":
            sr = ScreenResult.model_validate(out.screen, from_attributes=True)
            return Rejection(spec, list(sr.violations), sr, time.perf_counter() - t0)
        if out.kind == "accepted":
            if out.map is None or out.centreline is None or out.report is None:  # set with every acceptance
                raise InternalError("generate_lattice accepted without a map, centreline and report")
            data, origin = out.map
            return Acceptance(
                spec,
                OccupancyMap(data, config.resolution_m, origin),
                out.centreline,
                ValidationReport.model_validate(out.report, from_attributes=True),
                constructor,
                seed,
                out.tried,
                time.perf_counter() - t0,
            )
        seconds = time.perf_counter() - t0
        nearest = None if suggest_timeout is None else nearest_specs(spec, seed, config, suggest_timeout)
        return GenerationFailure(
            spec,
            constructor,
            seed,
            out.tried,
            dict(out.reasons),
            seconds,
            stopped=out.stopped,
            nearest=nearest,
        )
    raise AssertionError(f"unhandled constructor {constructor!r}")  # CONSTRUCTORS is checked above
