"""``python -m benchmarks ray``: the Ray executors against the local ones on this machine,
with a local Ray cluster (``ray.init(num_cpus=2)``), and a projection to more nodes.

* **Track generation**: the first ``--requests`` requests of the example sweep
  (:data:`~roboracer_arena.library.spec_sweep.EXAMPLE_SWEEP`) in this process, on the local
  pool (2 processes) and as Ray tasks (1 and 2 workers); wall time (median of
  ``--repeats``), requests/s, overhead per request, and whether every executor returned
  the same tracks. A no-op task rate gives the driver/scheduler ceiling.
* **Rollouts**: per-``step`` wall time (median) of the native vector env (``E`` envs,
  one thread, in a child process) against ``RayVectorEnv(1, E)`` (one actor, one thread):
  the difference is Ray's overhead per step; then ``RayVectorEnv(2, E)`` for scaling, and
  a check that its rollouts equal the local vector env of ``2 E`` envs. Full lidar (1081
  beams) every 0.01 s physics step, the replayed pure-pursuit lap of ``bench env``.

Every local measurement runs in a fresh process with ``RAYON_NUM_THREADS`` set, and Ray
tasks/actors get one thread per reserved CPU, so "1 worker" is one core throughout. The
projection (printed last) extrapolates the measured per-worker rates and overheads; it
is not a measurement.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path
from typing import Any

import numpy as np

from roboracer_arena.bench.output import BenchModel, Skipped, add_bench_parser, write_json
from roboracer_arena.foundation.worker_pool import pool_map

PROJECT_WORKERS = (8, 32, 128)


class ExecutorRow(BenchModel):
    """One executor on the generation requests: median and every wall time, rates, and
    whether it returned the same tracks as the in-process run."""

    executor: str
    wall_s: float
    walls_s: list[float]
    requests_per_s: float
    tracks_per_s: float
    same_tracks: bool


class Generation(BenchModel):
    """Track generation on every executor, with the overheads and scalings derived from it."""

    requests: int
    accepted: int
    rows: list[ExecutorRow]
    seconds_per_request_1_core: float
    ray_overhead_per_request_s: float
    ray_vs_local_pool_overhead_per_request_s: float
    ray_scaling_1_to_2: float
    local_scaling_1_to_2: float
    ray_noop_tasks_per_s: float


class RolloutRow(BenchModel):
    """One rollout configuration: workers, envs, ms per step (median, p90), env-steps/s."""

    config: str
    workers: int
    num_envs: int
    step_ms_median: float
    step_ms_p90: float
    env_steps_per_s: float


class Rollouts(BenchModel):
    """Rollouts on every configuration, Ray's overhead and scaling, and the sameness check."""

    envs_per_actor: int
    beams: int
    physics_dt: float
    steps: int
    rows: list[RolloutRow]
    compute_ms_per_step_1_thread: float
    ray_overhead_ms_per_step_1_actor: float
    ray_overhead_ms_per_step_2_actors: float
    ray_scaling_1_to_2: float
    same_rollouts_as_local: bool


class ProjectionRow(BenchModel):
    """Projected throughput on ``workers`` workers."""

    workers: int
    requests_per_s: float
    env_steps_per_s: float
    step_overhead_ms: float


class Projection(BenchModel):
    """See :func:`project` (a projection, not a measurement: ``note`` says so)."""

    note: str
    rows: list[ProjectionRow]


class LoadAverage(BenchModel):
    """The 1-minute load average at the start and the end of the run."""

    start: float
    end: float


class RayResult(BenchModel):
    """``bench ray``: the cluster, the machine's load, and each half (None when not run)."""

    cluster: str
    ray_version: str
    cluster_start_s: float
    load_average_1min: LoadAverage
    cores: int | None
    generation: Generation | None
    rollouts: Rollouts | None
    projection: Projection | None


