"""Drive the stage's PhysX vehicle (``build --car``) through ovphysx on the CPU exactly as
our simulator drives its car, and the same runs in our simulator for comparison.

:class:`PhysxCar` runs, around every PhysX step, what ``arena_core::sim::vehicle`` runs
inside ours (same constants, same order, same step): the steering servo (first-order lag,
then the rate limit) on the virtual centre wheel, turned into the Ackermann API's
normalised steer; the VESC-style PI speed loop on the wheels' mean surface speed (read
from PhysX's wheels), with anti-windup; the motor current lag and the current window the
battery can drive against the back-EMF; the wheel torque that current gives, as
accelerator (torque along the wheels' rotation) or brake (against it); and the losses as
one wrench on the chassis: aerodynamic drag, and each wheel's rolling resistance from its
own load at its own contact patch (PhysX's basic drive shares one torque equally, so a
load-weighted resistance per wheel cannot go through it). The car's PhysX parameters come from
the same ``VehicleConfig`` (:func:`roboracer_arena.usd.vehicle.physx_params`).

A driver's commands ``[steer (rad), speed (m/s)]`` arrive at the env's control rate
(``EnvConfig.control_rate_hz``, 20 Hz by default) and hold for the physics steps between.

* :func:`drive_physx`: any per-step controller ``controller(scan, odometry) -> (steer,
  speed)`` on a built stage; the scan is our lidar's (the same walls, our exact 2D caster)
  at the PhysX car's pose. Returns a :class:`Trace`.
* :func:`drive_physx_lap` / :func:`drive_native_lap`: one pure-pursuit lap in each engine.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..config.build import BuildConfig
from ..config.sim import SimConfig
from ..drivers import PurePursuitDriver
from ..envs.env_config import EnvConfig
from ..envs.single import RoboRacerEnv
from ..errors import ConfigError
from ..foundation.frozen_model import FrozenModel
from ..usd.stage import StageMesh, author_stage
from ..usd.vehicle import AIR_DENSITY, CAR, ROLL_FADE, ackermann_command, author_car, physx_params
from .check import physx_scan, track_of_stage
from .runtime import PhysxScene

#: Settling steps on the suspension before a run starts (not counted in its time).
SETTLE_STEPS = 20
#: What the drive reads of each wheel every step: spin (the speed loop, the rolling
#: resistance's fade) and what places each wheel's rolling resistance.
WHEEL_COLUMNS = ["rotationSpeed", "suspensionForce", "isOnGround", "tireLongitudinalDirection", "groundHitPosition"]

Controller = Callable[[np.ndarray, dict[str, float]], tuple[float, float]]


def lag_step(tau: float, dt: float) -> float:
    """Fraction of the way a first-order lag of time constant ``tau`` moves in ``dt`` (ours)."""
    return 1.0 - math.exp(-dt / tau) if tau > 0.0 else 1.0


class Actuators:
    """Our model's actuator and drivetrain state and laws (``VehicleModel::apply`` and
    ``drive_substep``), for a car whose wheels another engine spins."""

    def __init__(self, sim: SimConfig) -> None:
        self.v = sim.vehicle
        self.g = float(sim.physics.gravity)
        self.par = physx_params(self.v, self.g)
        self.steer = 0.0
        self.current = 0.0
        self.integral = 0.0

    def sanitise(self, steer: float, speed: float) -> tuple[float, float]:
        """NaN/inf become 0; finite values clip to the documented domain (ours)."""
        v = self.v
        s = min(max(steer, -v.max_steer), v.max_steer) if math.isfinite(steer) else 0.0
        u = min(max(speed, v.min_speed), v.max_speed) if math.isfinite(speed) else 0.0
        return s, u

    def current_window(self, v_wheel: float) -> tuple[float, float]:
        """Motor current window (A) at wheel surface speed ``v_wheel`` (ours)."""
        v = self.v
        emf = self.par.force_per_amp * v_wheel
        v_max = v.max_duty * v.battery_voltage
        pos, neg = (
            (v.max_motor_current, v.max_brake_current) if v_wheel >= 0.0 else (v.max_brake_current, v.max_motor_current)
        )
        lo = max(-neg, (-v_max - emf) / v.motor_resistance)
        hi = max(min(pos, (v_max - emf) / v.motor_resistance), lo)
        return lo, hi

    def update(self, cmd: tuple[float, float], v_wheel: float, dt: float) -> tuple[float, float]:
        """Advance the servo and the speed loop by ``dt`` toward ``cmd`` (sanitised); returns
        (centre-wheel steer angle, motor torque at the wheels summed over the four, N m)."""
        v = self.v
        max_d = v.max_steer_rate * dt
        self.steer += min(max((cmd[0] - self.steer) * lag_step(v.steer_time_constant, dt), -max_d), max_d)
        err = cmd[1] - v_wheel
        lo, hi = self.current_window(v_wheel)
        want = v.speed_kp * err + v.speed_ki * self.integral
        if (want < hi or err < 0.0) and (want > lo or err > 0.0):
            self.integral += err * dt
        self.current += (min(max(want, lo), hi) - self.current) * lag_step(v.throttle_time_constant, dt)
        self.current = min(max(self.current, lo), hi)
        return self.steer, self.par.force_per_amp * self.current * v.wheel_radius


class CarState(FrozenModel):
    """The PhysX car after a step: pose (CoM), body-frame velocity, yaw rate, actual
    centre-wheel steer, planar speed signed by vx, mean wheel surface speed."""

    x: float
    y: float
    yaw: float
    vx: float
    vy: float
    yaw_rate: float
    steer: float
    speed: float
    wheel_speed: float


class PhysxCar:
    """The car at ``path`` of a loaded :class:`PhysxScene`, stepped as ours (module doc).
    Use as a context manager; :meth:`step` runs one physics step of ``dt``."""

    def __init__(self, scene: PhysxScene, sim: SimConfig, path: str = CAR) -> None:
        from ovphysx.types import SimObjectType

        self.scene, self.sim, self.physx = scene, sim, scene.physx
        self.dt = float(sim.physics.dt)
        self.act = Actuators(sim)
        self._queries = [
            self.physx.query(SimObjectType.VEHICLE, pattern=path).wait(),
            self.physx.query(SimObjectType.RIGID_BODY, pattern=path).wait(),
            self.physx.query(SimObjectType.VEHICLE_WHEEL, pattern=f"{path}/**").wait(),
        ]
        self._vq, self._bq, self._wq = (q.__enter__() for q in self._queries)
        if self._vq.metadata.total_prim_count != 1 or self._wq.metadata.total_prim_count != 4:
            self.close()
            raise ConfigError(f"no PhysX vehicle with four wheels at {path} (build the stage with --car)")
        self._gear = 1
        self.state = self._read()
        self.steps = 0
        self.step_seconds = 0.0

    def __enter__(self) -> PhysxCar:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        for q in getattr(self, "_queries", []):
            q.__exit__(None, None, None)
        self._queries = []
        self.physx.wait_all()

    def place(self, x: float, y: float, yaw: float) -> None:
        """Put the chassis at rest at ``(x, y, yaw)`` (its CoM at ``com_height``); settle after."""
        h = float(self.sim.vehicle.com_height)
        quat = [0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)]  # PhysX order: x, y, z, w
        self._write(self._bq, {"position": [x, y, h], "orientation": quat})
        self._write(self._bq, {"linearVelocity": [0.0, 0.0, 0.0], "angularVelocity": [0.0, 0.0, 0.0]})
        self.state = self._read()

    def settle(self, steps: int = SETTLE_STEPS) -> None:
        """Let the car sink onto its suspension with no command (not counted in :attr:`steps`)."""
        for _ in range(steps):
            self._write_controls(0.0, 0.0, 0.0)
            self.scene.step(self.dt)
        self.state = self._read()

    def set_speed(self, speed: float, max_steps: int = 60) -> None:
        """Rolling start (as ``Simulator.set_speeds``): the chassis at ``speed`` along its
        heading with the wheels rolling at it and the actuators at rest. PhysX's wheel spin
        is not writable: the chassis velocity is held while the free wheels roll up to it
        (at most ``max_steps`` physics steps, not counted in :attr:`steps`)."""
        for _ in range(max_steps):
            yaw = self.state.yaw
            self._write(self._bq, {"linearVelocity": [speed * math.cos(yaw), speed * math.sin(yaw), 0.0]})
            self._write(self._bq, {"angularVelocity": [0.0, 0.0, 0.0]})
            self._write_controls(0.0, 0.0, 0.0)
            self.scene.step(self.dt)
            self.state = self._read()
            if abs(self.state.wheel_speed - speed) < 0.002 * max(1.0, abs(speed)):
                break
        yaw = self.state.yaw
        self._write(self._bq, {"linearVelocity": [speed * math.cos(yaw), speed * math.sin(yaw), 0.0]})
        self.act.steer = self.act.current = self.act.integral = 0.0
        self.state = self._read()

    def step(self, steer: float, speed: float, count: bool = True) -> CarState:
        """One physics step toward the command ``(steer, speed)``; returns the new state."""
        cmd = self.act.sanitise(float(steer), float(speed))
        delta, torque = self.act.update(cmd, self.state.wheel_speed, self.dt)
        par, v = self.act.par, self.sim.vehicle
        direction = self.state.wheel_speed if abs(self.state.wheel_speed) > 1e-3 else torque
        if torque * direction >= 0.0:  # along the wheels' rotation: the motor drives
            gear = 1 if torque >= 0.0 else -1
            if gear != self._gear:
                self._write(self._vq, {"requestedGear": gear}, dtype=np.int32)
                self._gear = gear
            accel, brake = min(abs(torque) / par.peak_torque, 1.0), 0.0
        else:  # against it: motor braking
            accel, brake = 0.0, min(abs(torque) / 4.0 / par.max_brake_torque, 1.0)
        self._write_controls(ackermann_command(delta, v), accel, brake)
        self._write(self._bq, {"wrench": self._losses()})
        t0 = time.perf_counter()
        self.scene.step(self.dt)
        if count:
            self.step_seconds += time.perf_counter() - t0
            self.steps += 1
        self.state = self._read()
        return self.state

    def _losses(self) -> np.ndarray:
        """The losses as one wrench on the chassis (force, torque about the CoM, the CoM):
        aerodynamic drag on the horizontal velocity, and each wheel's rolling resistance,
        ``C_rr N`` against its rolling at its contact patch, ``N`` its own suspension load and
        faded in with its own surface speed, as ours (``drive_substep``). A load-weighted
        resistance per wheel, not one share of the total in the drive torque: the inner,
        lighter wheels resist less in a turn, which turns the car out of it (the measured
        understeer gradient moves by about 10 % at 3 m/s)."""
        v, w = self.sim.vehicle, self._wheels
        vx, vy = self._vel
        force = -0.5 * AIR_DENSITY * v.drag_area * math.hypot(vx, vy) * np.array([vx, vy, 0.0])
        torque = np.zeros(3)
        fade = np.clip(w["rotationSpeed"][:, 0] * v.wheel_radius / ROLL_FADE, -1.0, 1.0)
        loads = np.maximum(w["suspensionForce"][:, 2], 0.0) * w["isOnGround"][:, 0]
        for k in range(4):
            f = -v.rolling_resistance * loads[k] * fade[k] * w["tireLongitudinalDirection"][k]
            force += f
            torque += np.cross(w["groundHitPosition"][k] - self._com, f)
        return np.concatenate([force, torque, self._com])

    # ------------------------------------------------------------------ I/O
    def _write_controls(self, steer: float, accel: float, brake: float) -> None:
        self._write(self._vq, {"steer": steer, "accelerator": accel, "brake0": brake})

    def _write(self, query: Any, values: dict[str, Any], dtype: Any = np.float32) -> None:
        names = list(values)
        with self.physx.write(query, names).wait() as w:
            while (g := w.fetch_next().wait()) is not None:
                tensor = g.tensors[0]
                tensor.assign(np.asarray(values[names[g.attribute_index]], dtype=dtype).reshape(tuple(tensor.shape)))
                w.commit(g).wait()

    def _read_columns(self, query: Any, names: list[str]) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = {}
        with self.physx.read(query, names).wait() as result:
            while (g := result.fetch_next().wait()) is not None:
                arr = g.tensors[0].numpy()[g.prim_offset : g.prim_offset + g.prim_count].copy()
                out[query.dictionary.token_to_string(g.attribute)] = arr
                del g
        return out

    def _read(self) -> CarState:
        body = self._read_columns(self._bq, ["position", "orientation", "linearVelocity", "angularVelocity"])
        wheels = self._read_columns(self._wq, WHEEL_COLUMNS)
        self.physx.wait_all()
        self._wheels = {k: a.reshape(4, -1).astype(np.float64) for k, a in wheels.items()}  # (wheel, lane)
        self._com = body["position"][0][:3].astype(np.float64)
        px, py = (float(c) for c in body["position"][0][:2])
        qx, qy, qz, qw = (float(c) for c in body["orientation"][0][:4])  # PhysX order: x, y, z, w
        yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
        vel = body["linearVelocity"][0]
        self._vel = (float(vel[0]), float(vel[1]))
        c, s = math.cos(yaw), math.sin(yaw)
        vx, vy = self._vel[0] * c + self._vel[1] * s, -self._vel[0] * s + self._vel[1] * c
        omega = float(np.mean(self._wheels["rotationSpeed"][:, 0]))
        return CarState(
            x=px,
            y=py,
            yaw=yaw,
            vx=vx,
            vy=vy,
            yaw_rate=float(body["angularVelocity"][0][2]),
            steer=self.act.steer,
            speed=math.copysign(math.hypot(vx, vy), vx),
            wheel_speed=omega * self.sim.vehicle.wheel_radius,
        )


def write_flat_stage(path: str | Path, sim: SimConfig, half_size: float = 150.0) -> Path:
    """A stage of a flat square floor (``2 half_size`` m, no walls) with the car of ``sim``
    at the origin heading +x: the open-loop manoeuvres' ground."""
    h = float(half_size)
    floor = StageMesh(
        path="/World/Track/Floor",
        points=np.array([[-h, -h, 0.0], [h, -h, 0.0], [h, h, 0.0], [-h, h, 0.0]]),
        triangles=np.array([[0, 1, 2], [0, 2, 3]]),
        look="Floor",
        collider=True,
    )
    stage, _ = author_stage([floor], BuildConfig(), {"map_kind": "flat"})
    author_car(stage, sim, (0.0, 0.0, 0.0))
    out = Path(path)
    stage.GetRootLayer().Export(str(out))
    return out


