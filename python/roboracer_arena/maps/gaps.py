"""Gap closing, shown: close the openings of a map's walls up to a given width (doorways,
sensor leaks), so that a hallway loop that leaks becomes a closed corridor with laps and
progress. Every closed gap is returned (centre, width, cells) for the report and the
preview to show; nothing is closed silently.

The rule: grow the walls (occupied cells) by half of ``max_width_m``. Every opening up
to that width is then shut, and the free space falls apart into regions (a hallway loop,
the rooms behind its doorways, the exterior beyond a leak). Each free cell of the map
goes to the region nearest to it; where two free cells side by side go to different
regions, the free space crosses from one region to the other through an opening, and
those cells — a line one or two cells thick across the opening — become wall. Each
connected line is one gap. A corridor narrower than ``max_width_m`` is cut as well:
choose a width below the narrowest corridor you want to keep.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from .. import _core
from ..errors import InvalidArgumentError
from .occupancy import OccupancyMap

OCCUPIED = 0


@dataclass(frozen=True)
class ClosedGap:
    """One opening closed with a wall: centre (map metres), width (m: the length of the
    wall line put across it) and size in cells."""

    x: float
    y: float
    width_m: float
    cells: int

    def to_json_dict(self) -> dict[str, float | int]:
        """Plain numbers for reports and stage metadata."""
        return {"x": round(self.x, 3), "y": round(self.y, 3), "width_m": round(self.width_m, 3), "cells": self.cells}


def close_gaps(m: OccupancyMap, max_width_m: float) -> tuple[OccupancyMap, list[ClosedGap]]:
    """The map with every opening up to ``max_width_m`` closed, and the gaps closed."""
    w = float(max_width_m)
    if not np.isfinite(w) or w <= 0 or w > 20:
        raise InvalidArgumentError(f"close_gaps width must be in (0, 20] m, got {max_width_m!r}")
    data = np.asarray(m.data)
    free = data != OCCUPIED  # unknown cells too: a doorway may open onto unmapped space
    r = 0.5 * w / float(m.resolution)
    seeds = free & (_core.distance_transform(~free) > r)
    if not seeds.any():
        return m, []
    regions, n = ndimage.label(seeds)  # 4-connected regions once the openings are shut
    if n < 2:
        return m, []
    nearest = ndimage.distance_transform_edt(~seeds, return_distances=False, return_indices=True)
    owner = np.where(free, regions[nearest[0], nearest[1]], 0)
    cut = np.zeros_like(free)
    for a, b, sa, sb in (
        (owner[:, :-1], owner[:, 1:], (slice(None), slice(None, -1)), (slice(None), slice(1, None))),
        (owner[:-1, :], owner[1:, :], (slice(None, -1), slice(None)), (slice(1, None), slice(None))),
    ):
        differ = (a > 0) & (b > 0) & (a != b)
        cut[sa] |= differ & (a > b)  # one side of each boundary: a line one cell thick
        cut[sb] |= differ & (b > a)
    if not cut.any():
        return m, []
    patches, count = ndimage.label(cut, structure=np.ones((3, 3), bool))
    out = data.copy()
    out[cut] = OCCUPIED
    gaps = []
    h = data.shape[0]
    res, (ox, oy, yaw) = float(m.resolution), m.origin
    for k, box in enumerate(ndimage.find_objects(patches), start=1):
        rows, cols = np.nonzero(patches[box] == k)
        rows, cols = rows + box[0].start, cols + box[1].start
        u, v = cols.mean() + 0.5, (h - 1 - rows.mean()) + 0.5
        c, s = np.cos(yaw), np.sin(yaw)
        x, y = ox + res * (c * u - s * v), oy + res * (s * u + c * v)
        width = float(np.hypot(np.ptp(rows) + 1, np.ptp(cols) + 1)) * res  # the cut's length
        gaps.append(ClosedGap(float(x), float(y), width, int(len(rows))))
    return OccupancyMap(data=out, resolution=m.resolution, origin=m.origin, path=m.path, meta=m.meta), gaps


__all__ = ["ClosedGap", "close_gaps"]
