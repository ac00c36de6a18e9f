"""Drive the stage's PhysX vehicle (``build --car``) through ovphysx on the CPU with the
reference pure pursuit (:class:`~roboracer_arena.drivers.PurePursuitDriver`), for one
lap; and the same lap in our simulator, for comparison (``scripts/physx_lap_bench.py``).

The driver gives ``[steer (rad), speed (m/s)]``; PhysX's basic drive takes a normalised
steer (``steer / max_steer``), an accelerator and a brake: a proportional speed loop
turns the speed command into those two, as the car's VESC speed loop does in our model.
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..drivers import PurePursuitDriver
from ..envs.env_config import EnvConfig
from ..envs.single import RoboRacerEnv
from ..errors import ConfigError
from ..frozen_model import FrozenModel
from ..sim_config import SimConfig
from ..usd.vehicle import MAX_BRAKE_TORQUE_NM, PEAK_TORQUE_NM
from .runtime import PhysxScene

CAR = "/World/Car"
#: Acceleration asked per m/s of speed error (1/s): a 1/8 s lag, so the car slows
#: into bends about as fast as the driver's speed profile drops.
SPEED_GAIN = 8.0
#: Largest acceleration / deceleration the speed loop asks (m/s^2). Full accelerator is
#: about 8 m/s^2 (mu g): the tyres then have no lateral grip left, and the car slid off
#: Monaco's first bend on a 3 m/s speed error. 4 m/s^2 leaves ~7 m/s^2 for cornering.
MAX_ACCEL = 4.0
MAX_DECEL = 8.0
#: Control period (s): the env's default 40 Hz control loop.
CONTROL_DT = 0.025


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
    def from_trace(
        cls, engine: str, points: np.ndarray, xy: list[tuple[float, float]], lap: float | None, **timing: Any
    ) -> LapRun:
        """The run of ``engine`` whose car passed ``xy``: deviation is each point's distance
        from the driver's resampled centreline ``points`` (5 cm spacing)."""
        if xy:
            p = np.asarray(xy)
            dev = np.hypot(points[None, :, 0] - p[:, 0:1], points[None, :, 1] - p[:, 1:2]).min(axis=1)
        else:
            dev = np.zeros(1)
        return cls(
            engine=engine,
            completed=lap is not None,
            lap_time_s=lap,
            mean_deviation_m=float(dev.mean()),
            max_deviation_m=float(dev.max()),
            **timing,
        )


