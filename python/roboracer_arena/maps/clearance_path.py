"""A reference path for narrow and cluttered maps: the loop that keeps the most
clearance from the walls, with a speed cap from that clearance.

The corridor's medial centreline runs midway between the infield and the outer side;
an obstacle in the corridor, or a room much wider on one side, pulls it close to a wall.
:func:`clearance_path` starts from it and lets it slide, as an elastic band, up the
signed distance field of the corridor (positive inside, negative in the walls) while a
smoothing term keeps it smooth and evenly spaced: it settles on the ridge of the distance
field, the medial axis of the free space, where the nearest wall is farthest. The speed
cap grows with the clearance left beside the car, so the driver slows where the path is
tight (the curvature limit of :class:`~roboracer_arena.drivers.PurePursuitDriver`
still applies).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import ndimage

from .. import _core

#: Elastic-band iterations, step up the distance field (cells) and smoothing weight.
ITERATIONS = 400
STEP_CELLS = 0.25
SMOOTHING = 0.25
#: Speed cap: ``SPEED_PER_M`` m/s per metre of clearance beyond the car's half width.
SPEED_PER_M = 5.0
MIN_SPEED = 0.8


@dataclass(frozen=True)
class ClearancePath:
    """The path (closed, (M, 2) map metres, the centreline's direction), the clearance
    (m) at each vertex, and the speed cap (m/s) per vertex."""

    line: np.ndarray
    clearance_m: np.ndarray
    speed_cap: np.ndarray

    @property
    def min_clearance_m(self) -> float:
        """The tightest clearance along the path (m)."""
        return float(self.clearance_m.min())


def _cells(m: Any, xy: np.ndarray) -> np.ndarray:
    """Map metres → (row, col) float indices of cell centres."""
    c, s = np.cos(m.origin[2]), np.sin(m.origin[2])
    dx, dy = xy[:, 0] - m.origin[0], xy[:, 1] - m.origin[1]
    u, v = (c * dx + s * dy) / m.resolution, (-s * dx + c * dy) / m.resolution
    return np.stack([m.data.shape[0] - v - 0.5, u - 0.5], axis=1)


def _world(m: Any, rc: np.ndarray) -> np.ndarray:
    c, s = np.cos(m.origin[2]), np.sin(m.origin[2])
    u, v = (rc[:, 1] + 0.5) * m.resolution, (m.data.shape[0] - rc[:, 0] - 0.5) * m.resolution
    return np.stack([m.origin[0] + c * u - s * v, m.origin[1] + s * u + c * v], axis=1)


def clearance_path(geo: Any, centreline: Any, half_width_m: float = 0.145, spacing_m: float = 0.1) -> ClearancePath:
    """The most-clearance loop of a corridor (``geo``: ``extract_corridor``'s result)
    starting from ``centreline`` (its driving direction is kept)."""
    m, mask = geo.map, np.asarray(geo.corridor_mask, bool)
    sdf = _core.distance_transform(~mask) - _core.distance_transform(mask)  # cells, > 0 inside
    g_r, g_c = np.gradient(sdf.astype(np.float64))
    rc = _cells(m, _core.resample_closed(np.asarray(centreline, np.float64), spacing_m))
    step = spacing_m / m.resolution
    for it in range(ITERATIONS):
        grad = np.stack([ndimage.map_coordinates(g, rc.T, order=1, mode="nearest") for g in (g_r, g_c)], axis=1)
        tangent = np.roll(rc, -1, axis=0) - np.roll(rc, 1, axis=0)
        tangent /= np.maximum(np.linalg.norm(tangent, axis=1, keepdims=True), 1e-9)
        normal = grad - (grad * tangent).sum(axis=1, keepdims=True) * tangent  # slide sideways only
        rc = rc + STEP_CELLS * normal / np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1.0)
        rc = rc + SMOOTHING * (0.5 * (np.roll(rc, 1, axis=0) + np.roll(rc, -1, axis=0)) - rc)
        if it % 20 == 19:  # even spacing again
            rc = _cells(m, _core.resample_closed(_world(m, rc), step * m.resolution))
    line = _world(m, rc)
    clear = ndimage.map_coordinates(sdf.astype(np.float64), rc.T, order=1, mode="nearest") * m.resolution
    cap = np.maximum(MIN_SPEED, SPEED_PER_M * (clear - half_width_m))
    return ClearancePath(line=line, clearance_m=clear, speed_cap=cap)


__all__ = ["ClearancePath", "clearance_path"]
