"""The racing driver: the project's pure pursuit (:mod:`roboracer_arena.drivers`, speed-
dependent lookahead) on a raceline instead of the centreline, commanding the raceline's
planned speed. Its own curvature limits are set out of the way, so the speed it commands
is the plan's (the driver still looks ~0.6 m ahead and takes the lowest planned speed
there, which makes it brake a little early).

>>> line = plan_raceline(track, preset("car"))                      # doctest: +SKIP
>>> result = drive_raceline("gym-berlin", line)                     # doctest: +SKIP
>>> result.lap_times, line.lap_time                                 # doctest: +SKIP
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import gymnasium as gym
import numpy as np

from ..drivers import DriveResult, PurePursuitParams, drive_laps
from .plan import Raceline

#: Lookahead of the racing driver: 0.6 m + 0.2 s x speed, at most 2.2 m.
RACING_LOOKAHEAD = {"lookahead_min": 0.6, "lookahead_gain": 0.2, "lookahead_max": 2.2}


def racing_params(line: Raceline, base: PurePursuitParams | None = None) -> PurePursuitParams:
    """Pure-pursuit settings that follow ``line``'s speed plan (its own speed profile
    limits lifted above the plan's, so the plan caps the speed)."""
    p = base or PurePursuitParams()
    return replace(
        p,
        max_speed=float(line.vx.max()),
        min_speed=min(p.min_speed, float(line.vx.min())),
        lateral_accel=1e3,
        brake_decel=1e3,
        accel=1e3,
        spacing=min(p.spacing, 0.05),
        **RACING_LOOKAHEAD,
    )


class StartOnLine(gym.Wrapper):
    """Starts the car standing on the raceline at its first point (the one nearest the
    start line), heading along it, as a racing car lines up: from the centreline grid
    the line can be a metre and a half to the side, too far to join within a car length."""

    def __init__(self, env: gym.Env, line: Raceline) -> None:
        super().__init__(env)
        self._pose = np.array([line.xy[0, 0], line.xy[0, 1], line.psi[0]])

    def __getattr__(self, name: str) -> Any:  # forward env helpers (gymnasium>=1.0 does not)
        return getattr(self.env, name)

    def reset(self, **kwargs: Any):
        options = dict(kwargs.pop("options", None) or {})
        options.setdefault("poses", self._pose)
        return self.env.reset(options=options, **kwargs)


def drive_raceline(track: Any, line: Raceline, laps: int = 1, **kwargs: Any) -> DriveResult:
    """Drive ``laps`` laps of ``track`` (anything ``drive_laps`` takes: a catalog id, a map
    YAML, a Track) on ``line`` at its planned speeds, from a standing start on the line
    (:class:`StartOnLine`); laps count along the track's centreline."""
    params = kwargs.pop("params", None) or racing_params(line)
    outer = kwargs.pop("env_wrapper", None)

    def wrap(env: gym.Env) -> gym.Env:
        inner = StartOnLine(env, line)
        return outer(inner) if outer is not None else inner

    return drive_laps(track, laps, params=params, path=line.path, env_wrapper=wrap, **kwargs)
