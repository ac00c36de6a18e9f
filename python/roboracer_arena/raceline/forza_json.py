"""ForzaETH race_stack's ``global_waypoints.json``: every message its global planner
saves, as ``rospy_message_converter`` dictionaries, so their ``read_global_waypoints``
rebuilds them. The keys it reads:

* ``map_info_str`` ``{"data": str}`` and ``est_lap_time`` ``{"data": float}``;
* ``centerline_waypoints``, ``global_traj_wpnts_iqp`` (the raceline) and
  ``global_traj_wpnts_sp`` (their shortest-path line; here the same raceline) as
  ``f110_msgs/WpntArray``: ``{"header": ..., "wpnts": [Wpnt, ...]}`` with per point
  ``id, s_m, d_m, x_m, y_m, d_right, d_left, psi_rad, kappa_radpm, vx_mps, ax_mps2``;
* ``centerline_markers``, ``global_traj_markers_iqp``, ``global_traj_markers_sp`` and
  ``trackbounds_markers`` as ``visualization_msgs/MarkerArray`` (written empty: they are
  RViz decoration, rebuilt from the waypoints by their publisher).

``psi_rad`` is the heading from +x in (-pi, pi] (their planner adds pi/2 to TUM's), ``s_m``
the arc length along the line, ``d_m`` the lateral offset from it (0 on the line itself),
``d_left``/``d_right`` the distance to the walls.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..foundation.fileio import atomic_write_text, parse_json, read_text
from .format_error import RacelineFormatError

WPNT_FIELDS = ("id", "s_m", "d_m", "x_m", "y_m", "d_right", "d_left", "psi_rad", "kappa_radpm", "vx_mps", "ax_mps2")
REQUIRED_KEYS = (
    "map_info_str",
    "est_lap_time",
    "centerline_markers",
    "centerline_waypoints",
    "global_traj_markers_iqp",
    "global_traj_wpnts_iqp",
    "global_traj_markers_sp",
    "global_traj_wpnts_sp",
    "trackbounds_markers",
)


@dataclass(frozen=True)
class ForzaWaypoints:
    """What :func:`read_forza_json` returns: the raceline's columns (N,) by Wpnt field name,
    the centreline's, the estimated lap time and the info string."""

    raceline: dict[str, np.ndarray]
    centerline: dict[str, np.ndarray]
    est_lap_time: float
    map_info_str: str


def _header() -> dict[str, Any]:
    return {"seq": 0, "stamp": {"secs": 0, "nsecs": 0}, "frame_id": "map"}


def wpnt_array(columns: dict[str, np.ndarray]) -> dict[str, Any]:
    """A ``WpntArray`` dictionary from columns (each (N,), ``id`` optional)."""
    n = len(columns["x_m"])
    cols = {k: np.asarray(columns.get(k, np.zeros(n)), dtype=np.float64) for k in WPNT_FIELDS if k != "id"}
    wpnts = [{"id": i, **{k: round(float(cols[k][i]), 7) + 0.0 for k in WPNT_FIELDS if k != "id"}} for i in range(n)]
    return {"header": _header(), "wpnts": wpnts}


def forza_text(
    raceline: dict[str, np.ndarray], centerline: dict[str, np.ndarray], est_lap_time: float, info: str
) -> str:
    """The JSON text of a ``global_waypoints.json``."""
    empty: dict[str, list[Any]] = {"markers": []}
    doc = {
        "map_info_str": {"data": info},
        "est_lap_time": {"data": round(float(est_lap_time), 4)},
        "centerline_markers": empty,
        "centerline_waypoints": wpnt_array(centerline),
        "global_traj_markers_iqp": empty,
        "global_traj_wpnts_iqp": wpnt_array(raceline),
        "global_traj_markers_sp": empty,
        "global_traj_wpnts_sp": wpnt_array(raceline),
        "trackbounds_markers": empty,
    }
    return json.dumps(doc) + "\n"


def write_forza_json(path: str | Path, text: str) -> Path:
    """Write ``global_waypoints.json`` atomically."""
    atomic_write_text(path, text)
    return Path(path)


def _columns(doc: Any, key: str, p: Path) -> dict[str, np.ndarray]:
    arr = doc.get(key)
    if not isinstance(arr, dict) or not isinstance(arr.get("wpnts"), list):
        raise RacelineFormatError(f"{p}: {key} must be a WpntArray object with a 'wpnts' list")
    wp = arr["wpnts"]
    if len(wp) < 4:
        raise RacelineFormatError(f"{p}: {key}.wpnts has {len(wp)} points, a line needs at least 4")
    out: dict[str, list[float]] = {k: [] for k in WPNT_FIELDS}
    for i, w in enumerate(wp):
        if not isinstance(w, dict):
            raise RacelineFormatError(f"{p}: {key}.wpnts[{i}] must be an object")
        for k in WPNT_FIELDS:
            v = w.get(k, 0)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not np.isfinite(v):
                raise RacelineFormatError(f"{p}: {key}.wpnts[{i}].{k} must be a finite number, got {v!r}")
            out[k].append(float(v))
        for k in ("x_m", "y_m"):
            if k not in w:
                raise RacelineFormatError(f"{p}: {key}.wpnts[{i}] has no {k}")
    return {k: np.asarray(v) for k, v in out.items()}


def read_forza_json(path: str | Path) -> ForzaWaypoints:
    """A ``global_waypoints.json`` (every key their reader needs must be there); a
    :class:`RacelineFormatError` naming the file and the field if not."""
    p = Path(path)
    doc = parse_json(read_text(p, "global_waypoints.json"), p, "global_waypoints.json", RacelineFormatError)
    if not isinstance(doc, dict):
        raise RacelineFormatError(f"{p}: global_waypoints.json must be a JSON object")
    missing = [k for k in REQUIRED_KEYS if k not in doc]
    if missing:
        raise RacelineFormatError(f"{p}: missing {', '.join(missing)}")
    lap = doc["est_lap_time"].get("data") if isinstance(doc["est_lap_time"], dict) else None
    if isinstance(lap, bool) or not isinstance(lap, (int, float)) or not np.isfinite(lap) or lap < 0:
        raise RacelineFormatError(f"{p}: est_lap_time.data must be a finite number >= 0, got {lap!r}")
    info = doc["map_info_str"].get("data") if isinstance(doc["map_info_str"], dict) else None
    if not isinstance(info, str):
        raise RacelineFormatError(f"{p}: map_info_str.data must be a string")
    for k in REQUIRED_KEYS:
        if k.endswith("markers") and not (isinstance(doc[k], dict) and isinstance(doc[k].get("markers"), list)):
            raise RacelineFormatError(f"{p}: {k} must be a MarkerArray object with a 'markers' list")
    return ForzaWaypoints(
        raceline=_columns(doc, "global_traj_wpnts_iqp", p),
        centerline=_columns(doc, "centerline_waypoints", p),
        est_lap_time=float(lap),
        map_info_str=info,
    )
