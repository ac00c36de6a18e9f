"""The catalog's raceline records (``tracks/racelines.json``), read without planning
anything: :mod:`.racelines` is the job that writes them; ``tracks show`` prints them."""

from __future__ import annotations

from pathlib import Path

from ..catalog.catalog_file import default_tracks_dir
from ..foundation.fileio import read_json
from ..foundation.frozen_model import FrozenModel

INDEX_NAME = "racelines.json"


class DriverLap(FrozenModel):
    """The racing driver on its own (derated) line: planned and driven flying lap (s)."""

    planned_s: float
    driven_s: float | None
    clean: bool
    within_5pct: bool


class RacelineRecord(FrozenModel):
    """One catalog track's raceline (car limits, mincurv, default margin)."""

    id: str
    length_m: float
    lap_time_s: float
    v_min_mps: float
    v_max_mps: float
    csv_sha1: str
    plan_seconds: float
    driver: DriverLap | None = None
    error: str | None = None


class RacelineIndex(FrozenModel):
    """``tracks/racelines.json``: the limits and settings, and one record per track."""

    version: int = 1
    limits: str
    limits_sha1: str
    margin_m: float
    driver: dict[str, float]
    records: list[RacelineRecord]

    def get(self, track_id: str) -> RacelineRecord | None:
        return next((r for r in self.records if r.id == track_id), None)


def index_path(tracks_dir: Path | None = None) -> Path:
    return (tracks_dir or default_tracks_dir()) / INDEX_NAME


def load_index(path: Path | None = None) -> RacelineIndex | None:
    """The recorded index, or None if there is none yet."""
    p = path or index_path()
    if not p.is_file():
        return None
    return RacelineIndex.model_validate(read_json(p, "raceline index"))


def record_lines(rec: RacelineRecord) -> list[str]:
    """A record as the lines ``tracks show`` prints."""
    if rec.error:
        return [f"raceline: failed: {rec.error}"]
    out = [
        f"raceline: {rec.length_m:.1f} m, planned lap {rec.lap_time_s:.2f} s with the car's limits "
        f"({rec.v_min_mps:.2f}-{rec.v_max_mps:.2f} m/s; roboracer-arena raceline {rec.id} writes it)"
    ]
    d = rec.driver
    if d is not None:
        driven = f"{d.driven_s:.2f} s" if d.driven_s is not None else "no lap"
        out.append(
            f"racing driver: plan {d.planned_s:.2f} s, flying lap {driven}"
            f" ({'clean' if d.clean else 'CONTACT'}{', within 5 %' if d.within_5pct else ''})"
        )
    return out
