"""``python -m benchmarks peer --f1tenth-gym PYTHON``: our single env against F1TENTH Gym,
both measured in the same run on the same machine.

The cell is ``bench env``'s ``constant`` single env: ``gymnasium.make("RoboRacerArena-v0")``
with its standard wrappers on Spielberg (or ``--map``), a 1080-beam scan every 0.01 s step,
the action [0 rad, 1 m/s], a reset to the grid start on collision. F1TENTH Gym runs the
same map from the same start pose with the same action, under PYTHON (an interpreter
whose environment imports ``f110_gym``; ``f1tenth_gym_driver.py`` is what it runs). The
two alternate ``--pairs`` times, peer first, so a change in the machine's load hits both
sides of a pair; the ratio reported is the median of the pairs' ratios (issue 24's
target: at least 8×).

F1TENTH Gym is not on PyPI: install it from its repository into a venv of its own (it
pins old numpy and gym; ``pip install --no-deps`` it and add numba, numpy<2, scipy,
pyyaml, pillow, gym, pyglet<1.5 and pyopengl) and pass that venv's python, or set
``F1TENTH_GYM_PYTHON``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from roboracer_arena import envs
from roboracer_arena.bench.env import default_map, env_kwargs, grid_start_pose, load_average
from roboracer_arena.bench.output import BenchModel, add_bench_parser, write_json
from roboracer_arena.envs.track_argument import resolve_tracks
from roboracer_arena.errors import ArenaError, InvalidArgumentError

DRIVER = Path(__file__).with_name("f1tenth_gym_driver.py")
TARGET_RATIO = 8.0
BEAMS = 1080  # F1TENTH Gym's fixed beam count


class PeerUnavailableError(ArenaError):
    """The given interpreter cannot run F1TENTH Gym."""


class PeerRun(BenchModel):
    """One timed run: steps, resets, wall and CPU seconds, beams per scan (F1TENTH Gym's
    as its driver printed it; ours from the same loop in this process)."""

    steps: int
    resets: int
    seconds: float
    cpu_seconds: float
    beams: int

    @property
    def steps_per_s(self) -> float:
        return self.steps / self.seconds


class Pair(BenchModel):
    """F1TENTH Gym then ours, back to back; ratios of env-steps per wall and per CPU second."""

    f1tenth_gym: PeerRun
    ours: PeerRun
    ratio_wall: float
    ratio_cpu: float


class PeerResult(BenchModel):
    """``benchmarks peer``: the map, start pose, load, every pair and the median ratios."""

    map: str
    start_pose: list[float]
    f1tenth_gym_python: str
    load_average_1min: list[float | None]
    pairs: list[Pair]
    median_ratio_wall: float
    median_ratio_cpu: float
    target_ratio: float


def register(kinds) -> None:
    p = add_bench_parser(kinds, "peer", "single env against F1TENTH Gym, both measured in one run", __doc__)
    p.add_argument(
        "--f1tenth-gym",
        metavar="PYTHON",
        default=os.environ.get("F1TENTH_GYM_PYTHON"),
        help="an interpreter whose environment imports f110_gym (default: $F1TENTH_GYM_PYTHON)",
    )
    p.add_argument("--map", type=Path, default=None, help="map YAML (default: f1tenth-racetracks Spielberg)")
    p.add_argument("--seconds", type=float, default=3.0, help="seconds per timed run (default 3)")
    p.add_argument("--pairs", type=int, default=3, help="alternating F1TENTH Gym / ours pairs (default 3)")

    def cli(args: argparse.Namespace) -> int:
        if not args.f1tenth_gym:
            raise InvalidArgumentError("--f1tenth-gym PYTHON (or F1TENTH_GYM_PYTHON) is required: see --help")
        res = run(args.f1tenth_gym, args.map, args.seconds, args.pairs)
        write_json(args.json, res)
        return 0

    p.set_defaults(func=cli)


def run_peer(python: str, map_yaml: Path, pose: tuple[float, float, float], seconds: float) -> PeerRun:
    """One timed F1TENTH Gym run under ``python``; :class:`PeerUnavailableError` with the
    peer's last error line when it cannot run."""
    cmd = [python, str(DRIVER), str(map_yaml), *(repr(v) for v in pose), repr(seconds)]
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=120 + 4 * seconds, check=False)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise PeerUnavailableError(f"F1TENTH Gym under {python}: {e}") from None
    lines = [ln for ln in done.stdout.splitlines() if ln.startswith("{")]
    if done.returncode != 0 or not lines:
        errs = [ln for ln in done.stderr.splitlines() if ln.strip()]
        last = errs[-1] if errs else f"exit {done.returncode}, no output"
        raise PeerUnavailableError(f"F1TENTH Gym under {python} did not run: {last}")
    return PeerRun.model_validate(json.loads(lines[-1]))


