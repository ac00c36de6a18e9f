"""Closed loop for ``python -m benchmarks engines --laps``: the same driver at the same
control rate (the env's, 20 Hz) on the same stage in both engines (issue 36).

Stages: a recorded map (f1tenth-gym Berlin), a circuit (Monaco at 1:10) and a generated
track (40 m, seed 3), each built with ``build --car``, driven by the reference pure pursuit
and by the racing driver on the raceline it plans (``raceline.driver``, from a standing
start on the line); on Berlin also the conditions of the issue's table (mu 0.4, mass x1.5, mass x2) and the NUC6 preset (ForzaETH's real car); and
one trained policy file (:data:`POLICY_FILE`, the default recipe's seed 0) on a recorded map it
never trained on (:data:`POLICY_MAP`), each engine casting its own lidar. Each
run is a :class:`roboracer_arena.physx.drive.Trace`; the pair is compared on arc length
along the centreline from one origin (5 cm bins; ``start_gap_m``: how far apart along the
centreline the two engines' cars started): lap time, lateral error, and the RMS difference of
speed, yaw rate and steering between the engines at the same place on the track.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from roboracer_arena.bench.output import BenchModel
from roboracer_arena.config.sim import SimConfig, VehicleConfig

LAP_TARGET = 0.05
#: The policy file driven in both engines, and the held-out recorded map (catalog id) it drives.
POLICY_FILE = Path(__file__).resolve().parents[1] / "docs" / "learning" / "policies" / "pool_rand-seed0.npz"
POLICY_MAP = "gym-skirk"


class PairedLap(BenchModel):
    """One stage and condition: both engines' lap time (s; None = no lap), mean and max
    lateral error (m), and the RMS differences at the same arc length."""

    track: str
    condition: str
    length_m: float
    ours_lap_s: float | None
    physx_lap_s: float | None
    lap_diff: float | None
    ours_lateral_mean_m: float
    ours_lateral_max_m: float
    physx_lateral_mean_m: float
    physx_lateral_max_m: float
    rms_speed_m_s: float
    rms_yaw_rate: float
    rms_steer_rad: float
    rms_lateral_offset_m: float
    start_gap_m: float
    traces: dict[str, dict[str, list[float]]]


def _arc(track: Any, run: Any) -> np.ndarray:
    """Arc length (m) of each sample of ``run`` along the track's centreline from the
    centreline's first point, unwrapped from the run's first sample on (the two engines'
    runs then share one origin even when they start at different places)."""
    from roboracer_arena.drivers import PurePursuitDriver

    ref = PurePursuitDriver(track.centreline)
    n = len(ref.points)
    out, last = [], None
    s = 0.0
    for x, y in zip(run.x, run.y):
        i = ref.project(x, y)
        s = i * ref.ds if last is None else s + ((i - last + n // 2) % n - n // 2) * ref.ds
        last = i
        out.append(s)
    return np.asarray(out)


def _signed_offset(track: Any, run: Any) -> np.ndarray:
    """Signed lateral offset (m, left positive) of each sample from the centreline."""
    from roboracer_arena.drivers import PurePursuitDriver

    ref = PurePursuitDriver(track.centreline)
    pts = ref.points
    out = []
    for x, y in zip(run.x, run.y):
        i = ref.project(x, y)
        a, b = pts[i], pts[(i + 1) % len(pts)]
        t = b - a
        out.append(float(np.cross(t / (np.linalg.norm(t) + 1e-12), np.array([x, y]) - a)))
    return np.asarray(out)


def compare(track: Any, name: str, condition: str, ours: Any, physx: Any) -> PairedLap:
    """The paired comparison of two runs on ``track``."""
    so, sp = _arc(track, ours), _arc(track, physx)
    length = float(track.length)
    if sp[0] - so[0] > length / 2:
        sp = sp - length
    elif so[0] - sp[0] > length / 2:
        sp = sp + length
    start_gap = float(abs(sp[0] - so[0]))
    grid = np.arange(max(so[0], sp[0]) + 0.5, min(so[-1], sp[-1]), 0.05)
    cols = {
        "speed": (ours.speed, physx.speed),
        "yaw_rate": (ours.yaw_rate, physx.yaw_rate),
        "steer": (ours.steer, physx.steer),
        "offset": (_signed_offset(track, ours), _signed_offset(track, physx)),
    }
    rms = {}
    for k, (a, b) in cols.items():
        ia = np.interp(grid, so, np.asarray(a))
        ib = np.interp(grid, sp, np.asarray(b))
        rms[k] = float(np.sqrt(np.mean((ia - ib) ** 2))) if len(grid) else float("nan")
    lo, lp = ours.lap_time_s, physx.lap_time_s
    every = 4
    traces = {
        run.engine: {
            "s": [round(float(x), 3) for x in arc[::every]],
            "t": [round(x, 3) for x in run.t[::every]],
            "speed": [round(x, 4) for x in run.speed[::every]],
            "yaw_rate": [round(x, 4) for x in run.yaw_rate[::every]],
            "steer": [round(x, 4) for x in run.steer[::every]],
            "lateral_error": [round(x, 4) for x in run.lateral_error[::every]],
        }
        for run, arc in ((ours, so), (physx, sp))
    }
    return PairedLap(
        track=name,
        condition=condition,
        length_m=float(track.length),
        ours_lap_s=lo,
        physx_lap_s=lp,
        lap_diff=abs(lp - lo) / lo if lo and lp else None,
        ours_lateral_mean_m=float(np.mean(ours.lateral_error)),
        ours_lateral_max_m=float(np.max(ours.lateral_error)),
        physx_lateral_mean_m=float(np.mean(physx.lateral_error)),
        physx_lateral_max_m=float(np.max(physx.lateral_error)),
        rms_speed_m_s=rms["speed"],
        rms_yaw_rate=rms["yaw_rate"],
        rms_steer_rad=rms["steer"],
        rms_lateral_offset_m=rms["offset"],
        start_gap_m=start_gap,
        traces=traces,
    )


def _stages(sources: Path, work: Path) -> dict[str, Path]:
    from roboracer_arena import TrackSpec, generate_track
    from roboracer_arena.cli import main
    from roboracer_arena.generate import write_outputs

    if main(["circuits", "--sources", str(sources), "-o", str(work), "--only", "monaco", "--jobs", "1"]) != 0:
        raise RuntimeError("could not build the Monaco circuit")
    gen = write_outputs(generate_track(TrackSpec(lap_length_m=40.0), seed=3), work / "generated")
    return {
        "berlin (recorded)": sources / "f1tenth-gym" / "maps" / "berlin.yaml",
        "monaco (circuit, 1:10)": work / "monaco" / "map.yaml",
        "generated (40 m, seed 3)": gen["map_yaml"],
    }


def with_tyre(vehicle: VehicleConfig, lateral_tyre: str) -> VehicleConfig:
    """``vehicle`` with the lateral tyre law ``lateral_tyre`` ('brush' or 'linear')."""
    return VehicleConfig(**{**vehicle.model_dump(), "lateral_tyre": lateral_tyre})


def _sim_with_tyre(sim: SimConfig, lateral_tyre: str) -> SimConfig:
    return SimConfig(**{**sim.model_dump(), "vehicle": with_tyre(sim.vehicle, lateral_tyre).model_dump()})


def conditions(lateral_tyre: str = "brush") -> dict[str, SimConfig]:
    """The Berlin conditions: the paper's car, mu 0.4, mass x1.5, mass x2 (yaw inertia
    unchanged, as the issue's runs), and ForzaETH's NUC6; all with ``lateral_tyre``."""
    from roboracer_arena.config.vehicle_presets import forzaeth_preset

    base = VehicleConfig(lateral_tyre=lateral_tyre)  # type: ignore[arg-type]

    def veh(**kw: float) -> SimConfig:
        return SimConfig(vehicle=VehicleConfig(**{**base.model_dump(), **kw}))

    return {
        "paper's car": SimConfig(vehicle=base),
        "mu 0.4": veh(tyre_friction=0.4),
        "mass x1.5": veh(mass=1.5 * base.mass),
        "mass x2": veh(mass=2.0 * base.mass),
        "NUC6 preset": _sim_with_tyre(SimConfig(vehicle=forzaeth_preset("NUC6")), lateral_tyre),
    }


def policy_lap(work: Path, lateral_tyre: str, max_seconds: float) -> PairedLap:
    """:data:`POLICY_FILE` on :data:`POLICY_MAP` in both engines: the policy's own env config
    (control rate, car), ``lateral_tyre``, each engine's lidar (PhysX: its raycasts)."""
    from roboracer_arena.builder import build_environment
    from roboracer_arena.envs.env_config import EnvConfig
    from roboracer_arena.learn import load_policy, policy_env_kwargs
    from roboracer_arena.learn.runner import policy_controller
    from roboracer_arena.physx.drive import drive_native, drive_physx
    from roboracer_arena.physx.laps import map_and_track
    from roboracer_arena.usd.vehicle import replace_car

    policy = load_policy(POLICY_FILE)
    config = EnvConfig.build(policy_env_kwargs(policy))
    sim, rate = _sim_with_tyre(config.sim, lateral_tyre), config.control_rate_hz
    map_yaml, track = map_and_track(POLICY_MAP)
    stage = work / "policy.usdc"
    build_environment(map_yaml, stage, car=True)
    replace_car(stage, sim)
    lid = sim.lidar

    def make() -> Any:
        return policy_controller(policy, track, lid.num_beams, lid.fov, config)

    ours = drive_native(track, make(), sim, control_rate_hz=rate, max_seconds=max_seconds)
    physx = drive_physx(
        stage,
        make(),
        sim,
        track=track,
        control_rate_hz=rate,
        max_seconds=max_seconds,
        lidar="physx",
        start=tuple(ours.start),
    )
    return compare(track, f"{POLICY_MAP} (recorded, held out)", f"policy {POLICY_FILE.name}", ours, physx)


