"""Observation assembly for the batch engine: raw or normalised frames (see
:class:`~roboracer_arena.envs.env_config.ObservationConfig`), frame stacking and the
previous action. Normalised frames are the core's (``_core.ObservationNormaliser``,
``arena_core::sim::observation``): it writes them straight into the observation buffers,
so no Python arithmetic runs per step. Observation randomisation (lidar noise and
dropout) is drawn natively with the scan, from each env's own stream (see :mod:`.batch`).

A *frame* is computed once per env step (and at reset), so repeated reads of the same
step's observation (``obs`` and ``final_obs``) agree, noise included.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

from .._core import ObservationNormaliser
from .env_config import EnvConfig


class ObservationAssembler:
    """Frames of ``E`` envs x ``V`` vehicles, with history when ``frame_stack > 1``."""

    def __init__(
        self, config: EnvConfig, field_index: dict[str, int], num_envs: int, vehicles: int, num_beams: int
    ) -> None:
        cfg = self.cfg = config.observation
        self.config = config
        E, V, B = num_envs, vehicles, num_beams
        self.k = cfg.frame_stack
        self.fields = tuple(cfg.odometry)
        cols = [field_index[f] for f in self.fields]
        # Odometry columns that are one contiguous run of state columns (the default x .. steer)
        # are read as a slice: a view, copied once into the observation (no gather).
        run = bool(cols) and cols == list(range(cols[0], cols[0] + len(cols)))
        self.cols: slice | np.ndarray = slice(cols[0], cols[0] + len(cols)) if run else np.array(cols, np.intp)
        veh, lid = config.sim.vehicle, config.sim.lidar
        #: The core's normaliser (None for raw frames): it owns the scales and the columns.
        self.norm = (
            ObservationNormaliser(
                self.fields,
                position_scale=cfg.position_scale,
                horizon=cfg.horizon,
                range_max=lid.range_max,
                max_speed=veh.max_speed,
                max_steer=veh.max_steer,
            )
            if cfg.normalise
            else None
        )
        #: Names of the columns of obs["odometry"] (yaw becomes yaw_sin, yaw_cos when normalised).
        self.columns: tuple[str, ...] = self.fields if self.norm is None else self.norm.columns
        #: What each normalised column was divided by (for :meth:`odometry_raw`).
        self._column_scale = {} if self.norm is None else dict(zip(self.columns, self.norm.column_scales))
        self.range_max = float(lid.range_max)
        self.scan_high = 1.0 if cfg.normalise else self.range_max
        K = len(self.columns)
        stack = (self.k,) if self.k > 1 else ()
        self.buf: dict[str, np.ndarray] = {}
        if cfg.scan:
            self.buf["scan"] = np.zeros((E, V, *stack, B), np.float32)
        if self.fields:
            self.buf["odometry"] = np.zeros((E, V, *stack, K), np.float32)
        if cfg.previous_action:
            self.buf["previous_action"] = np.zeros((E, V, *stack, 2), np.float32)
        #: Raw scans without history: the batch lets the simulator write into buf["scan"].
        self.shares_scan = cfg.scan and self.k == 1 and not cfg.normalise
        self._views = {k: v[0, 0] for k, v in self.buf.items()}
        #: (observation buffer, state view) pairs a step's refresh copies, when every key of
        #: the frame is a plain copy of the batch's state (one raw frame, no previous
        #: action); set by :meth:`bind`.
        self._copies: list[tuple[np.ndarray, np.ndarray]] | None = None
        self._view_items = list(self._views.items())

    # ------------------------------------------------------------------ spaces
    def space(self, lead: tuple[int, ...], action_space: spaces.Box) -> spaces.Dict:
        """Observation space of one env (``lead`` = () or (V,))."""
        stack = (self.k,) if self.k > 1 else ()
        out: dict[str, spaces.Space] = {}
        if "scan" in self.buf:
            out["scan"] = spaces.Box(
                0.0, self.scan_high, shape=(*lead, *stack, self.buf["scan"].shape[-1]), dtype=np.float32
            )
        if "odometry" in self.buf:
            shape = (*lead, *stack, len(self.columns))
            hi = np.broadcast_to(self._odometry_high(), shape).astype(np.float32)
            out["odometry"] = spaces.Box(-hi, hi, dtype=np.float32)
        if "previous_action" in self.buf:
            lo = np.broadcast_to(
                action_space.low.reshape(*lead, 2)[..., None, :] if stack else action_space.low.reshape(*lead, 2),
                (*lead, *stack, 2),
            )
            hi2 = np.broadcast_to(
                action_space.high.reshape(*lead, 2)[..., None, :] if stack else action_space.high.reshape(*lead, 2),
                (*lead, *stack, 2),
            )
            out["previous_action"] = spaces.Box(lo.astype(np.float32), hi2.astype(np.float32), dtype=np.float32)
        return spaces.Dict(out)

    def _odometry_high(self) -> np.ndarray:
        """Per-column bound: the core's clip (1, the position unbounded) when normalised."""
        if self.norm is None:
            return np.full(len(self.columns), np.inf)
        return np.array(self.norm.column_bounds)

    # ------------------------------------------------------------------ per episode / per step
    def refresh(self, batch: Any, mask: np.ndarray | None = None) -> None:
        """Compute the current frame from the batch buffers: of every env, pushed into its
        history (a step: ``mask`` None), or of the envs where ``mask`` is True, filling
        their whole history (a reset)."""
        if mask is None and self._copies is not None:
            # Raw single frames of every env (each step): straight copies between views.
            for dst, src in self._copies:
                np.copyto(dst, src, casting="same_kind")
            return
        envs = slice(None) if mask is None else np.flatnonzero(mask)
        if mask is None and self.k > 1:  # age the history: the newest frame slot is rewritten below
            for buf in self.buf.values():
                buf[:, :, :-1] = buf[:, :, 1:]
        self._write_frame(batch, envs, mask)
        if mask is not None and self.k > 1:  # a reset's history is its first frame, repeated
            for buf in self.buf.values():
                buf[envs, :, :-1] = buf[envs, :, -1:]

    def bind(self, state: np.ndarray) -> None:
        """Use ``state`` (the batch's (E, V, S) state buffer, fixed for its lifetime) for
        the step refresh's direct copies, when the frame is only raw copies of it."""
        plain = self.k == 1 and not self.cfg.normalise and not self.cfg.previous_action
        view = isinstance(self.cols, slice)  # (a gather would copy once, then go stale)
        if plain and view and (self.shares_scan or not self.cfg.scan):
            self._copies = [(self.buf["odometry"], state[..., self.cols])] if self.fields else []

    def observation_one(self) -> dict[str, np.ndarray]:
        """Fresh copies of env 0, vehicle 0's observation (what the single env returns)."""
        return {k: v.copy() for k, v in self._view_items}

    def observation(self, envs: Any) -> dict[str, np.ndarray]:
        """Fresh copies of the observation of ``envs``, shapes (e, V, ...)."""
        return {k: v[envs].copy() for k, v in self.buf.items()}

    def _write_frame(self, batch: Any, envs: Any, mask: np.ndarray | None) -> None:
        """Write the current frame of ``envs`` (the envs where ``mask`` is True, or all
        when it is None) into the newest frame slot of each buffer."""
        cfg, norm = self.cfg, self.norm
        newest = (envs, slice(None), -1) if self.k > 1 else (envs,)
        if cfg.scan and not self.shares_scan:  # (a shared scan is already in place)
            if norm is not None:  # batch.scans stays in metres
                norm.scan(batch.scans, self.buf["scan"], mask)
            else:
                self.buf["scan"][newest] = batch.scans[envs]
        if self.fields:
            if norm is not None:
                norm.odometry(batch.state, batch.start_pose, self.buf["odometry"], mask)
            else:  # (a view when the columns are a run: one float64 -> float32 copy)
                self.buf["odometry"][newest] = batch.state[envs][..., self.cols]
        if cfg.previous_action:
            reset = mask is not None
            self.buf["previous_action"][newest] = 0.0 if reset else batch.from_ackermann(batch.actions[envs])

    def odometry_raw(self, odo: np.ndarray, start: np.ndarray) -> np.ndarray:
        """Invert the normalisation for the newest frame: (..., V, K) SI columns, map frame.
        ``odo`` is (V, [k,] K') or (E, V, [k,] K'); ``start`` the matching start poses."""
        if self.k > 1:
            odo = odo[..., -1, :]
        if not self.cfg.normalise:
            return odo
        start = np.broadcast_to(start, (*odo.shape[:-1], 3))
        c0, s0 = np.cos(start[..., 2]), np.sin(start[..., 2])
        col = {name: odo[..., i] for i, name in enumerate(self.columns)}
        out = []
        for f in self.fields:
            if f in ("x", "y"):
                fx = col.get("x", np.zeros_like(c0)) * self.cfg.position_scale
                fy = col.get("y", np.zeros_like(c0)) * self.cfg.position_scale
                out.append(start[..., 0] + fx * c0 - fy * s0 if f == "x" else start[..., 1] + fx * s0 + fy * c0)
            elif f == "yaw":
                yaw = np.arctan2(col["yaw_sin"], col["yaw_cos"]) + start[..., 2]
                out.append(np.arctan2(np.sin(yaw), np.cos(yaw)))
            else:
                out.append(col[f] * self._column_scale[f])
        return np.stack(out, axis=-1)
