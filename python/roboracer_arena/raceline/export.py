"""A :class:`~.plan.Raceline` in the formats racing stacks read: TUM's CSV
(:mod:`.tum_csv`) and ForzaETH's ``global_waypoints.json`` (:mod:`.forza_json`), written
together atomically (all of them appear, or none)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..foundation.fileio import atomic_paths
from .bounds import lateral_bounds
from .clearance import WallDistance
from .forza_json import forza_text
from .geometry import closed_path
from .plan import Raceline
from .tum_csv import tum_text


def raceline_csv_text(line: Raceline) -> str:
    """TUM's CSV of ``line`` (the closing row included)."""
    return tum_text(
        line.s, line.xy, line.psi, line.kappa, line.vx, line.ax, line.length, line.limits.sha1(), line.track
    )


def raceline_forza_text(line: Raceline, track: Any, step: float = 0.1) -> str:
    """ForzaETH's ``global_waypoints.json`` of ``line`` on ``track`` (its centreline
    resampled every ``step`` m with its distances to the walls)."""
    c = closed_path(track.loop, step)
    c_left, c_right = lateral_bounds(c.xy, c.normals, WallDistance(track.walls), 0.0)
    centre = {
        "s_m": c.s,
        "x_m": c.xy[:, 0],
        "y_m": c.xy[:, 1],
        "d_right": c_right,
        "d_left": c_left,
        "psi_rad": c.psi,
        "kappa_radpm": c.kappa,
    }
    race = {
        "s_m": line.s,
        "d_m": np.zeros(len(line.s)),
        "x_m": line.xy[:, 0],
        "y_m": line.xy[:, 1],
        "d_right": line.d_right,
        "d_left": line.d_left,
        "psi_rad": np.angle(np.exp(1j * line.psi)),
        "kappa_radpm": line.kappa,
        "vx_mps": line.vx,
        "ax_mps2": line.ax,
    }
    mode = "IQP" if line.mode == "mincurv" else "min-time"
    info = (
        f"roboracer-arena {mode} raceline of {line.track}; limits {line.limits.name}; "
        f"{mode} estimated lap time: {line.lap_time:.4f}s; {mode} maximum speed: {float(line.vx.max()):.4f}m/s; "
    )
    return forza_text(race, centre, line.lap_time, info)


def write_outputs(files: Sequence[tuple[Path, str | bytes]]) -> list[Path]:
    """Write every ``(path, text or bytes)`` atomically as a set."""
    paths = [Path(p) for p, _ in files]
    with atomic_paths(paths) as temps:
        for tmp, (_, data) in zip(temps, files):
            tmp.write_bytes(data.encode() if isinstance(data, str) else data)
    return paths
