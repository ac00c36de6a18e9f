"""``roboracer-arena bench env``: gymnasium ``step`` throughput with a full lidar scan
every step at 0.01 s physics (one physics step per env step, as F1TENTH Gym does), for a
single env and for the native vector env, in three workloads:

* ``constant``: the action [0 rad, 1 m/s] every step (``python -m benchmarks env``, in a
  checkout, sets F1TENTH Gym's figure for it beside ours);
* ``lap``: a recorded pure-pursuit lap of the map replayed open loop (the simulator is
  deterministic, so the replay drives the same lap; restarted at the end of the lap);
* ``random``: uniformly random actions over the action space (crash-heavy, as early
  reinforcement learning is).

Every workload autoresets on collision (``collision_ends_episode``; the vector env's
next-step autoreset, the single env resets on ``terminated``). An *env-step* is one
``step()`` of one environment; the vector env's figure is the aggregate over its envs.

The per-step breakdown: ``physics`` and ``scan`` replay the same actions on a bare
``_core.Simulator`` (same config, same resets on collision): its step without the scan,
and the extra time of the step with the scan. ``python`` is the time of the env's
``step()`` calls spent outside the native simulator's calls (action sanitising, reward,
observation, info, gymnasium's wrappers, the vector env's autoresets' Python side),
measured in the env run itself by timing those calls (the timers' own ~0.3 µs per call
count as Python). The single env's resets (``env.reset()`` on termination) are in the
throughput but not in the per-step breakdown. A last line times
one 1081-beam scan alone, median over centreline poses around the lap.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from .. import envs
from .._core import EVENT_VEHICLE, EVENT_WALL, Simulator
from ..drivers import PurePursuitDriver
from ..envs.env_config import EnvConfig
from ..envs.single import RoboRacerEnv
from ..envs.track_argument import resolve_tracks
from ..foundation.paths import sources_dir
from ..track.start_grid import centreline_pose, grid_start_s
from .output import BenchModel, add_bench_parser, write_json

#: Targets (issue 14): single env µs per step; vector env env-steps/s per workload.
TARGET_SINGLE_US = 35.0
TARGET_SCAN_US = 15.0  # one 1081-beam scan, median over a lap
TARGET_VECTOR = {"constant": 65_000.0, "random": 52_000.0}
DEFAULT_MAP = Path("f1tenth-racetracks") / "Spielberg" / "Spielberg_map.yaml"
WORKLOADS = ("constant", "lap", "random")


class Breakdown(BenchModel):
    """µs per ``step()`` call: the bare simulator's step, the scan's extra, the env's Python."""

    physics: float
    scan: float
    python: float


class EnvRow(BenchModel):
    """One (workload, env count): steps and resets in the timed wall and CPU seconds,
    env-steps/s, µs per call, the Python part of it, and the breakdown."""

    workload: str
    num_envs: int
    steps: int
    resets: int
    seconds: float
    cpu_seconds: float
    env_steps_per_s: float
    us_per_step: float
    python_us_per_step: float
    breakdown_us_per_call: Breakdown | None = None  # set by run() after the bare-simulator replays


class ScanOverLap(BenchModel):
    """One scan's cost (µs) over centreline poses around the lap."""

    beams: int
    poses: int
    median_us: float
    p90_us: float
    max_us: float


class EnvResult(BenchModel):
    """``bench env``: the map and settings, the machine's load, the scan and every row."""

    map: str
    beams: int
    physics_dt: float
    threads: int | None
    load_average_1min: list[float | None]
    recorded_lap_steps: int
    scan_over_lap: ScanOverLap
    f1tenth_gym_env_steps_per_s: list[float] = []  # the peer's figure, when a comparison passed it
    rows: list[EnvRow]


def register(kinds, reference: tuple[float, float] | None = None) -> None:
    """The ``env`` subcommand; ``reference`` as in :func:`run`."""
    p = add_bench_parser(
        kinds, "env", "gymnasium step throughput, full lidar every 0.01 s step, three workloads", __doc__
    )
    p.add_argument(
        "--num-envs", type=int, nargs="+", default=[1, 256], help="env counts (default 1 256; 1 = single env)"
    )
    p.add_argument(
        "--map", type=Path, default=None, help="map YAML (default: f1tenth-racetracks Spielberg from the sources)"
    )
    p.add_argument("--seconds", type=float, default=3.0, help="time budget per measurement (default 3)")
    p.add_argument("--beams", type=int, default=1080, help="lidar beams (default 1080)")
    p.add_argument(
        "--workloads",
        nargs="+",
        choices=WORKLOADS,
        default=list(WORKLOADS),
        help="workloads to run (default: all three)",
    )

    def cli(args: argparse.Namespace) -> int:
        res = run(args.map, args.num_envs, args.seconds, args.beams, args.workloads, reference)
        write_json(args.json, res)
        return 0

    p.set_defaults(func=cli)


