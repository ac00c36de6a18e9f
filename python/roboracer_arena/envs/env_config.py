"""Configuration of the gymnasium environments (``RoboRacerArena-v0``).

:class:`EnvConfig` holds everything about the task (control rate, observation, action,
reward, episode ends, reset poses, vehicles per env) and the native simulator's
:class:`~roboracer_arena.envs.config.SimConfig` (vehicle, lidar, physics). Every field
can also be passed as a keyword to ``gymnasium.make``/``make_vec``; unknown keys fail.
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from ..errors import ConfigError

from .config import SimConfig

_FROZEN = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

#: Odometry columns an observation may contain (a subset of the simulator's state fields).
ODOMETRY_FIELDS = ("x", "y", "yaw", "vx", "vy", "yaw_rate", "steer", "speed")


class ObservationConfig(BaseModel):
    """What the agent sees: the lidar scan and/or odometry columns, raw or normalised.

    Raw: ranges in metres, odometry in SI units (map frame pose, body-frame velocities).
    Normalised: ranges / ``range_max`` in [0, 1]; x, y relative to the track's bounding-box
    centre divided by its half-extent; yaw / pi; speeds / ``max_speed``; yaw rate / 2 pi;
    steer / ``max_steer``.
    """

    model_config = _FROZEN

    scan: bool = Field(
        True,
        description="Include the lidar scan ('scan' key, (B,) or (V, B)), computed at the end of every env step "
        "(so at control_rate_hz, whatever LidarConfig.rate_hz says); False skips the scan entirely.",
    )
    odometry: tuple[str, ...] = Field(
        ("x", "y", "yaw", "vx", "vy", "yaw_rate", "steer"),
        description=f"Odometry columns ('odometry' key) in this order; any of {ODOMETRY_FIELDS}.",
    )
    normalise: bool = Field(False, description="Scale scan and odometry to about [-1, 1] (see class docstring).")

    @model_validator(mode="after")
    def _check(self) -> ObservationConfig:
        bad = [f for f in self.odometry if f not in ODOMETRY_FIELDS]
        if bad:
            raise ValueError(f"unknown odometry fields {bad}; choose from {ODOMETRY_FIELDS}")
        if len(set(self.odometry)) != len(self.odometry):
            raise ValueError("odometry fields must not repeat")
        if not self.scan and not self.odometry:
            raise ValueError("the observation must contain the scan or at least one odometry field")
        return self


class RewardConfig(BaseModel):
    """Per vehicle and step: ``progress * Δs − collision_penalty * [contact] − time_penalty * dt``.

    Δs is the signed progress along the centreline (m) during the step, wrapped at the lap.
    An env's reward is the sum over its vehicles (the per-vehicle terms are in ``info``).
    """

    model_config = _FROZEN

    progress: float = Field(1.0, description="Weight of centreline progress (per metre).")
    collision_penalty: float = Field(10.0, ge=0, description="Subtracted on a step with a wall or vehicle contact.")
    time_penalty: float = Field(0.0, ge=0, description="Subtracted per second of simulated time.")


class EnvConfig(BaseModel):
    """Task configuration of ``RoboRacerArena-v0`` (single env and vector env)."""

    model_config = _FROZEN

    control_rate_hz: float = Field(20.0, gt=0, description="Agent steps per simulated second (drive commands: 20 Hz).")
    action_mode: Literal["ackermann", "normalised"] = Field(
        "ackermann",
        description="'ackermann': [steer (rad), speed (m/s)] like /drive; 'normalised': both in [-1, 1] "
        "(steer * max_steer; speed piecewise linear: -1 -> min_speed, 0 -> stop, 1 -> max_speed).",
    )
    observation: ObservationConfig = Field(default_factory=ObservationConfig)
    reward: RewardConfig = Field(default_factory=RewardConfig)
    collision_ends_episode: bool = Field(True, description="A wall or vehicle contact terminates the episode.")
    time_limit_s: float | None = Field(60.0, gt=0, description="Truncate after this much simulated time (None: never).")
    reset_poses: Literal["random", "grid"] = Field(
        "random",
        description="'random': a uniformly random point of the centreline; 'grid': the centreline start (s = 0). "
        "Further vehicles line up behind the first in a staggered two-wide grid.",
    )
    grid_spacing: float = Field(1.0, gt=0, description="Longitudinal gap between grid slots (m).")
    grid_offset: float = Field(0.2, ge=0, description="Lateral offset of the staggered grid slots (m).")
    reverse: bool = Field(
        False,
        description="Drive every track against its racing direction (the centreline reversed; "
        "see roboracer_arena.direction). The grid starts at the same start line, facing the other way.",
    )
    vehicles_per_env: int = Field(1, ge=1, le=64, description="Vehicles sharing one track (one world) per env.")
    sim: SimConfig = Field(default_factory=SimConfig)

    @property
    def control_dt(self) -> float:
        """Simulated seconds per agent step."""
        return self.substeps * self.sim.physics.dt

    @property
    def substeps(self) -> int:
        """Physics steps per agent step: round(1 / (control_rate_hz * dt)), at least 1."""
        return max(1, round(1.0 / (self.control_rate_hz * self.sim.physics.dt)))

    @property
    def max_episode_steps(self) -> int | None:
        """Agent steps before truncation (None without a time limit)."""
        if self.time_limit_s is None:
            return None
        return max(1, round(self.time_limit_s / self.control_dt))

    @classmethod
    def build(cls, config: EnvConfig | dict | None = None, **overrides: object) -> EnvConfig:
        """An EnvConfig from a config (or dict) plus keyword overrides (``gymnasium.make`` kwargs).
        Nested dicts merge into the base (``sim={"lidar": {"num_beams": 271}}`` keeps the rest of ``sim``)."""
        base = config.model_dump() if isinstance(config, EnvConfig) else dict(config or {})
        base = _deep_merge(base, overrides)
        try:
            return cls.model_validate(base)
        except ValidationError as e:
            raise ConfigError(f"invalid environment configuration: {e}") from e


def _deep_merge(base: dict, overrides: dict) -> dict:
    out = dict(base)
    for k, v in overrides.items():
        if isinstance(v, BaseModel):
            v = v.model_dump()
        if isinstance(v, dict) and isinstance(out.get(k), dict):
            out[k] = _deep_merge(out[k], v)
        else:
            out[k] = v
    return out
