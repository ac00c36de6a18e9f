"""The base controller of the residual policy: the reference pure pursuit
(:class:`~roboracer_arena.drivers.PurePursuitDriver`, same law, same speed profile), run
for many cars on many tracks at once.

Every track's resampled centreline and speed profile are concatenated into one array, so
one call steers every car of a vector env whatever track each is on, with no Python loop
per car: each car's nearest centreline point is searched in a window ahead of its last
one (a global search only after a reset or a jump, as the single-car driver does).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from ..drivers import PurePursuitDriver, PurePursuitParams

#: Window of the local projection search: from 1 m behind to 2 m ahead of the last point.
_BEHIND_M, _AHEAD_M = 1.0, 2.0
#: A car further than this from its windowed nearest point is searched for again globally.
_JUMP_M = 1.0
#: The speed command is the profile's minimum over this distance ahead (as the driver's).
_SPEED_WINDOW_M = 0.6


class PursuitBase:
    """Pure pursuit for ``N`` cars over ``centrelines`` (closed (M, 2) lines, driving order)."""

    def __init__(self, centrelines: Sequence[Any], params: PurePursuitParams) -> None:
        self.params = params
        drivers = [PurePursuitDriver(line, params) for line in centrelines]
        self.count = np.array([len(d.points) for d in drivers], dtype=np.int64)
        self.offset = np.concatenate([[0], np.cumsum(self.count)[:-1]]).astype(np.int64)
        self.ds = np.array([d.ds for d in drivers])
        self.points = np.concatenate([d.points for d in drivers])
        self.profile = np.concatenate([d.speed_profile for d in drivers])
        spacing = float(self.ds.max())
        self._window = np.arange(-round(_BEHIND_M / spacing), round(_AHEAD_M / spacing) + 1)
        self._ahead = np.arange(max(1, round(_SPEED_WINDOW_M / spacing)))
        self._idx: np.ndarray | None = None  # (N,) index within its track, -1 = unknown
        self._tracks: np.ndarray | None = None

    def reset(self, cars: Any = slice(None)) -> None:
        """Forget the projection of ``cars`` (an index, mask or slice; call after their reset)."""
        if self._idx is not None:
            self._idx[cars] = -1

    def _project(self, tid: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        n = len(tid)
        if self._idx is None or len(self._idx) != n:
            self._idx, self._tracks = np.full(n, -1, np.int64), tid.copy()
        assert self._tracks is not None
        self._idx[self._tracks != tid] = -1  # a car now on another track: search again
        self._tracks[:] = tid
        cnt, off = self.count[tid], self.offset[tid]
        cand = (self._idx[:, None] + self._window[None, :]) % cnt[:, None]
        pts = self.points[off[:, None] + cand]
        d = np.hypot(pts[..., 0] - x[:, None], pts[..., 1] - y[:, None])
        k = np.argmin(d, axis=1)
        idx = cand[np.arange(n), k]
        lost = (self._idx < 0) | (d[np.arange(n), k] >= _JUMP_M)
        for i in np.flatnonzero(lost):  # after a reset or a jump only
            seg = self.points[off[i] : off[i] + cnt[i]]
            idx[i] = int(np.argmin(np.hypot(seg[:, 0] - x[i], seg[:, 1] - y[i])))
        self._idx[:] = idx
        return idx

    def act(self, track_ids: Any, x: Any, y: Any, yaw: Any, speed: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(steer rad, speed m/s)`` of every car (1-D arrays of the same length): pose of
        its centre of mass in the map frame, its forward speed and its track's index."""
        p = self.params
        tid = np.asarray(track_ids, dtype=np.int64).ravel()
        x, y, yaw, v = (np.asarray(a, dtype=np.float64).ravel() for a in (x, y, yaw, speed))
        finite = np.isfinite(x) & np.isfinite(y) & np.isfinite(yaw) & np.isfinite(v)
        x, y, yaw, v = (np.where(finite, a, 0.0) for a in (x, y, yaw, v))
        c, s = np.cos(yaw), np.sin(yaw)
        rx, ry = x - p.rear_axle_offset * c, y - p.rear_axle_offset * s
        i = self._project(tid, rx, ry)
        cnt, off, ds = self.count[tid], self.offset[tid], self.ds[tid]
        lookahead = np.clip(p.lookahead_min + p.lookahead_gain * np.maximum(v, 0.0), p.lookahead_min, p.lookahead_max)
        j = (i + np.maximum(1, np.rint(lookahead / ds)).astype(np.int64)) % cnt
        target = self.points[off + j]
        dx, dy = target[:, 0] - rx, target[:, 1] - ry
        lx, ly = c * dx + s * dy, -s * dx + c * dy
        steer = np.clip(np.arctan2(2.0 * p.wheelbase * ly, lx * lx + ly * ly), -p.max_steer, p.max_steer)
        ahead = off[:, None] + (i[:, None] + self._ahead[None, :]) % cnt[:, None]
        cmd = self.profile[ahead].min(axis=1)
        return np.where(finite, steer, 0.0), np.where(finite, cmd, 0.0)
