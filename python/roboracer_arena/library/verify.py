"""``tracks verify``: check every catalog track (or a subset) end to end.

Per track: (1) *load*: the map loads and its image matches the catalog checksum;
(2) *ring*: its free space holds one closed corridor ring whose raster centreline length
agrees with the catalog (2 %); (3) *usd*: the builder turns it into a USD stage that
validates; (4) *drive*: the reference pure-pursuit driver completes one lap without a
collision. Steps (3) and (4) are hooks onto the builder and the simulator: when those
packages are not installed they report ``not run`` with the reason, never a pass.
"""

from __future__ import annotations

import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..distributed.executor import Executor, LocalExecutor, map_ordered
from ..errors import ArenaError
from .catalog import Catalog, sha256_file
from .tracks import entry_track

PASS, FAIL, NOT_RUN = "pass", "FAIL", "not run"
LAP_TOLERANCE = 0.02


@dataclass
class Check:
    status: str  # pass | FAIL | not run
    detail: str = ""


@dataclass
class TrackResult:
    id: str
    kind: str
    checks: dict[str, Check] = field(default_factory=dict)
    seconds: float = 0.0

    @property
    def passed(self) -> bool:
        """No check failed (checks that could not run are reported, not counted as passes)."""
        return all(c.status != FAIL for c in self.checks.values())

    def to_dict(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "kind": self.kind,
            "passed": self.passed,
            "seconds": round(self.seconds, 3),
            "checks": {k: {"status": c.status, "detail": c.detail} for k, c in self.checks.items()},
        }


def check_load(entry: dict, yaml_path: Path):
    from ..maps import load_map

    try:
        m = load_map(yaml_path)
    except (ArenaError, OSError) as e:
        return Check(FAIL, f"does not load: {e}"), None
    digest = sha256_file(Path(m.meta["image_path"]))
    if entry.get("sha256") and digest != entry["sha256"]:
        return Check(FAIL, f"image checksum {digest[:12]} != catalog {entry['sha256'][:12]}"), m
    h, w = np.asarray(m.data).shape
    return Check(PASS, f"{w}x{h} at {m.resolution:g} m, checksum ok"), m


def check_ring(entry: dict, m, yaml_path: Path) -> Check:
    from .recorded import corridor_grid

    data = np.asarray(m.data, np.uint8)
    iso, why, _ = corridor_grid(yaml_path, data)
    if iso is None:
        return Check(FAIL, why)
    try:
        mm = _core.measure_map(iso, float(m.resolution), tuple(m.origin))
    except ArenaError as e:
        return Check(FAIL, f"no closed corridor: {e}")
    lap = mm.centreline_length_m
    if entry.get("grade_separated"):
        return Check(
            PASS,
            f"one corridor with {mm.infields} enclosed regions (grade-separated crossing; "
            f"lap length not comparable on the planar raster)",
        )
    if entry["kind"] != "recorded" and mm.infields != 1:
        return Check(FAIL, f"{mm.infields} enclosed regions, expected 1")
    ref = entry.get("lap_length_m")
    if ref and abs(lap - ref) / ref > LAP_TOLERANCE:
        return Check(FAIL, f"raster lap {lap:.2f} m vs catalog {ref:.2f} m (> {100 * LAP_TOLERANCE:g} %)")
    return Check(PASS, f"one closed ring, raster lap {lap:.2f} m, mean width {mm.mean_width_m:.2f} m")


def check_usd(entry: dict, yaml_path: Path) -> Check:
    """Hook onto the builder: build the USD stage and run every usd-core validator on it."""
    from ..builder import build_environment
    from ..usd.validate import validation_errors

    with tempfile.TemporaryDirectory(prefix="rra-verify-") as tmp:
        out = Path(tmp) / "stage.usdc"
        try:
            report = build_environment(yaml_path, out)
        except ArenaError as e:
            return Check(FAIL, f"build failed: {e}")
        errors = validation_errors(out)
        if errors:
            return Check(FAIL, f"stage invalid: {'; '.join(map(str, errors[:3]))}")
        return Check(PASS, f"stage {report.usd_bytes // 1024} KiB, {report.walls} walls, IoU {report.iou:.4f}")


#: The retry after a collision at the reference settings: slower, shorter lookahead.
CAUTIOUS = {"max_speed": 2.5, "lateral_accel": 2.5, "lookahead_min": 0.5}


def check_drive(cat: Catalog, entry: dict, sources: Path | None = None, reverse: bool = False) -> Check:
    """Hook onto the simulator: the reference pure-pursuit driver completes one lap without
    a contact (default env: full vehicle model, 1081-beam lidar), in the racing direction
    the catalog records (against it with ``reverse``). After a collision it tries once
    more at cautious settings (:data:`CAUTIOUS`); a pass then says so."""
    from ..drivers import PurePursuitParams, drive_laps

    try:
        target, follows = entry_track(cat, entry, sources)
        if reverse:
            target = target.reversed()
        want = entry.get("direction")
        if want and not reverse and target.direction != want:
            return Check(FAIL, f"the simulator's track runs {target.direction}, the catalog says {want}")
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
    except ArenaError as e:
        return Check(FAIL, f"simulator refused the track: {e}")
    if r.completed:
        return Check(PASS, f"lap {r.lap_times[0]:.1f} s over {r.track_length:.1f} m ({follows}, {how})")
    why = "collision" if r.collided else f"{r.laps_completed} lap(s) in {r.sim_time:.0f} s"
    return Check(
        FAIL,
        f"lap not completed ({why} after {r.distance:.1f} of {r.track_length:.1f} m, {follows}, "
        f"also at {CAUTIOUS['max_speed']:g} m/s)",
    )