def run_ours(track: Any, seconds: float) -> PeerRun:
    """Our side, timed the way the driver times F1TENTH Gym's: ``gymnasium.make`` with its
    standard wrappers, the constant action, a reset on ``terminated``/``truncated``, the
    clock read every 64 steps, nothing else in the loop."""
    kwargs = env_kwargs(BEAMS)
    kwargs.pop("time_limit_s")  # under gymnasium.make the limit is max_episode_steps (-1: none)
    env = gym.make("RoboRacerArena-v0", track=track, max_episode_steps=-1, **kwargs)
    action = np.array([0.0, 1.0], np.float32)
    obs, _ = env.reset(seed=0)
    steps = resets = 0
    t0, c0 = time.perf_counter(), time.process_time()
    while True:
        obs, _, terminated, truncated, _ = env.step(action)
        steps += 1
        if terminated or truncated:
            env.reset()
            resets += 1
        if steps % 64 == 0 and time.perf_counter() - t0 >= seconds:
            wall, cpu = time.perf_counter() - t0, time.process_time() - c0
            env.close()
            return PeerRun(steps=steps, resets=resets, seconds=wall, cpu_seconds=cpu, beams=obs["scan"].shape[-1])


def run(python: str, map_path: Path | None = None, seconds: float = 3.0, pairs: int = 3) -> PeerResult:
    """Alternate F1TENTH Gym and our single env ``pairs`` times; print and return the ratios."""
    if not (0.5 <= seconds <= 600 and 1 <= pairs <= 50):
        raise InvalidArgumentError(f"--seconds {seconds} must be in [0.5, 600] and --pairs {pairs} in [1, 50]")
    envs.register_envs()
    map_yaml = Path(map_path or default_map()).resolve()
    track = resolve_tracks(map_yaml)[0]
    pose = grid_start_pose(track, BEAMS)
    run_ours(track, 0.5)  # warm caches, untimed
    load_before = load_average()
    print(f"single env against F1TENTH Gym: map {track.name}, start {tuple(round(v, 3) for v in pose)}, ")
    print(f"{BEAMS} beams, 0.01 s step, action [0, 1], {seconds:g} s per run, F1TENTH Gym under {python}")
    print(f"{'pair':<6}{'F1TENTH Gym':>13}{'ours':>10}{'× wall':>9}{'× CPU-s':>9}{'resets (peer/ours)':>20}")
    rows = []
    for i in range(pairs):
        peer = run_peer(python, map_yaml, pose, seconds)
        ours = run_ours(track, seconds)
        pair = Pair(
            f1tenth_gym=peer,
            ours=ours,
            ratio_wall=round(ours.steps_per_s / peer.steps_per_s, 3),
            ratio_cpu=round((ours.steps / ours.cpu_seconds) / (peer.steps / peer.cpu_seconds), 3),
        )
        rows.append(pair)
        print(
            f"{i + 1:<6}{peer.steps_per_s:>13,.0f}{ours.steps_per_s:>10,.0f}{pair.ratio_wall:>9.2f}"
            f"{pair.ratio_cpu:>9.2f}{f'{peer.resets}/{ours.resets}':>20}"
        )
        sys.stdout.flush()
        time.sleep(0.2)
    wall = statistics.median(p.ratio_wall for p in rows)
    cpu = statistics.median(p.ratio_cpu for p in rows)
    verdict = "ok" if wall >= TARGET_RATIO else "MISS"
    print(f"median ratio: {wall:.2f}× wall, {cpu:.2f}× per CPU-second; target ≥ {TARGET_RATIO:g}× {verdict}")
    return PeerResult(
        map=track.name,
        start_pose=[float(v) for v in pose],
        f1tenth_gym_python=python,
        load_average_1min=[load_before, load_average()],
        pairs=rows,
        median_ratio_wall=round(wall, 3),
        median_ratio_cpu=round(cpu, 3),
        target_ratio=TARGET_RATIO,
    )
