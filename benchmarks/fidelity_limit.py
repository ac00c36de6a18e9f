"""Quasi-static steady cornering of our vehicle model, solved from its equations rather
than simulated: the honest reference for the friction limit of ``bench fidelity``.

The car turns on a circle at constant speed ``v`` and centre steering angle ``delta``.
The unknowns are the yaw rate ``r`` (lateral acceleration ``a = v r``), the sideslip
``beta`` and the total drive force ``F``; the three equations are the force balance along
and across the body and the yaw-moment balance. Everything else follows the simulator's
vehicle model (``crates/arena_core/src/sim/vehicle.rs``), term by term:

* wheel loads of a rigid chassis on four equal springs: ``N_i = A + B y_i + C x_i`` with
  ``sum N = m g``, ``sum y N = -h sum F_y`` (roll) and ``sum x N = -h sum F_x`` (pitch),
  the tyre forces acting at the ground, ``h`` the CoM height;
* Ackermann front wheel angles of the virtual centre wheel;
* lateral tyre force ``-C_a N atan(v_t / max(|v_l|, v0))``, perpendicular to the wheel;
* open differentials: every wheel carries a quarter of the drive force, less its rolling
  resistance ``f_r N`` (a spinning wheel in steady state transmits exactly its torque);
* the friction ellipse ``(F_x / mu_x N)^2 + (F_y / mu N)^2 <= 1``: a saturated tyre keeps
  its longitudinal force (set by the torque) and gives what is left laterally;
* aerodynamic drag ``0.5 rho C_d A v^2`` against the velocity, at the CoM.

Not modelled (all small, see BENCHMARKS.md): the sideways shift of the contact points
under body roll, suspension damping (zero in steady state), the bump stop (not reached).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from roboracer_arena.config.sim import VehicleConfig
from roboracer_arena.errors import InvalidArgumentError

AIR_DENSITY = 1.2  # kg/m^3, as in the simulator
V0 = 0.5  # m/s: slip reference speed floor, as in the simulator


@dataclass(frozen=True)
class SteadyTurn:
    """One quasi-static steady turn: the solution and what the tyres do in it."""

    v: float
    steer: float
    yaw_rate: float
    lat_acc: float
    sideslip: float
    drive_force: float
    loads: tuple[float, float, float, float]
    """Wheel loads (N) of FL, FR, RL, RR."""
    friction_use: tuple[float, float, float, float]
    """Each tyre's place on its friction ellipse (1 = saturated)."""


def _four(a: np.ndarray) -> tuple[float, float, float, float]:
    return float(a[0]), float(a[1]), float(a[2]), float(a[3])


def _ackermann(vc: VehicleConfig, steer: float) -> tuple[float, float]:
    wheelbase, half = vc.com_to_front + vc.com_to_rear, vc.track_width / 2.0
    tan = math.tan(steer)
    left = math.atan(wheelbase * tan / (wheelbase - half * tan))
    right = math.atan(wheelbase * tan / (wheelbase + half * tan))
    return left, right


class _Model:
    """The residuals of the three balance equations for one car, speed and steer."""

    def __init__(self, vc: VehicleConfig, g: float, v: float, steer: float, equal_split: bool) -> None:
        self.vc, self.g, self.v, self.equal_split = vc, g, v, equal_split
        lf, lr, half = vc.com_to_front, vc.com_to_rear, vc.track_width / 2.0
        self.x = np.array([lf, lf, -lr, -lr])
        self.y = np.array([half, -half, half, -half])
        left, right = _ackermann(vc, steer)
        self.angle = np.array([left, right, 0.0, 0.0])
        self.stiff = np.array([vc.cornering_stiffness_front] * 2 + [vc.cornering_stiffness_rear] * 2)
        # Loads N_i = A + B y_i + C x_i: rows are sum N, sum y N, sum x N.
        self.load_matrix = np.array(
            [
                [4.0, self.y.sum(), self.x.sum()],
                [self.y.sum(), (self.y**2).sum(), (self.x * self.y).sum()],
                [self.x.sum(), (self.x * self.y).sum(), (self.x**2).sum()],
            ]
        )

    def forces(self, unknowns: np.ndarray) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        r, beta, drive = unknowns
        vc, v, m = self.vc, self.v, self.vc.mass
        a = v * r
        acc = np.array([-a * math.sin(beta), a * math.cos(beta)])
        drag = -0.5 * AIR_DENSITY * vc.drag_area * v * v * np.array([math.cos(beta), math.sin(beta)])
        tyre_total = m * acc - drag  # what the four tyres must give together
        rhs = np.array([m * self.g, -vc.com_height * tyre_total[1], -vc.com_height * tyre_total[0]])
        coef = np.linalg.solve(self.load_matrix, rhs)
        n = coef[0] + coef[1] * self.y + coef[2] * self.x
        # Contact-point velocities, each wheel's own frame.
        vx = v * math.cos(beta) - r * self.y
        vy = v * math.sin(beta) + r * self.x
        c, s = np.cos(self.angle), np.sin(self.angle)
        vl, vt = vx * c + vy * s, -vx * s + vy * c
        fy = -self.stiff * n * np.arctan2(vt, np.maximum(np.abs(vl), V0))
        share = np.full(4, 0.25) if self.equal_split else n / n.sum()
        fx = share * drive - vc.rolling_resistance * n
        mu, mu_x = vc.tyre_friction, vc.tyre_friction * vc.longitudinal_friction_ratio
        n_pos = np.maximum(n, 1e-9)
        lon = np.clip(fx / (mu_x * n_pos), -1.0, 1.0)
        room = mu * n_pos * np.sqrt(1.0 - lon**2)
        fy = np.clip(fy, -room, room)
        use = np.sqrt(lon**2 + (fy / (mu * n_pos)) ** 2)
        fbx, fby = fx * c - fy * s, fx * s + fy * c
        res = np.array(
            [
                fbx.sum() - tyre_total[0],
                fby.sum() - tyre_total[1],
                (self.x * fby - self.y * fbx).sum(),
            ]
        )
        # A wheel asked for more longitudinal force than it can give spins up: no steady state.
        spin = np.maximum(np.abs(fx) - mu_x * n_pos, 0.0).sum()
        return res + spin, {"n": n, "use": use}


