"""The numpy grid start that ``arena_core::sim::start_grid`` replaced, kept as the test
oracle: the core must give bit-identical results (``test_start_grid_oracle.py``), since
the documented ES curve and generalisation figures depend on the start poses.

Verbatim the old ``start_grid.py`` algorithm and ``Track._segments`` / ``Track.clearance``,
with the wall geometry computed here instead of read from the Track's private cache.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def segments(track: Any) -> tuple[np.ndarray, np.ndarray]:
    """(starts (S, 2), deltas (S, 2)) of every wall edge, closing edges included."""
    rings = [np.vstack([w, w[:1]]) if len(w) > 2 and not np.allclose(w[0], w[-1]) else w for w in track.walls]
    starts = np.vstack([r[:-1] for r in rings])
    return starts, np.vstack([r[1:] for r in rings]) - starts


def clearance(track: Any, points: Any) -> np.ndarray:
    p = np.atleast_2d(np.asarray(points, dtype=np.float64))
    a, d = segments(track)
    l2 = np.maximum((d * d).sum(axis=1), 1e-18)
    out = np.empty(len(p))
    for i, q in enumerate(p):
        t = np.clip(((q - a) * d).sum(axis=1) / l2, 0.0, 1.0)
        out[i] = np.sqrt((((a + t[:, None] * d) - q) ** 2).sum(axis=1).min())
    return out


def centreline_pose(track: Any, s: float) -> tuple[float, float, float]:
    if getattr(track, "is_open", False):
        x, y, yaw = track.start_pose
        return x + s * math.cos(yaw), y + s * math.sin(yaw), yaw
    loop, arc = track.loop, track.arclength
    s = float(s) % arc[-1]
    i = min(int(np.searchsorted(arc, s, side="right")) - 1, len(loop) - 1)
    a, b = loop[i], loop[(i + 1) % len(loop)]
    seg = arc[i + 1] - arc[i]
    t = (s - arc[i]) / seg if seg > 0 else 0.0
    p = a + t * (b - a)
    return float(p[0]), float(p[1]), math.atan2(float(b[1] - a[1]), float(b[0] - a[0]))


def free_run_ahead(track: Any, x: float, y: float, heading: float) -> float:
    a, e = segments(track)
    d = np.array([math.cos(heading), math.sin(heading)])
    ap = a - np.array([x, y])
    den = d[0] * e[:, 1] - d[1] * e[:, 0]
    ok = np.abs(den) > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (ap[:, 0] * e[:, 1] - ap[:, 1] * e[:, 0]) / den
        u = (ap[:, 0] * d[1] - ap[:, 1] * d[0]) / den
    hit = ok & (t > 0) & (u >= 0) & (u <= 1)
    return float(t[hit].min()) if hit.any() else math.inf


def grid_start_s(track: Any, slots: int = 1, spacing: float = 1.0) -> float:
    if getattr(track, "is_open", False):
        return 0.0
    length = track.length
    step = max(0.25, length / 400.0)
    cand = np.arange(0.0, length, step)
    poses = np.array([centreline_pose(track, s) for s in cand])
    clear = clearance(track, poses[:, :2])
    need = 0.75 * float(np.median(clear))
    behind = [np.round(((cand - k * spacing) % length) / step).astype(int) % len(cand) for k in range(int(slots))]
    slot_clear = np.min([clear[b] for b in behind], axis=0)
    ok = slot_clear >= need
    if getattr(track, "source_start", False) and ok[0]:
        best = 0
    elif ok.any():
        runs = np.array([free_run_ahead(track, *poses[i]) if ok[i] else -1.0 for i in range(len(cand))])
        runs = np.minimum(runs, 1e6)
        best = int(np.lexsort((slot_clear, runs))[-1])
    else:
        best = int(np.argmax(slot_clear))
    return float(cand[best])


def grid_poses(track: Any, slots: int, spacing: float, offset: float, s0: float | None = None) -> np.ndarray:
    length = track.length
    if s0 is None:
        s0 = grid_start_s(track, slots, spacing)
    out = np.zeros((int(slots), 3))
    for k in range(int(slots)):
        s = s0 - k * spacing
        x, y, yaw = centreline_pose(track, s % length if length > 0 else s)
        lat = 0.0 if slots == 1 else (offset if k % 2 == 0 else -offset)
        out[k] = (x - lat * math.sin(yaw), y + lat * math.cos(yaw), yaw)
    return out