def default_map() -> Path:
    """The bench's default map: f1tenth-racetracks Spielberg from the track sources."""
    return sources_dir(None, "bench env (its default map is f1tenth-racetracks Spielberg; or pass --map)") / DEFAULT_MAP


def env_kwargs(beams: int) -> dict[str, Any]:
    """The env keywords every bench cell uses: 100 Hz control, one 0.01 s physics step and a
    ``beams``-beam scan per step, the grid start, no time limit (as F1TENTH Gym steps)."""
    return {
        "control_rate_hz": 100.0,
        "sim": {"physics": {"dt": 0.01}, "lidar": {"num_beams": beams, "rate_hz": 100.0}},
        "reset_poses": "grid",
        "time_limit_s": None,
    }


def grid_start_pose(track: Any, beams: int = 1080) -> tuple[float, float, float]:
    """The pose (x, y, yaw) every bench cell starts and restarts from: the env's grid start."""
    cfg = EnvConfig.build(None, **env_kwargs(beams))
    return centreline_pose(track, grid_start_s(track, 1, cfg.grid_spacing))


def record_lap(track: Any, beams: int, max_steps: int = 20_000) -> np.ndarray:
    """Pure-pursuit actions (steps, 2) for one lap from the grid start (untimed)."""

    env = RoboRacerEnv(track=track, **env_kwargs(beams))
    driver = PurePursuitDriver.for_env(env)
    obs, info = env.reset(seed=0)
    actions = []
    for _ in range(max_steps):
        a = driver.act(obs)
        actions.append(a)
        obs, _, term, trunc, info = env.step(a)
        if term or trunc or info["progress"] >= env.tracks[0].length:
            break
    return np.asarray(actions, dtype=np.float32)


def workload_actions(
    kind: str, lap: np.ndarray, n: int, bounds: tuple[np.ndarray, np.ndarray], steps: int = 4096
) -> np.ndarray:
    """Actions (T, n, 2) float32 of a workload for ``n`` envs, cycled by the timing loops."""
    if kind == "constant":
        return np.broadcast_to(np.array([0.0, 1.0], np.float32), (1, n, 2)).copy()
    if kind == "lap":
        return np.repeat(lap[:, None, :], n, axis=1)
    lo, hi = bounds
    return np.random.default_rng(0).uniform(lo, hi, (steps, n, 2)).astype(np.float32)


def _timed(step: Callable[[int], None], seconds: float, check_every: int) -> tuple[int, float, float]:
    """Call ``step(i)`` for i = 0, 1, ... until ``seconds`` of wall time pass; returns
    (calls, wall seconds, process CPU seconds)."""
    i, t0, c0 = 0, time.perf_counter(), time.process_time()
    while True:
        step(i)
        i += 1
        if i % check_every == 0 and time.perf_counter() - t0 >= seconds:
            return i, time.perf_counter() - t0, time.process_time() - c0


class _CoreTimer:
    """Stands in for an env's ``_core.Simulator`` and adds up the time spent in its calls
    (``step``, ``reset_drawn``, ``observe``), so the Python around them can be told apart."""

    def __init__(self, sim: Any) -> None:
        self.sim, self.seconds = sim, 0.0

    def __getattr__(self, name: str) -> Any:
        attr = getattr(self.sim, name)
        if name not in ("step", "reset_drawn", "observe"):
            return attr

        def timed(*args: Any) -> Any:
            t0 = time.perf_counter()
            try:
                return attr(*args)
            finally:
                self.seconds += time.perf_counter() - t0

        return timed


