"""``roboracer-arena bench env``: gymnasium ``step`` throughput with the full lidar
(1081 beams) computed every step at 0.01 s physics (one physics step per env step, as
F1TENTH Gym does), for a single env and for the native vector env.

The actions are a recorded pure-pursuit lap of the map replayed open loop (the
simulator is deterministic, so the replay drives the same lap), so the timing contains
the env's full step but not the Python driver. An *env-step* is one ``step()`` of one
environment; the vector env's figure is the aggregate over its environments.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..fileio import atomic_write_text

F1TENTH_GYM = (2800.0, 3400.0)  # env-steps/s, one planar vehicle, 1080 beams, 0.01 s, this machine
TARGET_SINGLE, TARGET_AGGREGATE = 5.0, 10.0  # multiples of the F1TENTH Gym midpoint
DEFAULT_MAP = Path("f1tenth-gym") / "maps" / "berlin.yaml"


def register(kinds) -> None:
    p = kinds.add_parser("env", help="gymnasium step throughput, 1081-beam lidar every 0.01 s step",
                         description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--num-envs", type=int, nargs="+", default=[1, 256], help="vector env sizes (default 1 256)")
    p.add_argument("--map", type=Path, default=None, help="map YAML (default: f1tenth-gym berlin from the sources)")
    p.add_argument("--seconds", type=float, default=5.0, help="time budget per configuration (default 5)")
    p.add_argument("--beams", type=int, default=1081, help="lidar beams (default 1081)")
    p.add_argument("--json", metavar="FILE", type=Path, help="write the results to FILE as JSON")
    p.set_defaults(func=_run_cli)


def _default_map() -> Path:
    from ..paths import sources_dir

    return sources_dir(None, "bench env (its default map is f1tenth-gym berlin; or pass --map)") / DEFAULT_MAP


def _env_kwargs(beams: int) -> dict[str, Any]:
    return {
        "control_rate_hz": 100.0,
        "sim": {"physics": {"dt": 0.01}, "lidar": {"num_beams": beams, "rate_hz": 100.0}},
        "reset_poses": "grid",
        "time_limit_s": None,
    }


def record_lap(track: Any, beams: int, max_steps: int = 20_000) -> np.ndarray:
    """Pure-pursuit actions (steps, 2) for one lap from the grid start (untimed)."""
    from ..drivers import PurePursuitDriver
    from ..envs.single import RoboRacerEnv

    env = RoboRacerEnv(track=track, **_env_kwargs(beams))
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


def _time_single(track: Any, beams: int, actions: np.ndarray, seconds: float) -> dict[str, Any]:
    import gymnasium as gym

    kwargs = _env_kwargs(beams)
    kwargs.pop("time_limit_s")  # under gymnasium.make the limit is max_episode_steps (-1: none)
    env = gym.make("RoboRacerArena-v0", track=track, max_episode_steps=-1, **kwargs)
    env.reset(seed=0)
    steps, resets, t0, c0 = 0, 0, time.perf_counter(), time.process_time()
    while True:
        _, _, term, trunc, _ = env.step(actions[steps % len(actions)])
        steps += 1
        if term or trunc or steps % len(actions) == 0:
            env.reset(seed=0)
            resets += 1
        if steps % 64 == 0 and time.perf_counter() - t0 >= seconds:
            break
    dt, cpu = time.perf_counter() - t0, time.process_time() - c0
    env.close()
    return {"kind": "single (gymnasium.make)", "num_envs": 1, "steps": steps, "resets": resets,
            "seconds": round(dt, 3), "cpu_seconds": round(cpu, 3), "env_steps_per_s": round(steps / dt, 1),
            "env_steps_per_cpu_s": round(steps / cpu, 1)}


def _time_vector(track: Any, beams: int, actions: np.ndarray, n: int, seconds: float) -> dict[str, Any]:
    import gymnasium as gym

    env = gym.make_vec("RoboRacerArena-v0", num_envs=n, vectorization_mode="vector_entry_point", track=track,
                       **_env_kwargs(beams))
    env.reset(seed=0)
    batch = np.repeat(actions[:, None, :], n, axis=1)
    calls, resets, t0, c0 = 0, 0, time.perf_counter(), time.process_time()
    while True:
        _, _, term, trunc, _ = env.step(batch[calls % len(batch)])
        calls += 1
        resets += int(np.count_nonzero(term | trunc))
        if calls % len(batch) == 0:
            env.reset(seed=0)
        if calls % 8 == 0 and time.perf_counter() - t0 >= seconds:
            break
    dt, cpu = time.perf_counter() - t0, time.process_time() - c0
    env.close()
    return {"kind": f"vector (make_vec, N={n})", "num_envs": n, "steps": calls * n, "resets": resets,
            "seconds": round(dt, 3), "cpu_seconds": round(cpu, 3), "env_steps_per_s": round(calls * n / dt, 1),
            "env_steps_per_cpu_s": round(calls * n / cpu, 1)}


def run(map_path: Path | None = None, num_envs: list[int] | None = None, seconds: float = 5.0,
        beams: int = 1081) -> dict[str, Any]:
    """Measure and print the table; returns the results."""
    from .. import envs  # noqa: F401  (registers RoboRacerArena-v0)
    from ..envs.tracks import resolve_tracks

    envs.register_envs()
    track = resolve_tracks(map_path or _default_map())[0]
    actions = record_lap(track, beams)
    rows = [_time_single(track, beams, actions, seconds)]
    for n in num_envs or [1, 256]:
        rows.append(_time_vector(track, beams, actions, n, seconds))
    ref = sum(F1TENTH_GYM) / 2
    for r in rows:
        r["x_f1tenth_gym"] = round(r["env_steps_per_s"] / ref, 2)
    load = round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None
    _print_table(track.name, beams, rows, threads=os.cpu_count() or 1, load=load)
    return {"map": track.name, "beams": beams, "physics_dt": 0.01, "threads": os.cpu_count(), "load_average_1min": load,
            "recorded_lap_steps": len(actions), "f1tenth_gym_env_steps_per_s": list(F1TENTH_GYM), "rows": rows}


def _print_table(name: str, beams: int, rows: list[dict[str, Any]], threads: int, load: float | None) -> None:
    lo, hi = F1TENTH_GYM
    print(f"gymnasium step throughput: map {name}, {beams}-beam lidar every step, 0.01 s physics step, "
          f"1 physics step per env step, {threads} threads, load average {load} at the end")
    print(f"{'configuration':<28}{'env-steps/s':>14}{'per CPU-s':>11}{'× F1TENTH Gym':>15}  target")
    print(f"{'F1TENTH Gym (reference)':<28}{f'{lo:,.0f}–{hi:,.0f}':>14}{'':>11}{'1.0':>15}")
    for r in rows:
        target = TARGET_AGGREGATE if r["num_envs"] > 1 else TARGET_SINGLE
        ok = "ok" if r["x_f1tenth_gym"] >= target else "MISS"
        print(f"{r['kind']:<28}{r['env_steps_per_s']:>14,.0f}{r['env_steps_per_cpu_s']:>11,.0f}"
              f"{r['x_f1tenth_gym']:>15.1f}  ≥{target:.0f}× {ok}")
    print("(env-steps/s is wall clock, the figure compared with the targets; 'per CPU-s' divides by the "
          "process CPU time, which a loaded machine inflates less)")


def run_quick() -> dict[str, Any]:
    return run(num_envs=[1, 256], seconds=2.0)


def _run_cli(args: argparse.Namespace) -> int:
    res = run(args.map, args.num_envs, args.seconds, args.beams)
    if args.json:
        atomic_write_text(args.json, json.dumps(res, indent=2))
        print(f"wrote {args.json}")
    return 0