def register(kinds) -> None:
    p = add_bench_parser(kinds, "ray", "Ray executors and RayVectorEnv vs local, 1 -> 2 workers, projection", __doc__)
    p.add_argument("--requests", type=int, default=24, help="sweep requests per generation run (default 24)")
    p.add_argument("--repeats", type=int, default=3, help="runs per configuration; the median is reported (default 3)")
    p.add_argument("--envs-per-actor", type=int, default=64, help="environments per actor / local batch (default 64)")
    p.add_argument("--steps", type=int, default=300, help="timed steps per rollout configuration (default 300)")
    p.add_argument("--beams", type=int, default=1081, help="lidar beams (default 1081)")
    p.add_argument(
        "--map",
        type=Path,
        default=None,
        help="map YAML (default: bench env's, f1tenth-racetracks Spielberg from the sources)",
    )
    p.add_argument("--only", choices=["generation", "rollouts"], help="run one half only (no projection)")
    p.set_defaults(func=_run_cli)


def _in_child(threads: int, fn, *args) -> Any:
    """``fn(*args)`` in a fresh spawned process whose native thread pool has ``threads`` threads."""
    return pool_map(_apply, [(fn, args)], isolate=True, initializer=_set_threads, initargs=(threads,))[0]


def _apply(call: tuple) -> Any:
    fn, args = call
    return fn(*args)


def _set_threads(threads: int) -> None:
    os.environ["RAYON_NUM_THREADS"] = str(threads)


def _strip(results: list) -> list:
    """generate_files results without wall-clock timings, for the sameness check."""
    out = []
    for rec, files in results:
        files = {
            k: (v if k != "report.json" else json.dumps({**json.loads(v), "seconds": 0})) for k, v in files.items()
        }
        out.append((rec.model_copy(update={"seconds": 0.0}), files))
    return out


# ---------------------------------------------------------------------------- generation
def _timed_runs(ex: Any, tasks: list, repeats: int) -> tuple[list[float], list]:
    """Wall times of ``repeats`` runs of the tasks on ``ex`` and the first run's results."""
    from roboracer_arena.distributed import map_ordered
    from roboracer_arena.library.generated import generate_files

    walls: list[float] = []
    first: list = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = map_ordered(ex, generate_files, tasks)
        walls.append(time.perf_counter() - t0)
        first = first or res
    return walls, first


def _gen_local(jobs: int, tasks: list, repeats: int) -> tuple[list[float], list]:
    from roboracer_arena.distributed import LocalExecutor

    with LocalExecutor(jobs) as ex:
        return _timed_runs(ex, tasks, repeats)


def _gen_ray(workers: int, tasks: list, repeats: int) -> tuple[list[float], list]:
    from roboracer_arena.distributed import RayExecutor, map_ordered

    ex = RayExecutor("auto", workers=workers)
    map_ordered(ex, _noop, list(range(2 * workers)))  # start the workers (not timed; reported apart)
    return _timed_runs(ex, tasks, repeats)


def _noop(x: Any) -> Any:
    return x


def _noop_rate(n: int = 400) -> float:
    from roboracer_arena.distributed import RayExecutor, map_ordered

    ex = RayExecutor("auto")
    map_ordered(ex, _noop, list(range(8)))
    t0 = time.perf_counter()
    map_ordered(ex, _noop, list(range(n)))
    return n / (time.perf_counter() - t0)


