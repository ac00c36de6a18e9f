"""Map → environment: ``build_environment(map, out.usdc)`` loads a ROS occupancy map,
extracts the corridor and its meshes in Rust, and writes a physics-ready USD stage.

Stages timed in the report: ``load`` (map I/O), ``geometry`` (Rust: flood fill, EDT,
marching squares, smoothing, meshes, IoU check; its own sub-stages are reported as
``geometry.<name>``), ``usd_author`` (stage in memory, incl. textures) and ``usd_write``
(encoding + atomic rename).
"""

from __future__ import annotations

import json
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import BaseModel, Field

from ._core import __version__
from .config.build import BuildConfig
from .errors import ConfigError, InvalidArgumentError
from .foundation.fileio import check_output
from .maps.corridor import extract_corridor
from .maps.occupancy import load_map

MapLike = Any  # OccupancyMap | str | Path
ConfigLike = BuildConfig | Mapping[str, Any] | str | Path | None


class MeshCount(BaseModel):
    vertices: int
    triangles: int


class BuildReport(BaseModel):
    """What a build produced and what it cost."""

    source: str = Field(description="The map YAML the environment was built from ('' for an in-memory map).")
    output: str = Field(description="The USD file written.")
    usd_format: str
    usd_bytes: int = Field(description="Size of the USD file (textures not counted).")
    textures: list[str] = Field(default_factory=list, description="Texture files written beside the stage.")
    raster_px: tuple[int, int] = Field(description="(width, height) of the source raster in cells.")
    raster_mp: float = Field(description="Raster size in megapixels (width × height / 1e6).")
    resolution_m: float
    origin: tuple[float, float, float]
    timings_s: dict[str, float] = Field(description="Seconds per stage; 'total' is load + geometry + usd.")
    meshes: dict[str, MeshCount]
    walls: int = Field(description="Number of closed collision-wall polylines.")
    ducts: int = Field(description="Number of duct polylines (the visible ducts).")
    centreline_length_m: float
    iou: float = Field(
        description="IoU of the drivable region re-rasterised from the collision walls with the source corridor."
    )
    max_wall_deviation_cells: float = Field(
        description="Worst distance (cells) from a wall vertex to the corridor border."
    )
    border_contact_cells: int = Field(
        0,
        description="Corridor cells on the map edge; > 0 means the map edge closes the corridor there (it acts as a wall).",
    )
    map_kind: str = Field(
        "track",
        description="'track' (a closed corridor with a centreline) or 'open' (an open map: walls only, no centreline).",
    )
    open_reason: str | None = Field(None, description="Why the map was built as an open map (its corridor error).")
    start_pose: tuple[float, float, float] | None = Field(
        None,
        description="An open map's start pose (x, y, yaw): the given one or the free cell farthest from the walls.",
    )
    closed_gaps: list[dict[str, float]] = Field(
        default_factory=list, description="Openings closed with close_gaps_m: centre x, y (m), width_m, cells."
    )

    def summary(self) -> str:
        """A few human-readable lines."""
        t = self.timings_s
        stages = ", ".join(f"{k} {v * 1e3:.0f} ms" for k, v in t.items() if "." not in k and k != "total")
        counts = ", ".join(f"{k} {m.vertices:,} v / {m.triangles:,} t" for k, m in self.meshes.items())
        return (
            f"built {self.output} from {self.source or 'an in-memory map'}: "
            f"{self.raster_px[0]}x{self.raster_px[1]} cells ({self.raster_mp:.3f} MP) in {t['total']:.3f} s\n"
            f"  stages: {stages}\n"
            f"  meshes: {counts}\n"
            f"  USD {self.usd_bytes / 1e6:.2f} MB ({self.usd_format}), IoU {self.iou:.4f}, "
            f"worst wall deviation {self.max_wall_deviation_cells:.2f} cells"
            + (
                f"\n  note: the corridor meets the map edge on {self.border_contact_cells} cells; the edge acts as a wall there"
                if self.border_contact_cells and self.map_kind == "track"
                else ""
            )
            + (
                f"\n  open map (walls only, no centreline; start {tuple(round(v, 3) for v in self.start_pose or ())})"
                + (f": {self.open_reason}" if self.open_reason else "")
                if self.map_kind == "open"
                else ""
            )
            + "".join(
                f"\n  closed gap at ({g['x']:.2f}, {g['y']:.2f}) m, {g['width_m']:.2f} m wide" for g in self.closed_gaps
            )
        )


def resolve_config(config: ConfigLike) -> BuildConfig:
    """``None`` → defaults; a mapping is validated; a path is loaded (TOML/JSON)."""
    if config is None:
        return BuildConfig()
    if isinstance(config, BuildConfig):
        return config
    if isinstance(config, Mapping):
        return BuildConfig.from_dict(dict(config))
    if isinstance(config, (str, Path)):
        return BuildConfig.from_file(config)
    raise ConfigError(f"config must be a BuildConfig, a mapping or a file path, not {type(config).__name__}")


