"""Racelines: the minimum-curvature line inside a track's corridor less a safety margin
(an iterated QP on lateral offsets, :mod:`.mincurv`), its speed profile under vehicle
limits (:mod:`.speed`, :mod:`.limits`), and the formats racing stacks read: TUM's CSV
(:mod:`.tum_csv`) and ForzaETH's ``global_waypoints.json`` (:mod:`.forza_json`).

>>> from roboracer_arena.raceline import plan_raceline, preset, resolve_track
>>> track, _ = resolve_track("gym-berlin")                          # doctest: +SKIP
>>> line = plan_raceline(track, preset("car"))                      # doctest: +SKIP
>>> line.lap_time                                                   # doctest: +SKIP
"""

from __future__ import annotations

from .format_error import RacelineFormatError
from .forza_json import ForzaWaypoints, read_forza_json
from .limits import PRESETS, VehicleLimits, load_limits, preset, resolve_limits
from .plan import DEFAULT_MARGIN, MODES, Raceline, plan_raceline
from .source import resolve_track
from .speed import SpeedProfile, speed_profile
from .tum_csv import TumRaceline, read_tum_csv

__all__ = [
    "DEFAULT_MARGIN",
    "MODES",
    "PRESETS",
    "ForzaWaypoints",
    "Raceline",
    "RacelineFormatError",
    "SpeedProfile",
    "TumRaceline",
    "VehicleLimits",
    "load_limits",
    "plan_raceline",
    "preset",
    "read_forza_json",
    "read_tum_csv",
    "resolve_limits",
    "resolve_track",
    "speed_profile",
]