def verify_entry(
    cat: Catalog, entry: dict, sources: Path | None = None, usd: bool = True, drive: bool = True, reverse: bool = False
) -> TrackResult:
    t0 = time.perf_counter()
    res = TrackResult(entry["id"], entry["kind"])
    yaml_path = cat.map_path(entry, sources)
    res.checks["load"], m = check_load(entry, yaml_path)
    if m is not None and res.checks["load"].status == PASS:
        res.checks["ring"] = check_ring(entry, m, yaml_path)
    else:
        res.checks["ring"] = Check(NOT_RUN, "not run: map did not load")
    res.checks["usd"] = check_usd(entry, yaml_path) if usd else Check(NOT_RUN, "not run: --no-usd")
    res.checks["drive"] = check_drive(cat, entry, sources, reverse) if drive else Check(NOT_RUN, "not run: --no-drive")
    res.seconds = time.perf_counter() - t0
    return res


def _work(args) -> dict:
    cat, entry, sources, usd, drive, reverse = args
    try:
        return verify_entry(cat, entry, sources, usd, drive, reverse).to_dict()
    except Exception as e:  # one broken track never stops the run
        return {
            "id": entry["id"],
            "kind": entry["kind"],
            "passed": False,
            "seconds": 0.0,
            "checks": {"internal": {"status": FAIL, "detail": f"{type(e).__name__}: {e}"}},
        }


def verify(
    cat: Catalog,
    entries: list[dict],
    sources: Path | None = None,
    jobs: int = 1,
    usd: bool = True,
    drive: bool = True,
    progress=None,
    reverse: bool = False,
    executor: Executor | None = None,
) -> dict[str, Any]:
    """Verify ``entries`` (laps against the racing direction with ``reverse``) on ``executor``
    (default: a local pool of ``jobs`` processes); returns per-track results in entry order
    and a summary. On a Ray cluster every node must see the same catalog and sources paths."""
    t0 = time.perf_counter()
    tasks = [(cat, e, sources, usd, drive, reverse) for e in entries]
    ex = executor or LocalExecutor(jobs)
    try:
        results = map_ordered(ex, _work, tasks, progress)
    finally:
        if executor is None:
            ex.close()
    jobs = ex.workers
    names = ("load", "ring", "usd", "drive")
    per_check = {
        n: {s: sum(1 for r in results if r["checks"].get(n, {}).get("status") == s) for s in (PASS, FAIL, NOT_RUN)}
        for n in names
    }
    by_kind = {}
    for k in sorted({r["kind"] for r in results}):
        rs = [r for r in results if r["kind"] == k]
        by_kind[k] = {"tracks": len(rs), "passed": sum(r["passed"] for r in rs)}
    cautious = [
        r["id"]
        for r in results
        if r["checks"].get("drive", {}).get("status") == PASS and "cautious" in r["checks"]["drive"]["detail"]
    ]
    return {
        "tracks": len(results),
        "passed": sum(r["passed"] for r in results),
        "drive_cautious": cautious,
        "failed": [r["id"] for r in results if not r["passed"]],
        "per_check": per_check,
        "by_kind": by_kind,
        "seconds": round(time.perf_counter() - t0, 2),
        "jobs": jobs,
        "results": results,
    }


def prune_catalog(cat: Catalog, summary: dict[str, Any]) -> list[str]:
    """Move recorded maps that failed verify to ``left_out`` (with the failing check as the
    reason) and record each verified entry's drive result; returns the ids moved.
    Circuits and generated tracks are never moved: a failure there is a bug to fix."""
    by_id = {r["id"]: r for r in summary["results"]}
    moved, keep = [], []
    for e in cat.entries:
        r = by_id.get(e["id"])
        if r is None:
            keep.append(e)
            continue
        if not r["passed"] and e["kind"] == "recorded":
            bad = "; ".join(f"{k}: {v['detail']}" for k, v in r["checks"].items() if v["status"] == FAIL)
            cat.left_out.append({"id": e["id"], "source_path": e["map"], "reason": f"verify failed: {bad}"})
            moved.append(e["id"])
            continue
        e["verified"] = {k: v["status"] for k, v in r["checks"].items()}
        e["drive"] = r["checks"].get("drive", {}).get("detail", "")
        keep.append(e)
    cat.entries = keep
    cat.meta["counts"] = {k: sum(e["kind"] == k for e in keep) for k in ("circuit", "recorded", "generated")}
    return moved
