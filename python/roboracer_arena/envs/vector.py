"""Native vector env: ``num_envs`` RoboRacer environments on ONE batched
``_core.Simulator`` (rayon-parallel, GIL released), not Sync/AsyncVectorEnv.

Autoreset mode (``metadata["autoreset_mode"]``), chosen with ``autoreset_mode=``:

* **NEXT_STEP** (default, like gymnasium's own vector envs, and the only mode gymnasium's
  vector observation wrappers accept): the step that ends an episode returns its last
  observation; the *next* step resets that environment, ignores its action and returns
  the first observation of the new episode with reward 0 and ``terminated = truncated =
  False``.
* **SAME_STEP**: the step that ends an episode resets the environment before returning;
  the returned observation is the new episode's first, ``infos["final_obs"]`` (object
  array, ``None`` elsewhere) and ``infos["final_info"]`` hold the last ones, with
  ``_final_obs`` / ``_final_info`` masks.
* **DISABLED**: nothing resets by itself. An environment whose episode ended keeps being
  stepped by the batched simulator (its results are meaningless) until the caller resets
  it with ``reset(options={"reset_mask": mask})``; use this for episodic evaluation and
  ignore finished environments. (The native batch has no masked step: the finished
  environments still cost simulation time.)

Open maps (``open=``, ``unknown=``, ``infos["open_map"]``) as in :mod:`.single`: walls
only, no laps or progress, episodes end on a collision or the time limit.

``reset(options=...)`` also takes ``"track_ids"`` ((E,) ints) or ``"track_id"`` (one int)
and ``"poses"`` ((E, V, 3) or (E, 3)); see :mod:`.reset_options`. The episode limit is the
one of :mod:`.episode_limit`; ``spec.max_episode_steps`` reports it.

Only the reset environments are re-observed (a masked native reset and observe), so an
autoreset costs the envs it resets, and no other environment's noise stream moves.

Seeding: ``reset(seed=s)`` reseeds the simulator with ``s``; environment ``i`` draws its
tracks, start poses, speeds and lidar noise from its own native streams seeded from
``(s, i)``, so environment ``i`` sees the same episodes, bit for bit and lidar noise
included, whatever ``num_envs``, the thread count or the other environments' resets. ``env_index_offset=k``
numbers the environments ``k, k+1, ...`` for those streams: a batch that is a slice of a
larger one (e.g. one actor of :class:`~roboracer_arena.distributed.RayVectorEnv`) sees
exactly the episodes of that slice.
"""

from __future__ import annotations

from typing import Any, cast

import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from .._core import Simulator
from .batch import EnvHelpers, SimBatch
from .env_config import EnvConfig
from .episode_limit import time_limit_given, vector_config
from .reset_options import reset_mask, reset_options
from .track_pool import resolve_track_pool


