"""``python -m benchmarks fidelity``: what the vehicle model does in standard
manoeuvres, against physics a reader can check and beside F1TENTH Gym's single-track
model (re-implemented in :mod:`benchmarks.f1tenth_st`, reference only).

All runs use one car in an empty 300 m hall (no walls reached), the default
``VehicleConfig`` unless a row says otherwise:

* top speed (``max_speed`` raised to 25 m/s, so the motor, drag and rolling resistance
  decide), 0 -> 6.66 m/s (the recorded maximum) time and distance;
* braking 6 -> 0 m/s against the ideal friction-limited stop ``v / (mu g)``,
  ``v^2 / (2 mu g)``;
* steady cornering at v = 1..6 m/s and several steering angles: yaw rate and lateral
  acceleration against linear single-track theory ``r = v delta / (L + K v^2)`` with
  ``K = (1/C_Sf - 1/C_Sr) / g`` (cornering stiffness per unit load), and against the
  friction limit ``a <= mu g``, and against the quasi-static steady state of the same
  vehicle model solved from its equations (:mod:`benchmarks.fidelity_limit`),
  whose best steering angle gives the honest friction limit of this car (below mu g: the
  drive force that holds speed against the saturated tyres' drag shares their friction);
* whether the recorded envelope (6.66 m/s; 5.46 rad/s yaw rate) is reachable without
  sliding, and the largest transient yaw rate of a full-lock step steer;
* dt sensitivity of a steady turn and of the braking stop.
"""

from __future__ import annotations

import argparse
import math

import numpy as np
from pydantic import ConfigDict, Field

from roboracer_arena import _core
from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.config.sim import PhysicsConfig, SimConfig, VehicleConfig

from . import fidelity_limit
from .f1tenth_st import GYM_PARAMS, SingleTrack

HALL = 150.0
RECORDED_SPEED = 6.66  # paper: observed maximum (m/s)
RECORDED_YAW = 5.46  # paper: observed yaw-rate p99 (rad/s)
SPEEDS = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
# Multiples of the gym's steering step sv_max * dt = 0.032 rad: its bang-bang steering
# dithers by one step around any other target.
STEERS = [0.064, 0.128, 0.192, 0.288]


class Straight(BenchModel):
    """Top speed (m/s) and the time (s) and distance (m) to 6.66 m/s (None: never reached)."""

    top_speed: float
    t_0_to_6_66: float | None
    d_0_to_6_66: float | None


class Braking(BenchModel):
    """Time (s) and distance (m) of a full stop; for ours also the ideal mu g stop."""

    t: float
    d: float
    t_ideal: float | None = None
    d_ideal: float | None = None


class Turn(BenchModel):
    """A steady turn at command (v, steer): ours, linear theory, the friction limit mu g,
    the quasi-static model (None: no steady state) and the gym's single-track model."""

    v: float
    steer: float
    yaw_rate: float
    lat_acc: float
    linear_yaw_rate: float
    limit_lat_acc: float
    linear_saturated: bool
    qs_lat_acc: float | None
    gym_yaw_rate: float
    gym_lat_acc: float


class CorneringLimit(BenchModel):
    """See :func:`cornering_limit`."""

    v: float
    ours_peak: float
    qs_limit: float
    qs_steer: float
    qs_drive_force: float
    qs_inner_front_load: float
    qs_load_split_limit: float


class Envelope(BenchModel):
    """See :func:`envelope`."""

    r_max: float
    v_at_r_max: float
    mu_needed_for_recorded: float


class DtSensitivity(BenchModel):
    """At one physics step: the yaw rate of a 3 m/s, 0.2 rad turn and the 6 -> 0 stop."""

    model_config = ConfigDict(serialize_by_alias=True, validate_by_name=True)

    dt: float
    yaw_rate_3ms: float = Field(alias="yaw_rate_3ms_0.2")
    brake_t: float
    brake_d: float


class FidelityResult(BenchModel):
    """``bench fidelity``: every manoeuvre, ours beside the gym's and the physics."""

    limit: list[CorneringLimit]
    straight: Straight
    gym_straight: Straight
    braking: Braking
    gym_braking: Braking
    turns: list[Turn]
    envelope: Envelope
    step_steer_peak_yaw: dict[float, float]
    dt_sensitivity: list[DtSensitivity]
    mu_g: float
    gym_params: dict[str, float]


