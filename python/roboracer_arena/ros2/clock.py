"""Simulated time for the bridge: publication rates, the event schedule on the physics
clock, and pacing against the wall clock.

Time is simulated. The physics advances in steps of ``dt``; each stream (scan, odometry
and ``/tf``, ``/clock``) publishes at the first physics step at or after each multiple of
its period, so a 39.9 Hz scanner on a 5 ms physics step publishes 39.9 times per
simulated second on average. :class:`Pacer` holds the simulation to ``rate`` × real time
(1 by default) or lets it run as fast as it can (``rate=None``, the CLI's ``--rate max``).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

from pydantic import ConfigDict, Field, ValidationError

from ..config.sim import MIN_RATE_HZ, SimConfig
from ..errors import ArenaError, ConfigError
from ..foundation.fileio import read_json
from ..foundation.strict import NumbersAreNumbers, format_validation_error
from .start import StartConfig

_EPS = 1e-9


class RatesConfig(NumbersAreNumbers):
    """Publication and control rates (Hz). Defaults are the paper's (scan 39.9 Hz, odometry
    50 Hz, drive commands 20 Hz); ``/clock`` at 100 Hz, ``/tf`` with odometry."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    scan_hz: float = Field(39.9, ge=MIN_RATE_HZ, le=1000, description="LaserScan rate per car.")
    odom_hz: float = Field(50.0, ge=MIN_RATE_HZ, le=1000, description="Odometry and /tf rate.")
    drive_hz: float = Field(
        20.0, ge=MIN_RATE_HZ, le=1000, description="Control rate: one --lockstep period is 1/drive_hz."
    )
    clock_hz: float = Field(100.0, ge=MIN_RATE_HZ, le=1000, description="/clock rate.")


class BridgeConfig(NumbersAreNumbers):
    """Everything ``roboracer-arena ros2 --config F`` reads (JSON): rates, the simulator
    and where the cars start (the env's start options, :class:`~.start.StartConfig`)."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    rates: RatesConfig = Field(default_factory=RatesConfig)
    sim: SimConfig = Field(default_factory=SimConfig)
    start: StartConfig = Field(default_factory=StartConfig)

    @classmethod
    def load(cls, path: str | Path) -> BridgeConfig:
        """Read a JSON file; bad JSON or fields fail with :class:`ConfigError` naming the file."""
        p = Path(path)
        try:
            raw = read_json(p, "bridge config", ConfigError)
        except ArenaError as e:  # unreadable: one line, as a config error
            raise ConfigError(str(e)) from None
        try:
            return cls.model_validate(raw)
        except ValidationError as e:
            raise ConfigError(f"{p}: {format_validation_error(e, top='(config)')}") from e


class Schedule:
    """Integer physics-step times of the periodic streams (see module docstring)."""

    def __init__(self, dt: float, periods: dict[str, float]) -> None:
        self.dt = dt
        self.periods = dict(periods)
        self._count = {k: 0 for k in periods}  # events emitted so far per stream
        self._next = {k: 0 for k in periods}  # step of the next event (step 0: initial state)

    def _step_of(self, name: str, k: int) -> int:
        return math.ceil(k * self.periods[name] / self.dt - _EPS)

    def next_step(self) -> int:
        """Physics step of the earliest pending event."""
        return min(self._next.values())

    def next_step_of(self, name: str) -> int:
        """Physics step of stream ``name``'s next event."""
        return self._next[name]

    def due(self, step: int) -> list[str]:
        """Streams due at ``step`` (call once per step reached); advances them."""
        out = []
        for k, n in self._next.items():
            if n <= step:
                out.append(k)
                while self._next[k] <= step:
                    self._count[k] += 1
                    self._next[k] = self._step_of(k, self._count[k])
        return out


class Pacer:
    """Keeps simulated time at ``rate`` × wall time (``rate=None``: no waiting). Falling
    more than ``max_lag`` wall seconds behind re-anchors instead of bursting to catch up."""

    def __init__(self, rate: float | None, max_lag: float = 0.25) -> None:
        if rate is not None and not (math.isfinite(rate) and MIN_RATE_HZ <= rate <= 1e6):
            raise ConfigError(
                f"rate must be in [{MIN_RATE_HZ:g}, 1e6] (x real time) or None (as fast as possible), got {rate}"
            )
        self.rate = rate
        self.max_lag = max_lag
        self._anchor_wall = time.perf_counter()
        self._anchor_sim = 0.0

    def reanchor(self, sim_time: float) -> None:
        self._anchor_wall, self._anchor_sim = time.perf_counter(), sim_time

    def wait_time(self, sim_time: float) -> float:
        """Wall seconds to wait before ``sim_time`` is due (0 if due or running at max)."""
        if self.rate is None:
            return 0.0
        target = self._anchor_wall + (sim_time - self._anchor_sim) / self.rate
        late = time.perf_counter() - target
        if late > self.max_lag:
            self.reanchor(sim_time)
            return 0.0
        return max(0.0, -late)
