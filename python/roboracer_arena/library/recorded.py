"""Recorded third-party ROS maps in ``../shared/track-sources``: find every map YAML,
load it, decide whether it holds one closed racing corridor, and measure it. The maps
are referenced by their path relative to the sources directory and never copied.

A map is *usable* when its free space holds a ring-shaped corridor, as the builder's
corridor rule (``roboracer_arena.maps.corridor.extract_corridor``, the one rule) decides. The
statistics come from the raster measurement shared with the circuits (``_core.measure_map``).
"""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np

from .. import _core
from ..catalog.catalog_file import provenance, sha256_file
from ..catalog.entry import Raster, Source, TrackEntry
from ..circuits.geometry import MIN_RADIUS_SPAN_M
from ..circuits.sources import slug
from ..errors import ArenaError
from ..foundation.frozen_model import FrozenModel
from ..foundation.worker_pool import Progress, pool_map
from ..maps.corridor import extract_corridor
from ..maps.occupancy import load_map

#: Source folders in order of preference (an identical map later on is a duplicate).
SOURCE_DIRS = {
    "f1tenth-racetracks": "racetracks",
    "f1tenth-gym": "gym",
    "f1tenth-gym-ros": "gym-ros",
    "f1tenth-simulator": "simulator",
    "cps-tuwien-f1tenth-maps": "cps",
    "bdevan5-f1tenth-benchmarks": "bdevan5",
}
FREE, UNKNOWN = 254, 205
#: A corridor must be at least this long (m) and wide on average (m) for a 1:10 car.
MIN_LAP_M = 8.0
MIN_MEAN_WIDTH_M = 0.5
#: Wider than this on average is an open area (a lobby), not a racing corridor.
MAX_MEAN_WIDTH_M = 6.0


class RecordedMap(FrozenModel):
    """One recorded map assessed: where it is, whether it is ``usable`` (else the
    ``reason``), and as far as the assessment got, its grid (resolution in m, raster, a
    digest of cells + resolution for finding duplicates, the corridor check that decided)
    and its corridor measured (lengths in m)."""

    id: str
    name: str
    source_path: str
    source_dir: str
    usable: bool = False
    reason: str | None = None
    resolution_m: float | None = None
    raster: Raster | None = None
    grid_sha256: str | None = None
    corridor_check: str | None = None
    lap_length_m: float | None = None
    width_mean_m: float | None = None
    width_min_m: float | None = None
    min_radius_m: float | None = None
    infields: int | None = None


def find_map_yamls(sources: Path) -> list[Path]:
    """Every ROS map YAML (a YAML with an ``image:`` key) under the known source folders."""
    out = []
    for folder in SOURCE_DIRS:
        for y in sorted((sources / folder).rglob("*.yaml")):
            try:
                text = y.read_text(encoding="utf-8", errors="replace")
            except OSError:
                continue
            if any(line.strip().startswith("image:") for line in text.splitlines()):
                out.append(y)
    return out


def record_id(sources: Path, yaml_path: Path) -> str:
    rel = yaml_path.relative_to(sources)
    stem = yaml_path.stem[:-4] if yaml_path.stem.endswith("_map") else yaml_path.stem
    return f"{SOURCE_DIRS[rel.parts[0]]}-{slug(stem.replace('_', '-'))}"


def corridor_grid(yaml_path: Path, data: np.ndarray) -> tuple[np.ndarray | None, str, str]:
    """The map with only its corridor free: ``(grid or None, reason, which check decided)``.

    The builder's corridor rule decides (``extract_corridor``'s ``corridor_mask``)."""
    check = "corridor.extract_corridor"
    try:
        geo = extract_corridor(yaml_path)
    except ArenaError as e:
        return None, f"no closed corridor (extract_corridor: {e})", check
    mask = np.asarray(geo.corridor_mask, bool)
    if mask.shape != data.shape:
        return None, f"corridor mask {mask.shape} does not match the map {data.shape}", check
    iso = np.where(mask, FREE, np.where(data == FREE, UNKNOWN, data)).astype(np.uint8)
    return iso, "", check


