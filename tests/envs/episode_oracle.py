"""Test-only reference of the episode step (issue 24): the progress, reward, wrong-way,
termination and truncation arithmetic that ``envs/batch.py`` ran in numpy after the
core's step before the core took it over, kept here verbatim so that the core's
episode step can be held to it bit for bit.

It reads only what the simulator reports after each step (the ``travel`` and ``vx``
state columns and the event bits), as the Python did. One deliberate difference from the
old Python: a reset zeroes the reset env's per-vehicle rewards (the old batch left the
last step's values in ``info["vehicle_rewards"]`` on a next-step autoreset, next to the
reward 0 it returned).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from roboracer_arena.envs.env_config import EnvConfig

#: The event bits as the old Python declared them (the core's EVENT_* must agree).
CONTACT_WALL, CONTACT_VEHICLE, LAP_COMPLETED = 1, 2, 4
#: A step that loses more than this (m) of centreline progress counts as moving backwards.
BACKWARDS_EPS = 1e-3


@dataclass
class OracleStep:
    """One step's outputs: per env (E,) and per vehicle (E, V)."""

    reward: np.ndarray
    terminated: np.ndarray
    truncated: np.ndarray
    vehicle_rewards: np.ndarray
    vehicle_terminated: np.ndarray
    progress: np.ndarray
    wrong_way: np.ndarray


class EpisodeOracle:
    """The old ``SimBatch.step`` bookkeeping for ``num_envs`` x ``vehicles``."""

    def __init__(self, config: EnvConfig, num_envs: int, vehicles: int, max_steps: int | None) -> None:
        E, V = num_envs, vehicles
        self.config, self.max_steps = config, max_steps
        self.prev_s = np.zeros((E, V))
        self.progress = np.zeros((E, V))
        self.elapsed = np.zeros(E, np.int64)
        self.vehicle_rewards = np.zeros((E, V))
        self.best_progress = np.zeros((E, V))
        self.wrong_way = np.zeros((E, V), np.int8)
        self.vehicle_terminated = np.zeros((E, V), bool)
        self._stall_ds = config.reward.stall_speed * config.control_dt

    def reset(self, mask: np.ndarray, travel: np.ndarray) -> None:
        """Start new episodes in the envs of ``mask``; ``travel`` (E, V) after the reset."""
        idx = np.flatnonzero(mask)
        self.prev_s[idx] = travel[idx]
        self.progress[idx] = 0.0
        self.best_progress[idx] = 0.0
        self.wrong_way[idx] = 0
        self.vehicle_terminated[idx] = False
        self.vehicle_rewards[idx] = 0.0  # (the one difference, see the module docstring)
        self.elapsed[idx] = 0

    def step(self, travel: np.ndarray, vx: np.ndarray, events: np.ndarray) -> OracleStep:
        """The old arithmetic, from the state after a step: ``travel``, ``vx`` (E, V) and
        ``events`` (E, V) uint8."""
        s = travel
        ds = s - self.prev_s
        self.prev_s[:] = s
        self.progress += ds
        self.elapsed += 1
        r = self.config.reward
        vr = self.vehicle_rewards
        np.multiply(ds, r.progress, out=vr)
        if r.stall_penalty:
            vr -= (r.stall_penalty * self.config.control_dt) * (ds < self._stall_ds)
        if r.time_penalty:
            vr -= r.time_penalty * self.config.control_dt
        ends = self.vehicle_terminated
        contact = (events & (CONTACT_WALL | CONTACT_VEHICLE)) != 0
        vr -= r.collision_penalty * contact
        np.logical_and(contact, self.config.collision_ends_episode, out=ends)
        np.maximum(self.best_progress, self.progress, out=self.best_progress)
        wrong = (ds < -BACKWARDS_EPS) & (self.best_progress - self.progress > self.config.wrong_way_distance)
        self.wrong_way[:] = np.where(wrong, np.where(vx >= 0.0, 1, -1), 0)
        if r.wrong_way_penalty:
            vr -= r.wrong_way_penalty * wrong
        if self.config.wrong_way_ends_episode:
            ends |= wrong
        terminated = ends.any(axis=1)
        reward = vr.sum(axis=1)
        if self.max_steps is None:
            truncated = np.zeros_like(terminated)
        else:
            truncated = (self.elapsed >= self.max_steps) & ~terminated
        return OracleStep(
            reward=reward,
            terminated=terminated,
            truncated=truncated,
            vehicle_rewards=vr.copy(),
            vehicle_terminated=ends.copy(),
            progress=self.progress.copy(),
            wrong_way=self.wrong_way.copy(),
        )

    def after_reset(self, mask: np.ndarray, out: OracleStep) -> OracleStep:
        """``out`` with the envs of ``mask`` as a fresh episode reports them (a next-step
        autoreset: reward 0, not ended, progress 0)."""
        idx = np.flatnonzero(mask)
        for a in (out.reward, out.vehicle_rewards, out.progress, out.wrong_way):
            a[idx] = 0
        for a in (out.terminated, out.truncated, out.vehicle_terminated):
            a[idx] = False
        return out