class RoboRacerVectorEnv(EnvHelpers, VectorEnv):
    """Batched RoboRacer environments (see module docstring); spaces as in
    :class:`~roboracer_arena.envs.single.RoboRacerEnv` with a leading env axis."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20, "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        num_envs: int = 1,
        track: Any = None,
        config: EnvConfig | dict | None = None,
        render_mode: str | None = None,
        corridor_params: Any = None,
        render_size: int = 400,
        max_episode_steps: int | None = None,
        autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
        env_index_offset: int = 0,
        open: bool | None = None,
        unknown: str = "occupied",
        close_gaps: float | None = None,
        **overrides: Any,
    ) -> None:
        if num_envs < 1:
            raise ValueError(f"num_envs must be >= 1, got {num_envs}")
        if env_index_offset < 0:
            raise ValueError(f"env_index_offset must be >= 0, got {env_index_offset}")
        self._env_offset = int(env_index_offset)
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be one of {self.metadata['render_modes']}, got {render_mode!r}")
        explicit = time_limit_given({**overrides, "config": config})
        self.config = vector_config(EnvConfig.build(config, **overrides), max_episode_steps, explicit)
        self.tracks, probs = resolve_track_pool(
            track, corridor_params, reverse=self.config.reverse, open=open, unknown=unknown, close_gaps=close_gaps
        )
        self.num_envs = int(num_envs)
        self._batch = SimBatch(
            self.tracks, self.num_envs, self.config, seed=0, track_probs=probs, env_index_offset=self._env_offset
        )
        self.single_observation_space, self.single_action_space = self._batch.single_spaces()
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.render_mode = render_mode
        mode = _autoreset_mode(autoreset_mode)
        if mode is None:
            raise ValueError(f"autoreset_mode must be NEXT_STEP, SAME_STEP or DISABLED, got {autoreset_mode!r}")
        self.autoreset_mode = mode
        self._autoreset = np.zeros(self.num_envs, bool)
        self.metadata = {**self.metadata, "render_fps": self.config.control_rate_hz, "autoreset_mode": mode}
        self._render_size = render_size
        self._view: Any = None
        self._squeeze = self.config.vehicles_per_env == 1
        self._seeded = False
        self._all = np.ones(self.num_envs, bool)
        self._spec: Any = None
        self._track_names = np.array([t.name for t in self.tracks], dtype=object)

    @property
    def spec(self) -> Any:
        """The EnvSpec, its ``max_episode_steps`` the limit this env applies."""
        return self._spec

    @spec.setter
    def spec(self, value: Any) -> None:
        if value is not None:
            from dataclasses import replace

            value = replace(value, max_episode_steps=self.config.max_episode_steps)
        self._spec = value

    def reset(self, *, seed: int | list[int] | None = None, options: dict[str, Any] | None = None):
        if isinstance(seed, (list, tuple)):
            raise ValueError("pass one integer seed; environment i is seeded with (seed, i)")
        if seed is None and not self._seeded:
            entropy = cast(int, np.random.SeedSequence().entropy)  # fresh from the OS: always an int
            seed = int(entropy % (2**63))
        if seed is not None:
            self._np_random_seed = int(seed)
            self._np_random = np.random.default_rng(seed)
            self._seeded = True
            self._batch.rebuild(int(seed))
        given = reset_mask(options, self.num_envs)
        mask = self._all if given is None else given
        track_ids, poses, speeds = reset_options(
            options, self.num_envs, self.vehicles_per_env, len(self.tracks), single=False
        )
        self._batch.reset(mask, track_ids, poses, speeds)
        self._autoreset &= ~mask
        return self._obs(), self._info()

    def step(self, actions: Any):
        b = self._batch
        b.set_actions(actions)
        # Views of the core's episode buffers: a reset rewrites the reset envs' rows.
        reward, terminated, truncated = b.step()
        infos: dict[str, Any] = {}
        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            pending = self._autoreset
            if pending.any():  # episodes that ended last step start now; their action was moot
                b.reset(pending)  # their rows now read reward 0, not terminated or truncated
            self._autoreset = terminated | truncated
        elif self.autoreset_mode == AutoresetMode.SAME_STEP:
            done = terminated | truncated
            if done.any():
                # The ending step's results, before the reset rewrites those rows.
                reward, terminated, truncated = reward.copy(), terminated.copy(), truncated.copy()
                idx = np.flatnonzero(done)
                final_obs = np.full(self.num_envs, None, dtype=object)
                last = self._obs(idx)
                for j, e in enumerate(idx):
                    final_obs[e] = {k: v[j] for k, v in last.items()}
                final_info = self._masked(self._info(), done)
                b.reset(done)
                infos = {
                    "final_obs": final_obs,
                    "_final_obs": done.copy(),
                    "final_info": final_info,
                    "_final_info": done.copy(),
                }
        infos.update(self._info())
        return self._obs(), reward.copy(), terminated.copy(), truncated.copy(), infos

    def render(self) -> tuple[np.ndarray, ...] | None:
        if self.render_mode != "rgb_array":
            return None
        if self._view is None:
            from ..render.sim_view import SimView

            self._view = SimView(self.tracks, self.config.sim, size=self._render_size)
        from ..render.sim_view import hud_lines

        b = self._batch
        scans = b.scans if self.config.observation.scan else [None] * self.num_envs
        return tuple(
            self._view.draw(int(b.track_ids[e]), b.state[e], b.field_index, scans[e], hud=hud_lines(b, e))
            for e in range(self.num_envs)
        )

    # ------------------------------------------------------------------ helpers
    def _obs(self, envs: Any = slice(None)) -> dict[str, np.ndarray]:
        obs = self._batch.observation(envs)
        return {k: v[:, 0] for k, v in obs.items()} if self._squeeze else obs

    def _info(self) -> dict[str, Any]:
        info = self._batch.info()
        if self._squeeze:
            info = {k: (v[:, 0] if v.ndim == 2 else v) for k, v in info.items()}
        info["track"] = self._track_names[info["track_id"]]  # the single env's "track", per env
        return self._masked(info, self._all)

    @staticmethod
    def _masked(info: dict[str, Any], mask: np.ndarray) -> dict[str, Any]:
        """Add gymnasium's ``_key`` masks (one shared read-only array for all keys)."""
        mask = mask.copy()
        mask.flags.writeable = False
        out = dict(info)
        for k in info:
            out[f"_{k}"] = mask
        return out

    # ------------------------------------------------------------------ drivers, tools
    @property
    def current_track_ids(self) -> np.ndarray:
        """Index (into :attr:`tracks`) of each environment's current track, (E,)."""
        return self._batch.track_ids.copy()

    def start_state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Track index (E,), start poses (E, V, 3) and start speeds (E, V) of each environment's
        current episode (pass them back as reset options to replay the same starts)."""
        b = self._batch
        return b.track_ids.copy(), b.start_pose.copy(), b.start_speed.copy()

    @property
    def simulator(self) -> Simulator:
        """The native simulator (``_core.Simulator``) this env steps, for tools that read or
        drive it beside the env (the ROS 2 bridge). A reseeding ``reset`` builds a new one, so
        fetch it again after a reset; stepping it directly leaves the env's episode state behind.
        """
        return self._batch.sim

    @property
    def simulator_state(self) -> tuple[np.ndarray, dict[str, int]]:
        """The raw simulator state (E, V, S) of every env and the column of each field."""
        return self._batch.state.copy(), dict(self._batch.field_index)

    @property
    def simulator_scans(self) -> np.ndarray | None:
        """The latest raw lidar ranges (E, V, B) in metres (all beams, before any observation
        preset), or None when the observation has no scan."""
        return self._batch.scans.copy() if self.config.observation.scan else None

    def odometry_raw(self, obs: dict[str, np.ndarray]) -> np.ndarray:
        """``obs["odometry"]`` in SI units, shape (E, V, K), whatever the normalisation."""
        if "odometry" not in obs:
            raise ValueError("the observation has no odometry (ObservationConfig.odometry is empty)")
        odo = np.asarray(obs["odometry"])
        return self._batch.odometry_raw(odo[:, None] if self._squeeze else odo, slice(None))

    def from_ackermann(self, cmds: Any) -> np.ndarray:
        """``[steer rad, speed m/s]`` commands ((E, V, 2)) as an action of this vector env."""
        a = self._batch.from_ackermann(np.reshape(cmds, (self.num_envs, self.vehicles_per_env, 2)))
        return a[:, 0] if self._squeeze else a


def _autoreset_mode(value: AutoresetMode | str) -> AutoresetMode | None:
    """An AutoresetMode from the enum, its value ("NextStep") or its name ("next_step")."""
    if isinstance(value, AutoresetMode):
        return value
    for m in AutoresetMode:
        if str(value) in (m.value, m.name, m.name.lower()):
            return m
    return None
