"""Reference drivers. :class:`PurePursuitDriver` follows a track's centreline: the pose
comes from the odometry observation, the lookahead grows with speed, and the speed
command comes from a curvature-limited speed profile (lateral-acceleration limit,
braking and acceleration passes around the closed loop).

>>> env = gymnasium.make("RoboRacerArena-v0", track="berlin.yaml")
>>> driver = PurePursuitDriver.for_env(env)
>>> obs, info = env.reset(seed=0)
>>> obs, reward, terminated, truncated, info = env.step(driver.act(obs))

The same ``for_env`` works on the native vector env (every env and vehicle, each on its
own track). :func:`drive_laps` drives whole laps and reports lap times and contacts (the
``roboracer-arena drive`` command and the track library's drivability check).
"""

from __future__ import annotations

import copy
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from . import _core
from .envs.single import RoboRacerEnv
from .errors import ConfigError, InvalidArgumentError

__all__ = ["DriveResult", "EnvPurePursuit", "PurePursuitDriver", "PurePursuitParams", "drive_laps"]


@dataclass(frozen=True)
class PurePursuitParams:
    """Tuning of the reference driver (SI units). Defaults suit the Traxxas 1:10 car."""

    wheelbase: float = 0.3275
    rear_axle_offset: float = 0.1522  # CoM to rear axle: pure pursuit steers the rear axle
    max_steer: float = 0.524
    lookahead_min: float = 0.7
    lookahead_gain: float = 0.3  # s: lookahead = min + gain * speed
    lookahead_max: float = 2.5
    max_speed: float = 5.0
    min_speed: float = 1.0
    lateral_accel: float = 4.0  # m/s^2, well under mu*g = 8.1 so the car stays on the line
    brake_decel: float = 4.0
    accel: float = 3.0
    spacing: float = 0.05  # resampling of the centreline (m)
    curvature_window: float = 0.4  # half-width of the curvature smoothing window (m)


