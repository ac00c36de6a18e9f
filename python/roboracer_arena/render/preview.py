"""Track previews: a top-down picture of a map (with its extracted corridor, collision
walls and ducts) or of a built USD stage (its meshes read back), framed with a title,
legend, scale bar and map-frame axes (:mod:`.frame`), with the racing direction, start line
and grid start as the env has them (:mod:`.race_marks`) and — for a generated track — the
design centreline and the detected features from ``report.json``.

The visible barriers are called *ducts* everywhere a user reads (air-duct tubes with
rings; the stage keeps them under ``/World/Track/Barriers``); the invisible physics
boundary is the *collision walls*."""

from __future__ import annotations

import csv
import json
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..builder import parse_start, resolve_config
from ..errors import ArenaError, MapFormatError
from ..maps.corridor import extract_corridor
from ..maps.direction import direction_for_map
from ..maps.occupancy import load_map
from ..track.drivable import Track, track_from_map_path
from ..usd import open_stage, read_meshes
from ..usd.metadata import checked_source, stage_metadata_of
from .formats import image_format
from .frame import LegendEntry, framed
from .race_marks import draw_race_marks
from .topdown import TopDown, save_image

CORRIDOR = (60, 170, 90, 90)
FLOOR = (30, 130, 60, 255)
WALL = (220, 30, 30)
DUCT = (120, 120, 130, 200)
GENERATED = (240, 140, 0)
GAP = (230, 0, 200)
START = (20, 90, 230)
FEATURE = {"hairpin": (170, 0, 170), "chicane": (0, 120, 160), "sweeper": (160, 90, 0)}


@dataclass
class PreviewSummary:
    """What a preview drew (the CLI prints it as JSON); ``layout`` has the pixel boxes of
    title, legend, scale bar, axes, map and labels in the written picture."""

    output: str
    source: str
    size_px: tuple[int, int]
    drawn: list[str] = field(default_factory=list)
    features: list[dict[str, Any]] = field(default_factory=list)
    race: dict[str, Any] = field(default_factory=dict)
    layout: dict[str, Any] = field(default_factory=dict)


def track_name(map_path: Path) -> str:
    """A map's display name: its folder for ``<name>/map.yaml`` (circuits, generated), else its stem."""
    return map_path.parent.name if map_path.stem == "map" and map_path.parent.name else map_path.stem


def preview_map(
    map_path: str | Path,
    out_png: str | Path,
    config: Any = None,
    start: Any = None,
    max_px: int = 2048,
    vehicles: int = 1,
    open: bool | None = None,
    close_gaps_m: float | None = None,
) -> PreviewSummary:
    """Extract the corridor of a ROS map and draw map, corridor, collision walls, ducts,
    racing direction, start line and grid (``vehicles`` cars); write PNG or JPEG.

    A map without a closed corridor is drawn as an open map (``open=None``; walls and its
    start pose, the title says "open map"); ``close_gaps_m`` closes the openings up to
    that width first and marks every gap closed (a magenta ring and its width)."""
    image_format(out_png)  # a bad extension fails before any work
    map_path = Path(map_path)
    canvas, geo, occ, drawn, legend = map_canvas(map_path, config, start, max_px, open=open, close_gaps_m=close_gaps_m)
    features = _generated_overlay(canvas, map_path, drawn, legend)
    gaps = [g.to_json_dict() for g in geo.closed_gaps]
    if gaps:
        features = [*features, *({"closed_gap": g} for g in gaps)]
    name = track_name(map_path)
    race: dict[str, Any] = {}
    if len(geo.centreline) > 2:
        track = Track.from_polylines(list(geo.walls), geo.centreline, name=name).oriented(direction_for_map(map_path))
        marks, race = _race_marks(canvas, track, vehicles)
        drawn += ["centreline", "direction", "start"]
        legend += marks
    title = map_title(name, race, occ, open_map=geo.kind == "open")
    return _write(canvas, title, _subtitle(race, vehicles), legend, out_png, map_path, drawn, features, race)