def steady_turn(
    v: float,
    steer: float,
    vc: VehicleConfig | None = None,
    g: float = 9.81,
    equal_split: bool = True,
) -> SteadyTurn | None:
    """The quasi-static steady turn at chassis speed `v` (m/s) and centre steering angle
    `steer` (rad), or None if the car has none there (a wheel would spin up, or the
    equations have no solution). `equal_split=False` gives every wheel drive force in
    proportion to its load instead of a quarter (ideal torque distribution)."""
    if not (math.isfinite(v) and v > 0.0 and math.isfinite(steer)):
        raise InvalidArgumentError(f"steady_turn: v must be a finite speed > 0 m/s and steer finite, got {v}, {steer}")
    vc = vc or VehicleConfig()
    model = _Model(vc, g, v, steer, equal_split)
    k = (1.0 / vc.cornering_stiffness_front - 1.0 / vc.cornering_stiffness_rear) / g
    r0 = v * steer / (vc.wheelbase + k * v * v)
    sol = least_squares(
        lambda u: model.forces(u)[0],
        x0=np.array([r0, 0.0, 0.05 * vc.mass * g]),
        x_scale=np.array([1.0, 0.1, 1.0]),
        xtol=1e-12,
        ftol=1e-12,
    )
    res, extra = model.forces(sol.x)
    if np.abs(res).max() > 1e-6:
        return None
    r, beta, drive = (float(x) for x in sol.x)
    return SteadyTurn(
        v=v,
        steer=steer,
        yaw_rate=r,
        lat_acc=v * r,
        sideslip=beta,
        drive_force=drive,
        loads=_four(extra["n"]),
        friction_use=_four(extra["use"]),
    )


def cornering_limit(v: float, vc: VehicleConfig | None = None, g: float = 9.81, equal_split: bool = True) -> SteadyTurn:
    """The steady turn of largest lateral acceleration at speed `v`: the best steering
    angle up to `max_steer` (the lateral force falls off past the front's saturation,
    as the saturated front tyres' drag grows with their slip angle). Raises
    InvalidArgumentError if the car has no steady turn at `v` at all."""
    vc = vc or VehicleConfig()

    def neg_acc(steer: float) -> float:
        t = steady_turn(v, steer, vc, g, equal_split)
        return -t.lat_acc if t else 0.0

    grid = np.linspace(0.01, vc.max_steer, 40)
    best = grid[int(np.argmin([neg_acc(d) for d in grid]))]
    step = grid[1] - grid[0]
    lo, hi = max(0.005, best - step), min(vc.max_steer, best + step)
    opt = minimize_scalar(neg_acc, bounds=(lo, hi), method="bounded", options={"xatol": 1e-5})
    turn = steady_turn(v, float(opt.x), vc, g, equal_split)
    if turn is None:  # the bounded search ended where no steady state exists
        turn = steady_turn(v, float(best), vc, g, equal_split)
    if turn is None:
        raise InvalidArgumentError(
            f"cornering_limit: this vehicle has no steady turn at {v} m/s (a wheel spins up at every steering angle)"
        )
    return turn
