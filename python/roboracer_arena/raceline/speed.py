"""Speed profile of a closed path under :class:`~.limits.VehicleLimits`: the lateral limit
``v <= sqrt(ay_max(v) / |kappa|)`` capped by ``v_max``, then a forward pass (accelerate
with what the tyres leave after cornering, and no more than the motor curve gives) and a
backward pass (brake with what the tyres leave), both around the loop from its slowest
point, as TUM's ``calc_vel_profile`` does. The tyre limits combine as
``ax_avail = ax_max * (1 - (|ay| / ay_max)^p)^(1/p)`` with ``p = dyn_model_exp``.

``ax`` is then ``(v[i+1]^2 - v[i]^2) / (2 ds[i])`` and the lap time ``sum 2 ds / (v[i] + v[i+1])``
(TUM's definitions, so lap times compare).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .limits import VehicleLimits

_DV = 0.005  # m/s: the resolution of the limit lookups inside the passes


@dataclass(frozen=True)
class SpeedProfile:
    """``vx`` (N,) m/s at each point, ``ax`` (N,) m/s^2 from point i to i+1, ``lap_time`` s."""

    vx: np.ndarray
    ax: np.ndarray
    lap_time: float


class _Table:
    """A limit sampled on a fine speed grid for the scalar loops (``np.interp`` per call is slow)."""

    def __init__(self, values: np.ndarray) -> None:
        self.values = values.tolist()
        self.last = len(values) - 2

    def __call__(self, v: float) -> float:
        x = v / _DV
        i = int(x)
        if i >= self.last:
            return self.values[-1]
        a = self.values[i]
        return a + (x - i) * (self.values[i + 1] - a)  # linear, as np.interp on the table


def lateral_limit(kappa: np.ndarray, lim: VehicleLimits) -> np.ndarray:
    """The largest speed each point's curvature allows (m/s), at most ``v_max``."""
    k = np.abs(np.asarray(kappa, dtype=np.float64))
    v = np.full(len(k), lim.v_max)
    for _ in range(4):  # ay_max depends on speed: a few fixed-point rounds settle it
        v = np.minimum(lim.v_max, np.sqrt(lim.ay_tyre(v) / np.maximum(k, 1e-9)))
    return v


def speed_profile(kappa: np.ndarray, ds: np.ndarray, lim: VehicleLimits) -> SpeedProfile:
    """Speed profile of a closed path: ``kappa`` (N,) 1/m at each point, ``ds`` (N,) m from
    point i to point i+1 (the last back to the first)."""
    kappa = np.asarray(kappa, dtype=np.float64)
    ds = np.asarray(ds, dtype=np.float64)
    n = len(kappa)
    grid = np.arange(0.0, lim.v_max + 2 * _DV, _DV)
    ax_t, ay_t, ax_m = _Table(lim.ax_tyre(grid)), _Table(lim.ay_tyre(grid)), _Table(lim.ax_machine(grid))
    p = lim.dyn_model_exp
    v = lateral_limit(kappa, lim)
    k = np.abs(kappa).tolist()
    dsl = ds.tolist()
    vl = v.tolist()
    start = int(np.argmin(v))

    def avail(vi: float, ki: float) -> float:
        ratio = min(1.0, ki * vi * vi / ay_t(vi))
        return ax_t(vi) * (1.0 - ratio**p) ** (1.0 / p) if ratio < 1.0 else 0.0

    for step in range(n):  # forward: accelerate out of each corner
        i = (start + step) % n
        j = (i + 1) % n
        vi = vl[i]
        a = min(avail(vi, k[i]), ax_m(vi))
        cap = math.sqrt(vi * vi + 2.0 * a * dsl[i])
        if cap < vl[j]:
            vl[j] = cap
    for step in range(n):  # backward: brake into each corner
        j = (start - step) % n
        i = (j - 1) % n
        vj = vl[j]
        cap = math.sqrt(vj * vj + 2.0 * avail(vj, k[j]) * dsl[i])
        if cap < vl[i]:
            vl[i] = cap
    vx = np.asarray(vl)
    nxt = np.roll(vx, -1)
    ax = (nxt**2 - vx**2) / (2.0 * ds)
    lap = float(np.sum(2.0 * ds / np.maximum(vx + nxt, 1e-9)))
    return SpeedProfile(vx=vx, ax=ax, lap_time=lap)


def lap_time(vx: np.ndarray, ds: np.ndarray) -> float:
    """Lap time (s) of a closed profile: ``vx`` (N,) at the points, ``ds`` (N,) between them."""
    vx = np.asarray(vx, dtype=np.float64)
    return float(np.sum(2.0 * np.asarray(ds) / np.maximum(vx + np.roll(vx, -1), 1e-9)))