def time_env(track: Any, beams: int, kind: str, acts: np.ndarray, n: int, seconds: float) -> EnvRow:
    """Env-steps/s of ``gymnasium.make`` (n = 1) or ``make_vec`` (n > 1) on a workload, and
    the µs per call spent outside the native simulator's calls (the Python)."""

    kwargs = env_kwargs(beams)
    counts = {"resets": 0}
    core = {"seconds": 0.0, "step": 0.0}

    def timed_step(env: Any, action: np.ndarray) -> tuple[Any, Any]:
        """``env.step(action)`` with its time and its simulator calls' time added up;
        returns (terminated, truncated)."""
        b = env.unwrapped._batch
        if not isinstance(b.sim, _CoreTimer):  # (again after a reseed rebuilt the simulator)
            b.sim = _CoreTimer(b.sim)
        before, t0 = b.sim.seconds, time.perf_counter()
        _, _, term, trunc, _ = env.step(action)
        core["step"] += time.perf_counter() - t0
        core["seconds"] += b.sim.seconds - before
        return term, trunc

    restart = len(acts) if kind == "lap" else 0
    env: gym.Env | gym.vector.VectorEnv
    if n == 1:
        kwargs.pop("time_limit_s")  # under gymnasium.make the limit is max_episode_steps (-1: none)
        env = gym.make("RoboRacerArena-v0", track=track, max_episode_steps=-1, **kwargs)
        env.reset(seed=0)
        single = [a[0] for a in acts]
        T = len(single)

        def step(i: int) -> None:
            term, trunc = timed_step(env, single[i % T])
            if term or trunc or (restart and (i + 1) % restart == 0):
                env.reset()  # (no reseed: that would rebuild the simulator; the grid start has no noise)
                counts["resets"] += 1
    else:
        env = gym.make_vec(
            "RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point", track=track, **kwargs
        )
        env.reset(seed=0)
        T = len(acts)

        def step(i: int) -> None:
            term, trunc = timed_step(env, acts[i % T])
            counts["resets"] += int(np.count_nonzero(term | trunc))
            if restart and (i + 1) % restart == 0:
                env.reset()

    calls, dt, cpu = _timed(step, seconds, 64 if n == 1 else 4)
    env.close()
    steps = calls * n
    return EnvRow(
        workload=kind,
        num_envs=n,
        steps=steps,
        resets=counts["resets"],
        seconds=round(dt, 3),
        cpu_seconds=round(cpu, 3),
        env_steps_per_s=round(steps / dt, 1),
        us_per_step=round(dt / calls * 1e6, 2),
        python_us_per_step=round((core["step"] - core["seconds"]) / calls * 1e6, 2),
    )


def _time_core(track: Any, beams: int, kind: str, acts: np.ndarray, n: int, seconds: float, scan: bool) -> float:
    """µs per ``Simulator.step`` call of a bare simulator on the same actions (with or
    without the scan), resetting a collided env to its grid start like the env does."""

    cfg = EnvConfig.build(None, **env_kwargs(beams))
    sim = Simulator([track.native()], n, 1, cfg.sim, 0)
    start = np.array(grid_start_pose(track, beams))
    poses = np.broadcast_to(start, (n, 1, 3)).copy()
    sim.reset(np.ones(n, bool), poses)
    scans = np.zeros((n, 1, sim.num_beams), np.float32) if scan else None
    state = np.zeros((n, 1, len(sim.state_fields)), np.float64)
    events = np.zeros((n, 1), np.uint8)
    a64 = [np.ascontiguousarray(a[:, None, :], dtype=np.float64) for a in acts]
    T = len(a64)
    restart = T if kind == "lap" else 0

    def step(i: int) -> None:
        sim.step(a64[i % T], 1, scans, state, events)
        hit = (events[:, 0] & (EVENT_WALL | EVENT_VEHICLE)) != 0
        if restart and (i + 1) % restart == 0:
            hit[:] = True
        if hit.any():
            sim.reset(hit, poses)

    calls, dt, _ = _timed(step, seconds, 64 if n == 1 else 4)
    return dt / calls * 1e6


def scan_over_lap(track: Any, beams: int = 1081, every_m: float = 1.0, repeats: int = 30) -> ScanOverLap:
    """One scan's cost (µs) at centreline poses every ``every_m`` around the lap: per pose
    the median of ``observe`` with the scan minus without it (one env, one car)."""

    cfg = EnvConfig.build(None, **env_kwargs(beams))
    sim = Simulator([track.native()], 1, 1, cfg.sim, 0)
    scans = np.zeros((1, 1, sim.num_beams), np.float32)
    state, events, mask = np.zeros((1, 1, len(sim.state_fields))), np.zeros((1, 1), np.uint8), np.ones(1, bool)

    def median_us(sc: np.ndarray | None) -> float:
        t = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            sim.observe(sc, state, events)
            t.append(time.perf_counter() - t0)
        return float(np.median(t)) * 1e6

    per = []
    for s in np.arange(0.0, track.length, every_m):
        sim.reset(mask, np.array(centreline_pose(track, s)).reshape(1, 1, 3))
        per.append(median_us(scans) - median_us(None))
    a = np.array(per)
    return ScanOverLap(
        beams=beams,
        poses=len(a),
        median_us=round(float(np.median(a)), 2),
        p90_us=round(float(np.percentile(a, 90)), 2),
        max_us=round(float(a.max()), 2),
    )


