"""Simulation environments: native simulator configuration (:mod:`.config`) and the
gymnasium ``RoboRacerArena-v0`` env / vector env built on ``_core.Simulator``.

``import roboracer_arena`` registers ``RoboRacerArena-v0`` with gymnasium, so
``gymnasium.make("RoboRacerArena-v0", track=...)`` and
``gymnasium.make_vec("RoboRacerArena-v0", num_envs=N, vectorization_mode="vector_entry_point", ...)``
work; ``gymnasium.make("roboracer_arena:RoboRacerArena-v0", ...)`` works without it.
"""

from ..config.sim import LidarConfig, PhysicsConfig, SimConfig, VehicleConfig
from ..registration import ENV_ID, register_envs


def __getattr__(name: str):
    lazy = {
        "EnvConfig": "env_config",
        "ObservationConfig": "env_config",
        "RewardConfig": "env_config",
        "RoboRacerEnv": "single",
        "RoboRacerVectorEnv": "vector",
        "resolve_tracks": "track_argument",
    }
    if name == "Track":  # defined in the neutral roboracer_arena.track.drivable
        from ..track.drivable import Track

        return Track
    if name in lazy:
        from importlib import import_module

        return getattr(import_module(f"{__name__}.{lazy[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "ENV_ID",
    "EnvConfig",
    "LidarConfig",
    "ObservationConfig",
    "PhysicsConfig",
    "RewardConfig",
    "RoboRacerEnv",
    "RoboRacerVectorEnv",
    "SimConfig",
    "Track",
    "VehicleConfig",
    "register_envs",
    "resolve_tracks",
]
