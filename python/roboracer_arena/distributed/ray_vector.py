"""``RayVectorEnv``: a gymnasium ``VectorEnv`` whose environments live in Ray actors, each
actor holding ONE native batch (``gym.make_vec(..., vectorization_mode="vector_entry_point")``,
i.e. :class:`~roboracer_arena.envs.vector.RoboRacerVectorEnv`).

Actor ``a`` holds environments ``a * m .. a * m + m - 1`` (``m = envs_per_actor``) and is
built with ``env_index_offset = a * m``, so ``reset(seed=s)`` gives environment ``i`` the
RNG ``default_rng([s, i])`` exactly as one local vector env of ``num_actors * m``
environments does: same spaces, same autoreset mode and semantics (each actor applies
them to its own slice), same episodes for the same seed and actions (noise-free lidar,
the default; see the vector env's docstring).

``step`` sends each actor its slice of the action array in one call, waits for all, and
concatenates the arrays: the cost per step is one round trip per actor, not per env.
"""

from __future__ import annotations

import math
import pickle
import sys
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import VectorEnv
from gymnasium.vector.utils import batch_space

from ..envs import ENV_ID
from ..envs.track_pool import check_track_names
from .ray_cluster import connect, import_ray
from .ray_fit import check_actors_fit, check_cluster_fits, local_cpus

#: Ray returns a result smaller than its direct-call limit (100 KiB by default) inline in
#: the reply and a larger one through the object store, a slower path for every step (64
#: envs x 1081 beams is 277 KB). ``step`` therefore returns its pickled result in pieces
#: below this size; the driver joins and unpickles them (``bench ray`` measures the step).
INLINE_BYTES = 90_000


