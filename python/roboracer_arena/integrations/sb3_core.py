"""The numpy-only half of the Stable-Baselines3 adapter: it turns the native vector env's
gymnasium batch API into SB3's ``VecEnv`` conventions, without importing SB3 (or torch),
so the conversion is tested where SB3 is not installed.

SB3's conventions (those of its ``DummyVecEnv``), and where each comes from here:

* ``reset()`` returns only the observation; the infos go to ``reset_infos`` (one dict per env).
* ``step`` returns ``(obs, rewards float32 (E,), dones bool (E,), infos list of E dicts)``.
  A done env has already been reset (the native env runs ``AutoresetMode.SAME_STEP``):
  ``obs`` holds its new episode's first observation, ``infos[i]["terminal_observation"]``
  the last one (``final_obs``), ``infos[i]`` the episode's last step info (``final_info``)
  and ``reset_infos[i]`` the new episode's first.
* ``infos[i]["TimeLimit.truncated"]`` is True when the episode hit the time limit without
  terminating (so SB3 bootstraps its value).
* Each info dict holds every per-env key of the vector env (``track``, ``track_id``,
  ``progress``, ``lap_completed``, ``laps``, ``lap_time``, ...), as Python scalars.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode


class Sb3Translator:
    """Steps a native vector env (``AutoresetMode.SAME_STEP``) and returns SB3's tuples."""

    def __init__(self, venv: Any) -> None:
        mode = venv.metadata.get("autoreset_mode")
        if mode != AutoresetMode.SAME_STEP:
            raise ValueError(f"the SB3 adapter needs a vector env with autoreset_mode=SAME_STEP, got {mode}")
        self.venv = venv
        self.num_envs = int(venv.num_envs)
        self.reset_infos: list[dict[str, Any]] = [{} for _ in range(self.num_envs)]

    def reset(self, seed: int | None = None, options: dict[str, Any] | None = None) -> dict[str, np.ndarray]:
        """Reset every env (env ``i`` seeded from ``(seed, i)`` when ``seed`` is given)."""
        obs, info = self.venv.reset(seed=seed, options=options)
        self.reset_infos = _split(info, self.num_envs)
        return obs

    def step(self, actions: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray, np.ndarray, list[dict[str, Any]]]:
        """One step of every env in SB3's form (see the module docstring)."""
        obs, reward, terminated, truncated, info = self.venv.step(actions)
        dones = terminated | truncated
        infos = _split(info, self.num_envs)
        if dones.any():
            final_obs, final_info = info["final_obs"], _split(info["final_info"], self.num_envs)
            for i in np.flatnonzero(dones).tolist():
                self.reset_infos[i] = infos[i]  # the new episode's first info
                infos[i] = final_info[i]
                infos[i]["terminal_observation"] = final_obs[i]
                infos[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
        return obs, reward.astype(np.float32), dones, infos


def _split(info: dict[str, Any], n: int) -> list[dict[str, Any]]:
    """gymnasium's vector info (dict of (E, ...) arrays plus ``_key`` masks) as E dicts of
    Python values, leaving out the masks and the SAME_STEP ``final_*`` entries."""
    cols = {
        k: (v.tolist() if isinstance(v, np.ndarray) else list(v))
        for k, v in info.items()
        if not k.startswith("_") and k not in ("final_obs", "final_info")
    }
    return [{k: col[i] for k, col in cols.items()} for i in range(n)]