class Trace(FrozenModel):
    """One closed-loop run, sampled at every control step: time (s), pose, speed (m/s),
    yaw rate (rad/s), actual steer (rad), the commands, and the lateral distance (m) from
    the track's centreline; ``lap_time_s`` once the car travelled one centreline length."""

    engine: str
    control_rate_hz: float
    t: list[float]
    x: list[float]
    y: list[float]
    yaw: list[float]
    speed: list[float]
    yaw_rate: list[float]
    steer: list[float]
    steer_cmd: list[float]
    speed_cmd: list[float]
    lateral_error: list[float]
    lap_time_s: float | None
    physics_steps: int
    wall_seconds: float
    steps_per_second: float
    start: list[float] = []
    """The car's pose (x, y, yaw) when the run began."""


class _Recorder:
    """Collects a :class:`Trace`'s columns and the lap: the core's progress along the
    track's centreline (``_core.ProgressTracker``, the simulator's own lap rule), fed the
    car's position every control step."""

    def __init__(self, track: Any, x: float, y: float) -> None:
        self.ref = PurePursuitDriver(track.centreline)
        self.prog = _core.ProgressTracker(np.asarray(track.centreline, dtype=np.float64), x, y)
        self.cols: dict[str, list[float]] = {
            k: []
            for k in ("t", "x", "y", "yaw", "speed", "yaw_rate", "steer", "steer_cmd", "speed_cmd", "lateral_error")
        }
        self.lap: float | None = None
        self._t = 0.0

    def add(self, t: float, s: dict[str, float], cmd: tuple[float, float]) -> bool:
        """Record one control step; True once the lap is complete."""
        pts = self.ref.points
        dev = float(np.hypot(pts[:, 0] - s["x"], pts[:, 1] - s["y"]).min())
        for k, val in (("t", t), ("steer_cmd", cmd[0]), ("speed_cmd", cmd[1]), ("lateral_error", dev)):
            self.cols[k].append(float(val))
        for k in ("x", "y", "yaw", "speed", "yaw_rate", "steer"):
            self.cols[k].append(float(s[k]))
        elapsed, self._t = t - self._t, t
        if self.prog.update(s["x"], s["y"], elapsed, abs(s["speed"]) * elapsed) and self.lap is None:
            self.lap = t
        return self.lap is not None


