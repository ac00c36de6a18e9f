"""One episode limit for ``RoboRacerArena-v0``, whichever way the env is made.

* ``RoboRacerEnv(...)`` / ``RoboRacerVectorEnv(...)`` directly: ``time_limit_s`` (default
  120 s) truncates the episode; ``spec.max_episode_steps`` (when a spec is attached)
  reports the same number of steps.
* ``gymnasium.make(ID)``: the registered ``max_episode_steps``
  (:data:`REGISTERED_MAX_EPISODE_STEPS`, 120 s at the default 20 Hz) or the one passed
  to ``make`` is the limit, applied by gymnasium's ``TimeLimit``; the env then does not
  truncate by itself, so a longer ``max_episode_steps`` really gives longer episodes.
  ``time_limit_s`` is refused there (two limits could not agree); ``max_episode_steps=-1``
  means no limit.
* ``gymnasium.make_vec(ID, vectorization_mode="vector_entry_point")``: the vector env
  receives ``max_episode_steps`` (the registered one unless given) and truncates itself at
  it; an explicit ``time_limit_s`` wins over the registered default, and one that
  contradicts an explicit ``max_episode_steps`` is refused. ``spec.max_episode_steps``
  is set to the limit the env applies.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..errors import ConfigError
from ..registration import REGISTERED_MAX_EPISODE_STEPS
from .env_config import EnvConfig


def time_limit_given(kwargs: Mapping[str, Any]) -> bool:
    """Whether env kwargs set ``time_limit_s`` explicitly (directly or inside ``config``)."""
    if "time_limit_s" in kwargs:
        return True
    config = kwargs.get("config")
    if isinstance(config, EnvConfig):
        return "time_limit_s" in config.model_fields_set
    return isinstance(config, Mapping) and "time_limit_s" in config


def vector_config(config: EnvConfig, max_episode_steps: int | None, explicit_time_limit: bool) -> EnvConfig:
    """The config of a vector env given make_vec's ``max_episode_steps`` (see module docstring)."""
    if max_episode_steps is None:
        return config
    steps = None if max_episode_steps == -1 else int(max_episode_steps)
    if steps is not None and steps < 1:
        raise ConfigError(f"max_episode_steps must be >= 1 or -1 (no limit), got {max_episode_steps}")
    if explicit_time_limit:
        if steps in (None, REGISTERED_MAX_EPISODE_STEPS) or steps == config.max_episode_steps:
            return config
        raise ConfigError(
            f"max_episode_steps={steps} contradicts time_limit_s={config.time_limit_s} "
            f"({config.max_episode_steps} steps); give one of them"
        )
    return EnvConfig.build(config, time_limit_s=None if steps is None else steps * config.control_dt)


def check_make_kwargs(kwargs: Mapping[str, Any]) -> None:
    """Refuse ``time_limit_s`` under ``gymnasium.make`` (its TimeLimit is the limit there)."""
    if time_limit_given(kwargs):
        raise ConfigError(
            "time_limit_s cannot be used with gymnasium.make: pass max_episode_steps=N "
            "(steps; -1 for no limit) to make, or construct RoboRacerEnv(...) directly"
        )