class _Progress:
    """Arc length travelled along the driver's resampled centreline, unwrapped."""

    def __init__(self, driver: Any, x: float, y: float) -> None:
        self.driver, self.n = driver, len(driver.points)
        self.last = driver.project(x, y)
        self.s = 0.0

    def update(self, x: float, y: float) -> float:
        i = self.driver.project(x, y)
        step = (i - self.last + self.n // 2) % self.n - self.n // 2
        self.last = i
        self.s += step * self.driver.ds
        return self.s


def drive_physx_lap(stage: str | Path, track: Any, sim: SimConfig | None = None, max_seconds: float = 120.0) -> LapRun:
    """Drive the stage's car one lap in PhysX; the stage must carry ``/World/Car``."""
    from ovphysx.types import SimObjectType

    sim = sim or SimConfig()
    dt = float(sim.physics.dt)
    sub = max(1, round(CONTROL_DT / dt))
    driver = PurePursuitDriver(track.centreline)
    xy: list[tuple[float, float]] = []
    stepping = 0.0
    with PhysxScene(stage) as scene:
        physx = scene.physx
        with (
            physx.query(SimObjectType.VEHICLE, pattern=CAR).wait() as vq,
            physx.query(SimObjectType.RIGID_BODY, pattern=CAR).wait() as bq,
        ):
            if vq.metadata.total_prim_count != 1:
                raise ConfigError(f"{stage}: no PhysX vehicle at {CAR} (build it with --car)")
            scene.step(dt, 20)  # settle on the suspension
            x, y, yaw, v = _pose(physx, bq)
            prog = _Progress(driver, x, y)
            steps, t0, lap = 20, time.perf_counter(), None
            while steps * dt < max_seconds:
                steer, v_cmd = driver.act_pose(x, y, yaw, v)
                accelerator, brake = pedals(float(v_cmd), v, sim)
                controls = {
                    "steer": float(np.clip(steer / sim.vehicle.max_steer, -1.0, 1.0)),
                    "accelerator": accelerator,
                    "brake0": brake,
                }
                with physx.write(vq, list(controls)).wait() as w:
                    while (g := w.fetch_next().wait()) is not None:
                        g.tensors[0].fill_(controls[list(controls)[g.attribute_index]])
                        w.commit(g).wait()
                ts = time.perf_counter()
                scene.step(dt, sub)
                stepping += time.perf_counter() - ts
                steps += sub
                x, y, yaw, v = _pose(physx, bq)
                xy.append((x, y))
                if prog.update(x, y) >= driver.length:
                    lap = (steps - 20) * dt
                    break
            wall = time.perf_counter() - t0
        physx.wait_all()
    return LapRun.from_trace(
        "physx-cpu",
        driver.points,
        xy,
        lap,
        physics_steps=steps,
        wall_seconds=wall,
        steps_per_second=(steps - 20) / stepping if stepping > 0 else 0.0,
    )


def pedals(v_cmd: float, v: float, sim: SimConfig) -> tuple[float, float]:
    """(accelerator, brake) in [0, 1] for the basic drive: a proportional loop asks an
    acceleration (bounded by :data:`MAX_ACCEL` / :data:`MAX_DECEL`), turned into wheel
    torque through the car's mass, plus a feed-forward for rolling resistance and drag so
    the car holds the commanded speed instead of settling below it."""
    veh = sim.vehicle
    accel = float(np.clip(SPEED_GAIN * (v_cmd - v), -MAX_DECEL, MAX_ACCEL))
    resist = veh.rolling_resistance * veh.mass * 9.81 + 0.5 * 1.2 * veh.drag_area * v * v if v > 0.1 else 0.0
    force = veh.mass * accel + resist
    if force >= 0.0:
        return float(min(force * veh.wheel_radius / PEAK_TORQUE_NM, 1.0)), 0.0
    return 0.0, float(min(-force * veh.wheel_radius / (4.0 * MAX_BRAKE_TORQUE_NM), 1.0))


_POSE_ATTRS = ["position", "orientation", "linearVelocity"]


def _pose(physx: Any, query: Any) -> tuple[float, float, float, float]:
    """(x, y, yaw, forward speed) of the car's chassis."""
    body: dict[str, np.ndarray] = {}
    with physx.read(query, _POSE_ATTRS).wait() as result:
        while (g := result.fetch_next().wait()) is not None:
            body[query.dictionary.token_to_string(g.attribute)] = g.tensors[0].numpy()[g.prim_offset].copy()
            del g
    physx.wait_all()
    px, py = float(body["position"][0]), float(body["position"][1])
    qx, qy, qz, qw = (float(c) for c in body["orientation"][:4])  # PhysX order: x, y, z, w
    yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
    vel = body["linearVelocity"]
    return px, py, yaw, float(vel[0]) * math.cos(yaw) + float(vel[1]) * math.sin(yaw)


def drive_native_lap(track: Any, sim: SimConfig | None = None, max_seconds: float = 120.0) -> LapRun:
    """The same lap in our simulator (the env, grid start, pure pursuit)."""
    sim = sim or SimConfig()
    env = RoboRacerEnv(track=track, config=EnvConfig(sim=sim))
    driver = PurePursuitDriver(track.centreline)
    try:
        env.reset(seed=0)
        state, idx = env.simulator_state
        x, y = float(state[0, idx["x"]]), float(state[0, idx["y"]])
        prog = _Progress(driver, x, y)
        xy, t, lap, t0 = [], 0.0, None, time.perf_counter()
        ctrl_dt = float(env.config.control_dt)
        while t < max_seconds:
            state, idx = env.simulator_state
            x, y, yaw = (float(state[0, idx[k]]) for k in ("x", "y", "yaw"))
            v = float(state[0, idx["vx"]]) if "vx" in idx else 0.0
            steer, v_cmd = driver.act_pose(x, y, yaw, v)
            env.step(env.from_ackermann(np.array([steer, v_cmd])))
            t += ctrl_dt
            state, idx = env.simulator_state
            x, y = float(state[0, idx["x"]]), float(state[0, idx["y"]])
            xy.append((x, y))
            if prog.update(x, y) >= driver.length:
                lap = t
                break
        wall = time.perf_counter() - t0
    finally:
        env.close()
    steps = round(t / float(sim.physics.dt))
    return LapRun.from_trace(
        "roboracer-arena",
        driver.points,
        xy,
        lap,
        physics_steps=steps,
        wall_seconds=wall,
        steps_per_second=steps / wall if wall > 0 else 0.0,
    )