class _Car:
    """One car of `config` in the empty hall at (-HALL + 10, 0) heading +x."""

    def __init__(self, config: SimConfig, speed: float = 0.0, x: float = -HALL + 10.0) -> None:
        h = HALL
        walls = [np.array([[-h, -h], [h, -h], [h, h], [-h, h]], float)]
        centre = np.array([[-5.0, -5.0], [5.0, -5.0], [5.0, 5.0], [-5.0, 5.0]])
        self.sim = _core.Simulator([(walls, centre)], 1, 1, config, 0)
        self.dt = config.physics.dt
        mask = np.ones(1, bool)
        self.sim.reset(mask, np.array([[[x, 0.0, 0.0]]]))
        if speed:
            self.sim.set_speeds(mask, np.array([[speed]]))
        fields = self.sim.state_fields
        self.i = {k: fields.index(k) for k in ("x", "y", "vx", "vy", "yaw_rate", "speed")}
        self.state = np.zeros((1, 1, len(fields)))
        self.events = np.zeros((1, 1), np.uint8)
        self.actions = np.zeros((1, 1, 2))
        self.sim.observe(None, self.state, self.events)
        self.t = 0.0

    def step(self, steer: float, speed: float, substeps: int = 1) -> None:
        self.actions[0, 0] = steer, speed
        self.sim.step(self.actions, substeps, None, self.state, self.events)
        self.t += substeps * self.dt

    def __getitem__(self, key: str) -> float:
        return float(self.state[0, 0, self.i[key]])


def _config(dt: float = 0.005, **vehicle: float) -> SimConfig:
    return SimConfig(vehicle=VehicleConfig(**vehicle), physics=PhysicsConfig(dt=dt))


def straight_line(dt: float = 0.005) -> Straight:
    """Top speed and the 0 -> 6.66 m/s run (ours)."""
    car = _Car(_config(dt, max_speed=25.0))
    t_rec = d_rec = None
    top, x0 = 0.0, car["x"]
    while car.t < 14.0:
        car.step(0.0, 25.0)
        v = car["vx"]
        top = max(top, v)
        if t_rec is None and v >= RECORDED_SPEED:
            t_rec, d_rec = car.t, car["x"] - x0
    return Straight(top_speed=top, t_0_to_6_66=t_rec, d_0_to_6_66=d_rec)


def braking(dt: float = 0.005, v0: float = 6.0) -> Braking:
    """Full stop from `v0` with a 0 m/s command (ours), and the ideal mu g stop."""
    cfg = _config(dt)
    car = _Car(cfg, speed=v0)
    x0 = car["x"]
    while car["vx"] > 0.01 and car.t < 5.0:
        car.step(0.0, 0.0)
    mu_g = cfg.vehicle.tyre_friction * cfg.physics.gravity
    return Braking(t=car.t, d=car["x"] - x0, t_ideal=v0 / mu_g, d_ideal=v0**2 / (2 * mu_g))


def steady_turn(v: float, steer: float, dt: float = 0.005, seconds: float = 6.0) -> dict[str, float]:
    """Mean yaw rate and speed over the last second of a constant (steer, v) command."""
    car = _Car(_config(dt), speed=v, x=0.0)
    n = max(1, round(0.05 / dt))
    rs, vs = [], []
    while car.t < seconds - 1e-9:
        car.step(steer, v, n)
        if car.t > seconds - 1.0:
            rs.append(car["yaw_rate"])
            vs.append(math.hypot(car["vx"], car["vy"]))
    r, speed = float(np.mean(rs)), float(np.mean(vs))
    return {"yaw_rate": r, "speed": speed, "lat_acc": r * speed}


def linear_theory(v: float, steer: float, vc: VehicleConfig | None = None, g: float = 9.81) -> float:
    """Steady yaw rate of the linear single-track model with our tyre stiffness per load."""
    vc = vc or VehicleConfig()
    k = (1.0 / vc.cornering_stiffness_front - 1.0 / vc.cornering_stiffness_rear) / g
    return v * steer / (vc.wheelbase + k * v * v)


def gym_straight() -> Straight:
    car = SingleTrack()
    t, top, t_rec, d_rec = 0.0, 0.0, None, None
    while t < 14.0:
        car.step(0.0, 25.0)
        t += car.dt
        top = max(top, car.speed)
        if t_rec is None and car.speed >= RECORDED_SPEED:
            t_rec, d_rec = t, car.position[0]
    return Straight(top_speed=top, t_0_to_6_66=t_rec, d_0_to_6_66=d_rec)


def gym_braking(v0: float = 6.0) -> Braking:
    car = SingleTrack()
    car.reset(v0)
    t = 0.0
    while car.speed > 0.01 and t < 5.0:
        car.step(0.0, 0.0)
        t += car.dt
    return Braking(t=t, d=car.position[0])


