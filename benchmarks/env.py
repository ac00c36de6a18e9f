"""``python -m benchmarks env``: the wheel's ``roboracer-arena bench env`` (gymnasium step
throughput, full lidar every 0.01 s step) with F1TENTH Gym's figure beside ours."""

from __future__ import annotations

from roboracer_arena.bench import env
from roboracer_arena.bench.env import EnvResult

#: F1TENTH Gym, env-steps/s: constant action, Spielberg, 1080 beams, 0.01 s (issue 14).
F1TENTH_GYM = (5264.0, 5476.0)


def register(kinds) -> None:
    env.register(kinds, reference=F1TENTH_GYM)


def run_quick() -> EnvResult:
    return env.run_quick(reference=F1TENTH_GYM)