class PurePursuitDriver:
    """Pure pursuit on one closed centreline ((M, 2), map frame, driving direction = vertex order).

    ``speed_cap`` ((M,) m/s, one per centreline vertex, optional) caps the speed profile
    before its braking and acceleration passes, e.g. by the wall clearance along a
    narrow path (:mod:`roboracer_arena.maps.clearance_path`)."""

    def __init__(self, centreline: Any, params: PurePursuitParams | None = None, speed_cap: Any = None) -> None:
        self.params = p = params or PurePursuitParams()
        line = np.asarray(centreline, dtype=np.float64)
        self.points = _core.resample_closed(line, p.spacing)
        self.length = _core.polyline_length(line)
        self.ds = self.length / len(self.points)
        # Signed three-point curvature over chords of ±curvature_window (a smoothed estimate).
        self.curvature = _core.curvature(self.points, p.curvature_window)
        cap = None
        if speed_cap is not None:
            vals = _core.resample_closed_values(line, np.asarray(speed_cap, dtype=np.float64), p.spacing)[1]
            cap = vals[: len(self.points)]
        self.speed_profile = _speed_profile(self.curvature, self.ds, p, cap)
        self._idx: int | None = None

    @staticmethod
    def for_env(env: Any, params: PurePursuitParams | None = None) -> EnvPurePursuit:
        """A pure-pursuit policy for a RoboRacer env (see :class:`EnvPurePursuit`)."""
        return EnvPurePursuit(env, params)

    def reset(self) -> None:
        """Forget the last projection (call at the start of an episode)."""
        self._idx = None

    def project(self, x: float, y: float) -> int:
        """Index of the resampled centreline point nearest (x, y); searches near the last one."""
        n = len(self.points)
        if self._idx is not None:
            window = int(3.0 / self.ds) + 1
            cand = (self._idx + np.arange(-window // 3, window)) % n
            d = np.hypot(self.points[cand, 0] - x, self.points[cand, 1] - y)
            k = int(np.argmin(d))
            if d[k] < 1.0:
                self._idx = int(cand[k])
                return self._idx
        d = np.hypot(self.points[:, 0] - x, self.points[:, 1] - y)
        self._idx = int(np.argmin(d))
        return self._idx

    def act_pose(self, x: float, y: float, yaw: float, speed: float) -> np.ndarray:
        """``[steer (rad), speed (m/s)]`` for a vehicle at pose (x, y, yaw) (CoM) moving at ``speed``."""
        p = self.params
        if not np.isfinite([x, y, yaw, speed]).all():
            return np.zeros(2)
        rx, ry = x - p.rear_axle_offset * np.cos(yaw), y - p.rear_axle_offset * np.sin(yaw)
        i = self.project(rx, ry)
        steer, v = self._steer_and_speed(np.array([i]), rx, ry, yaw, speed)
        return np.array([steer[0], v[0]])

    def act_along(
        self, x: np.ndarray, y: np.ndarray, yaw: np.ndarray, speed: np.ndarray, progress_s: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Vectorised :meth:`act_pose` for many cars whose arc length along this centreline
        is already known (the simulator's ``progress_s``), so no per-car projection:
        ``(steer, speed)`` arrays shaped like the inputs."""
        p = self.params
        rx, ry = x - p.rear_axle_offset * np.cos(yaw), y - p.rear_axle_offset * np.sin(yaw)
        i = np.rint(np.mod(progress_s, self.length) / self.ds).astype(np.int64) % len(self.points)
        return self._steer_and_speed(i, rx, ry, yaw, speed)

    def _steer_and_speed(self, i: np.ndarray, rx: Any, ry: Any, yaw: Any, speed: Any) -> tuple[np.ndarray, np.ndarray]:
        """The pursuit law: steer the rear axle at (rx, ry) onto the point a speed-dependent
        lookahead beyond centreline index ``i``; speed from the profile just ahead."""
        p = self.params
        n = len(self.points)
        lookahead = np.clip(
            p.lookahead_min + p.lookahead_gain * np.maximum(speed, 0.0), p.lookahead_min, p.lookahead_max
        )
        target = self.points[(i + np.maximum(1, np.rint(lookahead / self.ds)).astype(np.int64)) % n]
        dx, dy = target[..., 0] - rx, target[..., 1] - ry
        c, s = np.cos(yaw), np.sin(yaw)
        lx, ly = c * dx + s * dy, -s * dx + c * dy
        steer = np.clip(np.arctan2(2.0 * p.wheelbase * ly, lx * lx + ly * ly), -p.max_steer, p.max_steer)
        ahead = (i[..., None] + np.arange(max(1, round(0.6 / self.ds)))) % n
        return np.asarray(steer, dtype=np.float64), self.speed_profile[ahead].min(axis=-1)


def _speed_profile(curv: np.ndarray, ds: float, p: PurePursuitParams, cap: np.ndarray | None = None) -> np.ndarray:
    v = np.sqrt(p.lateral_accel / np.maximum(np.abs(curv), 1e-6))
    v = np.clip(v, p.min_speed, p.max_speed)
    if cap is not None:
        v = np.minimum(v, cap)
    n = len(v)
    for _ in range(2):  # two laps so the passes wrap around the closed loop
        for k in range(2 * n - 1, -1, -1):  # braking: v_i^2 <= v_{i+1}^2 + 2 a ds
            i, j = k % n, (k + 1) % n
            v[i] = min(v[i], np.sqrt(v[j] ** 2 + 2 * p.brake_decel * ds))
        for k in range(1, 2 * n):  # acceleration
            i, j = k % n, (k - 1) % n
            v[i] = min(v[i], np.sqrt(v[j] ** 2 + 2 * p.accel * ds))
    return v


class EnvPurePursuit:
    """Drives a RoboRacer env — single env or native vector env, every vehicle — with pure pursuit.

    Reads the pose and speed from the odometry observation (raw or normalised), follows
    the centreline of the track each environment is currently on, and returns an action
    in the env's action mode. Create it with :meth:`PurePursuitDriver.for_env`.
    """

    def __init__(self, env: Any, params: PurePursuitParams | None = None, paths: dict[int, Any] | None = None) -> None:
        """``paths``: per track id, ``(line (M, 2), speed cap (M,) or None)`` to follow
        instead of the track's centreline (e.g. a clearance path)."""
        self.env = env.unwrapped
        self._paths = dict(paths or {})
        self.params = params or PurePursuitParams(
            max_steer=float(self.env.max_steer), wheelbase=float(self.env.wheelbase)
        )
        self._vector = hasattr(self.env, "num_envs")
        self._geometry: dict[int, PurePursuitDriver] = {}  # one resampled centreline per track
        self._slots: dict[tuple[int, int], tuple[int, PurePursuitDriver]] = {}  # (env, vehicle) -> state
        f = self.env.odometry_index
        missing = [k for k in ("x", "y", "yaw") if k not in f]
        if missing:
            raise ConfigError(
                f"pure pursuit needs the odometry fields x, y, yaw in the observation (missing {missing})"
            )
        self._cols = (f["x"], f["y"], f["yaw"], f.get("speed", f.get("vx")))
        state_fields = self.env.simulator_state[1] if hasattr(self.env, "simulator_state") else {}
        if self._cols[3] is None and "vx" not in state_fields:
            # Never guess: a speed of 0 plans for a standing car and steers into the wall.
            raise ConfigError(
                "pure pursuit needs the car's speed: add 'vx' (or 'speed') to the observation's odometry "
                "fields, or use an env whose simulator state it can read"
            )

    def _driver(self, e: int, k: int, track_id: int) -> PurePursuitDriver:
        slot = self._slots.get((e, k))
        if slot is None or slot[0] != track_id:
            base = self._geometry.get(track_id)
            if base is None:
                line, cap = self._paths.get(track_id, (self.env.tracks[track_id].centreline, None))
                base = self._geometry[track_id] = PurePursuitDriver(line, self.params, cap)
            slot = (track_id, copy.copy(base))  # shares the geometry, own projection state
            slot[1].reset()
            self._slots[(e, k)] = slot
        return slot[1]

    def act(self, obs: Any) -> np.ndarray:
        """An action for ``obs`` (the env's last observation)."""
        env = self.env
        odo = np.asarray(env.odometry_raw(obs), dtype=np.float64)  # (V, K) or (E, V, K), SI units
        track_ids = np.atleast_1d(env.current_track_ids if self._vector else env.current_track_id)
        if not self._vector:
            odo = odo[None]
        cx, cy, cyaw, cv = self._cols
        if cv is None:  # no speed in the observation: the env's own state has it (checked at creation)
            state, field = env.simulator_state
            speeds = np.asarray(state[..., field["vx"]], dtype=np.float64).reshape(odo.shape[:2])
        else:
            speeds = odo[..., cv]
        cmds = np.zeros((*odo.shape[:2], 2))
        for e, tid in enumerate(track_ids):
            for k, row in enumerate(odo[e]):
                cmds[e, k] = self._driver(e, k, int(tid)).act_pose(row[cx], row[cy], row[cyaw], speeds[e, k])
        return env.from_ackermann(cmds if self._vector else cmds[0])

    def reset(self) -> None:
        """Forget every vehicle's last projection (optional: a jump is detected anyway)."""
        for _, d in self._slots.values():
            d.reset()


@dataclass
class DriveResult:
    """Outcome of :func:`drive_laps` (times in simulated seconds)."""

    track: str
    track_length: float
    laps_requested: int
    laps_completed: int
    lap_times: list[float]
    collided: bool
    contact_steps: int
    sim_time: float
    distance: float
    max_speed: float
    wall_time: float
    video: str | None = None
    contact_at: list[float] | None = None  # (x, y) of the first contact
    corridor_width_at_contact: float | None = None  # narrowest corridor width within 1 m of it
    vehicle_width: float | None = None

    @property
    def completed(self) -> bool:
        """All requested laps driven without a contact."""
        return self.laps_completed >= self.laps_requested and not self.collided

    def to_dict(self) -> dict[str, Any]:
        from dataclasses import asdict

        return {**asdict(self), "completed": self.completed}


def drive_laps(
    track: Any,
    laps: int = 1,
    *,
    params: PurePursuitParams | None = None,
    video: Any = None,
    video_fps: float = 10.0,
    render_size: int = 720,
    max_time_s: float | None = None,
    progress: bool = False,
    env_wrapper: Any = None,
    path: Any = None,
    controller: Any = None,
    **env_kwargs: Any,
) -> DriveResult:
    """Drive ``laps`` laps of ``track`` (anything ``track=`` accepts; the first track if a
    list) with :class:`PurePursuitDriver` from the centreline start, stopping at the first
    contact. Optionally writes a GIF/MP4 of the drive, framed as a preview (``render_size``:
    the longer side of its map, px) with a HUD (:mod:`.render.drive_view`). With
    ``progress``, a bar shows the distance driven, the simulated time and the car's speed.
    ``env_kwargs`` go to the env; ``env_wrapper(env)`` (e.g. an MCAP recorder) wraps it
    before driving. ``path``: ``(line (M, 2), speed cap (M,) or None)`` for the driver to
    follow instead of the centreline (laps still count along the track's centreline).
    ``controller(env)``: another driver for the env (an object with ``act(obs)``, e.g. a
    policy's :class:`~roboracer_arena.learn.runner.PolicyDriver`) instead of pure pursuit. On
    SIGINT (and SIGTERM in the CLI) the env is closed, so a recording is finished; on any
    other error a wrapper's ``abort()`` discards its output."""
    if laps < 1:
        raise InvalidArgumentError(f"laps must be >= 1, got {laps}")
    if video:
        from .render.formats import video_format

        video_format(video)  # a bad extension fails before the lap is driven
    env = RoboRacerEnv(
        track=track,
        **{"reset_poses": "grid", "collision_ends_episode": True, "time_limit_s": None, **env_kwargs},
    )
    base_env = env
    if env_wrapper is not None:
        env = env_wrapper(env)
    length = env.tracks[0].length
    limit = max_time_s if max_time_s is not None else laps * (length / 0.5 + 30.0)  # >= 0.5 m/s average
    dt = env.config.control_dt
    try:
        if controller is not None:
            driver = controller(env)
        else:
            driver = EnvPurePursuit(env, params, None if path is None else {0: path})
        return _drive(env, base_env, driver, laps, limit, length, dt, video, video_fps, render_size, progress)
    except KeyboardInterrupt:
        env.close()  # SIGINT/SIGTERM: what was driven is kept whole (a recording is finished)
        raise
    except BaseException:
        getattr(env, "abort", env.close)()  # a failed drive leaves no partial output
        raise


def _drive(
    env: Any,
    base_env: Any,
    driver: Any,
    laps: int,
    limit: float,
    length: float,
    dt: float,
    video: Any,
    video_fps: float,
    render_size: int,
    progress: bool,
) -> DriveResult:
    """Step ``env`` with ``driver`` until ``laps`` laps, the end of the episode or ``limit``
    simulated seconds; film it into ``video`` and show a bar when asked."""
    log = _DriveLog(laps, length, dt)
    film = _Film(env, base_env, laps, video_fps, render_size) if video else None
    bar = _progress_bar(env, laps, length) if progress else None
    t0 = time.perf_counter()
    obs, info = env.reset(seed=0, options={"track_id": 0})
    if film is not None:
        film.add(log)
    state_speed = env.odometry_index.get("speed", env.odometry_index.get("vx"))
    while log.steps * dt < limit:
        obs, _, terminated, truncated, info = env.step(driver.act(obs))
        log.record(env, obs, info, state_speed)
        if bar is not None:
            bar.set_postfix_str(f"sim {log.steps * dt:.1f} s, {_speed_now(base_env):.2f} m/s", refresh=False)
            bar.update(round(min(log.progressed, laps * length), 1) - bar.n)
        if film is not None and log.steps % film.every == 0:
            film.add(log)
        if terminated or truncated or len(log.lap_times) >= laps:
            break
    if bar is not None:
        bar.refresh()  # a fast drive can end within tqdm's refresh interval: show the final state
        bar.close()
    out = None
    if film is not None:
        film.add(log)
        out = film.write(video)
    env.close()
    return log.result(env, info, round(time.perf_counter() - t0, 3), out)


def _speed_now(base_env: Any) -> float:
    """The first car's speed (m/s) from the env's simulator state."""
    state, f = base_env.simulator_state
    row = state[0]
    return float(row[f["speed"]]) if "speed" in f else float(np.hypot(row[f["vx"]], row[f["vy"]]))


def _progress_bar(env: Any, laps: int, length: float) -> Any:
    """A tqdm bar of the distance driven, with the simulated time and the car's speed (m/s)
    beside it. No tqdm rate: it would be metres per wall-clock second, not the car's speed."""
    from tqdm import tqdm

    return tqdm(
        total=round(laps * length, 1),
        desc=f"driving {env.tracks[0].name}",
        leave=False,
        bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.1f}/{total:.1f} m{postfix}",  # postfix: ", sim ..."
    )


@dataclass
class _DriveLog:
    """What a drive has seen so far: its steps, lap times, contacts and top speed."""

    laps: int
    length: float
    dt: float
    steps: int = 0
    progressed: float = 0.0
    lap_times: list[float] = field(default_factory=list)
    contacts: int = 0
    vmax: float = 0.0
    collided: bool = False
    contact_at: list[float] | None = None
    width_at_contact: float | None = None

    def record(self, env: Any, obs: Any, info: dict[str, Any], state_speed: int | None) -> None:
        """Take in one step's observation and info."""
        self.steps += 1
        self.progressed = float(np.min(info["progress"]))
        while len(self.lap_times) < self.laps and self.progressed >= (len(self.lap_times) + 1) * self.length:
            self.lap_times.append(round(self.steps * self.dt, 3))
        contact = bool(np.any(info["contact_wall"]) or np.any(info["contact_vehicle"]))
        self.contacts += contact
        if contact and not self.collided:
            state, f = env.simulator_state
            x, y = float(state[0, f["x"]]), float(state[0, f["y"]])
            self.contact_at = [round(x, 3), round(y, 3)]
            self.width_at_contact = round(env.tracks[0].corridor_width_near(x, y), 3)
        self.collided = self.collided or contact
        if state_speed is not None:
            self.vmax = max(self.vmax, float(np.max(np.abs(env.odometry_raw(obs)[:, state_speed]))))

    def last_lap(self) -> float | None:
        """The time of the last completed lap (s), or None before the first."""
        t = self.lap_times
        return t[-1] - (t[-2] if len(t) > 1 else 0.0) if t else None

    def result(self, env: Any, info: dict[str, Any], wall_time: float, video: str | None) -> DriveResult:
        """The drive's result, ``info`` being the last step's."""
        return DriveResult(
            track=env.tracks[0].name,
            track_length=round(self.length, 3),
            laps_requested=self.laps,
            laps_completed=len(self.lap_times),
            lap_times=[round(b - a, 3) for a, b in zip([0.0, *self.lap_times[:-1]], self.lap_times)],
            collided=self.collided,
            contact_steps=self.contacts,
            sim_time=round(self.steps * self.dt, 3),
            distance=round(float(np.min(info["progress"])), 3),
            max_speed=round(self.vmax, 3),
            wall_time=wall_time,
            video=video,
            contact_at=self.contact_at,
            corridor_width_at_contact=self.width_at_contact,
            vehicle_width=env.config.sim.vehicle.chassis_width,
        )


class _Film:
    """The drive's video: a frame every ``every`` steps, framed as a preview with a HUD."""

    def __init__(self, env: Any, base_env: Any, laps: int, video_fps: float, render_size: int) -> None:
        from .render.drive_view import DriveView, drive_subtitle

        self.env, self.base_env, self.laps = env, base_env, laps
        self.every = max(1, round(env.config.control_rate_hz / video_fps))
        self.view = DriveView(
            base_env.tracks[0], base_env.config.sim, subtitle=drive_subtitle(laps), map_px=render_size
        )
        self.frames: list[np.ndarray] = []

    def add(self, log: _DriveLog) -> None:
        """One frame of the car's state now, with the drive's HUD."""
        from .render.drive_view import HudState

        state, f = self.base_env.simulator_state
        hud = HudState(log.steps * log.dt, _speed_now(self.base_env), len(log.lap_times), self.laps, log.last_lap())
        self.frames.append(self.view.frame(state, f, self.base_env.simulator_scans, hud))

    def write(self, video: Any) -> str:
        """Write the frames to ``video``; returns its path."""
        from .render.video import write_video

        return str(write_video(self.frames, video, fps=self.env.config.control_rate_hz / self.every))