class _Lidar:
    """Our lidar at any pose on ``track``: a one-car simulator reset to the pose, scanned."""

    def __init__(self, track: Any, sim: SimConfig) -> None:
        self.sim = _core.Simulator([track.native()], 1, 1, sim, 0)
        self.mask = np.ones(1, bool)
        self.state = np.zeros((1, 1, len(self.sim.state_fields)))
        self.events = np.zeros((1, 1), np.uint8)
        self.scan = np.zeros((1, 1, self.sim.num_beams), np.float32)

    def __call__(self, x: float, y: float, yaw: float) -> np.ndarray:
        self.sim.reset(self.mask, np.array([[[x, y, yaw]]]))
        self.sim.observe(self.scan, self.state, self.events)
        return self.scan[0, 0].copy()


def _scanner(kind: str, track: Any, sim: SimConfig) -> Callable[[Any, dict[str, float]], np.ndarray]:
    """The lidar of a PhysX run: ``"ours"`` (our exact caster at the car's pose) or
    ``"physx"`` (PhysX raycasts against the stage's collision walls, as a PhysX lidar)."""
    if kind == "physx":
        return lambda scene, odo: physx_scan(scene, (odo["x"], odo["y"], odo["yaw"]), sim)
    if kind != "ours":
        raise ConfigError(f"lidar must be 'ours' or 'physx', got {kind!r}")
    ours = _Lidar(track, sim)
    return lambda scene, odo: ours(odo["x"], odo["y"], odo["yaw"])


