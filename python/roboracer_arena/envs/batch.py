"""The batch engine behind both gymnasium envs: one native ``_core.Simulator`` holding
``E`` environments of ``V`` vehicles, preallocated buffers, the action mapping (the
core sanitises: one action rule for the envs and the ROS 2 bridge) and observation
assembly. The single env is this with ``E = 1``; the vector env adds
autoreset on top.

The episode step (progress since reset, the reward terms, wrong-way driving,
termination and truncation) is the core's (``arena_core::sim::episode``): the simulator
runs it inside its step for every env and writes the results into this batch's
``_core.EpisodeBuffers``, which the envs read; no Python arithmetic runs per step.

Resets are native and masked: the simulator draws each reset env's track, start poses,
rolling-start speeds and lidar randomisation from that env's own stream (seeded from
(seed, env index)), places its cars and re-observes only the reset envs, writing into
this batch's preallocated buffers. No Python loop runs per env or per car, and an env's
episodes (noise included) do not depend on when the other envs reset.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from gymnasium import spaces

from .._core import (
    EVENT_LAP,
    EVENT_VEHICLE,
    EVENT_WALL,
    EpisodeBuffers,
    EpisodeConfig,
    Simulator,
    StartSpec,
    check_sim_size,
)
from ..errors import ConfigError, InvalidArgumentError
from ..track.drivable import Track
from .env_config import EnvConfig
from .observation import ObservationAssembler

#: Stream index of the per-env vehicle-randomisation RNG (apart from every other draw).
_VEHICLE_STREAM = 0x7E41
#: Stream index of the per-env actuation-delay RNG.
_DELAY_STREAM = 0xDE1A
#: Simulator state columns copied into ``info`` when present.
STATE_INFO = ("laps", "lap_time", "last_lap_time", "progress_s")


def check_size_budget(num_envs: int, config: EnvConfig) -> None:
    """Refuse an env whose size would exhaust memory, before anything is allocated (the
    native allocator aborts the process on failure, which Python cannot catch). The rule
    and its limits are the core's (``_core.check_sim_size``, ``SIM_MAX_VEHICLES``,
    ``SIM_MAX_SCAN_VALUES``); the observation's buffers hold ``frame_stack + 1`` scans
    per vehicle."""
    obs = config.observation
    frames = obs.frame_stack + 1 if obs.scan else 0
    check_sim_size(num_envs, config.vehicles_per_env, config.sim.lidar.num_beams, frames)


class SimBatch:
    """``E`` environments × ``V`` vehicles on one native simulator (see module docstring)."""

    def __init__(
        self,
        tracks: list[Track],
        num_envs: int,
        config: EnvConfig,
        seed: int,
        track_probs: np.ndarray | None = None,
        env_index_offset: int = 0,
    ) -> None:
        self._Simulator = Simulator
        self.tracks = tracks
        self.track_probs = track_probs
        self.config = config
        self.num_envs = E = int(num_envs)
        self.vehicles = V = config.vehicles_per_env
        check_size_budget(E, config)
        self._natives = [t.native() for t in tracks]
        self.track_names = [t.name for t in tracks]
        #: Per track: True for an open map (walls only: no lap, progress 0; see ``Track.open_map``).
        self.open_maps = np.array([t.is_open for t in tracks], dtype=bool)
        self.seed = int(seed)
        self.env_index_offset = int(env_index_offset)  # env e draws from the streams of env offset + e
        self._start = self._start_spec(tracks, probs=track_probs)
        self.sim = self._new_sim(self.seed)
        self.never_reset = np.ones(E, bool)  # an env observes nothing until its first reset
        self.num_beams = B = int(self.sim.num_beams)
        self.fields = tuple(self.sim.state_fields)
        self.field_index = {f: i for i, f in enumerate(self.fields)}
        missing = [f for f in (*config.observation.odometry, "x", "y", "yaw") if f not in self.field_index]
        if missing:
            raise RuntimeError(f"the simulator's state lacks fields {missing} (it has {self.fields})")
        self.substeps = config.substeps
        self.lengths = np.array([self.sim.centreline_length(i) for i in range(len(tracks))], dtype=np.float64)

        self.actions = np.zeros((E, V, 2), np.float64)
        self.scans = np.zeros((E, V, B), np.float32)
        self.state = np.zeros((E, V, len(self.fields)), np.float64)
        self.events = np.zeros((E, V), np.uint8)
        self.track_ids = np.zeros(E, np.int64)
        #: The core's episode results (written by each step and reset), and views of them.
        self.episode = ep = EpisodeBuffers(E, V)
        self.progress = ep.progress  # (E, V) metres since reset
        self.elapsed = ep.elapsed  # (E,) steps since reset
        self.vehicle_rewards = ep.vehicle_reward  # (E, V)
        self.wrong_way = ep.wrong_way  # (E, V) 0, +1 nose first, -1 reversing (see info)
        self.vehicle_terminated = ep.vehicle_terminated  # (E, V)
        self.start_pose = np.zeros((E, V, 3), np.float64)
        self.start_speed = np.zeros((E, V), np.float64)

        veh, lid = config.sim.vehicle, config.sim.lidar
        self._lo = np.array([-veh.max_steer, veh.min_speed])
        self._hi = np.array([veh.max_steer, veh.max_speed])
        frac = config.normalised_speed_range
        #: (low, high) m/s of normalised speed actions -1 and +1, or None for the piecewise map.
        self._speed_range = None if frac is None else (frac[0] * veh.max_speed, frac[1] * veh.max_speed)
        self._scalar_actions = E * V == 1
        self._info_names = [f for f in STATE_INFO if f in self.field_index]
        self._info_state = [(f, self.field_index[f]) for f in self._info_names]
        self._info_cols = np.array([self.field_index[f] for f in self._info_names], dtype=np.intp)
        self._range_max = float(lid.range_max)
        self.obs = ObservationAssembler(config, self.field_index, E, V, B)
        if self.obs.shares_scan:  # the simulator writes the observation's scans directly
            self.scans = self.obs.buf["scan"]
        self.obs.bind(self.state)
        self.first_row = self.state[0, 0]  # view: env 0, vehicle 0 (the single env's info)
        # The scanner runs at its own rate: under a faster control loop the observation
        # holds the latest scan until the next one is due (a 40 Hz scanner at 100 Hz control
        # scans on 2 of every 5 steps). Scan ticks count on one clock for the whole batch.
        self._scan_every_step = lid.rate_hz * config.control_dt >= 1.0 - 1e-9
        self._every_step_scans = self.scans if config.observation.scan and self._scan_every_step else None
        self._scan_ticks_per_step = lid.rate_hz * config.control_dt
        self._scan_clock = 0.0
        self._max_steps = config.max_episode_steps
        self.sim.set_episode(self._episode_config())
        self.delay = ActuationDelay(E, V, config.randomisation.action_delay_steps)

    @property
    def max_steps(self) -> int | None:
        """Steps before the core truncates an episode (None: never; gymnasium's TimeLimit
        may take over, see :mod:`.episode_limit`)."""
        return self._max_steps

    @max_steps.setter
    def max_steps(self, value: int | None) -> None:
        self._max_steps = value
        self.sim.set_episode(self._episode_config())

    def _episode_config(self) -> EpisodeConfig:
        """The core's episode parameters from the env config (see ``RewardConfig``)."""
        cfg, r = self.config, self.config.reward
        return EpisodeConfig(
            progress=r.progress,
            collision_penalty=r.collision_penalty,
            stall_penalty=r.stall_penalty,
            stall_speed=r.stall_speed,
            time_penalty=r.time_penalty,
            wrong_way_penalty=r.wrong_way_penalty,
            wrong_way_distance=cfg.wrong_way_distance,
            dt=cfg.control_dt,
            collision_ends_episode=cfg.collision_ends_episode,
            wrong_way_ends_episode=cfg.wrong_way_ends_episode,
            max_steps=self._max_steps,
        )

    # ------------------------------------------------------------------ spaces
    def single_spaces(self) -> tuple[spaces.Space, spaces.Space]:
        """(observation_space, action_space) of one environment."""
        cfg, V = self.config, self.vehicles
        lead = () if V == 1 else (V,)
        if cfg.action_mode == "ackermann":
            lo, hi = np.broadcast_to(self._lo, (*lead, 2)), np.broadcast_to(self._hi, (*lead, 2))
            act = spaces.Box(lo.astype(np.float32), hi.astype(np.float32), dtype=np.float32)
        else:
            act = spaces.Box(-1.0, 1.0, shape=(*lead, 2), dtype=np.float32)
        return self.obs.space(lead, act), act

    # ------------------------------------------------------------------ actions
    def set_actions(self, actions: Any) -> None:
        """Store actions ((E, V, 2) after reshape) as [steer rad, speed m/s] commands (the
        normalised mode maps [-1, 1] to them first), sanitised by the core's action rule
        (``_core.Simulator.sanitise_actions``: NaN -> 0, straight and stop; ±inf and
        out-of-range values clipped to the bounds), so they hold what the car is given."""
        out = self.actions
        if self._scalar_actions and self.config.action_mode == "ackermann":
            try:  # one vehicle: plain floats are several times faster than numpy calls
                steer, speed = actions.tolist() if hasattr(actions, "tolist") else actions
                out[0, 0, 0], out[0, 0, 1] = float(steer), float(speed)
            except (TypeError, ValueError):
                pass
            else:
                self.sim.sanitise_actions(out)
                return
        raw = np.asarray(actions)
        if raw.dtype.kind not in "biuf" or raw.size != self.num_envs * self.vehicles * 2:
            raise InvalidArgumentError(
                f"actions must be {self.num_envs * self.vehicles * 2} numbers "
                f"({self.num_envs} env(s) x {self.vehicles} vehicle(s) x [steer, speed]), got {actions!r:.80}"
            )
        a = raw.astype(np.float64, copy=False).reshape(self.num_envs, self.vehicles, 2)
        if self.config.action_mode == "ackermann":
            out[:] = a
        else:  # the mapping's domain is [-1, 1] (±inf -> ±1); NaN maps to NaN
            n = np.clip(a, -1.0, 1.0)
            out[..., 0] = n[..., 0] * self._hi[0]
            sp = n[..., 1]
            if self._speed_range is None:
                out[..., 1] = np.where(sp >= 0.0, sp * self._hi[1], -sp * self._lo[1])
            else:
                lo, hi = self._speed_range
                out[..., 1] = lo + (hi - lo) * 0.5 * (sp + 1.0)
        self.sim.sanitise_actions(out)

    def from_ackermann(self, cmds: np.ndarray) -> np.ndarray:
        """Convert [steer rad, speed m/s] commands to this env's action mode (float32)."""
        c = np.clip(np.asarray(cmds, dtype=np.float64), self._lo, self._hi)
        if self.config.action_mode == "normalised":
            if self._speed_range is None:
                v = np.where(c[..., 1] >= 0, c[..., 1] / self._hi[1], -c[..., 1] / self._lo[1])
            else:  # speeds outside the range map to its ends
                lo, hi = self._speed_range
                v = np.clip(2.0 * (c[..., 1] - lo) / (hi - lo) - 1.0, -1.0, 1.0)
            c = np.stack([c[..., 0] / self._hi[0], v], axis=-1)
        return c.astype(np.float32)

    # ------------------------------------------------------------------ reset
    def _randomise_vehicles(self, rngs: list[np.random.Generator], mask: np.ndarray, idx: np.ndarray) -> None:
        """Draw this episode's tyre friction, mass and actuator lags of each reset env from
        its stream (factors on the configured values) and hand them to the simulator."""
        rnd, veh = self.config.randomisation, self.config.sim.vehicle
        E = self.num_envs
        friction, mass = np.full(E, veh.tyre_friction), np.full(E, veh.mass)
        steer, throttle = np.full(E, veh.steer_time_constant), np.full(E, veh.throttle_time_constant)
        for e in idx:
            f, m, lag = (rngs[e].uniform(*r) for r in (rnd.friction_scale, rnd.mass_scale, rnd.lag_scale))
            friction[e], mass[e] = veh.tyre_friction * f, veh.mass * m
            steer[e], throttle[e] = veh.steer_time_constant * lag, veh.throttle_time_constant * lag
        self.sim.set_vehicle_params(mask, friction, mass, steer, throttle)

    def _start_spec(self, tracks: list[Track], probs: np.ndarray | None) -> StartSpec:
        """The simulator's reset draws (``_core.Simulator.set_start_spec``)."""
        cfg = self.config
        rnd = cfg.randomisation
        return cfg.start_spec(
            tracks,
            self.vehicles,
            cfg.sim.vehicle.chassis_width,
            track_weights=probs,
            noise_std=(float(rnd.lidar_noise_std[0]), float(rnd.lidar_noise_std[1])),
            dropout=float(rnd.lidar_dropout),
        )

    def _new_sim(self, seed: int) -> Any:
        """A simulator with this batch's tracks, counts, config and start spec (the episode
        parameters are set by the caller: ``__init__`` and :meth:`rebuild`)."""
        sim = self._Simulator(
            self._natives,
            self.num_envs,
            self.vehicles,
            self.config.sim,
            seed,
            env_index_offset=self.env_index_offset,
        )
        sim.set_start_spec(self._start)
        # Vehicle factors (tyre friction, mass, lags) per episode, from each env's own stream
        # seeded from (seed, env index): the same episodes whatever num_envs.
        self._vehicle_rngs = (
            [
                np.random.default_rng([int(seed), self.env_index_offset + e, _VEHICLE_STREAM])
                for e in range(self.num_envs)
            ]
            if self.config.randomisation.vehicle_active
            else None
        )
        self._delay_rngs = [
            np.random.default_rng([int(seed), self.env_index_offset + e, _DELAY_STREAM]) for e in range(self.num_envs)
        ]
        return sim

    def reset(
        self,
        mask: np.ndarray,
        track_ids: np.ndarray | None = None,
        poses: np.ndarray | None = None,
        speeds: np.ndarray | None = None,
    ) -> None:
        """Reset the environments where ``mask`` is True and observe them (only them).

        ``track_ids`` ((E,) ints, or None): the track of each reset env, else drawn (with
        the pool's weights). ``poses`` ((E, V, 3) x, y, yaw, or None): the start poses of
        each reset env, else the configured start (``reset_poses`` plus start noise).
        ``speeds`` ((E, V) m/s, or None): rolling-start forward speeds, else drawn from
        [0, start_speed_noise] (at rest when 0). The draws come from each env's own stream
        in the simulator (see the module docstring)."""
        mask = np.asarray(mask, dtype=bool)
        if (self.never_reset & ~mask).any():
            raise ConfigError(
                f"reset_mask leaves env(s) {np.flatnonzero(self.never_reset & ~mask)[:8].tolist()} that were "
                "never reset (after creation or a new seed every env must be reset once)"
            )
        self.never_reset &= ~mask
        self.sim.reset_drawn(mask, self.track_ids, self.start_pose, self.start_speed, track_ids, poses, speeds)
        idx = np.flatnonzero(mask)
        if self._vehicle_rngs is not None:
            self._randomise_vehicles(self._vehicle_rngs, mask, idx)
        if self.delay.active:
            self.delay.reset(idx, self._delay_rngs)
        # The core restarted these envs' episodes: their rows of the episode buffers now
        # read reward 0, not ended, progress 0, no wrong way, elapsed 0.
        scans = self.scans if self.config.observation.scan else None
        self.sim.observe(scans, self.state, self.events, mask, self.episode)
        self.obs.refresh(self, mask)

    def _scan_due(self) -> bool:
        """Whether the scanner produces a new scan at the end of this step."""
        if not self.config.observation.scan:
            return False
        if self._scan_every_step:
            return True
        before = self._scan_clock
        self._scan_clock += self._scan_ticks_per_step
        return math.floor(self._scan_clock + 1e-9) > math.floor(before + 1e-9)

    # ------------------------------------------------------------------ step
    def step(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Step all environments with the stored actions: one native call runs the physics,
        the scan, the state and the episode step. Returns the episode buffers' reward (E,),
        terminated (E,) and truncated (E,): views, valid until the next step or reset."""
        scans = self._every_step_scans if self._scan_every_step else (self.scans if self._scan_due() else None)
        actions = self.delay.apply(self.actions) if self.delay.active else self.actions
        self.sim.step(actions, self.substeps, scans, self.state, self.events, self.episode)
        self.obs.refresh(self)
        ep = self.episode
        return ep.reward, ep.terminated, ep.truncated

    # ------------------------------------------------------------------ observation
    def observation(self, envs: Any = slice(None)) -> dict[str, np.ndarray]:
        """Observation dict for ``envs`` (a slice or index array), shapes (e, V, ·) — fresh arrays."""
        return self.obs.observation(envs)

    def odometry_raw(self, odo: np.ndarray, env: Any) -> np.ndarray:
        """The newest frame of ``obs["odometry"]`` rows of env(s) ``env`` in SI units (map
        frame, one column per configured field), whatever the normalisation."""
        return self.obs.odometry_raw(np.asarray(odo, dtype=np.float64), self.start_pose[env])

    def info(self, envs: Any = slice(None)) -> dict[str, np.ndarray]:
        """Per-env diagnostics, fresh arrays with leading env axis (then vehicle axis):
        track_id, progress (m since reset), contact_wall / contact_vehicle / lap_completed
        (this step), wrong_way (0, +1 nose first, -1 reversing), the simulator's laps /
        lap_time / last_lap_time / progress_s, open_map (the env's track is an open map: no
        laps, progress 0) and, with several vehicles, vehicle_rewards and vehicle_terminated."""
        ev = self.events[envs]
        info = {
            "track_id": self.track_ids[envs].copy(),
            "open_map": self.open_maps[self.track_ids[envs]],
            "progress": self.progress[envs].copy(),
            "contact_wall": (ev & EVENT_WALL) != 0,
            "contact_vehicle": (ev & EVENT_VEHICLE) != 0,
            "lap_completed": (ev & EVENT_LAP) != 0,
            "wrong_way": self.wrong_way[envs].copy(),
        }
        if self.vehicles > 1:
            info["vehicle_rewards"] = self.vehicle_rewards[envs].copy()
            info["vehicle_terminated"] = self.vehicle_terminated[envs].copy()
        cols = self.state[envs][..., self._info_cols]  # one gather; the columns are views of it
        for j, name in enumerate(self._info_names):
            info[name] = cols[..., j]
        return info

    def single_observation(self) -> dict[str, np.ndarray]:
        """Env 0's observation as the single env returns it: fresh arrays, without the
        vehicle axis when the env has one vehicle."""
        return self.obs.observation_one() if self.vehicles == 1 else self.obs.observation(0)

    def single_info(self) -> dict[str, Any]:
        """Env 0's :meth:`info` as the single env returns it, with its track's name under
        ``"track"``: with one vehicle a flat dict of Python scalars, read with a few scalar
        reads (this runs every step), else :meth:`info` of env 0."""
        tid = self.track_ids.item(0)
        if self.vehicles > 1:
            info: dict[str, Any] = self.info(0)
            info.update(track_id=tid, track=self.track_names[tid], open_map=self.open_maps.item(tid))
            return info
        ev, row = self.events.item(0), self.first_row.tolist()
        info = {
            "track_id": tid,
            "track": self.track_names[tid],
            "open_map": self.open_maps.item(tid),
            "progress": self.progress.item(0),
            "contact_wall": bool(ev & EVENT_WALL),
            "contact_vehicle": bool(ev & EVENT_VEHICLE),
            "lap_completed": bool(ev & EVENT_LAP),
            "wrong_way": self.wrong_way.item(0),
        }
        for name, col in self._info_state:
            info[name] = row[col]
        return info

    def rebuild(self, seed: int) -> None:
        """Recreate the native simulator with ``seed`` (same tracks, counts and config), so
        its per-vehicle noise streams restart: the same seed gives the same episode."""
        self.seed = int(seed)
        self.sim = self._new_sim(self.seed)
        self.sim.set_episode(self._episode_config())
        self.never_reset[:] = True


class ActuationDelay:
    """The actuation delay of ``E`` envs (see ``RandomisationConfig.action_delay_steps``):
    a ring of the last ``high + 1`` sanitised actions per env; each env executes the one
    given ``delay[e]`` steps ago, its delay drawn at each of its resets from its own stream."""

    def __init__(self, num_envs: int, vehicles: int, steps: tuple[int, int]) -> None:
        self.low, self.high = int(steps[0]), int(steps[1])
        self.active = self.high > 0
        n = self.high + 1
        self.ring = np.zeros((n, num_envs, vehicles, 2), np.float64)
        self.steps = np.full(num_envs, self.low, np.int64)
        self._head = 0
        self._out = np.zeros((num_envs, vehicles, 2), np.float64)
        self._envs = np.arange(num_envs)

    def reset(self, envs: np.ndarray, rngs: list[np.random.Generator]) -> None:
        """Draw the delay of each env in ``envs`` and clear its pending actions (zero commands)."""
        for e in envs:
            self.steps[e] = rngs[e].integers(self.low, self.high + 1)
        self.ring[:, envs] = 0.0

    def apply(self, actions: np.ndarray) -> np.ndarray:
        """Push this step's ``actions`` (E, V, 2) and return the ones each env executes now."""
        n = len(self.ring)
        self._head = (self._head + 1) % n
        self.ring[self._head] = actions
        self._out[:] = self.ring[(self._head - self.steps) % n, self._envs]
        return self._out


class EnvHelpers:
    """Properties both envs expose to drivers and tools (they hold ``config``)."""

    config: EnvConfig

    @property
    def vehicles_per_env(self) -> int:
        return self.config.vehicles_per_env

    @property
    def max_steer(self) -> float:
        return self.config.sim.vehicle.max_steer

    @property
    def wheelbase(self) -> float:
        return self.config.sim.vehicle.wheelbase

    @property
    def odometry_index(self) -> dict[str, int]:
        """Column of each odometry field in ``obs["odometry"]``."""
        return {f: i for i, f in enumerate(self.config.observation.odometry)}
