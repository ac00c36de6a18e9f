"""Where the bridge starts its cars: the env's start, through the same code.

``gym.make("RoboRacerArena-v0", track=T, reset_poses="grid")`` and ``roboracer-arena ros2
T`` put the cars at the same poses: both hand their start fields' ``start_spec`` (see
:func:`~roboracer_arena.track.start_grid.start_spec`) to the simulator (``set_start_spec``) and
reset with its ``reset_drawn``. The options are the env's: :class:`StartConfig` (the
``"start"`` section of the bridge's ``--config``) is the env config's start fields
(:class:`~roboracer_arena.envs.env_config.StartOptions`) with the grid as default start,
and fixed ``poses`` / ``speeds`` are the env's reset options (``reset(options={"poses":
..., "speeds": ...})``), which the CLI's ``--start X Y YAW`` gives, as
``f1tenth_gym_ros``' ``sx sy stheta`` do.
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
from pydantic import Field

from ..envs.env_config import StartOptions
from ..errors import InvalidArgumentError


class StartConfig(StartOptions):
    """The env config's start fields (:class:`~roboracer_arena.envs.env_config.StartOptions`),
    with the bridge's default ``reset_poses="grid"``."""

    reset_poses: Literal["random", "grid", "centreline_start"] = Field(
        "grid", description="As EnvConfig.reset_poses: the grid start, s = 0 of the centreline, or random."
    )


def fixed_poses(poses: Any, vehicles: int) -> np.ndarray | None:
    """``poses`` ((3,) for one car, or one (x, y, yaw) per car) as (1, vehicles, 3), or
    None when not given. Wrong shapes and non-finite values fail with a typed error."""
    if poses is None:
        return None
    p = np.asarray(poses, dtype=np.float64)
    if p.shape == (3,):
        p = p[None]
    if p.shape != (vehicles, 3):
        raise InvalidArgumentError(
            f"--start needs one X Y YAW per car ({vehicles} car(s)), got {p.size // 3 if p.ndim else 0}"
        )
    if not np.isfinite(p).all():
        raise InvalidArgumentError(f"--start values must be finite numbers, got {p.tolist()}")
    return p[None]


def fixed_speeds(speeds: Any, vehicles: int) -> np.ndarray | None:
    """Rolling-start ``speeds`` (one, or one per car; m/s) as (1, vehicles), or None."""
    if speeds is None:
        return None
    sp = np.asarray(speeds, dtype=np.float64).reshape(-1)
    if sp.size == 1:
        sp = np.full(vehicles, sp[0])
    if sp.shape != (vehicles,) or not np.isfinite(sp).all():
        raise InvalidArgumentError(f"start speeds must be one finite number per car ({vehicles}), got {sp.tolist()}")
    return sp[None]
