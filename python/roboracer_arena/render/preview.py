"""Track previews: a top-down picture of a map (with its extracted corridor, collision
walls and ducts) or of a built USD stage (its meshes read back), plus — for a generated
track — the centreline and the detected features from ``report.json``."""

from __future__ import annotations

import csv
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .topdown import TopDown

CORRIDOR = (60, 170, 90, 90)
FLOOR = (30, 130, 60, 255)
WALL = (220, 30, 30)
DUCT = (120, 120, 130, 200)
CENTRELINE = (30, 90, 220)
GENERATED = (240, 140, 0)
FEATURE = {"hairpin": (170, 0, 170), "chicane": (0, 120, 160), "sweeper": (160, 90, 0)}


@dataclass
class PreviewSummary:
    """What a preview drew (the CLI prints it as JSON)."""

    output: str
    source: str
    size_px: tuple[int, int]
    drawn: list[str] = field(default_factory=list)
    features: list[dict[str, Any]] = field(default_factory=list)


def preview_map(map_path: str | Path, out_png: str | Path, config: Any = None, start: Any = None, max_px: int = 2048) -> PreviewSummary:
    """Extract the corridor of a ROS map and draw map, corridor, walls, ducts, centreline."""
    from ..builder import parse_start, resolve_config
    from ..corridor import extract_corridor
    from ..maps import load_map

    cfg = resolve_config(config)
    occ = load_map(map_path)
    canvas = TopDown.for_raster(occ.data, occ.resolution, occ.origin, max_px=max_px)
    geo = extract_corridor(occ, params=cfg.geometry_params(), start=parse_start(start))
    drawn = ["map"]
    mask = getattr(geo, "corridor_mask", None)
    if mask is not None and np.shape(mask) == occ.data.shape:
        canvas.tint(mask, CORRIDOR)
        drawn.append("corridor")
    for duct in geo.ducts:
        canvas.polyline(duct, DUCT, width_m=cfg.geometry.tube_diameter_m, closed=True)
    for wall in geo.walls:
        canvas.polyline(wall, WALL, closed=True, min_px=2)
    drawn += ["ducts", "walls"]
    if len(geo.centreline) > 1:
        canvas.polyline(geo.centreline, CENTRELINE, closed=True)
        drawn.append("centreline")
    legend = [("corridor", CORRIDOR[:3]), ("collision walls", WALL), ("ducts", DUCT[:3]), ("centreline", CENTRELINE)]
    features = _generated_overlay(canvas, Path(map_path), drawn, legend)
    canvas.legend(legend)
    canvas.save(out_png)
    return PreviewSummary(str(out_png), str(map_path), canvas.image.size, drawn, features)


def preview_usd(usd_path: str | Path, out_png: str | Path, max_px: int = 2048) -> PreviewSummary:
    """Read a built stage's meshes back and draw floor, ducts and walls over the source map
    (when the map named in the stage metadata is still there)."""
    from ..usd import open_stage, read_meshes, stage_metadata

    stage = open_stage(usd_path)
    meta = stage_metadata(stage)
    meshes = read_meshes(stage)
    if not meshes:
        from ..errors import MapFormatError

        raise MapFormatError(f"{usd_path}: no meshes under /World/Track; not a RoboRacer Arena stage")
    drawn: list[str] = []
    src = Path(str(meta.get("source_map", ""))) if meta.get("source_map") else None
    canvas = None
    if src is not None and src.is_file():
        from ..maps import load_map

        occ = load_map(src)
        canvas = TopDown.for_raster(occ.data, occ.resolution, occ.origin, max_px=max_px)
        drawn.append("map")
    if canvas is None:
        allp = np.concatenate([m.points for m in meshes.values() if len(m.points)])
        canvas = TopDown.for_bounds(allp.min(0)[:2], allp.max(0)[:2], max_px=max_px)
    for path, m in meshes.items():
        if path.endswith("/Floor") and len(m.triangles):
            a, b = boundary_edges(m.triangles)
            canvas.segments(m.points[a, :2], m.points[b, :2], FLOOR[:3], width_px=3)
            drawn.append("floor outline")
    barriers = [m for path, m in meshes.items() if "/Barriers" in path]
    for m in barriers:
        canvas.triangles(m.points[m.triangles][:, :, :2], DUCT)
    if barriers:
        drawn.append("barriers")
    walls = meshes.get("/World/Track/Walls")
    if walls is not None and len(walls.triangles):
        tri = walls.points[walls.triangles][:, :, :2]
        for a, b in ((0, 1), (1, 2), (2, 0)):
            canvas.segments(tri[:, a], tri[:, b], WALL, width_px=2)
        drawn.append("walls")
    legend = [("floor outline", FLOOR[:3]), ("collision walls", WALL), ("barriers", DUCT[:3])]
    features = _generated_overlay(canvas, src, drawn, legend) if src is not None else []
    canvas.legend(legend)
    canvas.save(out_png)
    return PreviewSummary(str(out_png), str(usd_path), canvas.image.size, drawn, features)


def _generated_overlay(canvas: TopDown, map_yaml: Path, drawn: list[str], legend: list) -> list[dict[str, Any]]:
    """If ``map_yaml`` is a generated track (``centreline.csv`` and ``report.json`` beside it,
    as :mod:`roboracer_arena.generate.outputs` writes them), draw its centreline and label
    each detected feature; returns the features drawn."""
    folder = map_yaml.parent
    cl_path, rep_path = folder / "centreline.csv", folder / "report.json"
    if not (cl_path.is_file() and rep_path.is_file()):
        return []
    line = read_centreline_csv(cl_path)
    if len(line) > 1:
        canvas.polyline(line, GENERATED, closed=True, min_px=2)
        drawn.append("generated centreline")
        legend.append(("generated centreline", GENERATED))
    try:
        report = json.loads(rep_path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError):
        return []
    features = [f for f in report.get("features", []) if {"kind", "x", "y"} <= set(f)]
    counts: dict[str, int] = {}
    for f in features:
        counts[f["kind"]] = counts.get(f["kind"], 0) + 1
        canvas.label((f["x"], f["y"]), f"{f['kind']} {counts[f['kind']]}", FEATURE.get(f["kind"], (0, 0, 0)))
    if features:
        drawn.append("features")
    if line.size:
        canvas.label(line[0], "start", (0, 0, 0))
    return features


def boundary_edges(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertex pairs of the edges used by exactly one triangle (a mesh's outline)."""
    t = np.asarray(triangles, dtype=np.int64)
    e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    uniq, counts = np.unique(e, axis=0, return_counts=True)
    once = uniq[counts == 1]
    return once[:, 0], once[:, 1]


def read_centreline_csv(path: Path) -> np.ndarray:
    """x, y columns of a centreline CSV (``#`` comment lines skipped)."""
    rows = []
    with open(path, newline="", encoding="utf-8") as f:
        for row in csv.reader(line for line in f if not line.lstrip().startswith("#")):
            if len(row) >= 2:
                try:
                    rows.append((float(row[0]), float(row[1])))
                except ValueError:
                    continue
    return np.asarray(rows, dtype=np.float64).reshape(-1, 2)
