"""A track's raceline: :func:`plan_raceline` puts the minimum-curvature line (or the
minimum-time heuristic) inside the corridor less a safety margin, and the speed profile
of the given limits on it.

>>> from roboracer_arena.raceline import plan_raceline, preset
>>> line = plan_raceline(track, preset("f1tenth-racetracks"))   # doctest: +SKIP
>>> round(line.lap_time, 2), line.length                        # doctest: +SKIP
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..config.sim import VehicleConfig
from ..errors import InvalidArgumentError
from .bounds import Clearance, lateral_bounds
from .clearance import WallDistance
from .geometry import ArcSampled, ClosedPath
from .limits import VehicleLimits
from .mincurv import iterate_min_curvature
from .speed import SpeedProfile, speed_profile

MODES = ("mincurv", "mintime")
#: Default safety margin (m) beyond half the car's width.
DEFAULT_MARGIN = 0.10
#: Extra clearance (m) the QP keeps so that the spline through its points (and the
#: resampling after it) stays outside the margin: both move points by millimetres.
SPLINE_TOLERANCE = 0.015


@dataclass(frozen=True)
class Raceline(ArcSampled):
    """A closed raceline with its speed profile (map frame, SI units). Arrays are (N,), one
    entry per point, every ``step`` metres from the point nearest the track's start line;
    ``s`` is the arc length along the raceline, ``psi`` the heading (0 along +x), ``kappa``
    the curvature (> 0 turning left), ``vx`` the planned speed, ``ax`` the acceleration to
    the next point, ``d_left``/``d_right`` the distance to the walls along the normal."""

    track: str
    s: np.ndarray
    xy: np.ndarray
    psi: np.ndarray
    kappa: np.ndarray
    vx: np.ndarray
    ax: np.ndarray
    d_left: np.ndarray
    d_right: np.ndarray
    length: float
    lap_time: float
    limits: VehicleLimits
    mode: str = "mincurv"
    half_width: float = 0.0
    min_clearance: float = 0.0
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def path(self) -> tuple[np.ndarray, np.ndarray]:
        """``(line (N, 2), speed (N,))``: what a driver follows (``drivers.EnvPurePursuit``'s ``paths``)."""
        return self.xy, self.vx

    def summary(self) -> dict[str, Any]:
        """The numbers a person reads (CLI ``--json``, catalog, benchmark)."""
        return {
            "track": self.track,
            "mode": self.mode,
            "limits": self.limits.name,
            "length_m": round(self.length, 3),
            "lap_time_s": round(self.lap_time, 3),
            "points": len(self.s),
            "v_min_mps": round(float(self.vx.min()), 3),
            "v_max_mps": round(float(self.vx.max()), 3),
            "half_width_m": round(self.half_width, 3),
            "min_wall_clearance_m": round(self.min_clearance, 3),
            "timings_s": {k: round(v, 4) for k, v in self.timings.items()},
        }


def plan_raceline(
    track: Any,
    limits: VehicleLimits,
    *,
    mode: str = "mincurv",
    margin: float = DEFAULT_MARGIN,
    vehicle_width: float | None = None,
    step: float = 0.2,
    iterations: int = 5,
) -> Raceline:
    """The raceline of ``track`` (a :class:`~roboracer_arena.track.drivable.Track`, driven in its
    racing direction) for ``limits``: within the walls less ``vehicle_width / 2 + margin``
    (default width: the simulator's car), sampled every ``step`` m. ``mode``:
    ``"mincurv"`` (TUM's iterated minimum curvature) or ``"mintime"`` (the same QP with the
    curvature at slow points weighted up, kept only where it is faster)."""
    if mode not in MODES:
        raise InvalidArgumentError(f"mode must be one of {', '.join(MODES)}, got {mode!r}")
    if getattr(track, "is_open", False):
        raise InvalidArgumentError(f"track {track.name!r} is an open map: it has no lap to plan a raceline on")
    if not (0.0 <= margin <= 2.0):
        raise InvalidArgumentError(f"margin must be in [0, 2] m, got {margin}")
    if not (0.02 <= step <= 2.0):
        raise InvalidArgumentError(f"step must be in [0.02, 2] m, got {step}")
    width = VehicleConfig().chassis_width if vehicle_width is None else float(vehicle_width)
    half = 0.5 * width + margin
    t0 = time.perf_counter()
    walls = WallDistance(track.walls)
    line, _ = iterate_min_curvature(track.loop, walls, half + SPLINE_TOLERANCE, step, iterations)
    t_qp = time.perf_counter() - t0
    prof = speed_profile(line.kappa, line.ds, limits)
    if mode == "mintime":
        line, prof = _min_time(walls, line, prof, limits, half + SPLINE_TOLERANCE, step)
    t_speed = time.perf_counter() - t0 - t_qp
    line = _from_start(line, np.asarray(track.loop[0], dtype=np.float64))
    prof = speed_profile(line.kappa, line.ds, limits)
    left, right = lateral_bounds(line.xy, line.normals, walls, 0.0)
    return Raceline(
        track=str(getattr(track, "name", "track")),
        s=line.s,
        xy=line.xy,
        psi=line.psi,
        kappa=line.kappa,
        vx=prof.vx,
        ax=prof.ax,
        d_left=left,
        d_right=right,
        length=line.length,
        lap_time=prof.lap_time,
        limits=limits,
        mode=mode,
        half_width=half,
        min_clearance=float(track.clearance(line.xy).min()),
        timings={"qp": t_qp, "speed": t_speed, "total": time.perf_counter() - t0},
    )


def _from_start(line: ClosedPath, start: np.ndarray) -> ClosedPath:
    """The same loop beginning at its point nearest ``start`` (the track's start line)."""
    k = int(np.argmin(np.hypot(*(line.xy - start).T)))
    if k == 0:
        return line
    s = np.roll(line.s, -k) - line.s[k]
    s[s < 0] += line.length
    return ClosedPath(
        xy=np.roll(line.xy, -k, axis=0),
        s=s,
        length=line.length,
        psi=np.roll(line.psi, -k),
        kappa=np.roll(line.kappa, -k),
    )


def _min_time(
    walls: Clearance, line: ClosedPath, prof: SpeedProfile, limits: VehicleLimits, half: float, step: float
) -> tuple[ClosedPath, SpeedProfile]:
    """Minimum-time heuristic: re-solve the curvature QP with the curvature at each point
    weighted by how slow the current profile is there ((v_max / v)^2), three times, and
    keep the fastest line found that keeps the margin (so never slower than minimum
    curvature)."""
    best_line, best = line, prof
    for _ in range(3):
        cur_line, cur = best_line, best
        ref_prof = cur

        def weights(ref: ClosedPath, src: ClosedPath = cur_line, p: SpeedProfile = ref_prof) -> np.ndarray:
            v = np.interp(ref.s, src.s, p.vx, period=src.length)
            w = (limits.v_max / np.maximum(v, 0.1)) ** 2
            return w / w.mean()

        cand, _ = iterate_min_curvature(cur_line.xy, walls, half, step, 2, weights=weights, smooth=False)
        cand_prof = speed_profile(cand.kappa, cand.ds, limits)
        inside = float(walls(cand.xy).min()) >= half - SPLINE_TOLERANCE
        if inside and cand_prof.lap_time < best.lap_time:
            best_line, best = cand, cand_prof
        else:
            break
    return best_line, best
