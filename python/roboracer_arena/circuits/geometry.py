"""Closed-loop geometry for the circuits: periodic cubic spline smoothing and uniform
resampling, self-intersections (grade-separated crossings), and the local width
reduction where non-local sections of the loop would merge after rasterisation."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import splev, splprep
from scipy.ndimage import minimum_filter1d, uniform_filter1d
from scipy.spatial import cKDTree

#: Narrowing never goes below this fraction of the nominal width (the paper's 60 %).
MIN_WIDTH_FRACTION = 0.6


def loop_length(xy: np.ndarray) -> float:
    """Length of a closed polyline (no repeated end point)."""
    d = np.diff(np.vstack([xy, xy[:1]]), axis=0)
    return float(np.hypot(d[:, 0], d[:, 1]).sum())


def smooth_resample(
    xy: np.ndarray, widths: np.ndarray, spacing: float, tolerance: float
) -> tuple[np.ndarray, np.ndarray]:
    """Fit a periodic cubic smoothing spline through a closed loop and resample it every
    ``spacing`` metres of arc length. ``tolerance`` is the RMS distance (m) the spline
    may keep from the input vertices (``s = N · tolerance²``). Widths are interpolated
    periodically along the same parameter. Returns ``(xy (M, 2), widths (M,))``."""
    xy = np.asarray(xy, float)
    n = len(xy)
    closed = np.vstack([xy, xy[:1]])
    seg = np.hypot(*np.diff(closed, axis=0).T)
    keep = np.concatenate([[True], seg[:-1] > 1e-9])  # drop repeated vertices
    xy, widths, closed = xy[keep], np.asarray(widths, float)[keep], np.vstack([xy[keep], xy[keep][:1]])
    n = len(xy)
    tck, u = splprep([closed[:, 0], closed[:, 1]], s=n * tolerance**2, per=1, k=3, quiet=2)
    # Arc length of the spline by dense sampling, then invert for uniform spacing.
    dense_u = np.linspace(0.0, 1.0, 20 * n + 1)
    dx, dy = splev(dense_u, tck)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(dx), np.diff(dy)))])
    m = max(8, int(round(s[-1] / spacing)))
    target = np.linspace(0.0, s[-1], m, endpoint=False)
    uu = np.interp(target, s, dense_u)
    x, y = splev(uu, tck)
    w_closed = np.concatenate([widths, widths[:1]])
    w = np.interp(uu, u, w_closed)
    return np.column_stack([x, y]), w


def self_intersections(xy: np.ndarray, step: int = 1) -> list[tuple[int, int, np.ndarray]]:
    """Crossings of a closed polyline with itself: ``(i, j, point)`` for segments i < j
    that are not neighbours. Vectorised O(N²); pass a coarse loop (a few hundred vertices)."""
    p = np.asarray(xy, float)[::step]
    a, b = p, np.roll(p, -1, axis=0)
    n = len(p)
    d = b - a
    out = []
    for i in range(n - 2):
        j = np.arange(i + 2, n if i else n - 1)
        if len(j) == 0:
            continue
        r, s = d[i], d[j]
        denom = r[0] * s[:, 1] - r[1] * s[:, 0]
        qp = a[j] - a[i]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (qp[:, 0] * s[:, 1] - qp[:, 1] * s[:, 0]) / denom
            uu = (qp[:, 0] * r[1] - qp[:, 1] * r[0]) / denom
        hit = (np.abs(denom) > 1e-12) & (t >= 0) & (t < 1) & (uu >= 0) & (uu < 1)
        for k in np.nonzero(hit)[0]:
            out.append((i * step, int(j[k]) * step, a[i] + t[k] * r))
    return out


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
    crossings: Sequence[tuple[int, int, np.ndarray]] = (),
    min_fraction: float = MIN_WIDTH_FRACTION,
) -> Narrowing:
    """Narrow the corridor where two non-local sections would merge.

    Two vertices i, j are *non-local* when the arc distance between them exceeds
    ``3 (w_i + w_j)/2 + wall`` (so the two sides of one bend never count). They would
    merge when their centreline separation ``d`` is below ``(w_i + w_j)/2 + wall``: one
    wall strip must stay between the two corridors. Both widths are then scaled by
    ``(d − wall) / ((w_i + w_j)/2)``, clamped to ``[min_fraction, 1]``; the factor is
    eased in and out over ±1 m of arc (a minimum then a mean filter, which never raises
    it above the required value). Near grade-separated crossings (``crossings``) the
    overlap is intended and the width is kept.
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
        if len(crossings):
            near = np.zeros(n, bool)
            win = int(np.ceil(2 * reach / spacing))
            for ci, cj, _ in crossings:
                for c in (ci, cj):
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
