"""``roboracer-arena bench physics``: vehicle-steps per second of the native simulator
with the lidar off, for 1, 256, 1024 and 2048 vehicles, against the project's targets,
plus the time of one 1081-beam lidar scan. (``python -m benchmarks physics``, in a
checkout, prints the paper's Isaac Sim figures beside them.)

A *vehicle-step* is one physics step (``dt``) of one vehicle. N vehicles run as
``N / per_env`` independent rapier worlds of ``per_env`` cars each (``--per-env``).
Cars follow the centreline of a stadium track with a vectorised pure-pursuit law
(computed in numpy between calls, outside the timed region), ``--substeps`` physics
steps per ``Simulator.step`` call (10 = a 20 Hz control loop at dt = 5 ms).
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from .. import _core
from ..config.sim import PhysicsConfig, SimConfig
from ..drivers import PurePursuitDriver, PurePursuitParams
from .output import BenchModel, add_bench_parser, write_json

TARGETS = {1: 50_000.0, 256: 200_000.0, 2048: 200_000.0}


class PhysicsRow(BenchModel):
    """Throughput of one vehicle count: its worlds, time step, timed calls, vehicle-steps
    per second, and the share of steps with a wall contact or through the rapier pipeline."""

    vehicles: int
    envs: int
    per_env: int
    dt: float
    substeps: int
    calls: int
    vehicle_steps_per_s: float
    sim_seconds_per_wall_second: float
    wall_contact_fraction: float
    rapier_pipeline_fraction: float
    mean_speed: float


class ScanTiming(BenchModel):
    """Median time of one full lidar scan (µs) over ``repeats`` scans."""

    beams: int
    scan_us_median: float
    repeats: int


class PhysicsResult(BenchModel):
    """``bench physics``: the machine, thread count, one row per vehicle count and the scan."""

    machine: str
    threads: str
    rows: list[PhysicsRow]
    scan: ScanTiming


def _track(scale: float = 3.0):
    """A 3x stadium: 18 m straights, 9 m centreline radius, 2 m corridor (~93 m lap)."""
    return _core.stadium_track(6.0 * scale, 3.0 * scale, 2.0)


class _Driver:
    """The reference pure pursuit, vectorised over thousands of cars per call: each car's
    place on the centreline is the simulator's own ``progress_s``, so there is no per-car
    projection, and the speed command is the bench's constant ``speed``."""

    def __init__(self, sim: _core.Simulator, speed: float):
        vehicle = SimConfig().vehicle
        params = PurePursuitParams(
            wheelbase=vehicle.wheelbase, max_steer=vehicle.max_steer, max_speed=speed, min_speed=speed
        )
        self.driver = PurePursuitDriver(sim.centreline(0), params)
        fields = sim.state_fields
        self.cols = [fields.index(k) for k in ("x", "y", "yaw", "vx", "progress_s")]

    def actions(self, state: np.ndarray, out: np.ndarray) -> None:
        x, y, yaw, vx, s = (state[..., c] for c in self.cols)
        out[..., 0], out[..., 1] = self.driver.act_along(x, y, yaw, vx, s)


