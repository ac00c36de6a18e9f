"""Closed-loop geometry for the circuits: periodic cubic spline smoothing with uniform
resampling, and the local width reduction where non-local sections of the loop would
merge after rasterisation. Lengths, resampling stations, crossings and radii come from
the core's polyline toolbox (``_core.polyline_length`` etc.)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import splev, splprep
from scipy.ndimage import minimum_filter1d, uniform_filter1d
from scipy.spatial import cKDTree

from .. import _core

#: Narrowing never goes below this fraction of the nominal width (the paper's 60 %).
MIN_WIDTH_FRACTION = 0.6
#: Chord half-span (m) of the three-point circumradius (``_core.min_radius``) behind every
#: catalog ``min_radius_m`` (circuits and recorded maps alike).
MIN_RADIUS_SPAN_M = 0.5


def smooth_resample(
    xy: np.ndarray, widths: np.ndarray, spacing: float, tolerance: float
) -> tuple[np.ndarray, np.ndarray]:
    """Fit a periodic cubic smoothing spline through a closed loop and resample it every
    ``spacing`` metres of arc length. ``tolerance`` is the RMS distance (m) the spline
    may keep from the input vertices (``s = N · tolerance²``). Widths are interpolated
    periodically along the same parameter. Returns ``(xy (M, 2), widths (M,))``."""
    xy = np.asarray(xy, float)
    closed = np.vstack([xy, xy[:1]])
    seg = np.hypot(*np.diff(closed, axis=0).T)
    keep = np.concatenate([[True], seg[:-1] > 1e-9])  # drop repeated vertices
    xy, widths, closed = xy[keep], np.asarray(widths, float)[keep], np.vstack([xy[keep], xy[keep][:1]])
    n = len(xy)
    tck, u = splprep([closed[:, 0], closed[:, 1]], s=n * tolerance**2, per=1, k=3, quiet=2)
    # The spline's arc length by dense sampling; the core places the stations along it and
    # carries the (unwrapped) spline parameter, at which the spline is then evaluated.
    dense_u = np.linspace(0.0, 1.0, 20 * n + 1)
    dense = np.column_stack(splev(dense_u[:-1], tck))
    _, uu = _core.resample_closed_values(dense, dense_u, spacing)
    x, y = splev(uu, tck)
    w = np.interp(uu, u, np.concatenate([widths, widths[:1]]))
    return np.column_stack([x, y]), w


@dataclass
class Narrowing:
    """Result of :func:`reduce_widths`."""

    widths: np.ndarray
    factor: np.ndarray  # applied width / nominal width, per vertex
    narrowed_fraction: float  # share of the lap (by vertex count on a uniform loop) with factor < 1
    unresolved_fraction: float  # share where even 60 % leaves the corridors closer than the wall
    min_separation_m: float  # closest approach of non-local sections (centreline to centreline)


def reduce_widths(
    xy: np.ndarray,
    widths: np.ndarray,
    wall_thickness: float,
    spacing: float,
    crossings: np.ndarray | None = None,
    min_fraction: float = MIN_WIDTH_FRACTION,
) -> Narrowing:
    """Narrow the corridor where two non-local sections would merge.

    Two vertices i, j are *non-local* when the arc distance between them exceeds
    ``3 (w_i + w_j)/2 + wall`` (so the two sides of one bend never count). They would
    merge when their centreline separation ``d`` is below ``(w_i + w_j)/2 + wall``: one
    wall strip must stay between the two corridors. Both widths are then scaled by
    ``(d − wall) / ((w_i + w_j)/2)``, clamped to ``[min_fraction, 1]``; the factor is
    eased in and out over ±1 m of arc (a minimum then a mean filter, which never raises
    it above the required value). Near grade-separated crossings (``crossings``: the
    (K, 2) segment pairs of ``_core.self_intersections``) the overlap is intended and the
    width is kept.
    """
    xy = np.asarray(xy, float)
    w = np.asarray(widths, float)
    n = len(xy)
    reach = float(w.max()) + wall_thickness
    tree = cKDTree(xy)
    pairs = tree.query_pairs(r=reach, output_type="ndarray")
    factor = np.ones(n)
    min_sep = float("inf")
    unresolved = np.zeros(n, bool)
    if len(pairs):
        i, j = pairs[:, 0], pairs[:, 1]
        gap = np.abs(i - j)
        arc = np.minimum(gap, n - gap) * spacing
        wsum = (w[i] + w[j]) / 2
        nonlocal_ = arc > 3 * wsum + wall_thickness
        if crossings is not None and len(crossings):
            near = np.zeros(n, bool)
            win = int(np.ceil(2 * reach / spacing))
            for c in np.asarray(crossings, np.int64).ravel():
                near[(np.arange(c - win, c + win + 1)) % n] = True
            nonlocal_ &= ~(near[i] & near[j])
        i, j, wsum = i[nonlocal_], j[nonlocal_], wsum[nonlocal_]
        d = np.hypot(*(xy[i] - xy[j]).T)
        if len(d):
            min_sep = float(d.min())
        need = (d - wall_thickness) / wsum
        bad = need < 1.0
        f = need[bad]
        for a in (i[bad], j[bad]):  # both ends of every too-close pair narrow
            np.minimum.at(factor, a, np.clip(f, min_fraction, 1.0))
            unresolved[a[f < min_fraction]] = True
    ease = max(1, int(round(1.0 / spacing)))
    eased = uniform_filter1d(minimum_filter1d(factor, 2 * ease + 1, mode="wrap"), 2 * ease + 1, mode="wrap")
    eased = np.minimum(eased, factor)
    return Narrowing(
        widths=w * eased,
        factor=eased,
        narrowed_fraction=float(np.mean(eased < 0.999)),
        unresolved_fraction=float(np.mean(unresolved)),
        min_separation_m=min_sep,
    )
