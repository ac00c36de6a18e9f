"""Synthetic tracks with exact geometry for the env tests (no map needed)."""

from __future__ import annotations

import numpy as np

from roboracer_arena.track.drivable import Track


def stadium(
    straight: float = 6.0, radius: float = 3.0, half_width: float = 0.8, spacing: float = 0.05, name: str = "stadium"
) -> Track:
    """A CCW stadium: two straights joined by semicircles; walls offset ±half_width."""
    n_arc = max(8, int(np.pi * radius / spacing))
    n_str = max(2, int(straight / spacing))
    pts = []
    for i in range(n_str):  # bottom straight, left to right
        pts.append((-straight / 2 + straight * i / n_str, -radius))
    for i in range(n_arc):  # right semicircle
        a = -np.pi / 2 + np.pi * i / n_arc
        pts.append((straight / 2 + radius * np.cos(a), radius * np.sin(a)))
    for i in range(n_str):  # top straight, right to left
        pts.append((straight / 2 - straight * i / n_str, radius))
    for i in range(n_arc):  # left semicircle
        a = np.pi / 2 + np.pi * i / n_arc
        pts.append((-straight / 2 + radius * np.cos(a), radius * np.sin(a)))
    c = np.array(pts)
    d = np.roll(c, -1, axis=0) - np.roll(c, 1, axis=0)
    nrm = np.column_stack([-d[:, 1], d[:, 0]]) / np.linalg.norm(d, axis=1)[:, None]
    inner, outer = c + half_width * nrm, c - half_width * nrm
    close = lambda p: np.vstack([p, p[:1]])
    return Track.from_polylines([close(outer), close(inner)], c, name=name)
