"""Split the Rust ``barriers`` mesh into duct tubes and rings, and give the tubes texture
coordinates (u along the duct, v around it).

The core builds, for each duct polyline ``d`` (``n`` points) with ``s`` = ``tube_segments``:
a closed tube of ``n`` cross-sections of ``s`` vertices (``2 n s`` triangles, quad
``(i, k)`` = ``[p, t, r], [p, q, t]`` with p = (i, k), q = (i, k+1), r = (i+1, k),
t = (i+1, k+1)), then ``floor(L / ring_spacing)`` rings of two sections each
(``2 s`` vertices, ``2 s`` triangles). :func:`split_barriers` recomputes that layout from
the duct polylines and **checks it against the mesh** (counts and every tube triangle);
on any mismatch it returns ``None`` and the caller keeps one untextured barrier mesh.

Tube texture coordinates are face-varying and indexed, with a seam row at the loop's
closure and a seam column around the tube, so the ribs run continuously.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

DUCT_TEXTURE_TILE_M = 0.5  # metres of duct per texture tile (16 ribs → 3 cm rib pitch)


@dataclass(frozen=True)
class BarrierParts:
    duct_points: np.ndarray
    duct_triangles: np.ndarray
    duct_st: np.ndarray  # (U, 2) float32 values
    duct_st_indices: np.ndarray  # (3 T,) int32, one per face-vertex
    ring_points: np.ndarray
    ring_triangles: np.ndarray


def split_barriers(
    vertices: np.ndarray,
    triangles: np.ndarray,
    ducts: list[np.ndarray],
    segments: int,
    ring_spacing_m: float,
    ring_width_m: float,
) -> BarrierParts | None:
    """Ducts and rings of a barrier mesh, or ``None`` if the mesh is not laid out as expected."""
    v = np.asarray(vertices)
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    s = max(3, int(segments))
    is_tube = np.zeros(len(v), dtype=bool)
    tri_is_tube = np.zeros(len(t), dtype=bool)
    st_blocks, idx_blocks = [], []
    v0 = t0 = st_base = 0
    for d in ducts:
        d = np.asarray(d, dtype=np.float64).reshape(-1, 2)
        n = len(d)
        seg_len = np.hypot(*(np.roll(d, -1, axis=0) - d).T)
        if n >= 3:
            nv, nt = n * s, 2 * n * s
            if v0 + nv > len(v) or t0 + nt > len(t):
                return None
            if not np.array_equal(t[t0 : t0 + nt], _tube_triangles(n, s) + v0):
                return None
            is_tube[v0 : v0 + nv] = True
            tri_is_tube[t0 : t0 + nt] = True
            u = np.r_[0.0, np.cumsum(seg_len)] / DUCT_TEXTURE_TILE_M  # n + 1 rows (seam row)
            vv = np.arange(s + 1) / s  # s + 1 columns (seam column)
            st_blocks.append(np.stack(np.meshgrid(u, vv, indexing="ij"), axis=-1).reshape(-1, 2))
            idx_blocks.append(_tube_st_indices(n, s) + st_base)
            st_base += (n + 1) * (s + 1)
            v0, t0 = v0 + nv, t0 + nt
        rings = 0
        if n >= 2 and ring_spacing_m > 0 and ring_width_m > 0:
            rings = int(np.floor(seg_len.sum() / ring_spacing_m))
        v0, t0 = v0 + 2 * s * rings, t0 + 2 * s * rings
    if v0 != len(v) or t0 != len(t) or not st_blocks:
        return None
    # every triangle must stay within its part
    if not (np.all(is_tube[t[tri_is_tube]]) and not np.any(is_tube[t[~tri_is_tube]])):
        return None
    new_index = np.empty(len(v), dtype=np.int64)
    new_index[is_tube] = np.arange(int(is_tube.sum()))
    new_index[~is_tube] = np.arange(int((~is_tube).sum()))
    return BarrierParts(
        duct_points=v[is_tube],
        duct_triangles=new_index[t[tri_is_tube]].astype(np.int32),
        duct_st=np.concatenate(st_blocks).astype(np.float32),
        duct_st_indices=np.concatenate(idx_blocks).astype(np.int32),
        ring_points=v[~is_tube],
        ring_triangles=new_index[t[~tri_is_tube]].astype(np.int32),
    )


def _quads(n: int, s: int, row_stride: int, wrap_rows: bool, wrap_cols: bool) -> np.ndarray:
    """Triangles of the (i, k) quad grid in the core's order: [p, t, r], [p, q, t]."""
    i = np.arange(n)[:, None]
    k = np.arange(s)[None, :]
    i2 = (i + 1) % n if wrap_rows else i + 1
    k2 = (k + 1) % s if wrap_cols else k + 1
    p, q = i * row_stride + k, i * row_stride + k2
    r, tt = i2 * row_stride + k, i2 * row_stride + k2
    return np.stack([np.stack([p, tt, r], -1), np.stack([p, q, tt], -1)], axis=2).reshape(-1, 3)


def _tube_triangles(n: int, s: int) -> np.ndarray:
    """Vertex indices of a closed tube (sections wrap around, columns wrap around)."""
    return _quads(n, s, s, wrap_rows=True, wrap_cols=True)


def _tube_st_indices(n: int, s: int) -> np.ndarray:
    """Face-vertex indices into the (n + 1) × (s + 1) texture-coordinate grid (no wrap)."""
    return _quads(n, s, s + 1, wrap_rows=False, wrap_cols=False).reshape(-1)
