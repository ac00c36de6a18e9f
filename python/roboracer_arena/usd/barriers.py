"""Texture coordinates of the duct tubes (u along the duct, v around it).

The core's ``ducts`` mesh holds, for each duct polyline ``d`` (``n`` points) with ``s`` =
``tube_segments``, a closed tube of ``n`` cross-sections of ``s`` vertices whose quad
``(i, k)`` is ``[p, t, r], [p, q, t]`` with p = (i, k), q = (i, k+1), r = (i+1, k),
t = (i+1, k+1) (``geometry::tube::sweep_closed_tube``); a test checks that layout against
the core. Coordinates are face-varying and indexed, with a seam row at the loop's closure
and a seam column around the tube, so the ribs run continuously.
"""

from __future__ import annotations

import numpy as np

DUCT_TEXTURE_TILE_M = 0.5  # metres of duct per texture tile (16 ribs → 3 cm rib pitch)


def duct_st(ducts: list[np.ndarray], segments: int) -> tuple[np.ndarray, np.ndarray]:
    """``(st values (U, 2) float32, face-vertex indices (3 T,) int32)`` for the ducts mesh."""
    s = max(3, int(segments))
    st_blocks, idx_blocks, base = [], [], 0
    for d in ducts:
        d = np.asarray(d, dtype=np.float64).reshape(-1, 2)
        n = len(d)
        if n < 3:
            continue
        seg_len = np.hypot(*(np.roll(d, -1, axis=0) - d).T)
        u = np.r_[0.0, np.cumsum(seg_len)] / DUCT_TEXTURE_TILE_M  # n + 1 rows (seam row)
        v = np.arange(s + 1) / s  # s + 1 columns (seam column)
        st_blocks.append(np.stack(np.meshgrid(u, v, indexing="ij"), axis=-1).reshape(-1, 2))
        idx_blocks.append(_quads(n, s, s + 1, wrap_rows=False, wrap_cols=False).reshape(-1) + base)
        base += (n + 1) * (s + 1)
    if not st_blocks:
        return np.zeros((0, 2), np.float32), np.zeros(0, np.int32)
    return np.concatenate(st_blocks).astype(np.float32), np.concatenate(idx_blocks).astype(np.int32)


def tube_triangles(n: int, s: int) -> np.ndarray:
    """Vertex indices of one closed tube in the core's order (sections and columns wrap)."""
    return _quads(n, s, s, wrap_rows=True, wrap_cols=True)


def _quads(n: int, s: int, row_stride: int, wrap_rows: bool, wrap_cols: bool) -> np.ndarray:
    """Triangles of the (i, k) quad grid in the core's order: [p, t, r], [p, q, t]."""
    i = np.arange(n)[:, None]
    k = np.arange(s)[None, :]
    i2 = (i + 1) % n if wrap_rows else i + 1
    k2 = (k + 1) % s if wrap_cols else k + 1
    p, q = i * row_stride + k, i * row_stride + k2
    r, tt = i2 * row_stride + k, i2 * row_stride + k2
    return np.stack([np.stack([p, tt, r], -1), np.stack([p, q, tt], -1)], axis=2).reshape(-1, 3)
