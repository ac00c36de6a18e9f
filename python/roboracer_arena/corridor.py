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

>>> from roboracer_arena.corridor import extract_corridor
>>> geo = extract_corridor("maps/berlin.yaml")          # doctest: +SKIP
>>> geo.iou, len(geo.walls), geo.centreline.shape      # doctest: +SKIP
(0.9987, 2, (709, 2))
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _core
from .errors import CorridorError, InvalidArgumentError
from .maps import OccupancyMap, load_map

Mesh = tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]

#: The builder's geometry defaults (one source of truth: the Rust ``BuildParams``;
#: mirrored by ``BuildConfig.geometry``).
DEFAULT_PARAMS: dict[str, Any] = json.loads(_core.config_defaults("build"))


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
    params: dict[str, Any]
    map: OccupancyMap

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

    Raises:
        CorridorError: no closed corridor (blank or open map), walls that leak (the
            fill reaches the map border; the message gives the map coordinates), an
            empty map, or a start pose off the map / not on a free cell.
        InvalidArgumentError: a bad parameter name or value.
        MapIOError, MapFormatError: when given a path that does not load.
    """
    m = map_or_path if isinstance(map_or_path, OccupancyMap) else load_map(map_or_path)
    s = None if start is None else [float(v) for v in start]
    try:
        params_json = json.dumps(params or {}, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise InvalidArgumentError(f"params must be a JSON-able mapping of finite numbers: {e}") from None
    try:
        out = _core.build_geometry(m.data, m.resolution, m.origin, params_json, s)
    except CorridorError as e:
        if m.path is None:
            raise
        raise CorridorError(f"{m.path}: {e}") from None
    return CorridorGeometry(
        walls=list(out["walls"]),
        ducts=list(out["ducts"]),
        centreline=out["centreline"],
        meshes={k: (v, t) for k, (v, t) in out["meshes"].items()},
        duct_st=out["duct_st"],
        iou=float(out["iou"]),
        max_wall_deviation_cells=float(out["max_wall_deviation_cells"]),
        corridor_mask=out["corridor_mask"],
        border_contact_cells=int(out["border_contact_cells"]),
        timings=dict(out["timings"]),
        params=json.loads(out["params_json"]),
        map=m,
    )


__all__ = ["DEFAULT_PARAMS", "CorridorGeometry", "Mesh", "extract_corridor"]
