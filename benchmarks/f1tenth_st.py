"""REFERENCE ONLY: F1TENTH Gym's single-track vehicle model, re-implemented from its
published equations and parameters for ``python -m benchmarks fidelity`` to compare
against. Not used by the simulator.

The model is the CommonRoad single-track (ST) model with load transfer through ``h``
(Althoff et al., CommonRoad: Vehicle Models, 2020, section 7), as F1TENTH Gym
(``f110_gym``, ``vehicle_dynamics_st``) uses it: a kinematic model below 0.5 m/s, a
linear tyre with stiffness ``mu * C_S * F_z`` (no saturation), the acceleration limit
``a_max`` (scaled by ``v_switch / v`` above ``v_switch``), the steering-rate limit
``sv_max``, and the gym's proportional speed and bang-bang steering controller, all
integrated with fourth-order Runge-Kutta at the gym's 0.01 s step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

G = 9.81

#: F1TENTH Gym's published default parameters (its F1/10 Traxxas car).
GYM_PARAMS: dict[str, float] = {
    "mu": 1.0489,
    "C_Sf": 4.718,
    "C_Sr": 5.4562,
    "lf": 0.15875,
    "lr": 0.17145,
    "h": 0.074,
    "m": 3.74,
    "I": 0.04712,
    "s_min": -0.4189,
    "s_max": 0.4189,
    "sv_min": -3.2,
    "sv_max": 3.2,
    "v_switch": 7.319,
    "a_max": 9.51,
    "v_min": -5.0,
    "v_max": 20.0,
}


@dataclass
class STState:
    """x, y (m), steering angle delta (rad), speed v (m/s), heading psi, yaw rate (rad/s),
    slip angle beta at the CoM (rad)."""

    x: float = 0.0
    y: float = 0.0
    delta: float = 0.0
    v: float = 0.0
    psi: float = 0.0
    r: float = 0.0
    beta: float = 0.0

    def vec(self) -> list[float]:
        return [self.x, self.y, self.delta, self.v, self.psi, self.r, self.beta]


def _accl_limit(v: float, a: float, p: dict[str, float]) -> float:
    pos = p["a_max"] * p["v_switch"] / v if v > p["v_switch"] else p["a_max"]
    if (v <= p["v_min"] and a <= 0) or (v >= p["v_max"] and a >= 0):
        return 0.0
    return min(max(a, -p["a_max"]), pos)


def _steer_limit(delta: float, sv: float, p: dict[str, float]) -> float:
    if (delta <= p["s_min"] and sv <= 0) or (delta >= p["s_max"] and sv >= 0):
        return 0.0
    return min(max(sv, p["sv_min"]), p["sv_max"])


def _controller(speed: float, steer: float, s: list[float], p: dict[str, float]) -> tuple[float, float]:
    """The gym's controller: bang-bang steering rate, proportional acceleration."""
    diff = steer - s[2]
    sv = math.copysign(p["sv_max"], diff) if abs(diff) > 1e-4 else 0.0
    dv = speed - s[3]
    if s[3] > 0:
        kp = 10.0 * p["a_max"] / p["v_max"] if dv > 0 else 10.0 * p["a_max"] / -p["v_min"]
    else:
        kp = 2.0 * p["a_max"] / p["v_max"] if dv > 0 else 2.0 * p["a_max"] / -p["v_min"]
    return kp * dv, sv


def _deriv(s: list[float], a: float, sv: float, p: dict[str, float]) -> list[float]:
    x, y, d, v, psi, r, beta = s
    a, sv = _accl_limit(v, a, p), _steer_limit(d, sv, p)
    lf, lr, h, m, inertia, mu = p["lf"], p["lr"], p["h"], p["m"], p["I"], p["mu"]
    lwb = lf + lr
    if abs(v) < 0.5:  # kinematic model at low speed
        return [
            v * math.cos(psi),
            v * math.sin(psi),
            sv,
            a,
            v / lwb * math.tan(d),
            a / lwb * math.tan(d) + v / (lwb * math.cos(d) ** 2) * sv,
            0.0,
        ]
    cf, cr = p["C_Sf"], p["C_Sr"]
    nf, nr = G * lr - a * h, G * lf + a * h
    k = mu * m / (inertia * lwb)
    r_dot = (
        -k * (lf**2 * cf * nf + lr**2 * cr * nr) * r / v
        + k * (lr * cr * nr - lf * cf * nf) * beta
        + k * lf * cf * nf * d
    )
    beta_dot = (
        (mu / (v**2 * lwb) * (cr * nr * lr - cf * nf * lf) - 1.0) * r
        - mu / (v * lwb) * (cr * nr + cf * nf) * beta
        + mu / (v * lwb) * cf * nf * d
    )
    return [v * math.cos(psi + beta), v * math.sin(psi + beta), sv, a, r, r_dot, beta_dot]


class SingleTrack:
    """One car under the gym's model; :meth:`step` advances one 0.01 s RK4 step."""

    def __init__(self, params: dict[str, float] | None = None, dt: float = 0.01) -> None:
        self.p = dict(GYM_PARAMS if params is None else params)
        self.dt = dt
        self.s = STState().vec()

    def reset(self, speed: float = 0.0) -> None:
        self.s = STState(v=speed).vec()

    def step(self, steer: float, speed: float) -> None:
        a, sv = _controller(speed, steer, self.s, self.p)  # held over the step, as in the gym
        h, s = self.dt, self.s
        k1 = _deriv(s, a, sv, self.p)
        k2 = _deriv([x + h / 2 * k for x, k in zip(s, k1)], a, sv, self.p)
        k3 = _deriv([x + h / 2 * k for x, k in zip(s, k2)], a, sv, self.p)
        k4 = _deriv([x + h * k for x, k in zip(s, k3)], a, sv, self.p)
        self.s = [x + h / 6 * (q1 + 2 * q2 + 2 * q3 + q4) for x, q1, q2, q3, q4 in zip(s, k1, k2, k3, k4)]

    @property
    def speed(self) -> float:
        return self.s[3]

    @property
    def yaw_rate(self) -> float:
        return self.s[5]

    @property
    def position(self) -> tuple[float, float]:
        return self.s[0], self.s[1]
