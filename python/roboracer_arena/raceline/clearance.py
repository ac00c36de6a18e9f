"""A fast lower bound of the distance to the nearest wall, for the many queries of
sphere tracing (:mod:`.bounds`): the walls sampled every ``spacing`` metres in a k-d tree.
The distance to the nearest sample exceeds the true distance by at most ``spacing / 2``,
so that much is taken off: the result never overstates the clearance."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.spatial import cKDTree


class WallDistance:
    """Callable: points (N, 2) -> (N,) lower bound of their distance to the walls (m)."""

    def __init__(self, walls: Sequence[np.ndarray], spacing: float = 0.02) -> None:
        samples = []
        for w in walls:
            w = np.asarray(w, dtype=np.float64)
            seg = np.diff(w, axis=0)
            lengths = np.hypot(seg[:, 0], seg[:, 1])
            for a, d, n in zip(w[:-1], seg, np.maximum(1, np.ceil(lengths / spacing)).astype(int)):
                samples.append(a + np.outer(np.arange(n) / n, d))
            samples.append(w[-1:])
        self.spacing = spacing
        self._tree = cKDTree(np.vstack(samples))

    def __call__(self, points: np.ndarray) -> np.ndarray:
        d, _ = self._tree.query(np.atleast_2d(np.asarray(points, dtype=np.float64)))
        return np.maximum(d - 0.5 * self.spacing, 0.0)
