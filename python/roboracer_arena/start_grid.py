"""Start poses: where the grid start of a track is, and start-pose noise.

A track concept, not an env one: the envs, the renderer and the benches all place cars
with it.

The grid start is chosen from the track's geometry, not from wherever the extracted
centreline happens to begin: the first grid slot sits on the centreline where every slot
of the grid keeps a safe distance from the walls and the free run straight ahead (to the
first wall along the start heading) is longest, i.e. at the start of the longest straight.
Where the track's source defines its start line (``Track.source_start``: circuits and
recorded maps with a centreline file), the grid stays on that line as long as every slot
is clear. Whatever the direction the centreline runs (see ``Track``), the grid faces
along it, so this composes with a reversed track.
"""

from __future__ import annotations

import math
import weakref
from typing import Any

import numpy as np

#: Cached grid start arc length per (track, slots, spacing).
_GRID_CACHE: weakref.WeakKeyDictionary[Any, dict[tuple[int, float], float]] = weakref.WeakKeyDictionary()

#: Metres kept between the car's side and a wall when start noise moves it sideways (the
#: simulator's reset draws cap the lateral start noise with it, see ``envs.batch``).
SIDE_MARGIN = 0.1

#: Default longitudinal gap between grid slots (m), ``EnvConfig.grid_spacing``.
GRID_SPACING = 1.0
#: Default lateral offset of the staggered grid slots (m), ``EnvConfig.grid_offset``.
GRID_OFFSET = 0.2


def centreline_pose(track: Any, s: float) -> tuple[float, float, float]:
    """(x, y, heading) of the track's centreline at arc length ``s`` (wrapped at the lap);
    on an open map, ``s`` metres along the start heading (behind the start for ``s < 0``),
    as the simulator places a grid there."""
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
    """Distance (m) from (x, y) along ``heading`` to the first wall (inf if none)."""
    a, e = track._segments  # wall edge starts and deltas
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
    """Arc length of the first grid slot (see module docstring); cached per track.

    Candidates every ``max(0.25 m, lap / 400)``; a candidate qualifies when each of the
    ``slots`` grid positions behind it (``spacing`` apart) has at least 75 % of the track's
    median wall clearance; among those the longest free run ahead wins (ties: the larger
    clearance). With no qualifying candidate, the one with the largest clearance wins.
    """
    if getattr(track, "is_open", False):
        return 0.0  # an open map's grid starts at its start pose
    per_track = _GRID_CACHE.setdefault(track, {})
    key = (int(slots), float(spacing))
    if key in per_track:
        return per_track[key]
    length = track.length
    step = max(0.25, length / 400.0)
    cand = np.arange(0.0, length, step)
    poses = np.array([centreline_pose(track, s) for s in cand])
    clear = track.clearance(poses[:, :2])
    need = 0.75 * float(np.median(clear))
    behind = [np.round(((cand - k * spacing) % length) / step).astype(int) % len(cand) for k in range(int(slots))]
    slot_clear = np.min([clear[b] for b in behind], axis=0)
    ok = slot_clear >= need
    if getattr(track, "source_start", False) and ok[0]:
        best = 0  # the source's own start line, when every grid slot behind it is clear
    elif ok.any():
        runs = np.array([free_run_ahead(track, *poses[i]) if ok[i] else -1.0 for i in range(len(cand))])
        runs = np.minimum(runs, 1e6)
        best = int(np.lexsort((slot_clear, runs))[-1])
    else:
        best = int(np.argmax(slot_clear))
    per_track[key] = s = float(cand[best])
    return s


def grid_poses(track: Any, slots: int, spacing: float, offset: float, s0: float | None = None) -> np.ndarray:
    """Poses (slots, 3) of a staggered grid (the layout the simulator's native reset uses;
    previews draw it, and a test holds the two together): the first slot at arc length ``s0`` (default:
    :func:`grid_start_s`), each further one ``spacing`` behind the one before and, with
    more than one slot, ``offset`` left and right of the centreline in turn."""
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


def start_spec(
    tracks: list[Any],
    vehicles: int,
    *,
    reset_poses: str = "grid",
    grid_spacing: float = GRID_SPACING,
    grid_offset: float = GRID_OFFSET,
    lateral_noise: float = 0.0,
    heading_noise: float = 0.0,
    speed_noise: float = 0.0,
    side_clearance: float = 0.0,
    track_weights: Any = None,
    noise_std: tuple[float, float] = (0.0, 0.0),
    dropout: float = 0.0,
) -> str:
    """The simulator's reset draws (``_core.Simulator.set_start_spec``) as JSON: where
    ``reset_drawn`` puts the cars. ``reset_poses`` is ``"grid"`` (first slot at
    :func:`grid_start_s`), ``"centreline_start"`` (s = 0) or ``"random"``. The envs and the
    ROS 2 bridge both start their cars through this, so one track gives one start."""
    import json

    if reset_poses == "grid":
        s0 = [grid_start_s(t, vehicles, grid_spacing) for t in tracks]
    elif reset_poses in ("centreline_start", "random"):
        s0 = [0.0] * len(tracks)
    else:
        raise ValueError(f"reset_poses must be 'grid', 'centreline_start' or 'random', got {reset_poses!r}")
    spec = {
        "random_s": reset_poses == "random",
        "s0": s0,
        "track_weights": [] if track_weights is None else [float(p) for p in track_weights],
        "grid_spacing": float(grid_spacing),
        "grid_offset": float(grid_offset),
        "lateral_noise": float(lateral_noise),
        "heading_noise": float(heading_noise),
        "side_clearance": float(side_clearance),
        "speed_noise": float(speed_noise),
        "noise_std": [float(x) for x in noise_std],
        "dropout": float(dropout),
    }
    return json.dumps(spec)
