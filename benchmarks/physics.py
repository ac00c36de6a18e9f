"""``python -m benchmarks physics``: the wheel's ``roboracer-arena bench physics``
(vehicle-steps/s of the native simulator, lidar off) with the paper's Isaac Sim figures
beside ours."""

from __future__ import annotations

from roboracer_arena.bench import physics
from roboracer_arena.bench.physics import PhysicsResult

#: Paper (Isaac Sim, AMD EPYC 9654 + RTX PRO 6000): vehicle-steps/s by vehicle count.
PAPER = {1: 28.1, 256: 8707.0, 1024: 8368.0, 2048: 6818.0}


def register(kinds) -> None:
    physics.register(kinds, paper=PAPER)


def run_quick() -> PhysicsResult:
    return physics.run_quick(paper=PAPER)
