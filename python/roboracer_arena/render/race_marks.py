"""Race markings on a top-down picture: the racing direction as arrows along the
centreline, the start line and the grid where the env really puts the cars.

The track is the env's own :class:`~roboracer_arena.track.drivable.Track` (in its racing
direction), and the grid comes from the env's grid-start code
(:func:`~roboracer_arena.track.start_grid.grid_poses`) with the env's default grid spacing and
offset, so the picture shows what ``reset_poses="grid"`` does."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..config.sim import VehicleConfig
from ..track.start_grid import GRID_OFFSET, GRID_SPACING, grid_poses
from .frame import LegendEntry, direction_chevron
from .topdown import TopDown

ARROW = (0, 70, 230)
CAR = (214, 39, 40)  # the first vehicle's colour in the simulation renderer
#: Screen spacing of the direction arrows along the centreline (px).
ARROW_EVERY_PX = 140
#: Smallest drawn car length (px): a 0.5 m car on a 5 km circuit would vanish otherwise.
MIN_CAR_PX = 22


def draw_race_marks(
    canvas: TopDown, track: Any, vehicles: int = 1, cars: bool = True
) -> tuple[list[LegendEntry], dict[str, Any]]:
    """Draw direction arrows, start line and (with ``cars``) the grid on ``canvas``;
    returns the legend entries and what was drawn (direction, lap length, grid poses)."""
    _direction_arrows(canvas, track)
    poses = grid_poses(track, vehicles, GRID_SPACING, GRID_OFFSET)
    x, y, yaw = poses[0]
    # across the corridor, and at least 36 px long so it shows on a big circuit
    half = max(float(track.clearance([[x, y]])[0]), 18.0 / canvas.px_per_m())
    canvas.reserve(_start_line(canvas, (x, y), yaw, half))
    length, width = car_size(canvas)
    if cars:
        for p in poses:
            canvas.reserve(draw_car(canvas, p, length, width))
    canvas.label((x, y), "start", (0, 0, 0), marker=False, size_px=16)
    grid = "the car" if vehicles == 1 else f"{vehicles} cars"
    legend = [
        LegendEntry(f"racing direction ({track.direction})", ARROW, "arrow"),
        LegendEntry("start line", (0, 0, 0), "startline"),
    ]
    if cars:
        enlarged = length > VehicleConfig().chassis_length
        legend.append(LegendEntry(f"grid start: {grid}" + (" (enlarged)" if enlarged else ""), CAR, "car"))
    info = {
        "direction": track.direction,
        "lap_length_m": round(track.length, 2),
        "grid": [[round(float(v), 3) for v in p] for p in poses],
    }
    return legend, info


def _direction_arrows(canvas: TopDown, track: Any) -> None:
    """Arrow heads along the centreline every :data:`ARROW_EVERY_PX` screen pixels (at
    least 6 a lap), pointing the way the centreline runs."""
    loop, arc = track.loop, track.arclength
    n = int(np.clip(track.length * canvas.px_per_m() / ARROW_EVERY_PX, 6, 60))
    ring = np.vstack([loop, loop[:1]])
    canvas.polyline(ring, (*ARROW, 110), closed=False, min_px=2)
    for s in (np.arange(n) + 0.5) * track.length / n:
        i = min(int(np.searchsorted(arc, s, side="right")) - 1, len(loop) - 1)
        a, b = ring[i], ring[i + 1]
        t = (s - arc[i]) / max(arc[i + 1] - arc[i], 1e-12)
        pa, pb = canvas.to_px(np.array([a + t * (b - a), b]))
        v = pb - pa
        norm = float(np.hypot(*v))
        if norm < 1e-9:
            continue
        direction_chevron(
            canvas.draw, (float(pa[0]), float(pa[1])), (float(v[0] / norm), float(v[1] / norm)), ARROW, size=15
        )


def _start_line(canvas: TopDown, xy: tuple[float, float], yaw: float, half_width: float) -> np.ndarray:
    """A chequered line across the corridor at ``xy``, ``half_width`` to each side; returns its ends."""
    nx, ny = -math.sin(yaw), math.cos(yaw)
    a = np.array([xy[0] - half_width * nx, xy[1] - half_width * ny])
    b = np.array([xy[0] + half_width * nx, xy[1] + half_width * ny])
    width = max(5, round(0.15 * canvas.px_per_m()))
    canvas.polyline(np.array([a, b]), (0, 0, 0), min_px=width + 2)
    cells = 8
    for k in range(cells):
        if k % 2 == 0:
            p, q = a + (b - a) * k / cells, a + (b - a) * (k + 1) / cells
            canvas.polyline(np.array([p, q]), (255, 255, 255), min_px=width)
    return np.array([a, b])


def car_size(canvas: TopDown, vehicle: Any = None) -> tuple[float, float]:
    """Drawn length and width (m) of the car on ``canvas``: its own, enlarged so that it is
    at least :data:`MIN_CAR_PX` long (a 0.5 m car on a 5 km circuit would vanish)."""
    veh = vehicle or VehicleConfig()
    scale = max(1.0, MIN_CAR_PX / (veh.chassis_length * canvas.px_per_m()))
    return veh.chassis_length * scale, veh.chassis_width * scale


def draw_car(canvas: TopDown, pose: Any, length: float, width: float, colour: Any = CAR) -> np.ndarray:
    """The car as an oriented rectangle with a white line from its centre to its nose; returns its corners."""
    x, y, yaw = (float(v) for v in pose)
    c, s = math.cos(yaw), math.sin(yaw)
    hl, hw = length / 2, width / 2
    body = np.array([[hl, hw], [hl, -hw], [-hl, -hw], [-hl, hw]])
    corners = np.c_[x + body[:, 0] * c - body[:, 1] * s, y + body[:, 0] * s + body[:, 1] * c]
    canvas.polygon(corners, colour, outline=(0, 0, 0))
    canvas.polyline(np.array([[x, y], [x + hl * c, y + hl * s]]), (255, 255, 255), min_px=2)
    return corners