def gym_turn(v: float, steer: float, seconds: float = 6.0) -> dict[str, float]:
    car = SingleTrack()
    car.reset(v)
    n = round(seconds / car.dt)
    rs = []
    for i in range(n):
        car.step(steer, v)
        if i >= n - round(1.0 / car.dt):
            rs.append(car.yaw_rate)
    r = float(np.mean(rs))
    return {"yaw_rate": r, "lat_acc": r * car.speed}


def peak_step_yaw(v: float, dt: float = 0.005) -> float:
    """Largest |yaw rate| in 2 s after a full-lock step steer at speed v (ours)."""
    cfg = _config(dt)
    car = _Car(cfg, speed=v, x=0.0)
    peak = 0.0
    while car.t < 2.0:
        car.step(cfg.vehicle.max_steer, v)
        peak = max(peak, abs(car["yaw_rate"]))
    return peak


def envelope(vc: VehicleConfig, g: float = 9.81) -> Envelope:
    """The steady, non-sliding yaw-rate bound min(v tan(dmax) / L, mu g / v): its
    maximum, the speed of it, and the friction needed for the recorded yaw rate."""
    tan = math.tan(vc.max_steer)
    v_star = math.sqrt(vc.tyre_friction * g * vc.wheelbase / tan)
    return Envelope(
        r_max=v_star * tan / vc.wheelbase,
        v_at_r_max=v_star,
        mu_needed_for_recorded=RECORDED_YAW**2 * vc.wheelbase / (g * tan),
    )


def run(quick: bool = False) -> FidelityResult:
    vc = VehicleConfig()
    mu_g = vc.tyre_friction * 9.81
    speeds = [1.0, 3.0, 5.0] if quick else SPEEDS
    turns = []
    for v in speeds:
        for d in STEERS:
            ours, gym = steady_turn(v, d), gym_turn(v, d)
            lin = linear_theory(v, d, vc)
            qs = fidelity_limit.steady_turn(ours["speed"], d, vc)
            turns.append(
                Turn(
                    v=v,
                    steer=d,
                    yaw_rate=ours["yaw_rate"],
                    lat_acc=ours["lat_acc"],
                    linear_yaw_rate=lin,
                    limit_lat_acc=mu_g,
                    linear_saturated=lin * v > mu_g,
                    qs_lat_acc=qs.lat_acc if qs else None,
                    gym_yaw_rate=gym["yaw_rate"],
                    gym_lat_acc=gym["lat_acc"],
                )
            )
    dts = [0.0025, 0.005, 0.01, 0.02]
    sens = []
    for dt in dts:
        stop = braking(dt)
        sens.append(
            DtSensitivity(dt=dt, yaw_rate_3ms=steady_turn(3.0, 0.2, dt)["yaw_rate"], brake_t=stop.t, brake_d=stop.d)
        )
    return FidelityResult(
        limit=[cornering_limit(v, turns, vc) for v in speeds if v >= 4.0],
        straight=straight_line(),
        gym_straight=gym_straight(),
        braking=braking(),
        gym_braking=gym_braking(),
        turns=turns,
        envelope=envelope(vc),
        step_steer_peak_yaw={v: peak_step_yaw(v) for v in ([2.0, 4.0] if quick else [2.0, 3.0, 4.0, 5.0, 6.0])},
        dt_sensitivity=sens,
        mu_g=mu_g,
        gym_params=GYM_PARAMS,
    )


def cornering_limit(v: float, turns: list[Turn], vc: VehicleConfig) -> CorneringLimit:
    """At speed `v`: the largest steady lateral acceleration among our grid's turns, the
    quasi-static limit of the same model (best steering angle), and that limit if the
    drive force were shared in proportion to the wheel loads instead of a quarter each."""
    qs = fidelity_limit.cornering_limit(v, vc)
    return CorneringLimit(
        v=v,
        ours_peak=max(t.lat_acc for t in turns if t.v == v),
        qs_limit=qs.lat_acc,
        qs_steer=qs.steer,
        qs_drive_force=qs.drive_force,
        qs_inner_front_load=qs.loads[0],
        qs_load_split_limit=fidelity_limit.cornering_limit(v, vc, equal_split=False).lat_acc,
    )


def _f(x: float | None, spec: str = ".2f") -> str:
    return "-" if x is None else format(x, spec)


