"""RoboRacer Arena: any ROS occupancy map to a physics-ready 3D environment.

Public API (each name is documented where it is defined):

* :func:`load_map`, :func:`build_environment` -- map to USD stage and physics geometry
* :class:`TrackSpec`, :func:`generate_track` -- requirements to a validated map
* :func:`parse_request` -- natural-language request to a ``TrackSpec``
* :func:`load_policy` -- a trained policy file (``roboracer-arena train``)
* ``gymnasium.make("RoboRacerArena-v0", track=...)`` -- simulation

This package's face: it imports nothing of its own floors. Every name above loads on first
use (so ``import roboracer_arena`` stays fast, and a user who only parses requests never
imports pxr or the simulator), and the gym id is registered from the leaf
:mod:`.registration`, whose entry points are strings.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

from .registration import register_envs

# Gymnasium 1.x has no plugin entry points (removed in 1.0), so, as ale_py does, the
# package registers RoboRacerArena-v0 when it is imported: the one import-time effect.
register_envs()

#: Public name -> the module that defines it, imported on first use.
_LAZY = {
    "__version__": "roboracer_arena._core",
    "errors": "roboracer_arena.errors",
    "TrackSpec": "roboracer_arena.spec",
    "load_map": "roboracer_arena.maps.occupancy",
    "OccupancyMap": "roboracer_arena.maps.occupancy",
    "extract_corridor": "roboracer_arena.maps.corridor",
    "build_environment": "roboracer_arena.builder",
    "BuildConfig": "roboracer_arena.config.build",
    "BuildReport": "roboracer_arena.builder",
    "generate_track": "roboracer_arena.generate",
    "parse_request": "roboracer_arena.parse",
    "load_policy": "roboracer_arena.learn.policy_file",
}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'roboracer_arena' has no attribute {name!r}")
    if name == "errors":
        return import_module(module)
    return getattr(import_module(module), name)


def __dir__() -> list[str]:
    return sorted([*globals(), *_LAZY])


__all__ = [*_LAZY]