def map_canvas(
    map_path: Path,
    config: Any = None,
    start: Any = None,
    max_px: int = 2048,
    min_px: int = 1024,
    open: bool | None = None,
    close_gaps_m: float | None = None,
) -> tuple[TopDown, Any, Any, list[str], list[LegendEntry]]:
    """A canvas of the map with its drivable corridor, ducts and collision walls drawn (what
    a preview shows before its race marks; drive videos draw on it too): returns the canvas,
    the extracted corridor geometry, the map, what was drawn and the legend entries. An
    open map (``open``, see ``extract_corridor``) gets its start pose drawn; the gaps
    ``close_gaps_m`` closes are marked."""
    cfg = resolve_config(config)
    occ = load_map(map_path)
    canvas = TopDown.for_raster(occ.data, occ.resolution, occ.origin, max_px=max_px, min_px=min_px)
    geo = extract_corridor(
        occ, params=cfg.geometry_params(), start=parse_start(start), open=open, close_gaps_m=close_gaps_m
    )
    drawn = ["map"]
    legend: list[LegendEntry] = []
    mask = getattr(geo, "corridor_mask", None)
    if mask is not None and np.shape(mask) == occ.data.shape:
        canvas.tint(mask, CORRIDOR)
        drawn.append("corridor")
        legend.append(LegendEntry("drivable corridor", CORRIDOR[:3]))
    for duct in geo.ducts:
        canvas.polyline(duct, DUCT, width_m=cfg.geometry.tube_diameter_m, closed=True)
    for wall in geo.walls:
        canvas.polyline(wall, WALL, closed=True, min_px=2)
    drawn += ["ducts", "walls"]
    legend += [LegendEntry("ducts (visible)", DUCT[:3]), LegendEntry("collision walls (invisible)", WALL, "line")]
    gaps = [g.to_json_dict() for g in geo.closed_gaps]
    for g in gaps:
        canvas.points(np.array([[g["x"], g["y"]]]), GAP, radius_px=max(6.0, 0.75 * g["width_m"] * canvas.px_per_m()))
        canvas.label((g["x"], g["y"]), f"gap {g['width_m']:.2f} m", GAP)
    if gaps:
        drawn.append("closed gaps")
        legend.append(LegendEntry(f"closed gaps ({len(gaps)})", GAP))
    if geo.kind == "open" and geo.start_pose is not None:
        x, y, yaw = geo.start_pose
        canvas.points(np.array([[x, y]]), START, radius_px=6.0)
        canvas.polyline(np.array([[x, y], [x + np.cos(yaw), y + np.sin(yaw)]]), START, closed=False, min_px=3)
        drawn.append("open map start")
        legend.append(LegendEntry("start (open map)", START))
    return canvas, geo, occ, drawn, legend


def map_title(name: str, race: dict[str, Any], occ: Any, open_map: bool = False) -> str:
    """``name: direction, lap length, map size``, the title of a map's picture."""
    h, w = occ.data.shape
    facts = [
        "open map (walls only, no lap)" if open_map else race.get("direction", "direction unknown"),
        f"lap {race['lap_length_m']:.1f} m" if race else None,
        f"map {w * occ.resolution:.1f} x {h * occ.resolution:.1f} m at {occ.resolution:g} m/cell",
    ]
    return f"{name}: {', '.join(f for f in facts if f)}"


def _recorded_source(usd_path: str | Path, stage: Any) -> Path | None:
    """The stage's source map when it is still there as built (absolute path, same
    checksums: :func:`~roboracer_arena.usd.metadata.checked_source`), else None: the
    picture is then drawn from the meshes alone, never over another map of that name."""
    try:
        return checked_source(usd_path, stage_metadata_of(stage, usd_path))
    except ArenaError:
        return None