def bench_generation(requests: int, repeats: int) -> Generation:
    from roboracer_arena.library.spec_sweep import EXAMPLE_SWEEP, SweepFile

    tasks = SweepFile.model_validate(EXAMPLE_SWEEP).requests(0, requests)
    runs = {
        "in-process (1 worker)": _in_child(1, _gen_local, 1, tasks, repeats),
        "local pool, 2 processes": _in_child(1, _gen_local, 2, tasks, repeats),
        "Ray tasks, 1 worker": _gen_ray(1, tasks, repeats),
        "Ray tasks, 2 workers": _gen_ray(2, tasks, repeats),
    }
    ref = _strip(runs["in-process (1 worker)"][1])
    accepted = sum(bool(files) for _, files in runs["in-process (1 worker)"][1])
    rows = []
    for name, (walls, res) in runs.items():
        wall = statistics.median(walls)
        rows.append(
            ExecutorRow(
                executor=name,
                wall_s=round(wall, 3),
                walls_s=[round(w, 3) for w in walls],
                requests_per_s=round(requests / wall, 2),
                tracks_per_s=round(accepted / wall, 2),
                same_tracks=_strip(res) == ref,
            )
        )
    by = {r.executor: r.wall_s for r in rows}
    per_task = by["in-process (1 worker)"] / requests
    return Generation(
        requests=requests,
        accepted=accepted,
        rows=rows,
        seconds_per_request_1_core=round(per_task, 4),
        ray_overhead_per_request_s=round((by["Ray tasks, 1 worker"] - by["in-process (1 worker)"]) / requests, 4),
        ray_vs_local_pool_overhead_per_request_s=round(
            (by["Ray tasks, 2 workers"] - by["local pool, 2 processes"]) / requests, 4
        ),
        ray_scaling_1_to_2=round(by["Ray tasks, 1 worker"] / by["Ray tasks, 2 workers"], 2),
        local_scaling_1_to_2=round(by["in-process (1 worker)"] / by["local pool, 2 processes"], 2),
        ray_noop_tasks_per_s=round(_noop_rate(), 1),
    )


# ---------------------------------------------------------------------------- rollouts
def _step_times(env: Any, actions: np.ndarray, steps: int) -> list[float]:
    env.reset(seed=0)
    for i in range(5):  # warm-up: first observations, object store, caches
        env.step(actions[i % len(actions)])
    times = []
    for i in range(steps):
        t0 = time.perf_counter()
        env.step(actions[i % len(actions)])
        times.append(time.perf_counter() - t0)
    return times


def _local_steps(track: Any, n: int, actions: np.ndarray, steps: int, beams: int) -> list[float]:
    import gymnasium as gym

    import roboracer_arena  # noqa: F401  (registers the env id)
    from roboracer_arena.bench.env import env_kwargs

    env = gym.make_vec(
        "RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point", track=track, **env_kwargs(beams)
    )
    try:
        return _step_times(env, np.repeat(actions[:, None], n, axis=1), steps)
    finally:
        env.close()


def _ray_steps(track: Any, actors: int, per: int, actions: np.ndarray, steps: int, beams: int) -> list[float]:
    from roboracer_arena.bench.env import env_kwargs
    from roboracer_arena.distributed import RayVectorEnv

    env = RayVectorEnv(actors, per, track=track, **env_kwargs(beams))
    try:
        return _step_times(env, np.repeat(actions[:, None], actors * per, axis=1), steps)
    finally:
        env.close()


def _same_rollouts(track: Any, per: int, actions: np.ndarray, beams: int, steps: int = 40) -> bool:
    import gymnasium as gym
    from gymnasium.utils.env_checker import data_equivalence

    from roboracer_arena.bench.env import env_kwargs
    from roboracer_arena.distributed import RayVectorEnv

    kw = {**env_kwargs(beams), "reset_poses": "random"}
    renv = RayVectorEnv(2, per, track=track, **kw)
    lenv = gym.make_vec(
        "RoboRacerArena-v0", num_envs=2 * per, vectorization_mode="vector_entry_point", track=track, **kw
    )
    try:
        ok = data_equivalence(renv.reset(seed=7), lenv.reset(seed=7), exact=True)
        for i in range(steps):
            a = np.repeat(actions[i % len(actions)][None], 2 * per, axis=0)
            ok = ok and data_equivalence(renv.step(a), lenv.step(a), exact=True)
        return bool(ok)
    finally:
        renv.close()
        lenv.close()


