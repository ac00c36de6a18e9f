"""Configuration of the gymnasium environments (``RoboRacerArena-v0``).

:class:`EnvConfig` holds everything about the task (control rate, observation, action,
reward, episode ends, reset poses, vehicles per env) and the native simulator's
:class:`~roboracer_arena.config.sim.SimConfig` (vehicle, lidar, physics). Every field
can also be passed as a keyword to ``gymnasium.make``/``make_vec``; unknown keys fail.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Literal, get_args

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from ..config.sim import MIN_RATE_HZ, SimConfig
from ..errors import ConfigError
from ..foundation.strict import NumbersAreNumbers
from ..track.start_grid import GRID_OFFSET, GRID_SPACING, SIDE_MARGIN, start_spec

if TYPE_CHECKING:
    from .._core import StartSpec
    from ..track.drivable import Track

_FROZEN = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

#: An odometry column: one of the simulator's state fields (the core's ``OdometryField``).
OdometryField = Literal["x", "y", "yaw", "vx", "vy", "yaw_rate", "steer", "speed"]
#: Odometry columns an observation may contain, in state order.
ODOMETRY_FIELDS: tuple[OdometryField, ...] = get_args(OdometryField)


class ObservationConfig(NumbersAreNumbers):
    """What the agent sees: the lidar scan and/or odometry columns, raw or normalised.

    Raw (``normalise=False``, for control people): ranges in metres, odometry in SI units
    (map-frame pose, body-frame velocities), one column per field.

    Normalised (``normalise=True``, for RL libraries; every value in [-1, 1] or [0, 1]):

    * scan: ranges clipped to ``horizon`` metres, then divided by it, in [0, 1];
    * x, y: position in the frame of the episode's start pose (x forward, y left), divided
      by ``position_scale`` (not clipped: the only unbounded columns) -- the same on every map;
    * yaw: TWO columns, sin and cos of the heading relative to the start heading (no wrap);
    * vx, vy, speed / ``max_speed``; yaw_rate / 2 pi; steer / ``max_steer``.

    ``EnvConfig(observation="normalise")`` is the preset for learning: normalised scan and
    ``vx, vy, yaw_rate, steer`` (the pose is left out: it means nothing across tracks).
    ``frame_stack = k > 1`` stacks the last k frames on a new axis before the last one
    (scan (k, B), odometry (k, K)); ``previous_action`` adds the last action the env
    applied (in the env's action mode) as ``obs["previous_action"]``.
    """

    model_config = _FROZEN

    scan: bool = Field(
        True,
        description="Include the lidar scan ('scan' key, (B,) or (V, B)), computed at the end of every env step "
        "(so at control_rate_hz, whatever LidarConfig.rate_hz says); False skips the scan entirely.",
    )
    odometry: tuple[OdometryField, ...] = Field(
        ("x", "y", "yaw", "vx", "vy", "yaw_rate", "steer"),
        description=f"Odometry columns ('odometry' key) in this order; any of {ODOMETRY_FIELDS}.",
    )
    normalise: bool = Field(False, description="Scale scan and odometry for learning (see class docstring).")
    horizon: float = Field(
        10.0, gt=0, description="Normalised scan: ranges are clipped to this (m), then scaled to [0, 1]."
    )
    position_scale: float = Field(
        20.0, gt=0, description="Normalised x, y: metres from the start pose that map to +-1."
    )
    frame_stack: int = Field(1, ge=1, le=64, description="Number of most recent frames stacked in each key.")
    previous_action: bool = Field(False, description="Add the previous action as obs['previous_action'].")

    @model_validator(mode="after")
    def _check(self) -> ObservationConfig:
        if len(set(self.odometry)) != len(self.odometry):
            raise ValueError("odometry fields must not repeat")
        if not self.scan and not self.odometry:
            raise ValueError("the observation must contain the scan or at least one odometry field")
        return self


class RewardConfig(NumbersAreNumbers):
    """Per vehicle and step of ``dt`` seconds::

        progress * Δs
        − stall_penalty * dt * [Δs < stall_speed * dt]
        − time_penalty * dt
        − collision_penalty * [contact]
        − wrong_way_penalty * [wrong way]

    Δs is the signed progress along the centreline (m) during the step, wrapped at the lap.
    An env's reward is the sum over its vehicles (the per-vehicle terms are in ``info``).

    The stall term makes standing still worse than driving: a car making less than
    ``stall_speed`` m/s of progress pays ``stall_penalty`` per second, so a parked car loses
    120 per 120 s episode while a slow driver gains its metres (before it, parking scored 0,
    above any run that ended in a crash: PPO learned to park). ``stall_penalty=0`` restores
    the old reward.
    """

    model_config = _FROZEN

    progress: float = Field(1.0, description="Weight of centreline progress (per metre).")
    collision_penalty: float = Field(10.0, ge=0, description="Subtracted on a step with a wall or vehicle contact.")
    stall_penalty: float = Field(
        1.0,
        ge=0,
        description="Subtracted per second while the vehicle makes less than stall_speed of centreline "
        "progress (parked, crawling or going backwards); 0 turns it off (the reward before stall_penalty).",
    )
    stall_speed: float = Field(
        0.5, ge=0, description="Progress rate (m/s along the centreline) below which stall_penalty applies."
    )
    time_penalty: float = Field(0.0, ge=0, description="Subtracted per second of simulated time.")
    wrong_way_penalty: float = Field(0.0, ge=0, description="Subtracted on each step the vehicle drives the wrong way.")


#: Longest actuation delay an env accepts (control steps).
MAX_ACTION_DELAY_STEPS = 64


class RandomisationConfig(NumbersAreNumbers):
    """Per-episode domain randomisation, drawn from each env's own RNG (deterministic for a
    given seed).

    Observation: the simulator's scan is exact; each episode draws a range-noise std
    uniformly from ``lidar_noise_std`` (added to every beam, every step) and each beam of
    each step reads ``range_max`` (a lost return) with probability ``lidar_dropout``.

    Vehicle: each episode draws factors uniformly from ``(low, high)`` that scale the
    configured tyre friction (``friction_scale``), mass and with it the inertia
    (``mass_scale``), and both actuator time constants, steering servo and motor current
    (``lag_scale``). (1, 1) leaves the parameter at its configured value.

    Actuation delay: each episode draws a whole number of control steps uniformly from
    ``action_delay_steps`` (low, high, both included); the car then executes the action
    given that many steps earlier (zero commands, i.e. straight and stopped, before the
    first ones arrive). (0, 0) is no delay; (2, 2) a fixed 100 ms at 20 Hz.
    """

    model_config = _FROZEN

    lidar_noise_std: tuple[float, float] = Field((0.0, 0.0), description="(low, high) range-noise std (m).")
    lidar_dropout: float = Field(0.0, ge=0, lt=1, description="Probability a beam reads range_max, per step.")
    friction_scale: tuple[float, float] = Field((1.0, 1.0), description="(low, high) factor on vehicle.tyre_friction.")
    mass_scale: tuple[float, float] = Field((1.0, 1.0), description="(low, high) factor on vehicle.mass (and inertia).")
    lag_scale: tuple[float, float] = Field(
        (1.0, 1.0), description="(low, high) factor on vehicle.steer_time_constant and throttle_time_constant."
    )
    action_delay_steps: tuple[int, int] = Field(
        (0, 0), description="(low, high) actuation delay in control steps, drawn per episode (both included)."
    )

    @model_validator(mode="after")
    def _ranges(self) -> RandomisationConfig:
        lo, hi = self.lidar_noise_std
        if not 0 <= lo <= hi <= 1e4:
            raise ValueError(
                f"randomisation.lidar_noise_std must be (low, high) with 0 <= low <= high <= 1e4, got {(lo, hi)}"
            )
        for name in ("friction_scale", "mass_scale", "lag_scale"):
            lo, hi = getattr(self, name)
            if not (0 < lo <= hi if name != "lag_scale" else 0 <= lo <= hi):
                raise ValueError(
                    f"randomisation.{name} must be (low, high) with {'0 <=' if name == 'lag_scale' else '0 <'} low <= high, "
                    f"got {(lo, hi)}"
                )
        lo, hi = self.action_delay_steps
        if not 0 <= lo <= hi <= MAX_ACTION_DELAY_STEPS:
            raise ValueError(
                "randomisation.action_delay_steps must be (low, high) whole steps with "
                f"0 <= low <= high <= {MAX_ACTION_DELAY_STEPS}, got {(lo, hi)}"
            )
        return self

    @property
    def active(self) -> bool:
        """Whether any observation randomisation is on."""
        return self.lidar_noise_std[1] > 0 or self.lidar_dropout > 0

    @property
    def vehicle_active(self) -> bool:
        """Whether any vehicle-parameter randomisation is on."""
        return any(getattr(self, n) != (1.0, 1.0) for n in ("friction_scale", "mass_scale", "lag_scale"))


#: Named observation presets (``EnvConfig(observation="normalise")``).
OBSERVATION_PRESETS = {
    "raw": {},
    "normalise": {"normalise": True, "odometry": ("vx", "vy", "yaw_rate", "steer")},
}


class StartOptions(NumbersAreNumbers):
    """Where an episode's cars start: the start fields of :class:`EnvConfig`, which the ROS 2
    bridge's start config (``ros2.start.StartConfig``) reuses, so both front ends state and
    bound them once; :meth:`start_spec` turns them into the simulator's reset draws."""

    model_config = _FROZEN

    reset_poses: Literal["random", "grid", "centreline_start"] = Field(
        "random",
        description="'random': a uniformly random point of the centreline; 'grid': the grid start "
        "(track/start_grid.py: on the line, clear of walls, facing the longest free run ahead); 'centreline_start': "
        "s = 0 of the centreline as extracted. Further vehicles line up behind the first in a staggered grid.",
    )
    start_lateral_noise: float = Field(
        0.0,
        ge=0,
        le=1e4,
        description="Start pose: uniform lateral offset in +-this (m), capped to keep the car off the walls.",
    )
    start_heading_noise: float = Field(
        0.0, ge=0, le=3.2, description="Start pose: uniform heading offset in +-this (rad)."
    )
    start_speed_noise: float = Field(
        0.0, ge=0, le=1e4, description="Rolling start: forward speed drawn uniformly from [0, this] m/s (<= max_speed)."
    )
    grid_spacing: float = Field(GRID_SPACING, gt=0, le=1e4, description="Longitudinal gap between grid slots (m).")
    grid_offset: float = Field(GRID_OFFSET, ge=0, le=1e4, description="Lateral offset of the staggered grid slots (m).")

    def start_spec(
        self,
        tracks: Sequence[Track | None],
        vehicles: int,
        chassis_width: float,
        *,
        track_weights: Iterable[float] | None = None,
        noise_std: tuple[float, float] = (0.0, 0.0),
        dropout: float = 0.0,
    ) -> StartSpec:
        """The simulator's reset draws (``_core.Simulator.set_start_spec``) of ``vehicles``
        cars of width ``chassis_width`` on ``tracks`` with these start fields (see
        :func:`~roboracer_arena.track.start_grid.start_spec`; lateral noise keeps the car's side
        :data:`~roboracer_arena.track.start_grid.SIDE_MARGIN` from the walls)."""
        return start_spec(
            tracks,
            vehicles,
            reset_poses=self.reset_poses,
            grid_spacing=self.grid_spacing,
            grid_offset=self.grid_offset,
            lateral_noise=self.start_lateral_noise,
            heading_noise=self.start_heading_noise,
            speed_noise=self.start_speed_noise,
            side_clearance=chassis_width / 2 + SIDE_MARGIN,
            track_weights=track_weights,
            noise_std=noise_std,
            dropout=dropout,
        )


