"""Typed results of ``tracks verify`` (:mod:`.verify`): one :class:`TrackResult` per track
and the run's :class:`VerifySummary`. Frozen, ``extra="forbid"``; their JSON
(``to_json_dict``) is what ``tracks verify --json`` prints."""

from __future__ import annotations

from ..catalog.entry import Kind, Status
from ..foundation.frozen_model import FrozenModel

PASS: Status = "pass"
FAIL: Status = "FAIL"
NOT_RUN: Status = "not run"
#: The checks, in the order they run and are printed.
CHECKS = ("load", "ring", "usd", "physx", "drive")


class Check(FrozenModel):
    """One check's verdict (``pass`` | ``FAIL`` | ``not run``) and what it found."""

    status: Status
    detail: str = ""


class TrackResult(FrozenModel):
    """Every check of one track; ``passed``: no check failed (checks that could not run
    are reported, not counted as passes)."""

    id: str
    kind: Kind
    passed: bool
    seconds: float
    checks: dict[str, Check]

    def status(self, check: str) -> Status | None:
        """The status of ``check``, or None when it is not in this result."""
        c = self.checks.get(check)
        return None if c is None else c.status

    def failures(self) -> list[str]:
        """``"check: detail"`` of every failed check."""
        return [f"{k}: {c.detail}" for k, c in self.checks.items() if c.status == FAIL]


class KindTally(FrozenModel):
    """Tracks of one kind, and how many of them passed."""

    tracks: int
    passed: int


class VerifySummary(FrozenModel):
    """A verify run: counts, the ids that failed or needed the cautious retry, per-check
    and per-kind tallies, and every track's result in entry order."""

    tracks: int
    passed: int
    drive_cautious: list[str]
    failed: list[str]
    per_check: dict[str, dict[Status, int]]
    by_kind: dict[str, KindTally]
    seconds: float
    jobs: int
    results: list[TrackResult]
    moved_to_left_out: list[str] | None = None

    @classmethod
    def tally(cls, results: list[TrackResult], seconds: float, jobs: int) -> VerifySummary:
        """The summary of ``results``."""
        kinds = sorted({r.kind for r in results})
        return cls(
            tracks=len(results),
            passed=sum(r.passed for r in results),
            drive_cautious=[
                r.id for r in results if r.status("drive") == PASS and "cautious" in r.checks["drive"].detail
            ],
            failed=[r.id for r in results if not r.passed],
            per_check={n: {s: sum(r.status(n) == s for r in results) for s in (PASS, FAIL, NOT_RUN)} for n in CHECKS},
            by_kind={
                k: KindTally(
                    tracks=sum(r.kind == k for r in results), passed=sum(r.passed for r in results if r.kind == k)
                )
                for k in kinds
            },
            seconds=round(seconds, 2),
            jobs=jobs,
            results=results,
        )