def drive_physx(
    stage: str | Path,
    controller: Controller,
    sim: SimConfig | None = None,
    *,
    track: Any = None,
    control_rate_hz: float | None = None,
    max_seconds: float = 120.0,
    stop_at_lap: bool = True,
    start: tuple[float, float, float] | None = None,
    scan: bool = True,
    lidar: str = "ours",
) -> Trace:
    """Drive the stage's PhysX car with ``controller(scan, odometry) -> (steer, speed)`` at
    ``control_rate_hz`` (default: the env's, ``EnvConfig().control_rate_hz``) for up to
    ``max_seconds`` (or one lap, with ``stop_at_lap``). ``scan``: our lidar's raw ranges (m)
    at the car's pose on ``track`` (default: the stage's own track), or an empty array with
    ``scan=False``; ``lidar="physx"``: PhysX's own raycasts instead (:func:`_scanner`);
    ``odometry``: ``x, y, yaw, vx, vy, yaw_rate, steer, speed`` (SI, body
    frame velocities). ``sim``: the car's config, the one the stage was built with. ``start``: put the car
    at this pose (x, y, yaw) first (default: where the stage has it)."""
    sim = sim or SimConfig()
    rate = float(control_rate_hz or EnvConfig().control_rate_hz)
    track = track if track is not None else track_of_stage(stage)
    scanner = _scanner(lidar, track, sim) if scan else None
    sub = max(1, round(1.0 / (rate * float(sim.physics.dt))))
    with PhysxScene(stage) as scene, PhysxCar(scene, sim) as car:
        if start is not None:
            car.place(*start)
        car.settle()
        rec = _Recorder(track, car.state.x, car.state.y)
        pose0 = [car.state.x, car.state.y, car.state.yaw]
        t0, t = time.perf_counter(), 0.0
        while t < max_seconds - 1e-9:
            odo = car.state.to_json_dict()
            ranges = scanner(scene, odo) if scanner else np.zeros(0, np.float32)
            steer, speed = controller(ranges, odo)
            cmd = (float(steer), float(speed))
            for _ in range(sub):
                car.step(*cmd)
            t += sub * car.dt
            if rec.add(t, car.state.to_json_dict(), cmd) and stop_at_lap:
                break
        wall = time.perf_counter() - t0
        steps, busy = car.steps, car.step_seconds
    return Trace(
        engine="physx-cpu",
        control_rate_hz=rate,
        **rec.cols,
        lap_time_s=rec.lap,
        physics_steps=steps,
        wall_seconds=wall,
        steps_per_second=steps / busy if busy > 0 else 0.0,
        start=pose0,
    )


