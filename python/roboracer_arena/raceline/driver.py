"""The racing driver: the project's pure pursuit (:mod:`roboracer_arena.drivers`, speed-
dependent lookahead) on a raceline instead of the centreline, commanding the raceline's
planned speed, from a standing start on the line.

The line it races is planned for it (:func:`plan_for_driver`) with the car's measured
limits derated to what pure pursuit holds in our physics: 75 % of the lateral grip and
35 % of the longitudinal (braking hard into a corner spins the simulated car, as it does
a real 1:10 car: the rear goes light), and a 0.15 m margin for its tracking error. Its
steering assumes a 30 % longer wheelbase than the car's, which makes up for the car's
understeer at the planned lateral accelerations. These numbers were tuned on a handful
of catalog tracks; the catalog job reports how they hold on all of them.

>>> line = plan_for_driver(track)                                  # doctest: +SKIP
>>> result = drive_raceline("gym-berlin", line, laps=2)            # doctest: +SKIP
>>> result.lap_times[-1], line.lap_time                            # doctest: +SKIP
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import gymnasium as gym
import numpy as np

from ..drivers import DriveResult, PurePursuitParams, drive_laps
from .limits import VehicleLimits, preset
from .plan import Raceline, plan_raceline
from .source import resolve_track

#: Share of the car's lateral and longitudinal limits the driver's line is planned with.
DRIVER_LATERAL, DRIVER_LONGITUDINAL = 0.75, 0.35
#: Safety margin (m) of the driver's line beyond half the car's width.
DRIVER_MARGIN = 0.15
#: The pure pursuit commands the lowest planned speed over the next 0.6 m
#: (``drivers.PurePursuitDriver``): it brakes 0.6 m early, which at 3 m/s is 0.2 s, far
#: more than the speed loop lags. The speed cap it is given is the highest planned speed
#: over the last ``0.6 m - SPEED_LEAD_S x v`` (a morphological closing), so that together
#: it brakes ``SPEED_LEAD_S`` early at any speed (and as before from 6 m/s up).
DRIVER_WINDOW_M = 0.6
SPEED_LEAD_S = 0.1
#: Steering geometry's wheelbase over the car's (understeer compensation).
UNDERSTEER_FACTOR = 1.3
#: Lookahead of the racing driver: 0.5 m + 0.15 s x speed, at most 1.8 m.
RACING_LOOKAHEAD = {"lookahead_min": 0.5, "lookahead_gain": 0.15, "lookahead_max": 1.8}


def driver_limits(limits: VehicleLimits | None = None) -> VehicleLimits:
    """``limits`` (default: the car's measured ones) derated for the racing driver."""
    return (limits or preset("car")).scaled(DRIVER_LATERAL, DRIVER_LONGITUDINAL)


def plan_for_driver(track: Any, limits: VehicleLimits | None = None, **kwargs: Any) -> Raceline:
    """The raceline the racing driver races: minimum curvature with :func:`driver_limits`
    and :data:`DRIVER_MARGIN` (``kwargs`` go to :func:`plan_raceline`)."""
    kwargs.setdefault("margin", DRIVER_MARGIN)
    return plan_raceline(track, driver_limits(limits), **kwargs)


def racing_params(line: Raceline, base: PurePursuitParams | None = None) -> PurePursuitParams:
    """Pure-pursuit settings that follow ``line``'s speed plan (its own speed profile
    limits lifted above the plan's, so the plan caps the speed)."""
    p = base or PurePursuitParams()
    return replace(
        p,
        wheelbase=p.wheelbase * UNDERSTEER_FACTOR,
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


def raceline_drive_kwargs(line: Raceline, env_wrapper: Any = None) -> dict[str, Any]:
    """What :func:`~roboracer_arena.drivers.drive_laps` needs to race ``line``:
    ``params``, ``path`` and an ``env_wrapper`` that starts on the line (around ``env_wrapper``)."""

    def wrap(env: gym.Env) -> gym.Env:
        inner = StartOnLine(env, line)
        return env_wrapper(inner) if env_wrapper is not None else inner

    return {"params": racing_params(line), "path": (line.xy, speed_cap(line)), "env_wrapper": wrap}


def speed_cap(line: Raceline, lead_s: float = SPEED_LEAD_S) -> np.ndarray:
    """(N,) the highest planned speed over the ``0.6 m - lead_s x v`` up to each point
    (see :data:`SPEED_LEAD_S`)."""
    n = len(line.vx)
    ds = float(np.mean(line.ds))
    window = np.clip(DRIVER_WINDOW_M - lead_s * line.vx, 0.0, DRIVER_WINDOW_M)
    back = np.arange(int(round(DRIVER_WINDOW_M / ds)) + 1)
    idx = (np.arange(n)[:, None] - back[None, :]) % n
    vals = np.where(back[None, :] * ds <= window[:, None], line.vx[idx], -np.inf)
    return np.asarray(vals.max(axis=1))


def drive_raceline(track: Any, line: Raceline, laps: int = 2, **kwargs: Any) -> DriveResult:
    """Drive ``laps`` laps of ``track`` (anything ``drive_laps`` takes: a catalog id, a map
    YAML, a Track) on ``line`` at its planned speeds, from a standing start on the line;
    laps count along the track's centreline, and the last one is the flying lap to set
    beside ``line.lap_time``."""
    given = kwargs.pop("params", None)
    kw = raceline_drive_kwargs(line, kwargs.pop("env_wrapper", None))
    if given is not None:
        kw["params"] = given
    return drive_laps(track, laps, **kw, **kwargs)


def raceline_drive_kwargs_for(source: Any, env_wrapper: Any = None) -> dict[str, Any]:
    """:func:`raceline_drive_kwargs` for the driver's line of a map YAML or catalog id
    (``roboracer-arena drive MAP --raceline``)."""
    return raceline_drive_kwargs(plan_for_driver(resolve_track(source)[0]), env_wrapper)