def run(
    map_path: Path | None = None,
    num_envs: list[int] | None = None,
    seconds: float = 3.0,
    beams: int = 1080,
    workloads: list[str] | None = None,
    reference: tuple[float, float] | None = None,
) -> EnvResult:
    """Measure and print the table; returns the results. ``reference``: F1TENTH Gym's
    (low, high) env-steps/s on the constant workload, printed and stored beside ours."""

    envs.register_envs()
    track = resolve_tracks(map_path or default_map())[0]
    veh = EnvConfig().sim.vehicle
    bounds = (np.array([-veh.max_steer, veh.min_speed]), np.array([veh.max_steer, veh.max_speed]))
    lap = record_lap(track, beams)
    load_before = load_average()
    rows = []
    for kind in workloads or list(WORKLOADS):
        for n in num_envs or [1, 256]:
            acts = workload_actions(kind, lap, n, bounds)
            row = time_env(track, beams, kind, acts, n, seconds)
            physics = _time_core(track, beams, kind, acts, n, seconds / 2, scan=False)
            core = _time_core(track, beams, kind, acts, n, seconds / 2, scan=True)
            breakdown = Breakdown(
                physics=round(physics, 2), scan=round(max(core - physics, 0.0), 2), python=row.python_us_per_step
            )
            rows.append(row.model_copy(update={"breakdown_us_per_call": breakdown}))
    scan = scan_over_lap(track)
    load = load_average()
    _print_table(track.name, beams, rows, os.cpu_count() or 1, (load_before, load), reference)
    print(
        f"one {scan.beams}-beam scan at {scan.poses} centreline poses around the lap: median "
        f"{scan.median_us:.1f} µs, p90 {scan.p90_us:.1f}, max {scan.max_us:.1f}  "
        f"target ≤{TARGET_SCAN_US:.0f} µs {'ok' if scan.median_us <= TARGET_SCAN_US else 'MISS'}"
    )
    return EnvResult(
        map=track.name,
        beams=beams,
        physics_dt=0.01,
        threads=os.cpu_count(),
        load_average_1min=[load_before, load],
        recorded_lap_steps=len(lap),
        scan_over_lap=scan,
        f1tenth_gym_env_steps_per_s=list(reference or ()),
        rows=rows,
    )


def load_average() -> float | None:
    """The 1-minute load average (None where the OS has none), stored beside timings."""
    return round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None


def _verdict(r: EnvRow) -> str:
    if r.num_envs == 1:
        t = TARGET_SINGLE_US
        return f"≤{t:.0f} µs {'ok' if r.us_per_step <= t else 'MISS'}" if r.workload == "constant" else ""
    target = TARGET_VECTOR.get(r.workload)
    return f"≥{target:,.0f} {'ok' if r.env_steps_per_s >= target else 'MISS'}" if target else ""


def _print_table(
    name: str,
    beams: int,
    rows: list[EnvRow],
    threads: int,
    loads: tuple[float | None, float | None],
    reference: tuple[float, float] | None,
) -> None:
    print(
        f"gymnasium step throughput: map {name}, {beams}-beam lidar every step, 0.01 s physics step, "
        f"autoreset on collision, {threads} threads, load average {loads[0]} before / {loads[1]} after"
    )
    if reference:
        lo, hi = reference
        print(f"F1TENTH Gym reference (constant action, single env): {lo:,.0f}–{hi:,.0f} env-steps/s")
    print(
        f"{'workload':<10}{'envs':>6}{'env-steps/s':>13}{'µs/call':>10}{'resets':>8}"
        f"{'physics':>9}{'scan':>8}{'python':>8}  target"
    )
    for r in rows:
        b = r.breakdown_us_per_call
        assert b is not None  # run() sets it on every row
        print(
            f"{r.workload:<10}{r.num_envs:>6}{r.env_steps_per_s:>13,.0f}{r.us_per_step:>10.1f}"
            f"{r.resets:>8}{b.physics:>9.1f}{b.scan:>8.1f}{b.python:>8.1f}  {_verdict(r)}"
        )
    print(
        "(wall clock; µs per step() call, for the vector env per call over all envs; physics and scan replay the "
        "actions on a bare Simulator: physics = its step without the scan, scan = the extra of the scan; python = "
        "the time of the env's step() spent outside the simulator's calls)"
    )


def run_quick(reference: tuple[float, float] | None = None) -> EnvResult:
    return run(num_envs=[1, 256], seconds=1.0, reference=reference)
