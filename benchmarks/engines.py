"""``python -m benchmarks engines``: one car, two engines, open loop (issue 36).

The same ``VehicleConfig`` drives the same open-loop manoeuvres in our simulator (the core
``Simulator``, one car in an empty 300 m hall) and in PhysX (ovphysx on the CPU, the car
that ``build --car`` authors, :func:`roboracer_arena.usd.vehicle.physx_params`, on a flat
300 m floor, driven by :class:`roboracer_arena.physx.drive.PhysxCar`: our servo, speed loop,
motor and losses around PhysX's chassis, suspension, tyres and wheels). No driver: every
command is a fixed function of time, so nothing can hide a difference in the dynamics.

Manoeuvres, each at tyre friction mu in {0.4, 0.6, 0.83, 1.0} and mass x {0.8, 1, 1.5}
(yaw inertia scaled with the mass, as domain randomisation does):

* **step steer**: rolling start at 3 m/s, 0.5 s straight, then a 0.04 rad step on the
  steering command at a constant 3 m/s command; yaw rate: 10-90 % rise time from the step,
  overshoot over the steady value, steady-state gain (yaw rate / steer, mean of the last 0.5 s);
* **steady cornering**: 3 m/s, the steering command ramped from 0 to 0.3 rad over 8 s
  (quasi-steady: 0.0375 rad/s); lateral acceleration ``r v`` against the actual steer,
  sampled at 0.05, 0.10, 0.15, 0.20 rad, its peak, and the understeer gradient ``K``
  (rad per m/s^2, the slope of ``delta - L r / v`` against ``a_y`` below 0.4 mu g);
* **acceleration**: from rest, the top speed command (``max_speed``, 7 m/s) for 5 s; time to
  5 m/s and the highest speed;
* **braking**: rolling start at 5 m/s, command 0; distance and time to a stop (< 0.05 m/s).

**Real-car anchor** (``--anchor``): ForzaETH's identified cars (On-Track-SysID, MIT; read
from ``../shared/vehicle-data`` when there) as ``VehicleConfig`` presets
(:mod:`roboracer_arena.config.vehicle_presets`): the steady yaw rate at 5 m/s and 0.05 rad of the
real car's own single-track model with its Pacejka tyres, of our engine and of PhysX on the
preset, and of the paper's car; ``--tyre-plot FILE`` draws our tyre (linear to ``mu N``) and
PhysX's (brush) beside the Pacejka fits at the same normal load.

Agreement: ``|PhysX - ours| / |ours|`` per metric (the overshoot, itself a fraction of the
steady value, absolutely: ``|PhysX - ours|``), target 10 %. Every cell is printed and
written (``--json``), including misses; ``--plot FILE`` draws the curves. ``--quick``: the
nominal cell only.
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from roboracer_arena import _core
from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.config.sim import SimConfig, VehicleConfig

from .engines_laps import PairedLap, with_tyre

MUS = [0.4, 0.6, 0.83, 1.0]
MASSES = [0.8, 1.0, 1.5]
TARGET = 0.10
HALL = 150.0
STEP_V, STEP_DELTA, STEP_PRE, STEP_T = 3.0, 0.04, 0.5, 2.5
RAMP_V, RAMP_MAX, RAMP_T = 3.0, 0.3, 8.0
RAMP_SAMPLES = [0.05, 0.10, 0.15, 0.20]
ACCEL_T, ACCEL_TO = 5.0, 5.0
BRAKE_V, BRAKE_STOP, BRAKE_T = 5.0, 0.05, 4.0


def config(mu: float, mass_scale: float, base: VehicleConfig | None = None) -> SimConfig:
    """The car of one cell: ``base`` (default: the paper's) with tyre friction ``mu`` and mass
    and yaw inertia times ``mass_scale``."""
    b = base or VehicleConfig()
    return SimConfig(
        vehicle=VehicleConfig(
            **{
                **b.model_dump(),
                "tyre_friction": mu,
                "mass": b.mass * mass_scale,
                "yaw_inertia": b.yaw_inertia * mass_scale,
            }
        )
    )


def crossing(t: np.ndarray, y: np.ndarray, level: float, below: bool = False) -> float | None:
    """The time ``y`` first reaches ``level`` (from below; ``below``: falls under it), linearly
    interpolated between the samples: a 5 ms physics step is 3 % of a 0.15 s rise time."""
    hit = np.nonzero(y < level if below else y >= level)[0]
    if not len(hit):
        return None
    i = int(hit[0])
    if i == 0:
        return float(t[0])
    y0, y1 = float(y[i - 1]), float(y[i])
    return float(t[i - 1] + (t[i] - t[i - 1]) * (level - y0) / (y1 - y0)) if y1 != y0 else float(t[i])


# ---------------------------------------------------------------------------- engines
class _Ours:
    """One car of our simulator in an empty hall, stepped one physics step at a time."""

    engine = "ours"

    def __init__(self, sim: SimConfig, speed: float = 0.0) -> None:
        h = HALL
        walls = [np.array([[-h, -h], [h, -h], [h, h], [-h, h]], float)]
        centre = np.array([[-5.0, -5.0], [5.0, -5.0], [5.0, 5.0], [-5.0, 5.0]])
        self.sim = _core.Simulator([(walls, centre)], 1, 1, sim, 0)
        self.dt = float(sim.physics.dt)
        mask = np.ones(1, bool)
        self.sim.reset(mask, np.array([[[-h + 20.0, 0.0, 0.0]]]))
        if speed:
            self.sim.set_speeds(mask, np.array([[speed]]))
        f = self.sim.state_fields
        self.i = {k: f.index(k) for k in ("x", "y", "vx", "vy", "yaw_rate", "steer", "speed")}
        self.state = np.zeros((1, 1, len(f)))
        self.events = np.zeros((1, 1), np.uint8)
        self.actions = np.zeros((1, 1, 2))
        self.sim.observe(None, self.state, self.events)

    def step(self, steer: float, speed: float) -> dict[str, float]:
        self.actions[0, 0] = steer, speed
        self.sim.step(self.actions, 1, None, self.state, self.events)
        return {k: float(self.state[0, 0, j]) for k, j in self.i.items()}

    def close(self) -> None:
        pass


class _Physx:
    """The PhysX car on a flat floor (a stage written once per config), one physics step at a time."""

    engine = "physx"

    def __init__(self, stage: Path, sim: SimConfig, speed: float = 0.0) -> None:
        from roboracer_arena.physx.drive import PhysxCar
        from roboracer_arena.physx.runtime import PhysxScene

        self.dt = float(sim.physics.dt)
        self.scene = PhysxScene(stage)
        self.car = PhysxCar(self.scene, sim)
        self.car.settle()
        if speed:
            self.car.set_speed(speed)

    def step(self, steer: float, speed: float) -> dict[str, float]:
        s = self.car.step(steer, speed)
        return {k: float(getattr(s, k)) for k in ("x", "y", "vx", "vy", "yaw_rate", "steer", "speed")}

    def close(self) -> None:
        self.car.close()
        self.scene.close()


# ---------------------------------------------------------------------------- manoeuvres
class StepSteer(BenchModel):
    """Yaw-rate response to a steering step: 10-90 % rise time (s), overshoot (fraction of
    the steady value), steady gain (1/s), and the trace (t from the step, yaw rate)."""

    rise_time: float | None
    overshoot: float
    gain: float
    t: list[float]
    yaw_rate: list[float]


class Cornering(BenchModel):
    """Quasi-steady cornering: lateral acceleration (m/s^2) at the sampled steers, its peak,
    the understeer gradient (rad per m/s^2), and the curve (actual steer, a_y)."""

    ay_at: dict[str, float | None]
    ay_peak: float
    understeer_gradient: float | None
    steer: list[float]
    ay: list[float]


class Accel(BenchModel):
    """From rest at the top speed command: time (s) to 5 m/s, highest speed (m/s), speed trace."""

    t_to_5: float | None
    top_speed: float
    t: list[float]
    speed: list[float]


class Brake(BenchModel):
    """Stop from 5 m/s with a 0 command: distance (m), time (s), speed trace."""

    distance: float
    time: float
    t: list[float]
    speed: list[float]


class EngineRun(BenchModel):
    """All four manoeuvres of one engine in one cell."""

    step: StepSteer
    cornering: Cornering
    accel: Accel
    brake: Brake


def step_steer(car: Any) -> StepSteer:
    n_pre, n = round(STEP_PRE / car.dt), round(STEP_T / car.dt)
    for _ in range(n_pre):
        car.step(0.0, STEP_V)
    ts, rs = [], []
    for k in range(n):
        s = car.step(STEP_DELTA, STEP_V)
        ts.append((k + 1) * car.dt)
        rs.append(s["yaw_rate"])
    r = np.asarray(rs)
    steady = float(r[-round(0.5 / car.dt) :].mean())
    t = np.asarray(ts)
    rise = None
    if steady > 0:
        t10, t90 = crossing(t, r, 0.1 * steady), crossing(t, r, 0.9 * steady)
        if t10 is not None and t90 is not None:
            rise = t90 - t10
    overshoot = float(max(0.0, r.max() / steady - 1.0)) if steady > 0 else 0.0
    every = max(1, round(0.02 / car.dt))
    return StepSteer(
        rise_time=rise,
        overshoot=overshoot,
        gain=steady / STEP_DELTA,
        t=[round(x, 4) for x in ts[::every]],
        yaw_rate=[round(x, 5) for x in rs[::every]],
    )


def cornering(car: Any, sim: SimConfig) -> Cornering:
    n = round(RAMP_T / car.dt)
    deltas, ays = [], []
    for k in range(n):
        s = car.step(RAMP_MAX * (k + 1) / n, RAMP_V)
        deltas.append(s["steer"])
        ays.append(s["yaw_rate"] * abs(s["speed"]))
    d, a = np.asarray(deltas), np.asarray(ays)
    # a_y rises with steer to the friction limit and may fall past it: sample the rising part.
    peak_i = int(np.argmax(a))
    at: dict[str, float | None] = {}
    for x in RAMP_SAMPLES:
        at[f"{x:.2f}"] = float(np.interp(x, d[: peak_i + 1], a[: peak_i + 1])) if x <= d[peak_i] else None
    v = sim.vehicle
    lin = (a > 0.2) & (a < 0.4 * v.tyre_friction * sim.physics.gravity) & (np.arange(len(a)) <= peak_i)
    grad = None
    if lin.sum() > 10:
        speeds = RAMP_V
        y = d[lin] - v.wheelbase * a[lin] / speeds**2  # delta - L r / v with r = a / v
        grad = float(np.polyfit(a[lin], y, 1)[0])
    every = max(1, round(0.1 / car.dt))
    return Cornering(
        ay_at=at,
        ay_peak=float(a.max()),
        understeer_gradient=grad,
        steer=[round(x, 5) for x in deltas[::every]],
        ay=[round(x, 4) for x in ays[::every]],
    )


def accel(car: Any, sim: SimConfig) -> Accel:
    n = round(ACCEL_T / car.dt)
    ts, vs = [0.0], [0.0]
    for k in range(n):
        s = car.step(0.0, sim.vehicle.max_speed)
        ts.append((k + 1) * car.dt)
        vs.append(s["speed"])
    t5 = crossing(np.asarray(ts), np.asarray(vs), ACCEL_TO)
    every = max(1, round(0.05 / car.dt))
    return Accel(
        t_to_5=t5,
        top_speed=float(max(vs)),
        t=[round(x, 3) for x in ts[::every]],
        speed=[round(x, 4) for x in vs[::every]],
    )


def brake(car: Any) -> Brake:
    n = round(BRAKE_T / car.dt)
    x0 = None
    ts, vs, xs = [0.0], [BRAKE_V], [0.0]
    for k in range(n):
        s = car.step(0.0, 0.0)
        if x0 is None:  # the first step's travel counts too
            x0 = s["x"] - BRAKE_V * car.dt
        ts.append((k + 1) * car.dt)
        vs.append(s["speed"])
        xs.append(s["x"] - x0)
        if s["speed"] < BRAKE_STOP:
            break
    t, v = np.asarray(ts), np.asarray(vs)
    t_stop = crossing(t, v, BRAKE_STOP, below=True)
    t_stop = t_stop if t_stop is not None else float(t[-1])
    d_stop = float(np.interp(t_stop, t, np.asarray(xs)))
    every = max(1, round(0.02 / car.dt))
    return Brake(
        distance=float(d_stop),
        time=float(t_stop),
        t=[round(x, 3) for x in ts[::every]],
        speed=[round(x, 4) for x in vs[::every]],
    )


def run_engine(make: Any, sim: SimConfig) -> EngineRun:
    """The four manoeuvres on fresh cars from ``make(speed)``."""
    out = {}
    for name, speed, fn in (
        ("step", STEP_V, step_steer),
        ("cornering", RAMP_V, lambda c: cornering(c, sim)),
        ("accel", 0.0, lambda c: accel(c, sim)),
        ("brake", BRAKE_V, brake),
    ):
        car = make(speed)
        try:
            out[name] = fn(car)
        finally:
            car.close()
    return EngineRun(**out)


# ---------------------------------------------------------------------------- the grid
class Cell(BenchModel):
    """One (mu, mass x) cell: both engines' runs and each metric's relative difference."""

    mu: float
    mass_scale: float
    ours: EngineRun
    physx: EngineRun
    metrics: dict[str, dict[str, float | None]]


class EnginesResult(BenchModel):
    """``python -m benchmarks engines``: every cell; the share of metric comparisons within target.
    ``lateral_tyre``: our engine's lateral tyre law in every run ('brush': PhysX's law, the same
    car; 'linear': the default car, which PhysX's brush tyre can only approximate)."""

    lateral_tyre: str = "linear"
    target: float
    cells: list[Cell]
    anchor: list[AnchorRow]
    laps: list[PairedLap] = []
    within_target: int
    compared: int
    seconds: float


def _rel(p: float | None, o: float | None) -> float | None:
    if p is None or o is None or o == 0:
        return None
    return abs(p - o) / abs(o)


def metrics(o: EngineRun, p: EngineRun) -> dict[str, dict[str, float | None]]:
    """``{metric: {ours, physx, diff}}`` of one cell."""
    pairs: dict[str, tuple[float | None, float | None]] = {
        "step rise time (s)": (o.step.rise_time, p.step.rise_time),
        "step overshoot": (o.step.overshoot, p.step.overshoot),
        "step gain (1/s)": (o.step.gain, p.step.gain),
        "understeer gradient (rad s^2/m)": (o.cornering.understeer_gradient, p.cornering.understeer_gradient),
        "peak a_y (m/s^2)": (o.cornering.ay_peak, p.cornering.ay_peak),
        "0-5 m/s (s)": (o.accel.t_to_5, p.accel.t_to_5),
        "top speed (m/s)": (o.accel.top_speed, p.accel.top_speed),
        "braking distance (m)": (o.brake.distance, p.brake.distance),
        "braking time (s)": (o.brake.time, p.brake.time),
    }
    for k in RAMP_SAMPLES:
        key = f"{k:.2f}"
        pairs[f"a_y at steer {key} (m/s^2)"] = (o.cornering.ay_at[key], p.cornering.ay_at[key])
    out = {k: {"ours": a, "physx": b, "diff": _rel(b, a)} for k, (a, b) in pairs.items()}
    # Overshoot is itself a fraction of the steady value (often near 0): compared absolutely.
    out["step overshoot"]["diff"] = abs(p.step.overshoot - o.step.overshoot)
    return out


def run_cell(mu: float, mass_scale: float, work: Path, base: VehicleConfig | None = None) -> Cell:
    """Both engines' four manoeuvres on the car of one cell."""
    from roboracer_arena.physx.drive import write_flat_stage

    sim = config(mu, mass_scale, base)
    stage = write_flat_stage(work / f"flat-{mu}-{mass_scale}.usda", sim, half_size=HALL)
    ours = run_engine(lambda v: _Ours(sim, v), sim)
    physx = run_engine(lambda v: _Physx(stage, sim, v), sim)
    return Cell(mu=mu, mass_scale=mass_scale, ours=ours, physx=physx, metrics=metrics(ours, physx))


def run(
    mus: list[float],
    masses: list[float],
    base: VehicleConfig | None = None,
    progress: bool = True,
    with_anchor: bool = False,
    lateral_tyre: str = "brush",
) -> EnginesResult:
    """The open-loop grid over ``mus`` x ``masses`` on ``base`` (default: the paper's car) with
    the lateral tyre law ``lateral_tyre`` in our engine (PhysX's is always the brush)."""
    from roboracer_arena.physx import available

    if not available():
        from roboracer_arena.errors import ConfigError

        raise ConfigError("python -m benchmarks engines needs the 'physx' extra (ovphysx, physx-usd-schemas)")
    warnings.simplefilter("ignore")
    t0 = time.perf_counter()
    cells = []
    with tempfile.TemporaryDirectory() as tmp:
        for mu in mus:
            for m in masses:
                cells.append(run_cell(mu, m, Path(tmp), with_tyre(base or VehicleConfig(), lateral_tyre)))
                if progress:
                    print(f"  cell mu {mu:g}, mass x{m:g}: {time.perf_counter() - t0:.0f} s", flush=True)
        rows = anchor(Path(tmp), lateral_tyre=lateral_tyre) if with_anchor else []
    diffs = [v["diff"] for c in cells for v in c.metrics.values() if v["diff"] is not None]
    return EnginesResult(
        lateral_tyre=lateral_tyre,
        target=TARGET,
        cells=cells,
        anchor=rows,
        within_target=sum(d <= TARGET for d in diffs),
        compared=len(diffs),
        seconds=time.perf_counter() - t0,
    )


# ---------------------------------------------------------------------------- real-car anchor
ANCHOR_V, ANCHOR_STEER, ANCHOR_T = 5.0, 0.05, 5.0


class AnchorRow(BenchModel):
    """Steady yaw rate (rad/s) at 5 m/s and 0.05 rad: the real car's identified single-track
    model (None for the paper's car), ours and PhysX on the preset, and the kinematic value."""

    car: str
    real_model: float | None
    ours: float
    physx: float
    kinematic: float


def _steady_yaw(car: Any) -> float:
    n = round(ANCHOR_T / car.dt)
    rs = [car.step(ANCHOR_STEER, ANCHOR_V)["yaw_rate"] for _ in range(n)]
    return float(np.mean(rs[-round(1.0 / car.dt) :]))


def anchor(work: Path, cars: list[str] | None = None, lateral_tyre: str = "brush") -> list[AnchorRow]:
    """The anchor rows: the paper's car and ForzaETH's NUC2, NUC6, NUC7 (presets), with the
    lateral tyre law ``lateral_tyre``."""
    from roboracer_arena.config.vehicle_presets import FORZAETH_MODELS, forzaeth_preset, single_track_yaw_rate
    from roboracer_arena.physx.drive import write_flat_stage

    rows = []
    for name in ["paper (Traxxas)", *(cars or ["NUC2", "NUC6", "NUC7"])]:
        vc = with_tyre(VehicleConfig() if name.startswith("paper") else forzaeth_preset(name), lateral_tyre)
        sim = SimConfig(vehicle=vc)
        stage = write_flat_stage(work / f"anchor-{len(rows)}.usda", sim, half_size=HALL)
        res = {}
        for eng in ("ours", "physx"):
            car = _Ours(sim, ANCHOR_V) if eng == "ours" else _Physx(stage, sim, ANCHOR_V)
            try:
                res[eng] = _steady_yaw(car)
            finally:
                car.close()
        real = (
            None if name.startswith("paper") else single_track_yaw_rate(FORZAETH_MODELS[name], ANCHOR_V, ANCHOR_STEER)
        )
        rows.append(
            AnchorRow(car=name, real_model=real, **res, kinematic=ANCHOR_V * math.tan(ANCHOR_STEER) / vc.wheelbase)
        )
    return rows


def forzaeth_models(data_dir: Path | None = None) -> dict[str, dict[str, Any]]:
    """ForzaETH's models from ``data_dir`` (``<NAME>_pacejka.txt``) when it exists, else the presets' copy."""
    from roboracer_arena.config.vehicle_presets import FORZAETH_MODELS, read_forzaeth_model

    if data_dir and data_dir.is_dir():
        return {p.name.split("_")[0]: read_forzaeth_model(p) for p in sorted(data_dir.glob("*_pacejka.txt"))}
    return FORZAETH_MODELS


def plot_tyres(path: Path, data_dir: Path | None = None) -> None:
    """Lateral force per wheel against slip angle at NUC6's static front and rear wheel loads:
    ForzaETH's Pacejka fits, our tyre (linear to mu N) and PhysX's (brush) for the paper's car
    and for the NUC6 preset."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from roboracer_arena.config.vehicle_presets import forzaeth_preset, pacejka, static_axle_loads

    models = forzaeth_models(data_dir)
    ref = models["NUC6"]
    loads = [x / 2.0 for x in static_axle_loads(ref)]
    alpha = np.linspace(0.0, 0.35, 300)

    def ours(c: float, mu: float, n: float) -> np.ndarray:
        return np.minimum(c * n * alpha, mu * n)

    def brush(c: float, mu: float, n: float) -> np.ndarray:
        k = c * n * np.tan(alpha) / (mu * n)
        return mu * n * np.minimum(1.0, k - k * k / 3 + k**3 / 27)

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    paper, nuc6 = VehicleConfig(), forzaeth_preset("NUC6")
    for ax, axle, n in zip(axes, ("front", "rear"), loads):
        for i, (name, mod) in enumerate(models.items()):
            ax.plot(
                alpha,
                n * pacejka(alpha, mod["C_Pf" if axle == "front" else "C_Pr"]),
                color=f"C{i}",
                label=f"ForzaETH {name} (Pacejka fit)",
            )
        for vc, lab, col in ((paper, "paper's car", "k"), (nuc6, "NUC6 preset", "C2")):
            c = vc.cornering_stiffness_front if axle == "front" else vc.cornering_stiffness_rear
            ax.plot(alpha, ours(c, vc.tyre_friction, n), "-", color=col, lw=2.2, alpha=0.6, label=f"ours, {lab}")
            ax.plot(alpha, brush(c, vc.tyre_friction, n), ":", color=col, lw=2.2, label=f"PhysX, {lab}")
        ax.set(title=f"{axle} tyre at NUC6's static {axle} wheel load {n:.2f} N", xlabel="slip angle (rad)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("lateral force per wheel (N)")
    axes[1].legend(fontsize=7, loc="lower right")
    fig.suptitle("Lateral tyre force: real-car fits (ForzaETH On-Track-SysID, MIT) beside our tyre and PhysX's")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


def _f(x: float | None, fmt: str = ".3f") -> str:
    return "–" if x is None else format(x, fmt)


def print_table(res: EnginesResult) -> None:
    print("| mu | mass x | metric | ours | PhysX | difference |")
    print("|---:|---:|---|---:|---:|---:|")
    for c in res.cells:
        for name, v in c.metrics.items():
            d = v["diff"]
            flag = "" if d is None or d <= res.target else " **miss**"
            print(
                f"| {c.mu:g} | {c.mass_scale:g} | {name} | {_f(v['ours'])} | {_f(v['physx'])} | "
                f"{_f(None if d is None else 100 * d, '.1f')} %{flag} |"
            )
    if res.anchor:
        print(f"\nReal-car anchor: steady yaw rate (rad/s) at {ANCHOR_V:g} m/s, {ANCHOR_STEER} rad")
        print("| car | real car's model | ours | PhysX | kinematic |")
        print("|---|---:|---:|---:|---:|")
        for a in res.anchor:
            print(f"| {a.car} | {_f(a.real_model)} | {a.ours:.3f} | {a.physx:.3f} | {a.kinematic:.3f} |")
    if res.laps:
        from .engines_laps import print_laps

        print("\nClosed loop: pure pursuit at the env's control rate, same stage, both engines")
        print_laps(res.laps)
    print(f"\nwithin {100 * res.target:.0f} %: {res.within_target} of {res.compared} comparisons ({res.seconds:.0f} s)")


def plot(res: EnginesResult, path: Path) -> None:
    """Curves of the nominal-mass cells (ours solid, PhysX dashed), one colour per mu."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    cells = [c for c in res.cells if c.mass_scale == 1.0] or res.cells
    for i, c in enumerate(cells):
        col = f"C{i}"
        for run, ls, who in ((c.ours, "-", "ours"), (c.physx, "--", "PhysX")):
            lab = f"{who}, mu {c.mu:g}"
            ax[0, 0].plot(run.step.t, run.step.yaw_rate, ls, color=col, label=lab)
            ax[0, 1].plot(run.cornering.steer, run.cornering.ay, ls, color=col, label=lab)
            ax[1, 0].plot(run.accel.t, run.accel.speed, ls, color=col, label=lab)
            ax[1, 1].plot(run.brake.t, run.brake.speed, ls, color=col, label=lab)
    ax[0, 0].set(
        title=f"step steer {STEP_DELTA} rad at {STEP_V:g} m/s", xlabel="time from step (s)", ylabel="yaw rate (rad/s)"
    )
    ax[0, 1].set(title=f"quasi-steady cornering at {RAMP_V:g} m/s", xlabel="steer (rad)", ylabel="a_y (m/s^2)")
    ax[1, 0].set(title="acceleration from rest (7 m/s command)", xlabel="time (s)", ylabel="speed (m/s)")
    ax[1, 1].set(title=f"braking from {BRAKE_V:g} m/s (0 command)", xlabel="time (s)", ylabel="speed (m/s)")
    for a in ax.flat:
        a.grid(alpha=0.3)
    ax[0, 1].legend(fontsize=7)
    fig.suptitle(f"One car, two engines (mass x1, our lateral tyre: {res.lateral_tyre}): ours solid, PhysX dashed")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")


def _cli(args: argparse.Namespace) -> int:
    if args.mass_study:
        from roboracer_arena.foundation.paths import default_sources_dir

        from .engines_laps import MassStudy, mass_study, print_mass

        study = MassStudy(rows=mass_study(args.sources or default_sources_dir()))
        print_mass(study.rows)
        write_json(args.json, study)
        return 0
    mus, masses = ([0.83], [1.0]) if args.quick else (args.mu or MUS, args.mass or MASSES)
    res = run(mus, masses, with_anchor=args.anchor, lateral_tyre=args.tyre)
    if args.laps:
        from roboracer_arena.foundation.paths import default_sources_dir

        from .engines_laps import run_laps

        laps = run_laps(args.sources or default_sources_dir(), quick=args.quick, lateral_tyre=args.tyre)
        res = res.model_copy(update={"laps": laps})
    print_table(res)
    write_json(args.json, res)
    if args.plot:
        plot(res, args.plot)
    if args.tyre_plot:
        plot_tyres(args.tyre_plot, args.vehicle_data)
    return 0


def _default_vehicle_data() -> Path:
    from roboracer_arena.foundation.paths import default_sources_dir

    return default_sources_dir().parent / "vehicle-data" / "forzaeth-on-track-sysid"


def register(kinds: Any) -> None:
    p = add_bench_parser(kinds, "engines", "the same car open loop in our engine and PhysX", __doc__)
    p.add_argument("--quick", action="store_true", help="the nominal cell only (mu 0.83, mass x1)")
    p.add_argument(
        "--tyre",
        choices=("brush", "linear"),
        default="brush",
        help="our engine's lateral tyre law (VehicleConfig.lateral_tyre): 'brush' (default) is PhysX's law, the same "
        "car in both engines; 'linear' is the default car, which PhysX's brush tyre approximates",
    )
    p.add_argument("--mu", type=float, nargs="+", help=f"tyre friction values (default {MUS})")
    p.add_argument("--mass", type=float, nargs="+", help=f"mass scales (default {MASSES})")
    p.add_argument("--plot", metavar="FILE", type=Path, help="draw the curves to FILE (png)")
    p.add_argument("--anchor", action="store_true", help="the real-car anchor rows (ForzaETH presets)")
    p.add_argument(
        "--laps", action="store_true", help="closed loop: pure pursuit laps on three stages in both engines (minutes)"
    )
    p.add_argument(
        "--mass-study",
        action="store_true",
        help="only: why a heavier car laps Berlin faster in our engine (speed vs the driver's plan)",
    )
    p.add_argument(
        "--sources", metavar="DIR", type=Path, help="track sources for --laps (default: ../shared/track-sources)"
    )
    p.add_argument("--tyre-plot", metavar="FILE", type=Path, help="draw the tyre curves beside the real-car fits")
    p.add_argument(
        "--vehicle-data",
        metavar="DIR",
        type=Path,
        default=_default_vehicle_data(),
        help="ForzaETH On-Track-SysID model files (default: ../shared/vehicle-data/forzaeth-on-track-sysid)",
    )
    p.set_defaults(func=_cli)


def run_quick() -> EnginesResult:
    """`bench all`: the nominal cell."""
    res = run([0.83], [1.0])
    print_table(res)
    return res