def preview_usd(usd_path: str | Path, out_png: str | Path, max_px: int = 2048, vehicles: int = 1) -> PreviewSummary:
    """Read a built stage's meshes back and draw floor, ducts and collision walls over the
    source map (when the map named in the stage metadata is still there, also its racing
    direction, start line and grid); write PNG or JPEG."""
    image_format(out_png)
    stage = open_stage(usd_path)
    meshes = read_meshes(stage)
    if not meshes:
        raise MapFormatError(f"{usd_path}: no meshes under /World/Track; not a RoboRacer Arena stage")
    drawn: list[str] = []
    src = _recorded_source(usd_path, stage)
    canvas = None
    if src is not None and src.is_file():
        occ = load_map(src)
        canvas = TopDown.for_raster(occ.data, occ.resolution, occ.origin, max_px=max_px)
        drawn.append("map")
    if canvas is None:
        allp = np.concatenate([m.points for m in meshes.values() if len(m.points)])
        canvas = TopDown.for_bounds(allp.min(0)[:2], allp.max(0)[:2], max_px=max_px)
    legend: list[LegendEntry] = []
    for path, m in meshes.items():
        if path.endswith("/Floor") and len(m.triangles):
            a, b = boundary_edges(m.triangles)
            canvas.segments(m.points[a, :2], m.points[b, :2], FLOOR[:3], width_px=3)
            drawn.append("floor outline")
            legend.append(LegendEntry("floor outline", FLOOR[:3], "line"))
    ducts = [m for path, m in meshes.items() if "/Barriers" in path]
    for m in ducts:
        canvas.triangles(m.points[m.triangles][:, :, :2], DUCT)
    if ducts:
        drawn.append("ducts")
        legend.append(LegendEntry("ducts (visible)", DUCT[:3]))
    walls = meshes.get("/World/Track/Walls")
    if walls is not None and len(walls.triangles):
        tri = walls.points[walls.triangles][:, :, :2]
        for i, j in ((0, 1), (1, 2), (2, 0)):
            canvas.segments(tri[:, i], tri[:, j], WALL, width_px=2)
        drawn.append("walls")
        legend.append(LegendEntry("collision walls (invisible)", WALL, "line"))
    features = _generated_overlay(canvas, src, drawn, legend) if src is not None else []
    race: dict[str, Any] = {}
    if "map" in drawn and src is not None:
        marks, race = _race_marks(canvas, track_from_map_path(src), vehicles)
        drawn += ["direction", "start"]
        legend += marks
    name = Path(usd_path).stem
    facts = [
        race.get("direction", "direction unknown (source map not found)"),
        f"lap {race['lap_length_m']:.1f} m" if race else None,
        "stage meshes read back",
    ]
    title = f"{name}: {', '.join(f for f in facts if f)}"
    return _write(canvas, title, _subtitle(race, vehicles), legend, out_png, Path(usd_path), drawn, features, race)


def _race_marks(canvas: TopDown, track: Any, vehicles: int) -> tuple[list[LegendEntry], dict[str, Any]]:
    return draw_race_marks(canvas, track, vehicles)


def _subtitle(race: dict[str, Any], vehicles: int) -> str:
    if not race:
        return ""
    x, y, yaw = race["grid"][0]
    return (
        f"Arrows: the way the env drives it. Start: the env's grid start (reset_poses='grid', "
        f"{vehicles} car{'s' if vehicles > 1 else ''}) at x {x:.2f} m, y {y:.2f} m, "
        f"heading {np.degrees(yaw):.0f}°."
    )


def _write(
    canvas: TopDown,
    title: str,
    subtitle: str,
    legend: list[LegendEntry],
    out: str | Path,
    source: Path,
    drawn: list[str],
    features: list[dict[str, Any]],
    race: dict[str, Any],
) -> PreviewSummary:
    img, layout = framed(canvas, title, subtitle, legend)
    save_image(img, out)
    return PreviewSummary(str(out), str(source), img.size, drawn, features, race, asdict(layout))


def _generated_overlay(
    canvas: TopDown, map_yaml: Path, drawn: list[str], legend: list[LegendEntry]
) -> list[dict[str, Any]]:
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
        legend.append(LegendEntry("design centreline (generator)", GENERATED, "line"))
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