def _racing_driver(track: Any, sim: SimConfig) -> tuple[Any, tuple[float, float, float]]:
    """The racing driver on ``track`` (the raceline it plans, its speed plan capping the
    speed) as a controller factory, and its start: standing on the line's first point. It
    plans with the limits of the car it drives, measured in our engine
    (:func:`~roboracer_arena.raceline.measure.measure_limits`; for the default car those are
    the ``car`` preset), as a team plans with its own car's limits."""
    from roboracer_arena.drivers import PurePursuitDriver
    from roboracer_arena.raceline.driver import plan_for_driver, racing_params, speed_cap
    from roboracer_arena.raceline.measure import measure_limits

    line = plan_for_driver(track, measure_limits({"sim": sim.model_dump()}))
    params, cap = racing_params(line), speed_cap(line)

    def make() -> Any:
        driver = PurePursuitDriver(line.xy, params, speed_cap=cap)

        def act(_scan: np.ndarray, odo: dict[str, float]) -> tuple[float, float]:
            steer, speed = driver.act_pose(odo["x"], odo["y"], odo["yaw"], odo["vx"])
            return float(steer), float(speed)

        return act

    return make, (float(line.xy[0, 0]), float(line.xy[0, 1]), float(line.psi[0]))


def run_laps(
    sources: Path,
    max_seconds: float = 150.0,
    quick: bool = False,
    progress: bool = True,
    racing: bool = True,
    lateral_tyre: str = "brush",
) -> list[PairedLap]:
    """Every stage with the paper's car under the pure pursuit and the racing driver (on its
    own raceline), Berlin under every condition, and the policy file on its held-out map
    (``quick``: Berlin only); our engine's lateral tyre law ``lateral_tyre``."""
    from roboracer_arena.builder import build_environment
    from roboracer_arena.physx.check import track_of_stage
    from roboracer_arena.physx.drive import drive_native, drive_physx, pure_pursuit
    from roboracer_arena.usd.vehicle import replace_car

    out = []
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        stages = _stages(sources, work)
        if quick:
            stages = dict(list(stages.items())[:1])
        for k, (name, map_yaml) in enumerate(stages.items()):
            paper = conditions(lateral_tyre)["paper's car"]
            conds = conditions(lateral_tyre) if name.startswith("berlin") else {"paper's car": paper}
            runs = [(c, sim, "pure pursuit") for c, sim in conds.items()]
            if racing:
                runs.append(("paper's car, racing driver", paper, "racing"))
            for cname, sim, driver in runs:
                stage = work / f"{k}-{len(out)}.usdc"
                build_environment(map_yaml, stage, car=True)
                replace_car(stage, sim)
                track = track_of_stage(stage)
                if driver == "racing":
                    make, start = _racing_driver(track, sim)
                    ours = drive_native(track, make(), sim, max_seconds=max_seconds, start=start)
                else:
                    make = lambda track=track: pure_pursuit(track)
                    ours = drive_native(track, make(), sim, max_seconds=max_seconds)
                physx = drive_physx(
                    stage,
                    make(),
                    sim,
                    track=track,
                    max_seconds=max_seconds,
                    scan=False,
                    start=tuple(ours.start),  # the env's start (the stage's car may sit elsewhere)
                )
                out.append(compare(track, name, cname, ours, physx))
                _report(out[-1], t0, progress)
        if not quick:
            out.append(policy_lap(work, lateral_tyre, max_seconds))
            _report(out[-1], t0, progress)
    return out


