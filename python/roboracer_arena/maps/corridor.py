"""Corridor geometry of a map: the one call the USD builder, the simulator and the track
library share.

:func:`extract_corridor` isolates the drivable ring of an occupancy map (filled maps
and thin-line maps alike), and derives from it, in the map frame (metres, Z up):

* ``walls``: the collision walls -- closed loops on the level set of the free-space
  distance field at ``wall_offset_m``, simplified; free space lies on the left of each
  loop (the outer wall runs counter-clockwise, the infield wall clockwise);
* ``ducts``: centre lines of the visual air-duct tubes, i.e. the smoothed corridor
  borders offset outward by the tube radius;
* ``centreline``: the medial line of the corridor, closed (no repeated end point),
  counter-clockwise, resampled every ``centreline_spacing_m``;
* ``meshes``: ``floor``, ``walls`` (extruded to ``wall_height_m``), ``ducts`` (the visual
  tubes) and ``rings`` (around the tubes) as ``(vertices (V, 3) float32, triangles (T, 3)
  uint32)``;
* the round-trip check: ``iou`` of the walls' re-rasterised drivable region with the
  corridor, and ``max_wall_deviation_cells``;
* ``corridor_mask`` (H, W) bool, ``border_contact_cells`` (corridor cells on the map
  edge, where the edge closes the corridor; 0 for a corridor fully walled in),
  ``timings`` per stage (seconds) and the effective ``params``.

Parameters (all optional; see :data:`DEFAULT_PARAMS`): ``wall_height_m``,
``wall_offset_m`` (positive moves the walls away from the free space),
``tube_diameter_m``, ``tube_segments``, ``ring_spacing_m``, ``ring_width_m``,
``ring_scale`` (ring radius / tube radius), ``simplify_tolerance_m`` (0 = half a cell),
``smoothing_iterations``, ``centreline_spacing_m``, ``floor_margin_m``. Unknown names
raise :class:`~roboracer_arena.errors.InvalidArgumentError`.

>>> from roboracer_arena.maps.corridor import extract_corridor
>>> geo = extract_corridor("maps/berlin.yaml")          # doctest: +SKIP
>>> geo.iou, len(geo.walls), geo.centreline.shape      # doctest: +SKIP
(0.9987, 2, (709, 2))
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from .. import _core
from ..errors import CorridorError, InvalidArgumentError
from .car_fit import NoRoomForCarError, check_start, clearance_cells, place_car
from .occupancy import OccupancyMap, load_map

Mesh = tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]

#: The builder's geometry defaults (one source of truth: the Rust ``BuildParams``;
#: mirrored by ``BuildConfig.geometry``).
DEFAULT_PARAMS: _core.GeometryConfigDoc = _core.config_defaults("build")


@dataclass(frozen=True, eq=False)
class CorridorGeometry:
    """Everything :func:`extract_corridor` derives from a map (see the module docs)."""

    walls: list[npt.NDArray[np.float64]]
    ducts: list[npt.NDArray[np.float64]]
    centreline: npt.NDArray[np.float64]
    meshes: dict[str, Mesh]
    #: Texture coordinates of the ``ducts`` mesh, face-varying: ``(st (U, 2) float32, one
    #: index per triangle corner (3 T,) uint32)``; ``u`` in metres along the duct, ``v``
    #: 0..1 around it, with seam rows/columns so a texture repeats continuously.
    duct_st: tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]
    iou: float
    max_wall_deviation_cells: float
    corridor_mask: npt.NDArray[np.bool_]
    border_contact_cells: int
    timings: dict[str, float]
    params: _core.GeometryConfigDoc
    map: OccupancyMap
    #: ``"track"`` (a closed corridor: centreline, laps, progress) or ``"open"`` (an open
    #: map, see :func:`extract_open`: walls only, ``centreline`` empty).
    kind: str = "track"
    #: An open map's start pose (x, y, yaw): the given one, else the map origin when it
    #: is drivable (f1tenth_gym_ros's default), else the free cell farthest from the walls.
    start_pose: tuple[float, float, float] | None = None
    #: Why a map asked for as a track is open: the corridor error (``open=None``).
    open_reason: str | None = None
    #: The openings closed with ``close_gaps_m`` (see :mod:`roboracer_arena.maps.gaps`).
    closed_gaps: tuple[Any, ...] = ()

    @property
    def vertex_count(self) -> int:
        """Vertices over all meshes."""
        return sum(int(v.shape[0]) for v, _ in self.meshes.values())

    @property
    def triangle_count(self) -> int:
        """Triangles over all meshes."""
        return sum(int(t.shape[0]) for _, t in self.meshes.values())

    @property
    def centreline_length(self) -> float:
        """Length (m) of the closed centreline."""
        return _core.polyline_length(self.centreline)


def extract_corridor(
    map_or_path: OccupancyMap | str | Path,
    params: dict[str, Any] | None = None,
    start: Sequence[float] | None = None,
    open: bool | None = False,
    unknown: str = "occupied",
    close_gaps_m: float | None = None,
) -> CorridorGeometry:
    """Isolate the drivable corridor of a map and build its geometry.

    Args:
        map_or_path: an :class:`OccupancyMap` or the path of a ROS map YAML.
        params: geometry parameters overriding :data:`DEFAULT_PARAMS`.
        start: optional pose ``(x, y)`` or ``(x, y, yaw)`` in map metres inside the
            corridor (the yaw is accepted and ignored; the centreline is always
            counter-clockwise). Without it the corridor is found automatically: the
            largest outermost free region that encloses an infield and does not leak.
            A region touching the map edge along more than 2 % of the border cells
            leaks (the exterior of a thin-line map); a few cells of contact are
            accepted, the map edge then acts as a wall (see ``border_contact_cells``).
        open: ``False`` (default): a closed corridor or an error. ``True``: build the map
            as an open map (:func:`extract_open`). ``None``: a closed corridor when the
            map has one, else an open map whose ``open_reason`` says why (the corridor
            error) — never silently: ``kind`` says which one was built.
        unknown: how an open map reads unknown cells (see :func:`extract_open`).
        close_gaps_m: close every opening in the walls up to this width (m) first
            (:func:`roboracer_arena.maps.gaps.close_gaps`): a hallway loop with doorways
            becomes a closed corridor. ``closed_gaps`` lists each gap closed.

    Raises:
        CorridorError: no closed corridor (blank or open map), walls that leak (the
            fill reaches the map border; the message gives the map coordinates), an
            empty map, or a start pose off the map / not on a free cell.
        InvalidArgumentError: a bad parameter name or value.
        MapIOError, MapFormatError: when given a path that does not load.
    """
    m = map_or_path if isinstance(map_or_path, OccupancyMap) else load_map(map_or_path)
    if close_gaps_m is not None:
        from .gaps import close_gaps

        m, gaps = close_gaps(m, close_gaps_m)
        geo = extract_corridor(m, params, start, open, unknown)
        return replace(geo, closed_gaps=tuple(gaps))
    if open:
        return extract_open(m, params, start, unknown)
    s = None if start is None else [float(v) for v in start]
    core_params = _params(params)
    try:
        out = _core.build_geometry(m.data, m.resolution, m.origin, core_params, s)
    except CorridorError as e:
        err = CorridorError(f"{m.path}: {e}" if m.path is not None else str(e))
        if open is None:
            try:
                geo = extract_open(m, params, start, unknown)
            except NoRoomForCarError:
                raise  # it names the map and its free space: more than "no closed corridor"
            except CorridorError:
                raise err from None
            return replace(geo, open_reason=str(e))
        raise err from None
    return _geometry(out, m)


#: How an open map reads unknown cells: as walls (nav2's planners with
#: ``allow_unknown: false``) or as floor (F1TENTH Gym thresholds the image at 128, so 205
#: is free).
UNKNOWN_AS = ("occupied", "free")


def extract_open(
    map_or_path: OccupancyMap | str | Path,
    params: dict[str, Any] | None = None,
    start: Sequence[float] | None = None,
    unknown: str = "occupied",
) -> CorridorGeometry:
    """Build a map as an *open map*, the way F1TENTH Gym simulates any map: every free
    cell is floor, every occupied cell (and unknown cell, with ``unknown="occupied"``)
    and the map edge are walls. Walls, ducts and meshes as for a track; no centreline
    (``centreline`` is empty), so no lap and no progress.

    Args:
        map_or_path: an :class:`OccupancyMap` or the path of a ROS map YAML (read with
            nav2's rules: ``occupied_thresh``, ``free_thresh``, ``negate``).
        params: geometry parameters, as for :func:`extract_corridor`.
        start: the start pose ``(x, y)`` or ``(x, y, yaw)`` (yaw 0 when omitted), as
            f1tenth_gym_ros gives it; it must be on a drivable cell. Default: the map
            origin (0, 0, 0), f1tenth_gym_ros's default, when it is drivable and at least
            :data:`ORIGIN_START_CLEARANCE_M` from the walls; else the drivable cell
            farthest from the walls, heading along its longest free line.
        unknown: one of :data:`UNKNOWN_AS`.

    Raises:
        CorridorError: no drivable cell, or a start off the map or not on a drivable cell.
        InvalidArgumentError: a bad parameter or ``unknown`` value.
    """
    if unknown not in UNKNOWN_AS:
        raise InvalidArgumentError(f"unknown must be one of {UNKNOWN_AS}, got {unknown!r}")
    m = map_or_path if isinstance(map_or_path, OccupancyMap) else load_map(map_or_path)
    where = f"{m.path}: " if m.path is not None else ""
    s = None if start is None else [float(v) for v in start]
    try:
        out = _core.build_open_geometry(
            m.data, m.resolution, m.origin, _params(params), unknown_free=unknown == "free", start=s
        )
    except CorridorError as e:
        raise CorridorError(f"{where}{e}") from None
    geo = _geometry(out, m)
    mask = np.asarray(geo.corridor_mask, bool)
    origin = (float(m.origin[0]), float(m.origin[1]), float(m.origin[2]))
    if s is not None:  # the user's start: the whole car must fit there
        x, y, yaw = (float(v) for v in out.start_pose or ())
        check_start(mask, origin, float(m.resolution), (x, y, yaw), where)
    else:
        x, y, yaw = _default_start(geo, out.start_pose, where)
    return replace(geo, kind="open", start_pose=(x, y, yaw))


#: Clearance (m) the map origin needs to be an open map's default start.
ORIGIN_START_CLEARANCE_M = 0.3


def _default_start(geo: CorridorGeometry, farthest: Any, where: str = "") -> tuple[float, float, float]:
    """An open map's default start, as f1tenth_gym_ros gives it: the map-frame origin
    (0, 0) heading along +x (its ``sx, sy, stheta`` defaults; a SLAM map starts where the
    car was) when that is a drivable cell at least :data:`ORIGIN_START_CLEARANCE_M` from
    the walls and the map edge and the car's whole footprint fits there; else the drivable
    cell farthest from the walls (the core's choice), else the best-clearance place where
    the footprint fits (:func:`roboracer_arena.maps.car_fit.place_car`); a map with none is a
    :class:`~roboracer_arena.maps.car_fit.NoRoomForCarError` naming the map and its free space."""
    m = geo.map
    mask = np.asarray(geo.corridor_mask, bool)
    origin = (float(m.origin[0]), float(m.origin[1]), float(m.origin[2]))
    preferred: list[tuple[float, float, float]] = []
    c, s = np.cos(m.origin[2]), np.sin(m.origin[2])
    u = (c * -m.origin[0] + s * -m.origin[1]) / m.resolution
    v = (-s * -m.origin[0] + c * -m.origin[1]) / m.resolution
    h, w = m.data.shape
    if 0 <= u < w and 0 <= v < h:
        col, row = int(u), h - 1 - int(v)
        if mask[row, col]:
            clear = float(clearance_cells(mask)[row, col]) * m.resolution
            if clear >= ORIGIN_START_CLEARANCE_M:
                preferred.append((0.0, 0.0, 0.0))
    if farthest is not None:
        x, y, yaw = (float(v) for v in farthest)
        preferred.append((x, y, yaw))
    return place_car(mask, origin, float(m.resolution), preferred, where)


def _params(params: Mapping[str, Any] | None) -> dict[str, Any]:
    """``params`` as the core reads them: a mapping whose numbers are finite (the core
    checks the names, types and ranges: ``ConfigError``)."""
    if params is None:
        return {}
    if not isinstance(params, Mapping):
        raise InvalidArgumentError(f"params must be a mapping of finite numbers, got {type(params).__name__}")
    bad = {k: v for k, v in params.items() if isinstance(v, float) and not math.isfinite(v)}
    if bad:
        raise InvalidArgumentError(f"params must be a mapping of finite numbers: {bad}")
    return dict(params)


def _geometry(out: _core.Geometry, m: OccupancyMap) -> CorridorGeometry:
    return CorridorGeometry(
        walls=list(out.walls),
        ducts=list(out.ducts),
        centreline=out.centreline,
        meshes={k: (v, t) for k, (v, t) in out.meshes.items()},
        duct_st=out.duct_st,
        iou=out.iou,
        max_wall_deviation_cells=out.max_wall_deviation_cells,
        corridor_mask=out.corridor_mask,
        border_contact_cells=out.border_contact_cells,
        timings=dict(out.timings),
        params=out.params.copy(),
        map=m,
    )


__all__ = ["DEFAULT_PARAMS", "UNKNOWN_AS", "CorridorGeometry", "Mesh", "extract_corridor", "extract_open"]
