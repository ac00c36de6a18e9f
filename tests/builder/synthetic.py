"""A synthetic ring track made in numpy (annulus floor, extruded walls, tube barriers), so
the USD layer can be tested without the map pipeline."""

from __future__ import annotations

import numpy as np

from roboracer_arena.usd import StageMesh


def circle(r: float, n: int = 64) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[r * np.cos(a), r * np.sin(a)]


def annulus(r_in: float, r_out: float, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
    pts = np.r_[circle(r_in, n), circle(r_out, n)]
    pts3 = np.c_[pts, np.zeros(len(pts))]
    i = np.arange(n)
    j = (i + 1) % n
    tris = np.r_[np.c_[i, j, n + i], np.c_[j, n + j, n + i]]
    return pts3.astype(np.float32), tris.astype(np.uint32)


def extrude(loop: np.ndarray, height: float) -> tuple[np.ndarray, np.ndarray]:
    n = len(loop)
    pts = np.r_[np.c_[loop, np.zeros(n)], np.c_[loop, np.full(n, height)]]
    i = np.arange(n)
    j = (i + 1) % n
    tris = np.r_[np.c_[i, j, n + i], np.c_[j, n + j, n + i]]
    return pts.astype(np.float32), tris.astype(np.uint32)


def tube(loop: np.ndarray, radius: float, seg: int = 8) -> tuple[np.ndarray, np.ndarray]:
    n = len(loop)
    d = np.roll(loop, -1, 0) - np.roll(loop, 1, 0)
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    normal = np.c_[d[:, 1], -d[:, 0]]
    a = np.linspace(0, 2 * np.pi, seg, endpoint=False)
    xy = loop[:, None, :] + radius * np.cos(a)[None, :, None] * normal[:, None, :]
    z = radius + radius * np.sin(a)[None, :].repeat(n, 0)
    pts = np.c_[xy.reshape(-1, 2), z.reshape(-1)]
    i, k = np.meshgrid(np.arange(n), np.arange(seg), indexing="ij")
    i2, k2 = (i + 1) % n, (k + 1) % seg
    v = lambda ii, kk: (ii * seg + kk).ravel()
    tris = np.r_[np.c_[v(i, k), v(i2, k), v(i, k2)], np.c_[v(i2, k), v(i2, k2), v(i, k2)]]
    return pts.astype(np.float32), tris.astype(np.uint32)


def ring_meshes(r_in: float = 3.0, r_out: float = 4.5) -> list[StageMesh]:
    fp, ft = annulus(r_in, r_out)
    w_in, w_in_t = extrude(circle(r_in), 0.5)
    w_out, w_out_t = extrude(circle(r_out), 0.5)
    walls_p = np.r_[w_in, w_out]
    walls_t = np.r_[w_in_t, w_out_t + len(w_in)]
    d_in, d_in_t = tube(circle(r_in - 0.165), 0.165)
    d_out, d_out_t = tube(circle(r_out + 0.165), 0.165)
    seg = 8
    st = np.c_[np.repeat(np.arange(len(d_in) // seg), seg) * 0.3, np.tile(np.arange(seg) / seg, len(d_in) // seg)]
    return [
        StageMesh("/World/Track/Floor", fp, ft, "Floor", collider=True, st=fp[:, :2] / 2.0),
        StageMesh("/World/Track/Walls", walls_p, walls_t, "Wall", collider=True, guide=True),
        StageMesh(
            "/World/Track/Barriers/Ducts",
            np.r_[d_in, d_out],
            np.r_[d_in_t, d_out_t + len(d_in)],
            "Duct",
            st=np.r_[st, st],
        ),
    ]


def load_physics(stage):
    """usd-core's UsdPhysics parse of a stage (the newer name when usd-core has it)."""
    from pxr import UsdPhysics

    load = getattr(UsdPhysics, "UsdPhysicsLoadStageFromPrimRange", None) or UsdPhysics.LoadUsdPhysicsFromRange
    return load(stage, ["/"])