def _report(r: PairedLap, t0: float, progress: bool) -> None:
    if progress:
        print(
            f"  {r.track}, {r.condition}: ours {r.ours_lap_s} s, PhysX {r.physx_lap_s} s "
            f"({time.perf_counter() - t0:.0f} s)",
            flush=True,
        )


def _f(x: float | None, fmt: str = ".2f") -> str:
    return "no lap" if x is None else format(x, fmt)


def print_laps(rows: list[PairedLap]) -> None:
    print(
        "| track | car | lap ours (s) | lap PhysX (s) | difference | lateral error mean / max, ours (m) | PhysX (m) | RMS speed (m/s) | RMS yaw rate (rad/s) | RMS steer (rad) | RMS offset (m) | start gap (m) |"
    )
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        d = (
            "–"
            if r.lap_diff is None
            else f"{100 * r.lap_diff:.1f} %" + ("" if r.lap_diff <= LAP_TARGET else " **miss**")
        )
        print(
            f"| {r.track} | {r.condition} | {_f(r.ours_lap_s)} | {_f(r.physx_lap_s)} | {d} | "
            f"{r.ours_lateral_mean_m:.3f} / {r.ours_lateral_max_m:.3f} | {r.physx_lateral_mean_m:.3f} / {r.physx_lateral_max_m:.3f} | "
            f"{r.rms_speed_m_s:.3f} | {r.rms_yaw_rate:.3f} | {r.rms_steer_rad:.4f} | {r.rms_lateral_offset_m:.3f} | "
            f"{r.start_gap_m:.2f} |"
        )