def print_table(res: FidelityResult) -> None:
    s, gs, b, gb = res.straight, res.gym_straight, res.braking, res.gym_braking
    print("straight line and braking            ours     F1TENTH Gym ST   reference")
    print(
        f"top speed (m/s)                   {s.top_speed:7.2f}   {gs.top_speed:14.2f}   Velineon 3500 kV on 3S, F1TENTH gearing: 16.8 no-load"
    )
    print(f"0 -> 6.66 m/s time (s)            {_f(s.t_0_to_6_66):>7}   {_f(gs.t_0_to_6_66):>14}")
    print(f"0 -> 6.66 m/s distance (m)        {_f(s.d_0_to_6_66):>7}   {_f(gs.d_0_to_6_66):>14}")
    print(f"brake 6 -> 0 time (s)             {b.t:7.2f}   {gb.t:14.2f}   ideal mu g stop {b.t_ideal:.2f}")
    print(f"brake 6 -> 0 distance (m)         {b.d:7.2f}   {gb.d:14.2f}   ideal mu g stop {b.d_ideal:.2f}")
    print()
    print(
        f"steady cornering (last 1 s of 6 s); linear theory r = v d / (L + K v^2); friction limit mu g = {res.mu_g:.2f} m/s^2"
    )
    head = f"{'v':>4} {'steer':>6} {'r ours':>8} {'r linear':>9} {'ours/lin':>9} {'a ours':>7} {'a/mu g':>7} {'a QS':>7} {'r gym':>7} {'a gym':>7}"
    print(head)
    print("-" * len(head))
    for t in res.turns:
        ratio = t.yaw_rate / t.linear_yaw_rate
        sat = " (lin > mu g)" if t.linear_saturated else ""
        print(
            f"{t.v:4.1f} {t.steer:6.3f} {t.yaw_rate:8.3f} {t.linear_yaw_rate:9.3f} {ratio:9.3f} "
            f"{t.lat_acc:7.2f} {t.lat_acc / t.limit_lat_acc:7.3f} {_f(t.qs_lat_acc):>7} "
            f"{t.gym_yaw_rate:7.3f} {t.gym_lat_acc:7.2f}{sat}"
        )
    print("a QS: the quasi-static steady state of our model at our measured speed (bench/fidelity_limit.py)")
    print()
    print("friction limit (quasi-static, best steering angle) vs mu g; why it is below mu g:")
    for lim in res.limit:
        mu_g = res.mu_g
        print(
            f"  {lim.v:g} m/s: ours peak {lim.ours_peak:.2f} m/s^2, QS limit {lim.qs_limit:.2f} "
            f"({lim.qs_limit / mu_g:.3f} mu g) at steer {lim.qs_steer:.3f}; holding speed takes "
            f"{lim.qs_drive_force:.1f} N of drive, a quarter per wheel, on an inner front wheel loaded "
            f"{lim.qs_inner_front_load:.1f} N; drive shared by load instead: {lim.qs_load_split_limit:.2f} "
            f"({lim.qs_load_split_limit / mu_g:.3f} mu g)"
        )
    e = res.envelope
    print()
    print(
        f"recorded envelope: {RECORDED_SPEED} m/s reachable: {'yes' if s.top_speed >= RECORDED_SPEED else 'NO'} (top {s.top_speed:.2f} m/s)"
    )
    print(
        f"  {RECORDED_YAW} rad/s without sliding: no. The steady non-sliding bound min(v tan(dmax)/L, mu g/v) peaks at "
        f"{e.r_max:.2f} rad/s at {e.v_at_r_max:.2f} m/s; {RECORDED_YAW} rad/s would need mu >= "
        f"{e.mu_needed_for_recorded:.2f}. Peak |yaw rate| of a full-lock step steer (transient, ours): "
        + ", ".join(f"{v:g} m/s {r:.2f}" for v, r in res.step_steer_peak_yaw.items())
    )
    print()
    print("dt sensitivity (internal steps of at most 10 ms)")
    print(f"{'dt (s)':>7} {'r @3 m/s, 0.2':>14} {'brake t':>8} {'brake d':>8}")
    for r in res.dt_sensitivity:
        print(f"{r.dt:7.4f} {r.yaw_rate_3ms:14.4f} {r.brake_t:8.3f} {r.brake_d:8.3f}")


def _cli(args: argparse.Namespace) -> int:
    res = run(quick=args.quick)
    print_table(res)
    write_json(args.json, res)
    return 0


def register(kinds) -> None:
    p = add_bench_parser(kinds, "fidelity", "vehicle model vs physics and F1TENTH Gym's single-track model", __doc__)
    p.add_argument("--quick", action="store_true", help="fewer speeds (1, 3, 5 m/s)")
    p.set_defaults(func=_cli)


def run_quick() -> FidelityResult:
    """`bench all`: the quick variant."""
    res = run(quick=True)
    print_table(res)
    return res