def drive_native(
    track: Any,
    controller: Controller,
    sim: SimConfig | None = None,
    *,
    control_rate_hz: float | None = None,
    max_seconds: float = 120.0,
    stop_at_lap: bool = True,
    start: tuple[float, float, float] | None = None,
) -> Trace:
    """The same run in our simulator: the env (grid start, ``control_rate_hz``), the same
    ``controller(scan, odometry)`` with the env's raw scan. ``start``: reset the car at this
    pose (x, y, yaw) instead of the grid start."""
    sim = sim or SimConfig()
    rate = float(control_rate_hz or EnvConfig().control_rate_hz)
    env = RoboRacerEnv(track=track, config=EnvConfig(sim=sim, control_rate_hz=rate))
    try:
        options = {"poses": np.asarray(start, dtype=np.float64)} if start is not None else None
        obs, _ = env.reset(seed=0, options=options)
        odo = _native_odometry(env)
        rec = _Recorder(track, odo["x"], odo["y"])
        pose0 = [odo["x"], odo["y"], odo["yaw"]]
        t, t0, steps = 0.0, time.perf_counter(), 0
        while t < max_seconds - 1e-9:
            steer, speed = controller(np.asarray(obs["scan"], np.float32).reshape(-1), odo)
            cmd = (float(steer), float(speed))
            obs, *_ = env.step(env.from_ackermann(np.array(cmd)))
            t += float(env.config.control_dt)
            steps += env.config.substeps
            odo = _native_odometry(env)
            if rec.add(t, odo, cmd) and stop_at_lap:
                break
        wall = time.perf_counter() - t0
    finally:
        env.close()
    return Trace(
        engine="roboracer-arena",
        control_rate_hz=rate,
        **rec.cols,
        lap_time_s=rec.lap,
        physics_steps=steps,
        wall_seconds=wall,
        steps_per_second=steps / wall if wall > 0 else 0.0,
        start=pose0,
    )


