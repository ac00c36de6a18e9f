"""How far a raceline point may move along its normal, left and right, and keep the car
``half_width`` (half the car's width plus the safety margin) away from every wall.

The reach is found by sphere tracing the wall distance field (``clearance``: points ->
distance to the nearest wall): from the point, step along the normal by
``clearance - half_width`` until that is ~0. Every step stays inside a disc free of
walls, so the reach never overshoots; a ray that grazes a wall converges slowly and is
cut at ``max_iter`` steps, which only shortens it. Every point of the segment from the
point to its reach then has at least ``half_width`` of clearance.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

Clearance = Callable[[np.ndarray], np.ndarray]


def normal_reach(
    points: np.ndarray,
    directions: np.ndarray,
    clearance: Clearance,
    half_width: float,
    max_reach: float = 5.0,
    tol: float = 5e-3,
    max_iter: int = 24,
) -> np.ndarray:
    """(N,) distance each of ``points`` (N, 2) may move along its unit ``directions``
    (N, 2) with ``half_width`` of clearance all the way, at most ``max_reach``; 0 where
    the point itself has less."""
    pts = np.asarray(points, dtype=np.float64)
    d = np.asarray(directions, dtype=np.float64)
    t = np.zeros(len(pts))
    active = np.ones(len(pts), dtype=bool)
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        if len(idx) == 0:
            break
        f = clearance(pts[idx] + t[idx, None] * d[idx]) - half_width
        step = np.maximum(f, 0.0)
        t[idx] = np.minimum(t[idx] + step, max_reach)
        active[idx] = (f > tol) & (t[idx] < max_reach)
    return t


def lateral_bounds(
    points: np.ndarray, normals: np.ndarray, clearance: Clearance, half_width: float, max_reach: float = 5.0
) -> tuple[np.ndarray, np.ndarray]:
    """``(left, right)`` reach (N,) along ``normals`` and against them (both >= 0)."""
    both = normal_reach(np.vstack([points, points]), np.vstack([normals, -normals]), clearance, half_width, max_reach)
    n = len(points)
    return both[:n], both[n:]