def parse_start(start: Sequence[float] | str | None) -> tuple[float, ...] | None:
    """A start pose ``(x, y)`` or ``(x, y, yaw)``; also accepts the CLI text ``"x,y[,yaw]"``."""
    if start is None:
        return None
    if isinstance(start, str):
        try:
            start = [float(s) for s in start.split(",")]
        except ValueError as e:
            raise InvalidArgumentError(f"start pose must be 'x,y' or 'x,y,yaw' in metres/radians, got {start!r}") from e
    vals = tuple(float(v) for v in start)
    if len(vals) not in (2, 3) or not all(np.isfinite(vals)):
        raise InvalidArgumentError(f"start pose must be finite (x, y) or (x, y, yaw), got {vals!r}")
    return vals


def build_environment(
    map_or_path: MapLike,
    out_path: str | Path,
    config: ConfigLike = None,
    start: Sequence[float] | str | None = None,
    car: bool = False,
    open: bool | None = None,
    unknown: str = "occupied",
    close_gaps_m: float | None = None,
    record_source_as: str | Path | None = None,
) -> BuildReport:
    """Build the USD environment of a ROS occupancy map.

    ``map_or_path`` is a map YAML path or an :class:`~roboracer_arena.maps.occupancy.OccupancyMap`;
    ``out_path`` ends in ``.usdc`` (default encoding), ``.usda`` or ``.usd`` (encoding from
    ``config.usd_format``); ``config`` is a :class:`BuildConfig`, a mapping or a TOML/JSON
    file; ``start`` optionally seeds the corridor from a pose ``(x, y[, yaw])`` (an open
    map's start pose); ``car`` adds the paper's car as a PhysX vehicle at the grid start
    (needs the ``physx`` extra). ``open``: ``None`` builds a map without a closed corridor as an
    open map (walls from every occupied region; the report's ``map_kind`` and
    ``open_reason`` say so), ``True`` always, ``False`` never; ``unknown`` is how an open
    map reads unknown cells (``"occupied"`` or ``"free"``). ``close_gaps_m`` closes the
    openings of the walls up to that width first (:mod:`roboracer_arena.maps.gaps`); the
    report, the stage metadata and the summary list every gap closed. ``record_source_as``:
    the path the stage records for its source map when the map is read from a staging copy
    that is moved there afterwards (its checksums are the copy's, the same bytes).

    Raises a :class:`~roboracer_arena.errors.ArenaError` subclass on bad input (unreadable
    map, no closed corridor, leaking walls, bad config); nothing is written then.
    """
    from .usd import write_stage
    from .usd.stage import resolve_format

    cfg = resolve_config(config)
    pose = parse_start(start)
    out = Path(out_path)
    resolve_format(out, cfg)  # refuse a bad suffix or an unwritable output before any work
    src = map_or_path if isinstance(map_or_path, (str, Path)) else getattr(map_or_path, "path", None)
    check_output(out, inputs=[src])

    t0 = time.perf_counter()
    occ = load_map(map_or_path) if isinstance(map_or_path, (str, Path)) else map_or_path
    check_output(out, inputs=[getattr(occ.meta, "image_path", None)])  # None: a map made in memory
    t1 = time.perf_counter()
    geo = extract_corridor(
        occ, params=cfg.geometry_params(), start=pose, open=open, unknown=unknown, close_gaps_m=close_gaps_m
    )
    t2 = time.perf_counter()
    meshes = stage_meshes(geo, cfg)
    t3 = time.perf_counter()
    source = str(getattr(occ, "path", "") or "")
    if car and geo.kind == "open":  # the car starts on a track's grid, which an open map has not
        raise InvalidArgumentError(
            f"{source or 'the map'}: --car needs a closed track (the car starts on the grid along its "
            f"centreline); this map builds only as an open map (walls only, no centreline): "
            f"{geo.open_reason or 'built as an open map'}"
        )
    gaps = [g.to_json_dict() for g in geo.closed_gaps]
    metadata = _stage_metadata(
        occ, geo, cfg, source, record_source_as, pose, unknown, gaps if close_gaps_m is not None else None
    )
    car_pose = None
    if car:
        from .usd.vehicle import grid_start_pose

        car_pose = grid_start_pose(geo, cfg, source)
        metadata["car_pose"] = list(car_pose)
    written = write_stage(out, meshes, cfg, metadata, car_pose)

    timings = {"load": t1 - t0, "geometry": t2 - t1}
    timings.update({f"geometry.{k}": float(v) for k, v in dict(getattr(geo, "timings", {}) or {}).items()})
    timings["usd_author"] = (t3 - t2) + written.seconds_author  # mesh records + stage in memory
    timings["usd_write"] = written.seconds_write
    timings["total"] = timings["load"] + timings["geometry"] + timings["usd_author"] + timings["usd_write"]
    return _build_report(source, out, occ, geo, written, timings, gaps)


