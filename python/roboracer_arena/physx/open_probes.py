"""Probe stations and the free region of an *open map* for the PhysX containment check.

An open map (:meth:`~roboracer_arena.track.Track.open_map`) has no centreline to place
probes along, and its free region may reach the map border (the edge is then a wall),
so the even–odd test over wall loops that suits a closed corridor does not apply. Here
the drivable region is the open map's own raster: the free cells (``corridor_mask``)
connected to the start, the map edge closing it. Probe stations are free cells of that
region with room for a car-sized box in any orientation, close enough to a wall for the
bodies to reach it, spread over the floor plan by farthest-point sampling from the start
(deterministic).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import ndimage

#: Clearance beyond the box's half-diagonal a station needs (m): the walls are smoothed
#: polygons within about half a cell of the raster, so the box starts clear of them.
STATION_MARGIN_M = 0.1
#: Stations lie at most this far (m) beyond the needed clearance, so the slowest bodies
#: (a third of the top speed) still reach a wall within the run.
STATION_BAND_M = 0.5
#: Candidate cells are taken on this stride (cells) before the spread: plenty for a
#: handful of stations, and it keeps a 4-megapixel map fast.
CANDIDATE_STRIDE = 3


@dataclass(frozen=True)
class FreeRegion:
    """The start's connected free cells of an open map, and the map frame to index it."""

    region: np.ndarray  # (H, W) bool, row 0 at the top of the image
    origin: tuple[float, float, float]
    resolution: float

    @classmethod
    def of_geometry(cls, geo: Any, start_xy: tuple[float, float]) -> FreeRegion:
        """The free cells of ``geo`` (an open map's ``extract_corridor`` result) 4-connected
        to ``start_xy``; all free cells when the start is not on one."""
        m = geo.map
        mask = np.asarray(geo.corridor_mask, bool)
        origin = (float(m.origin[0]), float(m.origin[1]), float(m.origin[2]))
        free = cls(mask, origin, float(m.resolution))
        rows, cols, ok = free.cells(np.asarray([start_xy], dtype=np.float64))
        if not ok[0] or not mask[rows[0], cols[0]]:
            return free
        labels, _ = ndimage.label(mask)
        return cls(labels == labels[rows[0], cols[0]], origin, float(m.resolution))

    def cells(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Row and column of the cell under each point, and whether it is on the map."""
        ox, oy, th = self.origin
        c, s = math.cos(th), math.sin(th)
        dx, dy = xy[:, 0] - ox, xy[:, 1] - oy
        u = np.floor((c * dx + s * dy) / self.resolution).astype(np.int64)
        v = np.floor((-s * dx + c * dy) / self.resolution).astype(np.int64)
        h, w = self.region.shape
        ok = (u >= 0) & (u < w) & (v >= 0) & (v < h)
        return np.where(ok, h - 1 - v, 0), np.where(ok, u, 0), ok

    def contains(self, xy: np.ndarray) -> np.ndarray:
        """True where a point lies on a cell of the region (off the map is outside)."""
        rows, cols, ok = self.cells(np.asarray(xy, dtype=np.float64).reshape(-1, 2))
        return ok & self.region[rows, cols]

    def centre(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """Map-frame centres (N, 2) of cells."""
        ox, oy, th = self.origin
        c, s = math.cos(th), math.sin(th)
        u = (cols + 0.5) * self.resolution
        v = (self.region.shape[0] - 1 - rows + 0.5) * self.resolution
        return np.column_stack([ox + c * u - s * v, oy + s * u + c * v])


def open_stations(
    free: FreeRegion, start_xy: tuple[float, float], points: int, half_diagonal_m: float
) -> list[tuple[float, float, float]]:
    """``points`` stations ``(x, y, yaw)`` in ``free``: cells with a clearance from the
    walls (and the map edge) of ``half_diagonal_m + STATION_MARGIN_M`` up to
    :data:`STATION_BAND_M` more, spread by farthest-point sampling from the one nearest
    the start. Cells whose nearest wall is the map edge are left out when others qualify
    (a floor plan whose free space reaches the border would otherwise spend its stations
    on the empty margin). ``yaw`` runs along the nearest wall, as a track's heading does, so the
    probe angles mean the same as on a closed track. Fewer stations when fewer cells
    qualify; none on a map too tight for the box anywhere."""
    padded = np.pad(free.region, 1, constant_values=False)  # the map edge is a wall
    dist, (near_r, near_c) = ndimage.distance_transform_edt(padded, return_indices=True)
    dist, near_r, near_c = dist[1:-1, 1:-1] * free.resolution, near_r[1:-1, 1:-1] - 1, near_c[1:-1, 1:-1] - 1
    need = half_diagonal_m + STATION_MARGIN_M
    ok = free.region & (dist >= need) & (dist <= need + STATION_BAND_M)
    h, w = free.region.shape
    by_edge = (near_r < 0) | (near_r >= h) | (near_c < 0) | (near_c >= w)
    if (ok & ~by_edge).any():  # the map's own walls first; the edge only on a map with no others
        ok &= ~by_edge
    sub = np.zeros_like(ok)
    sub[::CANDIDATE_STRIDE, ::CANDIDATE_STRIDE] = ok[::CANDIDATE_STRIDE, ::CANDIDATE_STRIDE]
    rows, cols = np.nonzero(sub)
    if len(rows) == 0:
        return []
    xy = free.centre(rows, cols)
    picked = [int(np.argmin(np.hypot(xy[:, 0] - start_xy[0], xy[:, 1] - start_xy[1])))]
    gap = np.hypot(xy[:, 0] - xy[picked[0], 0], xy[:, 1] - xy[picked[0], 1])
    while len(picked) < min(points, len(rows)):
        k = int(np.argmax(gap))
        picked.append(k)
        gap = np.minimum(gap, np.hypot(xy[:, 0] - xy[k, 0], xy[:, 1] - xy[k, 1]))
    wall_xy = free.centre(near_r[rows, cols], near_c[rows, cols])
    out = []
    for k in picked:
        to_wall = math.atan2(wall_xy[k, 1] - xy[k, 1], wall_xy[k, 0] - xy[k, 0])
        out.append((float(xy[k, 0]), float(xy[k, 1]), to_wall + math.pi / 2.0))
    return out


def crosses_walls(walls: list[np.ndarray], a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """True where the move from ``a[i]`` to ``b[i]`` ((N, 2)) crosses a wall edge (walls are
    closed rings). On a floor plan a body that passes through a thin wall lands in free
    space again, often the same connected region, so its path is what shows the escape; a
    body that stays clear of the walls (its centre at least half its width away) never
    crosses one between two close samples, even when it bounces."""
    hit = np.zeros(len(a), dtype=bool)
    ax, ay, bx, by = (v[:, None] for v in (a[:, 0], a[:, 1], b[:, 0], b[:, 1]))
    for w in walls:
        p, q = w, np.roll(w, -1, axis=0)
        px, py, qx, qy = (v[None, :] for v in (p[:, 0], p[:, 1], q[:, 0], q[:, 1]))

        def side(x0, y0, x1, y1, x, y):  # sign of the cross product (x1 - x0, y1 - y0) x (x - x0, y - y0)
            return np.sign((x1 - x0) * (y - y0) - (y1 - y0) * (x - x0))

        hit |= (
            (side(ax, ay, bx, by, px, py) * side(ax, ay, bx, by, qx, qy) < 0)
            & (side(px, py, qx, qy, ax, ay) * side(px, py, qx, qy, bx, by) < 0)
        ).any(axis=1)
    return hit


__all__ = ["FreeRegion", "crosses_walls", "open_stations"]
