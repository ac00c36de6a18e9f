"""``RoboRacerArena-v0``: one environment (one track, ``vehicles_per_env`` cars) as a
:class:`gymnasium.Env` on the native simulator.

Spaces (``V`` = vehicles per env; the vehicle axis is dropped when ``V == 1``):

* action: ``(V, 2)`` float32 — ``[steer rad, speed m/s]`` (``action_mode="ackermann"``) or
  both in [-1, 1] (``"normalised"``). NaN becomes 0 (straight, stop); ±inf and
  out-of-range values are clipped to the bounds. The observation never holds NaN.
* observation: ``Dict(scan=(V, B) ranges, odometry=(V, K))`` as configured in
  :class:`~roboracer_arena.envs.env_config.ObservationConfig`.
* reward: progress along the centreline (m) minus a stall cost (per second below
  ``stall_speed`` m/s of progress), a collision penalty (and time and wrong-way penalties
  if set; see :class:`~.env_config.RewardConfig`), summed over the env's vehicles; ``terminated`` on a contact (if
  ``collision_ends_episode``) or wrong-way driving (if ``wrong_way_ends_episode``),
  ``truncated`` at the episode limit (see :mod:`.episode_limit`).

Two semantics, stated per step in ``info["open_map"]``:

* a **track** (a map with a closed corridor, a catalog track, a circuit): laps, progress
  and wrong-way along the centreline, as above;
* an **open map** (a floor plan without a closed corridor, e.g. f1tenth_gym_ros's
  ``levine.yaml``; or any map with ``open=True``), simulated as F1TENTH Gym does: walls
  from every occupied region (unknown cells are walls, or floor with
  ``unknown="free"``), the same lidar and physics, and no reference path — ``progress``,
  ``laps`` and the progress reward stay 0, there is no wrong way, and an episode ends on
  a collision or the time limit. The start is ``reset(options={"poses": ...})`` (as
  f1tenth_gym_ros gives it) or the free cell farthest from the walls
  (``Track.start_pose``); ``env.tracks[i].open_reason`` says why a map is open.
  ``open=None`` (default) picks per map; ``open=False`` refuses open maps.
  ``close_gaps=W`` (m) closes the openings of a map's walls up to ``W`` wide first
  (doorways, sensor leaks; :mod:`roboracer_arena.maps.gaps`), so that a leaking loop becomes a
  track with laps; the track's ``source.closed_gaps`` lists every gap closed.

``reset(options=...)``: ``"track_id"`` (or ``"track_ids"``) picks a track of the list,
otherwise each reset draws one with the env's RNG (weighted for a track pool);
``"poses"`` ((V, 3) or (3,) x, y, yaw in the map frame) sets the start poses instead of
the configured start. ``reset(seed=s)`` reseeds the simulator, whose per-env streams draw
the track, start poses and speeds and the lidar noise; the same seed gives the same
episodes.

Several vehicles (``vehicles_per_env = V > 1``): the reward is the sum over vehicles and
``terminated`` says any vehicle ended; per-vehicle rewards are ``info["vehicle_rewards"]``
(V,) and per-vehicle ends ``info["vehicle_terminated"]`` (V,). :mod:`.multi_agent` wraps
this as a PettingZoo-style ParallelEnv.

Per-step layout (one vehicle): ``obs`` is a dict of fresh float32 arrays, ``scan``
(B,) in metres (raw config; the simulator writes it straight into the observation buffer)
and ``odometry`` (K,) in :attr:`odometry_index` order; ``info`` is a flat dict of Python
scalars: ``track_id``, ``track``, ``open_map``, ``progress``, ``contact_wall``, ``contact_vehicle``,
``lap_completed``, ``wrong_way``, ``laps``, ``lap_time``, ``last_lap_time``,
``progress_s``. The step is one native call (physics, scan and the core's episode step:
reward, ends, progress, wrong way); the Python around it reads the results as scalars,
so it is a few microseconds: no per-step validation, no arithmetic, no temporary arrays
beyond the returned observation copies.

Render modes: ``rgb_array``; ``gymnasium.make(..., render_mode="human")`` wraps it in
gymnasium's ``HumanRendering`` (needs pygame and a display).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np

from .._core import Simulator
from .batch import EnvHelpers, SimBatch
from .env_config import EnvConfig
from .episode_limit import check_make_kwargs
from .reset_options import reset_options
from .track_pool import resolve_track_pool


class RoboRacerEnv(EnvHelpers, gym.Env):
    """Single RoboRacer environment (see module docstring)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(
        self,
        track: Any = None,
        config: EnvConfig | dict | None = None,
        render_mode: str | None = None,
        corridor_params: Any = None,
        render_size: int = 600,
        open: bool | None = None,
        unknown: str = "occupied",
        close_gaps: float | None = None,
        **overrides: Any,
    ) -> None:
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode must be one of {self.metadata['render_modes']}, got {render_mode!r}")
        self.config = EnvConfig.build(config, **overrides)
        self.tracks, probs = resolve_track_pool(
            track, corridor_params, reverse=self.config.reverse, open=open, unknown=unknown, close_gaps=close_gaps
        )
        self._batch = SimBatch(self.tracks, 1, self.config, seed=0, track_probs=probs)
        self.observation_space, self.action_space = self._batch.single_spaces()
        self.render_mode = render_mode
        self.metadata = {**self.metadata, "render_fps": self.config.control_rate_hz}
        self._render_size = render_size
        self._view: Any = None
        self._squeeze = self.config.vehicles_per_env == 1
        self._spec: Any = None
        self._seeded = False
        self._one = np.ones(1, bool)

    @property
    def spec(self) -> Any:
        """The EnvSpec; ``max_episode_steps`` is the limit the env applies (see :mod:`.episode_limit`)."""
        if self._spec is None or self._batch.max_steps is None:
            return self._spec
        from dataclasses import replace

        return replace(self._spec, max_episode_steps=self._batch.max_steps)

    @spec.setter
    def spec(self, value: Any) -> None:
        # gymnasium.make attaches the spec and wraps a TimeLimit (its registered or given
        # max_episode_steps): that is then the one limit, so the env stops truncating itself.
        if value is not None and getattr(value, "id", None) and self._spec is None:
            check_make_kwargs(value.kwargs or {})
            self._batch.max_steps = None
        self._spec = value

    # ------------------------------------------------------------ gymnasium API
    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        if seed is None and not self._seeded:  # unseeded: a fresh random stream, as gymnasium does
            seed = int(self.np_random.integers(2**63))
        if seed is not None:
            self._batch.rebuild(seed)
            self._seeded = True
        track_ids, poses, speeds = reset_options(options, 1, self.vehicles_per_env, len(self.tracks), single=True)
        b = self._batch
        b.reset(self._one, track_ids, poses, speeds)
        return b.single_observation(), b.single_info()

    def step(self, action: Any):
        b = self._batch
        b.set_actions(action)
        reward, terminated, truncated = b.step()
        return b.single_observation(), reward.item(0), terminated.item(0), truncated.item(0), b.single_info()

    def render(self) -> np.ndarray | None:
        if self.render_mode != "rgb_array":
            return None
        if self._view is None:
            from ..render.sim_view import SimView

            self._view = SimView(self.tracks, self.config.sim, size=self._render_size)
        from ..render.sim_view import hud_lines

        b = self._batch
        return self._view.draw(
            int(b.track_ids[0]),
            b.state[0],
            b.field_index,
            b.scans[0] if self.config.observation.scan else None,
            hud=hud_lines(b, 0),
        )

    # ------------------------------------------------------------ helpers (drivers, tools)
    @property
    def current_track_id(self) -> int:
        """Index (into :attr:`tracks`) of the track of the current episode."""
        return int(self._batch.track_ids[0])

    def odometry_raw(self, obs: dict[str, np.ndarray]) -> np.ndarray:
        """``obs["odometry"]`` in SI units, shape (V, K), whatever the normalisation."""
        if "odometry" not in obs:
            raise ValueError("the observation has no odometry (ObservationConfig.odometry is empty)")
        odo = np.asarray(obs["odometry"])
        return self._batch.odometry_raw(odo[None] if self._squeeze else odo, 0)

    def from_ackermann(self, cmds: Any) -> np.ndarray:
        """``[steer rad, speed m/s]`` commands ((V, 2) or (2,)) as an action of this env."""
        a = self._batch.from_ackermann(np.reshape(cmds, (self.vehicles_per_env, 2)))
        return a[0] if self._squeeze else a

    @property
    def simulator(self) -> Simulator:
        """The native simulator (``_core.Simulator``) this env steps, for tools that read or
        drive it beside the env (the ROS 2 bridge). A reseeding ``reset`` builds a new one, so
        fetch it again after a reset; stepping it directly leaves the env's episode state behind.
        """
        return self._batch.sim

    @property
    def simulator_state(self) -> tuple[np.ndarray, dict[str, int]]:
        """The raw simulator state (V, S) of this env and the column of each field."""
        return self._batch.state[0].copy(), dict(self._batch.field_index)

    @property
    def simulator_scans(self) -> np.ndarray | None:
        """The latest raw lidar ranges (V, B) in metres (all beams, before any observation
        preset), or None when the observation has no scan."""
        return self._batch.scans[0].copy() if self.config.observation.scan else None
