"""Whether the car fits on an open map: its whole footprint, not its centre.

An open map's start (the pose a user gives, the map origin, or the free cell farthest
from the walls) must hold the car's collision box (``VehicleConfig.chassis_length`` x
``chassis_width``, centred on the pose) plus :data:`START_MARGIN_M` on free cells, the map
edge counting as a wall. A start that does not fit would put the car across a wall (every
episode would end on its first step); a map with no such place at all is refused with
:class:`NoRoomForCarError` (a :class:`~roboracer_arena.errors.CorridorError`, CLI exit 2),
naming the map and its free space.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _core
from ..config.sim import SimConfig
from ..errors import CorridorError

#: Free space (m) the start needs beyond the car's box on every side: the walls are
#: smoothed within about half a cell of the raster, and the car must not start touching one.
START_MARGIN_M = 0.05
#: Headings tried at a candidate cell when the first one does not fit.
_YAWS = 16
#: Best-clearance cells tried before a map is declared too tight.
_CANDIDATES = 64
#: Most sample points per side of the footprint (a 1 mm raster is sampled at ~1.4 mm).
_MAX_SAMPLES = 400


class NoRoomForCarError(CorridorError):
    """An open map has no place, or the given start is no place, for the car's footprint."""


@dataclass(frozen=True)
class FreeSpace:
    """The free region's widest point: the clearance (m, from its centre to the nearest
    wall or map edge), where it is, and how much free floor there is."""

    clearance_m: float
    at: tuple[float, float]
    free_cells: int
    free_area_m2: float

    def text(self) -> str:
        if not self.free_cells:
            return "it has no free cell"
        return (
            f"its free space is {self.free_cells} cell{'s' if self.free_cells != 1 else ''} ({self.free_area_m2:.2f} m²), at most "
            f"{2 * self.clearance_m:.2f} m across (at {self.at[0]:.2f}, {self.at[1]:.2f})"
        )


def car_box() -> tuple[float, float]:
    """The car's collision box (length, width) in metres."""
    v = SimConfig().vehicle
    return float(v.chassis_length), float(v.chassis_width)


def _cells(shape: tuple[int, int], origin: tuple[float, float, float], res: float, xy: np.ndarray):
    ox, oy, th = origin
    c, s = math.cos(th), math.sin(th)
    dx, dy = xy[:, 0] - ox, xy[:, 1] - oy
    u = np.floor((c * dx + s * dy) / res)
    v = np.floor((-s * dx + c * dy) / res)
    h, w = shape
    ok = np.isfinite(u) & np.isfinite(v) & (u >= 0) & (u < w) & (v >= 0) & (v < h)
    rows = np.where(ok, h - 1 - np.where(ok, v, 0), 0).astype(np.int64)
    cols = np.where(ok, u, 0).astype(np.int64)
    return rows, cols, ok


def footprint_fits(
    mask: np.ndarray, origin: tuple[float, float, float], res: float, pose: tuple[float, float, float]
) -> bool:
    """True when the car's box at ``pose`` (x, y, yaw), grown by :data:`START_MARGIN_M`,
    covers only free cells of ``mask`` (row 0 at the top of the image; off the map is a wall)."""
    length, width = car_box()
    hl, hw = length / 2 + START_MARGIN_M, width / 2 + START_MARGIN_M
    nx = min(_MAX_SAMPLES, int(math.ceil(2 * hl / (res / 2))) + 1)
    ny = min(_MAX_SAMPLES, int(math.ceil(2 * hw / (res / 2))) + 1)
    gx, gy = np.meshgrid(np.linspace(-hl, hl, nx), np.linspace(-hw, hw, ny))
    x, y, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    xy = np.column_stack([x + c * gx.ravel() - s * gy.ravel(), y + s * gx.ravel() + c * gy.ravel()])
    rows, cols, ok = _cells(mask.shape, origin, res, xy)
    return bool(ok.all() and mask[rows, cols].all())


