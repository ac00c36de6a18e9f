"""One lap of any map on the PhysX car, the way ``drive --engine physx`` runs it: the map
(a YAML or a catalog id) is built with ``build --car`` into a temporary folder (or a
given stage is used), the controller (pure pursuit, or a policy file's) drives the
PhysX vehicle at the env's control rate, its lidar cast by PhysX itself
(:func:`~roboracer_arena.physx.check.physx_scan`: single-sided raycasts against the
stage's collision walls), and the lap is judged on the track's centreline.

A contact is judged from the trace: the chassis footprint (its rectangle's corners and
edge midpoints) closer than :data:`CONTACT_M` to a wall at any control step (PhysX
resolves a hit within a step or two, so the car is pressed against the wall then).
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import numpy as np

from ..builder import build_environment
from ..catalog.catalog_file import load_catalog
from ..catalog.entry_tracks import entry_track
from ..envs.track_argument import resolve_tracks
from ..foundation.frozen_model import FrozenModel
from .drive import drive_physx

#: A footprint point closer than this to a wall counts as a contact (m).
CONTACT_M = 0.02


class PhysxLap(FrozenModel):
    """The outcome of :func:`physx_lap`."""

    track: str
    engine: str
    controller: str
    completed: bool
    contact: bool
    lap_time_s: float | None
    sim_time_s: float
    min_clearance_m: float
    max_lateral_error_m: float
    wall_seconds: float

    @property
    def clean(self) -> bool:
        return self.completed and not self.contact


def map_and_track(map_arg: str | Path) -> tuple[Path, Any]:
    """``(map YAML, Track in its racing direction)`` for a map path or a catalog id."""
    p = Path(map_arg)
    if p.suffix.lower() in (".yaml", ".yml") or p.is_file():
        return p, resolve_tracks([str(p)])[0]
    cat = load_catalog()
    entry = cat.select_many(str(map_arg))
    if len(entry) != 1:
        raise ValueError(f"{map_arg!r} names {len(entry)} catalog tracks, not one")
    return cat.map_path(entry[0]), entry_track(cat, entry[0])[0]


def footprint_clearance(
    track: Any, x: np.ndarray, y: np.ndarray, yaw: np.ndarray, length: float, width: float
) -> np.ndarray:
    """Per pose, the smallest wall clearance (m) of the chassis rectangle's 8 outline points."""
    hl, hw = length / 2, width / 2
    local = np.array([[hl, hw], [hl, 0], [hl, -hw], [0, -hw], [-hl, -hw], [-hl, 0], [-hl, hw], [0, hw]])
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    px = x[:, None] + c * local[:, 0] - s * local[:, 1]
    py = y[:, None] + s * local[:, 0] + c * local[:, 1]
    d = track.clearance(np.stack([px.ravel(), py.ravel()], 1))
    return d.reshape(px.shape).min(axis=1)


def physx_lap(
    map_arg: str | Path,
    controller_for: Any,
    sim: Any,
    control_rate_hz: float,
    *,
    stage: str | Path | None = None,
    name: str = "pure pursuit",
    max_seconds: float | None = None,
) -> PhysxLap:
    """Drive one lap of ``map_arg`` on the PhysX car (see the module docstring).
    ``controller_for(track) -> controller(scan, odometry)``; ``sim``: the car's and lidar's
    config (a :class:`~roboracer_arena.config.sim.SimConfig`)."""
    yaml_path, track = map_and_track(map_arg)
    limit = max_seconds if max_seconds is not None else track.length / 0.5 + 30.0
    with tempfile.TemporaryDirectory(prefix="roboracer-physx-") as tmp:
        if stage is None:
            stage = Path(tmp) / "stage.usda"
            build_environment(yaml_path, stage, car=True)
        trace = drive_physx(
            stage,
            controller_for(track),
            sim,
            track=track,
            control_rate_hz=control_rate_hz,
            max_seconds=limit,
            lidar="physx",
        )
    x, y, yaw = (np.asarray(getattr(trace, k)) for k in ("x", "y", "yaw"))
    veh = sim.vehicle
    clear = footprint_clearance(track, x, y, yaw, veh.chassis_length, veh.chassis_width)
    min_clear = float(clear.min()) if len(clear) else 0.0
    return PhysxLap(
        track=track.name,
        engine=trace.engine,
        controller=name,
        completed=trace.lap_time_s is not None,
        contact=min_clear < CONTACT_M,
        lap_time_s=trace.lap_time_s,
        sim_time_s=float(trace.t[-1]) if trace.t else 0.0,
        min_clearance_m=round(min_clear, 4),
        max_lateral_error_m=round(float(max(trace.lateral_error, default=0.0)), 4),
        wall_seconds=round(trace.wall_seconds, 2),
    )
