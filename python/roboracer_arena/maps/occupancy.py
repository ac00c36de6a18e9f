"""ROS occupancy maps: loading any ``map_server`` YAML (PGM/PNG) and saving trinary maps.

The reading is done by the Rust core and follows nav2's ``map_io`` exactly: every
YAML field (``image``, ``resolution``, ``origin`` with yaw, ``negate``,
``occupied_thresh``, ``free_thresh``, ``mode`` trinary/scale/raw), PGM P2/P5 in 8 or
16 bit, PNG grey, grey+alpha, RGB and RGBA in 8 or 16 bit. The result is always a
trinary grid: 254 free, 0 occupied, 205 unknown (``scale`` mode's intermediate
percentages become unknown).

>>> from roboracer_arena import load_map
>>> m = load_map("maps/berlin.yaml")              # doctest: +SKIP
>>> m.data.shape, m.resolution, m.origin          # doctest: +SKIP
((600, 600), 0.05, (-11.60654, -26.520793, 0.0))
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
import numpy.typing as npt

from .. import _core
from ..errors import InvalidArgumentError

#: The image encodings ``save_map`` writes (the core also takes them in upper case).
ImageFormat = Literal["png", "pgm"]

FREE, OCCUPIED, UNKNOWN = 254, 0, 205


@dataclass(frozen=True, eq=False)
class OccupancyMap:
    """A trinary occupancy grid in the ROS map frame.

    Attributes:
        data: ``(H, W)`` uint8, 254 free / 0 occupied / 205 unknown; row 0 is the *top*
            image row, so ``data[-1, 0]`` is the cell at the origin.
        resolution: metres per cell.
        origin: ``(x, y, yaw)`` of the lower-left corner of the lower-left cell.
        path: the YAML it was loaded from (``None`` for maps made in memory).
        meta: what the file said besides the grid (``None`` for maps made in memory), a
            read-only ``_core.MapMeta``: ``image_path``, ``image_format``,
            ``image_channels``, ``image_bit_depth``, ``mode``, ``negate``, the thresholds
            and ``defaulted`` (optional keys that were absent).
    """

    data: npt.NDArray[np.uint8]
    resolution: float
    origin: tuple[float, float, float]
    path: Path | None = None
    meta: _core.MapMeta | None = None

    def __post_init__(self) -> None:
        data = np.ascontiguousarray(self.data, dtype=np.uint8)
        if data.ndim != 2 or 0 in data.shape:
            raise InvalidArgumentError(f"map data must be a non-empty 2-D array, got shape {data.shape}")
        if not (math.isfinite(self.resolution) and self.resolution > 0):
            raise InvalidArgumentError(f"resolution must be a finite number > 0, got {self.resolution}")
        origin = tuple(float(v) for v in self.origin)
        if len(origin) != 3 or not all(math.isfinite(v) for v in origin):
            raise InvalidArgumentError(f"origin must be three finite numbers (x, y, yaw), got {self.origin}")
        data.setflags(write=False)
        object.__setattr__(self, "data", data)
        object.__setattr__(self, "resolution", float(self.resolution))
        object.__setattr__(self, "origin", origin)

    @property
    def shape(self) -> tuple[int, int]:
        """``(height, width)`` in cells."""
        return (int(self.data.shape[0]), int(self.data.shape[1]))

    @property
    def image_path(self) -> Path:
        """The image a loaded map was read from (``InvalidArgumentError`` for a map made in memory)."""
        if self.meta is None:
            raise InvalidArgumentError("a map made in memory has no image file; save it first")
        return Path(self.meta.image_path)

    @property
    def megapixels(self) -> float:
        """Raster size in megapixels (the paper's "raster MP")."""
        return self.data.size / 1e6

    def save(self, yaml_path: str | Path, image_format: ImageFormat = "png") -> Path:
        """Write ``STEM.png`` (or ``.pgm``) beside ``yaml_path`` and the YAML, both
        atomically, in the trinary ``map_saver`` form. Returns the YAML path."""
        save_map(self.data, self.resolution, self.origin, yaml_path, image_format)
        return Path(yaml_path)


def load_map(path: str | Path) -> OccupancyMap:
    """Load a ROS map YAML and its image.

    Raises:
        MapIOError: the YAML or image cannot be read.
        MapFormatError: the YAML is malformed (missing/bad key, NaN resolution, ...), the
            image it names does not exist (with a hint when an image named after the
            YAML does), or the image is corrupt or empty.
    """
    path = Path(path)
    data, resolution, origin, meta = _core.load_map(path)
    return OccupancyMap(data, resolution, origin, path, meta)


def save_map(
    data: npt.ArrayLike,
    resolution: float,
    origin: tuple[float, float, float],
    yaml_path: str | Path,
    image_format: ImageFormat = "png",
) -> Path:
    """Write a trinary map (values 254/0/205 only) as image + YAML; returns the image path."""
    arr = np.ascontiguousarray(data, dtype=np.uint8)
    if arr.ndim != 2:
        raise InvalidArgumentError(f"map data must be 2-D, got shape {arr.shape}")
    o = tuple(float(v) for v in origin)
    if len(o) != 3:
        raise InvalidArgumentError(f"origin must be (x, y, yaw), got {origin}")
    return Path(_core.save_map(arr, float(resolution), o, Path(yaml_path), image_format))


__all__ = ["FREE", "ImageFormat", "OCCUPIED", "UNKNOWN", "OccupancyMap", "load_map", "save_map"]