class BatchWorker:
    """Body of one actor: a native vector env of ``num_envs`` environments numbered from
    ``offset`` (used through ``ray.remote``; plain class so it imports without Ray)."""

    def __init__(self, num_envs: int, offset: int, env_kwargs: dict[str, Any]) -> None:
        # ENV_ID is registered: the actor imported this module, hence roboracer_arena.
        self.env = gym.make_vec(
            ENV_ID, num_envs=num_envs, vectorization_mode="vector_entry_point", env_index_offset=offset, **env_kwargs
        )

    def describe(self) -> dict[str, Any]:
        e = self.env
        return {
            "single_observation_space": e.single_observation_space,
            "single_action_space": e.single_action_space,
            "metadata": e.metadata,
            "max_episode_steps": getattr(e.spec, "max_episode_steps", None),
            "render_mode": e.render_mode,
        }

    def reset(self, seed: int | None, options: dict[str, Any] | None) -> tuple[Any, Any]:
        return self.env.reset(seed=seed, options=options)

    def step(self, actions: np.ndarray) -> tuple[Any, ...]:
        return self.env.step(actions)

    def step_chunks(self, actions: np.ndarray, chunks: int) -> tuple[bytes, ...] | bytes:
        """:meth:`step`, its result pickled and cut into ``chunks`` pieces (see
        :data:`INLINE_BYTES`); one piece is returned bare (Ray's ``num_returns=1``)."""
        data = pickle.dumps(self.env.step(actions), protocol=pickle.HIGHEST_PROTOCOL)
        size = -(-len(data) // chunks)
        parts = tuple(data[i * size : (i + 1) * size] for i in range(chunks))
        return parts if chunks > 1 else parts[0]

    def get(self, name: str) -> Any:
        """An attribute of the native vector env (e.g. ``current_track_ids``)."""
        return getattr(self.env.unwrapped, name)

    def start_state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Track index, start poses and start speeds of each env's current episode."""
        env: Any = self.env.unwrapped
        return env.start_state()

    def render(self) -> Any:
        return self.env.render()

    def close(self) -> None:
        self.env.close()


def concat(parts: list[Any]) -> Any:
    """Join per-actor results along the env axis: dicts key by key, arrays with
    ``np.concatenate`` (object arrays too), so no Python loop over environments."""
    first = parts[0]
    if isinstance(first, dict):
        return {k: concat([p[k] for p in parts]) for k in first}
    if isinstance(first, np.ndarray):
        return np.concatenate(parts, axis=0)
    if isinstance(first, tuple):
        return tuple(x for p in parts for x in p)
    raise TypeError(f"cannot join per-actor results of type {type(first).__name__}")


class RayVectorEnv(VectorEnv):
    """``num_actors * envs_per_actor`` RoboRacer environments in ``num_actors`` Ray actors.

    ``env_kwargs`` are what ``gym.make_vec("RoboRacerArena-v0", ...)`` takes (``track=``,
    ``config=``, ``autoreset_mode=``, overrides); a catalog id or map path must resolve on
    every node. ``address`` is ``"auto"`` (a running cluster; the default unless Ray is
    already initialised in this process), ``"local"`` (start one on this machine) or
    ``"HOST:PORT"``; ``num_cpus_per_actor`` is the CPU share Ray reserves per actor, and the
    number of threads its native batch steps with. ``num_actors * num_cpus_per_actor``
    must fit the cluster's free CPUs: otherwise the constructor raises
    :class:`~roboracer_arena.errors.InvalidArgumentError` at once, saying what fits."""

    def __init__(
        self,
        num_actors: int,
        envs_per_actor: int,
        *,
        address: str | None = None,
        num_cpus_per_actor: float = 1.0,
        **env_kwargs: Any,
    ) -> None:
        if num_actors < 1 or envs_per_actor < 1:
            raise ValueError(f"num_actors and envs_per_actor must be >= 1, got {num_actors} and {envs_per_actor}")
        if "num_envs" in env_kwargs or "env_index_offset" in env_kwargs:
            raise ValueError("pass num_actors and envs_per_actor, not num_envs / env_index_offset")
        self.num_actors, self.envs_per_actor = int(num_actors), int(envs_per_actor)
        # First, before the track check's imports (seconds on a busy machine): the issue's
        # 8 x 256 request on 2 cores must fail within seconds, in one line.
        self._check_local_fit(address, float(num_cpus_per_actor))

        check_track_names(env_kwargs.get("track"))  # an unknown id: the local env's typed error, no actor started
        self._owns = self._connect_fitting(address, float(num_cpus_per_actor))
        ray = import_ray()
        self.num_envs = self.num_actors * self.envs_per_actor
        # The native batch's thread pool gets the CPUs Ray reserved for the actor, no more.
        threads = str(max(1, int(num_cpus_per_actor)))
        remote = ray.remote(num_cpus=num_cpus_per_actor, runtime_env={"env_vars": {"RAYON_NUM_THREADS": threads}})(
            BatchWorker
        )
        m = self.envs_per_actor
        self._actors = [remote.remote(m, a * m, env_kwargs) for a in range(self.num_actors)]
        try:
            d = ray.get([a.describe.remote() for a in self._actors])[0]
        except ray.exceptions.RayError as e:  # bad env_kwargs: re-raise the env's own error, kill the actors
            for a in self._actors:
                ray.kill(a)
            if self._owns:
                ray.shutdown()
            cause = getattr(e, "cause", None) or (
                e.as_instanceof_cause() if hasattr(e, "as_instanceof_cause") else None
            )
            raise (cause if isinstance(cause, Exception) else e) from None
        self.single_observation_space = d["single_observation_space"]
        self.single_action_space = d["single_action_space"]
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.metadata = dict(d["metadata"])
        self.autoreset_mode = self.metadata["autoreset_mode"]
        self.render_mode = d["render_mode"]
        self.max_episode_steps = d["max_episode_steps"]
        self._closed = False
        self._seeded = False
        self._chunks = 1

    def _check_local_fit(self, address: str | None, cpus: float) -> None:
        """With ``address="local"`` and no Ray running yet, check the actors fit this
        machine's CPUs before even importing Ray (seconds on a busy machine), let alone
        starting it (it can take tens of seconds)."""
        loaded = sys.modules.get("ray")
        if address == "local" and not (loaded is not None and loaded.is_initialized()):
            check_actors_fit(
                self.num_actors,
                cpus,
                local_cpus(),
                envs_per_actor=self.envs_per_actor,
                where="this machine (address='local')",
            )

    def _connect_fitting(self, address: str | None, cpus: float) -> bool:
        """Connect (see :func:`.ray_cluster.connect`) and fail at once, in one line, if the
        actors' CPUs do not fit the cluster: Ray would otherwise queue them forever."""
        n, m = self.num_actors, self.envs_per_actor
        ray = import_ray()
        owns = connect(address or "auto")
        try:
            check_cluster_fits(n, cpus, envs_per_actor=m)
        except Exception:
            if owns:
                ray.shutdown()
            raise
        return owns

    def _gather(self, refs: list[Any]) -> list[Any]:
        """``ray.get``; an actor's exception is raised as its own type (e.g. ValueError)."""
        ray = import_ray()
        try:
            return ray.get(refs)
        except ray.exceptions.RayTaskError as e:
            raise e.as_instanceof_cause() from None

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        if isinstance(seed, (list, tuple)):
            raise ValueError("pass one integer seed; environment i is seeded with (seed, i)")
        if seed is None and not self._seeded:
            # First reset unseeded: ONE entropy seed for all actors, as the local env draws one for all envs.
            seed = int(np.random.default_rng().integers(2**63))
        if seed is not None:
            self._seeded = True
            self._np_random_seed = int(seed)
            self._np_random = np.random.default_rng(seed)
        parts = [self._slice_options(options, a) for a in range(self.num_actors)]
        out = self._gather([actor.reset.remote(seed, o) for actor, o in zip(self._actors, parts)])
        return concat([o for o, _ in out]), concat([i for _, i in out])

    def step(self, actions: Any):
        a = np.asarray(actions)
        if a.shape[:1] != (self.num_envs,):
            raise ValueError(f"actions must have a leading axis of {self.num_envs} envs, got shape {a.shape}")
        k = self._chunks
        refs = [
            actor.step_chunks.options(num_returns=k).remote(c, k)
            for actor, c in zip(self._actors, np.split(a, self.num_actors))
        ]
        pieces = self._gather([r for ref in refs for r in (ref if k > 1 else [ref])])
        blobs = [b"".join(pieces[i * k : (i + 1) * k]) for i in range(self.num_actors)]
        # Pieces for the next step: the result size is fixed by the spaces (SAME_STEP's final
        # observations add to it on some steps; a larger result is still correct, only slower).
        self._chunks = max(1, math.ceil(max(len(b) for b in blobs) / INLINE_BYTES))
        out = [pickle.loads(b) for b in blobs]
        obs, rew, term, trunc, info = (concat(list(x)) for x in zip(*out))
        return obs, rew, term, trunc, info

    def _slice_options(self, options: dict[str, Any] | None, a: int) -> dict[str, Any] | None:
        """Actor ``a``'s share of reset options: per-env arrays (leading axis ``num_envs``:
        ``reset_mask``, ``track_ids``, ``poses``, ``speeds``) sliced, the rest as given."""
        if not options:
            return options
        lo, hi = a * self.envs_per_actor, (a + 1) * self.envs_per_actor
        out = {}
        for k, v in options.items():
            arr = None if v is None or isinstance(v, (str, bytes, dict)) else np.asarray(v)
            out[k] = arr[lo:hi] if arr is not None and arr.ndim >= 1 and len(arr) == self.num_envs else v
        return out

    # ------------------------------------------------------------------ tools
    @property
    def current_track_ids(self) -> np.ndarray:
        """Index of each environment's current track, (E,)."""
        return np.concatenate(self._gather([a.get.remote("current_track_ids") for a in self._actors]))

    def start_state(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Track indices (E,), start poses (E, V, 3) and start speeds (E, V) of the current episodes."""
        parts = self._gather([a.start_state.remote() for a in self._actors])
        return concat([p[0] for p in parts]), concat([p[1] for p in parts]), concat([p[2] for p in parts])

    def render(self) -> tuple[np.ndarray, ...] | None:
        if self.render_mode is None:
            return None
        return concat(self._gather([a.render.remote() for a in self._actors]))

    def close_extras(self, **kwargs: Any) -> None:
        if self._closed:
            return
        self._closed = True
        ray = import_ray()
        if ray.is_initialized():
            for a in self._actors:
                ray.kill(a)
            if self._owns:
                ray.shutdown()
