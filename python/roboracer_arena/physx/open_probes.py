"""Probe stations and the free region of an *open map* for the PhysX containment check.

An open map (:meth:`~roboracer_arena.track.drivable.Track.open_map`) has no centreline to place
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
from scipy.spatial import cKDTree

#: Clearance beyond the box's half-diagonal a station needs (m): the walls are smoothed
#: polygons within about half a cell of the raster, so the box starts clear of them.
STATION_MARGIN_M = 0.1
#: Stations lie at most this far (m) beyond the needed clearance, so the slowest bodies
#: (a third of the top speed) still reach a wall within the run.
STATION_BAND_M = 0.5
#: Candidate cells are taken on this stride (cells) before the spread: plenty for a
#: handful of stations, and it keeps a 4-megapixel map fast.
CANDIDATE_STRIDE = 3
#: Wall edges are indexed in pieces of at most this length (m) for the crossing test.
MAX_EDGE_PIECE_M = 0.5


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


class WallSegments:
    """Every edge of a set of closed wall rings, indexed once for crossing tests: moves are
    tested against only the edges near them (a k-d tree over edge midpoints), all in numpy
    (segment against many segments), so the cost per call grows with the number of moves
    and the edges near each, not with the number of walls. A floor plan speckled with
    thousands of one-pixel islands (a common SLAM artefact) costs no more per move than
    one with a few long walls."""

    def __init__(self, walls: list[np.ndarray]) -> None:
        rings = [np.asarray(w, dtype=np.float64).reshape(-1, 2) for w in walls if len(w) >= 2]
        p = np.concatenate(rings) if rings else np.zeros((0, 2))
        q = np.concatenate([np.roll(w, -1, axis=0) for w in rings]) if rings else np.zeros((0, 2))
        p, q = _split_long(p, q, MAX_EDGE_PIECE_M)
        self.p, self.q = p, q
        self.mid = 0.5 * (p + q)
        self.half_len = 0.5 * np.hypot(*(q - p).T) if len(p) else np.zeros(0)
        self.reach = float(self.half_len.max()) if len(p) else 0.0
        self._tree = cKDTree(self.mid) if len(p) else None

    def crossed(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """True where the move from ``a[i]`` to ``b[i]`` ((N, 2)) properly crosses a wall edge."""
        a = np.asarray(a, dtype=np.float64).reshape(-1, 2)
        b = np.asarray(b, dtype=np.float64).reshape(-1, 2)
        hit = np.zeros(len(a), dtype=bool)
        if self._tree is None or not len(a):
            return hit
        ok: np.ndarray = np.asarray(np.isfinite(a).all(axis=1) & np.isfinite(b).all(axis=1))
        centre = np.where(ok[:, None], 0.5 * (a + b), 0.0)
        radius = np.where(ok, 0.5 * np.hypot(*(b - a).T), 0.0) + self.reach + 1e-9
        # an edge can meet a move only if their midpoints are within both half-lengths
        near = self._tree.query_ball_point(centre, radius)
        counts = np.fromiter((len(n) for n in near), dtype=np.int64, count=len(near))
        if not counts.sum():
            return hit
        move = np.repeat(np.arange(len(a)), counts)
        edge = np.fromiter((j for n in near for j in n), dtype=np.int64, count=int(counts.sum()))
        keep = ok[move]
        move, edge = move[keep], edge[keep]
        crossing = _proper_crossings(a[move], b[move], self.p[edge], self.q[edge])
        hit[move[crossing]] = True
        return hit


def _split_long(p: np.ndarray, q: np.ndarray, longest: float) -> tuple[np.ndarray, np.ndarray]:
    """Edges ``p-q`` cut into collinear pieces of at most ``longest`` (m), so the index's
    search radius stays small beside a long straight wall."""
    n = np.maximum(1, np.ceil(np.hypot(*(q - p).T) / longest).astype(np.int64)) if len(p) else np.zeros(0, np.int64)
    if not len(p) or n.max() == 1:
        return p, q
    edge = np.repeat(np.arange(len(p)), n)
    k = np.arange(len(edge)) - np.repeat(np.cumsum(n) - n, n)
    t0, t1 = (k / n[edge])[:, None], ((k + 1) / n[edge])[:, None]
    d = q[edge] - p[edge]
    return p[edge] + t0 * d, p[edge] + t1 * d


def _proper_crossings(a: np.ndarray, b: np.ndarray, p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Row-wise: does segment ``a-b`` properly cross segment ``p-q`` (strict sign changes)."""

    def side(x0: np.ndarray, x1: np.ndarray, x: np.ndarray) -> np.ndarray:
        d, e = x1 - x0, x - x0
        return np.sign(d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0])

    return (side(a, b, p) * side(a, b, q) < 0) & (side(p, q, a) * side(p, q, b) < 0)


def crosses_walls(walls: list[np.ndarray], a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """True where the move from ``a[i]`` to ``b[i]`` ((N, 2)) crosses a wall edge (walls are
    closed rings). On a floor plan a body that passes through a thin wall lands in free
    space again, often the same connected region, so its path is what shows the escape; a
    body that stays clear of the walls (its centre at least half its width away) never
    crosses one between two close samples, even when it bounces. One call indexes the
    walls; a caller testing many times keeps a :class:`WallSegments`."""
    return WallSegments(walls).crossed(a, b)


__all__ = ["FreeRegion", "WallSegments", "crosses_walls", "open_stations"]