def bench_rollouts(track: Any, per: int, steps: int, beams: int) -> Rollouts:
    from roboracer_arena.bench.env import record_lap

    actions = record_lap(track, beams)
    timed = {
        "local native batch, 1 thread": (1, _in_child(1, _local_steps, track, per, actions, steps, beams)),
        "RayVectorEnv, 1 actor": (1, _ray_steps(track, 1, per, actions, steps, beams)),
        "local native batch, 2 threads": (2, _in_child(2, _local_steps, track, 2 * per, actions, steps, beams)),
        "RayVectorEnv, 2 actors": (2, _ray_steps(track, 2, per, actions, steps, beams)),
    }
    rows = []
    for name, (workers, times) in timed.items():
        med = statistics.median(times)
        rows.append(
            RolloutRow(
                config=name,
                workers=workers,
                num_envs=workers * per,
                step_ms_median=round(1e3 * med, 3),
                step_ms_p90=round(1e3 * float(np.percentile(times, 90)), 3),
                env_steps_per_s=round(workers * per / med, 1),
            )
        )
    ms = {r.config: r.step_ms_median for r in rows}
    return Rollouts(
        envs_per_actor=per,
        beams=beams,
        physics_dt=0.01,
        steps=steps,
        rows=rows,
        compute_ms_per_step_1_thread=ms["local native batch, 1 thread"],
        ray_overhead_ms_per_step_1_actor=round(ms["RayVectorEnv, 1 actor"] - ms["local native batch, 1 thread"], 3),
        ray_overhead_ms_per_step_2_actors=round(ms["RayVectorEnv, 2 actors"] - ms["local native batch, 1 thread"], 3),
        ray_scaling_1_to_2=round(2 * ms["RayVectorEnv, 1 actor"] / ms["RayVectorEnv, 2 actors"], 2),
        same_rollouts_as_local=_same_rollouts(track, min(per, 4), actions, beams),
    )


# ---------------------------------------------------------------------------- projection
def project(gen: Generation, roll: Rollouts) -> Projection:
    """Throughput on W workers from the measured per-worker cost and overheads (a projection):
    generation ``W / (t + o)`` (``o`` at least one no-op task's round trip) capped by the
    measured no-op task rate (the driver and scheduler); rollouts ``W E / (t_step + o(W))`` with the per-step overhead growing
    linearly in actors as measured from 1 to 2 (the driver sends and gathers per actor)."""
    cap = gen.ray_noop_tasks_per_s
    # The wall-time difference is noise-dominated on a shared machine (it can come out negative):
    # never assume less than one no-op task's round trip.
    t, o = gen.seconds_per_request_1_core, max(1.0 / cap, gen.ray_overhead_per_request_s)
    ts, o1, o2 = (
        roll.compute_ms_per_step_1_thread,
        max(0.0, roll.ray_overhead_ms_per_step_1_actor),
        max(0.0, roll.ray_overhead_ms_per_step_2_actors),
    )
    per = roll.envs_per_actor
    rows = []
    for w in PROJECT_WORKERS:
        ow = o1 + (max(o2, o1) - o1) * (w - 1)
        rows.append(
            ProjectionRow(
                workers=w,
                requests_per_s=round(min(w / (t + o), cap), 1),
                env_steps_per_s=round(w * per / ((ts + ow) / 1e3), 0),
                step_overhead_ms=round(ow, 2),
            )
        )
    return Projection(
        note="projection from this machine's per-worker measurements, not a measurement; ignores network "
        "latency between nodes and assumes the driver is not otherwise loaded",
        rows=rows,
    )


def run(
    requests: int = 24,
    repeats: int = 3,
    envs_per_actor: int = 64,
    steps: int = 300,
    beams: int = 1081,
    map_path: Path | None = None,
    only: str | None = None,
) -> RayResult:
    """Measure, print the tables (and the projection when both halves ran); returns the results."""
    from roboracer_arena.bench.env import default_map
    from roboracer_arena.distributed.ray_cluster import import_ray
    from roboracer_arena.envs.track_argument import resolve_tracks

    ray = import_ray()
    load0 = os.getloadavg()[0]
    t0 = time.perf_counter()
    owns = not ray.is_initialized()
    if owns:
        ray.init(num_cpus=2, include_dashboard=False, logging_level="ERROR", log_to_driver=False)
    start = time.perf_counter() - t0
    try:
        gen = bench_generation(requests, repeats) if only != "rollouts" else None
        roll = (
            bench_rollouts(resolve_tracks(map_path or default_map())[0], envs_per_actor, steps, beams)
            if only != "generation"
            else None
        )
    finally:
        if owns:
            ray.shutdown()
    res = RayResult(
        cluster="local, ray.init(num_cpus=2)",
        ray_version=ray.__version__,
        cluster_start_s=round(start, 2),
        load_average_1min=LoadAverage(start=round(load0, 2), end=round(os.getloadavg()[0], 2)),
        cores=os.cpu_count(),
        generation=gen,
        rollouts=roll,
        projection=project(gen, roll) if gen and roll else None,
    )
    _print(res)
    return res


