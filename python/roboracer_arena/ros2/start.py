"""Where the bridge starts its cars: the env's start, through the same code.

``gym.make("RoboRacerArena-v0", track=T, reset_poses="grid")`` and ``roboracer-arena ros2
T`` put the cars at the same poses: both hand :func:`~roboracer_arena.track.start_grid.start_spec`
to the simulator (``set_start_spec``) and reset with its ``reset_drawn``. The options
mirror the env's: :class:`StartConfig` holds the env config's start fields (the
``"start"`` section of the bridge's ``--config``), and fixed ``poses`` / ``speeds`` are
the env's reset options (``reset(options={"poses": ..., "speeds": ...})``), which the
CLI's ``--start X Y YAW`` gives, as ``f1tenth_gym_ros``' ``sx sy stheta`` do.
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
from pydantic import ConfigDict, Field

from .._core import StartSpec
from ..errors import InvalidArgumentError
from ..foundation.strict import NumbersAreNumbers
from ..track.drivable import Track
from ..track.start_grid import GRID_OFFSET, GRID_SPACING, SIDE_MARGIN, start_spec


class StartConfig(NumbersAreNumbers):
    """The start fields of the env's config, with the bridge's default ``reset_poses="grid"``."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    reset_poses: Literal["grid", "centreline_start", "random"] = Field(
        "grid", description="As EnvConfig.reset_poses: the grid start, s = 0 of the centreline, or random."
    )
    grid_spacing: float = Field(GRID_SPACING, gt=0, le=1e4, description="Longitudinal gap between grid slots (m).")
    grid_offset: float = Field(GRID_OFFSET, ge=0, le=1e4, description="Lateral offset of the staggered grid slots (m).")
    start_lateral_noise: float = Field(0.0, ge=0, le=1e4, description="Uniform lateral start offset in +-this (m).")
    start_heading_noise: float = Field(0.0, ge=0, le=3.2, description="Uniform heading offset in +-this (rad).")
    start_speed_noise: float = Field(0.0, ge=0, le=1e4, description="Rolling start speed drawn from [0, this] (m/s).")


def bridge_start_spec(track: Track, vehicles: int, config: StartConfig, chassis_width: float) -> StartSpec:
    """The ``set_start_spec`` of a bridge on ``track``, as the env makes it."""
    return start_spec(
        [track],
        vehicles,
        reset_poses=config.reset_poses,
        grid_spacing=config.grid_spacing,
        grid_offset=config.grid_offset,
        lateral_noise=config.start_lateral_noise,
        heading_noise=config.start_heading_noise,
        speed_noise=config.start_speed_noise,
        side_clearance=chassis_width / 2 + SIDE_MARGIN,
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
