"""``tracks verify``: check every catalog track (or a subset) end to end.

Per track: (1) *load*: the map loads and its image matches the catalog checksum;
(2) *ring*: its free space holds one closed corridor ring whose raster centreline length
agrees with the catalog (2 %); (3) *usd*: the builder turns it into a USD stage that
validates; (4) *drive*: the reference pure-pursuit driver completes one lap without a
collision. Steps (3) and (4) are hooks onto the builder and the simulator: when those
packages are not installed they report ``not run`` with the reason, never a pass.
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..builder import build_environment
from ..catalog.catalog_file import Catalog, sha256_file, update_catalog
from ..catalog.entry import LeftOut, OpenMap, TrackEntry
from ..catalog.entry_tracks import entry_track
from ..config.sim import SimConfig
from ..distributed.executor import Executor
from ..drivers import PurePursuitParams, drive_laps
from ..errors import ArenaError
from ..foundation.paths import sources_dir
from ..foundation.worker_pool import Progress, local_unless, map_ordered
from ..maps.clearance_path import clearance_path
from ..maps.corridor import extract_corridor
from ..maps.occupancy import OccupancyMap, load_map
from ..physx import available
from ..physx.check import check_stage
from ..usd.validate import validation_errors
from .recorded import corridor_grid
from .verify_report import FAIL, NOT_RUN, PASS, Check, TrackResult, VerifySummary

LAP_TOLERANCE = 0.02


def check_load(entry: TrackEntry, yaml_path: Path) -> tuple[Check, OccupancyMap | None]:
    try:
        m = load_map(yaml_path)
    except (ArenaError, OSError) as e:
        return Check(status=FAIL, detail=f"does not load: {e}"), None
    digest = sha256_file(m.image_path)
    if digest != entry.sha256:  # (the loader refuses an entry without a 64-hex-digit checksum)
        return Check(status=FAIL, detail=f"image checksum {digest[:12]} != catalog {entry.sha256[:12]}"), m
    h, w = np.asarray(m.data).shape
    if (w, h) != (entry.raster.width_px, entry.raster.height_px):
        return Check(
            status=FAIL, detail=f"raster {w}x{h} != catalog {entry.raster.width_px}x{entry.raster.height_px}"
        ), m
    if not math.isclose(m.resolution, entry.resolution_m, rel_tol=1e-6):
        return Check(status=FAIL, detail=f"resolution {m.resolution:g} m != catalog {entry.resolution_m:g} m"), m
    return Check(status=PASS, detail=f"{w}x{h} at {m.resolution:g} m, checksum ok"), m


def check_ring(entry: TrackEntry, m: OccupancyMap, yaml_path: Path) -> Check:
    data = np.asarray(m.data, np.uint8)
    iso, why, _ = corridor_grid(yaml_path, data)
    if iso is None:
        return Check(status=FAIL, detail=why)
    try:
        mm = _core.measure_map(iso, float(m.resolution), m.origin)
    except ArenaError as e:
        return Check(status=FAIL, detail=f"no closed corridor: {e}")
    lap = mm.centreline_length_m
    if entry.grade_separated:
        return Check(
            status=PASS,
            detail=f"one corridor with {mm.infields} enclosed regions (grade-separated crossing; "
            f"lap length not comparable on the planar raster)",
        )
    if entry.kind != "recorded" and mm.infields != 1:
        return Check(status=FAIL, detail=f"{mm.infields} enclosed regions, expected 1")
    ref = entry.lap_length_m  # > 0 and finite (checked on load)
    if abs(lap - ref) / ref > LAP_TOLERANCE:
        return Check(status=FAIL, detail=f"raster lap {lap:.2f} m vs catalog {ref:.2f} m (> {100 * LAP_TOLERANCE:g} %)")
    return Check(status=PASS, detail=f"one closed ring, raster lap {lap:.2f} m, mean width {mm.mean_width_m:.2f} m")


def check_usd(yaml_path: Path, physx: bool = False) -> tuple[Check, Check]:
    """Hook onto the builder: build the USD stage and run every usd-core validator on it;
    with ``physx``, the PhysX check (:mod:`roboracer_arena.physx.check`, lighter: 4 points,
    1 s) on the same stage. Returns the ``usd`` and ``physx`` verdicts."""
    skipped = Check(status=NOT_RUN, detail="not run: the stage did not build")
    with tempfile.TemporaryDirectory(prefix="rra-verify-") as tmp:
        out = Path(tmp) / "stage.usdc"
        try:
            report = build_environment(yaml_path, out)
        except ArenaError as e:
            return Check(status=FAIL, detail=f"build failed: {e}"), skipped
        errors = validation_errors(out)
        if errors:
            return Check(status=FAIL, detail=f"stage invalid: {'; '.join(map(str, errors[:3]))}"), skipped
        usd = Check(
            status=PASS, detail=f"stage {report.usd_bytes // 1024} KiB, {report.walls} walls, IoU {report.iou:.4f}"
        )
        return usd, (check_physx(out) if physx else physx_not_run())


def physx_not_run() -> Check:
    """The ``physx`` verdict when the PhysX check is not run, saying why."""
    why = "--no-physx" if available() else "the 'physx' extra is not installed"
    return Check(status=NOT_RUN, detail=f"not run: {why}")


def check_physx(stage: Path) -> Check:
    """The stage in PhysX (CPU): single-sided lidar parity and containment."""
    r = check_stage(stage, points=4, seconds=1.0)
    detail = (
        f"lidar {r.lidar.within_tolerance}/{r.lidar.beams} beams within 1 cm, "
        f"{r.containment.contained}/{r.containment.bodies} bodies contained"
    )
    return Check(status=PASS if r.ok else FAIL, detail=detail)


#: The retry after a collision at the reference settings: slower, shorter lookahead.
CAUTIOUS = {"max_speed": 2.5, "lateral_accel": 2.5, "lookahead_min": 0.5}


def check_drive(cat: Catalog, entry: TrackEntry, sources: Path | None = None, reverse: bool = False) -> Check:
    """Hook onto the simulator: the reference pure-pursuit driver completes one lap without
    a contact (default env: full vehicle model, 1081-beam lidar), in the racing direction
    the catalog records (against it with ``reverse``). After a collision it tries once
    more at cautious settings (:data:`CAUTIOUS`), then on the corridor's most-clearance path
    with a speed cap from its clearance (:mod:`roboracer_arena.maps.clearance_path`); a pass then
    says which."""
    try:
        target, follows = entry_track(cat, entry, sources)
        if reverse:
            target = target.reversed()
        want = entry.direction
        if want and not reverse and target.direction != want:
            return Check(status=FAIL, detail=f"the simulator's track runs {target.direction}, the catalog says {want}")
        follows = f"{target.direction}, {follows}"
        r = drive_laps(target, laps=1)
        how = "reference settings"
        if not r.completed:
            first = r
            r = drive_laps(target, laps=1, params=PurePursuitParams(**CAUTIOUS))
            how = (
                f"cautious retry at {CAUTIOUS['max_speed']:g} m/s after a collision at "
                f"{first.distance:.1f} m with the reference settings"
            )
        tight = None
        if not r.completed:  # narrow or cluttered: the most-clearance path, speed from clearance
            tight = _clearance_path(cat, entry, target, sources)
            r = drive_laps(target, laps=1, params=PurePursuitParams(**CAUTIOUS), path=(tight.line, tight.speed_cap))
            how = (
                f"clearance path (min clearance {tight.min_clearance_m:.2f} m) after collisions at "
                f"{first.distance:.1f} m (reference) and on the centreline at {CAUTIOUS['max_speed']:g} m/s"
            )
    except ArenaError as e:
        return Check(status=FAIL, detail=f"simulator refused the track: {e}")
    if r.completed:
        return Check(status=PASS, detail=f"lap {r.lap_times[0]:.1f} s over {r.track_length:.1f} m ({follows}, {how})")
    why = "collision" if r.collided else f"{r.laps_completed} lap(s) in {r.sim_time:.0f} s"
    also = f"also at {CAUTIOUS['max_speed']:g} m/s"
    if tight is not None:
        also += f" and on the clearance path (min clearance {tight.min_clearance_m:.2f} m)"
    return Check(
        status=FAIL,
        detail=f"lap not completed ({why} after {r.distance:.1f} of {r.track_length:.1f} m, {follows}, {also})",
    )


def _clearance_path(cat: Catalog, entry: TrackEntry, target: Any, sources: Path | None) -> Any:
    """The most-clearance path of an entry's corridor in the target's direction."""
    geo = extract_corridor(cat.map_path(entry, sources))
    return clearance_path(geo, target.centreline, half_width_m=SimConfig().vehicle.chassis_width / 2)


def verify_entry(
    cat: Catalog,
    entry: TrackEntry,
    sources: Path | None = None,
    usd: bool = True,
    drive: bool = True,
    reverse: bool = False,
    physx: bool | None = None,
) -> TrackResult:
    """Every check of one track (see the module doc); ``physx`` None = run the PhysX
    check when the ``physx`` extra is installed."""
    if physx is None:
        physx = available()
    t0 = time.perf_counter()
    yaml_path = cat.map_path(entry, sources)
    checks: dict[str, Check] = {}
    checks["load"], m = check_load(entry, yaml_path)
    if m is not None and checks["load"].status == PASS:
        checks["ring"] = check_ring(entry, m, yaml_path)
    else:
        checks["ring"] = Check(status=NOT_RUN, detail="not run: map did not load")
    if usd:
        checks["usd"], checks["physx"] = check_usd(yaml_path, physx)
    else:
        checks["usd"] = Check(status=NOT_RUN, detail="not run: --no-usd")
        checks["physx"] = Check(status=NOT_RUN, detail="not run: --no-usd")
    checks["drive"] = (
        check_drive(cat, entry, sources, reverse) if drive else Check(status=NOT_RUN, detail="not run: --no-drive")
    )
    return _result(entry, checks, time.perf_counter() - t0)


def _result(entry: TrackEntry, checks: dict[str, Check], seconds: float) -> TrackResult:
    passed = all(c.status != FAIL for c in checks.values())
    return TrackResult(id=entry.id, kind=entry.kind, passed=passed, seconds=round(seconds, 3), checks=checks)


def _work(args: tuple[Catalog, TrackEntry, Path | None, bool, bool, bool, bool | None]) -> TrackResult:
    cat, entry, sources, usd, drive, reverse, physx = args
    try:
        return verify_entry(cat, entry, sources, usd, drive, reverse, physx)
    except Exception as e:  # one broken track never stops the run
        return _result(entry, {"internal": Check(status=FAIL, detail=f"{type(e).__name__}: {e}")}, 0.0)


def verify(
    cat: Catalog,
    entries: list[TrackEntry],
    sources: Path | None = None,
    jobs: int = 1,
    usd: bool = True,
    drive: bool = True,
    progress: Progress | None = None,
    reverse: bool = False,
    executor: Executor | None = None,
    physx: bool | None = None,
) -> VerifySummary:
    """Verify ``entries`` (laps against the racing direction with ``reverse``) on ``executor``
    (default: a local pool of ``jobs`` processes); returns per-track results in entry order
    and a summary. On a Ray cluster every node must see the same catalog and sources paths.
    A sources folder that recorded maps need and that does not exist is a
    :class:`~roboracer_arena.errors.MapIOError` before any work, never a verdict on them."""
    t0 = time.perf_counter()
    if sources is not None or any(e.kind == "recorded" for e in entries):
        sources = sources_dir(sources, f"verifying recorded maps ({_first_recorded(entries)})")
    tasks = [(cat, e, sources, usd, drive, reverse, physx) for e in entries]
    with local_unless(executor, jobs) as ex:
        results = map_ordered(ex, _work, tasks, progress)
    return VerifySummary.tally(results, time.perf_counter() - t0, ex.workers)


def recorded_verdicts(entry: TrackEntry, result: TrackResult) -> dict[str, Any]:
    """The ``verified`` and ``drive`` fields an entry records after ``result``: a check this
    run did not make (``--no-drive``, ``--no-physx``, ...) keeps the entry's earlier verdict,
    so a partial run adds a column without erasing the others."""
    verified = dict(entry.verified or {})
    for name, check in result.checks.items():
        if check.status != NOT_RUN or name not in verified:
            verified[name] = check.status
    drive = result.checks.get("drive")
    if drive is None or drive.status == NOT_RUN:
        return {"verified": verified, "drive": entry.drive or ""}
    return {"verified": verified, "drive": drive.detail}


def _first_recorded(entries: list[TrackEntry]) -> str:
    ids = [e.id for e in entries if e.kind == "recorded"]
    return ", ".join(ids[:3]) + (f" and {len(ids) - 3} more" if len(ids) > 3 else "") if ids else "none"


def prune_catalog(cat: Catalog, summary: VerifySummary, opens: dict[str, OpenMap] | None = None) -> list[str]:
    """Move recorded maps that failed verify to ``left_out`` (with the failing check as the
    reason) and record each verified entry's drive result; returns the ids moved.
    Circuits and generated tracks are never moved: a failure there is a bug to fix.
    Only the entries ``summary`` checked change: every other track, left-out map and open
    map stays as it is; ``opens`` (id -> open-map entry) adds the open maps of the maps
    moved (replacing an earlier entry of the same id)."""
    by_id = {r.id: r for r in summary.results}
    moved, keep = [], []
    for e in cat.entries:
        r = by_id.get(e.id)
        if r is None:
            keep.append(e)
            continue
        if not r.passed and e.kind == "recorded":
            reason = f"verify failed: {'; '.join(r.failures())}"
            cat.left_out = [lo for lo in cat.left_out if lo.id != e.id]
            cat.left_out.append(LeftOut(id=e.id, source_path=e.map, reason=reason))
            moved.append(e.id)
            continue
        keep.append(e.with_fields(**recorded_verdicts(e, r)))
    cat.entries = keep
    new = [o for i, o in (opens or {}).items() if i in moved]
    if new:
        fresh = {o.id for o in new}
        cat.open_maps = [o for o in cat.open_maps if o.id not in fresh] + new
    cat.meta = cat.meta.model_copy(update={"counts": cat.counts()})
    return moved


def failed_recorded(cat: Catalog, summary: VerifySummary) -> list[LeftOut]:
    """The left-out entries :func:`prune_catalog` would make of ``summary``'s failed recorded maps."""
    kinds = {e.id: e for e in cat.entries}
    return [
        LeftOut(id=r.id, source_path=kinds[r.id].map, reason=f"verify failed: {'; '.join(r.failures())}")
        for r in summary.results
        if not r.passed and r.id in kinds and kinds[r.id].kind == "recorded"
    ]


def record_results(path: Path, summary: VerifySummary, opens: dict[str, OpenMap] | None = None) -> list[str]:
    """``tracks verify --update-catalog``'s write: :func:`prune_catalog` applied to the
    catalog file as it is now (re-read under its lock, written atomically:
    :func:`~roboracer_arena.catalog.catalog_file.update_catalog`), so a concurrent run on
    other ids keeps its verdicts and this one keeps its own. Returns the ids moved."""
    return update_catalog(path, lambda cat: prune_catalog(cat, summary, opens))