class EnvConfig(StartOptions):
    """Task configuration of ``RoboRacerArena-v0`` (single env and vector env); its start
    fields are those of :class:`StartOptions`."""

    model_config = _FROZEN

    control_rate_hz: float = Field(
        20.0, ge=MIN_RATE_HZ, le=10_000, description="Agent steps per simulated second (drive commands: 20 Hz)."
    )
    action_mode: Literal["ackermann", "normalised"] = Field(
        "ackermann",
        description="'ackermann': [steer (rad), speed (m/s)] like /drive; 'normalised': both in [-1, 1] "
        "(steer * max_steer; speed: see normalised_speed_range).",
    )
    normalised_speed_range: tuple[float, float] | None = Field(
        (0.15, 0.7),
        description="action_mode='normalised': the speeds, as fractions of sim.vehicle.max_speed, that speed "
        "actions -1 and +1 map to (linear in between; the default 1.05-4.9 m/s cannot stop or reverse, so a "
        "zero-mean policy starts by driving). None: the mapping before this option, piecewise linear "
        "-1 -> min_speed (reverse), 0 -> stop, 1 -> max_speed.",
    )
    observation: ObservationConfig = Field(default_factory=ObservationConfig)
    reward: RewardConfig = Field(default_factory=RewardConfig)
    collision_ends_episode: bool = Field(True, description="A wall or vehicle contact terminates the episode.")
    time_limit_s: float | None = Field(
        120.0,
        gt=0,
        description="Truncate after this much simulated time (None: never); see envs/episode_limit.py "
        "for how it agrees with gymnasium's max_episode_steps.",
    )
    wrong_way_distance: float = Field(
        2.0,
        gt=0,
        description="A vehicle drives the wrong way when it moves backwards along the centreline more "
        "than this (m) behind the furthest point it reached since reset.",
    )
    wrong_way_ends_episode: bool = Field(False, description="Driving the wrong way terminates the episode.")
    randomisation: RandomisationConfig = Field(default_factory=lambda: RandomisationConfig())
    reverse: bool = Field(
        False,
        description="Drive every track against its racing direction (the centreline reversed; "
        "see roboracer_arena.maps.direction). The grid starts at the same start line, facing the other way.",
    )
    vehicles_per_env: int = Field(1, ge=1, le=64, description="Vehicles sharing one track (one world) per env.")
    sim: SimConfig = Field(default_factory=SimConfig)

    @model_validator(mode="before")
    @classmethod
    def _observation_preset(cls, data: object) -> object:
        if isinstance(data, dict) and isinstance(data.get("observation"), str):
            name = data["observation"]
            if name not in OBSERVATION_PRESETS:
                raise ValueError(f"observation preset {name!r} is unknown; choose from {sorted(OBSERVATION_PRESETS)}")
            data = {**data, "observation": dict(OBSERVATION_PRESETS[name])}
        return data

    @model_validator(mode="after")
    def _start_speed(self) -> EnvConfig:
        if self.start_speed_noise > self.sim.vehicle.max_speed:
            raise ValueError(
                f"start_speed_noise {self.start_speed_noise} exceeds max_speed {self.sim.vehicle.max_speed}"
            )
        return self

    @model_validator(mode="after")
    def _speed_range(self) -> EnvConfig:
        r = self.normalised_speed_range
        if r is not None:
            floor = self.sim.vehicle.min_speed / self.sim.vehicle.max_speed
            if not floor <= r[0] < r[1] <= 1.0:
                raise ValueError(
                    f"normalised_speed_range must be (low, high) fractions of max_speed with "
                    f"{floor:g} <= low < high <= 1, got {r}"
                )
        return self

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