def _stage_metadata(
    occ: Any,
    geo: Any,
    cfg: BuildConfig,
    source: str,
    record_source_as: str | Path | None,
    pose: tuple[float, ...] | None,
    unknown: str,
    closed_gaps: list[dict[str, Any]] | None,
) -> dict[str, Any]:
    """The stage's metadata: the generator, the source map (by absolute path and checksums,
    so a later check reads this map or none), the raster, the configs and the geometry's
    quality; the start, the map kind and (when asked to close gaps) the gaps closed."""
    from .usd.metadata import source_fingerprint

    recorded = source_fingerprint(source, record_source_as) if source else {"source_map": ""}
    metadata = {
        "generator": f"roboracer-arena {__version__}",
        **recorded,
        "resolution": float(occ.resolution),
        "origin": [float(v) for v in occ.origin],
        "raster_px": [int(occ.data.shape[1]), int(occ.data.shape[0])],
        "build_config": cfg.model_dump_json(),
        "geometry_params": json.dumps(geo.params, sort_keys=True),
        "iou": float(geo.iou),
        "max_wall_deviation_cells": float(geo.max_wall_deviation_cells),
        "border_contact_cells": int(getattr(geo, "border_contact_cells", 0)),
    }
    if pose is not None:
        metadata["start"] = list(pose)
    metadata["map_kind"] = geo.kind
    if closed_gaps is not None:
        metadata["closed_gaps"] = json.dumps(closed_gaps)
    if geo.kind == "open" and geo.start_pose is not None:
        metadata["start"] = list(geo.start_pose)
        metadata["unknown_cells"] = unknown
        if geo.open_reason:
            metadata["open_reason"] = geo.open_reason
    return metadata


def _build_report(
    source: str, out: Path, occ: Any, geo: Any, written: Any, timings: dict[str, float], gaps: list[dict[str, Any]]
) -> BuildReport:
    """The report of a build that wrote ``out``."""
    h, w = occ.data.shape
    return BuildReport(
        source=source,
        output=str(out),
        usd_format=written.usd_format,
        usd_bytes=written.usd_bytes,
        textures=[str(p) for p in written.textures],
        raster_px=(int(w), int(h)),
        raster_mp=w * h / 1e6,
        resolution_m=float(occ.resolution),
        origin=tuple(float(v) for v in occ.origin),
        timings_s=timings,
        meshes={k: MeshCount(vertices=len(v), triangles=len(t)) for k, (v, t) in geo.meshes.items()},
        walls=len(geo.walls),
        ducts=len(geo.ducts),
        centreline_length_m=geo.centreline_length if len(geo.centreline) > 1 else 0.0,
        iou=float(geo.iou),
        max_wall_deviation_cells=float(geo.max_wall_deviation_cells),
        border_contact_cells=int(getattr(geo, "border_contact_cells", 0)),
        map_kind=geo.kind,
        open_reason=geo.open_reason,
        start_pose=geo.start_pose,
        closed_gaps=gaps,
    )


def stage_meshes(geo: Any, cfg: BuildConfig) -> list:
    """Turn the corridor meshes (``floor``, ``walls``, ``ducts``, ``rings``) into stage
    records with their looks and physics roles; the ducts get the core's texture
    coordinates (``u`` in metres along the duct, scaled here to the texture tile)."""
    from .usd import StageMesh
    from .usd.materials import DUCT_TEXTURE_TILE_M

    meshes = geo.meshes
    out = []
    if "floor" in meshes:
        v, t = meshes["floor"]
        st = np.asarray(v, dtype=np.float32)[:, :2] / np.float32(cfg.materials.floor_texture_tile_m)
        out.append(StageMesh("/World/Track/Floor", v, t, "Floor", collider=True, st=st))
    if "walls" in meshes:
        v, t = meshes["walls"]
        out.append(StageMesh("/World/Track/Walls", v, t, "Wall", collider=True, guide=True))
    v, t = meshes["ducts"]
    if len(t):
        st, st_idx = geo.duct_st
        st = st * np.array([1.0 / DUCT_TEXTURE_TILE_M, 1.0], dtype=np.float32)
        out.append(StageMesh("/World/Track/Barriers/Ducts", v, t, "Duct", st=st, st_indices=st_idx))
    v, t = meshes["rings"]
    if len(t):
        out.append(StageMesh("/World/Track/Barriers/Rings", v, t, "Ring"))
    return out
