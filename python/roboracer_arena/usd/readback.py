"""Read a track stage back: its metadata and its meshes in world coordinates (for the
preview and for tests)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from pxr import Usd, UsdGeom

from ..errors import MapFormatError, MapIOError
from ..foundation.fileio import require_regular
from .stage import METADATA_KEY


@dataclass(frozen=True)
class ReadMesh:
    path: str
    points: np.ndarray  # (V, 3) float64, world frame
    triangles: np.ndarray  # (T, 3) int64
    purpose: str
    visible: bool


def open_stage(path: str | Path) -> Usd.Stage:
    p = Path(path)
    require_regular(p, "USD stage")
    try:
        stage = Usd.Stage.Open(str(p))
    except Exception as e:  # pxr raises Tf.ErrorException
        raise MapIOError(f"{p}: usd-core cannot open it: {str(e).strip().splitlines()[-1]}") from e
    if stage is None:
        raise MapIOError(f"{p}: usd-core cannot open it")
    return stage


def stage_metadata(stage: Usd.Stage) -> dict[str, Any]:
    """The builder's ``customLayerData`` entry (source map, resolution, origin, config)."""
    data = stage.GetRootLayer().customLayerData.get(METADATA_KEY, {})
    if not isinstance(data, dict):  # typed reading: roboracer_arena.usd.metadata
        where = stage.GetRootLayer().realPath or "stage"
        raise MapFormatError(f"{where}: stage metadata {METADATA_KEY} must be a dictionary, not {type(data).__name__}")
    return {k: (list(v) if hasattr(v, "__len__") and not isinstance(v, (str, dict)) else v) for k, v in data.items()}


def read_meshes(stage: Usd.Stage, root: str = "/World/Track") -> dict[str, ReadMesh]:
    """Every triangle (or polygon, fan-triangulated) mesh under ``root``, keyed by prim path."""
    cache = UsdGeom.XformCache()
    out: dict[str, ReadMesh] = {}
    start = stage.GetPrimAtPath(root)
    if not start:
        return out
    for prim in Usd.PrimRange(start):
        if not prim.IsA(UsdGeom.Mesh):
            continue
        mesh = UsdGeom.Mesh(prim)
        pts = np.asarray(mesh.GetPointsAttr().Get() or [], dtype=np.float64).reshape(-1, 3)
        xf = np.asarray(cache.GetLocalToWorldTransform(prim), dtype=np.float64)
        if len(pts):
            pts = pts @ xf[:3, :3] + xf[3, :3]  # USD matrices are row-vector convention
        counts = np.asarray(mesh.GetFaceVertexCountsAttr().Get() or [], dtype=np.int64)
        idx = np.asarray(mesh.GetFaceVertexIndicesAttr().Get() or [], dtype=np.int64)
        _check_mesh(f"{stage.GetRootLayer().realPath or 'stage'}: {prim.GetPath()}", pts, counts, idx)
        tris = _triangulate(counts, idx)
        img = UsdGeom.Imageable(prim)
        out[str(prim.GetPath())] = ReadMesh(
            str(prim.GetPath()),
            pts,
            tris,
            str(img.ComputePurpose()),
            img.ComputeVisibility() != UsdGeom.Tokens.invisible,
        )
    return out


def _check_mesh(where: str, pts: np.ndarray, counts: np.ndarray, idx: np.ndarray) -> None:
    """Refuse a mesh a reader cannot trust: non-finite points, faces of fewer than three
    vertices, counts that do not add up to the indices, or indices outside the points."""
    if not np.isfinite(pts).all():
        raise MapFormatError(f"{where}: mesh points are not all finite (NaN or infinite)")
    if len(counts) and (counts.min() < 3 or int(counts.sum()) != len(idx)):
        raise MapFormatError(f"{where}: face vertex counts must be ≥ 3 and add up to the {len(idx)} indices")
    if len(idx) and (idx.min() < 0 or idx.max() >= len(pts)):
        raise MapFormatError(
            f"{where}: face vertex indices must be in [0, {len(pts) - 1}], got {idx.min()}..{idx.max()}"
        )


def _triangulate(counts: np.ndarray, idx: np.ndarray) -> np.ndarray:
    if len(counts) and np.all(counts == 3):
        return idx.reshape(-1, 3)
    tris: list[tuple[int, int, int]] = []
    start = 0
    for c in counts:
        face = idx[start : start + c]
        tris.extend((face[0], face[i], face[i + 1]) for i in range(1, c - 1))
        start += c
    return np.asarray(tris, dtype=np.int64).reshape(-1, 3)
