"""The gymnasium id this package registers, and where its env classes live.

A leaf that imports nothing of the package: ``import roboracer_arena`` registers the id
through it without loading the envs (the entry points are strings, loaded by
``gymnasium.make``). ``roboracer_arena.envs`` re-exports :data:`ENV_ID` and
:func:`register_envs`; a test checks that :data:`REGISTERED_MAX_EPISODE_STEPS` is the
env config's default limit (``tests/envs/test_learning_api.py``).
"""

from __future__ import annotations

ENV_ID = "RoboRacerArena-v0"
#: Steps the registry gives ``RoboRacerArena-v0``: ``EnvConfig``'s default time limit
#: (120 s) at its default control rate (20 Hz).
REGISTERED_MAX_EPISODE_STEPS: int = 2400


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
