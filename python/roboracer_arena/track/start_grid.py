"""Start poses: where the grid start of a track is, and the simulator's reset draws.

A track concept, not an env one: the envs, the renderers, the ROS 2 bridge, the PhysX
check and the library all place cars with it. The numbers come from the core
(``arena_core::sim::start_grid``, through :attr:`Track.start_grid <roboracer_arena.track.drivable.Track.start_grid>`);
this module is its typed view, with the env's defaults.

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

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Literal

import numpy as np
import numpy.typing as npt

from .. import _core

if TYPE_CHECKING:
    from .drivable import Track

#: Metres kept between the car's side and a wall when start noise moves it sideways (the
#: simulator's reset draws cap the lateral start noise with it, see ``envs.batch``).
SIDE_MARGIN = 0.1

#: Default longitudinal gap between grid slots (m), ``EnvConfig.grid_spacing``.
GRID_SPACING = 1.0
#: Default lateral offset of the staggered grid slots (m), ``EnvConfig.grid_offset``.
GRID_OFFSET = 0.2

ResetPoses = Literal["grid", "centreline_start", "random"]


def centreline_pose(track: Track, s: float) -> tuple[float, float, float]:
    """(x, y, heading) of the track's centreline at arc length ``s`` (wrapped at the lap);
    on an open map, ``s`` metres along the start heading (behind the start for ``s < 0``),
    as the simulator places a grid there."""
    return track.start_grid.pose_at(float(s))


def free_run_ahead(track: Track, x: float, y: float, heading: float) -> float:
    """Distance (m) from (x, y) along ``heading`` to the first wall (inf if none)."""
    return track.start_grid.free_run_ahead(float(x), float(y), float(heading))


def grid_start_s(track: Track, slots: int = 1, spacing: float = GRID_SPACING) -> float:
    """Arc length of the first grid slot (see module docstring); cached per track, slots
    and spacing.

    Candidates every ``max(0.25 m, lap / 400)``; a candidate qualifies when each of the
    ``slots`` grid positions behind it (``spacing`` apart) has at least 75 % of the track's
    median wall clearance; among those the longest free run ahead wins (ties: the larger
    clearance). With no qualifying candidate, the one with the largest clearance wins. An
    open map's grid starts at its start pose (0).
    """
    return track.start_grid.grid_start_s(int(slots), float(spacing))


def grid_poses(
    track: Track, slots: int, spacing: float, offset: float, s0: float | None = None
) -> npt.NDArray[np.float64]:
    """Poses (slots, 3) of a staggered grid (the layout the simulator's native reset uses;
    previews draw it, and a test holds the two together): the first slot at arc length ``s0`` (default:
    :func:`grid_start_s`), each further one ``spacing`` behind the one before and, with
    more than one slot, ``offset`` left and right of the centreline in turn."""
    return track.start_grid.grid_poses(int(slots), float(spacing), float(offset), None if s0 is None else float(s0))


def start_spec(
    tracks: Sequence[Track | None],
    vehicles: int,
    *,
    reset_poses: ResetPoses = "grid",
    grid_spacing: float = GRID_SPACING,
    grid_offset: float = GRID_OFFSET,
    lateral_noise: float = 0.0,
    heading_noise: float = 0.0,
    speed_noise: float = 0.0,
    side_clearance: float = 0.0,
    track_weights: Iterable[float] | None = None,
    noise_std: tuple[float, float] = (0.0, 0.0),
    dropout: float = 0.0,
) -> _core.StartSpec:
    """The simulator's reset draws (``_core.Simulator.set_start_spec``): where
    ``reset_drawn`` puts the cars. ``reset_poses`` is ``"grid"`` (first slot at
    :func:`grid_start_s`), ``"centreline_start"`` (s = 0) or ``"random"``; only ``"grid"``
    reads the tracks (``None`` entries stand for tracks the caller has no ``Track`` of).
    The envs and the ROS 2 bridge both start their cars through this, so one track gives
    one start. The core checks the ranges (``InvalidArgumentError``)."""
    if reset_poses == "grid":
        if any(t is None for t in tracks):
            raise ValueError("reset_poses='grid' needs a Track for every track")
        s0 = [grid_start_s(t, vehicles, grid_spacing) for t in tracks if t is not None]
    elif reset_poses in ("centreline_start", "random"):
        s0 = [0.0] * len(tracks)
    else:
        raise ValueError(f"reset_poses must be 'grid', 'centreline_start' or 'random', got {reset_poses!r}")
    return _core.StartSpec(
        random_s=reset_poses == "random",
        s0=s0,
        track_weights=None if track_weights is None else [float(p) for p in track_weights],
        grid_spacing=float(grid_spacing),
        grid_offset=float(grid_offset),
        lateral_noise=float(lateral_noise),
        heading_noise=float(heading_noise),
        side_clearance=float(side_clearance),
        speed_noise=float(speed_noise),
        noise_std=(float(noise_std[0]), float(noise_std[1])),
        dropout=float(dropout),
    )
