"""Stable-Baselines3 on the native batch: :class:`RoboRacerVecEnv` is an SB3 ``VecEnv``
over ``gym.make_vec("RoboRacerArena-v0", vectorization_mode="vector_entry_point")`` (one
native simulator for all envs, no subprocesses). Needs ``pip install 'roboracer-arena[sb3]'``
(stable-baselines3, which brings torch).

    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecMonitor
    from roboracer_arena.integrations.sb3 import make_sb3_vec_env

    venv = VecMonitor(make_sb3_vec_env(16, track="gym-berlin", observation="normalise", action_mode="normalised"))
    PPO("MultiInputPolicy", venv).learn(200_000)

The SB3 conventions (``terminal_observation``, ``TimeLimit.truncated``, ``reset_infos``)
are produced by :class:`~.sb3_core.Sb3Translator` (numpy only). Seeding differs from
``DummyVecEnv``: ``seed(s)`` seeds env ``i`` from ``(s, i)`` as ``make_vec`` does (env i
sees the same episodes whatever ``num_envs``), not from ``s + i``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from stable_baselines3.common.vec_env.base_vec_env import VecEnv, VecEnvIndices

from .sb3_core import Sb3Translator


class RoboRacerVecEnv(VecEnv):
    """An SB3 ``VecEnv`` over a native RoboRacer vector env built with
    ``autoreset_mode=SAME_STEP`` (use :func:`make_sb3_vec_env`)."""

    def __init__(self, venv: Any) -> None:
        self._core = Sb3Translator(venv)
        self.venv = venv
        self._actions: np.ndarray | None = None
        super().__init__(venv.num_envs, venv.single_observation_space, venv.single_action_space)
        self.reset_infos = self._core.reset_infos

    def reset(self) -> dict[str, np.ndarray]:
        seed = self._seeds[0]  # seed(s) sets s, s+1, ...; the native env seeds env i from (s, i)
        options = self._options[0] or None
        obs = self._core.reset(seed=seed, options=options)
        self.reset_infos = self._core.reset_infos
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = actions

    def step_wait(self) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray, list[dict[str, Any]]]:
        if self._actions is None:
            raise RuntimeError("step_wait() called before step_async()")
        out = self._core.step(self._actions)
        self._actions = None
        self.reset_infos = self._core.reset_infos
        return out

    def close(self) -> None:
        self.venv.close()

    def get_images(self) -> Sequence[np.ndarray | None]:
        frames = self.venv.render()
        return list(frames) if frames is not None else [None] * self.num_envs

    # The envs live in one native batch: attributes and methods are the vector env's, and
    # each index reads the same one.
    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        value = getattr(self.venv, attr_name)
        return [value for _ in self._indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        setattr(self.venv, attr_name, value)

    def env_method(
        self, method_name: str, *method_args: Any, indices: VecEnvIndices = None, **kwargs: Any
    ) -> list[Any]:
        result = getattr(self.venv, method_name)(*method_args, **kwargs)
        return [result for _ in self._indices(indices)]

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None) -> list[bool]:
        return [False for _ in self._indices(indices)]

    def _indices(self, indices: VecEnvIndices) -> Iterable[int]:
        if indices is None:
            return range(self.num_envs)
        if isinstance(indices, int):
            return [indices]
        return indices


def make_sb3_vec_env(num_envs: int, env_id: str = "RoboRacerArena-v0", **kwargs: Any) -> RoboRacerVecEnv:
    """``gym.make_vec(env_id, num_envs, vectorization_mode="vector_entry_point",
    autoreset_mode=SAME_STEP, **kwargs)`` as an SB3 ``VecEnv``. ``kwargs`` are the env's
    (``track``, ``observation``, ``action_mode``, ``reward``, ``max_episode_steps``, ...)."""
    # env_id is registered: importing this module imported roboracer_arena, which registers it.
    if "autoreset_mode" in kwargs and kwargs["autoreset_mode"] not in (AutoresetMode.SAME_STEP, "SameStep"):
        raise ValueError("the SB3 adapter needs autoreset_mode=SAME_STEP (SB3 resets an env the step it ends)")
    kwargs["autoreset_mode"] = AutoresetMode.SAME_STEP
    venv = gym.make_vec(env_id, num_envs=num_envs, vectorization_mode="vector_entry_point", **kwargs)
    return RoboRacerVecEnv(venv)