class MassRow(BenchModel):
    """One car on Berlin in our engine: lap time (s), mean speed and command (m/s), the share
    of control steps above the command by more than 0.05 m/s and the mean excess there."""

    car: str
    lap_s: float | None
    mean_speed: float
    mean_command: float
    above_command: float
    mean_excess: float
    max_lateral_error_m: float


def mass_study(sources: Path, max_seconds: float = 60.0) -> list[MassRow]:
    """Why a heavier car laps Berlin faster in our engine: the pure pursuit's speed plan with
    the paper's car, mass x1.5 and x2 (yaw inertia kept, as the issue's runs, and scaled),
    and the paper's car with half the braking or half the driving current."""
    from roboracer_arena.envs.track_argument import resolve_tracks
    from roboracer_arena.physx.drive import drive_native, pure_pursuit

    track = resolve_tracks(str(sources / "f1tenth-gym" / "maps" / "berlin.yaml"))[0]
    base = VehicleConfig()
    cars = {
        "paper's car": {},
        "mass x1.5": {"mass": 1.5 * base.mass},
        "mass x2": {"mass": 2 * base.mass},
        "mass x2, yaw inertia x2": {"mass": 2 * base.mass, "yaw_inertia": 2 * base.yaw_inertia},
        "max_brake_current x0.5": {"max_brake_current": 0.5 * base.max_brake_current},
        "max_motor_current x0.5": {"max_motor_current": 0.5 * base.max_motor_current},
    }
    rows = []
    for name, upd in cars.items():
        sim = SimConfig(vehicle=VehicleConfig(**{**base.model_dump(), **upd}))
        r = drive_native(track, pure_pursuit(track), sim, max_seconds=max_seconds)
        v, c = np.asarray(r.speed), np.asarray(r.speed_cmd)
        over = v - c
        rows.append(
            MassRow(
                car=name,
                lap_s=r.lap_time_s,
                mean_speed=float(v.mean()),
                mean_command=float(c.mean()),
                above_command=float(np.mean(over > 0.05)),
                mean_excess=float(over[over > 0].mean()) if (over > 0).any() else 0.0,
                max_lateral_error_m=float(max(r.lateral_error)),
            )
        )
    return rows


class MassStudy(BenchModel):
    """``python -m benchmarks engines --mass-study``."""

    rows: list[MassRow]


def print_mass(rows: list[MassRow]) -> None:
    print(
        "| car (ours, Berlin, pure pursuit) | lap (s) | mean speed (m/s) | mean command (m/s) | time above command | mean excess (m/s) | max lateral error (m) |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(
            f"| {r.car} | {_f(r.lap_s)} | {r.mean_speed:.3f} | {r.mean_command:.3f} | {100 * r.above_command:.0f} % | "
            f"{r.mean_excess:.3f} | {r.max_lateral_error_m:.3f} |"
        )