def measure(
    vehicles: int, per_env: int, seconds: float, substeps: int, dt: float, speed: float = 3.0, shortcut: bool = True
) -> PhysicsRow:
    """Vehicle-steps/s for `vehicles` cars as `vehicles / per_env` worlds."""
    per_env = max(1, min(per_env, vehicles))
    envs = max(1, vehicles // per_env)
    config = SimConfig(physics=PhysicsConfig(dt=dt, shortcut_free_steps=shortcut))
    sim = _core.Simulator([_track()], envs, per_env, config, 0)
    length = sim.centreline_length(0)
    poses = np.zeros((envs, per_env, 3))
    for v in range(per_env):
        poses[:, v] = sim.centreline_pose(0, (v * length / per_env) % length)
    sim.reset(np.ones(envs, bool), poses)
    state = np.zeros((envs, per_env, len(sim.state_fields)))
    events = np.zeros((envs, per_env), np.uint8)
    actions = np.zeros((envs, per_env, 2))
    driver = _Driver(sim, speed)
    sim.observe(None, state, events)
    # Warm-up (allocations, thread pool), then time only the simulator calls.
    for _ in range(3):
        driver.actions(state, actions)
        sim.step(actions, substeps, None, state, events)
    calls, busy, wall_contacts = 0, 0.0, 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds or calls < 3:
        driver.actions(state, actions)
        t0 = time.perf_counter()
        sim.step(actions, substeps, None, state, events)
        busy += time.perf_counter() - t0
        calls += 1
        wall_contacts += int(np.count_nonzero(events & _core.EVENT_WALL))
    steps = calls * substeps * envs * per_env
    pipeline, shortcut_steps = sim.step_counts()
    return PhysicsRow(
        vehicles=envs * per_env,
        envs=envs,
        per_env=per_env,
        dt=dt,
        substeps=substeps,
        calls=calls,
        vehicle_steps_per_s=steps / busy,
        sim_seconds_per_wall_second=calls * substeps * dt / busy,
        wall_contact_fraction=wall_contacts / max(1, calls * envs * per_env),
        rapier_pipeline_fraction=pipeline / max(1, pipeline + shortcut_steps),
        mean_speed=float(np.mean(np.abs(state[..., sim.state_fields.index("vx")]))),
    )


def measure_scan(seconds: float = 1.0, beams: int = 1081) -> ScanTiming:
    """Median time of one full scan by one vehicle on the stadium track."""
    sim = _core.Simulator([_track()], 1, 1, SimConfig(), 0)
    sim.reset(np.ones(1, bool), np.array([[sim.centreline_pose(0, 5.0)]]))
    scans = np.zeros((1, 1, sim.num_beams), np.float32)
    state = np.zeros((1, 1, len(sim.state_fields)))
    events = np.zeros((1, 1), np.uint8)
    times: list[float] = []
    start = time.perf_counter()
    while time.perf_counter() - start < seconds or len(times) < 20:
        t0 = time.perf_counter()
        sim.observe(scans, state, events)
        times.append(time.perf_counter() - t0)
    return ScanTiming(beams=beams, scan_us_median=float(np.median(times) * 1e6), repeats=len(times))


def _threads() -> str:
    return os.environ.get("RAYON_NUM_THREADS") or f"{os.cpu_count()} (all cores)"


def run(
    vehicles: list[int], per_env: int, seconds: float, substeps: int, dt: float, shortcut: bool = True
) -> PhysicsResult:
    rows = [measure(n, per_env, seconds, substeps, dt, shortcut=shortcut) for n in vehicles]
    scan = measure_scan(min(1.0, seconds))
    return PhysicsResult(machine=platform.processor() or platform.machine(), threads=_threads(), rows=rows, scan=scan)


def print_table(result: PhysicsResult, paper: dict[int, float] | None = None) -> None:
    """The table; ``paper``: published vehicle-steps/s by vehicle count, printed beside
    ours with the ratio (columns left out without it)."""
    print(f"physics throughput, lidar off (threads: {result.threads})")
    head = f"{'vehicles':>8} {'envs x per_env':>15} {'dt (s)':>7} {'substeps':>8} {'rapier steps':>12} {'ours (veh-steps/s)':>19}"
    head += f" {'paper':>8} {'ratio':>8}" * (paper is not None) + f" {'target':>9}"
    print(head)
    print("-" * len(head))
    for r in result.rows:
        n = r.vehicles
        target = TARGETS.get(n)
        ours = r.vehicle_steps_per_s
        versus = ""
        if paper is not None:
            ref = paper.get(n)
            versus = f" {ref if ref is not None else '-':>8} {(f'{ours / ref:,.0f}x' if ref else '-'):>8}"
        print(
            f"{n:>8} {str(r.envs) + ' x ' + str(r.per_env):>15} {r.dt:>7.3f} {r.substeps:>8} "
            f"{r.rapier_pipeline_fraction:>12.1%} {ours:>19,.0f}{versus} "
            f"{(('ok ' if ours >= target else 'MISS ') + f'{target:,.0f}') if target else '-':>9}"
        )
    s = result.scan
    print(
        f"one {s.beams}-beam lidar scan (exact 2D, stadium track): {s.scan_us_median:.1f} us median over {s.repeats} scans"
    )


def register(kinds, paper: dict[int, float] | None = None) -> None:
    """The ``physics`` subcommand; ``paper`` as in :func:`print_table`."""

    def cli(args: argparse.Namespace) -> int:
        result = run(args.vehicles, args.per_env, args.seconds, args.substeps, args.dt, not args.no_shortcut)
        print_table(result, paper)
        write_json(args.json, result)
        return 0

    p = add_bench_parser(kinds, "physics", "vehicle-steps/s of the native simulator (lidar off)", __doc__)
    p.add_argument(
        "--vehicles",
        type=int,
        nargs="+",
        default=[1, 256, 1024, 2048],
        metavar="N",
        help="vehicle counts (default: 1 256 1024 2048)",
    )
    p.add_argument(
        "--per-env", type=int, default=1, metavar="V", help="vehicles per world (default 1: one car per env)"
    )
    p.add_argument(
        "--seconds", type=float, default=3.0, metavar="S", help="timed seconds per vehicle count (default 3)"
    )
    p.add_argument("--substeps", type=int, default=10, help="physics steps per Simulator.step call (default 10)")
    p.add_argument("--dt", type=float, default=PhysicsConfig().dt, help="physics time step in s (default 0.005)")
    p.add_argument(
        "--no-shortcut",
        action="store_true",
        help="run the rapier pipeline in every step (physics.shortcut_free_steps=False)",
    )
    p.set_defaults(func=cli)


def run_quick(paper: dict[int, float] | None = None) -> PhysicsResult:
    """`bench all`: 1, 256 and 2048 vehicles, one second each."""
    result = run([1, 256, 2048], 1, 1.0, 10, PhysicsConfig().dt)
    print_table(result, paper)
    return result
