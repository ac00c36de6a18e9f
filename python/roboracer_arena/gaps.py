"""Gap closing, shown: close the openings of a map's walls up to a given width (doorways,
sensor leaks), so that a hallway loop that leaks becomes a closed corridor with laps and
progress. Every closed gap is returned (centre, width, cells) for the report and the
preview to show; nothing is closed silently.

The rule is a morphological closing of the occupied cells with a disc of diameter
``max_width_m``: a free or unknown cell becomes a wall when no disc of that diameter
through it fits between the walls. That fills every opening up to ``max_width_m``, and
also the corners of the free space; a filled patch counts as a *gap* (and stays filled)
only when it separates free space, i.e. borders two or more regions of the closed map's
non-wall cells (the hallway and a room behind a doorway, or the unknown outside). Corner
patches touch one region and are left as they were. A corridor narrower than
``max_width_m`` would be filled too: choose a width below the narrowest corridor.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from . import _core
from .errors import InvalidArgumentError
from .maps import OccupancyMap

OCCUPIED = 0


@dataclass(frozen=True)
class ClosedGap:
    """One opening closed with a wall: centre (map metres), width (m, about twice the
    largest distance of its cells from the old walls) and size in cells."""

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
    wall = data == OCCUPIED
    r = 0.5 * w / float(m.resolution)
    to_wall = _core.distance_transform(wall)
    dilated = to_wall <= r
    closed = _core.distance_transform(~dilated) > r
    filled = closed & ~wall
    if not filled.any():
        return m, []
    regions, _ = ndimage.label(~(wall | filled))  # 4-connected non-wall regions after closing
    patches, n = ndimage.label(filled, structure=np.ones((3, 3), bool))
    keep = np.zeros(n + 1, bool)
    ring = ndimage.generate_binary_structure(2, 1)
    for j, sl in enumerate(ndimage.find_objects(patches), start=1):
        k = int(j)
        if sl is None:
            continue
        box = tuple(slice(max(s.start - 1, 0), s.stop + 1) for s in sl)
        patch = patches[box] == k
        around = ndimage.binary_dilation(patch, ring) & ~patch
        keep[k] = len(np.unique(regions[box][around & (regions[box] > 0)])) >= 2
    gate = keep[patches]
    out = data.copy()
    out[gate] = OCCUPIED
    gaps = []
    h = data.shape[0]
    res, (ox, oy, yaw) = float(m.resolution), m.origin
    for k in np.flatnonzero(keep).tolist():
        rows, cols = np.nonzero(patches == k)
        u, v = cols.mean() + 0.5, (h - 1 - rows.mean()) + 0.5
        c, s = np.cos(yaw), np.sin(yaw)
        x, y = ox + res * (c * u - s * v), oy + res * (s * u + c * v)
        width = 2.0 * float(to_wall[rows, cols].max()) * res
        gaps.append(ClosedGap(float(x), float(y), width, int(len(rows))))
    return OccupancyMap(data=out, resolution=m.resolution, origin=m.origin, path=m.path, meta=m.meta), gaps


__all__ = ["ClosedGap", "close_gaps"]
