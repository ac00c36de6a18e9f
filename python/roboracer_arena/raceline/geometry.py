"""Closed smooth paths: a periodic cubic spline through a ring of points, resampled at a
uniform arc-length step, with heading and curvature from the spline's derivatives (not
from finite differences of the points, which amplify noise).

Headings are in the map frame (0 along +x, counter-clockwise positive); curvature is
positive in a left turn.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from ..errors import InvalidArgumentError


class ArcSampled:
    """What a closed path sampled along its arc length (``s``, ``length``, ``psi``) gives."""

    s: np.ndarray
    length: float
    psi: np.ndarray

    @property
    def ds(self) -> np.ndarray:
        """(N,) distance from each point to the next (the last one back to the first)."""
        return np.diff(np.append(self.s, self.length))

    @property
    def normals(self) -> np.ndarray:
        """(N, 2) unit normals pointing left of the direction of travel."""
        return np.column_stack([-np.sin(self.psi), np.cos(self.psi)])


@dataclass(frozen=True)
class ClosedPath(ArcSampled):
    """A closed path sampled every ``step`` metres: ``xy`` (N, 2) (no repeated closing
    point), ``s`` (N,) arc length of each point from the first, ``length`` of the loop,
    ``psi`` (N,) heading, ``kappa`` (N,) curvature (1/m)."""

    xy: np.ndarray
    s: np.ndarray
    length: float
    psi: np.ndarray
    kappa: np.ndarray


def _ring(xy: np.ndarray) -> np.ndarray:
    a = np.asarray(xy, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != 2 or len(a) < 4 or not np.isfinite(a).all():
        raise InvalidArgumentError(f"a closed path needs a finite (N>=4, 2) array of points, got shape {a.shape}")
    if np.allclose(a[0], a[-1]):
        a = a[:-1]
    keep = np.r_[True, np.hypot(*np.diff(a, axis=0).T) > 1e-9]  # drop repeated points
    a = a[keep]
    if np.hypot(*(a[-1] - a[0])) <= 1e-9:
        a = a[:-1]
    return a


def _spline(a: np.ndarray) -> tuple[CubicSpline, float]:
    closed = np.vstack([a, a[:1]])
    t = np.r_[0.0, np.cumsum(np.hypot(*np.diff(closed, axis=0).T))]
    return CubicSpline(t, closed, bc_type="periodic"), float(t[-1])


def closed_path(xy: np.ndarray, step: float) -> ClosedPath:
    """The closed path through the ring ``xy`` (a repeated closing point is dropped),
    resampled every ``step`` metres of arc length (the last step absorbs the remainder)."""
    if not step > 0:
        raise InvalidArgumentError(f"step must be > 0 m, got {step}")
    spl, total = _spline(_ring(xy))
    # Arc length of the chord-parametrised spline on a fine grid, then invert it.
    fine = np.linspace(0.0, total, max(64, int(total / step) * 8) + 1)
    d1 = spl(fine, 1)
    speed = np.hypot(d1[:, 0], d1[:, 1])
    arc = np.r_[0.0, np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(fine))]
    length = float(arc[-1])
    n = max(4, int(round(length / step)))
    s = np.linspace(0.0, length, n, endpoint=False)
    t = np.interp(s, arc, fine)
    p, d1, d2 = spl(t), spl(t, 1), spl(t, 2)
    psi = np.arctan2(d1[:, 1], d1[:, 0])
    kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.maximum(np.hypot(d1[:, 0], d1[:, 1]) ** 3, 1e-12)
    return ClosedPath(xy=p, s=s, length=length, psi=psi, kappa=kappa)


def smoothed(path: ClosedPath, sigma_m: float) -> ClosedPath:
    """``path`` with its points smoothed by a periodic Gaussian of ``sigma_m`` metres and
    resampled at the same step: a medial-axis centreline from a raster zigzags by a cell,
    and its normals with it, which a line offset by a metre along them would copy."""
    if sigma_m <= 0:
        return path
    step = float(np.mean(path.ds))
    sig = sigma_m / step
    half = int(np.ceil(3 * sig))
    k = np.exp(-0.5 * (np.arange(-half, half + 1) / sig) ** 2)
    k /= k.sum()
    n = len(path.xy)
    idx = (np.arange(n)[:, None] + np.arange(-half, half + 1)[None, :]) % n
    xy = np.einsum("ij,j->i", path.xy[idx, 0], k), np.einsum("ij,j->i", path.xy[idx, 1], k)
    return closed_path(np.column_stack(xy), step)


def signed_area(xy: np.ndarray) -> float:
    """Shoelace area of a ring (> 0 counter-clockwise)."""
    x, y = np.asarray(xy, dtype=np.float64).T
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))
