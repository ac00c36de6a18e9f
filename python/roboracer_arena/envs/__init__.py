"""Simulation environments: native simulator configuration (:mod:`.config`) and the
gymnasium ``RoboRacerArena-v0`` env / vector env built on ``_core.Simulator``.

``import roboracer_arena`` registers ``RoboRacerArena-v0`` with gymnasium, so
``gymnasium.make("RoboRacerArena-v0", track=...)`` and
``gymnasium.make_vec("RoboRacerArena-v0", num_envs=N, vectorization_mode="vector_entry_point", ...)``
work; ``gymnasium.make("roboracer_arena:RoboRacerArena-v0", ...)`` works without it.
"""

from ..sim_config import LidarConfig, PhysicsConfig, SimConfig, VehicleConfig
from .episode_limit import REGISTERED_MAX_EPISODE_STEPS

ENV_ID = "RoboRacerArena-v0"


def register_envs() -> None:
    """Register ``RoboRacerArena-v0`` (single and vector entry points) with gymnasium; idempotent."""
    from gymnasium.envs.registration import register, registry

    if ENV_ID not in registry:
        register(
            id=ENV_ID,
            entry_point="roboracer_arena.envs.single:RoboRacerEnv",
            vector_entry_point="roboracer_arena.envs.vector:RoboRacerVectorEnv",
            max_episode_steps=REGISTERED_MAX_EPISODE_STEPS,
            disable_env_checker=False,
        )


def __getattr__(name: str):
    lazy = {
        "EnvConfig": "env_config",
        "ObservationConfig": "env_config",
        "RewardConfig": "env_config",
        "RoboRacerEnv": "single",
        "RoboRacerVectorEnv": "vector",
        "resolve_tracks": "tracks",
    }
    if name == "Track":  # defined in the neutral roboracer_arena.track
        from ..track import Track

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