def _print(res: RayResult) -> None:
    load = res.load_average_1min
    print(
        f"Ray {res.ray_version}, {res.cluster}, {res.cores} cores; cluster start {res.cluster_start_s} s; "
        f"load average {load.start} -> {load.end} (shared machine)"
    )
    if res.generation:
        _print_generation(res.generation)
    if res.rollouts:
        _print_rollouts(res.rollouts)
    if res.projection:
        p = res.projection
        print(f"\nPROJECTION ({p.note}):")
        print(f"{'workers':>8}{'requests/s':>12}{'env-steps/s':>14}{'step overhead ms':>18}")
        for row in p.rows:
            print(
                f"{row.workers:>8}{row.requests_per_s:>12,.1f}{row.env_steps_per_s:>14,.0f}{row.step_overhead_ms:>18.2f}"
            )


def _print_generation(g: Generation) -> None:
    print(f"\ntrack generation: {g.requests} requests of the example sweep ({g.accepted} accepted), median of runs")
    print(f"{'executor':<28}{'wall s':>9}{'req/s':>8}{'tracks/s':>10}  same tracks")
    for row in g.rows:
        print(
            f"{row.executor:<28}{row.wall_s:>9.2f}{row.requests_per_s:>8.2f}{row.tracks_per_s:>10.2f}  {row.same_tracks}"
        )
    print(
        f"Ray overhead per request: {1e3 * g.ray_overhead_per_request_s:.1f} ms vs in-process, "
        f"{1e3 * g.ray_vs_local_pool_overhead_per_request_s:.1f} ms vs the local pool (compute {1e3 * g.seconds_per_request_1_core:.0f} ms"
        f"/request on 1 core); scaling 1 -> 2 workers: Ray {g.ray_scaling_1_to_2}x, local {g.local_scaling_1_to_2}x; "
        f"no-op task ceiling {g.ray_noop_tasks_per_s:.0f} tasks/s"
    )


def _print_rollouts(r: Rollouts) -> None:
    print(
        f"\nrollouts: {r.envs_per_actor} envs per actor/batch, {r.beams}-beam lidar every 0.01 s step, median of {r.steps} steps"
    )
    print(f"{'configuration':<32}{'envs':>6}{'ms/step':>10}{'p90':>8}{'env-steps/s':>13}")
    for row in r.rows:
        print(
            f"{row.config:<32}{row.num_envs:>6}{row.step_ms_median:>10.2f}{row.step_ms_p90:>8.2f}{row.env_steps_per_s:>13,.0f}"
        )
    print(
        f"Ray overhead per step: {r.ray_overhead_ms_per_step_1_actor:.2f} ms (1 actor), "
        f"{r.ray_overhead_ms_per_step_2_actors:.2f} ms (2 actors); scaling 1 -> 2 actors {r.ray_scaling_1_to_2}x; "
        f"rollouts equal to the local vector env: {r.same_rollouts_as_local}"
    )


def run_quick() -> RayResult | Skipped:
    try:
        import ray  # noqa: F401
    except ImportError:
        print("skipped: Ray is not installed (pip install 'roboracer-arena[ray]')")
        return Skipped(skipped="Ray is not installed")
    return run(requests=12, repeats=1, steps=100)


def _run_cli(args: argparse.Namespace) -> int:
    res = run(args.requests, args.repeats, args.envs_per_actor, args.steps, args.beams, args.map, args.only)
    write_json(args.json, res)
    return 0
