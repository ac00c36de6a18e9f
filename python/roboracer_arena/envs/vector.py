"""Native vector env: ``num_envs`` RoboRacer environments on ONE batched
``_core.Simulator`` (rayon-parallel, GIL released), not Sync/AsyncVectorEnv.

Autoreset mode: **SAME_STEP**. When an environment terminates or truncates, ``step``
resets it before returning: the returned observation is the first one of its next
episode, ``infos["final_obs"]`` (object array, ``None`` elsewhere) holds the last one
and ``infos["final_info"]`` its info, both with ``_final_obs``/``_final_info`` masks.
Every action of every step is therefore used (no dead "reset" step), which keeps the
batch dense.

Seeding: ``reset(seed=s)`` gives environment ``i`` the RNG ``default_rng([s, i])`` for its
track and start-pose draws and reseeds the simulator with ``s``, so environment ``i``
sees the same episode whatever ``num_envs`` is.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from .batch import SimBatch
from .env_config import EnvConfig
from .tracks import resolve_tracks


class RoboRacerVectorEnv(VectorEnv):
    """Batched RoboRacer environments (see module docstring); spaces as in
    :class:`~roboracer_arena.envs.single.RoboRacerEnv` with a leading env axis."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20, "autoreset_mode": AutoresetMode.SAME_STEP}

    def __init__(
        self,
        num_envs: int = 1,
        track: Any = None,
        config: EnvConfig | dict | None = None,
        render_mode: str | None = None,
        corridor_params: Any = None,
        render_size: int = 400,
        max_episode_steps: int | None = None,
        **overrides: Any,
    ) -> None:
        if num_envs < 1:
            raise ValueError(f"num_envs must be >= 1, got {num_envs}")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be one of {self.metadata['render_modes']}, got {render_mode!r}")
        self.config = EnvConfig.build(config, **overrides)
        if max_episode_steps is not None:  # gymnasium.make_vec passes the spec's limit
            self.config = EnvConfig.build(self.config, time_limit_s=max_episode_steps * self.config.control_dt)
        self.tracks = resolve_tracks(track, corridor_params)
        self.num_envs = int(num_envs)
        self._batch = SimBatch(self.tracks, self.num_envs, self.config, seed=0)
        self.single_observation_space, self.single_action_space = self._batch.single_spaces()
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.render_mode = render_mode
        self.metadata = {**self.metadata, "render_fps": self.config.control_rate_hz}
        self._render_size = render_size
        self._view: Any = None
        self._squeeze = self.config.vehicles_per_env == 1
        self._rngs: list[np.random.Generator] = []
        self._all = np.ones(self.num_envs, bool)

    def reset(self, *, seed: int | list[int] | None = None, options: dict[str, Any] | None = None):
        if isinstance(seed, (list, tuple)):
            raise ValueError("pass one integer seed; environment i is seeded with (seed, i)")
        if seed is None and not self._rngs:
            seed = int(np.random.SeedSequence().entropy % (2**63))
        if seed is not None:
            self._np_random_seed = int(seed)
            self._np_random = np.random.default_rng(seed)
            self._rngs = [np.random.default_rng([int(seed), i]) for i in range(self.num_envs)]
            self._batch.rebuild(int(seed))
        mask = self._all
        if options and "reset_mask" in options:
            mask = np.asarray(options["reset_mask"], dtype=bool).reshape(self.num_envs)
        track_id = (options or {}).get("track_id")
        self._batch.reset(mask, self._rngs, None if track_id is None else int(track_id))
        return self._obs(), self._info()

    def step(self, actions: Any):
        b = self._batch
        b.set_actions(actions)
        reward, terminated, truncated, _ = b.step()
        done = terminated | truncated
        infos: dict[str, Any] = {}
        if done.any():
            idx = np.flatnonzero(done)
            final_obs = np.full(self.num_envs, None, dtype=object)
            last = self._obs(idx)
            for j, e in enumerate(idx):
                final_obs[e] = {k: v[j] for k, v in last.items()}
            final_info = self._masked(self._info(), done)
            b.reset(done, self._rngs)
            infos = {"final_obs": final_obs, "_final_obs": done.copy(), "final_info": final_info, "_final_info": done.copy()}
        infos.update(self._info())
        return self._obs(), reward.astype(np.float64), terminated.copy(), truncated.copy(), infos

    def render(self) -> tuple[np.ndarray, ...] | None:
        if self.render_mode != "rgb_array":
            return None
        if self._view is None:
            from ..render.sim_view import SimView

            self._view = SimView(self.tracks, self.config.sim, size=self._render_size)
        b = self._batch
        scans = b.scans if self.config.observation.scan else [None] * self.num_envs
        return tuple(self._view.draw(int(b.track_ids[e]), b.state[e], b.field_index, scans[e]) for e in range(self.num_envs))

    # ------------------------------------------------------------------ helpers
    def _obs(self, envs: Any = slice(None)) -> dict[str, np.ndarray]:
        obs = self._batch.observation(envs)
        return {k: v[:, 0] for k, v in obs.items()} if self._squeeze else obs

    def _info(self) -> dict[str, Any]:
        info = self._batch.info()
        if self._squeeze:
            info = {k: (v[:, 0] if v.ndim == 2 else v) for k, v in info.items()}
        return self._masked(info, self._all)

    @staticmethod
    def _masked(info: dict[str, Any], mask: np.ndarray) -> dict[str, Any]:
        out = dict(info)
        for k in info:
            out[f"_{k}"] = mask.copy()
        return out