def _native_odometry(env: Any) -> dict[str, float]:
    state, idx = env.simulator_state
    return {k: float(state[0, idx[k]]) for k in ("x", "y", "yaw", "vx", "vy", "yaw_rate", "steer", "speed")}


def pure_pursuit(track: Any, sim: SimConfig | None = None) -> Controller:
    """The reference pure pursuit as a ``controller(scan, odometry)`` (it reads the pose)."""
    driver = PurePursuitDriver(track.centreline)

    def act(_scan: np.ndarray, odo: dict[str, float]) -> tuple[float, float]:
        steer, speed = driver.act_pose(odo["x"], odo["y"], odo["yaw"], odo["vx"])
        return float(steer), float(speed)

    return act


class LapRun(FrozenModel):
    """One lap driven by pure pursuit. ``steps_per_second``: physics steps per second of
    the engine's own stepping (PhysX: ``step_sync`` time only, not the Python reads and
    writes around it; ours: the env's whole step, lidar included)."""

    engine: str
    completed: bool
    lap_time_s: float | None
    mean_deviation_m: float
    max_deviation_m: float
    physics_steps: int
    wall_seconds: float
    steps_per_second: float

    @classmethod
    def from_run(cls, run: Trace) -> LapRun:
        dev = np.asarray(run.lateral_error or [0.0])
        return cls(
            engine=run.engine,
            completed=run.lap_time_s is not None,
            lap_time_s=run.lap_time_s,
            mean_deviation_m=float(dev.mean()),
            max_deviation_m=float(dev.max()),
            physics_steps=run.physics_steps,
            wall_seconds=run.wall_seconds,
            steps_per_second=run.steps_per_second,
        )


def drive_physx_lap(stage: str | Path, track: Any, sim: SimConfig | None = None, max_seconds: float = 120.0) -> LapRun:
    """Drive the stage's car one lap in PhysX with the reference pure pursuit at the env's
    control rate; the stage must carry ``/World/Car``."""
    run = drive_physx(stage, pure_pursuit(track, sim), sim, track=track, max_seconds=max_seconds, scan=False)
    return LapRun.from_run(run)


def drive_native_lap(track: Any, sim: SimConfig | None = None, max_seconds: float = 120.0) -> LapRun:
    """The same lap in our simulator (the env, grid start, pure pursuit)."""
    return LapRun.from_run(drive_native(track, pure_pursuit(track, sim), sim, max_seconds=max_seconds))
