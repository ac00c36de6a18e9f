"""Which left-out recorded maps the catalog offers as *open maps* (walls only, no lap;
see :func:`roboracer_arena.maps.corridor.extract_open`), and how every source map is
accounted for (:func:`map_kinds`: track, open map, duplicate or broken).

A left-out map is an open map unless it is a duplicate of another map or does not load:
F1TENTH Gym simulates any map that has walls, and so do we. For a map that has a closed
corridor but is not a track (the reference driver could not lap it), the entry also
measures the corridor's narrowest free width beside the car's width: the measured reason.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..catalog.catalog_file import Catalog
from ..catalog.directions import annotate_directions
from ..catalog.entry import LeftOut, OpenMap, Raster
from ..config.sim import SimConfig
from ..errors import ArenaError
from ..foundation.worker_pool import Progress, pool_map
from ..maps.corridor import extract_corridor, extract_open
from ..maps.occupancy import load_map
from ..track.drivable import track_from_corridor
from .recorded import assess_all, assess_map, find_map_yamls, recorded_entry
from .verify import verify_entry

#: The start of a reason that makes a left-out map no open map.
NOT_OPEN = ("duplicate of", "broken YAML or image")


def is_open_candidate(lo: LeftOut) -> bool:
    """True when a left-out map is neither a duplicate nor broken."""
    return not lo.reason.startswith(NOT_OPEN)


def narrowest_gap_m(yaml_path: Path) -> float | None:
    """The narrowest free width (m) along the closed corridor's medial line, or None when
    the map has no closed corridor."""
    try:
        geo = extract_corridor(yaml_path)
    except ArenaError:
        return None
    m = geo.map
    iso = np.where(geo.corridor_mask, 254, np.where(m.data == 254, 205, m.data)).astype(np.uint8)
    try:
        return round(float(np.min(_core.measure_map(iso, float(m.resolution), m.origin).widths)), 3)
    except ArenaError:
        return None


def open_map_entry(sources: Path, lo: LeftOut) -> OpenMap | None:
    """The open-map entry of a left-out map, or None when it builds no open map."""
    yaml_path = sources / lo.source_path
    try:
        geo = extract_open(yaml_path)
    except ArenaError:
        return None
    m = load_map(yaml_path)
    h, w = m.data.shape
    x, y, yaw = geo.start_pose or (0.0, 0.0, 0.0)
    gap = narrowest_gap_m(yaml_path)
    return OpenMap(
        id=lo.id,
        source_path=lo.source_path,
        reason=lo.reason,
        resolution_m=float(m.resolution),
        raster=Raster(width_px=w, height_px=h),
        start=(round(x, 3), round(y, 3), round(yaw, 4)),
        start_clearance_m=round(_start_clearance(geo), 3),
        narrowest_gap_m=gap,
        car_width_m=SimConfig().vehicle.chassis_width if gap is not None else None,
    )


def _start_clearance(geo: Any) -> float:
    """The default start's clearance (m) from the open build (``start_clearance_m``)."""
    t = track_from_corridor(geo, "open")
    return float(t.clearance(np.asarray([t.start_pose[:2]]))[0]) if t.start_pose else 0.0


def open_maps(
    sources: Path, left_out: Sequence[LeftOut], jobs: int = 1, progress: Progress | None = None
) -> list[OpenMap]:
    """Open-map entries of every left-out map that is neither a duplicate nor broken."""
    from functools import partial

    todo = [lo for lo in left_out if is_open_candidate(lo)]
    return [o for o in pool_map(partial(open_map_entry, sources), todo, jobs, progress) if o is not None]


def map_kinds(catalog: Any) -> dict[str, str]:
    """Every recorded source map's id → ``"track"``, ``"open"``, ``"duplicate"``,
    ``"broken"`` or ``"left out"`` (not even an open map)."""
    out = {e.id: "track" for e in catalog.entries if e.kind == "recorded"}
    opens = {o.id for o in catalog.open_maps}
    for lo in catalog.left_out:
        if lo.id in opens:
            out[lo.id] = "open"
        elif lo.reason.startswith("duplicate of"):
            out[lo.id] = "duplicate"
        elif lo.reason.startswith("broken YAML or image"):
            out[lo.id] = "broken"
        else:
            out[lo.id] = "left out"
    return out


def rejudge(cat: Any, sources: Path, jobs: int = 1) -> list[str]:
    """Verify again every recorded map that ``tracks verify`` moved to ``left_out``, with
    the current drivers (the reference, the cautious retry and the clearance path): a map
    that laps now goes back into the catalog's tracks (in the builder's order); one that
    does not keeps its place in ``left_out`` with the new drive result and, measured, its
    narrowest gap beside the car's width. The other left-out maps get the reason a fresh
    assessment gives (as ``tracks catalog`` would write it). Returns the ids that joined
    the tracks."""
    order = {str(p.relative_to(sources)): i for i, p in enumerate(find_map_yamls(sources))}
    width = SimConfig().vehicle.chassis_width
    joined: list[str] = []
    left: list[LeftOut] = []
    assessed = {r.id: r for r in assess_all(sources, jobs=jobs)}
    for lo in cat.left_out:
        if not lo.reason.startswith("verify failed"):
            fresh = assessed.get(lo.id)
            left.append(lo.with_fields(reason=fresh.reason) if fresh is not None and fresh.reason else lo)
            continue
        r = assess_map(sources, sources / lo.source_path).with_fields(id=lo.id)
        one = Catalog(entries=[recorded_entry(sources, r)], meta=cat.meta, path=cat.path)
        annotate_directions(one, sources)
        entry = one.entries[0]
        result = verify_entry(one, entry, sources)
        if result.passed:
            drive = result.checks.get("drive")
            cat.entries.append(
                entry.with_fields(
                    verified={k: c.status for k, c in result.checks.items()}, drive=drive.detail if drive else ""
                )
            )
            joined.append(lo.id)
            continue
        reason = f"verify failed: {'; '.join(result.failures())}"
        gap = narrowest_gap_m(sources / lo.source_path)
        if gap is not None:
            reason += f"; narrowest gap {gap:.2f} m {'<' if gap < width else '>='} car width {width:.2f} m"
        left.append(lo.with_fields(reason=reason))
    if joined:
        kinds = {"circuit": 0, "recorded": 1, "generated": 2}
        cat.entries.sort(key=lambda e: (kinds[e.kind], order.get(e.map, -1) if e.kind == "recorded" else 0))
    cat.left_out = left
    cat.meta = cat.meta.model_copy(update={"counts": cat.counts()})
    return joined
