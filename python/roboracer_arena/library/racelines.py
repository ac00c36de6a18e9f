"""The catalog's racelines: a library job that plans every catalog track's minimum-
curvature raceline with the car's own limits, drives the racing driver on its line, and
records the result in ``tracks/racelines.json`` beside the catalog.

Each record holds the planned lap time and length, the SHA-1 of the raceline's TUM CSV
(the line is deterministic: ``roboracer-arena raceline ID --csv F`` writes the same
bytes), and the racing driver's plan and flying lap (the second of two, from a standing
start on its line). :func:`verify_record` plans a track again and checks its record.

The job is staged and survives signals: each finished track is merged into the index
(written atomically, with SIGINT/SIGTERM held during the write), tracks already recorded
with the same limits are skipped on a rerun, so Ctrl-C loses at most the track being
planned and a rerun carries on.
"""

from __future__ import annotations

import hashlib
import json
import time
from collections.abc import Callable, Iterable
from pathlib import Path

from ..catalog.catalog_file import load_catalog
from ..errors import ArenaError
from ..foundation.fileio import atomic_write_text, signals_held
from ..raceline.driver import (
    DRIVER_LATERAL,
    DRIVER_LONGITUDINAL,
    DRIVER_MARGIN,
    RACING_LOOKAHEAD,
    SPEED_LEAD_S,
    UNDERSTEER_FACTOR,
    drive_raceline,
    plan_for_driver,
)
from ..raceline.export import raceline_csv_text
from ..raceline.limits import preset
from ..raceline.plan import DEFAULT_MARGIN, plan_raceline
from ..raceline.source import resolve_track
from .raceline_index import DriverLap, RacelineIndex, RacelineRecord, index_path, load_index

__all__ = ["DriverLap", "RacelineIndex", "RacelineRecord", "build_racelines", "load_index", "verify_record"]

#: Tolerances of :func:`verify_record` (a rebuild on another machine may differ in the
#: last digits of the QP's solution).
LAP_TOLERANCE_S = 0.05


def _empty_index() -> RacelineIndex:
    lim = preset("car")
    return RacelineIndex.model_validate(
        {
            "version": 1,
            "limits": lim.name,
            "limits_sha1": lim.sha1(),
            "margin_m": DEFAULT_MARGIN,
            "driver": {
                "lateral": DRIVER_LATERAL,
                "longitudinal": DRIVER_LONGITUDINAL,
                "margin_m": DRIVER_MARGIN,
                "understeer_factor": UNDERSTEER_FACTOR,
                "speed_lead_s": SPEED_LEAD_S,
                **RACING_LOOKAHEAD,
            },
            "records": [],
        }
    )


def plan_record(track_id: str, drive: bool = True) -> RacelineRecord:
    """Plan (and with ``drive`` race) one catalog track; an error becomes the record's ``error``."""
    t0 = time.process_time()
    try:
        track, _ = resolve_track(track_id)
        line = plan_raceline(track, preset("car"))
        secs = time.process_time() - t0
        rec = {
            "id": track_id,
            "length_m": round(line.length, 3),
            "lap_time_s": round(line.lap_time, 3),
            "v_min_mps": round(float(line.vx.min()), 3),
            "v_max_mps": round(float(line.vx.max()), 3),
            "csv_sha1": hashlib.sha1(raceline_csv_text(line).encode()).hexdigest(),
            "plan_seconds": round(secs, 3),
        }
        if drive:
            dl = plan_for_driver(track)
            res = drive_raceline(track_id, dl, 2)
            driven = res.lap_times[-1] if res.completed and res.lap_times else None
            rec["driver"] = {
                "planned_s": round(dl.lap_time, 3),
                "driven_s": driven,
                "clean": bool(res.completed),
                "within_5pct": driven is not None and driven <= 1.05 * dl.lap_time,
            }
        return RacelineRecord.model_validate(rec)
    except ArenaError as e:
        return RacelineRecord(
            id=track_id, length_m=0, lap_time_s=0, v_min_mps=0, v_max_mps=0, csv_sha1="", plan_seconds=0, error=str(e)
        )


def _write(index: RacelineIndex, path: Path) -> None:
    text = json.dumps(index.to_json_dict(), indent=1) + "\n"
    with signals_held():
        atomic_write_text(path, text)


def build_racelines(
    ids: Iterable[str] | None = None,
    path: Path | None = None,
    drive: bool = True,
    redo: bool = False,
    progress: Callable[[RacelineRecord], None] | None = None,
) -> RacelineIndex:
    """Plan every catalog track in ``ids`` (default: all) and merge the records into the
    index at ``path``, one track at a time (see the module doc)."""
    p = path or index_path()
    fresh = _empty_index()
    index = load_index(p)
    if index is None or index.limits_sha1 != fresh.limits_sha1 or index.driver != fresh.driver:
        index = fresh  # other limits: every record is stale
    wanted = list(ids) if ids is not None else [e.id for e in load_catalog().select_many("all")]
    for track_id in wanted:
        old = index.get(track_id)
        if old is not None and not redo and old.error is None and (old.driver is not None or not drive):
            continue
        rec = plan_record(track_id, drive)
        records = [r for r in index.records if r.id != track_id] + [rec]
        index = index.with_fields(records=sorted((r.to_json_dict() for r in records), key=lambda r: r["id"]))
        _write(index, p)
        if progress is not None:
            progress(rec)
    return index


def verify_record(track_id: str, index: RacelineIndex | None = None) -> list[str]:
    """Problems of a track's recorded raceline (empty when it holds): a record exists,
    has no error, and planning again gives the same lap time and CSV bytes."""
    index = index or load_index()
    rec = index.get(track_id) if index else None
    if rec is None:
        return [f"{track_id}: no raceline recorded (run the raceline library job)"]
    if rec.error:
        return [f"{track_id}: raceline failed: {rec.error}"]
    again = plan_record(track_id, drive=False)
    problems = []
    if abs(again.lap_time_s - rec.lap_time_s) > LAP_TOLERANCE_S:
        problems.append(f"{track_id}: planned lap {again.lap_time_s:.3f} s, recorded {rec.lap_time_s:.3f} s")
    if again.csv_sha1 != rec.csv_sha1:
        problems.append(f"{track_id}: raceline CSV differs from the recorded one (sha1)")
    return problems
