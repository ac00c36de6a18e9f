"""Several cars on one track as a multi-agent env: PettingZoo's ``ParallelEnv`` API.

``RoboRacerParallelEnv(track=..., vehicles_per_env=V, **env_kwargs)`` wraps one
:class:`~roboracer_arena.envs.single.RoboRacerEnv` with ``V`` vehicles. Agents are
``"car_0" .. "car_{V-1}"``; each has its own observation (its scan / odometry / previous
action, the single-vehicle spaces), action, reward (``info["vehicle_rewards"]``: its
own progress and penalties) and termination (``info["vehicle_terminated"]``: its own
contact or wrong-way end). As in PettingZoo, a terminated or truncated agent leaves
``agents``; its car stays in the world, parked (commanded to stop) until the episode
ends, which happens when no agent is left. Truncation is the env's episode limit
(``time_limit_s``), for every agent at once.

PettingZoo is optional (``pip install roboracer-arena[multiagent]``): with it installed
the class derives from ``pettingzoo.ParallelEnv``; without it, it has the same methods.
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np

try:  # optional dependency
    from pettingzoo import ParallelEnv as _Base
except ImportError:  # pragma: no cover - exercised where pettingzoo is absent
    _Base = object

from ..errors import ConfigError
from .single import RoboRacerEnv


class RoboRacerParallelEnv(_Base):
    """``V`` racing cars on one track, one agent each (see module docstring)."""

    metadata = {"name": "roboracer_arena_parallel_v0", "render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self, track: Any = None, vehicles_per_env: int = 2, render_mode: str | None = None, **env_kwargs: Any
    ) -> None:
        if vehicles_per_env < 2:
            raise ConfigError(f"vehicles_per_env must be >= 2 for a multi-agent env, got {vehicles_per_env}")
        self.env = RoboRacerEnv(track=track, vehicles_per_env=vehicles_per_env, render_mode=render_mode, **env_kwargs)
        self.render_mode = render_mode
        self.possible_agents = [f"car_{k}" for k in range(vehicles_per_env)]
        self.agents: list[str] = []
        self._index = {a: k for k, a in enumerate(self.possible_agents)}
        obs_space, act_space = self.env.observation_space, self.env.action_space
        from gymnasium import spaces

        # Per-agent spaces: the env's with the leading vehicle axis dropped (the env's
        # observation space is a Dict of Boxes, its action space a Box).
        def drop_vehicle_axis(s: spaces.Space) -> spaces.Box:
            box = cast(spaces.Box, s)
            return spaces.Box(box.low[0], box.high[0], dtype=box.dtype)

        self._obs_space = spaces.Dict({k: drop_vehicle_axis(s) for k, s in cast(spaces.Dict, obs_space).spaces.items()})
        self._act_space = drop_vehicle_axis(act_space)
        self._parked = self.env.from_ackermann(np.zeros((vehicles_per_env, 2)))[0]

    def observation_space(self, agent: str) -> Any:
        """The same space object for every agent (PettingZoo wants a stable object per agent)."""
        return self._obs_space

    def action_space(self, agent: str) -> Any:
        """The same space object for every agent."""
        return self._act_space

    def reset(self, seed: int | None = None, options: dict | None = None) -> tuple[dict, dict]:
        obs, info = self.env.reset(seed=seed, options=options)
        if seed is not None:
            for k, a in enumerate(self.possible_agents):
                self.action_space(a).seed(seed + k)
        self.agents = list(self.possible_agents)
        return self._split(obs), self._infos(info)

    def step(self, actions: dict[str, Any]) -> tuple[dict, dict, dict, dict, dict]:
        act = np.tile(self._parked, (len(self.possible_agents), 1))
        for a, value in actions.items():
            if a in self.agents:
                act[self._index[a]] = np.asarray(value, dtype=np.float32)
        obs, _, _, truncated, info = self.env.step(act)
        ended = info["vehicle_terminated"]
        live = list(self.agents)
        rewards = {a: float(info["vehicle_rewards"][self._index[a]]) for a in live}
        terms = {a: bool(ended[self._index[a]]) for a in live}
        truncs = {a: bool(truncated) for a in live}
        obs_d, infos = self._split(obs, live), self._infos(info, live)
        self.agents = [a for a in live if not (terms[a] or truncs[a])]
        return obs_d, rewards, terms, truncs, infos

    def render(self) -> Any:
        return self.env.render()

    def close(self) -> None:
        self.env.close()

    def state(self) -> np.ndarray:
        """The raw simulator state of all cars, (V, S)."""
        return self.env.simulator_state[0]

    # ------------------------------------------------------------------ helpers
    def _split(self, obs: dict[str, np.ndarray], agents: list[str] | None = None) -> dict[str, dict]:
        return {a: {k: v[self._index[a]] for k, v in obs.items()} for a in (agents or self.agents)}

    def _infos(self, info: dict[str, Any], agents: list[str] | None = None) -> dict[str, dict]:
        out = {}
        for a in agents or self.agents:
            k = self._index[a]
            out[a] = {
                key: (v[k] if isinstance(v, np.ndarray) and v.ndim >= 1 and len(v) == len(self.possible_agents) else v)
                for key, v in info.items()
            }
        return out
