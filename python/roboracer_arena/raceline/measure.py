"""The car's own limits, measured by driving the simulator's car on an open pad (no walls
within 100 m), as a test driver would measure a real one:

* **motor curve** (``ax_max_machines``): full speed command from standstill, straight;
  the acceleration at each speed is the slope of the speed trace;
* **braking** (ggv ``ax_max``): from top speed, command zero; the deceleration at each speed;
* **lateral** (ggv ``ay_max``): at each speed command, steady circles at growing steer;
  ``ay = speed * yaw rate`` once settled, the largest the car holds without losing more
  than 10 % of its speed (a speed whose largest circle is at full steering lock is
  steering-limited, not tyre-limited, and is left out: the table holds flat below);
* ``v_max``: the top speed reached.

:func:`measure_limits` returns :class:`~.limits.VehicleLimits` (``roboracer-arena
raceline --measure-limits FILE`` writes them; the ``car`` preset is that file for the
default :class:`~roboracer_arena.config.sim.SimConfig`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..envs.single import RoboRacerEnv
from ..track.drivable import Track
from .limits import VehicleLimits

#: Speeds (m/s) at which the lateral limit is measured.
LATERAL_SPEEDS = (1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 6.8)
#: Speed bins (m/s) of the longitudinal curves.
BIN = 0.5


def _pad() -> Track:
    th = np.linspace(0.0, 2 * np.pi, 256, endpoint=False)
    centre = np.column_stack([20.0 * np.cos(th), 20.0 * np.sin(th)])
    square = np.array([[-100.0, -100.0], [100.0, -100.0], [100.0, 100.0], [-100.0, 100.0], [-100.0, -100.0]])
    return Track.from_polylines([square], centre, name="test pad")


def _env(config: Any) -> RoboRacerEnv:
    kw: dict[str, Any] = {"reset_poses": "grid", "collision_ends_episode": False, "time_limit_s": None}
    if config is not None:
        kw["config"] = config
    return RoboRacerEnv(track=_pad(), **kw)


def _run(env: RoboRacerEnv, steer: float, speeds: list[float]) -> np.ndarray:
    """Drive with a fixed steer and the given speed command per step; rows (speed, yaw rate)."""
    env.reset(seed=0)
    rows = []
    for v in speeds:
        env.step(env.from_ackermann(np.array([steer, v])))
        state, f = env.simulator_state
        r = state[0]
        rows.append((float(np.hypot(r[f["vx"]], r[f["vy"]])), float(r[f["yaw_rate"]])))
    return np.asarray(rows)


def _binned_slope(speed: np.ndarray, dt: float, sign: float) -> list[tuple[float, float]]:
    """(v, |dv/dt|) by speed bin where the trace moves in ``sign``'s direction."""
    acc = np.diff(speed) / dt * sign
    mid = 0.5 * (speed[1:] + speed[:-1])
    out = []
    for lo in np.arange(0.0, float(speed.max()), BIN):
        m = (mid >= lo) & (mid < lo + BIN) & (acc > 0.05)
        if m.any():
            out.append((round(float(lo + BIN / 2), 3), round(float(np.median(acc[m])), 3)))
    if out:
        out.insert(0, (0.0, out[0][1]))
    return out


def measure_limits(config: Any = None, max_steer: float | None = None) -> VehicleLimits:
    """The simulator car's limits (default :class:`SimConfig`, or ``config``)."""
    env = _env(config)
    dt = float(env.config.control_dt)
    top = float(env.config.sim.vehicle.max_speed)
    steer_max = float(max_steer if max_steer is not None else env.max_steer)
    try:
        accel = _run(env, 0.0, [top] * int(8.0 / dt))
        v_top = float(accel[:, 0].max())
        machines = _binned_slope(accel[:, 0], dt, +1.0)
        brake_trace = _run(env, 0.0, [top] * int(8.0 / dt) + [0.0] * int(4.0 / dt))[int(8.0 / dt) :]
        # Below 1 m/s the speed loop eases the car to a stop: not a braking limit.
        brakes = [r for r in _binned_slope(brake_trace[:, 0], dt, -1.0) if r[0] >= 1.0]
        lateral = []
        settle = int(2.5 / dt)
        for v in LATERAL_SPEEDS:
            if v > v_top:
                break
            best, best_steer = 0.0, 0.0
            for steer in np.linspace(0.02, steer_max, 16):
                tr = _run(env, float(steer), [v] * (settle + int(1.0 / dt)))
                tail = tr[settle:]
                held = tail[:, 0].mean() >= 0.9 * v and np.ptp(tail[:, 1]) < 0.2 * max(abs(tail[:, 1].mean()), 0.1)
                ay = float(np.mean(tail[:, 0] * np.abs(tail[:, 1])))
                if held and ay > best:
                    best, best_steer = ay, float(steer)
            if best_steer < steer_max - 1e-6:  # at full lock the steering, not the tyres, limits ay
                lateral.append((v, round(best, 3)))
    finally:
        env.close()
    return _limits(v_top, machines, brakes, lateral)


def _limits(
    v_top: float,
    machines: list[tuple[float, float]],
    brakes: list[tuple[float, float]],
    lateral: list[tuple[float, float]],
) -> VehicleLimits:
    """Tables on one speed grid (each curve interpolated, held flat at its ends)."""
    b = np.asarray(brakes)
    lat = np.asarray([r for r in lateral if r[1] > 0])
    grid = np.round(np.arange(0.0, v_top + 1e-9, 0.5), 3)
    ggv = [
        (float(v), round(float(np.interp(v, b[:, 0], b[:, 1])), 3), round(float(np.interp(v, lat[:, 0], lat[:, 1])), 3))
        for v in grid
    ]
    return VehicleLimits(
        name="car",
        v_max=round(v_top, 3),
        ggv=ggv,
        ax_max_machines=[(float(v), a) for v, a in machines] or [(0.0, 1.0)],
        dyn_model_exp=2.0,
        source=(
            "measured from the simulator (raceline.measure): full-speed launch (motor curve), braking from top "
            "speed (ax_max), steady circles at growing steer per speed (ay_max); default SimConfig"
        ),
    )