def clearance_cells(mask: np.ndarray) -> np.ndarray:
    """Distance (cells) from each free cell's centre to the nearest non-free cell's centre,
    the map edge counting as a wall (0 on non-free cells)."""
    padded = np.pad(np.asarray(mask, bool), 1, constant_values=False)
    return np.asarray(_core.distance_transform(~padded), dtype=np.float64)[1:-1, 1:-1]


def _centre(shape: tuple[int, int], origin: tuple[float, float, float], res: float, row: int, col: int):
    ox, oy, th = origin
    u, v = (col + 0.5) * res, (shape[0] - 1 - row + 0.5) * res
    c, s = math.cos(th), math.sin(th)
    return ox + c * u - s * v, oy + s * u + c * v


def free_space(mask: np.ndarray, origin: tuple[float, float, float], res: float) -> FreeSpace:
    """Where the free region of ``mask`` is widest, and how big it is."""
    mask = np.asarray(mask, bool)
    n = int(mask.sum())
    if not n:
        return FreeSpace(0.0, (0.0, 0.0), 0, 0.0)
    dist = clearance_cells(mask)
    row, col = np.unravel_index(int(np.argmax(dist)), dist.shape)
    clear = max(0.0, float(dist[row, col]) - 0.5) * res
    return FreeSpace(clear, _centre(mask.shape, origin, res, int(row), int(col)), n, n * res * res)


def place_car(
    mask: np.ndarray,
    origin: tuple[float, float, float],
    res: float,
    preferred: list[tuple[float, float, float]],
    where: str = "",
) -> tuple[float, float, float]:
    """The first pose of ``preferred`` whose footprint fits, else a pose at one of the
    best-clearance cells (headings from the preferred one's round the circle) that does;
    :class:`NoRoomForCarError` naming ``where`` (the map) and its free space when none does."""
    mask = np.asarray(mask, bool)
    for pose in preferred:
        if footprint_fits(mask, origin, res, pose):
            return pose
    dist = clearance_cells(mask)
    length, width = car_box()
    need_cells = (width / 2 + START_MARGIN_M) / res  # narrower than this nowhere holds the car
    flat = dist.ravel()
    order = np.argsort(flat)[::-1][:_CANDIDATES]
    yaw0 = preferred[0][2] if preferred else 0.0
    for k in order:
        if flat[k] + 0.5 < need_cells:
            break
        row, col = np.unravel_index(int(k), dist.shape)
        x, y = _centre(mask.shape, origin, res, int(row), int(col))
        for j in range(_YAWS):
            pose = (x, y, yaw0 + math.pi * j / _YAWS)
            if footprint_fits(mask, origin, res, pose):
                return pose
    raise NoRoomForCarError(
        f"{where}no room for the car on this open map: its {length:.2f} x {width:.2f} m box needs "
        f"{width + 2 * START_MARGIN_M:.2f} m of free width and {length + 2 * START_MARGIN_M:.2f} m of length, "
        f"and {free_space(mask, origin, res).text()}"
    )


def check_start(
    mask: np.ndarray, origin: tuple[float, float, float], res: float, pose: tuple[float, float, float], where: str = ""
) -> None:
    """:class:`NoRoomForCarError` unless the car's footprint fits at the user's ``pose``."""
    if footprint_fits(np.asarray(mask, bool), origin, res, pose):
        return
    length, width = car_box()
    x, y, yaw = pose
    raise NoRoomForCarError(
        f"{where}the start ({x:.3f}, {y:.3f}, {yaw:.3f}) does not fit the car: its {length:.2f} x {width:.2f} m box "
        f"(+{START_MARGIN_M:.2f} m) there overlaps a wall, an unknown cell or the map edge; "
        f"{free_space(mask, origin, res).text()}"
    )


__all__ = [
    "START_MARGIN_M",
    "FreeSpace",
    "NoRoomForCarError",
    "car_box",
    "check_start",
    "footprint_fits",
    "free_space",
    "place_car",
]