def assess_map(sources: Path, yaml_path: Path) -> RecordedMap:
    """Load one recorded map and measure it; ``usable`` False comes with a ``reason``."""
    rel = str(yaml_path.relative_to(sources))

    def unsourced(reason: str) -> str:
        """The reason without this machine's sources folder: catalog entries name maps
        relative to it, and the shipped catalog must not carry a builder's paths."""
        return reason.replace(str(sources) + "/", "")

    name = yaml_path.stem[:-4] if yaml_path.stem.endswith("_map") else yaml_path.stem
    rec = RecordedMap(id=record_id(sources, yaml_path), name=name, source_path=rel, source_dir=rel.split("/")[0])
    try:
        m = load_map(yaml_path)
    except (ArenaError, OSError, ValueError) as e:
        return rec.with_fields(reason=unsourced(f"broken YAML or image: {e}"))
    data = np.asarray(m.data, np.uint8)
    h, w = data.shape
    iso, why, check = corridor_grid(yaml_path, data)
    rec = rec.with_fields(
        resolution_m=float(m.resolution),
        raster=Raster(width_px=w, height_px=h),
        grid_sha256=hashlib.sha256(data.tobytes() + repr(float(m.resolution)).encode()).hexdigest(),
        corridor_check=check,
    )
    if iso is None:
        return rec.with_fields(reason=unsourced(why))
    try:
        mm = _core.measure_map(iso, float(m.resolution), m.origin)
    except ArenaError as e:
        return rec.with_fields(reason=unsourced(f"no closed corridor: {e}"))
    lap = mm.centreline_length_m
    reason = None
    if lap < MIN_LAP_M:
        reason = f"corridor loop only {lap:.1f} m long (< {MIN_LAP_M} m)"
    elif mm.mean_width_m < MIN_MEAN_WIDTH_M:
        reason = f"corridor {mm.mean_width_m:.2f} m wide on average (< {MIN_MEAN_WIDTH_M} m)"
    elif mm.mean_width_m > MAX_MEAN_WIDTH_M:
        reason = (
            f"open area, not a corridor: {mm.mean_width_m:.1f} m wide on average "
            f"(> {MAX_MEAN_WIDTH_M} m) around a {lap:.1f} m loop"
        )
    return rec.with_fields(
        lap_length_m=round(lap, 3),
        width_mean_m=round(mm.mean_width_m, 3),
        width_min_m=round(float(np.percentile(mm.widths, 0.5)), 3),
        min_radius_m=round(_core.min_radius(mm.centreline, MIN_RADIUS_SPAN_M), 3),
        infields=mm.infields,
        usable=reason is None,
        reason=reason,
    )


def assess_all(sources: Path, jobs: int = 1, progress: Progress | None = None) -> list[RecordedMap]:
    """Assess every recorded map; identical grids after the first are marked duplicates,
    and a repeated id gets ``-2`` appended."""
    from functools import partial

    out = []
    seen: dict[str, str] = {}
    ids: set[str] = set()
    for r in pool_map(partial(assess_map, sources), find_map_yamls(sources), jobs, progress):
        g = r.grid_sha256
        if g and g in seen:  # usable or not: a copy is a duplicate (also of an open map)
            r = r.with_fields(usable=False, reason=f"duplicate of {seen[g]} (identical grid)")
        elif g:
            seen[g] = r.id
        rid = r.id
        while rid in ids:
            rid += "-2"
        ids.add(rid)
        out.append(r.with_fields(id=rid) if rid != r.id else r)
    return out


def recorded_entry(sources: Path, r: RecordedMap) -> TrackEntry:
    """The catalog entry of a usable recorded map (before directions and verify)."""
    prov = provenance(sources, r.source_dir)
    yaml_path = sources / r.source_path
    img_path = load_map(yaml_path).image_path
    notes = [f"corridor checked with {r.corridor_check}"]
    if (r.infields or 1) > 1:
        notes.append(f"{r.infields} enclosed regions (obstacles or islands in the corridor)")
    return TrackEntry(
        id=r.id,
        name=r.name,
        kind="recorded",
        source=Source(**prov, path=r.source_path),
        scale=None,
        resolution_m=r.resolution_m,
        lap_length_m=r.lap_length_m,
        width_mean_m=r.width_mean_m,
        width_min_m=r.width_min_m,
        min_radius_m=r.min_radius_m,
        raster=r.raster,
        sha256=sha256_file(img_path),
        map=r.source_path,
        notes=notes,
    )
